//! What the commands write: tables as CSV, and tables as the plots read
//! them.

use chaplygin::plot;
use chaplygin::runtime::record::{CsvRecorder, Recorder, Table};
use std::path::Path;

/// `table` as the plots read it.
pub fn plotted(table: &Table) -> Result<plot::Table, plot::PlotError> {
    let mut plotted = plot::Table::new(table.columns.clone())?;
    for row in &table.rows {
        plotted.push_row(row.clone())?;
    }
    Ok(plotted)
}

/// Writes `table` as CSV at `path`, creating its directory.
pub fn write_table(table: &Table, path: &Path) -> std::io::Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let mut csv = CsvRecorder::create(path)?;
    csv.start(&table.columns)?;
    for row in &table.rows {
        csv.record(row)?;
    }
    csv.finish()
}
