//! What the commands write: tables as CSV, and tables as the plots read
//! them.

use chaplygin::plot;
use chaplygin::runtime::record::{CsvRecorder, Recorder, Table};
use std::io::Write;
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
    write_rows(table, CsvRecorder::create(path)?)
}

/// Writes `table` as CSV at `path` after a first line `# MARK` that says
/// what its rows are (read with `comment="#"` in pandas, `comments="#"` in
/// NumPy).
pub fn write_marked_table(table: &Table, path: &Path, mark: &str) -> std::io::Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let mut file = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(file, "# {mark}")?;
    write_rows(table, CsvRecorder::new(file))
}

/// `table`'s header and rows into `csv`.
fn write_rows<W: Write>(table: &Table, mut csv: CsvRecorder<W>) -> std::io::Result<()> {
    csv.start(&table.columns)?;
    for row in &table.rows {
        csv.record(row)?;
    }
    csv.finish()
}
