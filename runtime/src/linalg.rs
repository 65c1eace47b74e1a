//! Dense linear algebra on the stack, for generated code.
//!
//! [`solve`] is Gaussian elimination with partial pivoting (Golub & Van Loan,
//! *Matrix Computations*, algorithm 3.4.1) on a fixed-size system: no heap,
//! no panics, `O(M^3)` operations (`M^3/3` multiply-adds to leading order).
//! [`solve_in_place`] is the same elimination on slices, for systems whose
//! size is known only at run time.

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
    match solve_in_place(a.as_flattened_mut(), &mut b) {
        Ok(()) => b,
        Err(_) => [f64::NAN; M],
    }
}

/// The matrix of [`solve_in_place`] does not have `rows * rows` entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "a right-hand side of {rows} entries needs a {rows} x {rows} matrix, found {found} entries"
)]
pub struct SizeMismatch {
    /// The length of the right-hand side.
    pub rows: usize,
    /// The number of matrix entries given.
    pub found: usize,
}

/// [`solve`] on slices: `a` is the `m x m` matrix in row-major order and
/// `b`, of length `m`, becomes the solution `x` (all NaN when `a` is
/// singular). The same operations in the same order as [`solve`], which
/// calls it, so both give bit-identical results; `a` is overwritten by the
/// elimination.
///
/// ```
/// use chaplygin_runtime::linalg::solve_in_place;
/// let mut b = [5.0, 10.0];
/// solve_in_place(&mut [2.0, 1.0, 1.0, 3.0], &mut b).unwrap();
/// assert!((b[0] - 1.0).abs() < 1e-15 && (b[1] - 3.0).abs() < 1e-15);
/// assert!(solve_in_place(&mut [1.0; 3], &mut b).is_err());
/// ```
pub fn solve_in_place(a: &mut [f64], b: &mut [f64]) -> Result<(), SizeMismatch> {
    let m = b.len();
    if m.checked_mul(m) != Some(a.len()) {
        return Err(SizeMismatch {
            rows: m,
            found: a.len(),
        });
    }
    for k in 0..m {
        let pivot_row = largest_below(a, m, k);
        swap_rows(a, m, k, pivot_row);
        b.swap(k, pivot_row);
        if a[k * m + k] == 0.0 {
            b.fill(f64::NAN);
            return Ok(());
        }
        eliminate_below(a, Some(b), m, k);
    }
    back_substitute(a, b, m);
    Ok(())
}

/// The row `i >= k` with the largest `|a_ik|` (the first on ties; NaNs
/// compare as not larger).
fn largest_below(a: &[f64], m: usize, k: usize) -> usize {
    let mut best = k;
    for i in k + 1..m {
        if a[i * m + k].abs() > a[best * m + k].abs() {
            best = i;
        }
    }
    best
}

fn swap_rows(a: &mut [f64], m: usize, first: usize, second: usize) {
    if first != second {
        for j in 0..m {
            a.swap(first * m + j, second * m + j);
        }
    }
}

/// Subtracts multiples of row `k` from the rows below so that column `k`
/// vanishes under the pivot, and the same multiples of `b[k]` from the
/// entries of `b` below (when there is a right-hand side).
fn eliminate_below(a: &mut [f64], mut b: Option<&mut [f64]>, m: usize, k: usize) {
    let (upper, lower) = a.split_at_mut((k + 1) * m);
    let pivot_row = &upper[k * m..];
    for (offset, row) in lower.chunks_exact_mut(m).enumerate() {
        let factor = row[k] / pivot_row[k];
        for (entry, pivot_entry) in row.iter_mut().zip(pivot_row).skip(k + 1) {
            *entry -= factor * pivot_entry;
        }
        if let Some(b) = b.as_deref_mut() {
            b[k + 1 + offset] -= factor * b[k];
        }
    }
}

/// Solves the upper triangular system in place: `b` becomes `x`.
fn back_substitute(a: &[f64], b: &mut [f64], m: usize) {
    for i in (0..m).rev() {
        let row = &a[i * m..(i + 1) * m];
        let (head, solved) = b.split_at_mut(i + 1);
        let reduced = row
            .iter()
            .skip(i + 1)
            .zip(solved.iter())
            .fold(head[i], |rest, (entry, x)| rest - entry * x);
        head[i] = reduced / row[i];
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
    determinant_in_place(a.as_flattened_mut(), M)
}

/// [`determinant`] on slices: `a` is the `m x m` matrix in row-major order
/// (overwritten by the elimination); NaN when it does not have `m * m`
/// entries.
///
/// ```
/// use chaplygin_runtime::linalg::determinant_in_place;
/// assert_eq!(determinant_in_place(&mut [0.0, 2.0, 3.0, 1.0], 2), -6.0);
/// assert!(determinant_in_place(&mut [1.0; 3], 2).is_nan());
/// ```
pub fn determinant_in_place(a: &mut [f64], m: usize) -> f64 {
    if m.checked_mul(m) != Some(a.len()) {
        return f64::NAN;
    }
    let mut product = 1.0;
    for k in 0..m {
        let pivot_row = largest_below(a, m, k);
        if pivot_row != k {
            swap_rows(a, m, k, pivot_row);
            product = -product;
        }
        if a[k * m + k] == 0.0 {
            return 0.0;
        }
        product *= a[k * m + k];
        eliminate_below(a, None, m, k);
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
    use super::{SizeMismatch, solve, solve_in_place};

    #[test]
    fn slices_of_the_wrong_size_are_an_error() {
        let mut b = [1.0, 2.0];
        assert_eq!(
            solve_in_place(&mut [1.0, 0.0, 0.0], &mut b),
            Err(SizeMismatch { rows: 2, found: 3 })
        );
        assert_eq!(b, [1.0, 2.0]);
        // The hand-solved system of the next test, on slices.
        let mut a = [0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, -1.0];
        let mut b = [7.0, 6.0, 1.0];
        solve_in_place(&mut a, &mut b).unwrap();
        assert_eq!(b, [1.0, 2.0, 3.0]);
    }

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
