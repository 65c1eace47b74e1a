//! Finding a steady motion (docs/INTERFACE.md section 14, MATH.md section
//! 6.1): unknowns `x` (variables of the operating point's expressions, and
//! coordinates it leaves free) such that the point they give is a zero of
//! the reduced flow `z' = F(z, u)` of [`super::steady`].
//!
//! **The point of `x`.** The caller gives, for each `x`, the coordinates
//! and velocities fixed (`None` where free), the inputs, and their exact
//! derivatives in `x` ([`Given`]). The point is completed as
//! [`OperatingPoint::solve`] completes it: of the free coordinates, the
//! pivots `q_D` of `df/dq` solved from `f(q) = 0`, the free velocities
//! `qdot_V` from `A(q) qdot = 0`. Differentiating both,
//!
//! ```text
//! df/dq_D dq_D = -df/dq_E dq_E,
//! A_V dqdot_V  = -A_E dqdot_E - d(A qdot)/dq dq,
//! ```
//!
//! gives the point's derivative (`E` the fixed entries), and that of
//! `z = (r, w)` follows by the chain rule through the body velocity
//! `(w_x, w_y) = R(-theta) (xdot, ydot)` of each `se2` factor. A
//! configuration constraint without a pivot among the free coordinates
//! ties fixed ones (an Ackermann linkage's right steer angle, an unknown,
//! with the left one given): the completion leaves it
//! ([`point::configuration_leaving_fixed`]) and it is a condition.
//!
//! **Gauss-Newton.** The conditions are `R(x) = F(z(x), u(x))` and
//! `f(q(x)) = 0` (the rows of the constraints the completion meets are 0,
//! exactly, not their round-off). Their Jacobian, `dF/dz dz/dx + dF/du
//! du/dx` over `df/dq dq/dx`, is exact but for `d(A qdot)/dq`, which is
//! by Richardson-extrapolated central differences as in [`super::steady`]
//! (error of order `eps^(4/5)`). Some conditions hold identically by the
//! symmetry (a wheel's momentum in a steady turn), so the step is the
//! least-squares one of least norm, `dx = -J^+ R`, halved until `|R|`
//! decreases. The iteration stops where no halving decreases
//! `|R|` (round-off) or the step is round-off in `x`; the point is steady
//! if it passes the check [`super::linearize`] applies and meets `f(q) = 0`
//! to the completion's round-off.

use super::point::{self, OperatingPoint, PointError, solvable};
use super::steady::{Layout, check_steady, richardson};
use super::{Dynamics, LinearSystem, largest, pivots};
use nalgebra::{DMatrix, DVector};

/// The fixed part of an operating point at some unknowns `x`, and its
/// derivatives in `x` (`k` unknowns, `n` coordinates, `p` inputs).
#[derive(Clone, Debug)]
pub struct Given {
    /// The coordinates fixed, `None` where free.
    pub q: Vec<Option<f64>>,
    /// The velocities fixed, `None` where free.
    pub qdot: Vec<Option<f64>>,
    /// The inputs.
    pub u: Vec<f64>,
    /// `dq/dx` of the fixed coordinates, `n x k` (rows of free ones 0).
    pub dq: DMatrix<f64>,
    /// `dqdot/dx` of the fixed velocities, `n x k` (rows of free ones 0).
    pub dqdot: DMatrix<f64>,
    /// `du/dx`, `p x k`.
    pub du: DMatrix<f64>,
}

/// A steady motion found.
#[derive(Clone, Debug)]
pub struct Found {
    /// The unknowns.
    pub x: Vec<f64>,
    /// The point.
    pub point: OperatingPoint,
    /// The inputs there.
    pub u: Vec<f64>,
    /// The Gauss-Newton steps taken.
    pub steps: usize,
    /// The largest entry of `|F(z, u)|` there.
    pub residual: f64,
}

/// Why no steady motion was found.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FindError {
    /// More unknowns than conditions.
    #[error(
        "{unknowns} unknowns but only {conditions} conditions (the reduced flow's rates and the configuration constraints)"
    )]
    TooManyUnknowns {
        /// The unknowns.
        unknowns: usize,
        /// The conditions.
        conditions: usize,
    },
    /// The conditions leave a combination of the unknowns free.
    #[error(
        "the conditions do not fix {}: the steady motions there form a family along them; fix one",
        unknowns.join(", ")
    )]
    Underdetermined {
        /// The unknowns along the free direction.
        unknowns: Vec<String>,
    },
    /// The point could not be completed at an iterate.
    #[error("at {at}: {source}")]
    Point {
        /// The unknowns there, `NAME=VALUE`.
        at: String,
        /// Why.
        source: PointError,
    },
    /// The equations are not finite at the guess.
    #[error("the equations of motion are not finite at the guess")]
    NonFinite,
    /// Gauss-Newton came no closer than this.
    #[error(
        "no steady motion near the guess: after {steps} Gauss-Newton steps the condition {condition} = 0 still fails by {residual:e}, the largest residual (at {at})"
    )]
    NotConverged {
        /// The condition that fails most: `d/dt NAME` of the reduced state
        /// entry whose rate stays largest, or a configuration constraint's
        /// name.
        condition: String,
        /// Its residual.
        residual: f64,
        /// The steps taken.
        steps: usize,
        /// The unknowns reached, `NAME=VALUE`.
        at: String,
    },
}

