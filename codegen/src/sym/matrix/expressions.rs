//! The arithmetic of matrices of expressions: the structured counterpart of
//! [`exact`](super::exact).
//!
//! Entries are [`ExprId`]s of the store's DAG. Products, sums and solves
//! build new nodes over the entries without expanding them, so shared
//! sub-expressions stay shared and sizes grow with the number of operations,
//! not with the number of terms of an expanded normal form (the basis of
//! the allowed velocities of a chain of N wheeled links has entries of about
//! `2 * 3^(N-2)` terms when expanded, against `O(N^2)` nodes here). Nothing
//! is decided here: an entry is known to be zero only when it is the
//! constant 0.
//!
//! [`Store::solve_in_order`] is Gaussian elimination whose pivots are fixed
//! in advance, the `i`-th on the diagonal: the caller orders the unknowns so
//! that the pivots do not vanish at the configurations of interest (the
//! constraint analysis chooses them at the model's defaults). Its result is
//! the exact solution as a rational function, written as the elimination
//! computes it.

use super::{Matrix, MatrixError};
use crate::sym::context::Context;
use crate::sym::expr::{ExprId, Store, SymbolId};

impl Matrix<ExprId> {
    /// `self * other`, each entry the sum of the products whose factors are
    /// not the constant 0.
    pub fn mul(
        &self,
        other: &Matrix<ExprId>,
        store: &mut Store,
    ) -> Result<Matrix<ExprId>, MatrixError> {
        if self.columns != other.rows {
            return Err(self.shape_error(other));
        }
        let mut entries = Vec::with_capacity(self.rows * other.columns);
        for i in 0..self.rows {
            for j in 0..other.columns {
                let mut terms = Vec::with_capacity(self.columns);
                for l in 0..self.columns {
                    let (a, b) = (*self.get(i, l), *other.get(l, j));
                    if !store.is_zero_constant(a) && !store.is_zero_constant(b) {
                        terms.push(store.mul2(a, b));
                    }
                }
                entries.push(store.add(&terms));
            }
        }
        Matrix::new(self.rows, other.columns, entries)
    }

    /// `self + other`.
    pub fn add(
        &self,
        other: &Matrix<ExprId>,
        store: &mut Store,
    ) -> Result<Matrix<ExprId>, MatrixError> {
        self.zip_with(other, |&a, &b| store.add2(a, b))
    }

    /// `self - other`.
    pub fn sub(
        &self,
        other: &Matrix<ExprId>,
        store: &mut Store,
    ) -> Result<Matrix<ExprId>, MatrixError> {
        self.zip_with(other, |&a, &b| store.sub(a, b))
    }

    /// Every entry times `factor`.
    pub fn scale(&self, factor: ExprId, store: &mut Store) -> Matrix<ExprId> {
        self.map(|&e| store.mul2(factor, e))
    }

    /// Every entry differentiated by `symbol`.
    pub fn derivative(&self, symbol: SymbolId, cx: &mut Context) -> Matrix<ExprId> {
        Matrix {
            rows: self.rows,
            columns: self.columns,
            entries: cx.derivatives(&self.entries, symbol),
        }
    }
}

impl Store {
    /// The zero matrix.
    pub fn zero_matrix(&mut self, rows: usize, columns: usize) -> Matrix<ExprId> {
        Matrix::filled(rows, columns, self.integer(0))
    }

    /// The identity.
    pub fn identity_matrix(&mut self, size: usize) -> Matrix<ExprId> {
        let mut identity = self.zero_matrix(size, size);
        let one = self.integer(1);
        for i in 0..size {
            identity.set(i, i, one);
        }
        identity
    }

    /// True when `id` is the constant 0.
    pub fn is_zero_constant(&self, id: ExprId) -> bool {
        self.as_number(id).is_some_and(|value| value.is_zero())
    }

