//! The arithmetic of matrices of normal forms.
//!
//! Entries are [`RationalFunction`]s, so every product and sum is exact and
//! every zero test is the normal form's. Determinants and solves use Bareiss'
//! fraction-free elimination (Bareiss 1968): with `p_0 = 1`,
//!
//! ```text
//! a_ij <- (a_kk a_ij - a_ik a_kj) / p_{k-1},   p_k = a_kk,
//! ```
//!
//! where each division is exact, so polynomial entries stay polynomials of
//! bounded degree instead of nesting fractions. A square matrix is first split
//! into its diagonal blocks (connected components of the pattern of non-zero
//! entries: the snakeboard metric splits into `{x}, {y}, {theta, psi}, {phi}`),
//! and each block is eliminated alone. The rank is available exactly (the
//! generic rank over the function field, i.e. at almost every configuration)
//! and numerically at a point.

use super::{Matrix, MatrixError};
use crate::sym::context::Context;
use crate::sym::expr::{ExprId, SymbolId};
use crate::sym::normal::RationalFunction;
use crate::sym::poly::Atoms;

impl Matrix<RationalFunction> {
    /// The zero matrix.
    pub fn zeros(rows: usize, columns: usize) -> Matrix {
        Matrix::filled(rows, columns, RationalFunction::zero())
    }

    /// The identity.
    pub fn identity(size: usize) -> Matrix {
        let mut m = Matrix::zeros(size, size);
        for i in 0..size {
            m.set(i, i, RationalFunction::one());
        }
        m
    }

    /// The normal forms of row-major expressions.
    pub fn from_expressions(
        cx: &mut Context,
        rows: usize,
        columns: usize,
        expressions: &[ExprId],
    ) -> Result<Matrix, MatrixError> {
        let entries = expressions
            .iter()
            .map(|&e| cx.normal(e))
            .collect::<Result<Vec<_>, _>>()?;
        Matrix::new(rows, columns, entries)
    }

    /// The entries rebuilt as expressions, row-major.
    pub fn to_expressions(&self, cx: &mut Context) -> Vec<ExprId> {
        self.entries.iter().map(|e| cx.expression_of(e)).collect()
    }

    /// The entries rebuilt as expressions, as a matrix.
    pub fn to_expression_matrix(&self, cx: &mut Context) -> Matrix<ExprId> {
        self.map(|e| cx.expression_of(e))
    }

    /// `self * other`.
    pub fn mul(&self, other: &Matrix, atoms: &Atoms) -> Result<Matrix, MatrixError> {
        if self.columns != other.rows {
            return Err(self.shape_error(other));
        }
        let mut product = Matrix::zeros(self.rows, other.columns);
        for i in 0..self.rows {
            for j in 0..other.columns {
                let mut sum = RationalFunction::zero();
                for k in 0..self.columns {
                    let (a, b) = (self.get(i, k), other.get(k, j));
                    if !a.is_zero() && !b.is_zero() {
                        sum = sum.add(&a.mul(b, atoms), atoms);
                    }
                }
                product.set(i, j, sum);
            }
        }
        Ok(product)
    }

    /// `self + other`.
    pub fn add(&self, other: &Matrix, atoms: &Atoms) -> Result<Matrix, MatrixError> {
        self.zip_with(other, |a, b| a.add(b, atoms))
    }

    /// `self - other`.
    pub fn sub(&self, other: &Matrix, atoms: &Atoms) -> Result<Matrix, MatrixError> {
        self.add(&other.neg(), atoms)
    }

    /// `-self`.
    pub fn neg(&self) -> Matrix {
        self.map(RationalFunction::neg)
    }

    /// Every entry times `factor`.
    pub fn scale(&self, factor: &RationalFunction, atoms: &Atoms) -> Matrix {
        self.map(|entry| entry.mul(factor, atoms))
    }

    /// True when every entry is written out
    /// ([`RationalFunction::is_written_out`]).
    pub fn is_written_out(&self) -> bool {
        self.entries.iter().all(RationalFunction::is_written_out)
    }

    /// True when every entry is exactly zero.
    pub fn is_zero(&self) -> bool {
        self.entries.iter().all(RationalFunction::is_zero)
    }

    /// True when the matrix equals its transpose exactly.
    pub fn is_symmetric(&self) -> bool {
        self.rows == self.columns && *self == self.transpose()
    }

    /// True when `self^T = -self` exactly (entrywise normal forms).
    pub fn is_skew(&self, atoms: &Atoms) -> bool {
        self.rows == self.columns
            && self
                .add(&self.transpose(), atoms)
                .is_ok_and(|sum| sum.is_zero())
    }

