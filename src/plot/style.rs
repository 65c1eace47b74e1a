//! What every plot shares: the canvas and its errors, the text styles,
//! start and end marks, the legend and where it goes, axis ranges and tick
//! labels, and the split of curves at non-finite samples.

use super::PlotError;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// Draws on a white canvas of `size` pixels with `draw` and saves it as
/// the PNG `file` (8-bit RGB, encoded by the `png` crate).
///
/// The file is created first so that an unwritable location is reported as
/// [`PlotError::Io`] rather than as a drawing failure.
pub(super) fn png(
    file: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), PlotError>,
) -> Result<(), PlotError> {
    let io = |source| PlotError::Io {
        path: file.to_path_buf(),
        source,
    };
    let output = std::fs::File::create(file).map_err(io)?;
    let mut pixels = vec![0; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
        root.fill(&WHITE).drawn(file)?;
        draw(&root)?;
        root.present().drawn(file)?;
    }
    let mut encoder = ::png::Encoder::new(std::io::BufWriter::new(output), size.0, size.1);
    encoder.set_color(::png::ColorType::Rgb);
    encoder.set_depth(::png::BitDepth::Eight);
    encoder
        .write_header()
        .and_then(|mut writer| writer.write_image_data(&pixels))
        .map_err(|error| match error {
            ::png::EncodingError::IoError(source) => io(source),
            other => PlotError::Drawing {
                path: file.to_path_buf(),
                message: other.to_string(),
            },
        })
}

/// Conversion of plotters' errors into [`PlotError::Drawing`] for a file.
pub(super) trait Drawn<T> {
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
pub(super) type DrawResult =
    Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

/// A chart's axis: its description and its tick labels.
pub(super) struct Axis<'a> {
    /// What the axis shows.
    pub name: &'a str,
    /// The text of a tick.
    pub labels: &'a dyn Fn(&f64) -> String,
}

/// Draws the axes of a chart of `f64` against `f64` (descriptions, tick
/// labels, the text styles), with its grid when `grid`.
pub(super) fn draw_axes(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x: Axis<'_>,
    y: Axis<'_>,
    grid: bool,
) -> DrawResult {
    let mut mesh = chart.configure_mesh();
    if !grid {
        mesh.disable_mesh();
    }
    mesh.x_desc(x.name)
        .x_label_formatter(x.labels)
        .y_desc(y.name)
        .y_label_formatter(y.labels)
        .axis_desc_style(label_style())
        .label_style(label_style())
        .draw()
}

/// Marks a curve's first and last finite points: the start as a wide green
/// disc, the end as a narrower red one on top, so that both show where
/// they coincide.
pub(super) fn draw_ends<CT: CoordTranslate>(
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
pub(super) fn draw_legend<'a, CT: CoordTranslate>(
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
pub(super) fn title_style() -> TextStyle<'static> {
    ("sans-serif", 26).into_font().into()
}

/// The text style of axis descriptions, legends and notes.
pub(super) fn label_style() -> TextStyle<'static> {
    ("sans-serif", 18).into_font().into()
}

/// The smallest and the largest finite value (infinities when none).
pub(super) fn finite_bounds(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
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
pub(super) fn padded_range(values: impl IntoIterator<Item = f64>, pad: f64) -> Range<f64> {
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
pub(super) fn tick_labels(range: &Range<f64>) -> impl Fn(&f64) -> String + use<> {
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
pub(super) fn centred(range: Range<f64>, span: f64) -> Range<f64> {
    let centre = (range.start + range.end) / 2.0;
    (centre - span / 2.0)..(centre + span / 2.0)
}

/// The maximal runs of consecutive finite points, each drawn as one curve.
pub(super) fn finite_runs<P: Copy>(
    points: &[P],
    finite: impl Fn(&P) -> bool,
) -> impl Iterator<Item = &[P]> {
    points
        .split(move |p| !finite(p))
        .filter(|run| !run.is_empty())
}

/// The corner of the plot whose legend-sized box (40% of the width, 30% of
/// the height) holds the fewest points: where the legend hides the least.
pub(super) fn emptiest_corner(
    points: &[(f64, f64)],
    x: &Range<f64>,
    y: &Range<f64>,
) -> SeriesLabelPosition {
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