/// The unknowns as the user names them: their names, and their values
/// `y(x)` at the unknowns `x` Gauss-Newton moves (an affine map: `x`
/// may be coordinates on a hyperplane of `y`).
pub struct Named<'a> {
    /// The names of `y`.
    pub names: &'a [String],
    /// `y(x)`.
    pub values: &'a dyn Fn(&[f64]) -> Vec<f64>,
}

impl Named<'_> {
    /// `NAME=VALUE, ...` of `y(x)`.
    fn assignments(&self, x: &[f64]) -> String {
        let pairs: Vec<String> = (self.names.iter().zip((self.values)(x)))
            .map(|(name, value)| format!("{name}={value}"))
            .collect();
        pairs.join(", ")
    }

    /// The names of `y` that move along the direction `dx` of `x`.
    fn moving(&self, dx: &[f64]) -> Vec<String> {
        let zero = vec![0.0; dx.len()];
        let (from, to) = ((self.values)(&zero), (self.values)(dx));
        (self.names.iter().zip(from.iter().zip(&to)))
            .filter(|(_, (a, b))| (*b - *a).abs() > 1e-6)
            .map(|(name, _)| name.clone())
            .collect()
    }
}

/// The Gauss-Newton steps allowed.
const STEPS: usize = 60;

/// The halvings of a step tried before it counts as making no progress.
const HALVINGS: usize = 30;

/// The iterations a singular value decomposition may take.
const SVD_ITERATIONS: usize = 10_000;

/// Below this times the largest singular value, a singular value of the
/// Jacobian counts as zero: a direction the conditions do not fix.
const RANK: f64 = 1e-9;

/// One iterate: the point, its inputs, the flow's rates, the pivots
/// `(constraint, coordinate)` of `df/dq` on the free coordinates there,
/// and the configuration constraints' residuals, 0 on those with a pivot
/// (the completion meets them, to round-off).
struct Iterate {
    point: OperatingPoint,
    u: Vec<f64>,
    rate: DVector<f64>,
    pivots: Vec<(usize, usize)>,
    holonomic: DVector<f64>,
}

impl Iterate {
    /// The conditions `R`: the rates, then the constraints' residuals.
    fn conditions(&self) -> DVector<f64> {
        let rows = self.rate.iter().chain(self.holonomic.iter());
        DVector::from_iterator(self.rate.len() + self.holonomic.len(), rows.copied())
    }
}

/// A steady motion near `guess` of the unknowns `x`, named by `named`,
/// the point at `x` being `given(x)` completed (see the module
/// documentation).
///
/// # Errors
/// [`FindError`]: more unknowns than conditions, a point that cannot be
/// completed, no convergence, or a solution the conditions do not isolate.
pub fn find(
    model: &dyn Dynamics,
    given: &dyn Fn(&[f64]) -> Given,
    named: &Named<'_>,
    guess: &[f64],
) -> Result<Found, FindError> {
    let layout = Layout::of(model);
    let conditions = layout.nr() + model.coordinates().len() + model.holonomic().len();
    if guess.len() > conditions {
        return Err(FindError::TooManyUnknowns {
            unknowns: guess.len(),
            conditions,
        });
    }
    let mut x = guess.to_vec();
    let mut now = iterate(model, &layout, &given(&x)).map_err(|source| FindError::Point {
        at: named.assignments(&x),
        source,
    })?;
    if now.conditions().iter().any(|r| !r.is_finite()) {
        return Err(FindError::NonFinite);
    }
    let mut steps = 0;
    while steps < STEPS {
        let jacobian = conditions_jacobian(model, &layout, &now, &given(&x));
        let step = least_squares(&jacobian, &now.conditions());
        let Some((next, moved)) = line_search(model, &layout, given, (&x, &now), &step) else {
            break;
        };
        steps += 1;
        (x, now) = next;
        if !moved {
            break;
        }
    }
    if let Some((condition, residual)) = unmet(model, &layout, &now) {
        return Err(FindError::NotConverged {
            condition,
            residual,
            steps,
            at: named.assignments(&x),
        });
    }
    isolated(
        &conditions_jacobian(model, &layout, &now, &given(&x)),
        named,
    )?;
    let residual = largest(now.rate.as_slice()).map_or(0.0, |(_, r)| r.abs());
    Ok(Found {
        x,
        point: now.point,
        u: now.u,
        steps,
        residual,
    })
}

