//! Dense linear algebra on the stack, for generated code.
//!
//! [`solve`] is Gaussian elimination with partial pivoting (Golub & Van Loan,
//! *Matrix Computations*, algorithm 3.4.1) on a fixed-size system: no heap,
//! no panics, `O(M^3)` operations (`M^3/3` multiply-adds to leading order).

/// The solution `x` of `a x = b`.
///
/// At step `k` the row with the largest `|a_ik|`, `i >= k`, becomes the pivot
/// row; rows below are reduced, then `x` follows by back substitution. When a
/// pivot is exactly zero the matrix is singular and every entry of the result
/// is NaN. NaN or infinite entries propagate to non-finite entries of the
/// result.
/// Nearly singular matrices are solved as they are: the result is then large
/// and inaccurate, never an error.
///
/// ```
/// use chaplygin_runtime::linalg::solve;
/// // 2x + y = 5, x + 3y = 10
/// let x = solve([[2.0, 1.0], [1.0, 3.0]], [5.0, 10.0]);
/// assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 3.0).abs() < 1e-15);
/// assert!(solve([[1.0, 2.0], [2.0, 4.0]], [1.0, 1.0]).iter().all(|v| v.is_nan()));
/// ```
pub fn solve<const M: usize>(mut a: [[f64; M]; M], mut b: [f64; M]) -> [f64; M] {
    for k in 0..M {
        let pivot_row = largest_below(&a, k);
        a.swap(k, pivot_row);
        b.swap(k, pivot_row);
        if a[k][k] == 0.0 {
            return [f64::NAN; M];
        }
        eliminate_below(&mut a, &mut b, k);
    }
    back_substitute(&a, &mut b);
    b
}

/// The row `i >= k` with the largest `|a_ik|` (the first on ties; NaNs
/// compare as not larger).
fn largest_below<const M: usize>(a: &[[f64; M]; M], k: usize) -> usize {
    let mut best = k;
    for (i, row) in a.iter().enumerate().skip(k + 1) {
        if row[k].abs() > a[best][k].abs() {
            best = i;
        }
    }
    best
}

/// Subtracts multiples of row `k` from the rows below so that column `k`
/// vanishes under the pivot.
fn eliminate_below<const M: usize>(a: &mut [[f64; M]; M], b: &mut [f64; M], k: usize) {
    let (upper, lower) = a.split_at_mut(k + 1);
    let (b_upper, b_lower) = b.split_at_mut(k + 1);
    let (pivot_row, pivot_rhs) = (&upper[k], b_upper[k]);
    for (row, rhs) in lower.iter_mut().zip(b_lower) {
        let factor = row[k] / pivot_row[k];
        for (entry, pivot_entry) in row.iter_mut().zip(pivot_row).skip(k + 1) {
            *entry -= factor * pivot_entry;
        }
        *rhs -= factor * pivot_rhs;
    }
}

/// Solves the upper triangular system in place: `b` becomes `x`.
fn back_substitute<const M: usize>(a: &[[f64; M]; M], b: &mut [f64; M]) {
    for i in (0..M).rev() {
        let (head, solved) = b.split_at_mut(i + 1);
        let reduced = a[i]
            .iter()
            .skip(i + 1)
            .zip(solved.iter())
            .fold(head[i], |rest, (entry, x)| rest - entry * x);
        head[i] = reduced / a[i][i];
    }
}

/// The determinant of `a` by Gaussian elimination with partial pivoting:
/// the product of the pivots, with the sign of the row permutation.
///
/// ```
/// use chaplygin_runtime::linalg::determinant;
/// assert_eq!(determinant([[0.0, 2.0], [3.0, 1.0]]), -6.0);
/// assert_eq!(determinant([[1.0, 2.0], [2.0, 4.0]]), 0.0);
/// ```
pub fn determinant<const M: usize>(mut a: [[f64; M]; M]) -> f64 {
    let mut product = 1.0;
    let mut b = [0.0; M];
    for k in 0..M {
        let pivot_row = largest_below(&a, k);
        if pivot_row != k {
            a.swap(k, pivot_row);
            product = -product;
        }
        if a[k][k] == 0.0 {
            return 0.0;
        }
        product *= a[k][k];
        eliminate_below(&mut a, &mut b, k);
    }
    product
}

/// The Jacobian `df/dx` of `f: R^D -> R^R` at `x` by central differences,
/// with the step `eps^(1/3) max(1, |x_j|)` (error of order `eps^(2/3)`
/// relative: about 4e-11 for smooth `f`).
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

#[cfg(test)]
mod tests {
    use super::solve;

    #[test]
    fn a_hand_solved_system_needing_a_row_swap() {
        // a_00 = 0 forces a swap at the first step; solved by hand:
        // 0 x + 2 y + 1 z = 7, 1 x + 1 y + 1 z = 6, 2 x + 1 y - 1 z = 1  =>  (1, 2, 3)
        let a = [[0.0, 2.0, 1.0], [1.0, 1.0, 1.0], [2.0, 1.0, -1.0]];
        let x = solve(a, [7.0, 6.0, 1.0]);
        assert_eq!(x, [1.0, 2.0, 3.0]);
    }

    #[test]
    fn partial_pivoting_keeps_a_tiny_pivot_accurate() {
        // [[eps, 1], [1, 1]] x = [1, 2]: x = (1/(1-eps), (1-2 eps)/(1-eps)).
        let eps = 1e-20;
        let x = solve([[eps, 1.0], [1.0, 1.0]], [1.0, 2.0]);
        assert!((x[0] - 1.0).abs() <= 1e-15, "{x:?}");
        assert!((x[1] - 1.0).abs() <= 1e-15, "{x:?}");
    }

    #[test]
    fn a_saddle_point_system_with_a_zero_block() {
        // [[2, 0, 1], [0, 4, 1], [1, 1, 0]] [a; b; m] = [0, 0, 3]:
        // 2a = -m, 4b = -m, a + b = 3  =>  m = -4, a = 2, b = 1.
        let a = [[2.0, 0.0, 1.0], [0.0, 4.0, 1.0], [1.0, 1.0, 0.0]];
        assert_eq!(solve(a, [0.0, 0.0, 3.0]), [2.0, 1.0, -4.0]);
    }

    #[test]
    fn singular_systems_give_nan_not_panics() {
        let x = solve(
            [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]],
            [1.0; 3],
        );
        assert!(x.iter().all(|v| v.is_nan()), "{x:?}");
        assert!(solve([[0.0]], [1.0])[0].is_nan());
        assert_eq!(solve::<0>([], []), [0.0; 0]);
    }

    #[test]
    fn non_finite_entries_propagate() {
        let x = solve([[f64::NAN, 1.0], [1.0, 1.0]], [1.0, 2.0]);
        assert!(x.iter().any(|v| !v.is_finite()), "{x:?}");
        let x = solve([[1.0, 0.0], [0.0, 1.0]], [f64::INFINITY, 1.0]);
        // 0 * inf = NaN in the elimination: the whole solution is non-finite.
        assert!(x.iter().all(|v| !v.is_finite()), "{x:?}");
        let x = solve([[f64::NAN; 2]; 2], [1.0, 1.0]);
        assert!(x.iter().all(|v| v.is_nan()), "{x:?}");
    }
}
