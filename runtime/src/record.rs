//! Recording a simulation: a header of column names, then one row of numbers
//! per recorded time, in the layout of the `chaplygin simulate` command's
//! `trajectory.csv`: `t`, the coordinates by name, the rest of the state by
//! name (`dot(q)`, the momenta, controller states), the inputs by name,
//! `energy` (the total stored energy, controller included) and
//! `constraint_residual` (the largest `|A(q) qdot|`).
//!
//! A [`Table`] keeps the rows in memory; a [`CsvRecorder`] writes them as CSV
//! (numbers printed as the shortest decimal that reads back to the same
//! `f64`, in scientific notation below `1e-5` and from `1e16`, so the same
//! run writes the same bytes).

use std::io;

/// Where a simulation's rows go.
pub trait Recorder {
    /// Called once, first, with the column names.
    ///
    /// # Errors
    /// An I/O error of the destination.
    fn start(&mut self, columns: &[String]) -> io::Result<()>;

    /// One row, as many values as there are columns.
    ///
    /// # Errors
    /// An I/O error of the destination.
    fn record(&mut self, row: &[f64]) -> io::Result<()>;

    /// Called once at the end, also when the simulation stops with an
    /// error, so that what was recorded is complete and flushed.
    ///
    /// # Errors
    /// An I/O error of the destination.
    fn finish(&mut self) -> io::Result<()>;
}

/// Rows kept in memory.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// The column names.
    pub columns: Vec<String>,
    /// The rows, each with one value per column.
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table.
    pub fn new() -> Self {
        Self::default()
    }

    /// The values of the column called `name`, if there is one.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let index = self.columns.iter().position(|c| c == name)?;
        Some(self.rows.iter().map(|row| row[index]).collect())
    }
}

/// A recorder behind a mutable reference (a `&mut dyn Recorder` among
/// them).
impl<R: Recorder + ?Sized> Recorder for &mut R {
    fn start(&mut self, columns: &[String]) -> io::Result<()> {
        (**self).start(columns)
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        (**self).record(row)
    }

    fn finish(&mut self) -> io::Result<()> {
        (**self).finish()
    }
}

impl Recorder for Table {
    fn start(&mut self, columns: &[String]) -> io::Result<()> {
        self.columns = columns.to_vec();
        self.rows.clear();
        Ok(())
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        self.rows.push(row.to_vec());
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// Rows written as CSV with a header row.
#[derive(Debug)]
pub struct CsvRecorder<W: io::Write> {
    writer: csv::Writer<W>,
    field: String,
}

impl<W: io::Write> CsvRecorder<W> {
    /// CSV into `destination`.
    pub fn new(destination: W) -> Self {
        Self {
            writer: csv::Writer::from_writer(destination),
            field: String::new(),
        }
    }

    /// The destination, after flushing what was written.
    ///
    /// # Errors
    /// When flushing fails.
    pub fn into_inner(self) -> io::Result<W> {
        self.writer
            .into_inner()
            .map_err(|error| io::Error::other(error.to_string()))
    }
}

impl CsvRecorder<io::BufWriter<std::fs::File>> {
    /// CSV into a new file at `path` (replacing one that is there).
    ///
    /// # Errors
    /// When the file cannot be created.
    pub fn create(path: impl AsRef<std::path::Path>) -> io::Result<Self> {
        Ok(Self::new(io::BufWriter::new(std::fs::File::create(path)?)))
    }
}

/// `value` as [`CsvRecorder`] writes it: the shortest decimal that reads
/// back to it, positional for magnitudes from `1e-5` to below `1e16` (and
/// zero), scientific otherwise.
pub fn shortest_decimal(value: f64) -> String {
    let mut text = String::new();
    write_number(&mut text, value).expect("writing to a String does not fail");
    text
}

/// The shortest decimal that reads back to `value`: positional for
/// magnitudes from `1e-5` to below `1e16` (and zero), scientific otherwise.
fn write_number(field: &mut String, value: f64) -> std::fmt::Result {
    use std::fmt::Write;
    let magnitude = value.abs();
    if value == 0.0 || (1e-5..1e16).contains(&magnitude) || !value.is_finite() {
        write!(field, "{value}")
    } else {
        write!(field, "{value:e}")
    }
}

impl<W: io::Write> Recorder for CsvRecorder<W> {
    fn start(&mut self, columns: &[String]) -> io::Result<()> {
        self.writer.write_record(columns).map_err(io::Error::from)
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        for value in row {
            self.field.clear();
            write_number(&mut self.field, *value).map_err(io::Error::other)?;
            self.writer.write_field(&self.field)?;
        }
        self.writer
            .write_record(None::<&[u8]>)
            .map_err(io::Error::from)
    }

    fn finish(&mut self) -> io::Result<()> {
        self.writer.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly() {
        let values = [
            0.0,
            -0.0,
            1.0,
            0.1,
            5.551115123125783e-17,
            -2.5e20,
            123456.789,
            1e-5,
        ];
        let mut csv = CsvRecorder::new(Vec::new());
        csv.start(&vec!["v".to_string(); 8]).unwrap();
        csv.record(&values).unwrap();
        let text = String::from_utf8(csv.into_inner().unwrap()).unwrap();
        let row = text.lines().nth(1).unwrap();
        assert_eq!(
            row,
            "0,-0,1,0.1,5.551115123125783e-17,-2.5e20,123456.789,0.00001"
        );
        let parsed: Vec<f64> = row.split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(parsed, values);
    }
}
