//! `--trace VAR=START:STOP:STEP`: a family of steady motions followed by
//! pseudo-arclength continuation (Keller 1977; Allgower & Georg,
//! "Introduction to Numerical Continuation Methods", 1990, chapter 2).
//!
//! The unknowns and VAR, `y = (x, VAR)`, satisfy `R(y) = 0`, one equation
//! short: a curve. Its tangent `t` is the null vector of `dR/dy`, oriented
//! as the last one (VAR increasing at the start). A step predicts
//! `y + h t` and corrects by Gauss-Newton on the hyperplane
//! `t . (y - y_pred) = 0`, so it passes folds where VAR turns back. A step
//! whose corrector fails, or whose tangent turns by more than 30 degrees,
//! is halved; one that converges in few steps grows, its VAR advance kept
//! within STEP. Where the curve crosses a grid value of VAR, the row there
//! is solved with VAR fixed from the interpolated point. A fold is where
//! the tangent's VAR component changes sign, located by bisection on the
//! step's length. Where stability changes
//! between rows, the change is located by bisection on VAR (to 1e-9), or
//! is the fold's where one lies between them. The trace ends where VAR
//! leaves the grid's range, or where the family ends (a singular
//! configuration): steps shrink to nothing, or STEPS_PER_POINT steps in a
//! row reach no grid value and no fold (VAR stalls while an unknown grows
//! without bound).

use super::{Affine, Problem, SteadyMotion, SteadyMotionError};
use crate::runtime::linearize::FindError;
use crate::runtime::nalgebra::{DMatrix, DVector};
use std::fmt::Write as _;

/// A point of the family at a grid value of VAR.
#[derive(Clone, Debug)]
pub struct Row {
    /// VAR.
    pub value: f64,
    /// The steady motion there.
    pub motion: SteadyMotion,
}

/// What happens along the family, in its order.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// VAR turns back near this value.
    Fold(f64),
    /// The motion becomes stable (`true`) or unstable at this value.
    Stability(f64, bool),
}

/// Why the trace stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum End {
    /// VAR left the grid's range at this end.
    LeftRange(f64),
    /// The family ends near this value of VAR: no step continues it.
    Ended(f64, String),
    /// The steps allowed were taken.
    Steps(usize),
}

/// A family of steady motions over a grid of VAR.
#[derive(Clone, Debug)]
pub struct Family {
    /// The rows, in the family's order.
    pub rows: Vec<Row>,
    /// Its folds and changes of stability, in order, each after the rows
    /// of this many.
    pub events: Vec<(usize, Event)>,
    /// Why it stopped.
    pub end: End,
}

impl Family {
    /// The rows, the folds, the changes of stability and the end, as
    /// `chaplygin steady --trace` prints them, VAR named `variable`.
    pub fn report(&self, variable: &str) -> String {
        let family = self;
        let mut text = format!(
            "followed the family of steady motions over {variable}: {} rows\n",
            family.rows.len()
        );
        for (after, event) in &family.events {
            let _ = match event {
                Event::Fold(value) => writeln!(
                    text,
                    "fold at {variable} = {value:.9} (after row {after}): the family turns back and goes on around it"
                ),
                Event::Stability(value, stable) => writeln!(
                    text,
                    "{} from {variable} = {value:.9} on (after row {after})",
                    if *stable { "stable" } else { "unstable" }
                ),
            };
        }
        let _ = match &family.end {
            End::LeftRange(edge) => {
                writeln!(text, "the family leaves the range at {variable} = {edge}")
            }
            End::Ended(value, reason) => writeln!(
                text,
                "the family ends near {variable} = {value:.6} (a singular configuration): {reason}"
            ),
            End::Steps(steps) => writeln!(text, "stopped after {steps} continuation steps"),
        };
        text
    }
}

/// The continuation steps allowed per grid point.
const STEPS_PER_POINT: usize = 50;

/// The smallest step, relative to STEP.
const SMALLEST: f64 = 1e-6;

/// The cosine of the largest turn of the tangent in one step.
const STRAIGHT: f64 = 0.866;

/// How closely a change of stability is located.
const LOCATED: f64 = 1e-9;

/// The family of `problem` (which traces a variable) over `grid`, from the
/// first solution at its first value.
///
/// # Errors
/// No steady motion at the first value.
pub fn trace(problem: &Problem, grid: &[f64]) -> Result<Family, SteadyMotionError> {
    let first = at_value(problem, grid[0], problem.guess())?;
    let step = if grid.len() > 1 {
        grid[1] - grid[0]
    } else {
        1.0
    };
    let y = state(&first.motion, first.value);
    let mut walk = Walk {
        problem,
        range: (grid[0], grid[grid.len() - 1]),
        step,
        tangent: tangent_at(problem, &y, None)?,
        y,
    };
    let mut rows = vec![first];
    let mut events = Vec::new();
    let end = walk.run(grid, &mut rows, &mut events);
    let events = with_stability(problem, &rows, events);
    Ok(Family { rows, events, end })
}

