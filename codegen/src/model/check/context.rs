//! What the rules share as the walk goes on: the model's symbolic context,
//! the names earlier sections declared and bound, and the diagnostics
//! recorded so far; and the shapes every section value is read in.

use crate::diagnostic::Diagnostics;
use crate::model::lower::{Lowerer, Scope};
use crate::sym::{self, Budget, ExprId, RationalFunction};
use crate::syntax::{self, Expr, List};
use proc_macro2::Span;
use std::collections::HashMap;

/// The state every rule reads and extends.
#[derive(Default)]
pub(super) struct Context {
    /// The symbolic context holding every expression of the model.
    pub(super) sym: sym::Context,
    /// The names an expression may use, bound by earlier sections.
    pub(super) scope: Scope,
    /// The errors found so far, in the order they were found.
    pub(super) diagnostics: Diagnostics,
    /// Names declared so far, with what they are and where.
    pub(super) declared: HashMap<String, (&'static str, Span)>,
}

impl Context {
    /// A context whose normal forms are charged to `budget`.
    pub(super) fn within(budget: Budget) -> Context {
        Context {
            sym: sym::Context::with_budget(budget),
            ..Context::default()
        }
    }

    /// A lowerer into the symbolic context, seeing the names bound so far.
    pub(super) fn lowerer(&mut self) -> Lowerer<'_> {
        Lowerer {
            cx: &mut self.sym,
            scope: &self.scope,
            diagnostics: &mut self.diagnostics,
        }
    }

    /// The expression in the context's store, or `None` after reporting why not.
    pub(super) fn lower(&mut self, expr: &Expr) -> Option<ExprId> {
        self.lowerer().lower(expr)
    }

    /// The normal form of `id`, or `None` after reporting the failure at `span`.
    pub(super) fn normal(&mut self, id: ExprId, span: Span) -> Option<RationalFunction> {
        match self.sym.normal(id) {
            Ok(form) => Some(form),
            Err(error) => {
                self.diagnostics.error(span, error.to_string());
                None
            }
        }
    }

    /// The section's list, or `None` after reporting that it takes one.
    pub(super) fn list<'a>(&mut self, section: &'a syntax::Section) -> Option<&'a List> {
        let list = section.value.as_list();
        if list.is_none() {
            self.diagnostics.error(
                section.value.span(),
                format!("section `{}` takes a list `[...]`", section.key),
            );
        }
        list
    }

    /// The section's expression, or `None` after reporting that it takes one.
    pub(super) fn expression<'a>(&mut self, section: &'a syntax::Section) -> Option<&'a Expr> {
        let expr = section.value.as_expr();
        if expr.is_none() {
            self.diagnostics.error(
                section.value.span(),
                format!("section `{}` takes an expression, not a list", section.key),
            );
        }
        expr
    }
}
