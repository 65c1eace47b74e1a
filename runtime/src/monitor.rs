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
use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, Dim, OMatrix};

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
/// choice has a ratio bounded away from 0.
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
) -> f64 {
    let scale: f64 = constraints
        .iter()
        .map(|row| row.iter().map(|v| v * v).sum::<f64>().sqrt())
        .product();
    if scale == 0.0 {
        return 0.0;
    }
    let mut minor: [[f64; C]; C] =
        core::array::from_fn(|i| core::array::from_fn(|k| constraints[i][dependent[k]]));
    let mut determinant = 1.0;
    for k in 0..C {
        let pivot = (k..C)
            .max_by(|&a, &b| minor[a][k].abs().total_cmp(&minor[b][k].abs()))
            .unwrap_or(k);
        if minor[pivot][k] == 0.0 {
            return 0.0;
        }
        minor.swap(k, pivot);
        determinant *= minor[k][k];
        let pivot_row = minor[k];
        for row in minor.iter_mut().skip(k + 1) {
            let factor = row[k] / pivot_row[k];
            for (entry, p) in row.iter_mut().zip(pivot_row).skip(k) {
                *entry -= factor * p;
            }
        }
    }
    determinant.abs() / scale
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
