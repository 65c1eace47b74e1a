//! What is plotted: the trajectory ([`Table`]) and which of its columns
//! each plot reads ([`PlotSpec`], [`PlanarPath`], [`Figure4`], [`Series`]).

use super::{EDGES, PlotError};
use std::collections::BTreeMap;

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
    /// Ground tracks of declared points drawn with the path.
    pub tracks: Vec<Track>,
}

/// The columns of one point's ground track: its x and y in ground axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    /// The point's name, shown in the legend.
    pub point: String,
    /// Column of the point's ground x.
    pub x: String,
    /// Column of the point's ground y.
    pub y: String,
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

/// Columns drawn together against time into `NAME.png`.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The file's name without `.png`.
    pub name: String,
    /// The title.
    pub title: String,
    /// The y axis description.
    pub y_desc: String,
    /// The columns, one curve each.
    pub columns: Vec<String>,
}

/// Which columns [`crate::plot::write_plots`] draws, their units, and the image size.
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
    /// Columns against time, each series into its own file.
    pub series: Vec<Series>,
    /// Units by column name, shown in axis labels as `name [unit]`.
    pub units: BTreeMap<String, String>,
    /// Image width and height in pixels, each from 200 to 8192.
    pub size: (u32, u32),
}

impl Default for PlotSpec {
    /// docs/INTERFACE.md section 3's names: `t`; `x`, `y`, `theta`; `energy`;
    /// `constraint_residual`. No Figure 4, no units, 1024 x 768 pixels.
    fn default() -> Self {
        Self {
            time: "t".into(),
            path: Some(PlanarPath {
                x: "x".into(),
                y: "y".into(),
                heading: Some("theta".into()),
                tracks: Vec::new(),
            }),
            energy: Some("energy".into()),
            constraint_residual: Some("constraint_residual".into()),
            figure4: None,
            series: Vec::new(),
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
                tracks: Vec::new(),
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

    /// This spec with `series` drawn too (one left out where it has no
    /// column).
    pub fn with_series(mut self, series: Series) -> Self {
        if !series.columns.is_empty() {
            self.series.push(series);
        }
        self
    }

    /// This spec with `tracks` drawn along the path (none without a path).
    pub fn with_tracks(mut self, tracks: Vec<Track>) -> Self {
        if let Some(path) = &mut self.path {
            path.tracks = tracks;
        }
        self
    }

    /// This spec with `unit` shown on the axes of `column`.
    pub fn with_unit(mut self, column: &str, unit: &str) -> Self {
        self.units.insert(column.to_string(), unit.to_string());
        self
    }

    /// The axis label of a column: `name [unit]`, or the name alone.
    pub(super) fn label(&self, column: &str) -> String {
        match self.units.get(column) {
            Some(unit) => format!("{column} [{unit}]"),
            None => column.to_string(),
        }
    }

    /// Every column the spec names, each once, time first.
    pub(super) fn named_columns(&self) -> Vec<&str> {
        let mut names = vec![self.time.as_str()];
        if let Some(path) = &self.path {
            names.extend([path.x.as_str(), path.y.as_str()]);
            names.extend(path.heading.as_deref());
            for track in &path.tracks {
                names.extend([track.x.as_str(), track.y.as_str()]);
            }
        }
        names.extend(self.energy.as_deref());
        names.extend(self.constraint_residual.as_deref());
        if let Some(figure4) = &self.figure4 {
            names.extend([&figure4.alpha1, &figure4.alpha2, &figure4.xt].map(String::as_str));
        }
        for series in &self.series {
            for name in &series.columns {
                if !names.contains(&name.as_str()) {
                    names.push(name);
                }
            }
        }
        names
    }

    /// Checks the image size and Figure 4's parameters.
    pub(super) fn validate(&self) -> Result<(), PlotError> {
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
