//! `--guess FILE.csv`: a table with `t` and any of `plan.csv`'s columns,
//! each interpolated linearly at the nodes' times and held at its end
//! values outside the table's range. Lines starting with `#` are skipped:
//! an interrupted plan's `plan.csv`, marked so, resumes the solve.
//!
//! A table in the reduced or the momentum form (a `trajectory.csv` or
//! `plan.csv` written in it) is read in the coordinates and velocities
//! its states move with: `dot(q) = X(q) alpha` in the chart of the row's
//! `chart` column (0 without one), or `dot(q)` reconstructed from `(q,
//! rdot, p)` ([`Form`]'s velocities). So `simulate`'s trajectory in its
//! default form is data for `identify` as it stands, unless those
//! velocities depend on a parameter it estimates (the reduced momenta of
//! a momentum basis weighted by the masses, say): a one-line error then
//! asks for the velocities themselves.

use super::RequestError;
use super::node_columns;
use crate::driver::plan::form::Form;
use crate::runtime::record;
use chaplygin_codegen::interpret::InterpretedModel;
use std::collections::BTreeSet;
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
    /// The table at `path` or, where given, `read` in memory (which
    /// messages call `path`), in the coordinates and velocities of
    /// `model`: its columns among a node's variables or `table.ignored`.
    /// `estimated` are the indices of the parameters an estimate leaves
    /// unknown.
    pub(in crate::driver::plan) fn of_model(
        (table, model, estimated): (Table, &InterpretedModel, &[usize]),
        path: &Path,
        read: Option<&record::Table>,
    ) -> Result<Self, RequestError> {
        let source = path.display().to_string();
        let file;
        let read = match read {
            Some(read) => read,
            None => {
                file = Self::read_file(table, path)?;
                &file
            }
        };
        let read =
            in_velocities((model, estimated), read).map_err(|reason| RequestError::GuessFile {
                flag: table.flag,
                path: source.clone(),
                reason,
            })?;
        Self::from_table(table, &source, &read, &node_columns(model))
    }

    /// The table at `path`, as written.
    fn read_file(table: Table, path: &Path) -> Result<record::Table, RequestError> {
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
        Ok(record::Table {
            columns: header,
            rows,
        })
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

/// `read` with the reduced or the momentum form's state in place of the
/// velocities (every one of that form's state columns, its momenta among
/// them) rewritten in the coordinates and the velocities `dot(q)`, the
/// velocities it held and its `chart` column dropped; any other table as
/// it is.
///
/// # Errors
/// A row whose `chart` is not one of the model's, or whose velocities
/// cannot be evaluated; velocities that read a parameter of `estimated`.
fn in_velocities(
    (model, estimated): (&InterpretedModel, &[usize]),
    read: &record::Table,
) -> Result<record::Table, String> {
    let width = read.columns.len();
    let whole = read.rows.iter().all(|row| row.len() == width);
    let Some((form, state)) = form_of(model, read).filter(|_| whole) else {
        return Ok(read.clone());
    };
    let position = |name: &str| read.columns.iter().position(|c| c == name);
    let chart = position("chart");
    check_estimated((model, form, estimated), &charts_of(read, chart)?)?;
    let (n, lagrange) = (model.sizes().n, Form::Lagrange.state_names(model));
    let dropped: Vec<usize> = (state[n..].iter().copied())
        .chain(chart)
        .chain(lagrange[n..].iter().filter_map(|name| position(name)))
        .collect();
    let kept: Vec<usize> = (0..width).filter(|c| !dropped.contains(c)).collect();
    let mut columns: Vec<String> = kept.iter().map(|&c| read.columns[c].clone()).collect();
    columns.extend_from_slice(&lagrange[n..]);
    let rows = (read.rows.iter().enumerate())
        .map(|(i, row)| {
            let x: Vec<f64> = state.iter().map(|&c| row[c]).collect();
            let qdot = velocities(model, form, &x, chart.map(|c| row[c] as usize))
                .map_err(|reason| format!("row {}: {reason}", i + 1))?;
            Ok(kept.iter().map(|&c| row[c]).chain(qdot).collect())
        })
        .collect::<Result<_, String>>()?;
    Ok(record::Table { columns, rows })
}

/// The form other than Lagrange's whose whole state `read` holds, its
/// own columns (the momenta) among them, and the state's columns.
fn form_of(model: &InterpretedModel, read: &record::Table) -> Option<(Form, Vec<usize>)> {
    let lagrange = Form::Lagrange.state_names(model);
    [Form::Reduced, Form::Momentum]
        .into_iter()
        .find_map(|form| {
            let names = form.state_names(model);
            let own = names.iter().any(|name| !lagrange.contains(name));
            let position = |name: &String| read.columns.iter().position(|c| c == name);
            let state: Option<Vec<usize>> = names.iter().map(position).collect();
            state.filter(|_| own).map(|state| (form, state))
        })
}

/// The charts the rows of `read` name in their column `chart`, each once.
///
/// # Errors
/// A value that is no chart's number.
fn charts_of(read: &record::Table, chart: Option<usize>) -> Result<Vec<usize>, String> {
    let values: BTreeSet<u64> = (chart.into_iter())
        .flat_map(|c| read.rows.iter().map(move |row| row[c].to_bits()))
        .collect();
    (values.into_iter().map(f64::from_bits))
        .map(|chart| {
            let index = chart as usize;
            (index as f64 == chart)
                .then_some(index)
                .ok_or_else(|| format!("`chart` = {chart} is not a chart's number"))
        })
        .collect()
}

/// Whether the velocities of `form`'s state in `charts` are free of the
/// parameters of indices `estimated`.
///
/// # Errors
/// The columns that give them and the estimated parameters they read.
fn check_estimated(
    (model, form, estimated): (&InterpretedModel, Form, &[usize]),
    charts: &[usize],
) -> Result<(), String> {
    let unknown: Vec<&str> = (estimated.iter())
        .filter(|&&k| reads_parameter(model, form, charts, k))
        .map(|&k| model.names().parameters[k].as_str())
        .collect();
    if unknown.is_empty() {
        return Ok(());
    }
    let (names, lagrange) = (form.state_names(model), Form::Lagrange.state_names(model));
    let own: Vec<&str> = (names.iter())
        .filter(|name| !lagrange.contains(name))
        .map(String::as_str)
        .collect();
    Err(format!(
        "its columns {} give the velocities through the estimated {}; give the velocities \
         dot(q) instead (simulate --formulation lagrange)",
        own.join(", "),
        unknown.join(", ")
    ))
}

/// Whether the velocities of `form`'s state read the parameter of index
/// `parameter`: in the reduced form, the `velocities` program of each of
/// `charts` (a chart composed at run time counts as reading every
/// parameter), in the momentum form `body_velocity` (the group's
/// reconstruction is kinematic).
fn reads_parameter(
    model: &InterpretedModel,
    form: Form,
    charts: &[usize],
    parameter: usize,
) -> bool {
    let name = if form == Form::Reduced {
        "velocities"
    } else {
        "body_velocity"
    };
    let programs: Vec<_> = (model.programs())
        .filter(|(function, _)| *function == name)
        .map(|(_, program)| program)
        .collect();
    let parameters = model.parameter_values().len();
    let reads = |chart: usize| {
        programs
            .get(chart)
            .is_none_or(|program| program.reads(program.input_count() - parameters + parameter))
    };
    match form {
        Form::Reduced if !charts.is_empty() => charts.iter().any(|&c| reads(c)),
        _ => reads(0),
    }
}

/// The velocities `dot(q)` of the state `x` of `form`, the reduced
/// momenta in `chart` (0 where none is given).
fn velocities(
    model: &InterpretedModel,
    form: Form,
    x: &[f64],
    chart: Option<usize>,
) -> Result<Vec<f64>, String> {
    let Some(chart) = chart.filter(|_| form == Form::Reduced) else {
        return Ok(form.velocities(model, x));
    };
    let (q, alpha) = x.split_at(model.sizes().n);
    model
        .call_in_chart(chart, "velocities", &[q, alpha])
        .map_err(|error| format!("chart {chart}: {error}"))
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
        let read = Guess::read_file(table, &path)?;
        Guess::from_table(table, &path.display().to_string(), &read, &variables)
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
