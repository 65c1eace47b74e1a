//! Linear algebra for the runtime, on nalgebra's matrices ([`SMatrix`] and
//! [`SVector`] on the stack in the stepping path). nalgebra factors
//! (LU with partial pivoting, Cholesky, the real Schur form); this module
//! keeps only what it does not do:
//!
//! - [`solve`] (LU) and [`solve_positive_definite`] (Cholesky): the
//!   generated code's row-major arrays in and out (through
//!   [`crate::arrays`]), and a structured [`MatrixError`] where nalgebra
//!   answers a bare `None`; [`cholesky`], nalgebra's factor of any size
//!   with that error;
//! - [`eigenvalues`]: nalgebra's `complex_eigenvalues` iterates the QR
//!   sweeps of the real Schur form without bound (a non-finite entry makes
//!   it loop forever) and returns the eigenvalues in the order of the
//!   diagonal blocks; here the iterations are bounded, a non-finite matrix
//!   or a failure to converge is an error, and the order is fixed;
//! - [`central_difference_jacobian`]: nalgebra has no numerical
//!   differentiation.
//!
//! On fixed sizes none of these allocates.

use crate::arrays::matrix_from_rows;
use nalgebra::allocator::Allocator;
use nalgebra::{
    Complex, Const, DefaultAllocator, Dim, DimDiff, DimMin, DimSub, OMatrix, OVector, Schur, U1,
};

pub use nalgebra::{SMatrix, SVector};

/// The sizes whose square matrices nalgebra factors by LU:
/// `Const<M>: Square` holds for `M` from 0 to 127, the sizes nalgebra names
/// as type-level numbers. Code generic over a state size `D` that steps an
/// implicit integrator states `where Const<D>: Square`.
pub trait Square: DimMin<Self, Output = Self> {}

impl<D: DimMin<D, Output = D>> Square for D {}

/// Why a matrix could not be factored or decomposed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MatrixError {
    /// LU with partial pivoting met a column with no nonzero pivot.
    #[error("the {order} x {order} matrix is singular (a zero pivot in its LU factorization)")]
    Singular {
        /// The number of rows and columns.
        order: usize,
    },
    /// Cholesky met a pivot that is not positive (or not a number).
    #[error(
        "the {order} x {order} matrix is not positive definite (a pivot of its Cholesky factorization is not positive)"
    )]
    NotPositiveDefinite {
        /// The number of rows and columns.
        order: usize,
    },
    /// An entry is NaN or infinite.
    #[error("the {order} x {order} matrix has a non-finite entry at row {row}, column {column}")]
    NonFinite {
        /// The number of rows and columns.
        order: usize,
        /// The entry's row, from 0.
        row: usize,
        /// The entry's column, from 0.
        column: usize,
    },
    /// The QR sweeps of the real Schur form did not converge.
    #[error(
        "the real Schur form of the {order} x {order} matrix did not converge in {sweeps} QR sweeps"
    )]
    NotConverged {
        /// The number of rows and columns.
        order: usize,
        /// The sweeps made.
        sweeps: usize,
    },
}

/// The solution `x` of `a x = b` by LU with partial pivoting (Golub & Van
/// Loan, *Matrix Computations*, algorithm 3.4.1), `a` row-major (`a[i][j]`
/// is row `i`).
///
/// Only an exactly zero pivot is an error: a nearly singular matrix is
/// solved as it is, and its solution is then large and inaccurate. NaN or
/// infinite entries give non-finite entries in the solution.
///
/// # Errors
/// [`MatrixError::Singular`] when a column has no nonzero pivot.
///
/// ```
/// use chaplygin_runtime::linalg::{MatrixError, solve};
/// // 2x + y = 5, x + 3y = 10
/// let x = solve(&[[2.0, 1.0], [1.0, 3.0]], &[5.0, 10.0]).unwrap();
/// assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 3.0).abs() < 1e-15);
/// let singular = solve(&[[1.0, 2.0], [2.0, 4.0]], &[1.0, 1.0]);
/// assert_eq!(singular, Err(MatrixError::Singular { order: 2 }));
/// ```
pub fn solve<const M: usize>(a: &[[f64; M]; M], b: &[f64; M]) -> Result<[f64; M], MatrixError>
where
    Const<M>: Square,
{
    matrix_from_rows(a)
        .lu()
        .solve(&SVector::from(*b))
        .map(Into::into)
        .ok_or(MatrixError::Singular { order: M })
}

