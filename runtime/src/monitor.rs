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
//! - The Lagrange-d'Alembert form needs the multiplier system, with the
//!   Gram matrix `A g^-1 A^T`, to be regular. [`constraint_regularity`] is
//!   its Hadamard ratio `det(A g^-1 A^T) / prod_i (A g^-1 A^T)_ii`, in
//!   `[0, 1]`, zero exactly where the rows of `A` are dependent.

use crate::linalg::{determinant_in_place, solve};

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
) -> f64 {
    const {
        assert!(
            N == C + K,
            "C constraint rows and K basis vectors make N rows"
        )
    };
    let mut rows: [[f64; N]; N] =
        core::array::from_fn(|i| if i < C { constraints[i] } else { basis[i - C] });
    reduced_regularity_in_place(rows.as_flattened_mut(), N)
}

/// [`reduced_regularity`] on slices: `rows` holds the `n x n` matrix
/// `[A; V^T]` in row-major order (overwritten).
pub fn reduced_regularity_in_place(rows: &mut [f64], n: usize) -> f64 {
    let scale: f64 = rows
        .chunks(n.max(1))
        .map(|row| row.iter().map(|v| v * v).sum::<f64>().sqrt())
        .product();
    if scale == 0.0 {
        return 0.0;
    }
    determinant_in_place(rows, n) / scale
}

/// `det(A g^-1 A^T) / prod_i (A g^-1 A^T)_ii` for the mass matrix `g` and the
/// constraint rows `A` (see the module documentation); 1 without constraints.
///
/// ```
/// use chaplygin_runtime::monitor::constraint_regularity;
/// let g = [[1.0, 0.0], [0.0, 1.0]];
/// assert_eq!(constraint_regularity(&g, &[[1.0, 0.0], [0.0, 1.0]]), 1.0);
/// assert_eq!(constraint_regularity(&g, &[[1.0, 1.0], [2.0, 2.0]]), 0.0);
/// ```
pub fn constraint_regularity<const N: usize, const C: usize>(
    mass_matrix: &[[f64; N]; N],
    constraints: &[[f64; N]; C],
) -> f64 {
    let inverse_rows: [[f64; N]; C] = core::array::from_fn(|i| solve(*mass_matrix, constraints[i]));
    let mut gram: [[f64; C]; C] =
        core::array::from_fn(|i| core::array::from_fn(|j| dot(&constraints[i], &inverse_rows[j])));
    gram_regularity_in_place(gram.as_flattened_mut(), C)
}

/// The Hadamard ratio `det(G) / prod_i G_ii` of the `c x c` Gram matrix `G`
/// in row-major order (overwritten); 1 for `c = 0`.
pub fn gram_regularity_in_place(gram: &mut [f64], c: usize) -> f64 {
    let diagonal: f64 = (0..c).map(|i| gram[i * c + i]).product();
    if diagonal == 0.0 {
        return 0.0;
    }
    determinant_in_place(gram, c) / diagonal
}

fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
