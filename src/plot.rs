//! PNG plots of a simulated trajectory, as `chaplygin simulate --out DIR`
//! writes them next to `trajectory.csv`.
//!
//! The input is a [`Table`] whose columns follow the CSV layout of
//! INTERFACE.md section 3 (`t`, the coordinates, the rest of the state,
//! controller states, inputs, `energy`, `constraint_residual`); a
//! [`PlotSpec`] names the columns each plot reads. [`write_plots`] writes:
//!
//! - `path.png`: the planar path `(x(t), y(t))` with equal axis scales,
//!   heading arrows along `theta` at regular time intervals, start and end
//!   marked;
//! - `energy.png`: the relative energy error `(E(t) - E(0)) / |E(0)|`
//!   against `t` (the absolute error `E(t) - E(0)` when `E(0) = 0`, as the
//!   axis label then says);
//! - `constraint_residual.png`: the residual against `t` on a logarithmic
//!   scale, values below [`RESIDUAL_FLOOR`] (zeros included) drawn at the
//!   floor, as the axis label then says;
//! - `figure4.png`: Figure 4 of Duindam & Stramigioli (2004) for the
//!   snakeboard under the energy-based controller of MATH.md 3.2: the curve
//!   `(alpha1, alpha2, xt)(t)` in a 3-D projection on the wireframe of the
//!   constant-energy ellipsoid
//!   `alpha1^2/(2m) + alpha2^2/(2Jt) + kt xt^2/2 = E0`.
//!
//! Non-finite samples (a diverged run) break the curves instead of being
//! drawn. Text uses DejaVu Sans (Bitstream Vera license, shipped in
//! `assets/fonts` with its license), embedded in the binary and registered
//! with plotters' `ab_glyph` renderer, so no system font library is needed.

mod figure4;
mod path;
mod series;

use plotters::coord::Shift;
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Residuals below this value (zeros included) are drawn at it on the
/// logarithmic axis of `constraint_residual.png`.
pub const RESIDUAL_FLOOR: f64 = 1e-18;

/// The font every plot's text uses, registered as plotters' `sans-serif`.
const FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// The image edges allowed, in pixels: room for titles and labels at the
/// low end, a bounded pixel buffer at the high end.
const EDGES: std::ops::RangeInclusive<u32> = 200..=8192;

/// A trajectory, row-major: one row per sample, one value per column.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table with these column names, which must be distinct.
    pub fn new(columns: Vec<String>) -> Result<Self, PlotError> {
        for (index, name) in columns.iter().enumerate() {
            if columns[..index].contains(name) {
                return Err(PlotError::DuplicateColumn { name: name.clone() });
            }
        }
        Ok(Self {
            columns,
            rows: Vec::new(),
        })
    }

    /// Appends one sample, with one value per column.
    pub fn push_row(&mut self, row: Vec<f64>) -> Result<(), PlotError> {
        if row.len() != self.columns.len() {
            return Err(PlotError::RowLength {
                row: self.rows.len(),
                expected: self.columns.len(),
                found: row.len(),
            });
        }
        self.rows.push(row);
        Ok(())
    }

    /// The column names, in order.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// The samples, in order.
    pub fn rows(&self) -> &[Vec<f64>] {
        &self.rows
    }

    /// Whether the table has a column of this name.
    pub fn has_column(&self, name: &str) -> bool {
        self.columns.iter().any(|column| column == name)
    }

    /// The values of one column, in row order.
    pub fn column(&self, name: &str) -> Result<Vec<f64>, PlotError> {
        let index = self
            .columns
            .iter()
            .position(|column| column == name)
            .ok_or_else(|| PlotError::MissingColumn {
                name: name.to_string(),
                available: self.columns.clone(),
            })?;
        Ok(self.rows.iter().map(|row| row[index]).collect())
    }
}

/// The columns of the planar path plot.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarPath {
    /// Abscissa of the position.
    pub x: String,
    /// Ordinate of the position.
    pub y: String,
    /// Heading angle in radians from the x axis; no arrows without it.
    pub heading: Option<String>,
}

