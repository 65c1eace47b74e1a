//! The local connection as a quotient of polynomials, and its curvature
//! (Koon & Marsden, section 2; Hatton & Choset, "Geometric motion planning:
//! the local connection, Stokes' theorem, and the importance of coordinate
//! choice", 2011; MATH.md section 4.3).
//!
//! The connection solves a square system `S(r) A(r) = R(r)`: the
//! independent body-frame constraint rows `A_xi A = A_r`, and for a model
//! with momenta the rows `e II A = e M_gr` (no momentum in the horizontal
//! part). By Cramer's rule
//!
//! ```text
//! A = N / d,   N = adj(S) R,   d = det S
//! ```
//!
//! with `N` and `d` polynomials in the shape's atoms, so `A` is finite
//! wherever `S` is regular. (The engine's normal form of the same solve
//! clears sines from its denominators by their conjugates, which adds
//! factors that vanish where `S` is regular: for the three-link snake
//! `a1 = -a2`, a line through its ordinary shapes, where the normal form
//! evaluates `0/0`.) `N - A d = 0` is proved on the normal form.
//!
//! For a principally kinematic model (no momenta: `xi = -A(r) rdot`), the
//! curvature of the connection on the plane of shape coordinates `(r_i,
//! r_j)`, `i < j`, with `A_i` the i-th column of `A`, is
//!
//! ```text
//! F_ij = -(d A_j / d r_i - d A_i / d r_j) + [A_i, A_j]
//!      = (-(d N_j/d r_i - d N_i/d r_j) d + N_j dd/dr_i - N_i dd/dr_j + [N_i, N_j]) / d^2
//! ```
//!
//! with `[., .]` the bracket of the group's algebra ([`super::algebra`]).
//! A loop of signed area `a` around `r` in that plane (counterclockwise
//! positive) moves the body by `exp(F_ij(r) a + O(a^(3/2)))`, and the
//! rotation part exactly by the integral of `F_ij`'s rotation entry over the
//! enclosed area (Stokes: se(2)'s bracket has no rotation part). The
//! numerator is proved equal, on the normal form, to `d^2` times the
//! curvature of the normal-form connection.

use super::algebra::bracket;
use crate::model::GroupFactor;
use crate::sym::{Context, Matrix, MatrixError, RationalFunction, SymbolId};

/// `A = numerators / denominator`, by Cramer's rule.
#[derive(Clone, Debug)]
pub struct ConnectionQuotient {
    /// `N = adj(S) R`, dg x nr.
    pub numerators: Matrix,
    /// `d = det S`.
    pub denominator: RationalFunction,
    /// `dd/dr`: where `d` vanishes the connection is singular, and a loop
    /// kept off that set measures its distance by `d`.
    pub divisor_gradient: Vec<RationalFunction>,
}

/// The curvature of a principally kinematic model's connection,
/// `F_ij = numerators[., plane] / denominator^2`.
#[derive(Clone, Debug)]
pub struct Curvature {
    /// The shape planes `(i, j)`, `i < j` (indices into the shape), in
    /// order: `(0, 1), (0, 2), .., (1, 2), ..`.
    pub planes: Vec<(usize, usize)>,
    /// The numerators, dg x planes.
    pub numerators: Matrix,
}

