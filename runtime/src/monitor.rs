//! Where a formulation degenerates: scale-free regularity measures that
//! generated models evaluate at every recorded state.
//!
//! - The reduced form `x = (q, alpha)` needs the `c` constraint rows `A(q)`
//!   to be independent and the momentum basis to span the allowed velocities
//!   `D_q = ker A(q)`. With `V(q)` the `n x k` matrix whose columns are the
//!   velocities of unit momenta (`velocities(q, e_j)`), both hold exactly when
//!   the square matrix `[A(q); V(q)^T]` is invertible (`A V = 0`, so the rows
//!   of `A` and the columns of `V` are orthogonal complements when both have
//!   full rank). [`reduced_regularity`] is its determinant over the product
//!   of its rows' norms: at most 1 in magnitude by Hadamard's inequality,
//!   zero where either degenerates, and it changes sign where a
//!   configuration path crosses such a point transversally. The snakeboard's
//!   two wheel constraints become parallel at `phi = +-pi/2` (Duindam &
//!   Stramigioli 2004, section 3: `tan(phi)` in the paper's basis of D).
//! - The momentum form `(q, rdot, p)` reconstructs the velocity from the
//!   shape velocities and the momenta, i.e. it solves the square system
//!   `[A(q); E_r; W(q)] qdot = (0, rdot, p)` with `E_r` the shape
//!   coordinates' unit rows and `W = h g` the momenta's rows
//!   (`p = W qdot`). [`momentum_regularity`] is its Hadamard ratio: zero
//!   where the constraint rows are dependent or the momentum basis
//!   degenerates (a derived basis vector `e_i(r)` vanishing, say), and it
//!   changes sign where a path crosses such a point.
//! - The Lagrange-d'Alembert form needs the multiplier system, with the
//!   Gram matrix `A g^-1 A^T`, to be regular. [`constraint_regularity`] is
//!   its Hadamard ratio `det(A g^-1 A^T) / prod_i (A g^-1 A^T)_ii`, in
//!   `[0, 1]`, zero where the rows of `A` are dependent (up to round-off:
//!   Cholesky of a rank-deficient Gram matrix meets a pivot of round-off
//!   size, or a negative one and then the measure is 0).
//!
//! Both work on nalgebra's matrices of any size, fixed (the generated
//! models, on the stack) or dynamic (models interpreted at run time): the
//! determinant of `[A; V^T]` by LU with partial pivoting, the Gram matrix
//! by Cholesky of the mass matrix `g` (symmetric positive definite), and its
//! determinant by its own Cholesky factor, `det G = prod_i L_ii^2`.

use crate::arrays::matrix_from_rows;
use crate::linalg::{Square, cholesky};
use crate::system::GroupFactor;
use nalgebra::allocator::Allocator;
use nalgebra::storage::Storage;
use nalgebra::{Const, DMatrix, DefaultAllocator, Dim, Matrix, OMatrix};

/// `det[A; V^T] / (prod |A_i| prod |V_j|)` (see the module documentation);
/// `N = C + K`.
///
/// ```
/// use chaplygin_runtime::monitor::reduced_regularity;
/// // The plane with the constraint ydot = 0 and the basis (1, 0) of D: regular.
/// assert_eq!(reduced_regularity(&[[0.0, 1.0]], &[[2.0, 0.0]]), -1.0);
/// // A basis vector outside D: not a basis of D.
/// assert_eq!(reduced_regularity(&[[0.0, 1.0]], &[[0.0, 3.0]]), 0.0);
/// ```
pub fn reduced_regularity<const N: usize, const C: usize, const K: usize>(
    constraints: &[[f64; N]; C],
    basis: &[[f64; N]; K],
) -> f64
where
    Const<N>: Square,
{
    const {
        assert!(
            N == C + K,
            "C constraint rows and K basis vectors make N rows"
        )
    };
    let rows: [[f64; N]; N] =
        core::array::from_fn(|i| if i < C { constraints[i] } else { basis[i - C] });
    hadamard_ratio(matrix_from_rows(&rows))
}