/// The condition that fails most at `now` and its residual, if one
/// fails: a rate by [`check_steady`], else a configuration constraint
/// beyond round-off (as [`OperatingPoint::solve`] meets them).
fn unmet(model: &dyn Dynamics, layout: &Layout, now: &Iterate) -> Option<(String, f64)> {
    let (_, w) = layout.reduce(&now.point);
    if let Err(super::SteadyError::NotSteady {
        quantity, residual, ..
    }) = check_steady(layout, &now.rate, &w)
    {
        return Some((format!("d/dt {quantity}"), residual));
    }
    let (worst, residual) = largest(now.holonomic.as_slice())?;
    (residual.abs() > point::round_off(&now.point.q))
        .then(|| (model.holonomic()[worst].clone(), residual))
}

/// The conditions `R` at the point `given` completes (the flow's rates,
/// then the configuration constraints' residuals), and their Jacobian
/// `dR/dx` in the unknowns `given` differentiates by.
///
/// # Errors
/// The point cannot be completed.
pub fn conditions(
    model: &dyn Dynamics,
    given: &Given,
) -> Result<(DVector<f64>, DMatrix<f64>), PointError> {
    let layout = Layout::of(model);
    let now = iterate(model, &layout, given)?;
    let jacobian = conditions_jacobian(model, &layout, &now, given);
    Ok((now.conditions(), jacobian))
}

/// The point of `given` completed, the flow's rates there and the
/// residuals of the configuration constraints without a pivot among the
/// free coordinates.
fn iterate(model: &dyn Dynamics, layout: &Layout, given: &Given) -> Result<Iterate, PointError> {
    let q = point::configuration_leaving_fixed(model, &given.q)?;
    let point = OperatingPoint::at(model, q, &given.qdot)?;
    let free: Vec<usize> = (0..point.q.len())
        .filter(|&i| given.q[i].is_none())
        .collect();
    let pivots = solvable(model, &point.q, &free);
    let mut holonomic = model.holonomic_residual(&point.q);
    pivots.iter().for_each(|&(row, _)| holonomic[row] = 0.0);
    let (q, w) = layout.reduce(&point);
    let rate = layout.flow(model, &q, &w, &given.u);
    Ok(Iterate {
        point,
        u: given.u.clone(),
        rate,
        pivots,
        holonomic,
    })
}

/// `|rate|`, infinite where not finite.
fn size(rate: &DVector<f64>) -> f64 {
    let norm = rate.norm();
    if norm.is_finite() {
        norm
    } else {
        f64::INFINITY
    }
}

/// The step `x + s step` for the largest `s = 2^-j` that decreases
/// `|R|`, and whether it moved `x` by more than round-off; `None` where
/// no halving does.
fn line_search(
    model: &dyn Dynamics,
    layout: &Layout,
    given: &dyn Fn(&[f64]) -> Given,
    (x, now): (&[f64], &Iterate),
    step: &DVector<f64>,
) -> Option<((Vec<f64>, Iterate), bool)> {
    let current = size(&now.conditions());
    let mut scale = 1.0;
    for _ in 0..HALVINGS {
        let trial: Vec<f64> = (x.iter().zip(step.iter()))
            .map(|(value, delta)| value - scale * delta)
            .collect();
        if let Ok(next) = iterate(model, layout, &given(&trial))
            && size(&next.conditions()) < current
        {
            let moved = (x.iter().zip(&trial))
                .any(|(a, b)| (a - b).abs() > 4.0 * f64::EPSILON * a.abs().max(1.0));
            return Some(((trial, next), moved));
        }
        scale *= 0.5;
    }
    None
}

/// `dx` of least norm minimizing `|J dx - rate|` (singular values below
/// [`RANK`] times the largest dropped).
fn least_squares(jacobian: &DMatrix<f64>, rate: &DVector<f64>) -> DVector<f64> {
    let zero = DVector::zeros(jacobian.ncols());
    let Some(svd) = jacobian
        .clone()
        .try_svd(true, true, f64::EPSILON, SVD_ITERATIONS)
    else {
        return zero;
    };
    let tolerance = RANK * svd.singular_values.amax();
    svd.solve(rate, tolerance).unwrap_or(zero)
}

