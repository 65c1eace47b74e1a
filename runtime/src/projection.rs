//! Projection of a state onto the constraint manifold, after each accepted
//! step of the Lagrange-d'Alembert equations (which keep the constraints
//! only through their derivatives, `A qddot + Adot qdot = 0`, so that their
//! residual drifts with the integrator's error).
//!
//! - Configuration, onto `f(q) = 0` ([`configuration`]): Newton's method on
//!   the underdetermined system, each update the minimum-norm solution of
//!   `F(q) dq = -f(q)` with `F = df/dq`,
//!
//!   ```text
//!   q <- q - F^T (F F^T)^-1 f(q),
//!   ```
//!
//!   the Gauss-Newton projection of Hairer, Lubich & Wanner, *Geometric
//!   Numerical Integration*, 2nd ed. (2006), section IV.4, algorithm 4.2,
//!   with the Euclidean metric. A constraint it cannot meet is a structured
//!   [`ProjectionError::Unmet`] naming it and its residual.
//! - Velocity, onto `D(q) = ker A(q)` in the kinetic-energy metric `g(q)`
//!   ([`velocity`]): the `g`-orthogonal projection
//!
//!   ```text
//!   qdot <- qdot - g^-1 A^T (A g^-1 A^T)^-1 A qdot,
//!   ```
//!
//!   the allowed velocity of least kinetic energy of the difference (Hairer,
//!   Lubich & Wanner, section VII.2, the projection of the index-2
//!   constraint). Its residual `A qdot` is round-off whatever the metric; the
//!   metric decides only which allowed velocity is chosen (the one an impulse
//!   along the constraint forces `A^T lambda` reaches).
//!
//! Both are written on nalgebra's matrices of any size, fixed (no
//! allocation) or dynamic (the interpreter).

mod surface;

pub use surface::Surface;

use crate::linalg::{MatrixError, cholesky};
use crate::system::LagrangeDalembert;
use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, OMatrix, OVector, SMatrix, SVector};

/// Why a state could not be projected onto the constraint manifold.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProjectionError {
    /// Newton's method did not bring a configuration constraint to zero.
    #[error(
        "the configuration constraint `{constraint}` cannot be met: residual {residual:e} \
         after {iterations} Newton iterations"
    )]
    Unmet {
        /// The constraint with the largest residual.
        constraint: String,
        /// Its residual `f(q)`.
        residual: f64,
        /// Newton iterations made.
        iterations: usize,
    },
    /// A matrix of the projection was not positive definite: the metric,
    /// or the Gram matrix of rows that have lost rank.
    #[error("the {matrix} cannot be factored: {source}")]
    Singular {
        /// Which matrix (`"mass matrix g"`, `"Gram matrix A g^-1 A^T"`, ...).
        matrix: &'static str,
        /// The factorization's failure.
        source: MatrixError,
    },
}

/// Newton's settings for [`configuration`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Met when every `|f_i(q)|` is at most this.
    pub tolerance: f64,
    /// Iterations allowed.
    pub max_iterations: usize,
}

impl Default for Settings {
    /// `tolerance = 1e-12`, `max_iterations = 20`.
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            max_iterations: 20,
        }
    }
}

/// The largest `|r_i|` and its index.
fn largest<R: Dim>(residual: &OVector<f64, R>) -> (usize, f64)
where
    DefaultAllocator: Allocator<R>,
{
    residual
        .iter()
        .enumerate()
        .fold((0, 0.0), |(at, worst), (i, r)| {
            if r.abs() > worst || r.is_nan() {
                (i, r.abs())
            } else {
                (at, worst)
            }
        })
}

/// `q` moved onto `f(q) = 0` by Newton's minimum-norm updates
/// `dq = -F^T (F F^T)^-1 f(q)`; `constraint` is `f` and its Jacobian `F`,
/// `names` the constraints' names. A `q` already on the surface is returned
/// unchanged.
///
/// # Errors
/// [`ProjectionError::Unmet`] when `f` is not within the tolerance after
/// the iterations allowed (or became non-finite), naming the constraint with
/// the largest residual; [`ProjectionError::Singular`] when `F F^T` is
/// singular (dependent constraint gradients).
pub fn configuration<N: Dim, H: Dim>(
    mut q: OVector<f64, N>,
    constraint: impl Fn(&OVector<f64, N>) -> (OVector<f64, H>, OMatrix<f64, H, N>),
    names: &[&str],
    settings: Settings,
) -> Result<OVector<f64, N>, ProjectionError>
where
    DefaultAllocator:
        Allocator<N> + Allocator<H> + Allocator<H, N> + Allocator<N, H> + Allocator<H, H>,
{
    let mut iteration = 0;
    loop {
        let (residual, jacobian) = constraint(&q);
        let (at, worst) = largest(&residual);
        if worst <= settings.tolerance {
            return Ok(q);
        }
        if iteration == settings.max_iterations || !worst.is_finite() {
            return Err(ProjectionError::Unmet {
                constraint: names.get(at).copied().unwrap_or("?").to_string(),
                residual: residual[at],
                iterations: iteration,
            });
        }
        let gram = cholesky(&jacobian * jacobian.transpose()).map_err(|source| {
            ProjectionError::Singular {
                matrix: "Gram matrix F F^T of the configuration constraints' gradients",
                source,
            }
        })?;
        q -= jacobian.transpose() * gram.solve(&residual);
        iteration += 1;
    }
}