/// The Hadamard ratio of the momentum form's reconstruction
/// `[A; E_r; W]` (see the module documentation), from the linear maps
/// `constraints(e_j) = A e_j` and `momenta(e_j) = W e_j` of each unit
/// velocity and the indices of the shape coordinates; `N = C + R + K`.
///
/// ```
/// use chaplygin_runtime::monitor::momentum_regularity;
/// // The plane with ydot = 0, no shape, the momentum p = 2 xdot: regular.
/// let a = |v: &[f64; 2]| [v[1]];
/// assert_eq!(momentum_regularity(a, |v: &[f64; 2]| [2.0 * v[0]], &[]), -1.0);
/// // A momentum row along the constraint's: degenerate.
/// assert_eq!(momentum_regularity(a, |v: &[f64; 2]| [v[1]], &[]), 0.0);
/// // A momentum row through zero: the measure changes sign.
/// let through = |s: f64| momentum_regularity(a, move |v: &[f64; 2]| [s * v[0]], &[]);
/// assert!(through(-0.1) * through(0.1) < 0.0);
/// ```
pub fn momentum_regularity<const N: usize, const C: usize, const R: usize, const K: usize>(
    constraints: impl Fn(&[f64; N]) -> [f64; C],
    momenta: impl Fn(&[f64; N]) -> [f64; K],
    shape: &[usize; R],
) -> f64
where
    Const<N>: Square,
{
    const {
        assert!(
            N == C + R + K,
            "C constraint rows, R shape rows and K momenta make N rows"
        )
    };
    let unit = |j: usize| -> [f64; N] { core::array::from_fn(|i| f64::from(u8::from(i == j))) };
    let a: [[f64; C]; N] = core::array::from_fn(|j| constraints(&unit(j)));
    let w: [[f64; K]; N] = core::array::from_fn(|j| momenta(&unit(j)));
    let rows: [[f64; N]; N] = core::array::from_fn(|i| {
        core::array::from_fn(|j| match i {
            i if i < C => a[j][i],
            i if i < C + R => f64::from(u8::from(shape[i - C] == j)),
            i => w[j][i - C - R],
        })
    });
    hadamard_ratio(matrix_from_rows(&rows))
}

/// How well a chart of D fits (MATH.md 1.1): with the dependent speeds
/// `dependent` (columns `r` of A), the basis `[I; -A_r^-1 A_s]` is regular
/// where the minor `det A_r` is not zero, and its pivot ratio
/// `|det A_r| / prod_i |A_i|` is in `[0, 1]` (Hadamard's inequality on the
/// rows of `A_r`, each no longer than its row of A). By Cauchy-Binet
/// `sum_r det(A_r)^2 = det(A A^T)`, so where the rows are independent some
/// choice has a ratio bounded away from 0. It is the fit of a chart whose
/// basis is the exact `A_r^-1 A_s`; a basis eliminated in order, row `i`
/// on column `r_i`, fits by [`elimination_ratio`].
///
/// ```
/// use chaplygin_runtime::monitor::pivot_ratio;
/// let theta: f64 = 1.2;
/// let blade = [[-theta.sin(), theta.cos(), 0.0]];
/// assert!((pivot_ratio(&blade, &[1]) - theta.cos()).abs() < 1e-15);
/// assert!((pivot_ratio(&blade, &[0]) - theta.sin()).abs() < 1e-15);
/// ```
pub fn pivot_ratio<const N: usize, const C: usize>(
    constraints: &[[f64; N]; C],
    dependent: &[usize; C],
) -> f64
where
    Const<C>: Square,
{
    signed_pivot_ratio(&matrix_from_rows(constraints), dependent).abs()
}

/// How well Gaussian elimination in order fits: row `i` of `a` pivots on
/// column `dependent[i]`, without row exchanges, so its `i`-th pivot is
/// `M_i / M_(i-1)` with `M_i` the leading minor of the first `i` rows on
/// the first `i` pivot columns. The elimination is regular exactly where
/// every `M_i` is non-zero; the ratio is the least `|M_i| / prod_(j<=i) |A_j|`,
/// in `[0, 1]`, and 0 where a pivot vanishes although `det A_r` does not.
///
/// ```
/// use chaplygin_runtime::monitor::elimination_ratio;
/// use chaplygin_runtime::nalgebra::DMatrix;
/// // det of the minor on columns (1, 0) is -1, but row 0 has no entry in
/// // column 1: elimination in order divides by zero.
/// let rows = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 1.0]);
/// assert_eq!(elimination_ratio(&rows, &[1, 0]), 0.0);
/// assert_eq!(elimination_ratio(&rows, &[0, 1]), 1.0);
/// ```
pub fn elimination_ratio<C, N, S>(a: &Matrix<f64, C, N, S>, dependent: &[usize]) -> f64
where
    C: Square,
    N: Dim,
    S: Storage<f64, C, N>,
    DefaultAllocator: Allocator<C, C> + Allocator<C>,
{
    let mut minor = minor_on(a, dependent);
    let (mut leading, mut scale, mut least) = (1.0_f64, 1.0_f64, 1.0_f64);
    for pivot in 0..dependent.len() {
        scale *= a.row(pivot).norm();
        leading *= minor[(pivot, pivot)];
        let ratio = leading.abs() / scale;
        if ratio.is_nan() || ratio == 0.0 {
            return 0.0;
        }
        least = least.min(ratio);
        for below in pivot + 1..dependent.len() {
            let factor = minor[(below, pivot)] / minor[(pivot, pivot)];
            for column in pivot..dependent.len() {
                minor[(below, column)] -= factor * minor[(pivot, column)];
            }
        }
    }
    least
}

