//! The runtime's linear algebra against hand-solved systems and matrices
//! whose eigenvalues are known: companion matrices of chosen polynomials
//! (their eigenvalues are the roots), rotations (`e^{+-i theta}`), a
//! non-normal triangular block hidden by an orthogonal similarity; and, for
//! random matrices, the power sums `sum_i lambda_i^k = trace(A^k)`, which
//! fix the characteristic polynomial (Newton's identities).

use chaplygin_runtime::arrays::{matrix_from_rows, rows_of};
use chaplygin_runtime::linalg::{
    MatrixError, SMatrix, eigenvalues, solve, solve_positive_definite,
};
use chaplygin_runtime::nalgebra::{Complex, DMatrix};
use proptest::prelude::*;

#[test]
fn a_hand_solved_system_needing_a_row_swap() {
    // a_00 = 0 forces a swap at the first step; solved by hand:
    // 0 x + 2 y + 1 z = 7, 1 x + 1 y + 1 z = 6, 2 x + 1 y - 1 z = 1  =>  (1, 2, 3)
    let a = [[0.0, 2.0, 1.0], [1.0, 1.0, 1.0], [2.0, 1.0, -1.0]];
    let x = solve(&a, &[7.0, 6.0, 1.0]).unwrap();
    for (found, wanted) in x.iter().zip([1.0, 2.0, 3.0]) {
        assert!((found - wanted).abs() < 1e-15, "{x:?}");
    }
}

#[test]
fn partial_pivoting_keeps_a_tiny_pivot_accurate() {
    // [[eps, 1], [1, 1]] x = [1, 2]: x = (1/(1-eps), (1-2 eps)/(1-eps)).
    let x = solve(&[[1e-20, 1.0], [1.0, 1.0]], &[1.0, 2.0]).unwrap();
    assert!(
        (x[0] - 1.0).abs() <= 1e-15 && (x[1] - 1.0).abs() <= 1e-15,
        "{x:?}"
    );
}

#[test]
fn a_saddle_point_system_with_a_zero_block() {
    // [[2, 0, 1], [0, 4, 1], [1, 1, 0]] [a; b; m] = [0, 0, 3]:
    // 2a = -m, 4b = -m, a + b = 3  =>  m = -4, a = 2, b = 1.
    let a = [[2.0, 0.0, 1.0], [0.0, 4.0, 1.0], [1.0, 1.0, 0.0]];
    let x = solve(&a, &[0.0, 0.0, 3.0]).unwrap();
    for (found, wanted) in x.iter().zip([2.0, 1.0, -4.0]) {
        assert!((found - wanted).abs() < 1e-14, "{x:?}");
    }
}

#[test]
fn singular_and_indefinite_matrices_are_errors_not_nan() {
    let dependent = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]];
    assert_eq!(
        solve(&dependent, &[1.0; 3]),
        Err(MatrixError::Singular { order: 3 })
    );
    assert_eq!(
        solve(&[[0.0]], &[1.0]),
        Err(MatrixError::Singular { order: 1 })
    );
    // eigenvalues 3 and -1: symmetric but indefinite
    let indefinite = [[1.0, 2.0], [2.0, 1.0]];
    assert_eq!(
        solve_positive_definite(&indefinite, &[1.0, 0.0]),
        Err(MatrixError::NotPositiveDefinite { order: 2 })
    );
    // positive semi-definite, singular
    assert_eq!(
        solve_positive_definite(&[[1.0, 1.0], [1.0, 1.0]], &[1.0, 0.0]),
        Err(MatrixError::NotPositiveDefinite { order: 2 })
    );
    assert_eq!(
        solve_positive_definite(&[[f64::NAN]], &[1.0]),
        Err(MatrixError::NotPositiveDefinite { order: 1 })
    );
    assert!(
        MatrixError::Singular { order: 3 }
            .to_string()
            .contains("3 x 3 matrix is singular")
    );
}

