//! `--guess FILE.csv`: a table with `t` and any of `plan.csv`'s columns,
//! each interpolated linearly at the nodes' times and held at its end
//! values outside the table's range. Lines starting with `#` are skipped:
//! an interrupted plan's `plan.csv`, marked so, resumes the solve.

use super::RequestError;
use crate::runtime::record;
use std::path::Path;

/// A guess as read: its times, increasing, and its columns of the nodes'
/// variables, by their index among a node's.
pub(in crate::driver::plan) struct Guess {
    t: Vec<f64>,
    columns: Vec<(usize, Vec<f64>)>,
}

/// What a table is read as: the flag it comes with, the columns read and
/// ignored, and how its messages name them.
#[derive(Clone, Copy)]
pub(in crate::driver::plan) struct Table {
    pub flag: &'static str,
    pub ignored: &'static [&'static str],
    pub others: &'static str,
}

impl Guess {
    /// The table at `path`, its columns among `variables` (a node's) or
    /// `table.ignored` (read and ignored).
    pub(in crate::driver::plan) fn read(
        table: Table,
        path: &Path,
        variables: &[String],
    ) -> Result<Self, RequestError> {
        let source = path.display().to_string();
        let failed = |reason: String| RequestError::GuessFile {
            flag: table.flag,
            path: source.clone(),
            reason,
        };
        let text = std::fs::read_to_string(path).map_err(|e| failed(e.to_string()))?;
        let mut lines = text
            .lines()
            .filter(|line| !line.trim().is_empty() && !line.starts_with('#'));
        let header: Vec<String> = lines
            .next()
            .ok_or_else(|| failed("it is empty".into()))?
            .split(',')
            .map(|name| name.trim().trim_matches('"').to_string())
            .collect();
        let rows = lines
            .enumerate()
            .map(|(row, line)| {
                numbers(line, header.len()).map_err(|e| failed(format!("row {}: {e}", row + 1)))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let read = record::Table {
            columns: header,
            rows,
        };
        Self::from_table(table, &source, &read, variables)
    }

    /// The table `read`, in memory, which messages call `source`; its
    /// columns among `variables` (a node's) or `table.ignored`.
    pub(in crate::driver::plan) fn from_table(
        table: Table,
        source: &str,
        read: &record::Table,
        variables: &[String],
    ) -> Result<Self, RequestError> {
        let failed = |reason: String| RequestError::GuessFile {
            flag: table.flag,
            path: source.to_string(),
            reason,
        };
        let header = &read.columns;
        let unknown: Vec<&str> = header
            .iter()
            .map(String::as_str)
            .filter(|name| *name != "t" && !variables.iter().any(|v| v == name))
            .filter(|name| !table.ignored.contains(name))
            .collect();
        if !unknown.is_empty() {
            return Err(RequestError::GuessColumns {
                flag: table.flag,
                others: table.others,
                path: source.to_string(),
                unknown: unknown.join(", "),
                known: variables.join(", "),
            });
        }
        if let Some(row) = read.rows.iter().position(|row| row.len() != header.len()) {
            let width = read.rows[row].len();
            return Err(failed(format!(
                "row {}: {width} values under {} columns",
                row + 1,
                header.len()
            )));
        }
        let column = |c: usize| read.rows.iter().map(|row| row[c]).collect::<Vec<f64>>();
        let time = header
            .iter()
            .position(|name| name == "t")
            .ok_or_else(|| failed("it has no column `t`".into()))?;
        let t = column(time);
        if t.is_empty() {
            return Err(failed("it has no rows".into()));
        }
        if let Some(row) = t.windows(2).position(|pair| pair[1] <= pair[0]) {
            return Err(failed(format!(
                "row {}: `t` = {} does not increase strictly from {}",
                row + 2,
                t[row + 1],
                t[row]
            )));
        }
        let columns = header
            .iter()
            .enumerate()
            .filter_map(|(c, name)| {
                let index = variables.iter().position(|v| v == name)?;
                Some((index, column(c)))
            })
            .collect();
        Ok(Self { t, columns })
    }

    /// The number of rows.
    pub(in crate::driver::plan) fn rows(&self) -> usize {
        self.t.len()
    }

    /// The times, increasing strictly.
    pub(in crate::driver::plan) fn times(&self) -> &[f64] {
        &self.t
    }

    /// The first and last `t`.
    pub(in crate::driver::plan) fn span(&self) -> (f64, f64) {
        (self.t[0], self.t[self.t.len() - 1])
    }

    /// The indices, among a node's variables, of the columns read.
    pub(in crate::driver::plan) fn columns(&self) -> impl Iterator<Item = usize> + '_ {
        self.columns.iter().map(|(index, _)| *index)
    }

    /// Each column read, by its index among a node's variables, with its
    /// value at `t`.
    pub(in crate::driver::plan) fn at(&self, t: f64) -> impl Iterator<Item = (usize, f64)> + '_ {
        let after = self.t.partition_point(|s| *s <= t);
        self.columns.iter().map(move |(index, values)| {
            let value = match after {
                0 => values[0],
                k if k == self.t.len() => values[k - 1],
                k => {
                    let s = (t - self.t[k - 1]) / (self.t[k] - self.t[k - 1]);
                    values[k - 1] + s * (values[k] - values[k - 1])
                }
            };
            (*index, value)
        })
    }
}