/// [`pivot_ratio`] with its sign, `det A_r / prod_i |A_i|`, for rows `a`
/// of any size (`c x n`, fixed or dynamic; `dependent` has `c` entries):
/// it changes sign where a path crosses the minor's zero set
/// transversally. 0 when a row of `a` vanishes.
///
/// ```
/// use chaplygin_runtime::monitor::signed_pivot_ratio;
/// use chaplygin_runtime::nalgebra::DMatrix;
/// let rows = DMatrix::from_row_slice(2, 3, &[1.0, 2.0, 0.0, 0.0, 1.0, 1.0]);
/// let ratio = signed_pivot_ratio(&rows, &[1, 0]);
/// assert!((ratio - (-1.0 / (5f64.sqrt() * 2f64.sqrt()))).abs() < 1e-15);
/// ```
pub fn signed_pivot_ratio<C, N, S>(a: &Matrix<f64, C, N, S>, dependent: &[usize]) -> f64
where
    C: Square,
    N: Dim,
    S: Storage<f64, C, N>,
    DefaultAllocator: Allocator<C, C> + Allocator<C>,
{
    let scale: f64 = a.row_iter().map(|row| row.norm()).product();
    if scale == 0.0 {
        return 0.0;
    }
    minor_on(a, dependent).determinant() / scale
}

/// The square minor `A_r` of the rows `a` on the columns `dependent`.
fn minor_on<C, N, S>(a: &Matrix<f64, C, N, S>, dependent: &[usize]) -> OMatrix<f64, C, C>
where
    C: Square,
    N: Dim,
    S: Storage<f64, C, N>,
    DefaultAllocator: Allocator<C, C>,
{
    let rows = a.shape_generic().0;
    OMatrix::<f64, C, C>::from_fn_generic(rows, rows, |i, k| a[(i, dependent[k])])
}

/// The configuration `q` carried to the group identity, every group
/// coordinate 0 (MATH.md 4): the rows `A(e, r)` there are the body rows a
/// basis chosen in the body frame is eliminated on, row for row. The rows
/// `A(q) L(q)` at `q` itself are the same only up to a rotation of the rows
/// (the no-slip rows' ground components turn with the heading), which
/// keeps `det A_r` but not the leading minors that elimination in order
/// divides by: at a heading of 90 degrees the bicycle's first leading
/// minor vanishes there and not on the body rows.
///
/// ```
/// use chaplygin_runtime::linearize::GroupFactor;
/// use chaplygin_runtime::monitor::at_group_identity;
/// let q = at_group_identity(&[GroupFactor::Se2 { x: 0, y: 1, theta: 2 }], [1.0, 2.0, 0.7, 0.3]);
/// assert_eq!(q, [0.0, 0.0, 0.0, 0.3]);
/// ```
pub fn at_group_identity<Q: AsMut<[f64]>>(factors: &[GroupFactor], mut q: Q) -> Q {
    let coordinates = q.as_mut();
    for factor in factors {
        match *factor {
            GroupFactor::Se2 { x, y, theta } => {
                for i in [x, y, theta] {
                    coordinates[i] = 0.0;
                }
            }
            GroupFactor::Translation(i) | GroupFactor::Rotation(i) => coordinates[i] = 0.0,
        }
    }
    q
}