/// [`FindError::Underdetermined`] where `jacobian` has a null direction,
/// naming the unknowns along it.
fn isolated(jacobian: &DMatrix<f64>, named: &Named<'_>) -> Result<(), FindError> {
    let k = jacobian.ncols();
    let rows = jacobian.nrows().max(k);
    let padded = DMatrix::from_fn(rows, k, |i, j| {
        if i < jacobian.nrows() {
            jacobian[(i, j)]
        } else {
            0.0
        }
    });
    let Some(svd) = padded.try_svd(false, true, f64::EPSILON, SVD_ITERATIONS) else {
        return Ok(());
    };
    let Some(v_t) = svd.v_t else {
        return Ok(());
    };
    let tolerance = RANK * svd.singular_values.amax().max(f64::MIN_POSITIVE);
    let mut free: Vec<String> = Vec::new();
    for i in (0..svd.singular_values.len()).filter(|&i| svd.singular_values[i] <= tolerance) {
        let direction: Vec<f64> = v_t.row(i).iter().copied().collect();
        for name in named.moving(&direction) {
            if !free.contains(&name) {
                free.push(name);
            }
        }
    }
    match free.is_empty() {
        true => Ok(()),
        false => Err(FindError::Underdetermined { unknowns: free }),
    }
}

/// `dR/dx` at `now`: `dF/dz dz/dx + dF/du du/dx` over `df/dq dq/dx` on
/// the constraints without a pivot (0 on the others).
fn conditions_jacobian(
    model: &dyn Dynamics,
    layout: &Layout,
    now: &Iterate,
    given: &Given,
) -> DMatrix<f64> {
    let (q, w) = layout.reduce(&now.point);
    let (by_z, by_u) = layout.jacobian(model, &q, &w, &now.u);
    let dq = coordinate_derivative(model, now, given);
    let rates = by_z * reduced_derivative(model, layout, &now.point, given, &dq) + by_u * &given.du;
    let by_q = model.holonomic_jacobian(&now.point.q);
    let (k, r) = (dq.ncols(), rates.nrows());
    let mut jacobian = DMatrix::zeros(r + by_q.nrows(), k);
    jacobian.view_mut((0, 0), (r, k)).copy_from(&rates);
    for row in (0..by_q.nrows()).filter(|&row| now.pivots.iter().all(|&(r, _)| r != row)) {
        jacobian.set_row(r + row, &(by_q.row(row) * &dq));
    }
    jacobian
}

/// `dz/dx` at `point` from `dq/dx` (module documentation).
fn reduced_derivative(
    model: &dyn Dynamics,
    layout: &Layout,
    point: &OperatingPoint,
    given: &Given,
    dq: &DMatrix<f64>,
) -> DMatrix<f64> {
    let dqdot = velocity_derivative(model, point, given, dq);
    let (nr, n, k) = (layout.nr(), point.q.len(), given.dq.ncols());
    let mut dz = DMatrix::zeros(nr + n, k);
    for (a, &i) in layout.shape.iter().enumerate() {
        dz.set_row(a, &dq.row(i));
    }
    dz.view_mut((nr, 0), (n, k)).copy_from(&dqdot);
    let (_, w) = layout.reduce(point);
    for &(x, y, theta) in &layout.se2 {
        let (sin, cos) = point.q[theta].sin_cos();
        let turn = dq.row(theta);
        let row_x = dqdot.row(x) * cos + dqdot.row(y) * sin + turn * w[y];
        let row_y = dqdot.row(y) * cos - dqdot.row(x) * sin - turn * w[x];
        dz.set_row(nr + x, &row_x);
        dz.set_row(nr + y, &row_y);
    }
    dz
}

/// `dq/dx`: the fixed coordinates' given, the pivots' from
/// `df/dq dq = 0`, the other free ones' 0.
fn coordinate_derivative(model: &dyn Dynamics, now: &Iterate, given: &Given) -> DMatrix<f64> {
    let mut dq = given.dq.clone();
    if now.pivots.is_empty() {
        return dq;
    }
    let (rows, solved): (Vec<usize>, Vec<usize>) = now.pivots.iter().copied().unzip();
    let jacobian = model.holonomic_jacobian(&now.point.q).select_rows(&rows);
    let rhs = -(&jacobian * &dq);
    let by_solved = jacobian.select_columns(&solved);
    let moved = by_solved
        .lu()
        .solve(&rhs)
        .unwrap_or_else(|| DMatrix::from_element(solved.len(), dq.ncols(), f64::NAN));
    for (row, &i) in solved.iter().enumerate() {
        dq.set_row(i, &moved.row(row));
    }
    dq
}