#[test]
fn cholesky_solves_a_mass_matrix_system() {
    // The mass matrix of a point mass m = 2 with a pendulum of length 1/2 at
    // angle 0 over (x, angle): [[m, m l], [m l, m l^2 + 1/4]] = [[2, 1], [1, 3/4]].
    // Solved by hand: 2 a + b = 3, a + 3/4 b = 2  =>  b = 2, a = 1/2.
    let x = solve_positive_definite(&[[2.0, 1.0], [1.0, 0.75]], &[3.0, 2.0]).unwrap();
    assert!(
        (x[0] - 0.5).abs() < 1e-15 && (x[1] - 2.0).abs() < 1e-15,
        "{x:?}"
    );
    let by_lu = solve(&[[2.0, 1.0], [1.0, 0.75]], &[3.0, 2.0]).unwrap();
    assert!((by_lu[0] - x[0]).abs() < 1e-15 && (by_lu[1] - x[1]).abs() < 1e-15);
}

#[test]
fn rows_and_columns_are_not_swapped() {
    let rows = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]];
    let m = matrix_from_rows(&rows);
    assert_eq!((m[(0, 2)], m[(1, 0)]), (3.0, 4.0));
    assert_eq!(rows_of(&m), rows);
    // nalgebra's own From reads the inner arrays as columns: the pitfall.
    let columns: SMatrix<f64, 3, 2> = SMatrix::from(rows);
    assert_eq!(columns, m.transpose());
}

/// The companion matrix of the monic polynomial with these roots (real,
/// or in conjugate pairs): ones below the diagonal, the last column
/// `-c_0, ..., -c_{n-1}` for `x^n + c_{n-1} x^{n-1} + ... + c_0`.
fn companion<const N: usize>(roots: [Complex<f64>; N]) -> SMatrix<f64, N, N> {
    let mut coefficients = vec![Complex::new(1.0, 0.0)]; // highest power first
    for root in roots {
        let mut next = coefficients.clone();
        next.push(Complex::new(0.0, 0.0));
        for (i, c) in coefficients.iter().enumerate() {
            next[i + 1] -= root * c;
        }
        coefficients = next;
    }
    SMatrix::from_fn(|i, j| {
        if j == N - 1 {
            let c = coefficients[N - i];
            assert!(c.im.abs() < 1e-12, "real coefficients");
            -c.re
        } else if i == j + 1 {
            1.0
        } else {
            0.0
        }
    })
}

fn real(re: f64) -> Complex<f64> {
    Complex::new(re, 0.0)
}

fn assert_close<const N: usize>(
    found: &chaplygin_runtime::nalgebra::SVector<Complex<f64>, N>,
    wanted: [Complex<f64>; N],
    tolerance: f64,
) {
    for (f, w) in found.iter().zip(wanted) {
        assert!((f - w).norm() <= tolerance, "{found:?} against {wanted:?}");
    }
}

#[test]
fn companion_matrices_have_their_polynomials_roots() {
    let roots = [real(3.0), real(2.0), real(1.0), real(-0.5)];
    assert_close(&eigenvalues(companion(roots)).unwrap(), roots, 1e-12);
    // (x - 2)(x^2 - 2x + 5)(x^2 + 1): 2, 1 +- 2i, +-i, in the documented order.
    let roots = [
        real(2.0),
        Complex::new(1.0, 2.0),
        Complex::new(1.0, -2.0),
        Complex::new(0.0, 1.0),
        Complex::new(0.0, -1.0),
    ];
    let found = eigenvalues(companion(roots)).unwrap();
    assert_close(&found, roots, 1e-12);
    // each pair is conjugate to the last bit
    assert_eq!(found[2], found[1].conj());
    assert_eq!(found[4], found[3].conj());
}

#[test]
fn a_rotation_has_eigenvalues_on_the_unit_circle() {
    // Rodrigues: R = I + sin(t) K + (1 - cos(t)) K^2 about the unit axis (1, 2, 2)/3.
    let t: f64 = 0.7;
    let (s, c) = t.sin_cos();
    let k = SMatrix::<f64, 3, 3>::new(
        0.0, -2.0, 2.0, //
        2.0, 0.0, -1.0, //
        -2.0, 1.0, 0.0,
    ) / 3.0;
    let rotation = SMatrix::identity() + k * s + k * k * (1.0 - c);
    let found = eigenvalues(rotation).unwrap();
    assert_close(
        &found,
        [real(1.0), Complex::new(c, s), Complex::new(c, -s)],
        1e-14,
    );
}

