//! The state vectors the integrators step and the simulation loop observes,
//! written once for both kinds of size:
//!
//! - `[f64; D]`, a size known when the model is compiled (every generated
//!   model): a step stays on the stack and allocates nothing
//!   (`models/tests/allocation.rs` counts);
//! - `Vec<f64>`, a size known only at run time (a model read from text
//!   and run through a slice-based interface, as the command line's
//!   formulations are; diffsol's `nstates()` is the same idea).
//!
//! A [`State`] makes states of its own size ([`State::with_entries`]) and
//! names the square matrices over it ([`State::Matrix`]: a Jacobian
//! `df/dx`, a structure matrix `J(x)`), and solves the one linear system
//! the implicit integrators need, Newton's `(I - c A) y = b`, by nalgebra's
//! LU with partial pivoting, factored once for several right-hand sides.

use crate::linalg::Square;
use core::fmt::Debug;
use core::ops::{Index, IndexMut};
use nalgebra::{Const, DMatrix, DVector, Dyn, LU, SMatrix, SVector};

/// A state vector of `f64` entries (see the module documentation).
pub trait State:
    Clone
    + Debug
    + PartialEq
    + AsRef<[f64]>
    + AsMut<[f64]>
    + Index<usize, Output = f64>
    + IndexMut<usize>
{
    /// A square matrix over the state, rows and columns indexed as the
    /// state's entries.
    type Matrix: Clone + Debug;

    /// The state of this one's size whose entry `i` is `entry(i)`.
    fn with_entries(&self, entry: impl FnMut(usize) -> f64) -> Self;

    /// Row `i`, column `j` of `matrix`.
    fn entry(matrix: &Self::Matrix, i: usize, j: usize) -> f64;

    /// Every entry of `matrix`, in an order of the storage's choosing (for
    /// checks that concern every entry alike, such as finiteness).
    fn entries(matrix: &Self::Matrix) -> &[f64];

    /// The LU factors of a shifted matrix `I - scale a`.
    type Factors;

    /// The LU factors of `I - scale a` with partial pivoting (Golub & Van
    /// Loan, algorithm 3.4.1); `None` when a column has no nonzero pivot.
    fn factor_shifted(scale: f64, a: &Self::Matrix) -> Option<Self::Factors>;

    /// The solution `y` of `(I - scale a) y = b` from the factors of
    /// `I - scale a` ([`State::factor_shifted`]).
    fn solve_factored(factors: &Self::Factors, b: &Self) -> Self;
}

/// `1` on the diagonal, `0` off it.
fn identity_entry(i: usize, j: usize) -> f64 {
    f64::from(u8::from(i == j))
}

impl<const D: usize> State for [f64; D]
where
    Const<D>: Square,
{
    type Matrix = [[f64; D]; D];

    fn with_entries(&self, entry: impl FnMut(usize) -> f64) -> Self {
        core::array::from_fn(entry)
    }

    fn entry(matrix: &Self::Matrix, i: usize, j: usize) -> f64 {
        matrix[i][j]
    }

    fn entries(matrix: &Self::Matrix) -> &[f64] {
        matrix.as_flattened()
    }

    type Factors = LU<f64, Const<D>, Const<D>>;

    fn factor_shifted(scale: f64, a: &Self::Matrix) -> Option<Self::Factors> {
        let lu = SMatrix::<f64, D, D>::from_fn(|i, j| identity_entry(i, j) - scale * a[i][j]).lu();
        lu.is_invertible().then_some(lu)
    }

    fn solve_factored(factors: &Self::Factors, b: &Self) -> Self {
        let mut y = SVector::from(*b);
        factors.solve_mut(&mut y);
        y.into()
    }
}

impl State for Vec<f64> {
    type Matrix = DMatrix<f64>;

    fn with_entries(&self, entry: impl FnMut(usize) -> f64) -> Self {
        (0..self.len()).map(entry).collect()
    }

    fn entry(matrix: &Self::Matrix, i: usize, j: usize) -> f64 {
        matrix[(i, j)]
    }

    fn entries(matrix: &Self::Matrix) -> &[f64] {
        matrix.as_slice()
    }

    type Factors = LU<f64, Dyn, Dyn>;

    fn factor_shifted(scale: f64, a: &Self::Matrix) -> Option<Self::Factors> {
        let n = a.nrows();
        let lu = DMatrix::from_fn(n, n, |i, j| identity_entry(i, j) - scale * a[(i, j)]).lu();
        lu.is_invertible().then_some(lu)
    }

    fn solve_factored(factors: &Self::Factors, b: &Self) -> Self {
        let mut y = DVector::from_column_slice(b);
        factors.solve_mut(&mut y);
        y.as_slice().to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::State;
    use nalgebra::DMatrix;

    /// `(I - c A) y = b` for `A = [[1, 2], [3, 4]]`, `c = 0.5`, `b = (1, 2)`:
    /// `I - c A = [[0.5, -1], [-1.5, -1]]`; subtracting the rows gives
    /// `2 y_1 = -1`, so `y = (-0.5, -1.25)`; the same factors solve `b = (0.5,
    /// -1.5)`, the first column, to `y = (1, 0)`.
    #[test]
    fn both_sizes_solve_the_shifted_system_alike() {
        let close = |y: &[f64], expected: [f64; 2]| {
            y.iter().zip(&expected).all(|(a, b)| (a - b).abs() < 1e-15)
        };
        let rows = [[1.0, 2.0], [3.0, 4.0]];
        let fixed = <[f64; 2]>::factor_shifted(0.5, &rows).unwrap();
        let matrix = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0]);
        let dynamic = Vec::factor_shifted(0.5, &matrix).unwrap();
        for (b, expected) in [([1.0, 2.0], [-0.5, -1.25]), ([0.5, -1.5], [1.0, 0.0])] {
            let y = <[f64; 2]>::solve_factored(&fixed, &b);
            let z = Vec::solve_factored(&dynamic, &b.to_vec());
            assert!(close(&y, expected) && close(&z, expected), "{y:?} {z:?}");
        }
        assert_eq!(<[f64; 2]>::entry(&rows, 1, 0), 3.0);
        assert_eq!(Vec::entry(&matrix, 1, 0), 3.0);
    }

    #[test]
    fn a_singular_shift_has_no_factors() {
        // I - 1 * I = 0.
        let identity = [[1.0, 0.0], [0.0, 1.0]];
        assert!(<[f64; 2]>::factor_shifted(1.0, &identity).is_none());
        let identity = DMatrix::identity(2, 2);
        assert!(Vec::factor_shifted(1.0, &identity).is_none());
    }
}