/// How well a declared momentum basis fits, in `[0, 1]`: the smaller of
/// its regularity `|det[A; V^T]|` over its rows' norms, which vanishes
/// where the basis loses rank, and of each basis vector's kinetic energy
/// `T(q, V e_j)` relative to its value at the default configuration (or
/// its inverse, whichever is smaller), which vanishes at a pole of the
/// basis, where the normalized measure does not see it (a momentum row
/// `m (1, tan(theta), 0)`: the velocity of a unit momentum shrinks like
/// `cos(theta)` while its direction stays regular). `energies` and
/// `defaults` are those energies now and at the defaults; a default that is
/// not positive and finite is left out.
///
/// ```
/// use chaplygin_runtime::monitor::declared_basis_fit;
/// assert_eq!(declared_basis_fit(0.8, &[0.5, 2.0], &[1.0, 1.0]), 0.5);
/// assert_eq!(declared_basis_fit(0.3, &[1.0, 1.0], &[1.0, 1.0]), 0.3);
/// let theta: f64 = 1.55; // near the pole of tan(theta)
/// let fit = declared_basis_fit(0.9, &[theta.cos().powi(2), 1.0], &[1.0, 1.0]);
/// assert!(fit < 1e-3);
/// ```
pub fn declared_basis_fit(regularity: f64, energies: &[f64], defaults: &[f64]) -> f64 {
    energies
        .iter()
        .zip(defaults)
        .filter(|(_, default)| default.is_finite() && **default > 0.0)
        .map(|(energy, default)| {
            let ratio = energy / default;
            match ratio.is_finite() && ratio > 0.0 {
                true => ratio.min(1.0 / ratio),
                false => 0.0,
            }
        })
        .fold(regularity.abs(), f64::min)
}

/// Rows whose Gram ratio ([`gram_ratio`]) is below this are named as
/// dependent where a run stops ([`dependent_rows`]).
pub const DEPENDENT_ROWS: f64 = 1e-4;

/// The rows of `a` (`c x n`) taking part in a dependency among them, where
/// their Gram ratio is below [`DEPENDENT_ROWS`] (none otherwise): the rows
/// with a weight of at least a tenth of the largest in the null vector of
/// the normalized rows' Gram matrix (its eigenvector of the smallest
/// eigenvalue).
///
/// ```
/// use chaplygin_runtime::monitor::dependent_rows;
/// use chaplygin_runtime::nalgebra::DMatrix;
/// // The snakeboard's wheel rows at phi = pi/2: (-cos, -sin, 0) and (cos, sin, 0).
/// let rows = DMatrix::from_row_slice(3, 3, &[-1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0]);
/// assert_eq!(dependent_rows(&rows), vec![0, 2]);
/// let regular = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
/// assert!(dependent_rows(&regular).is_empty());
/// ```
pub fn dependent_rows(a: &DMatrix<f64>) -> Vec<usize> {
    if a.nrows() == 0 || gram_ratio(a) >= DEPENDENT_ROWS {
        return Vec::new();
    }
    let mut normalized = a.clone();
    for mut row in normalized.row_iter_mut() {
        let norm = row.norm();
        if norm > 0.0 {
            row /= norm;
        }
    }
    let eigen = (&normalized * normalized.transpose()).symmetric_eigen();
    let smallest = eigen.eigenvalues.imin();
    let null = eigen.eigenvectors.column(smallest);
    let largest = null.amax();
    (0..a.nrows())
        .filter(|&i| null[i].abs() >= 0.1 * largest)
        .collect()
}

/// A pivot below this fraction of A's largest entry counts as vanishing
/// ([`partial_pivots`]).
pub const VANISHING_PIVOT: f64 = 1e-9;

/// The dependent speeds Gaussian elimination with partial pivoting picks
/// on the rows `a` (`c x n`): row by row, the remaining column of largest
/// magnitude, written into `pivots` (`c` entries). It is the choice of
/// coordinate partitioning (Wehage & Haug 1982) and fits well wherever the
/// rows are independent. `false` when a pivot vanishes (below
/// [`VANISHING_PIVOT`] times the largest entry): the rows are dependent.
///
/// ```
/// use chaplygin_runtime::monitor::partial_pivots;
/// use chaplygin_runtime::nalgebra::DMatrix;
/// let blade = DMatrix::from_row_slice(1, 3, &[-0.9, 0.1, 0.0]);
/// let mut pivots = [0];
/// assert!(partial_pivots(&blade, &mut pivots));
/// assert_eq!(pivots, [0]);
/// let parallel = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 2.0, 2.0]);
/// assert!(!partial_pivots(&parallel, &mut [0, 0]));
/// ```
pub fn partial_pivots<C, N, S>(a: &Matrix<f64, C, N, S>, pivots: &mut [usize]) -> bool
where
    C: Dim,
    N: Dim,
    S: Storage<f64, C, N>,
    DefaultAllocator: Allocator<C, N>,
{
    let mut m = a.clone_owned();
    let (rows, columns) = m.shape();
    let scale = m.amax();
    for row in 0..rows {
        let chosen = &pivots[..row];
        let Some(column) = (0..columns)
            .filter(|j| !chosen.contains(j))
            .max_by(|&x, &y| m[(row, x)].abs().total_cmp(&m[(row, y)].abs()))
        else {
            return false;
        };
        let pivot = m[(row, column)];
        if pivot.abs() <= VANISHING_PIVOT * scale || pivot.is_nan() {
            return false;
        }
        for below in row + 1..rows {
            let factor = m[(below, column)] / pivot;
            for j in 0..columns {
                m[(below, j)] -= factor * m[(row, j)];
            }
        }
        pivots[row] = column;
    }
    true
}