/// A row's `width` numbers.
fn numbers(line: &str, width: usize) -> Result<Vec<f64>, String> {
    let values = line
        .split(',')
        .map(|cell| {
            let cell = cell.trim();
            cell.parse::<f64>()
                .map_err(|_| format!("`{cell}` is not a number"))
        })
        .collect::<Result<Vec<f64>, String>>()?;
    if values.len() != width {
        return Err(format!("{} values under {width} columns", values.len()));
    }
    Ok(values)
}

#[cfg(test)]
mod tests {
    use super::{Guess, RequestError, record};

    /// The guess of `text` over the variables `x` and `push`.
    fn read(text: &str) -> Result<Guess, RequestError> {
        let dir = tempfile::tempdir().expect("a directory");
        let path = dir.path().join("guess.csv");
        std::fs::write(&path, text).expect("written");
        let variables = ["x", "dot(x)", "push"].map(String::from);
        let table = super::Table {
            flag: "--guess",
            ignored: &["energy"],
            others: "",
        };
        Guess::read(table, &path, &variables)
    }

    #[test]
    fn columns_are_interpolated_and_held_beyond_the_ends() {
        let guess = read("push,t,energy,x\n1,0,9,0\n3,2,9,4\n").expect("a guess");
        let at = |t: f64| guess.at(t).collect::<Vec<_>>();
        assert_eq!(at(-1.0), [(2, 1.0), (0, 0.0)]);
        assert_eq!(at(0.5), [(2, 1.5), (0, 1.0)]);
        assert_eq!(at(2.0), [(2, 3.0), (0, 4.0)]);
        assert_eq!(at(7.0), [(2, 3.0), (0, 4.0)]);
    }

    /// An interrupted plan's `plan.csv` starts with a `#` line.
    #[test]
    fn a_marked_table_is_read_past_its_mark() {
        let marked = "# not verified: interrupted after 3 iterations (plan.json)\nt,x\n0,1\n2,5\n";
        let guess = read(marked).expect("a guess");
        assert_eq!(guess.at(1.0).collect::<Vec<_>>(), [(0, 3.0)]);
    }

    /// A table in memory reads as its CSV does.
    #[test]
    fn a_table_in_memory_reads_as_its_csv() {
        let variables = ["x", "dot(x)", "push"].map(String::from);
        let kind = super::Table {
            flag: "--data",
            ignored: &[],
            others: "",
        };
        let rows = record::Table {
            columns: ["push", "t", "x"].map(String::from).to_vec(),
            rows: vec![vec![1.0, 0.0, 0.0], vec![3.0, 2.0, 4.0]],
        };
        let guess = Guess::from_table(kind, "rows", &rows, &variables).expect("a guess");
        let csv = read("push,t,x\n1,0,0\n3,2,4\n").expect("a guess");
        for t in [-1.0, 0.5, 2.0] {
            assert_eq!(
                guess.at(t).collect::<Vec<_>>(),
                csv.at(t).collect::<Vec<_>>()
            );
        }
        let unknown = record::Table {
            columns: ["t", "q"].map(String::from).to_vec(),
            rows: vec![vec![0.0, 1.0]],
        };
        let message = Guess::from_table(kind, "rows", &unknown, &variables)
            .err()
            .expect("an error")
            .to_string();
        assert_eq!(
            message,
            "--data rows: unknown columns q (t, x, dot(x), push)"
        );
    }

    #[test]
    fn bad_tables_are_one_line_errors() {
        let line = |text: &str| read(text).err().expect("an error").to_string();
        assert!(line("t,x,q\n0,1,2\n").contains("unknown columns q ("));
        assert!(line("x\n1\n").contains("no column `t`"));
        assert!(
            line("t,x\n0,1\n0,2\n").ends_with("row 2: `t` = 0 does not increase strictly from 0")
        );
        assert!(
            line("t,x\n0,1\n2,2\n1,3\n")
                .ends_with("row 3: `t` = 1 does not increase strictly from 2")
        );
        assert!(line("t,x\n").contains("it has no rows"));
        assert!(line("t,x\n0,a\n").contains("row 1: `a` is not a number"));
        assert!(line("t,x\n0\n").contains("row 1: 1 values under 2 columns"));
    }
}