/// The data of Duindam & Stramigioli's Figure 4 (MATH.md 3.2): the columns
/// of the group momentum `alpha1`, the torso momentum `alpha2` and the
/// torso spring state `xt`, and the parameters of the ellipsoid
/// `alpha1^2/(2m) + alpha2^2/(2Jt) + kt xt^2/2 = E0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure4 {
    /// Column of the group momentum `alpha1`.
    pub alpha1: String,
    /// Column of the torso momentum `alpha2`.
    pub alpha2: String,
    /// Column of the torso spring state `xt`.
    pub xt: String,
    /// The board's mass `m`.
    pub m: f64,
    /// The torso's inertia `Jt`.
    pub jt: f64,
    /// The torso spring's stiffness `kt`.
    pub kt: f64,
}

/// Which columns [`write_plots`] draws, their units, and the image size.
///
/// A plot whose field is `None` is not written; a named column missing from
/// the table is an error.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotSpec {
    /// The time column.
    pub time: String,
    /// The planar path, for `path.png`.
    pub path: Option<PlanarPath>,
    /// The total energy, for `energy.png`.
    pub energy: Option<String>,
    /// The constraint residual, for `constraint_residual.png`.
    pub constraint_residual: Option<String>,
    /// Figure 4's data, for `figure4.png`.
    pub figure4: Option<Figure4>,
    /// Units by column name, shown in axis labels as `name [unit]`.
    pub units: BTreeMap<String, String>,
    /// Image width and height in pixels, each from 200 to 8192.
    pub size: (u32, u32),
}

impl Default for PlotSpec {
    /// INTERFACE.md section 3's names: `t`; `x`, `y`, `theta`; `energy`;
    /// `constraint_residual`. No Figure 4, no units, 1024 x 768 pixels.
    fn default() -> Self {
        Self {
            time: "t".into(),
            path: Some(PlanarPath {
                x: "x".into(),
                y: "y".into(),
                heading: Some("theta".into()),
            }),
            energy: Some("energy".into()),
            constraint_residual: Some("constraint_residual".into()),
            figure4: None,
            units: BTreeMap::new(),
            size: (1024, 768),
        }
    }
}

impl PlotSpec {
    /// The [`Default`] spec restricted to the plots whose columns the table
    /// has: the path needs `x` and `y` (its arrows `theta`), the energy plot
    /// `energy`, the residual plot `constraint_residual`.
    pub fn for_table(table: &Table) -> Self {
        let present = |name: &str| table.has_column(name).then(|| name.to_string());
        let path = match (present("x"), present("y")) {
            (Some(x), Some(y)) => Some(PlanarPath {
                x,
                y,
                heading: present("theta"),
            }),
            _ => None,
        };
        Self {
            path,
            energy: present("energy"),
            constraint_residual: present("constraint_residual"),
            ..Self::default()
        }
    }

    /// This spec with Figure 4 drawn from `figure4`.
    pub fn with_figure4(self, figure4: Figure4) -> Self {
        Self {
            figure4: Some(figure4),
            ..self
        }
    }

    /// This spec with `unit` shown on the axes of `column`.
    pub fn with_unit(mut self, column: &str, unit: &str) -> Self {
        self.units.insert(column.to_string(), unit.to_string());
        self
    }

    /// The axis label of a column: `name [unit]`, or the name alone.
    fn label(&self, column: &str) -> String {
        match self.units.get(column) {
            Some(unit) => format!("{column} [{unit}]"),
            None => column.to_string(),
        }
    }

    /// Every column the spec names, each once, time first.
    fn named_columns(&self) -> Vec<&str> {
        let mut names = vec![self.time.as_str()];
        if let Some(path) = &self.path {
            names.extend([path.x.as_str(), path.y.as_str()]);
            names.extend(path.heading.as_deref());
        }
        names.extend(self.energy.as_deref());
        names.extend(self.constraint_residual.as_deref());
        if let Some(figure4) = &self.figure4 {
            names.extend([&figure4.alpha1, &figure4.alpha2, &figure4.xt].map(String::as_str));
        }
        names
    }