    /// `a = L D L^T` for a symmetric positive definite `a` (its lower
    /// triangle is read): the unit lower-triangular `L` and the pivots `D`,
    /// by elimination in order,
    /// `D_j = a_jj - sum_k<j L_jk^2 D_k`,
    /// `L_ij = (a_ij - sum_k<j L_ik L_jk D_k) / D_j`. The pivots of a
    /// positive definite matrix are positive, so no pivoting is needed.
    pub fn ldl(
        &mut self,
        a: &Matrix<ExprId>,
    ) -> Result<(Matrix<ExprId>, Vec<ExprId>), MatrixError> {
        let size = a.rows();
        let mut lower = self.identity_matrix(size);
        // scaled[i][k] = L_ik D_k
        let mut scaled = self.zero_matrix(size, size);
        let mut pivots = Vec::with_capacity(size);
        for j in 0..size {
            let pivot = self.reduced_entry(*a.get(j, j), &lower, &scaled, j, j);
            if self.is_zero_constant(pivot) {
                return Err(MatrixError::Singular { size, column: j });
            }
            let one = self.integer(1);
            let reciprocal = self.div(one, pivot)?;
            for i in j + 1..size {
                let entry = self.reduced_entry(*a.get(i, j), &lower, &scaled, i, j);
                if !self.is_zero_constant(entry) {
                    lower.set(i, j, self.mul2(entry, reciprocal));
                    scaled.set(i, j, entry);
                }
            }
            pivots.push(pivot);
        }
        Ok((lower, pivots))
    }

    /// `entry - sum_k<j L_ik (L_jk D_k)`, skipping the constant zeros.
    fn reduced_entry(
        &mut self,
        entry: ExprId,
        lower: &Matrix<ExprId>,
        scaled: &Matrix<ExprId>,
        i: usize,
        j: usize,
    ) -> ExprId {
        let mut terms = vec![entry];
        for k in 0..j {
            let (l, s) = (*lower.get(i, k), *scaled.get(j, k));
            if !self.is_zero_constant(l) && !self.is_zero_constant(s) {
                let product = self.mul2(l, s);
                terms.push(self.neg(product));
            }
        }
        self.add(&terms)
    }

    /// `L^-1 b` for a unit lower-triangular `L` (forward substitution).
    pub fn forward_substitution(
        &mut self,
        lower: &Matrix<ExprId>,
        b: &Matrix<ExprId>,
    ) -> Matrix<ExprId> {
        let rows = b.rows();
        self.substitution(b, 0..rows, |i| 0..i, |i, k| *lower.get(i, k))
    }

    /// `L^-T b` for a unit lower-triangular `L` (back substitution).
    pub fn back_substitution(
        &mut self,
        lower: &Matrix<ExprId>,
        b: &Matrix<ExprId>,
    ) -> Matrix<ExprId> {
        let rows = b.rows();
        self.substitution(b, (0..rows).rev(), |i| i + 1..rows, |i, k| *lower.get(k, i))
    }

    /// `x_i = b_i - sum_k u_ik x_k` for the rows `i` in `order`, each over the
    /// rows `known(i)` already solved, skipping the constant zeros: the solve
    /// of a unit triangular system whose entries are `u_ik = coefficient(i, k)`.
    fn substitution(
        &mut self,
        b: &Matrix<ExprId>,
        order: impl Iterator<Item = usize> + Clone,
        known: impl Fn(usize) -> std::ops::Range<usize>,
        coefficient: impl Fn(usize, usize) -> ExprId,
    ) -> Matrix<ExprId> {
        let mut x = b.clone();
        for column in 0..b.columns() {
            for i in order.clone() {
                let mut terms = vec![*b.get(i, column)];
                for k in known(i) {
                    let (u, solved) = (coefficient(i, k), *x.get(k, column));
                    if !self.is_zero_constant(u) && !self.is_zero_constant(solved) {
                        let product = self.mul2(u, solved);
                        terms.push(self.neg(product));
                    }
                }
                x.set(i, column, self.add(&terms));
            }
        }
        x
    }

    /// Row `i` of `b` divided by `pivots[i]`.
    pub fn divide_rows(
        &mut self,
        b: &Matrix<ExprId>,
        pivots: &[ExprId],
    ) -> Result<Matrix<ExprId>, MatrixError> {
        let mut x = b.clone();
        for (i, &pivot) in pivots.iter().enumerate() {
            for column in 0..b.columns() {
                let entry = *b.get(i, column);
                if !self.is_zero_constant(entry) {
                    x.set(i, column, self.div(entry, pivot)?);
                }
            }
        }
        Ok(x)
    }

