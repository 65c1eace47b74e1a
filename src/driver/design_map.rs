//! Design maps (docs/INTERFACE.md section 11): over a grid of one or two
//! parameters, at every design point the speeds at which a steady motion
//! is self-stable and the speeds where it gains or loses an unstable mode,
//! as Kooijman et al. (Science, 2011) and Moore's parameter studies chart
//! the benchmark bicycle over its trail, head angle and wheel sizes.
//!
//! A design point is the model with some parameters set: the request is
//! resolved on a clone of the model with the point's values
//! (`crate::driver::setup`), and [`linearize::stability`] run over the
//! speed grid. Parameters are run-time inputs of the model's programs, so a
//! design point costs linearizations, never a derivation or a compilation.
//! The points run in parallel (rayon); each is computed alone, from the
//! same inputs, so the map is the same, bit for bit, for any number of
//! threads. A stop flag set while the map runs (Ctrl-C) leaves the points
//! not yet started out.

use super::linearize::{self, LinearizeError, Stability};
use super::setup::{self, Asked, InputError, Setup};
use chaplygin_codegen::interpret::InterpretedModel;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::sync::atomic::{AtomicBool, Ordering};

/// A parameter varied over a map, and its values.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The parameter's name.
    pub name: String,
    /// Its values.
    pub values: Vec<f64>,
}

/// The steady motions a map linearizes: `linearize --at` assignments over
/// a speed grid.
#[derive(Clone, Copy, Debug)]
pub struct Motion<'a> {
    /// The operating point's assignments `NAME=EXPR`, whose expressions
    /// read the parameters and the speed variable.
    pub at: &'a [(String, String)],
    /// The speed variable and its grid.
    pub speed: (&'a str, &'a [f64]),
}

/// How a map runs: the threads, what is told as each point is done, and
/// the flag that stops it.
pub struct Run<'a> {
    /// The number of threads; `None` for rayon's default (every core, or
    /// `RAYON_NUM_THREADS`).
    pub jobs: Option<usize>,
    /// Called once per design point computed, from the thread that
    /// computed it.
    pub done: &'a (dyn Fn() + Sync),
    /// Once set, the points not yet started are left out.
    pub stop: &'a AtomicBool,
}

/// A design map's request that cannot be run.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// A varied or fixed parameter the model does not declare, or an
    /// `--at` assignment that does not read.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A parameter varied twice.
    #[error("--param {0}: varied twice")]
    Repeated(String),
    /// The speed variable is a parameter.
    #[error("--speed: `{0}` is a parameter; name the speed with a new variable that --at uses")]
    SpeedIsParameter(String),
    /// A design point with another number of values than parameters varied.
    #[error("design point {index}: {found} values for {expected} parameters")]
    PointSize {
        /// The point's index.
        index: usize,
        /// The number of parameters varied.
        expected: usize,
        /// The number of values given.
        found: usize,
    },
    /// The thread pool could not start.
    #[error("cannot start {jobs} threads: {message}")]
    Threads {
        /// The threads asked for.
        jobs: usize,
        /// Why not.
        message: String,
    },
}

/// The design points of `axes`: every combination of their values, the
/// last axis varying fastest.
pub fn grid(axes: &[Axis]) -> Vec<Vec<f64>> {
    axes.iter().fold(vec![Vec::new()], |points, axis| {
        points
            .iter()
            .flat_map(|point| {
                axis.values.iter().map(move |&value| {
                    let mut next = point.clone();
                    next.push(value);
                    next
                })
            })
            .collect()
    })
}

