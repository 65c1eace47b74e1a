//! The values of a mechanism's sections: evaluated in its space of frames
//! and points, depending on the configuration only; and the linear forms in
//! the velocities that contacts and holonomic constraints contribute.

use super::super::context::Context;
use super::super::velocities::first_velocity_span;
use crate::model::lower::Lowerer;
use crate::model::mechanism::evaluate::{Evaluator, Reference};
use crate::model::mechanism::space::Space;
use crate::sym::{ExprId, RationalFunction, SymError, SymbolId, SymbolKind};
use crate::syntax::Expr;

/// A row linear in the velocities: the normal form of each velocity's
/// coefficient, in coordinate order, and the expression it was derived as.
pub(in crate::model::check) type Row = (Vec<RationalFunction>, ExprId);

/// An evaluator of scalars, vectors and points in `space`.
pub(in crate::model::check) fn evaluator<'a>(
    cx: &'a mut Context,
    space: &'a Space,
    reference: &'a Reference,
) -> Evaluator<'a> {
    Evaluator {
        lowerer: Lowerer {
            cx: &mut cx.sym,
            scope: &cx.scope,
            diagnostics: &mut cx.diagnostics,
        },
        space,
        reference,
    }
}

/// Values in mechanism sections depend on the configuration only.
pub(in crate::model::check) fn check_configuration_only(
    cx: &mut Context,
    values: &[ExprId],
    expr: &Expr,
    what: &str,
) -> bool {
    let has_velocity = values.iter().any(|&id| {
        cx.sym
            .free_symbols(id)
            .iter()
            .any(|&s| matches!(cx.sym.symbol_info(s).kind, SymbolKind::Velocity(_)))
    });
    if has_velocity {
        let span = first_velocity_span(expr).unwrap_or_else(|| expr.first_span());
        cx.diagnostics.error(
            span,
            format!("{what} depends on the configuration only: no velocities"),
        );
    }
    !has_velocity
}

/// The normal forms of `df/dq_j`, the coefficients of `df/dt`: `f`'s
/// normal form differentiated exactly, one derivative per coordinate. For
/// the benchmark bicycle's front contact height (a square root) this takes
/// a fiftieth of normalizing each coefficient of `df/dt` on its DAG.
pub(super) fn gradient_coefficients(
    cx: &mut Context,
    f: ExprId,
    q: &[SymbolId],
) -> Result<Vec<RationalFunction>, SymError> {
    let form = cx.sym.normal(f)?;
    q.iter()
        .map(|&coordinate| cx.sym.derivative_of_normal(&form, coordinate))
        .collect()
}

/// The normal forms of the coefficients of `form`, linear in the
/// velocities of `q`: `d form / d qdot_j` taken on its DAG, then each in
/// normal form (the whole row's normal form, a rolling wheel's square
/// root in every term, is never formed).
pub(super) fn linear_coefficients(
    cx: &mut Context,
    form: ExprId,
    q: &[SymbolId],
) -> Result<Vec<RationalFunction>, SymError> {
    q.iter()
        .map(|&coordinate| {
            let velocity = cx.sym.velocity_of(coordinate);
            let coefficient = cx.sym.derivative(form, velocity);
            cx.sym.normal(coefficient)
        })
        .collect()
}
