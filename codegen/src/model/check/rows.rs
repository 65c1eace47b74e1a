//! Independent rows: of the constraint matrix, of a distribution's vector
//! fields, of a momentum basis.

use super::context::Context;
use crate::model::Declared;
use crate::sym::Matrix;

/// The term products the exact rank confirming a dependent row may take.
const EXACT_RANK_PRODUCTS: u64 = 2_000_000;

/// Rows of A (or of a distribution, or of a momentum basis) are
/// independent: each row adds rank.
pub(super) fn check_independent_rows(
    cx: &mut Context,
    m: &Matrix,
    names: &[Declared],
    what: &str,
) -> bool {
    let Some(dependent) = first_dependent_row(cx, m) else {
        return true;
    };
    dependent_row_error(cx, &names[dependent], what, "");
    false
}

/// The error on a row that depends on the ones before it (`where_` says
/// where, if not everywhere).
pub(super) fn dependent_row_error(cx: &mut Context, row: &Declared, what: &str, where_: &str) {
    cx.diagnostics.error(
        row.span,
        format!(
            "{what} `{}` depends on the ones before it{where_}: the rows must be linearly \
             independent",
            row.name
        ),
    );
}

/// The first row of `m` in the span of the rows before it. Ranks at
/// random points modulo a prime ([`crate::sym::modular`]) prove the
/// rows before it independent; the row they find no rank for is
/// confirmed by the exact rank within [`EXACT_RANK_PRODUCTS`] (beyond it,
/// by two random points: wrong with probability below `1e-15`).
pub(super) fn first_dependent_row(cx: &mut Context, m: &Matrix) -> Option<usize> {
    let proved_full = cx
        .sym
        .prefixes_of_full_rank_at_points(m)
        .unwrap_or_else(|_| vec![false; m.rows()]);
    (0..m.rows()).filter(|&i| !proved_full[i]).find(|&i| {
        let prefix = Matrix::new(
            i + 1,
            m.columns(),
            m.entries()[..(i + 1) * m.columns()].to_vec(),
        );
        let Ok(prefix) = prefix else { return false };
        cx.sym
            .attempt(EXACT_RANK_PRODUCTS, |store| prefix.rank(store.atoms()))
            .is_none_or(|rank| rank < i + 1)
    })
}