/// `y = (x, VAR)` of a motion.
fn state(motion: &SteadyMotion, value: f64) -> DVector<f64> {
    let mut y: Vec<f64> = motion.values.iter().map(|(_, v)| *v).collect();
    y.push(value);
    DVector::from_vec(y)
}

/// The motion with VAR at `value`, from the unknowns `start`.
fn at_value(problem: &Problem, value: f64, start: &[f64]) -> Result<Row, SteadyMotionError> {
    let k = start.len();
    let mut origin = DVector::zeros(k + 1);
    origin[k] = value;
    let basis = DMatrix::from_fn(k + 1, k, |i, j| f64::from(u8::from(i == j)));
    let (motion, _) = problem.solve_on(&Affine { origin, basis }, start)?;
    Ok(Row { value, motion })
}

/// The unit tangent at `y`, oriented as `previous` (else VAR
/// increasing).
fn tangent_at(
    problem: &Problem,
    y: &DVector<f64>,
    previous: Option<&DVector<f64>>,
) -> Result<DVector<f64>, SteadyMotionError> {
    let (_, jacobian) = problem.conditions(y.as_slice())?;
    if jacobian.iter().any(|x| !x.is_finite()) {
        return Err(FindError::NonFinite.into());
    }
    let columns = jacobian.ncols();
    let rows = jacobian.nrows().max(columns);
    let padded = DMatrix::from_fn(rows, columns, |i, j| {
        if i < jacobian.nrows() {
            jacobian[(i, j)]
        } else {
            0.0
        }
    });
    let svd = (padded.try_svd(false, true, f64::EPSILON, 10_000)).ok_or(FindError::NonFinite)?;
    let v_t = svd.v_t.ok_or(FindError::NonFinite)?;
    let smallest = (0..svd.singular_values.len())
        .min_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]))
        .expect("one unknown at least");
    let tangent = v_t.row(smallest).transpose();
    let forward = match previous {
        Some(previous) => tangent.dot(previous) >= 0.0,
        None => tangent[columns - 1] >= 0.0,
    };
    Ok(if forward { tangent } else { -tangent })
}

/// The continuation's state.
struct Walk<'a> {
    problem: &'a Problem,
    range: (f64, f64),
    step: f64,
    y: DVector<f64>,
    tangent: DVector<f64>,
}

impl Walk<'_> {
    /// The point on the hyperplane through `y + h t` normal to `t`, and
    /// the Gauss-Newton steps it took: the hyperplane's unknowns are the
    /// coordinates in the eigenvectors of `I - t t^T` of eigenvalue 1.
    fn corrected(&self, h: f64) -> Result<(DVector<f64>, usize), SteadyMotionError> {
        let tangent = &self.tangent;
        let predicted = &self.y + tangent * h;
        let m = tangent.len();
        let complement = DMatrix::from_fn(m, m, |i, j| {
            f64::from(u8::from(i == j)) - tangent[i] * tangent[j]
        });
        let vectors = complement.symmetric_eigen().eigenvectors;
        let kept: Vec<usize> = (0..m)
            .filter(|&j| vectors.column(j).dot(tangent).abs() < 0.5)
            .collect();
        let basis = vectors.select_columns(&kept);
        let map = Affine {
            origin: predicted,
            basis,
        };
        let (motion, y) = self.problem.solve_on(&map, &vec![0.0; m - 1])?;
        Ok((DVector::from_vec(y), motion.steps))
    }

    /// Steps along the family, adding the rows at the grid values crossed
    /// and the folds, until it leaves the range or ends.
    fn run(&mut self, grid: &[f64], rows: &mut Vec<Row>, events: &mut Vec<(usize, Event)>) -> End {
        let mut h = self.step;
        let mut idle = 0;
        for _ in 0..STEPS_PER_POINT * grid.len() {
            let tangent = self.tangent.clone();
            let cap = self.step / tangent[tangent.len() - 1].abs().max(1e-3);
            h = h.min(cap);
            let next = self.corrected(h).and_then(|(y, steps)| {
                let t = tangent_at(self.problem, &y, Some(&tangent))?;
                Ok((y, t, steps))
            });
            let (y, t, steps) = match next {
                Ok(found) if found.1.dot(&tangent) >= STRAIGHT => found,
                Ok(_) | Err(_) if h > SMALLEST * self.step => {
                    h /= 2.0;
                    continue;
                }
                Ok(_) => return self.ended("the family turns too sharply".into()),
                Err(error) => return self.ended(error.to_string()),
            };
            let last = tangent.len() - 1;
            let to = y[last];
            let (before, folds) = (rows.len(), tangent[last] * t[last] < 0.0);
            if folds {
                events.push((rows.len(), Event::Fold(self.fold(h))));
            }
            if let Err(error) = self.rows_between(grid, (&self.y.clone(), &y), rows) {
                return self.ended(error.to_string());
            }
            idle = if folds || rows.len() > before {
                0
            } else {
                idle + 1
            };
            (self.y, self.tangent) = (y, t);
            if idle == STEPS_PER_POINT {
                return self.ended(self.unbounded());
            }
            if to > self.range.1 || to < self.range.0 {
                let edge = if to > self.range.1 {
                    self.range.1
                } else {
                    self.range.0
                };
                return End::LeftRange(edge);
            }
            if steps <= 3 {
                h *= 1.5;
            }
        }
        End::Steps(STEPS_PER_POINT * grid.len())
    }

    /// VAR at the fold within a step of `h`: where the tangent's VAR
    /// component changes sign, by bisection on the step's length (the
    /// corrector from the current point), to `1e-12 h`; VAR is extremal
    /// there, so its error is of the order of the square of that.
    fn fold(&self, h: f64) -> f64 {
        let last = self.y.len() - 1;
        let sign = self.tangent[last].signum();
        let (mut short, mut long, mut value) = (0.0, h, self.y[last]);
        while long - short > 1e-12 * h {
            let middle = 0.5 * (short + long);
            let at = self
                .corrected(middle)
                .and_then(|(y, _)| Ok((tangent_at(self.problem, &y, Some(&self.tangent))?, y)));
            let Ok((tangent, y)) = at else {
                break;
            };
            value = y[last];
            if tangent[last] * sign > 0.0 {
                short = middle;
            } else {
                long = middle;
            }
        }
        value
    }

    /// Why a family ends where VAR stalls: the unknown largest there,
    /// growing without bound.
    fn unbounded(&self) -> String {
        let last = self.y.len() - 1;
        let names = &self.problem.names;
        let largest = (0..last.min(names.len()))
            .max_by(|&a, &b| self.y[a].abs().total_cmp(&self.y[b].abs()))
            .expect("one unknown at least");
        format!(
            "{} grows without bound ({} = {:e} after {STEPS_PER_POINT} steps that reach no grid value)",
            names[largest], names[largest], self.y[largest]
        )
    }

    /// [`End::Ended`] at the current point.
    fn ended(&self, reason: String) -> End {
        End::Ended(self.y[self.y.len() - 1], reason)
    }

    /// The rows at the grid values strictly past `a` up to `b` (VAR's
    /// entries), each solved with VAR fixed from the point interpolated.
    fn rows_between(
        &self,
        grid: &[f64],
        (a, b): (&DVector<f64>, &DVector<f64>),
        rows: &mut Vec<Row>,
    ) -> Result<(), SteadyMotionError> {
        let last = a.len() - 1;
        let (from, to) = (a[last], b[last]);
        let mut crossed: Vec<f64> = (grid.iter().copied())
            .filter(|&g| (g - from) * (g - to) <= 0.0 && g != from)
            .collect();
        if to < from {
            crossed.reverse();
        }
        for value in crossed {
            let share = (value - from) / (to - from);
            let start = a + (b - a) * share;
            rows.push(at_value(self.problem, value, &start.as_slice()[..last])?);
        }
        Ok(())
    }
}