    /// The solution `x` of `a x = b` by Gaussian elimination with the
    /// diagonal as pivots, in order (see the module documentation). Fails
    /// when a pivot is the constant 0.
    pub fn solve_in_order(
        &mut self,
        a: &Matrix<ExprId>,
        b: &Matrix<ExprId>,
    ) -> Result<Matrix<ExprId>, MatrixError> {
        let size = a.rows();
        if a.columns() != size || b.rows() != size {
            return Err(a.shape_error(b));
        }
        let mut rows: Vec<Vec<ExprId>> = (0..size)
            .map(|i| {
                (0..size)
                    .map(|j| *a.get(i, j))
                    .chain((0..b.columns()).map(|j| *b.get(i, j)))
                    .collect()
            })
            .collect();
        for pivot in 0..size {
            if self.is_zero_constant(rows[pivot][pivot]) {
                return Err(MatrixError::Singular {
                    size,
                    column: pivot,
                });
            }
            let one = self.integer(1);
            let inverse = self.div(one, rows[pivot][pivot])?;
            let pivot_row = rows[pivot].clone();
            for row in &mut rows[pivot + 1..] {
                if self.is_zero_constant(row[pivot]) {
                    continue;
                }
                let factor = self.mul2(row[pivot], inverse);
                for column in pivot + 1..pivot_row.len() {
                    if self.is_zero_constant(pivot_row[column]) {
                        continue;
                    }
                    let reduction = self.mul2(factor, pivot_row[column]);
                    row[column] = self.sub(row[column], reduction);
                }
            }
        }
        let mut solution = self.zero_matrix(size, b.columns());
        for column in 0..b.columns() {
            for i in (0..size).rev() {
                let mut terms = vec![rows[i][size + column]];
                for (j, &coefficient) in rows[i].iter().enumerate().take(size).skip(i + 1) {
                    if !self.is_zero_constant(coefficient) {
                        let known = self.mul2(coefficient, *solution.get(j, column));
                        terms.push(self.neg(known));
                    }
                }
                let value = self.add(&terms);
                let x = self.div(value, rows[i][i])?;
                solution.set(i, column, x);
            }
        }
        Ok(solution)
    }
}