    /// Checks the image size and Figure 4's parameters.
    fn validate(&self) -> Result<(), PlotError> {
        let (width, height) = self.size;
        if !(EDGES.contains(&width) && EDGES.contains(&height)) {
            return Err(PlotError::ImageSize { width, height });
        }
        let Some(figure4) = &self.figure4 else {
            return Ok(());
        };
        let parameters = [("m", figure4.m), ("jt", figure4.jt), ("kt", figure4.kt)];
        match parameters
            .iter()
            .find(|(_, value)| !(value.is_finite() && *value > 0.0))
        {
            Some(&(name, value)) => Err(PlotError::NonPositiveParameter { name, value }),
            None => Ok(()),
        }
    }
}

/// Why plots could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The spec names a column the table lacks.
    #[error("no column `{name}` in the trajectory (columns: {})", available.join(", "))]
    MissingColumn {
        /// The column asked for.
        name: String,
        /// The table's columns.
        available: Vec<String>,
    },
    /// Two columns share a name.
    #[error("column `{name}` appears twice")]
    DuplicateColumn {
        /// The repeated name.
        name: String,
    },
    /// A row's length differs from the number of columns.
    #[error("row {row} has {found} values but the table has {expected} columns")]
    RowLength {
        /// Index of the row, from 0.
        row: usize,
        /// The number of columns.
        expected: usize,
        /// The row's length.
        found: usize,
    },
    /// The table has no rows.
    #[error("the trajectory has no rows to plot")]
    EmptyTable,
    /// A plotted column has no finite value.
    #[error("column `{name}` has no finite value to plot")]
    NoFiniteValue {
        /// The column.
        name: String,
    },
    /// The image is too small for titles and labels, or too large.
    #[error(
        "image size {width}x{height}: each edge must be {} to {} pixels",
        EDGES.start(),
        EDGES.end()
    )]
    ImageSize {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
    },
    /// A Figure 4 parameter is not a positive finite number.
    #[error("Figure 4 parameter `{name}` must be positive and finite, found {value}")]
    NonPositiveParameter {
        /// The parameter: `m`, `jt` or `kt`.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The output directory or a file in it could not be created.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The directory or file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// Plotters failed to draw or encode an image.
    #[error("cannot draw {}: {message}", path.display())]
    Drawing {
        /// The image file.
        path: PathBuf,
        /// Plotters' description of the failure.
        message: String,
    },
    /// The embedded font could not be loaded.
    #[error("the embedded DejaVu Sans font could not be loaded")]
    Font,
}

