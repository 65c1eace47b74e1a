//! Linearization about a steady motion (MATH.md section 6): operating
//! points, the steady-motion check, the linear system with the symmetry
//! reduced and the constraints eliminated, and its eigenvalues.
//!
//! - [`point`]: an operating point `(q, qdot)` from the coordinates and
//!   velocities given: the other coordinates solved from the holonomic
//!   constraints `f(q) = 0`, the other velocities from `A(q) qdot = 0`;
//! - [`steady`]: the reduced flow `z' = F(z)` in `z = (r, w)` (shape `r`,
//!   velocities `w` at the group's identity), the check `F(z) = 0`, and the
//!   linear system `y' = A y + B u` in independent coordinates and speeds;
//! - [`find`]: a steady motion from unknowns of the point, by
//!   Gauss-Newton on the exact Jacobian of the reduced flow's rates;
//! - [`canonical`]: from two such systems, the canonical form
//!   `M qddot + v C1 qdot + (g K0 + v^2 K2) q = f` of Meijaard et al. (2007).
//!
//! Both work on a model seen through [`Dynamics`] (run-time sizes), which
//! [`Compiled`] implements for a generated model (the runtime traits
//! [`Linearization`] and, with configuration constraints, [`Holonomic`]).

pub mod canonical;
pub mod find;
pub mod point;
pub mod steady;

use crate::arrays::leading;
pub use crate::system::GroupFactor;
use crate::system::{Holonomic, LagrangeDalembert, ModelNames};
use nalgebra::{DMatrix, DVector};

pub use canonical::{CanonicalError, CanonicalForm};
pub use find::{Direction, FindError, Found, Given};
pub use point::{OperatingPoint, PointError};
pub use steady::{LinearSystem, SteadyError, linearize};

/// `(d qddot/dq, d qddot/dqdot, d qddot/du)` of a model with `N`
/// coordinates and `P` inputs, row `i` the derivatives of `qddot_i`.
pub type AccelerationJacobian<const N: usize, const P: usize> =
    ([[f64; N]; N], [[f64; N]; N], [[f64; P]; N]);

/// What linearizing the Lagrange-d'Alembert equations needs (MATH.md
/// section 6): the symmetry group, `A(q)`, and the
/// exact Jacobians of `qddot`. Generated models implement it.
pub trait Linearization<const N: usize, const C: usize, const P: usize>:
    LagrangeDalembert<N, C, P>
{
    /// The factors of the declared symmetry group (empty without one).
    fn symmetry(&self) -> &[GroupFactor];
    /// The mass matrix `g(q)`.
    fn mass_matrix(&self, q: &[f64; N]) -> [[f64; N]; N];
    /// The constraint rows `A(q)`.
    fn constraint_matrix(&self, q: &[f64; N]) -> [[f64; N]; C];
    /// The exact Jacobians of [`LagrangeDalembert::acceleration`]'s `qddot`.
    fn acceleration_jacobian(
        &self,
        q: &[f64; N],
        qdot: &[f64; N],
        u: &[f64; P],
    ) -> AccelerationJacobian<N, P>;
}

/// What linearization needs of a model, on run-time sizes: `n`
/// coordinates, `c` velocity constraint rows, `h` configuration
/// constraints, `p` inputs.
pub trait Dynamics {
    /// The coordinates' names, in order.
    fn coordinates(&self) -> Vec<String>;
    /// The velocity constraints' names, in order.
    fn constraints(&self) -> Vec<String>;
    /// The configuration constraints' names, in order.
    fn holonomic(&self) -> Vec<String>;
    /// The number of inputs `p`.
    fn inputs(&self) -> usize;
    /// The symmetry group's factors (empty without a symmetry).
    fn symmetry(&self) -> Vec<GroupFactor>;
    /// `f(q)`, `h` entries.
    fn holonomic_residual(&self, q: &[f64]) -> DVector<f64>;
    /// `df/dq`, `h x n`.
    fn holonomic_jacobian(&self, q: &[f64]) -> DMatrix<f64>;
    /// The mass matrix `g(q)`, `n x n`.
    fn mass_matrix(&self, q: &[f64]) -> DMatrix<f64>;
    /// `A(q)`, `c x n`.
    fn constraint_matrix(&self, q: &[f64]) -> DMatrix<f64>;
    /// `qddot(q, qdot, u)` of the Lagrange-d'Alembert equations.
    fn acceleration(&self, q: &[f64], qdot: &[f64], u: &[f64]) -> DVector<f64>;
    /// `(d qddot/dq, d qddot/dqdot, d qddot/du)`.
    fn acceleration_jacobian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
    ) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>);
}

/// `f(q)` and `df/dq` of a compiled model.
type HolonomicParts<M, const N: usize, const H: usize> = (
    fn(&M, &[f64; N]) -> [f64; H],
    fn(&M, &[f64; N]) -> [[f64; N]; H],
    fn(&M) -> [&str; H],
);

/// A generated model seen as [`Dynamics`]: `N` coordinates, `C`
/// constraint rows, `P` inputs, `H` configuration constraints.
pub struct Compiled<'a, M, const N: usize, const C: usize, const P: usize, const H: usize> {
    model: &'a M,
    holonomic: HolonomicParts<M, N, H>,
}

