//! `--sweep VAR=START:STOP:STEP`: the grid, `eigenvalues.csv` (columns
//! `VAR, re_1, im_1, ..., re_m, im_m`, eigenvalues by descending real
//! part), the intervals of VAR over which the motion is asymptotically
//! stable and the values where a count (of unstable modes) changes.

use std::fmt::Write as _;
use std::path::Path;

/// The grid points a sweep may take.
const MAX_POINTS: usize = 1_000_000;

/// The most decimal places of START and STEP whose grid points are rounded
/// to decimals.
const MAX_DECIMALS: i32 = 9;

/// A swept variable and its grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// The variable's name.
    pub variable: String,
    /// The first value.
    pub start: f64,
    /// The last value asked for.
    pub stop: f64,
    /// The step.
    pub step: f64,
}

/// What is wrong with a sweep.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// Not `VAR=START:STOP:STEP` with three numbers.
    #[error("--sweep: expected VAR=START:STOP:STEP with three numbers, found `{0}`")]
    Malformed(String),
    /// The step is not positive.
    #[error("--sweep {variable}: STEP must be positive, found {step}")]
    Step {
        /// The variable.
        variable: String,
        /// The step given.
        step: f64,
    },
    /// STOP is below START.
    #[error("--sweep {variable}: empty range, STOP {stop} is below START {start}")]
    Empty {
        /// The variable.
        variable: String,
        /// START.
        start: f64,
        /// STOP.
        stop: f64,
    },
    /// Too many grid points.
    #[error("--sweep {variable}: {points} grid points, at most {MAX_POINTS}")]
    TooMany {
        /// The variable.
        variable: String,
        /// The points asked for.
        points: f64,
    },
}

/// Parses `VAR=START:STOP:STEP` (clap's value parser).
pub fn parse(text: &str) -> Result<Sweep, String> {
    let malformed = || SweepError::Malformed(text.to_string()).to_string();
    let (variable, range) = text.split_once('=').ok_or_else(malformed)?;
    let numbers: Vec<f64> = range
        .split(':')
        .map(|part| part.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| malformed())?;
    let variable = variable.trim();
    let valid_name =
        variable.chars().all(|c| c.is_alphanumeric() || c == '_') && !variable.is_empty();
    match numbers[..] {
        [start, stop, step] if valid_name && numbers.iter().all(|x| x.is_finite()) => Ok(Sweep {
            variable: variable.to_string(),
            start,
            stop,
            step,
        }),
        _ => Err(malformed()),
    }
}

impl Sweep {
    /// `START + i STEP` for `i = 0, 1, ...` up to STOP, STOP included when
    /// it is on the grid (to round-off: within 1e-9 steps). When START and
    /// STEP are decimals of at most `MAX_DECIMALS` places, each point is
    /// the double nearest its decimal value (`0:10:0.01` has `6.02`, not
    /// `0.01 * 602 = 6.0200000000000005`).
    ///
    /// # Errors
    /// [`SweepError`]: a step that is not positive, an empty range, too
    /// many points.
    pub fn grid(&self) -> Result<Vec<f64>, SweepError> {
        let variable = self.variable.clone();
        if self.step <= 0.0 {
            return Err(SweepError::Step {
                variable,
                step: self.step,
            });
        }
        if self.stop < self.start {
            return Err(SweepError::Empty {
                variable,
                start: self.start,
                stop: self.stop,
            });
        }
        let intervals = ((self.stop - self.start) / self.step + 1e-9).floor();
        if intervals + 1.0 > MAX_POINTS as f64 {
            return Err(SweepError::TooMany {
                variable,
                points: intervals + 1.0,
            });
        }
        let points = 0..=intervals as usize;
        Ok(match self.decimal_scale() {
            Some(scale) => {
                let (start, step) = (self.start * scale, self.step * scale);
                points
                    .map(|i| (start + i as f64 * step).round() / scale)
                    .collect()
            }
            None => points.map(|i| self.start + i as f64 * self.step).collect(),
        })
    }

    /// `10^d` for the fewest decimal places `d` that write START and STEP
    /// (to 1e-9 of a unit in the last place), if at most [`MAX_DECIMALS`].
    fn decimal_scale(&self) -> Option<f64> {
        (0..=MAX_DECIMALS).map(|d| 10f64.powi(d)).find(|scale| {
            [self.start, self.step].iter().all(|x| {
                ((x * scale).round() - x * scale).abs() <= 1e-9 * (1.0 + (x * scale).abs())
            })
        })
    }
}