#[test]
fn a_non_normal_block_keeps_its_diagonal() {
    // T upper triangular with large couplings, hidden by an orthogonal Q:
    // the eigenvalues of Q T Q^T are the diagonal of T.
    let t = SMatrix::<f64, 3, 3>::new(
        1.0, 50.0, 0.0, //
        0.0, 2.0, 50.0, //
        0.0, 0.0, -1.0,
    );
    let (s, c) = 0.3f64.sin_cos();
    let turn = SMatrix::<f64, 3, 3>::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
    let tilt = SMatrix::<f64, 3, 3>::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c);
    let q = turn * tilt;
    let found = eigenvalues(q * t * q.transpose()).unwrap();
    assert_close(&found, [real(2.0), real(1.0), real(-1.0)], 1e-9);
}

#[test]
fn eigenvalues_of_any_size_and_of_bad_input() {
    let dynamic = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, 0.0]);
    let found = eigenvalues(dynamic).unwrap();
    assert_eq!(
        found.as_slice(),
        [Complex::new(0.0, 2.0), Complex::new(0.0, -2.0)]
    );
    let mut bad = SMatrix::<f64, 3, 3>::identity();
    bad[(2, 1)] = f64::NAN;
    assert_eq!(
        eigenvalues(bad),
        Err(MatrixError::NonFinite {
            order: 3,
            row: 2,
            column: 1
        })
    );
    assert_eq!(eigenvalues(DMatrix::<f64>::zeros(0, 0)).unwrap().len(), 0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// `sum_i lambda_i^k = trace(A^k)` for `k = 1..6` determines the six
    /// eigenvalues; complex ones come in adjacent conjugate pairs.
    #[test]
    fn power_sums_are_traces_of_powers(entries in prop::collection::vec(-1.0f64..1.0, 36)) {
        let a = SMatrix::<f64, 6, 6>::from_row_slice(&entries);
        let lambda = eigenvalues(a).unwrap();
        let scale = a.norm().max(1.0);
        let mut power = SMatrix::<f64, 6, 6>::identity();
        for k in 1..=6 {
            power *= a;
            let sum: Complex<f64> = lambda.iter().map(|l| l.powi(k)).sum();
            let tolerance = 1e-11 * scale.powi(k);
            prop_assert!((sum.re - power.trace()).abs() <= tolerance, "k = {k}: {sum} against {}", power.trace());
            prop_assert!(sum.im.abs() <= tolerance, "k = {k}: {sum}");
        }
        let mut i = 0;
        while i < 6 {
            if lambda[i].im == 0.0 {
                i += 1;
            } else {
                prop_assert!(lambda[i].im > 0.0);
                prop_assert_eq!(lambda[i + 1], lambda[i].conj());
                i += 2;
            }
        }
    }
}

proptest! {
    /// A chart's elimination in order against its definition: the least
    /// ratio of the leading minors `|det A[..i, r[..i]]| / prod_(j<i) |A_j|`,
    /// each minor's determinant taken by nalgebra's LU with pivoting.
    #[test]
    fn the_elimination_ratio_is_the_least_leading_minor_ratio(
        entries in proptest::collection::vec(-1.0f64..1.0, 12),
        order in Just(vec![2usize, 0, 3]).prop_shuffle(),
    ) {
        use chaplygin_runtime::monitor::elimination_ratio;
        let a = DMatrix::from_row_slice(3, 4, &entries);
        let mut scale = 1.0;
        let mut least = f64::INFINITY;
        for i in 1..=3 {
            scale *= a.row(i - 1).norm();
            let minor = DMatrix::from_fn(i, i, |row, k| a[(row, order[k])]);
            least = least.min(minor.determinant().abs() / scale);
        }
        let found = elimination_ratio(&a, &order);
        prop_assert!((found - least).abs() <= 1e-12 * (1.0 + least), "{found} against {least}");
    }
}