/// How far the rows `a` (`c x n`) are from dependent: the Gram ratio
/// `det(A A^T) / prod_i |A_i|^2`, in `[0, 1]` (Hadamard), zero exactly
/// where they are dependent (up to round-off) and 0 when a row vanishes.
///
/// ```
/// use chaplygin_runtime::monitor::gram_ratio;
/// use chaplygin_runtime::nalgebra::DMatrix;
/// let orthogonal = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, 0.0, 0.0, 3.0, 0.0]);
/// assert_eq!(gram_ratio(&orthogonal), 1.0);
/// let parallel = DMatrix::from_row_slice(2, 3, &[1.0, 2.0, 0.0, 2.0, 4.0, 0.0]);
/// assert!(gram_ratio(&parallel).abs() < 1e-15);
/// ```
pub fn gram_ratio<C, N, S>(a: &Matrix<f64, C, N, S>) -> f64
where
    C: Square,
    N: Dim,
    S: Storage<f64, C, N>,
    DefaultAllocator: Allocator<C, C> + Allocator<N, C> + Allocator<C>,
{
    let gram = a * a.transpose();
    let scale: f64 = gram.diagonal().iter().product();
    if scale == 0.0 {
        return 0.0;
    }
    gram.determinant() / scale
}

/// `det(m) / prod_i |m_i|`, the determinant over the product of the rows'
/// norms: at most 1 in magnitude (Hadamard's inequality), 0 when a row is
/// zero. [`reduced_regularity`] of the matrix `[A; V^T]`.
pub fn hadamard_ratio<D: Square>(m: OMatrix<f64, D, D>) -> f64
where
    DefaultAllocator: Allocator<D, D> + Allocator<D>,
{
    let scale: f64 = m.row_iter().map(|row| row.norm()).product();
    if scale == 0.0 {
        return 0.0;
    }
    m.determinant() / scale
}

/// `det(A g^-1 A^T) / prod_i (A g^-1 A^T)_ii` for the mass matrix `g` and the
/// constraint rows `A` (see the module documentation); 1 without
/// constraints, 0 when the Gram matrix or `g` itself is not positive
/// definite (the rows of `A` are dependent, or the mass matrix degenerates
/// and with it the whole Lagrange-d'Alembert system).
///
/// ```
/// use chaplygin_runtime::monitor::constraint_regularity;
/// let g = [[1.0, 0.0], [0.0, 1.0]];
/// assert_eq!(constraint_regularity(&g, &[[1.0, 0.0], [0.0, 1.0]]), 1.0);
/// // Dependent rows: zero up to round-off.
/// assert!(constraint_regularity(&g, &[[1.0, 1.0], [2.0, 2.0]]).abs() < 1e-15);
/// // A mass matrix that is not positive definite.
/// assert_eq!(constraint_regularity(&[[1.0, 0.0], [0.0, -1.0]], &[[1.0, 0.0]]), 0.0);
/// ```
pub fn constraint_regularity<const N: usize, const C: usize>(
    mass_matrix: &[[f64; N]; N],
    constraints: &[[f64; N]; C],
) -> f64 {
    gram_regularity(
        matrix_from_rows(mass_matrix),
        &matrix_from_rows(constraints),
    )
}

/// [`constraint_regularity`] on nalgebra matrices of any size: `g` is
/// `n x n`, `a` is `c x n`.
pub fn gram_regularity<N: Dim, C: Dim>(g: OMatrix<f64, N, N>, a: &OMatrix<f64, C, N>) -> f64
where
    DefaultAllocator:
        Allocator<N, N> + Allocator<C, N> + Allocator<N, C> + Allocator<C, C> + Allocator<C>,
{
    let Ok(g) = cholesky(g) else {
        return 0.0;
    };
    let gram = a * g.solve(&a.transpose());
    let diagonal = gram.diagonal();
    match cholesky(gram) {
        Ok(factor) => factor
            .l_dirty()
            .diagonal()
            .zip_map(&diagonal, |l, g| l * l / g)
            .product(),
        Err(_) => 0.0,
    }
}
