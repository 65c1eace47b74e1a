//! The Jacobians of the momentum equation and of the reconstruction in
//! their arguments `(r, rdot, p)`, what forward sensitivities of a gait
//! integrate (Koon & Marsden 1.1-1.2; MATH.md section 4).
//!
//! `pdot = f(r, rdot, p)` is a normal form, so `df/d(r, rdot, p)` is its
//! exact derivatives. The reconstruction is emitted as
//! `xi = -(N rdot) / d + v(r, p)` (the connection by Cramer's rule, 4.2, and
//! the vertical part `v = e^T I^-1 p`), so its Jacobian is kept in the same
//! form, `P / d^2 + V` with polynomial `P`:
//!
//! ```text
//! dxi/dr_j    = (-(d(N rdot)/dr_j) d + (N rdot) dd/dr_j) / d^2 + dv/dr_j
//! dxi/drdot_k = -N_k d / d^2
//! dxi/dp_m    = dv/dp_m
//! ```

use super::ConnectionQuotient;
use crate::sym::{Context, Matrix, MatrixError, RationalFunction, SymbolId};

/// The Jacobians, columns `(r, rdot, p)`.
#[derive(Clone, Debug)]
pub struct Sensitivity {
    /// `d pdot / d(r, rdot, p)`, mp x (2 nr + mp).
    pub momentum: Matrix,
    /// `P`: the reconstruction's Jacobian is `P / d^2 + V`, dg x (2 nr + mp).
    pub quotient: Matrix,
    /// `V`.
    pub vertical: Matrix,
}

/// The symbols of `(r, rdot, p)` and the pieces of the momentum form.
pub struct Pieces<'a> {
    /// `r`, `rdot`, `p`, in that order.
    pub arguments: Vec<SymbolId>,
    /// The shape coordinates' count.
    pub shape: usize,
    /// `pdot`.
    pub rhs: &'a [RationalFunction],
    /// `N / d`, with `dd/dr`.
    pub quotient: &'a ConnectionQuotient,
    /// `v`, dg entries.
    pub vertical: &'a [RationalFunction],
}

/// The Jacobians of `pieces`.
pub fn sensitivity(cx: &mut Context, pieces: &Pieces<'_>) -> Result<Sensitivity, MatrixError> {
    let arguments = &pieces.arguments;
    let nr = pieces.shape;
    let momentum = cx.jacobian(pieces.rhs, arguments)?;
    let vertical = cx.jacobian(pieces.vertical, arguments)?;
    let atoms = cx.atoms().clone();
    let rates: Vec<RationalFunction> = arguments[nr..2 * nr]
        .iter()
        .map(|&s| RationalFunction::from_poly(crate::sym::Poly::atom(cx.symbol_atom(s))))
        .collect();
    let rate_column = Matrix::new(nr, 1, rates)?;
    let numerators = &pieces.quotient.numerators;
    let horizontal = numerators.mul(&rate_column, &atoms)?;
    let (d, divisor_gradient) = (
        &pieces.quotient.denominator,
        &pieces.quotient.divisor_gradient,
    );
    let horizontal_gradient = cx.jacobian(horizontal.entries(), &arguments[..nr])?;
    let dg = numerators.rows();
    let mut quotient = Matrix::zeros(dg, arguments.len());
    for i in 0..dg {
        let h = horizontal.get(i, 0);
        for (j, divisor_slope) in divisor_gradient.iter().enumerate() {
            let by_shape = horizontal_gradient
                .get(i, j)
                .mul(d, &atoms)
                .neg()
                .add(&h.mul(divisor_slope, &atoms), &atoms);
            quotient.set(i, j, by_shape);
            quotient.set(i, nr + j, numerators.get(i, j).mul(d, &atoms).neg());
        }
    }
    Ok(Sensitivity {
        momentum,
        quotient,
        vertical,
    })
}