    /// The index sets of the diagonal blocks of a square matrix, each sorted,
    /// ordered by their first index.
    pub fn diagonal_blocks(&self) -> Vec<Vec<usize>> {
        let mut parent: Vec<usize> = (0..self.rows).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        for i in 0..self.rows {
            for j in 0..self.columns.min(self.rows) {
                if !self.get(i, j).is_zero() {
                    let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
        let mut blocks: Vec<Vec<usize>> = Vec::new();
        let mut block_of_root = std::collections::HashMap::new();
        for i in 0..self.rows {
            let r = root(&mut parent, i);
            let at = *block_of_root.entry(r).or_insert_with(|| {
                blocks.push(Vec::new());
                blocks.len() - 1
            });
            blocks[at].push(i);
        }
        blocks
    }

    /// The determinant: the product of the diagonal blocks' Bareiss determinants.
    pub fn determinant(&self, atoms: &Atoms) -> Result<RationalFunction, MatrixError> {
        if self.rows != self.columns {
            return Err(self.shape_error(self));
        }
        let mut determinant = RationalFunction::one();
        for block in self.diagonal_blocks() {
            let sub = self.submatrix(&block, &block);
            let part = match sub.eliminate(&Matrix::zeros(block.len(), 0), atoms) {
                Ok(elimination) => elimination.determinant(),
                Err(MatrixError::Singular { .. }) => return Ok(RationalFunction::zero()),
                Err(other) => return Err(other),
            };
            determinant = determinant.mul(&part, atoms);
        }
        Ok(determinant)
    }

    /// The adjugate and the determinant by cofactor expansion, without a
    /// division: `self adj = det I`, and for polynomial entries both are
    /// polynomials. The quotient `adj rhs / det` is the solve with no
    /// divisor cleared by a conjugate (the normal form keeps denominators
    /// free of sines, which adds factors that vanish where the matrix is
    /// regular), so it stays finite wherever `self` is regular. Cost grows
    /// as `size!`; meant for the small blocks of a group's dimension.
    pub fn adjugate(&self, atoms: &Atoms) -> Result<(Matrix, RationalFunction), MatrixError> {
        if self.rows != self.columns {
            return Err(self.shape_error(self));
        }
        let size = self.rows;
        let all: Vec<usize> = (0..size).collect();
        let mut adjugate = Matrix::zeros(size, size);
        for i in 0..size {
            for j in 0..size {
                let rows: Vec<usize> = all.iter().copied().filter(|&k| k != i).collect();
                let columns: Vec<usize> = all.iter().copied().filter(|&k| k != j).collect();
                let minor = self.submatrix(&rows, &columns).expanded_determinant(atoms);
                let cofactor = if (i + j) % 2 == 0 { minor } else { minor.neg() };
                adjugate.set(j, i, cofactor);
            }
        }
        let determinant = (0..size).fold(RationalFunction::zero(), |sum, j| {
            sum.add(&self.get(0, j).mul(adjugate.get(j, 0), atoms), atoms)
        });
        let determinant = if size == 0 {
            RationalFunction::one()
        } else {
            determinant
        };
        Ok((adjugate, determinant))
    }

    /// The determinant by Laplace expansion along the first row.
    fn expanded_determinant(&self, atoms: &Atoms) -> RationalFunction {
        if self.rows == 0 {
            return RationalFunction::one();
        }
        let rest: Vec<usize> = (1..self.rows).collect();
        (0..self.columns).fold(RationalFunction::zero(), |sum, j| {
            if self.get(0, j).is_zero() {
                return sum;
            }
            let columns: Vec<usize> = (0..self.columns).filter(|&k| k != j).collect();
            let minor = self.submatrix(&rest, &columns).expanded_determinant(atoms);
            let term = self.get(0, j).mul(&minor, atoms);
            match j % 2 {
                0 => sum.add(&term, atoms),
                _ => sum.sub(&term, atoms),
            }
        })
    }

    /// `X` with `self X = rhs`, block by block.
    pub fn solve(&self, rhs: &Matrix, atoms: &Atoms) -> Result<Matrix, MatrixError> {
        if self.rows != self.columns || rhs.rows != self.rows {
            return Err(self.shape_error(rhs));
        }
        let mut solution = Matrix::zeros(self.rows, rhs.columns);
        let all_columns: Vec<usize> = (0..rhs.columns).collect();
        for block in self.diagonal_blocks() {
            let sub = self.submatrix(&block, &block);
            let sub_rhs = rhs.submatrix(&block, &all_columns);
            let part = sub.eliminate(&sub_rhs, atoms)?.back_substitute(atoms)?;
            for (row, &i) in block.iter().enumerate() {
                for j in 0..rhs.columns {
                    solution.set(i, j, part.get(row, j).clone());
                }
            }
        }
        Ok(solution)
    }

    /// The inverse, block by block.
    pub fn inverse(&self, atoms: &Atoms) -> Result<Matrix, MatrixError> {
        self.solve(&Matrix::identity(self.rows), atoms)
    }

    /// Bareiss forward elimination of `[self | rhs]`.
    fn eliminate(&self, rhs: &Matrix, atoms: &Atoms) -> Result<Elimination, MatrixError> {
        let n = self.rows;
        let width = n + rhs.columns;
        let mut rows: Vec<Vec<RationalFunction>> = (0..n)
            .map(|i| {
                let mut row: Vec<RationalFunction> =
                    (0..n).map(|j| self.get(i, j).clone()).collect();
                row.extend((0..rhs.columns).map(|j| rhs.get(i, j).clone()));
                row
            })
            .collect();
        let mut previous = RationalFunction::one();
        let mut swaps = 0;
        for k in 0..n {
            let pivot_row =
                choose_pivot(&rows, k, k).ok_or(MatrixError::Singular { size: n, column: k })?;
            if pivot_row != k {
                rows.swap(pivot_row, k);
                swaps += 1;
            }
            for i in k + 1..n {
                for j in k + 1..width {
                    let product = rows[k][k].mul(&rows[i][j], atoms);
                    let cross = rows[i][k].mul(&rows[k][j], atoms);
                    rows[i][j] = product
                        .sub(&cross, atoms)
                        .div(&previous, atoms)
                        .ok_or(MatrixError::Singular { size: n, column: k })?;
                }
                rows[i][k] = RationalFunction::zero();
            }
            previous = rows[k][k].clone();
        }
        Ok(Elimination {
            rows,
            size: n,
            swaps,
            last_pivot: previous,
        })
    }

    /// A basis of the null space `{v : self v = 0}`, as the rows of the result,
    /// from the reduced row echelon form: one basis vector per free column,
    /// 1 in that column and minus the pivot rows' entries in the pivot columns.
    pub fn null_space(&self, atoms: &Atoms) -> Result<Matrix, MatrixError> {
        let (rows, pivots) = self.reduced_row_echelon(atoms)?;
        let free: Vec<usize> = (0..self.columns).filter(|c| !pivots.contains(c)).collect();
        let mut basis = Matrix::zeros(free.len(), self.columns);
        for (b, &f) in free.iter().enumerate() {
            basis.set(b, f, RationalFunction::one());
            for (row, &p) in pivots.iter().enumerate() {
                basis.set(b, p, rows[row][f].neg());
            }
        }
        Ok(basis)
    }

    /// The reduced row echelon form (pivots 1) and its pivot columns.
    fn reduced_row_echelon(
        &self,
        atoms: &Atoms,
    ) -> Result<(Vec<Vec<RationalFunction>>, Vec<usize>), MatrixError> {
        let mut rows: Vec<Vec<RationalFunction>> = (0..self.rows)
            .map(|i| (0..self.columns).map(|j| self.get(i, j).clone()).collect())
            .collect();
        let mut pivots = Vec::new();
        for column in 0..self.columns {
            let rank = pivots.len();
            let Some(pivot_row) = choose_pivot(&rows, rank, column) else {
                continue;
            };
            rows.swap(pivot_row, rank);
            let pivot = rows[rank][column].clone();
            let singular = MatrixError::Singular {
                size: self.rows,
                column,
            };
            for entry in rows[rank].iter_mut() {
                *entry = entry.div(&pivot, atoms).ok_or(singular.clone())?;
            }
            let pivot_values = rows[rank].clone();
            for (i, row) in rows.iter_mut().enumerate() {
                if i == rank || row[column].is_zero() {
                    continue;
                }
                let factor = row[column].clone();
                for (entry, p) in row.iter_mut().zip(&pivot_values) {
                    *entry = entry.sub(&factor.mul(p, atoms), atoms);
                }
            }
            pivots.push(column);
        }
        Ok((rows, pivots))
    }

    /// The exact (generic) rank, by elimination with exact zero tests.
    pub fn rank(&self, atoms: &Atoms) -> usize {
        let mut rows: Vec<Vec<RationalFunction>> = (0..self.rows)
            .map(|i| (0..self.columns).map(|j| self.get(i, j).clone()).collect())
            .collect();
        let mut rank = 0;
        for column in 0..self.columns {
            let Some(pivot_row) = choose_pivot(&rows, rank, column) else {
                continue;
            };
            rows.swap(pivot_row, rank);
            for i in rank + 1..self.rows {
                if rows[i][column].is_zero() {
                    continue;
                }
                let Some(factor) = rows[i][column].div(&rows[rank][column], atoms) else {
                    continue;
                };
                let pivot_row = rows[rank].clone();
                for (entry, pivot_entry) in rows[i].iter_mut().zip(&pivot_row).skip(column) {
                    *entry = entry.sub(&factor.mul(pivot_entry, atoms), atoms);
                }
            }
            rank += 1;
        }
        rank
    }

    /// The entries as numbers, row-major, with symbols valued by `value_of`.
    pub fn evaluate(&self, cx: &mut Context, value_of: &dyn Fn(SymbolId) -> f64) -> Vec<f64> {
        self.entries
            .iter()
            .map(|e| cx.evaluate_normal(e, value_of))
            .collect()
    }

    /// The rank at a point, by Gaussian elimination with partial pivoting; an
    /// entry counts as zero below `relative_tolerance` times the largest entry.
    pub fn rank_at(
        &self,
        cx: &mut Context,
        value_of: &dyn Fn(SymbolId) -> f64,
        relative_tolerance: f64,
    ) -> usize {
        numeric_rank(
            self.evaluate(cx, value_of),
            self.rows,
            self.columns,
            relative_tolerance,
        )
    }
}

/// The row at or below `from` with the smallest non-zero entry in `column`.
fn choose_pivot(rows: &[Vec<RationalFunction>], from: usize, column: usize) -> Option<usize> {
    (from..rows.len())
        .filter(|&i| !rows[i][column].is_zero())
        .min_by_key(|&i| rows[i][column].size())
}

/// The upper-triangular result of Bareiss elimination.
struct Elimination {
    rows: Vec<Vec<RationalFunction>>,
    size: usize,
    swaps: usize,
    last_pivot: RationalFunction,
}

impl Elimination {
    /// The last Bareiss pivot is the determinant, up to the sign of the row swaps.
    fn determinant(&self) -> RationalFunction {
        if self.swaps % 2 == 1 {
            self.last_pivot.neg()
        } else {
            self.last_pivot.clone()
        }
    }

    fn back_substitute(&self, atoms: &Atoms) -> Result<Matrix, MatrixError> {
        let n = self.size;
        let columns = self.rows.first().map_or(0, |r| r.len() - n);
        let mut solution = Matrix::zeros(n, columns);
        for c in 0..columns {
            for i in (0..n).rev() {
                let mut value = self.rows[i][n + c].clone();
                for j in i + 1..n {
                    let known = self.rows[i][j].mul(solution.get(j, c), atoms);
                    value = value.sub(&known, atoms);
                }
                let x = value
                    .div(&self.rows[i][i], atoms)
                    .ok_or(MatrixError::Singular { size: n, column: i })?;
                solution.set(i, c, x);
            }
        }
        Ok(solution)
    }
}

/// Rank of a row-major numeric matrix by Gaussian elimination with partial pivoting.
pub fn numeric_rank(
    mut values: Vec<f64>,
    rows: usize,
    columns: usize,
    relative_tolerance: f64,
) -> usize {
    let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return 0;
    }
    let threshold = relative_tolerance * scale;
    let mut rank = 0;
    for column in 0..columns {
        if rank == rows {
            break;
        }
        let best = (rank..rows).max_by(|&a, &b| {
            values[a * columns + column]
                .abs()
                .total_cmp(&values[b * columns + column].abs())
        });
        let Some(best) = best.filter(|&r| values[r * columns + column].abs() > threshold) else {
            continue;
        };
        for j in 0..columns {
            values.swap(best * columns + j, rank * columns + j);
        }
        for i in rank + 1..rows {
            let factor = values[i * columns + column] / values[rank * columns + column];
            for j in column..columns {
                values[i * columns + j] -= factor * values[rank * columns + j];
            }
        }
        rank += 1;
    }
    rank
}

impl Context {
    /// The Jacobian `d f_i / d x_j` of normal forms.
    pub fn jacobian(
        &mut self,
        functions: &[RationalFunction],
        variables: &[SymbolId],
    ) -> Result<Matrix, MatrixError> {
        let mut entries = Vec::with_capacity(functions.len() * variables.len());
        for f in functions {
            for &x in variables {
                entries.push(self.derivative_of_normal(f, x)?);
            }
        }
        Matrix::new(functions.len(), variables.len(), entries)
    }

    /// The Lie bracket `[X, Y] = (dY/dq) X - (dX/dq) Y` of two vector fields on
    /// the coordinates `q`.
    pub fn lie_bracket(
        &mut self,
        x: &[RationalFunction],
        y: &[RationalFunction],
        coordinates: &[SymbolId],
    ) -> Result<Vec<RationalFunction>, MatrixError> {
        let column = |v: &[RationalFunction]| Matrix::new(v.len(), 1, v.to_vec());
        let (x_column, y_column) = (column(x)?, column(y)?);
        let dy_x = self.jacobian(y, coordinates)?.mul(&x_column, &self.atoms)?;
        let dx_y = self.jacobian(x, coordinates)?.mul(&y_column, &self.atoms)?;
        Ok(dy_x.sub(&dx_y, &self.atoms)?.entries)
    }
}
