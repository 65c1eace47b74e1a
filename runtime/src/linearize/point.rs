//! An operating point `(q, qdot)` from the coordinates and velocities
//! given (docs/INTERFACE.md section 5, `--at`).
//!
//! - Coordinates: those given are fixed, the others 0 when that meets
//!   `f(q) = 0` already (the upright bicycle given its pitch, where `df/dq`
//!   vanishes on the lean and the steer); else, of the others, one per
//!   configuration constraint (the pivots of `df/dq` on them, by complete
//!   pivoting) is solved from `f(q) = 0` by Newton's method, and the rest
//!   are 0; a constraint the given coordinates meet alone needs none (an
//!   `orient` frame's unit norm). Newton starts from 0, or from [`GENERIC_START`] where `df/dq`
//!   is singular in the unset coordinates at 0 (a pendulum's length
//!   constraint at height 0). An error names the constraint and its
//!   residual: one the unset coordinates do not change
//!   ([`PointError::HolonomicFixed`]), or one Newton's method leaves
//!   unmet, with the smallest residual it reached
//!   ([`PointError::HolonomicNotConverged`]: no real solution, such as a
//!   pendulum's height given beyond its length).
//!   [`configuration_leaving_fixed`] leaves the first kind unmet instead,
//!   for a caller that moves the given coordinates to meet them.
//! - Velocities: those given are fixed and the others solved from
//!   `A(q) qdot = 0`, i.e. `A_free qdot_free = -A_given qdot_given`. If
//!   that leaves a direction free (`A_free` has a null space), the
//!   velocities with a component along it are named
//!   ([`PointError::FreeVelocities`]); if no solution exists, the
//!   constraint with the largest residual of the least-squares solution is
//!   ([`PointError::ConstraintViolated`]).

use super::{Dynamics, largest, pivots};
use nalgebra::{DMatrix, DVector};

/// A configuration and a velocity the constraints allow.
#[derive(Clone, Debug, PartialEq)]
pub struct OperatingPoint {
    /// The coordinates `q`.
    pub q: Vec<f64>,
    /// The velocities `qdot`, with `A(q) qdot = 0`.
    pub qdot: Vec<f64>,
}

/// Why no operating point was found.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PointError {
    /// The velocities given leave directions free.
    #[error("the velocities given leave {}", left_free(*directions, velocities))]
    FreeVelocities {
        /// The velocities (`dot(q)`) along a direction the constraints allow.
        velocities: Vec<String>,
        /// The number of those directions.
        directions: usize,
    },
    /// The velocities given contradict a constraint.
    #[error(
        "the velocity violates constraint `{constraint}`: A(q) qdot = {residual:e}, must be 0, whatever the velocities not given"
    )]
    ConstraintViolated {
        /// The constraint with the largest residual.
        constraint: String,
        /// Its residual `A(q) qdot`.
        residual: f64,
    },
    /// The constraint rows have a non-finite entry.
    #[error("the constraint matrix A(q) is not finite at the operating point")]
    NonFinite,
    /// A configuration constraint depends on no coordinate left to solve.
    #[error(
        "configuration constraint `{constraint}` cannot be met: it is {residual:e} and the coordinates left unset do not change it"
    )]
    HolonomicFixed {
        /// The constraint.
        constraint: String,
        /// Its residual `f(q)` with the coordinates given.
        residual: f64,
    },
    /// Newton's method on `f(q) = 0` did not converge.
    #[error(
        "configuration constraint `{constraint}` cannot be met: Newton's method on the coordinates left unset comes no closer than {residual:e} in {iterations} steps"
    )]
    HolonomicNotConverged {
        /// The constraint with the largest residual at the closest iterate.
        constraint: String,
        /// Its residual there.
        residual: f64,
        /// The steps taken.
        iterations: usize,
    },
}

/// The iterations the singular value decomposition may take.
const SVD_ITERATIONS: usize = 10_000;

/// The Newton steps allowed for `f(q) = 0`.
const NEWTON_STEPS: usize = 50;

