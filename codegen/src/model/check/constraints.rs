//! Constraint rows: declared (linear and homogeneous in the velocities) or
//! the annihilator of a declared distribution, then the mechanism's;
//! independent together.

use super::context::Context;
use super::items::{check_unique_in_section, item_expression, named_item, row_of_expressions};
use super::mechanisms::MechanismParts;
use super::redundant::{Layout, Rows, without_redundant};
use super::rows::check_independent_rows;
use super::section::{Section, Sections};
use super::velocities::{check_velocity_degree, velocity_free};
use crate::model::{Declared, Parameter, Variable};
use crate::sym::{ExprId, Matrix, RationalFunction, SymbolId, SymbolKind};
use crate::syntax::{self, Expr};

/// The constraint rows: the declared rows (or a distribution's
/// annihilator), then the mechanism's contact and holonomic rows; the
/// contact rows the others imply dropped ([`super::redundant`]), the rest
/// independent.
pub(super) fn constraints(
    cx: &mut Context,
    sections: &Sections,
    (coordinates, parameters): (&[Variable], &[Parameter]),
    mechanism: &MechanismParts,
) -> Option<Rows> {
    let n = coordinates.len();
    let (mut names, declared) = declared_constraints(cx, sections, n)?;
    let declared_rows = names.len();
    let mut entries = declared.entries().to_vec();
    let mut expressions: Vec<ExprId> = entries
        .iter()
        .map(|entry| cx.sym.expression_of(entry))
        .collect();
    for (declared, (coefficients, derived_as)) in mechanism.names.iter().zip(&mechanism.rows) {
        if !check_unique_in_section(cx, &names, &declared.name, declared.span) {
            return None;
        }
        expressions.extend(entry_expressions(cx, coefficients, *derived_as));
        entries.extend(coefficients.iter().cloned());
        names.push(declared.clone());
    }
    let rows = Rows {
        matrix: Matrix::new(names.len(), n, entries).ok()?,
        expressions: Matrix::new(names.len(), n, expressions).ok()?,
        names,
        redundant: Vec::new(),
    };
    let contacts = declared_rows..declared_rows + mechanism.mechanism.contacts.len();
    let layout = Layout {
        holonomic: contacts.end..rows.names.len(),
        contacts,
        residuals: mechanism.mechanism.expressions.holonomic_residual.entries(),
        coordinates,
        parameters,
    };
    without_redundant(cx, rows, layout)
}

/// The entries of a derived row as expressions
/// ([`crate::sym::Context::compact_expression`]): each normal form written
/// out, or the derivative of the expression the row was derived as in that
/// velocity.
fn entry_expressions(
    cx: &mut Context,
    entries: &[RationalFunction],
    derived_as: ExprId,
) -> Vec<ExprId> {
    let velocities = velocity_symbols(cx);
    entries
        .iter()
        .zip(velocities)
        .map(|(entry, velocity)| {
            let derivative = cx.sym.derivative(derived_as, velocity);
            cx.sym.compact_expression(entry, derivative)
        })
        .collect()
}

/// The coefficients of a linear form in the velocities, in coordinate order.
fn velocity_coefficients(
    cx: &mut Context,
    form: &RationalFunction,
) -> Option<Vec<RationalFunction>> {
    let velocities: Vec<SymbolId> = velocity_symbols(cx);
    velocities
        .into_iter()
        .map(|v| cx.sym.derivative_of_normal(form, v).ok())
        .collect()
}

/// The rows of `constraints` or `distribution` (none: c = 0).
fn declared_constraints(
    cx: &mut Context,
    sections: &Sections,
    n: usize,
) -> Option<(Vec<Declared>, Matrix)> {
    if let Some(section) = sections.get(Section::Distribution) {
        return annihilator_of_distribution(cx, section, n);
    }
    let Some(section) = sections.get(Section::Constraints) else {
        return Some((Vec::new(), Matrix::zeros(0, n)));
    };
    let list = cx.list(section)?;
    let mut names: Vec<Declared> = Vec::new();
    let mut rows = Vec::new();
    let mut ok = true;
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a constraint") else {
            ok = false;
            continue;
        };
        ok &= check_unique_in_section(cx, &names, &declared.name, declared.span);
        match item_expression(cx, value).and_then(|e| constraint_row(cx, e)) {
            Some(row) => rows.extend(row),
            None => ok = false,
        }
        names.push(declared);
    }
    if !ok {
        return None;
    }
    let a = Matrix::new(names.len(), n, rows).ok()?;
    Some((names, a))
}

/// One constraint: linear and homogeneous in the velocities; its row of A.
fn constraint_row(cx: &mut Context, expr: &Expr) -> Option<Vec<RationalFunction>> {
    let id = cx.lower(expr)?;
    let form = cx.normal(id, expr.first_span())?;
    if !check_velocity_degree(
        cx,
        &form,
        expr,
        1,
        "a constraint must be linear and homogeneous in the velocities (every term exactly one \
         velocity times a function of the configuration)",
    ) {
        return None;
    }
    velocity_coefficients(cx, &form)
}

/// The velocities of the store's symbols, in coordinate order.
fn velocity_symbols(cx: &Context) -> Vec<SymbolId> {
    cx.sym
        .symbols()
        .filter(|(_, s)| matches!(s.kind, SymbolKind::Velocity(_)))
        .map(|(id, _)| id)
        .collect()
}

/// A distribution: k independent vector fields of length n, no velocities;
/// the constraint rows are a basis of its annihilator.
fn annihilator_of_distribution(
    cx: &mut Context,
    section: &syntax::Section,
    n: usize,
) -> Option<(Vec<Declared>, Matrix)> {
    let list = cx.list(section)?;
    let mut names: Vec<Declared> = Vec::new();
    let mut entries = Vec::new();
    for item in &list.items {
        let (declared, _) = named_item(cx, item, "a vector field of the distribution")?;
        let row = row_of_expressions(cx, item, n, "a distribution vector")?;
        for expr in row {
            entries.push(velocity_free(
                cx,
                expr,
                "a distribution vector depends on the configuration only: no velocities",
            )?);
        }
        names.push(declared);
    }
    let fields = Matrix::new(names.len(), n, entries).ok()?;
    if !check_independent_rows(cx, &fields, &names, "distribution vector") {
        return None;
    }
    let annihilator = fields.null_space(cx.sym.atoms()).ok()?;
    let constraint_names = (1..=annihilator.rows())
        .map(|i| Declared {
            name: format!("c{i}"),
            span: section.key.span(),
        })
        .collect();
    Some((constraint_names, annihilator))
}