/// `events` with the changes of stability between consecutive rows,
/// located by bisection on VAR, in the family's order. Between rows on
/// either side of a fold the change is the fold's: there the conditions'
/// Jacobian in the unknowns is singular, and a real eigenvalue passes
/// through zero (VAR does not order the rows, so bisection on it cannot
/// bracket the change).
fn with_stability(
    problem: &Problem,
    rows: &[Row],
    mut events: Vec<(usize, Event)>,
) -> Vec<(usize, Event)> {
    let conserved = (rows.iter())
        .map(|row| row.motion.linear.conserved_zeros())
        .min()
        .unwrap_or(0);
    for (i, pair) in rows.windows(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        if a.motion.stable() != b.motion.stable() {
            let fold = events.iter().find_map(|(after, event)| match event {
                Event::Fold(value) if *after == i + 1 => Some(*value),
                _ => None,
            });
            let value = fold.unwrap_or_else(|| located(problem, (a, b), conserved));
            events.push((i + 1, Event::Stability(value, b.motion.stable())));
        }
    }
    events.sort_by_key(|(after, _)| *after);
    events
}

/// Where the largest real part (modulo `conserved` zeros) crosses zero
/// between the rows `a` and `b`, by bisection on VAR from the unknowns
/// interpolated; the midpoint of the last bracket (of the rows' values
/// where a point between does not solve).
fn located(problem: &Problem, (a, b): (&Row, &Row), conserved: usize) -> f64 {
    let stable_at = |row: &Row| row.motion.linear.largest_real_part_modulo(conserved) < 0.0;
    let unknowns = |row: &Row| -> Vec<f64> { row.motion.values.iter().map(|(_, v)| *v).collect() };
    let (mut low, mut high) = (a.clone(), b.clone());
    let low_stable = stable_at(&low);
    while (high.value - low.value).abs() > LOCATED * high.value.abs().max(1.0) {
        let middle = 0.5 * (low.value + high.value);
        let start: Vec<f64> = (unknowns(&low).iter().zip(unknowns(&high)))
            .map(|(l, h)| 0.5 * (l + h))
            .collect();
        match at_value(problem, middle, &start) {
            Ok(row) if stable_at(&row) == low_stable => low = row,
            Ok(row) => high = row,
            Err(_) => break,
        }
    }
    0.5 * (low.value + high.value)
}
