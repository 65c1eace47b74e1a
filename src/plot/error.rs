//! Why plots could not be written.

use super::EDGES;
use std::path::PathBuf;

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