/// Where the unset coordinates start when `df/dq` is singular in them at 0.
pub const GENERIC_START: f64 = 0.5;

impl OperatingPoint {
    /// The point with the coordinates and velocities given (`None` where
    /// not given, `n` entries each), completed as the module documentation
    /// says.
    ///
    /// # Errors
    /// [`PointError`]: unsolvable configuration constraints, velocities left
    /// free, or velocities contradicting the constraints.
    pub fn solve(
        model: &dyn Dynamics,
        coordinates: &[Option<f64>],
        velocities: &[Option<f64>],
    ) -> Result<OperatingPoint, PointError> {
        Self::at(model, configuration(model, coordinates)?, velocities)
    }

    /// The point at the coordinates `q`, with the velocities given
    /// (`None` where not) completed as the module documentation says.
    ///
    /// # Errors
    /// [`PointError`]: velocities left free, or velocities contradicting
    /// the constraints.
    pub fn at(
        model: &dyn Dynamics,
        q: Vec<f64>,
        velocities: &[Option<f64>],
    ) -> Result<OperatingPoint, PointError> {
        let names = velocity_names(&model.coordinates());
        let qdot = solve_velocities(
            &model.constraint_matrix(&q),
            &model.constraints(),
            &names,
            velocities,
        )?;
        Ok(OperatingPoint { q, qdot })
    }
}

/// [`PointError::FreeVelocities`]' words: the velocities left free, or,
/// where the constraints tie them, how many directions among them.
fn left_free(directions: usize, velocities: &[String]) -> String {
    let names = velocities.join(", ");
    if directions >= velocities.len() {
        let them = if velocities.len() == 1 { "it" } else { "them" };
        return format!("{names} free: give {them} too");
    }
    let plural = if directions == 1 { "" } else { "s" };
    format!(
        "{directions} direction{plural} free among {names}, which the constraints tie: give {directions} of them too"
    )
}

/// `dot(q)` for each coordinate `q`.
pub fn velocity_names(coordinates: &[String]) -> Vec<String> {
    coordinates.iter().map(|c| format!("dot({c})")).collect()
}

/// The coordinates given, the others 0 or solved from `f(q) = 0`.
///
/// # Errors
/// [`PointError::HolonomicFixed`], [`PointError::HolonomicNotConverged`].
pub fn configuration(model: &dyn Dynamics, given: &[Option<f64>]) -> Result<Vec<f64>, PointError> {
    let Start {
        mut q,
        pivots,
        unmet,
    } = newton_start(model, given);
    if let Some(&fixed) = unmet.first() {
        return Err(PointError::HolonomicFixed {
            constraint: model.holonomic()[fixed].clone(),
            residual: model.holonomic_residual(&q)[fixed],
        });
    }
    newton(model, &mut q, &pivots, &[])?;
    Ok(q)
}

/// As [`configuration`], but the constraints that no unset coordinate
/// changes are left unmet instead of refused: a caller that moves the
/// given coordinates meets them (`steady` solving for a coordinate such a
/// constraint ties, [`super::find`]).
///
/// # Errors
/// [`PointError::HolonomicNotConverged`] on the other constraints.
pub fn configuration_leaving_fixed(
    model: &dyn Dynamics,
    given: &[Option<f64>],
) -> Result<Vec<f64>, PointError> {
    let Start {
        mut q,
        pivots,
        unmet,
    } = newton_start(model, given);
    newton(model, &mut q, &pivots, &unmet)?;
    Ok(q)
}

/// Where Newton's method on `f(q) = 0` starts (module documentation).
struct Start {
    /// The coordinates given, the others 0 or [`GENERIC_START`].
    q: Vec<f64>,
    /// The pivots `(constraint, coordinate)` of `df/dq` on the unset
    /// coordinates there.
    pivots: Vec<(usize, usize)>,
    /// The constraints without a pivot that `q` does not meet.
    unmet: Vec<usize>,
}