/// `eigenvalues.csv`: a header `VAR, re_1, im_1, ...` and one row per value.
pub fn csv(variable: &str, values: &[f64], eigenvalues: &[Vec<(f64, f64)>]) -> String {
    let m = eigenvalues.first().map_or(0, Vec::len);
    let mut text = variable.to_string();
    for i in 1..=m {
        let _ = write!(text, ",re_{i},im_{i}");
    }
    text.push('\n');
    for (value, row) in values.iter().zip(eigenvalues) {
        let _ = write!(text, "{value}");
        for (re, im) in row {
            let _ = write!(text, ",{re},{im}");
        }
        text.push('\n');
    }
    text
}

/// Writes `text` to `file`, creating its directory.
pub fn write(file: &Path, text: &str) -> std::io::Result<()> {
    if let Some(dir) = file.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(file, text)
}

/// A run of consecutive grid values where a property holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Its first and last grid values.
    pub grid: (f64, f64),
    /// Its ends refined between grid points: where the property changes
    /// between a grid value inside and the next one outside, the change
    /// located by bisection to [`REFINED`] relative; a grid end stays.
    pub refined: (f64, f64),
}

/// How closely [`refined_intervals`] locates an end, relative to
/// `max(1, |value|)`.
pub const REFINED: f64 = 1e-11;

/// The runs of `holds` over the grid `values`, each end refined by
/// bisection of `at` (whether the property holds at a value) between the
/// grid values on either side of it.
///
/// # Errors
/// The first error of `at`.
pub fn refined_intervals<E>(
    values: &[f64],
    holds: &[bool],
    mut at: impl FnMut(f64) -> Result<bool, E>,
) -> Result<Vec<Interval>, E> {
    let mut intervals = Vec::new();
    let mut start = None;
    for index in 0..=values.len() {
        match (start, holds.get(index).copied().unwrap_or(false)) {
            (None, true) => start = Some(index),
            (Some(first), false) => {
                let last = index - 1;
                let refined = (
                    match first.checked_sub(1) {
                        Some(outside) => bisect(values[outside], values[first], &mut at)?,
                        None => values[first],
                    },
                    match index < values.len() {
                        true => bisect(values[index], values[last], &mut at)?,
                        false => values[last],
                    },
                );
                intervals.push(Interval {
                    grid: (values[first], values[last]),
                    refined,
                });
                start = None;
            }
            _ => {}
        }
    }
    Ok(intervals)
}

/// Where a count over a sweep (of unstable modes) changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Change {
    /// The value where it changes, refined between the grid values on
    /// either side to [`REFINED`] relative.
    pub value: f64,
    /// The count below and above it.
    pub counts: (usize, usize),
}

/// Where `counts` (one per grid value of `values`) changes between
/// consecutive grid values, each located by bisection of `at` (the count
/// at a value) for where it first takes the count of the grid value above.
///
/// # Errors
/// The first error of `at`.
pub fn changes<E>(
    values: &[f64],
    counts: &[usize],
    mut at: impl FnMut(f64) -> Result<usize, E>,
) -> Result<Vec<Change>, E> {
    let mut found = Vec::new();
    for (pair, grid) in counts.windows(2).zip(values.windows(2)) {
        let (below, above) = (pair[0], pair[1]);
        if below != above {
            let value = bisect(grid[0], grid[1], &mut |value| at(value).map(|n| n == above))?;
            found.push(Change {
                value,
                counts: (below, above),
            });
        }
    }
    Ok(found)
}