/// At each of `points` (the values of the parameters `names`, the model's
/// other parameters as `model` has them), the stability of `motion` over
/// its speed grid: `None` for a point the stop flag left out, an error for
/// a point that could not be linearized.
///
/// # Errors
/// [`MapError`]: a name that is not a parameter or is given twice, a
/// speed variable that is a parameter, a point of the wrong size, threads
/// that cannot start.
pub fn stability_at(
    model: &InterpretedModel,
    names: &[String],
    points: &[Vec<f64>],
    motion: Motion<'_>,
    run: &Run<'_>,
) -> Result<Vec<Option<Result<Stability, LinearizeError>>>, MapError> {
    check(model, names, points, motion)?;
    let point_stability = |point: &Vec<f64>| {
        if run.stop.load(Ordering::Relaxed) {
            return None;
        }
        let found = stability_of_design(model, names, point, motion);
        (run.done)();
        Some(found)
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(run.jobs.unwrap_or(0))
        .build()
        .map_err(|error| MapError::Threads {
            jobs: run.jobs.unwrap_or(0),
            message: error.to_string(),
        })?;
    Ok(pool.install(|| points.par_iter().map(point_stability).collect()))
}

/// Refuses names that are not parameters or are repeated, a speed that is
/// a parameter, points of the wrong size.
fn check(
    model: &InterpretedModel,
    names: &[String],
    points: &[Vec<f64>],
    motion: Motion<'_>,
) -> Result<(), MapError> {
    let parameters = &model.names().parameters;
    for (index, name) in names.iter().enumerate() {
        if names[..index].contains(name) {
            return Err(MapError::Repeated(name.clone()));
        }
    }
    if parameters.iter().any(|name| name == motion.speed.0) {
        return Err(MapError::SpeedIsParameter(motion.speed.0.to_string()));
    }
    design(model, names, None, motion)?;
    match points.iter().position(|point| point.len() != names.len()) {
        Some(index) => Err(MapError::PointSize {
            index,
            expected: names.len(),
            found: points[index].len(),
        }),
        None => Ok(()),
    }
}

/// `names` with the values of `point` (0 without one).
fn names_at(names: &[String], point: Option<&[f64]>) -> Vec<(String, f64)> {
    names
        .iter()
        .enumerate()
        .map(|(i, name)| (name.clone(), point.map_or(0.0, |values| values[i])))
        .collect()
}

/// The request of `motion` resolved on `model` with the parameters
/// `names` at `point` (0 without one).
///
/// # Errors
/// A name that is no parameter, or an assignment that does not read.
fn design(
    model: &InterpretedModel,
    names: &[String],
    point: Option<&[f64]>,
    motion: Motion<'_>,
) -> Result<Setup, InputError> {
    let params = names_at(names, point);
    let asked = Asked {
        params: &params,
        state_flag: "--at",
        state: motion.at,
        variables: &[motion.speed.0],
        ..Asked::default()
    };
    setup::resolve(model.clone(), &asked)
}

/// The stability of `motion` for the design with the parameters `names`
/// at `point`.
fn stability_of_design(
    model: &InterpretedModel,
    names: &[String],
    point: &[f64],
    motion: Motion<'_>,
) -> Result<Stability, LinearizeError> {
    let setup = design(model, names, Some(point), motion)?;
    linearize::stability(&setup, motion.speed)
}

/// `map.csv` (docs/INTERFACE.md section 11): a header of the parameters'
/// names, `intervals` (the stable intervals `a:b` joined by `;`),
/// `stable_from` and `stable_to` (the first interval's ends), `changes`
/// (each change of the number of unstable modes as `speed:before>after`,
/// joined by `;`) and `failure` (why a point could not be linearized); a
/// row per computed point, empty fields where there is nothing.
pub fn csv(
    names: &[String],
    points: &[Vec<f64>],
    results: &[Option<Result<Stability, LinearizeError>>],
) -> String {
    let mut text = names.join(",");
    text.push_str(",intervals,stable_from,stable_to,changes,failure\n");
    for (point, result) in points.iter().zip(results) {
        let Some(result) = result else { continue };
        for value in point {
            let _ = write!(text, "{value},");
        }
        match result {
            Ok(stability) => {
                let ends = |interval: &linearize::sweep::Interval| interval.refined;
                let intervals: Vec<String> = (stability.stable.iter().map(ends))
                    .map(|(a, b)| format!("{a}:{b}"))
                    .collect();
                let (from, to) = stability
                    .stable
                    .first()
                    .map_or((String::new(), String::new()), |first| {
                        (first.refined.0.to_string(), first.refined.1.to_string())
                    });
                let changes: Vec<String> = (stability.changes.iter())
                    .map(|c| format!("{}:{}>{}", c.value, c.counts.0, c.counts.1))
                    .collect();
                let _ = writeln!(
                    text,
                    "{},{from},{to},{},",
                    intervals.join(";"),
                    changes.join(";")
                );
            }
            Err(error) => {
                let _ = writeln!(text, ",,,,{}", quoted(&error.to_string()));
            }
        }
    }
    text
}

/// `field` as a CSV field: quoted, its quotes doubled, where it holds a
/// comma, a quote or a line break.
fn quoted(field: &str) -> String {
    if field.contains([',', '"', '\n']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::{Axis, grid, quoted};

    #[test]
    fn the_grid_varies_the_last_axis_fastest() {
        let axes = [
            Axis {
                name: "c".into(),
                values: vec![1.0, 2.0],
            },
            Axis {
                name: "w".into(),
                values: vec![3.0, 4.0, 5.0],
            },
        ];
        assert_eq!(
            grid(&axes),
            [
                [1.0, 3.0],
                [1.0, 4.0],
                [1.0, 5.0],
                [2.0, 3.0],
                [2.0, 4.0],
                [2.0, 5.0]
            ]
        );
    }

    #[test]
    fn fields_with_commas_or_quotes_are_quoted() {
        assert_eq!(quoted("plain"), "plain");
        assert_eq!(quoted("a, b"), "\"a, b\"");
        assert_eq!(quoted("say \"x\""), "\"say \"\"x\"\"\"");
    }
}