impl Context {
    /// The Lie bracket `[X, Y]_i = sum_j X_j dY_i/dq_j - Y_j dX_i/dq_j` of two
    /// vector fields given as expressions, unexpanded.
    pub fn lie_bracket_of_expressions(
        &mut self,
        x: &[ExprId],
        y: &[ExprId],
        coordinates: &[SymbolId],
    ) -> Vec<ExprId> {
        let mut terms: Vec<Vec<ExprId>> = vec![Vec::new(); x.len()];
        for (j, &q) in coordinates.iter().enumerate() {
            for (along, field, negate) in [(x[j], y, false), (y[j], x, true)] {
                if self.is_zero_constant(along) {
                    continue;
                }
                let derivatives = self.derivatives(field, q);
                let factor = if negate { self.neg(along) } else { along };
                for (i, &d) in derivatives.iter().enumerate() {
                    if !self.is_zero_constant(d) {
                        terms[i].push(self.mul2(factor, d));
                    }
                }
            }
        }
        terms.iter().map(|t| self.add(t)).collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::sym::{Context, Function, Matrix, SymbolKind};

    /// A 3 x 3 trigonometric system solved in order, against the exact
    /// solve of the normal forms: equal as rational functions, and not equal
    /// to the solution of a perturbed system.
    #[test]
    fn elimination_in_order_gives_the_exact_solution() {
        let mut store = Context::new();
        let [x, y, m] = [
            ("x", SymbolKind::Coordinate),
            ("y", SymbolKind::Coordinate),
            ("m", SymbolKind::Parameter),
        ]
        .map(|(name, kind)| {
            let symbol = store.declare(name, kind);
            store.symbol(symbol)
        });
        let sin_x = store.apply(Function::Sin, x).expect("applies");
        let cos_y = store.apply(Function::Cos, y).expect("applies");
        let two = store.integer(2);
        let m_sin = store.mul2(m, sin_x);
        let one = store.integer(1);
        let cos_y_plus_two = store.add2(cos_y, two);
        let zero = store.integer(0);
        let a = Matrix::new(
            3,
            3,
            vec![cos_y_plus_two, m_sin, one, sin_x, two, zero, one, cos_y, m],
        )
        .expect("3 x 3");
        let b = Matrix::new(3, 2, vec![one, x, zero, y, m_sin, one]).expect("3 x 2");
        let structured = store.solve_in_order(&a, &b).expect("regular pivots");
        let exact_a = Matrix::from_expressions(&mut store, 3, 3, a.entries()).expect("normal");
        let exact_b = Matrix::from_expressions(&mut store, 3, 2, b.entries()).expect("normal");
        let atoms = store.atoms().clone();
        let exact = exact_a.solve(&exact_b, &atoms).expect("regular");
        let found =
            Matrix::from_expressions(&mut store, 3, 2, structured.entries()).expect("normal");
        let atoms = store.atoms().clone();
        // equal as rational functions: the difference is exactly zero (the
        // two normal forms may keep different common factors)
        assert!(found.sub(&exact, &atoms).expect("same shape").is_zero());
        let perturbed = *a.get(0, 0);
        let mut other = a.clone();
        other.set(0, 0, store.add2(perturbed, one));
        let other = store.solve_in_order(&other, &b).expect("regular pivots");
        let other = Matrix::from_expressions(&mut store, 3, 2, other.entries()).expect("normal");
        let atoms = store.atoms().clone();
        assert!(!other.sub(&exact, &atoms).expect("same shape").is_zero());
    }

    /// `L D L^T` of a 3 x 3 positive definite trigonometric matrix
    /// multiplies back to it, and `L^-1`, `L^-T` invert `L` and `L^T`, as
    /// rational functions.
    #[test]
    fn ldl_factors_and_substitutions_invert() {
        let mut store = Context::new();
        let x = store.declare("x", SymbolKind::Coordinate);
        let x = store.symbol(x);
        let cos_x = store.apply(Function::Cos, x).expect("applies");
        let [one, two, three] = [1, 2, 3].map(|n| store.integer(n));
        let zero = store.integer(0);
        let three_plus_cos = store.add2(three, cos_x);
        let a = Matrix::new(
            3,
            3,
            vec![
                three_plus_cos,
                cos_x,
                one,
                cos_x,
                two,
                zero,
                one,
                zero,
                three,
            ],
        )
        .expect("3 x 3");
        let (lower, pivots) = store.ldl(&a).expect("positive definite");
        let mut diagonal = store.zero_matrix(3, 3);
        for (i, &p) in pivots.iter().enumerate() {
            diagonal.set(i, i, p);
        }
        let product = lower
            .mul(&diagonal, &mut store)
            .and_then(|ld| ld.mul(&lower.transpose(), &mut store))
            .expect("fits");
        let b = Matrix::new(3, 2, vec![one, x, two, cos_x, zero, three]).expect("3 x 2");
        let forward = store.forward_substitution(&lower, &b);
        let back = store.back_substitution(&lower, &b);
        let undone_forward = lower.mul(&forward, &mut store).expect("fits");
        let undone_back = lower.transpose().mul(&back, &mut store).expect("fits");
        for (found, expected) in [(&product, &a), (&undone_forward, &b), (&undone_back, &b)] {
            let rows = expected.rows();
            let columns = expected.columns();
            let found = Matrix::from_expressions(&mut store, rows, columns, found.entries())
                .expect("normal");
            let expected = Matrix::from_expressions(&mut store, rows, columns, expected.entries())
                .expect("normal");
            let atoms = store.atoms().clone();
            assert!(found.sub(&expected, &atoms).expect("same shape").is_zero());
        }
        assert_eq!(*lower.get(1, 2), zero, "L is unit lower-triangular");
        assert_eq!(*lower.get(1, 1), one);
    }

    #[test]
    fn a_vanishing_pivot_is_singular() {
        let mut store = Context::new();
        let zero = store.integer(0);
        let one = store.integer(1);
        let a = Matrix::new(2, 2, vec![zero, one, one, zero]).expect("2 x 2");
        let b = Matrix::column(vec![one, one]);
        assert!(store.solve_in_order(&a, &b).is_err());
    }

    #[test]
    fn products_skip_zero_factors_and_transpose_swaps_indices() {
        let mut store = Context::new();
        let x = store.declare("x", SymbolKind::Coordinate);
        let x = store.symbol(x);
        let zero = store.integer(0);
        let one = store.integer(1);
        let a = Matrix::new(1, 2, vec![x, zero]).expect("1 x 2");
        let b = Matrix::new(2, 1, vec![one, x]).expect("2 x 1");
        let product = a.mul(&b, &mut store).expect("fits");
        assert_eq!(product.entries(), [x]);
        assert_eq!(a.transpose().entries(), [x, zero]);
        assert_eq!(a.transpose().rows(), 2);
        assert!(a.mul(&a, &mut store).is_err());
    }
}