/// Where the property changes between `outside` (where it does not hold)
/// and `inside` (where it does), to [`REFINED`]; the midpoint of the last
/// bracket.
fn bisect<E>(
    mut outside: f64,
    mut inside: f64,
    at: &mut impl FnMut(f64) -> Result<bool, E>,
) -> Result<f64, E> {
    let tolerance = REFINED * inside.abs().max(1.0);
    while (inside - outside).abs() > tolerance {
        let middle = 0.5 * (inside + outside);
        match at(middle)? {
            true => inside = middle,
            false => outside = middle,
        }
    }
    Ok(0.5 * (inside + outside))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_includes_stop_when_on_it() {
        let sweep = parse("v=0:1:0.1").expect("parses");
        let grid = sweep.grid().expect("a grid");
        assert_eq!(grid.len(), 11);
        assert!((grid[10] - 1.0).abs() < 1e-15);
        let off = parse("v=0:1:0.3").expect("parses").grid().expect("a grid");
        assert_eq!(off.len(), 4);
    }

    /// Each point of a decimal grid is the double its decimal parses to.
    #[test]
    fn decimal_grids_have_decimal_points() {
        let grid = parse("v=0:10:0.01")
            .expect("parses")
            .grid()
            .expect("a grid");
        assert_eq!(grid.len(), 1001);
        assert_eq!(grid[602], "6.02".parse::<f64>().expect("a number"));
        assert_eq!(grid[430], 4.3);
        let fine = parse("v=4.2923:4.2925:0.000001").expect("parses");
        let fine = fine.grid().expect("a grid");
        assert_eq!(fine.len(), 201);
        assert_eq!(fine[83], 4.292383);
        let third = parse("v=0:1:0.3333333333333").expect("parses");
        assert_eq!(third.grid().expect("a grid").len(), 4);
    }

    #[test]
    fn bad_sweeps_are_named() {
        assert!(parse("v=0:1").is_err());
        assert!(parse("v 0:1:2").is_err());
        assert!(matches!(
            parse("v=0:1:0").expect("parses").grid(),
            Err(SweepError::Step { .. })
        ));
        assert!(matches!(
            parse("v=1:0:0.1").expect("parses").grid(),
            Err(SweepError::Empty { .. })
        ));
    }

    #[test]
    fn stable_runs_become_intervals() {
        let values = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let stable = [false, true, true, false, true, false];
        let grid: Vec<(f64, f64)> = refined_intervals(&values, &stable, |v| Ok::<_, ()>(v < 2.5))
            .unwrap()
            .iter()
            .map(|interval| interval.grid)
            .collect();
        assert_eq!(grid, [(1.0, 2.0), (4.0, 4.0)]);
    }

    #[test]
    fn the_csv_has_a_column_pair_per_eigenvalue() {
        let text = csv("v", &[0.5], &[vec![(-1.0, 2.0), (-1.0, -2.0)]]);
        assert_eq!(text, "v,re_1,im_1,re_2,im_2\n0.5,-1,2,-1,-2\n");
    }

    #[test]
    fn interval_ends_are_refined_between_grid_points() {
        let values: Vec<f64> = (0..=10).map(f64::from).collect();
        let inside = |v: f64| (2.5..=std::f64::consts::PI * 2.0).contains(&v) || v > 9.5;
        let holds: Vec<bool> = values.iter().map(|&v| inside(v)).collect();
        let found = refined_intervals(&values, &holds, |v| Ok::<_, ()>(inside(v))).unwrap();
        assert_eq!(found.len(), 2);
        assert_eq!(found[0].grid, (3.0, 6.0));
        assert!((found[0].refined.0 - 2.5).abs() <= 2.0 * REFINED * 2.5);
        assert!((found[0].refined.1 - 2.0 * std::f64::consts::PI).abs() <= 2.0 * REFINED * 6.3);
        assert_eq!(found[1].grid, (10.0, 10.0));
        assert!((found[1].refined.0 - 9.5).abs() <= 2.0 * REFINED * 9.5);
        assert_eq!(found[1].refined.1, 10.0);
        let none = refined_intervals(&values, &[false; 11], |_| Ok::<_, ()>(false)).unwrap();
        assert!(none.is_empty());
    }

    /// A count that steps at 2.5 (1 -> 0) and at pi (0 -> 2), the grid
    /// seeing both: each change located between its grid values.
    #[test]
    fn counts_change_where_bisection_finds_them() {
        let values: Vec<f64> = (0..=5).map(f64::from).collect();
        let count = |v: f64| match v {
            v if v < 2.5 => 1,
            v if v < std::f64::consts::PI => 0,
            _ => 2,
        };
        let counts: Vec<usize> = values.iter().map(|&v| count(v)).collect();
        let found = changes(&values, &counts, |v| Ok::<_, ()>(count(v))).unwrap();
        assert_eq!(found.len(), 2);
        assert_eq!(found[0].counts, (1, 0));
        assert!((found[0].value - 2.5).abs() <= 2.0 * REFINED * 2.5);
        assert_eq!(found[1].counts, (0, 2));
        assert!((found[1].value - std::f64::consts::PI).abs() <= 2.0 * REFINED * 4.0);
    }
}