/// Why the quotient or the curvature failed its proof: a bug.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CurvatureError {
    /// A product or derivative failed.
    #[error(transparent)]
    Matrix(#[from] MatrixError),
    /// `N - A d` or `P - F d^2` is not zero on the normal form.
    #[error("the {0} by Cramer's rule differs from its normal form")]
    Unproved(&'static str),
}

/// The largest group dimension whose system is solved by Cramer's rule
/// (cofactor expansion costs `dg!`); beyond it the quotient is the normal
/// form over 1.
pub const CRAMER_LIMIT: usize = 7;

/// The connection `solution` of `system solution = rhs` as a quotient,
/// proved equal to `solution`, with its divisor's gradient in the shape
/// `coordinates`; beyond [`CRAMER_LIMIT`], `solution / 1`.
pub fn connection_quotient(
    cx: &mut Context,
    (system, rhs): (&Matrix, &Matrix),
    solution: &Matrix,
    coordinates: &[SymbolId],
) -> Result<ConnectionQuotient, CurvatureError> {
    let atoms = cx.atoms().clone();
    let (numerators, denominator) = match system.rows() > CRAMER_LIMIT {
        true => (solution.clone(), RationalFunction::one()),
        false => {
            let (adjugate, denominator) = system.adjugate(&atoms)?;
            let numerators = adjugate.mul(rhs, &atoms)?;
            let scaled = solution.scale(&denominator, &atoms);
            if !numerators.sub(&scaled, &atoms)?.is_zero() {
                return Err(CurvatureError::Unproved("connection"));
            }
            (numerators, denominator)
        }
    };
    let divisor_gradient = cx
        .jacobian(std::slice::from_ref(&denominator), coordinates)?
        .entries()
        .to_vec();
    Ok(ConnectionQuotient {
        numerators,
        denominator,
        divisor_gradient,
    })
}

/// The curvature on every plane of the shape `coordinates` (the symbols
/// of `r`), proved against the normal-form `connection`.
pub fn curvature(
    cx: &mut Context,
    quotient: &ConnectionQuotient,
    connection: &Matrix,
    coordinates: &[SymbolId],
    factors: &[GroupFactor],
) -> Result<Curvature, CurvatureError> {
    let nr = coordinates.len();
    let planes: Vec<(usize, usize)> = (0..nr)
        .flat_map(|i| (i + 1..nr).map(move |j| (i, j)))
        .collect();
    let numerators = form_on_planes(
        cx,
        &quotient.numerators,
        Some(&quotient.denominator),
        coordinates,
        factors,
        &planes,
    )?;
    let exact = form_on_planes(cx, connection, None, coordinates, factors, &planes)?;
    let atoms = cx.atoms().clone();
    let square = quotient.denominator.mul(&quotient.denominator, &atoms);
    if !numerators
        .sub(&exact.scale(&square, &atoms), &atoms)?
        .is_zero()
    {
        return Err(CurvatureError::Unproved("curvature"));
    }
    Ok(Curvature { planes, numerators })
}

/// `-(d C_j/d r_i - d C_i/d r_j) + [C_i, C_j]` for the columns `C` of
/// `columns` on each plane; with a `denominator` `d`, the numerator of the
/// curvature of `C / d` over `d^2`, dg x planes.
fn form_on_planes(
    cx: &mut Context,
    columns: &Matrix,
    denominator: Option<&RationalFunction>,
    coordinates: &[SymbolId],
    factors: &[GroupFactor],
    planes: &[(usize, usize)],
) -> Result<Matrix, CurvatureError> {
    let dg = columns.rows();
    let column = |j: usize| -> Vec<RationalFunction> {
        (0..dg).map(|k| columns.get(k, j).clone()).collect()
    };
    let mut result = Matrix::zeros(dg, planes.len());
    for (plane, &(i, j)) in planes.iter().enumerate() {
        let (ci, cj) = (column(i), column(j));
        let dj_di = cx.jacobian(&cj, &[coordinates[i]])?;
        let di_dj = cx.jacobian(&ci, &[coordinates[j]])?;
        let atoms = cx.atoms().clone();
        let mut entries = dj_di.sub(&di_dj, &atoms)?.neg();
        if let Some(d) = denominator {
            let gradient =
                cx.jacobian(std::slice::from_ref(d), &[coordinates[i], coordinates[j]])?;
            let column = |c: &[RationalFunction]| Matrix::new(dg, 1, c.to_vec());
            entries = entries
                .scale(d, &atoms)
                .add(&column(&cj)?.scale(gradient.get(0, 0), &atoms), &atoms)?
                .sub(&column(&ci)?.scale(gradient.get(0, 1), &atoms), &atoms)?;
        }
        for (k, value) in bracket(&ci, &cj, factors, &atoms).into_iter().enumerate() {
            result.set(k, plane, entries.get(k, 0).add(&value, &atoms));
        }
    }
    Ok(result)
}