/// Writes the plots `spec` asks for into `dir` (created if absent) and
/// returns the files written, in the order of the module docs.
///
/// Every named column is checked before anything is drawn.
pub fn write_plots(table: &Table, spec: &PlotSpec, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    spec.validate()?;
    let columns = named_columns(table, spec)?;
    register_font()?;
    std::fs::create_dir_all(dir).map_err(|source| PlotError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let time = &columns[&spec.time];
    let mut written = Vec::new();
    if let Some(planar) = &spec.path {
        let file = dir.join("path.png");
        path::draw(&file, spec, planar, &columns)?;
        written.push(file);
    }
    if let Some(name) = &spec.energy {
        let file = dir.join("energy.png");
        series::draw_energy(&file, spec, time, &columns[name])?;
        written.push(file);
    }
    if let Some(name) = &spec.constraint_residual {
        let file = dir.join("constraint_residual.png");
        series::draw_residual(&file, spec, name, time, &columns[name])?;
        written.push(file);
    }
    if let Some(figure4) = &spec.figure4 {
        let file = dir.join("figure4.png");
        figure4::draw(&file, spec, figure4, &columns)?;
        written.push(file);
    }
    Ok(written)
}

/// The values of every column the spec names, each with a finite value.
fn named_columns(table: &Table, spec: &PlotSpec) -> Result<BTreeMap<String, Vec<f64>>, PlotError> {
    let mut columns = BTreeMap::new();
    for name in spec.named_columns() {
        columns.insert(name.to_string(), table.column(name)?);
    }
    if table.rows.is_empty() {
        return Err(PlotError::EmptyTable);
    }
    match columns
        .iter()
        .find(|(_, values)| !values.iter().any(|v| v.is_finite()))
    {
        Some((name, _)) => Err(PlotError::NoFiniteValue { name: name.clone() }),
        None => Ok(columns),
    }
}

/// Registers the embedded font as `sans-serif`, once per process.
fn register_font() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let registered = REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok()
    });
    if *registered {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

/// A white canvas that will be saved as the PNG `file`.
///
/// The file is created first so that an unwritable location is reported as
/// [`PlotError::Io`] rather than as a drawing failure.
fn canvas(
    file: &Path,
    size: (u32, u32),
) -> Result<DrawingArea<BitMapBackend<'_>, Shift>, PlotError> {
    std::fs::File::create(file).map_err(|source| PlotError::Io {
        path: file.to_path_buf(),
        source,
    })?;
    let root = BitMapBackend::new(file, size).into_drawing_area();
    root.fill(&WHITE).drawn(file)?;
    Ok(root)
}

/// Conversion of plotters' errors into [`PlotError::Drawing`] for a file.
trait Drawn<T> {
    /// The value, or the error with the file it concerns.
    fn drawn(self, file: &Path) -> Result<T, PlotError>;
}

impl<T, E: std::error::Error + Send + Sync> Drawn<T> for Result<T, DrawingAreaErrorKind<E>> {
    fn drawn(self, file: &Path) -> Result<T, PlotError> {
        self.map_err(|error| PlotError::Drawing {
            path: file.to_path_buf(),
            message: error.to_string(),
        })
    }
}

/// The result of drawing on a chart, before [`Drawn::drawn`].
type DrawResult =
    Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

/// Marks a curve's first and last finite points: the start as a wide green
/// disc, the end as a narrower red one on top, so that both show where
/// they coincide.
fn draw_ends<CT: CoordTranslate>(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, CT>,
    [start, end]: [Option<CT::From>; 2],
) -> DrawResult {
    for (point, name, color, radius) in [(start, "start", GREEN, 9), (end, "end", RED, 5)] {
        chart
            .draw_series(point.map(|p| Circle::new(p, radius, color.filled())))?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + 10, y), radius, color.filled()));
    }
    Ok(())
}

/// The legend of the labelled series, in `corner`.
fn draw_legend<'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, CT>,
    corner: SeriesLabelPosition,
) -> DrawResult {
    chart
        .configure_series_labels()
        .position(corner)
        .label_font(label_style())
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
}

/// The text style of titles.
fn title_style() -> TextStyle<'static> {
    ("sans-serif", 26).into_font().into()
}

/// The text style of axis descriptions, legends and notes.
fn label_style() -> TextStyle<'static> {
    ("sans-serif", 18).into_font().into()
}

/// The smallest and the largest finite value (infinities when none).
fn finite_bounds(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), v| {
            (low.min(v), high.max(v))
        })
}

/// The range of the finite values, widened by `pad` of its span on each
/// side; a single value `v` gets `v -/+ max(|v|/10, 1)` instead.
///
/// The caller guarantees at least one finite value.
fn padded_range(values: impl IntoIterator<Item = f64>, pad: f64) -> Range<f64> {
    let (low, high) = finite_bounds(values);
    let span = high - low;
    if span > 0.0 {
        (low - pad * span)..(high + pad * span)
    } else {
        let half = (low.abs() / 10.0).max(1.0);
        (low - half)..(low + half)
    }
}

