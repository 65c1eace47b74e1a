//! A declared momentum basis: k independent rows spanning g(D).

use super::context::Context;
use super::items::{named_item, row_of_expressions};
use super::rows::check_independent_rows;
use super::velocities::velocity_free;
use crate::model::{Declared, MomentumBasis};
use crate::sym::Matrix;
use crate::syntax;

/// A declared momentum basis: k = n - c independent rows spanning g(D),
/// i.e. `A g^-1 h^T = 0` exactly.
pub(super) fn momentum_basis(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    g: &Matrix,
    a: &Matrix,
    n: usize,
) -> Option<MomentumBasis> {
    let section = section?;
    let list = cx.list(section)?;
    let k = n - a.rows();
    if list.items.len() != k {
        cx.diagnostics.error(
            section.key.span(),
            format!(
                "the momentum basis needs k = n - c = {n} - {} = {k} rows, found {}",
                a.rows(),
                list.items.len()
            ),
        );
        return None;
    }
    let mut names = Vec::new();
    let mut entries = Vec::new();
    for item in &list.items {
        let (declared, _) = named_item(cx, item, "a momentum-basis row")?;
        let row = row_of_expressions(cx, item, n, "a momentum-basis row")?;
        for expr in row {
            entries.push(velocity_free(
                cx,
                expr,
                "a momentum-basis row depends on the configuration only: no velocities",
            )?);
        }
        names.push(declared);
    }
    let h = Matrix::new(k, n, entries).ok()?;
    if !check_independent_rows(cx, &h, &names, "momentum-basis row") {
        return None;
    }
    check_spans_momenta(cx, &h, g, a, &names).then_some(MomentumBasis { names, rows: h })
}

/// Each row of h lies in g(D): the column `A g^-1 h_i^T` is exactly zero.
fn check_spans_momenta(
    cx: &mut Context,
    h: &Matrix,
    g: &Matrix,
    a: &Matrix,
    names: &[Declared],
) -> bool {
    let atoms = cx.sym.atoms().clone();
    let Ok(product) = g
        .inverse(&atoms)
        .and_then(|inverse| a.mul(&inverse, &atoms))
        .and_then(|ag| ag.mul(&h.transpose(), &atoms))
    else {
        return false;
    };
    for (j, name) in names.iter().enumerate() {
        if (0..product.rows()).any(|i| !product.get(i, j).is_zero()) {
            cx.diagnostics.error(
                name.span,
                format!(
                    "momentum-basis row `{}` is not in g(D): the momenta of allowed motions \
                     satisfy A g^-1 h^T = 0, and this row's column is not zero",
                    name.name
                ),
            );
            return false;
        }
    }
    true
}
