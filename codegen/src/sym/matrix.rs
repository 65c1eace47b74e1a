//! Small symbolic matrices, generic over their entries.
//!
//! A [`Matrix`] is dense and row-major. Two kinds of entry carry its
//! arithmetic, each in its own module:
//!
//! - [`RationalFunction`] normal forms ([`exact`]): every product and sum is
//!   exact and every zero test is the normal form's; determinants, solves,
//!   null spaces and ranks by fraction-free elimination.
//! - [`ExprId`](super::ExprId) expressions of the store's DAG ([`expressions`]): products,
//!   sums and solves build nodes over the entries without expanding them, so
//!   shared sub-expressions stay shared.
//!
//! What does not depend on the entry is written once, here: the shape, access,
//! the transpose, submatrices and the placement of blocks.

pub mod exact;
pub mod expressions;

use super::expr::SymError;
use super::normal::RationalFunction;

pub use exact::numeric_rank;

/// A dense matrix, row-major, of exact normal forms unless said otherwise.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Matrix<E = RationalFunction> {
    rows: usize,
    columns: usize,
    entries: Vec<E>,
}

/// Why a matrix operation failed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MatrixError {
    /// The matrix is singular at every configuration (its exact rank is short),
    /// or a pivot fixed in advance is the constant 0.
    #[error("the {size}x{size} matrix is singular: column {column} has no non-zero pivot")]
    Singular {
        /// The matrix size.
        size: usize,
        /// The column without a pivot.
        column: usize,
    },
    /// Operand sizes do not fit.
    #[error("matrix sizes do not fit: {left:?} and {right:?}")]
    Shape {
        /// Rows and columns of the left operand.
        left: (usize, usize),
        /// Rows and columns of the right operand.
        right: (usize, usize),
    },
    /// The engine failed on an entry.
    #[error(transparent)]
    Symbolic(#[from] SymError),
}

impl<E: Clone> Matrix<E> {
    /// A matrix from row-major entries.
    pub fn new(rows: usize, columns: usize, entries: Vec<E>) -> Result<Matrix<E>, MatrixError> {
        if entries.len() != rows * columns {
            return Err(MatrixError::Shape {
                left: (rows, columns),
                right: (entries.len(), 1),
            });
        }
        Ok(Matrix {
            rows,
            columns,
            entries,
        })
    }

    /// Every entry `entry`.
    pub fn filled(rows: usize, columns: usize, entry: E) -> Matrix<E> {
        Matrix {
            rows,
            columns,
            entries: vec![entry; rows * columns],
        }
    }

    /// A matrix of no rows, `columns` wide.
    pub fn empty(columns: usize) -> Matrix<E> {
        Matrix {
            rows: 0,
            columns,
            entries: Vec::new(),
        }
    }

    /// A column.
    pub fn column(entries: Vec<E>) -> Matrix<E> {
        Matrix {
            rows: entries.len(),
            columns: 1,
            entries,
        }
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns.
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Entry `(i, j)`.
    pub fn get(&self, i: usize, j: usize) -> &E {
        &self.entries[i * self.columns + j]
    }

    /// Sets entry `(i, j)`.
    pub fn set(&mut self, i: usize, j: usize, value: E) {
        self.entries[i * self.columns + j] = value;
    }

    /// The entries, row-major.
    pub fn entries(&self) -> &[E] {
        &self.entries
    }

    /// Row `i` as a vector.
    pub fn row_entries(&self, i: usize) -> Vec<E> {
        self.entries[i * self.columns..(i + 1) * self.columns].to_vec()
    }

    /// Column `j` as a vector.
    pub fn column_entries(&self, j: usize) -> Vec<E> {
        (0..self.rows).map(|i| self.get(i, j).clone()).collect()
    }

    /// The transpose.
    pub fn transpose(&self) -> Matrix<E> {
        let entries = (0..self.columns)
            .flat_map(|j| (0..self.rows).map(move |i| (i, j)))
            .map(|(i, j)| self.get(i, j).clone())
            .collect();
        Matrix {
            rows: self.columns,
            columns: self.rows,
            entries,
        }
    }

    /// The entries at the given rows and columns, in that order.
    pub fn submatrix(&self, rows: &[usize], columns: &[usize]) -> Matrix<E> {
        let entries = rows
            .iter()
            .flat_map(|&i| columns.iter().map(move |&j| (i, j)))
            .map(|(i, j)| self.get(i, j).clone())
            .collect();
        Matrix {
            rows: rows.len(),
            columns: columns.len(),
            entries,
        }
    }

    /// Each entry mapped by `f`, in row-major order.
    pub fn map<F>(&self, f: impl FnMut(&E) -> F) -> Matrix<F> {
        Matrix {
            rows: self.rows,
            columns: self.columns,
            entries: self.entries.iter().map(f).collect(),
        }
    }

    /// `combine` of the entries at the same place in `self` and `other`.
    pub fn zip_with<F>(
        &self,
        other: &Matrix<E>,
        mut combine: impl FnMut(&E, &E) -> F,
    ) -> Result<Matrix<F>, MatrixError> {
        if (self.rows, self.columns) != (other.rows, other.columns) {
            return Err(self.shape_error(other));
        }
        let entries = self
            .entries
            .iter()
            .zip(&other.entries)
            .map(|(a, b)| combine(a, b))
            .collect();
        Ok(Matrix {
            rows: self.rows,
            columns: self.columns,
            entries,
        })
    }

    /// `[0; self]`: `zero_rows` rows of `zero` above the matrix.
    pub fn below_zero_rows(&self, zero_rows: usize, zero: E) -> Matrix<E> {
        let mut entries = vec![zero; zero_rows * self.columns];
        entries.extend_from_slice(&self.entries);
        Matrix {
            rows: zero_rows + self.rows,
            columns: self.columns,
            entries,
        }
    }

    /// `[[0, P^T], [-P, Gamma]]` for `P = self` (`k x n`) and `Gamma`
    /// (`k x k`), the negations made by `negate`: the skew structure matrix
    /// of a reduced port-Hamiltonian system.
    pub fn skew_structure(
        &self,
        gyroscopic: &Matrix<E>,
        zero: E,
        mut negate: impl FnMut(&E) -> E,
    ) -> Matrix<E> {
        let (k, n) = (self.rows, self.columns);
        let mut structure = Matrix::filled(n + k, n + k, zero);
        for a in 0..k {
            for j in 0..n {
                structure.set(j, n + a, self.get(a, j).clone());
                structure.set(n + a, j, negate(self.get(a, j)));
            }
            for b in 0..k {
                structure.set(n + a, n + b, gyroscopic.get(a, b).clone());
            }
        }
        structure
    }

    fn shape_error<F>(&self, other: &Matrix<F>) -> MatrixError {
        MatrixError::Shape {
            left: (self.rows, self.columns),
            right: (other.rows, other.columns),
        }
    }
}