/// Tick labels for an axis over `range` with plotters' default of at most
/// ten labels: ticks are then at least a tenth of the span apart, so that
/// many decimals suffice; no label reads `-0`.
fn tick_labels(range: &Range<f64>) -> impl Fn(&f64) -> String + use<> {
    let decimals = (-((range.end - range.start) / 10.0).log10().floor()).clamp(0.0, 12.0);
    let scale = 10f64.powf(decimals);
    move |value| {
        format!(
            "{:.*}",
            decimals as usize,
            (value * scale).round() / scale + 0.0
        )
    }
}

/// The range of length `span` with the same centre as `range`.
fn centred(range: Range<f64>, span: f64) -> Range<f64> {
    let centre = (range.start + range.end) / 2.0;
    (centre - span / 2.0)..(centre + span / 2.0)
}

/// The maximal runs of consecutive finite points, each drawn as one curve.
fn finite_runs<P: Copy>(points: &[P], finite: impl Fn(&P) -> bool) -> impl Iterator<Item = &[P]> {
    points
        .split(move |p| !finite(p))
        .filter(|run| !run.is_empty())
}

/// The corner of the plot whose legend-sized box (40% of the width, 30% of
/// the height) holds the fewest points: where the legend hides the least.
fn emptiest_corner(points: &[(f64, f64)], x: &Range<f64>, y: &Range<f64>) -> SeriesLabelPosition {
    let (width, height) = (0.4 * (x.end - x.start), 0.3 * (y.end - y.start));
    let count = |right: bool, upper: bool| {
        let left_edge = if right { x.end - width } else { x.start };
        let bottom_edge = if upper { y.end - height } else { y.start };
        points
            .iter()
            .filter(|(px, _)| (left_edge..left_edge + width).contains(px))
            .filter(|(_, py)| (bottom_edge..bottom_edge + height).contains(py))
            .count()
    };
    [
        (count(false, true), SeriesLabelPosition::UpperLeft),
        (count(true, true), SeriesLabelPosition::UpperRight),
        (count(false, false), SeriesLabelPosition::LowerLeft),
        (count(true, false), SeriesLabelPosition::LowerRight),
    ]
    .into_iter()
    .min_by_key(|(points, _)| *points)
    .map_or(SeriesLabelPosition::UpperLeft, |(_, corner)| corner)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn padded_range_widens_by_the_fraction_of_the_span() {
        let range = padded_range([1.0, 3.0, f64::NAN, 2.0], 0.25);
        assert_eq!(range, 0.5..3.5);
    }

    #[test]
    fn padded_range_of_a_single_value_is_centred_on_it() {
        assert_eq!(padded_range([20.0, 20.0], 0.1), 18.0..22.0);
        assert_eq!(padded_range([0.0], 0.1), -1.0..1.0);
    }

    #[test]
    fn tick_labels_have_the_decimals_of_a_tenth_of_the_span() {
        let path = tick_labels(&(-0.15..1.5));
        assert_eq!(
            [path(&-1e-17), path(&0.2), path(&1.4)],
            ["0.0", "0.2", "1.4"]
        );
        let time = tick_labels(&(0.0..30.0));
        assert_eq!([time(&5.0), time(&25.0)], ["5", "25"]);
    }

    #[test]
    fn the_legend_goes_where_no_points_are() {
        let points = [(0.1, 0.1), (0.9, 0.9), (0.1, 0.9), (0.5, 0.5)];
        let corner = emptiest_corner(&points, &(0.0..1.0), &(0.0..1.0));
        assert_eq!(corner, SeriesLabelPosition::LowerRight);
    }

    #[test]
    fn finite_runs_split_at_non_finite_points() {
        let values = [1.0, 2.0, f64::NAN, f64::INFINITY, 3.0, f64::NAN];
        let runs: Vec<&[f64]> = finite_runs(&values, |v| v.is_finite()).collect();
        assert_eq!(runs, vec![&[1.0, 2.0][..], &[3.0][..]]);
    }
}