/// `qdot - g^-1 A^T (A g^-1 A^T)^-1 A qdot`: the velocity allowed by the
/// rows `A` nearest `qdot` in the metric `g`.
///
/// # Errors
/// [`ProjectionError::Singular`] when `g` is not positive definite or the
/// rows are dependent (their Gram matrix `A g^-1 A^T` is not).
pub fn velocity<N: Dim, C: Dim>(
    metric: OMatrix<f64, N, N>,
    rows: &OMatrix<f64, C, N>,
    qdot: &OVector<f64, N>,
) -> Result<OVector<f64, N>, ProjectionError>
where
    DefaultAllocator: Allocator<N, N>
        + Allocator<C, N>
        + Allocator<N, C>
        + Allocator<C, C>
        + Allocator<N>
        + Allocator<C>,
{
    let metric = cholesky(metric).map_err(|source| ProjectionError::Singular {
        matrix: "mass matrix g",
        source,
    })?;
    let inverse_metric_rows = metric.solve(&rows.transpose());
    let gram =
        cholesky(rows * &inverse_metric_rows).map_err(|source| ProjectionError::Singular {
            matrix: "Gram matrix A g^-1 A^T of the constraint rows",
            source,
        })?;
    let multipliers = gram.solve(&(rows * qdot));
    Ok(qdot - inverse_metric_rows * multipliers)
}

/// The allowed velocity nearest `qdot` at `q` ([`velocity`]) for a
/// [`LagrangeDalembert`] model, whose rows and metric are read off what it
/// evaluates:
///
/// - `A(q)`, column `j`, is the residual `A(q) e_j` of the unit velocity
///   `e_j` (the residual is linear in `qdot`);
/// - `g(q)` by polarization of the energy `E(q, qdot) = qdot^T g qdot / 2 + V(q)`:
///   `g_jj = 2 (E(e_j) - E(0))`, `g_ij = E(e_i + e_j) - E(e_i) - E(e_j) + E(0)`.
///
/// The rounding of the polarization perturbs the metric, which chooses among
/// the allowed velocities; the residual of the result is round-off whatever
/// the metric. Without constraint rows `qdot` is returned unchanged.
///
/// # Errors
/// As [`velocity`].
pub fn dalembert_velocity<M, const N: usize, const C: usize, const P: usize>(
    model: &M,
    q: &[f64; N],
    qdot: &[f64; N],
) -> Result<[f64; N], ProjectionError>
where
    M: LagrangeDalembert<N, C, P>,
{
    if C == 0 {
        return Ok(*qdot);
    }
    let unit = |j: usize| -> [f64; N] { core::array::from_fn(|i| f64::from(u8::from(i == j))) };
    let mut rows = SMatrix::<f64, C, N>::zeros();
    for j in 0..N {
        rows.set_column(j, &SVector::from(model.constraint_residual(q, &unit(j))));
    }
    let energy = |v: &[f64; N]| model.energy(q, v);
    let (rest, along): (f64, [f64; N]) = (
        energy(&[0.0; N]),
        core::array::from_fn(|j| energy(&unit(j))),
    );
    // Cholesky reads the lower triangle only.
    let mut metric = SMatrix::<f64, N, N>::zeros();
    for i in 0..N {
        metric[(i, i)] = 2.0 * (along[i] - rest);
        for j in 0..i {
            let both: [f64; N] = core::array::from_fn(|k| f64::from(u8::from(k == i || k == j)));
            metric[(i, j)] = energy(&both) - along[i] - along[j] + rest;
        }
    }
    velocity(metric, &rows, &SVector::from(*qdot)).map(Into::into)
}