impl<'a, M, const N: usize, const C: usize, const P: usize> Compiled<'a, M, N, C, P, 0> {
    /// A model without configuration constraints.
    pub fn new(model: &'a M) -> Self {
        Self {
            model,
            holonomic: (|_, _| [], |_, _| [], |_| []),
        }
    }
}

impl<'a, M, const N: usize, const C: usize, const P: usize, const H: usize>
    Compiled<'a, M, N, C, P, H>
where
    M: Holonomic<N, H>,
{
    /// A model with its configuration constraints.
    pub fn holonomic(model: &'a M) -> Self {
        Self {
            model,
            holonomic: (
                M::holonomic_residual,
                M::holonomic_jacobian,
                M::holonomic_names,
            ),
        }
    }
}

/// Owned copies of `names`.
fn owned(names: &[&str]) -> Vec<String> {
    names.iter().map(|name| name.to_string()).collect()
}

/// A row-major array as a matrix.
fn matrix<const R: usize, const K: usize>(rows: &[[f64; K]; R]) -> DMatrix<f64> {
    DMatrix::from_fn(R, K, |i, j| rows[i][j])
}

impl<M, const N: usize, const C: usize, const P: usize, const H: usize> Dynamics
    for Compiled<'_, M, N, C, P, H>
where
    M: Linearization<N, C, P> + ModelNames,
{
    fn coordinates(&self) -> Vec<String> {
        owned(self.model.coordinate_names())
    }

    fn constraints(&self) -> Vec<String> {
        owned(self.model.constraint_names())
    }

    fn holonomic(&self) -> Vec<String> {
        owned(&(self.holonomic.2)(self.model))
    }

    fn inputs(&self) -> usize {
        P
    }

    fn symmetry(&self) -> Vec<GroupFactor> {
        Linearization::symmetry(self.model).to_vec()
    }

    fn holonomic_residual(&self, q: &[f64]) -> DVector<f64> {
        DVector::from_row_slice(&(self.holonomic.0)(self.model, &leading(q)))
    }

    fn holonomic_jacobian(&self, q: &[f64]) -> DMatrix<f64> {
        matrix(&(self.holonomic.1)(self.model, &leading(q)))
    }

    fn mass_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        matrix(&self.model.mass_matrix(&leading(q)))
    }

    fn constraint_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        matrix(&self.model.constraint_matrix(&leading(q)))
    }

    fn acceleration(&self, q: &[f64], qdot: &[f64], u: &[f64]) -> DVector<f64> {
        let (qddot, _) = self
            .model
            .acceleration(&leading(q), &leading(qdot), &leading(u));
        DVector::from_row_slice(&qddot)
    }

    fn acceleration_jacobian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
    ) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
        let (by_q, by_qdot, by_u) =
            self.model
                .acceleration_jacobian(&leading(q), &leading(qdot), &leading(u));
        (matrix(&by_q), matrix(&by_qdot), matrix(&by_u))
    }
}

/// The pivots of Gaussian elimination on `matrix` restricted to the
/// columns `candidates`: `(row, column)` pairs, as many as its rank. Each
/// step takes, among the rows and candidate columns left, the first
/// candidate (in the order given) whose largest entry is at least
/// `preference` times the largest entry left (`preference = 1` is complete
/// pivoting; smaller values let the order of `candidates` decide between
/// well-conditioned choices); it stops when no entry exceeds `tolerance`.
pub(crate) fn pivots(
    matrix: &DMatrix<f64>,
    candidates: &[usize],
    preference: f64,
    tolerance: f64,
) -> Vec<(usize, usize)> {
    let mut reduced = matrix.clone();
    let mut rows: Vec<usize> = (0..matrix.nrows()).collect();
    let mut columns = candidates.to_vec();
    let mut chosen = Vec::new();
    loop {
        let largest_in = |reduced: &DMatrix<f64>, column: usize| {
            rows.iter()
                .map(|&row| (row, reduced[(row, column)].abs()))
                .fold((usize::MAX, 0.0), |best, entry| {
                    if entry.1 > best.1 { entry } else { best }
                })
        };
        let largest = columns
            .iter()
            .map(|&column| largest_in(&reduced, column).1)
            .fold(0.0, f64::max);
        if largest <= tolerance || rows.is_empty() {
            return chosen;
        }
        let column = columns
            .iter()
            .copied()
            .find(|&column| largest_in(&reduced, column).1 >= preference * largest)
            .unwrap_or(columns[0]);
        let (row, _) = largest_in(&reduced, column);
        eliminate(&mut reduced, &rows, row, column);
        rows.retain(|&r| r != row);
        columns.retain(|&c| c != column);
        chosen.push((row, column));
    }
}

/// Subtracts multiples of `pivot_row` from the other `rows` to clear `column`.
fn eliminate(matrix: &mut DMatrix<f64>, rows: &[usize], pivot_row: usize, column: usize) {
    let pivot = matrix[(pivot_row, column)];
    for &row in rows.iter().filter(|&&row| row != pivot_row) {
        let factor = matrix[(row, column)] / pivot;
        if factor != 0.0 {
            for j in 0..matrix.ncols() {
                matrix[(row, j)] -= factor * matrix[(pivot_row, j)];
            }
        }
    }
}

/// The largest `|entry|` of `values` and its index (`None` when empty).
pub(crate) fn largest(values: &[f64]) -> Option<(usize, f64)> {
    values
        .iter()
        .copied()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
}