/// The start of Newton's method: the unset coordinates 0, or
/// [`GENERIC_START`] where that gives every unmet constraint a pivot and 0
/// does not.
fn newton_start(model: &dyn Dynamics, given: &[Option<f64>]) -> Start {
    let q: Vec<f64> = given.iter().map(|v| v.unwrap_or(0.0)).collect();
    if model.holonomic().is_empty() || meets(model, &q, &[]) {
        let (pivots, unmet) = (Vec::new(), Vec::new());
        return Start { q, pivots, unmet };
    }
    let unset: Vec<usize> = (0..q.len()).filter(|&i| given[i].is_none()).collect();
    let pivots = solvable(model, &q, &unset);
    let unmet = unmet_without_pivot(model, &q, &pivots);
    if unmet.is_empty() {
        return Start { q, pivots, unmet };
    }
    let mut generic = q.clone();
    unset.iter().for_each(|&i| generic[i] = GENERIC_START);
    let at_generic = solvable(model, &generic, &unset);
    if unmet_without_pivot(model, &generic, &at_generic).is_empty() {
        let unmet = Vec::new();
        return Start {
            q: generic,
            pivots: at_generic,
            unmet,
        };
    }
    Start { q, pivots, unmet }
}

/// The constraints that no unset coordinate can change (no pivot in
/// `chosen`) and that `q` does not meet already: the constraints the
/// coordinates given meet alone (an `orient` frame's unit norm, given its
/// parameters) need no coordinate of their own.
fn unmet_without_pivot(model: &dyn Dynamics, q: &[f64], chosen: &[(usize, usize)]) -> Vec<usize> {
    let residual = model.holonomic_residual(q);
    let tolerance = round_off(q);
    (0..residual.len())
        .filter(|&row| chosen.iter().all(|&(r, _)| r != row) && residual[row].abs() > tolerance)
        .collect()
}

/// The residual of `f(q)` that counts as met: round-off at `q`'s scale.
pub(super) fn round_off(q: &[f64]) -> f64 {
    1e-13 * q.iter().fold(1.0f64, |m, v| m.max(v.abs()))
}

/// `f(q)`, 0 on the constraints `left`.
fn residual_but(model: &dyn Dynamics, q: &[f64], left: &[usize]) -> DVector<f64> {
    let mut residual = model.holonomic_residual(q);
    left.iter().for_each(|&row| residual[row] = 0.0);
    residual
}

/// Whether `q` meets `f(q) = 0` but on the constraints `left` to
/// round-off (Newton's criterion).
fn meets(model: &dyn Dynamics, q: &[f64], left: &[usize]) -> bool {
    largest(residual_but(model, q, left).as_slice())
        .is_none_or(|(_, value)| value.abs() <= round_off(q))
}

/// The pivots `(constraint, coordinate)` of `df/dq` at `q` among the
/// coordinates `unset`.
pub(super) fn solvable(model: &dyn Dynamics, q: &[f64], unset: &[usize]) -> Vec<(usize, usize)> {
    let jacobian = model.holonomic_jacobian(q);
    pivots(&jacobian, unset, 1.0, 1e-12 * jacobian.amax().max(1.0))
}

/// Newton's method on `f(q) = 0` but the constraints `left`, each
/// constraint of `pivots` solved for its coordinate; the other constraints
/// stay met, or the method fails.
fn newton(
    model: &dyn Dynamics,
    q: &mut [f64],
    pivots: &[(usize, usize)],
    left: &[usize],
) -> Result<(), PointError> {
    let (rows, solved): (Vec<usize>, Vec<usize>) = pivots.iter().copied().unzip();
    let mut closest: Option<(usize, f64)> = None;
    for step in 0..=NEWTON_STEPS {
        if meets(model, q, left) {
            return Ok(());
        }
        let residual = residual_but(model, q, left);
        let Some((worst, value)) = largest(residual.as_slice()) else {
            return Ok(());
        };
        if closest.is_none_or(|(_, best)| value.abs() < best.abs()) {
            closest = Some((worst, value));
        }
        if step == NEWTON_STEPS {
            break;
        }
        let jacobian = model
            .holonomic_jacobian(q)
            .select_rows(&rows)
            .select_columns(&solved);
        let Some(newton_step) = jacobian.lu().solve(&residual.select_rows(&rows)) else {
            break;
        };
        if newton_step.iter().any(|delta| !delta.is_finite()) {
            break;
        }
        for (&i, delta) in solved.iter().zip(newton_step.iter()) {
            q[i] -= delta;
        }
    }
    let (worst, value) = closest.unwrap_or((0, f64::NAN));
    Err(PointError::HolonomicNotConverged {
        constraint: model.holonomic()[worst].clone(),
        residual: value,
        iterations: NEWTON_STEPS,
    })
}

