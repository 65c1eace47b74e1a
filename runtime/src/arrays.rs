//! nalgebra values to and from the arrays of the generated API
//! (docs/INTERFACE.md section 2): vectors `[f64; n]`, matrices `[[f64; n]; m]`
//! row-major, `m[i][j]` in row `i`, column `j`.
//!
//! Vectors convert both ways with nalgebra's own `From`:
//! `SVector::from(q)` and `<[f64; N]>::from(v)` (or `v.into()`). Matrices do
//! not: nalgebra's `From<[[T; R]; C]>` reads each inner array as a
//! **column**, so `SMatrix::from(model.mass_matrix(&q))` is the transpose of
//! the mass matrix (the same matrix only when it is symmetric, and silently
//! wrong for `constraint_matrix`, `input_matrix` or `structure_matrix`).
//! [`matrix_from_rows`] and [`rows_of`] read and write rows; [`leading`]
//! makes an array of a slice, as the run-time-sized views of a model need.
//!
//! ```
//! use chaplygin_runtime::arrays::{matrix_from_rows, rows_of};
//! use chaplygin_runtime::linalg::{SMatrix, SVector};
//!
//! // The constraint matrix A(q) of a knife edge at heading theta = 0:
//! // one row (-sin theta, cos theta, 0) over (x, y, theta).
//! let rows = [[-0.0, 1.0, 0.0]];
//! let a: SMatrix<f64, 1, 3> = matrix_from_rows(&rows);
//! assert_eq!(a[(0, 1)], 1.0); // row 0, column 1
//! let qdot = SVector::from([2.0, 0.0, 0.5]);
//! assert_eq!((a * qdot)[0], 0.0); // rolling along x violates nothing
//! assert_eq!(rows_of(&a), rows);
//! let back: [f64; 3] = qdot.into();
//! assert_eq!(back, [2.0, 0.0, 0.5]);
//! ```

use nalgebra::SMatrix;

/// The matrix whose row `i` is `rows[i]`.
///
/// ```
/// use chaplygin_runtime::arrays::matrix_from_rows;
/// let m = matrix_from_rows(&[[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
/// assert_eq!((m.nrows(), m.ncols()), (2, 3));
/// assert_eq!(m[(1, 0)], 4.0);
/// ```
pub fn matrix_from_rows<const R: usize, const C: usize>(
    rows: &[[f64; C]; R],
) -> SMatrix<f64, R, C> {
    SMatrix::from_fn(|i, j| rows[i][j])
}

/// The rows of `m`, row-major as the generated API writes matrices.
///
/// ```
/// use chaplygin_runtime::arrays::rows_of;
/// use chaplygin_runtime::linalg::SMatrix;
/// let m = SMatrix::<f64, 2, 3>::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0); // row by row
/// assert_eq!(rows_of(&m), [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
/// ```
pub fn rows_of<const R: usize, const C: usize>(m: &SMatrix<f64, R, C>) -> [[f64; C]; R] {
    core::array::from_fn(|i| core::array::from_fn(|j| m[(i, j)]))
}

/// The first `L` entries of `values` as an array, zero past its end.
///
/// ```
/// use chaplygin_runtime::arrays::leading;
/// assert_eq!(leading::<2>(&[1.0, 2.0, 3.0]), [1.0, 2.0]);
/// assert_eq!(leading::<3>(&[1.0]), [1.0, 0.0, 0.0]);
/// ```
pub fn leading<const L: usize>(values: &[f64]) -> [f64; L] {
    core::array::from_fn(|i| values.get(i).copied().unwrap_or(0.0))
}