/// The solution `x` of `a x = b` for a symmetric positive definite `a` (a
/// mass matrix, a Gram matrix) by Cholesky, `a = L L^T` (Golub & Van Loan,
/// algorithm 4.2.1): half the work of [`solve`], no pivoting, and a check
/// that `a` is positive definite. Only the lower triangle of `a` is read.
///
/// # Errors
/// [`MatrixError::NotPositiveDefinite`] when a pivot is not positive.
///
/// ```
/// use chaplygin_runtime::linalg::{MatrixError, solve_positive_definite};
/// let x = solve_positive_definite(&[[4.0, 2.0], [2.0, 3.0]], &[8.0, 7.0]).unwrap();
/// assert!((x[0] - 1.25).abs() < 1e-15 && (x[1] - 1.5).abs() < 1e-15);
/// let indefinite = solve_positive_definite(&[[1.0, 2.0], [2.0, 1.0]], &[1.0, 1.0]);
/// assert_eq!(indefinite, Err(MatrixError::NotPositiveDefinite { order: 2 }));
/// ```
pub fn solve_positive_definite<const M: usize>(
    a: &[[f64; M]; M],
    b: &[f64; M],
) -> Result<[f64; M], MatrixError> {
    let factor = cholesky(matrix_from_rows(a))?;
    Ok(factor.solve(&SVector::from(*b)).into())
}

/// The Cholesky factor of a symmetric positive definite `a` (its lower
/// triangle read), for any size, fixed or dynamic.
///
/// # Errors
/// [`MatrixError::NotPositiveDefinite`] when a pivot is not positive.
pub fn cholesky<D: Dim>(a: OMatrix<f64, D, D>) -> Result<nalgebra::Cholesky<f64, D>, MatrixError>
where
    DefaultAllocator: Allocator<D, D>,
{
    let order = a.nrows();
    a.cholesky()
        .ok_or(MatrixError::NotPositiveDefinite { order })
}

/// The eigenvalues of a real square matrix, from its real Schur form
/// `a = Q T Q^T` (Golub & Van Loan, section 7.5: Hessenberg reduction, then
/// Francis double-shift QR sweeps): each 1 x 1 block of `T` is a real
/// eigenvalue, each 2 x 2 block a complex conjugate pair. They are ordered
/// by decreasing real part, then decreasing imaginary part, so a pair
/// `a + bi, a - bi` (`b > 0`) comes in that order, its parts equal to the
/// last bit.
///
/// At most `30 n` sweeps for an `n x n` matrix (LAPACK's `dhseqr` allows
/// 30 per eigenvalue).
///
/// # Errors
/// [`MatrixError::NonFinite`] for a NaN or infinite entry;
/// [`MatrixError::NotConverged`] when the sweeps do not converge.
///
/// ```
/// use chaplygin_runtime::linalg::{SMatrix, eigenvalues};
/// // A rotation by 90 degrees: eigenvalues i and -i.
/// let rotation = SMatrix::<f64, 2, 2>::new(0.0, -1.0, 1.0, 0.0);
/// let lambda = eigenvalues(rotation).unwrap();
/// assert_eq!((lambda[0].re, lambda[0].im), (0.0, 1.0));
/// assert_eq!((lambda[1].re, lambda[1].im), (0.0, -1.0));
/// ```
pub fn eigenvalues<D>(a: OMatrix<f64, D, D>) -> Result<OVector<Complex<f64>, D>, MatrixError>
where
    D: Dim + DimSub<U1>,
    DefaultAllocator:
        Allocator<D, D> + Allocator<D> + Allocator<D, DimDiff<D, U1>> + Allocator<DimDiff<D, U1>>,
{
    let order = a.nrows();
    if order == 0 {
        // nalgebra's extraction of the eigenvalues assumes a row.
        return Ok(OVector::from_element_generic(
            a.shape_generic().0,
            U1,
            Complex::new(0.0, 0.0),
        ));
    }
    if let Some(index) = a.iter().position(|entry| !entry.is_finite()) {
        // nalgebra stores columns one after the other.
        let (column, row) = (index / order, index % order);
        return Err(MatrixError::NonFinite { order, row, column });
    }
    let sweeps = 30 * order.max(1);
    let schur = Schur::try_new(a, f64::EPSILON, sweeps)
        .ok_or(MatrixError::NotConverged { order, sweeps })?;
    let mut values = schur.complex_eigenvalues();
    values
        .as_mut_slice()
        .sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
    Ok(values)
}

/// The Jacobian `df/dx` of `f: R^D -> R^R` at `x` by central differences,
/// with the step `eps^(1/3) max(1, |x_j|)` (error of order `eps^(2/3)`
/// relative: about 4e-11 for smooth `f`). Row `i`, column `j` is
/// `d f_i / d x_j`.
pub fn central_difference_jacobian<const D: usize, const R: usize>(
    f: impl Fn(&[f64; D]) -> [f64; R],
    x: &[f64; D],
) -> [[f64; D]; R] {
    let mut jacobian = [[0.0; D]; R];
    for j in 0..D {
        let step = f64::EPSILON.cbrt() * x[j].abs().max(1.0);
        let (mut plus, mut minus) = (*x, *x);
        plus[j] += step;
        minus[j] -= step;
        let (f_plus, f_minus) = (f(&plus), f(&minus));
        for (row, (up, down)) in jacobian.iter_mut().zip(f_plus.iter().zip(&f_minus)) {
            row[j] = (up - down) / (plus[j] - minus[j]);
        }
    }
    jacobian
}