/// The velocities given (`None` where not), the others solved from
/// `A qdot = 0` with `A` the constraint rows (`constraints` their names,
/// `names` the velocities').
///
/// # Errors
/// [`PointError::FreeVelocities`], [`PointError::ConstraintViolated`].
pub fn solve_velocities(
    a: &DMatrix<f64>,
    constraints: &[String],
    names: &[String],
    given: &[Option<f64>],
) -> Result<Vec<f64>, PointError> {
    let free: Vec<usize> = (0..given.len()).filter(|&i| given[i].is_none()).collect();
    let mut qdot: Vec<f64> = given.iter().map(|v| v.unwrap_or(0.0)).collect();
    let a_free = a.select_columns(&free);
    let rhs = -(a * DVector::from_column_slice(&qdot));
    let scale = a.amax().max(f64::MIN_POSITIVE) * qdot.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let (solution, null_space) = least_squares(&a_free, &rhs).ok_or(PointError::NonFinite)?;
    for (&i, value) in free.iter().zip(solution.iter()) {
        qdot[i] = *value;
    }
    let residual = a * DVector::from_column_slice(&qdot);
    if let Some((worst, value)) = largest(residual.as_slice())
        && value.abs() > 1e-10 * scale
    {
        return Err(PointError::ConstraintViolated {
            constraint: constraints[worst].clone(),
            residual: value,
        });
    }
    let left_free: Vec<String> = free
        .iter()
        .enumerate()
        .filter(|&(j, _)| null_space.iter().any(|v| v[j].abs() > 1e-9))
        .map(|(_, &i)| names[i].clone())
        .collect();
    if !left_free.is_empty() {
        return Err(PointError::FreeVelocities {
            velocities: left_free,
            directions: null_space.len(),
        });
    }
    Ok(qdot)
}

/// The least-squares solution of `a x = b` of least norm, and an
/// orthonormal basis of the null space of `a`, by the singular value
/// decomposition (`a` padded with zero rows to at least square, so that
/// every right singular vector is computed); `None` when the decomposition
/// fails (a non-finite entry).
fn least_squares(a: &DMatrix<f64>, b: &DVector<f64>) -> Option<(DVector<f64>, Vec<DVector<f64>>)> {
    let columns = a.ncols();
    if columns == 0 {
        return Some((DVector::zeros(0), Vec::new()));
    }
    let rows = a.nrows().max(columns);
    let padded = DMatrix::from_fn(
        rows,
        columns,
        |i, j| {
            if i < a.nrows() { a[(i, j)] } else { 0.0 }
        },
    );
    let padded_b = DVector::from_fn(rows, |i, _| if i < b.len() { b[i] } else { 0.0 });
    if padded.iter().chain(padded_b.iter()).any(|x| !x.is_finite()) {
        return None;
    }
    let svd = padded.try_svd(true, true, f64::EPSILON, SVD_ITERATIONS)?;
    let tolerance = 1e-10 * svd.singular_values.amax().max(f64::MIN_POSITIVE);
    let (u, v_t) = (svd.u.as_ref()?, svd.v_t.as_ref()?);
    let mut solution = DVector::zeros(columns);
    let mut null_space = Vec::new();
    for (k, &sigma) in svd.singular_values.iter().enumerate() {
        let v = v_t.row(k).transpose();
        if sigma > tolerance {
            solution += v * (u.column(k).dot(&padded_b) / sigma);
        } else {
            null_space.push(v);
        }
    }
    Some((solution, null_space))
}