/// `dqdot/dx`: the fixed velocities' given, the free ones' from
/// `A dqdot + d(A qdot)/dq dq = 0` in the least-squares sense.
fn velocity_derivative(
    model: &dyn Dynamics,
    point: &OperatingPoint,
    given: &Given,
    dq: &DMatrix<f64>,
) -> DMatrix<f64> {
    let a = model.constraint_matrix(&point.q);
    let velocity = DVector::from_column_slice(&point.qdot);
    let mut by_q = DMatrix::zeros(a.nrows(), point.q.len());
    for i in (0..point.q.len()).filter(|&i| dq.row(i).amax() > 0.0) {
        let column = richardson(|step| {
            let mut moved = point.q.clone();
            moved[i] += step;
            model.constraint_matrix(&moved) * &velocity
        });
        by_q.set_column(i, &column);
    }
    let mut dqdot = given.dqdot.clone();
    let free: Vec<usize> = (0..point.q.len())
        .filter(|&i| given.qdot[i].is_none())
        .collect();
    if free.is_empty() || a.nrows() == 0 {
        return dqdot;
    }
    let rhs = -(&a * &dqdot + by_q * dq);
    let a_free = a.select_columns(&free);
    let moved = least_squares_columns(&a_free, &rhs);
    for (row, &i) in free.iter().enumerate() {
        dqdot.set_row(i, &moved.row(row));
    }
    dqdot
}

/// The least-squares solution of least norm of `a X = b`, column by column.
fn least_squares_columns(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut solution = DMatrix::zeros(a.ncols(), b.ncols());
    for j in 0..b.ncols() {
        solution.set_column(j, &least_squares(a, &b.column(j).into_owned()));
    }
    solution
}

/// The radius of the circle the origin of the body frame of the model's
/// first `se2` factor follows at a steady `point`, `|(w_x, w_y)| / |w_theta|`
/// (infinite when `w_theta` is round-off beside the speed); `None` without
/// an `se2` factor.
pub fn radius(model: &dyn Dynamics, point: &OperatingPoint) -> Option<f64> {
    let layout = Layout::of(model);
    let &(x, y, theta) = layout.se2.first()?;
    let (_, w) = layout.reduce(point);
    let speed = w[x].hypot(w[y]);
    let turning = w[theta].abs();
    Some(if turning <= 1e-12 * speed.max(1.0) {
        f64::INFINITY
    } else {
        speed / turning
    })
}

/// One direction of the family of steady motions through a point: the
/// state entries it moves and their coefficients, the first entry's 1.
pub type Direction = Vec<(String, f64)>;

/// The null directions of `A` of `linear` (its zeros of conserved
/// quantities, [`LinearSystem::conserved_zeros`]): along each the steady
/// motions form a family. A basis of the null space (the right singular
/// vectors of the smallest singular values) is reduced by Gaussian
/// elimination with complete pivoting, each direction 1 on its pivot entry
/// and 0 on the others' (entries below `1e-9` dropped).
pub fn family_directions(linear: &LinearSystem) -> Vec<Direction> {
    let conserved = linear.conserved_zeros();
    let svd = linear
        .a
        .clone()
        .try_svd(false, true, f64::EPSILON, SVD_ITERATIONS);
    let Some((v_t, values)) = svd.and_then(|svd| Some((svd.v_t?, svd.singular_values))) else {
        return Vec::new();
    };
    if conserved == 0 {
        return Vec::new();
    }
    let mut by_value: Vec<usize> = (0..values.len()).collect();
    by_value.sort_by(|&i, &j| values[i].total_cmp(&values[j]));
    let null = v_t.select_rows(&by_value[..conserved.min(by_value.len())]);
    let columns: Vec<usize> = (0..null.ncols()).collect();
    let chosen: Vec<usize> = (pivots(&null, &columns, 1.0, 1e-12).into_iter())
        .map(|(_, column)| column)
        .collect();
    let Some(reduced) = null
        .select_columns(&chosen)
        .try_inverse()
        .map(|p| p * &null)
    else {
        return Vec::new();
    };
    (chosen.iter().enumerate())
        .map(|(row, &pivot)| {
            let mut entries: Vec<usize> = vec![pivot];
            entries.extend(columns.iter().filter(|&&c| c != pivot));
            (entries.into_iter())
                .filter(|&c| reduced[(row, c)].abs() > 1e-9)
                .map(|c| (linear.state[c].clone(), reduced[(row, c)]))
                .collect()
        })
        .collect()
}
