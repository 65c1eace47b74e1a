//! Rolling contacts on a declared body with at least one direction, and
//! holonomic constraints free of velocities.

use super::super::*;
use super::Row;
use crate::model::mechanism::bodies::Body;
use crate::model::mechanism::evaluate::Reference;
use crate::model::mechanism::space::{self, Space};
use crate::model::mechanism::vector::{self, Vector};

impl Checker {
    /// `name = no_slip(body, point, [d_1, ...])`: one row `d_i . v_P` each.
    pub(super) fn contacts(
        &mut self,
        section: Option<&&Section>,
        space: &Space,
        reference: &Reference,
        bodies: &[(Declared, Body)],
        q: &[SymbolId],
    ) -> (Vec<Declared>, Vec<Row>) {
        let mut names = Vec::new();
        let mut rows = Vec::new();
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return (names, rows);
        };
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a rolling contact") else {
                continue;
            };
            let Some(slips) = self.contact(value, space, reference, bodies, q) else {
                continue;
            };
            let count = slips.len();
            for (i, slip) in slips.into_iter().enumerate() {
                let name = if count == 1 {
                    declared.name.clone()
                } else {
                    format!("{}_{}", declared.name, i + 1)
                };
                names.push(Declared {
                    name,
                    span: declared.span,
                });
                rows.push(slip);
            }
        }
        (names, rows)
    }

    /// The slip velocities `d_i . v_P` of one contact, in normal form and
    /// as the expression they were derived as.
    pub(super) fn contact(
        &mut self,
        value: &Value,
        space: &Space,
        reference: &Reference,
        bodies: &[(Declared, Body)],
        q: &[SymbolId],
    ) -> Option<Vec<Row>> {
        let Value::Expr(Expr::Call {
            function,
            arguments,
            ..
        }) = value
        else {
            return self.contact_form(value.span());
        };
        let [body, point, directions] = arguments.as_slice() else {
            return self.contact_form(function.span());
        };
        if function != "no_slip" {
            return self.contact_form(function.span());
        }
        let body = self.rule_body_known(body, bodies, space);
        let point = self.center(point, space, reference);
        let directions = self.directions(directions, space, reference);
        let (body, point, directions) = (body?, point?, directions?);
        let v = body.material_velocity(&mut self.store, &point, q).ok()?;
        directions
            .iter()
            .map(|d| {
                let slip = vector::inner(&mut self.store, d, &v);
                self.linear_coefficients(slip, q)
                    .ok()
                    .map(|row| (row, slip))
            })
            .collect()
    }

    pub(super) fn contact_form<T>(&mut self, span: Span) -> Option<T> {
        self.diagnostics.error(
            span,
            "a rolling contact is `name = no_slip(body, point, [direction, ...])`",
        );
        None
    }

    /// A contact names a declared body.
    pub(super) fn rule_body_known<'b>(
        &mut self,
        value: &Value,
        bodies: &'b [(Declared, Body)],
        space: &Space,
    ) -> Option<&'b Body> {
        let (found, broken) = match value {
            Value::Expr(Expr::Name(ident)) => (
                bodies.iter().find(|(d, _)| *ident == d.name),
                space.is_broken(&ident.to_string()),
            ),
            _ => (None, false),
        };
        if found.is_none() && !broken {
            self.diagnostics.error(
                value.span(),
                "unknown body: a rolling contact names a body declared in `bodies`",
            );
        }
        found.map(|(_, body)| body)
    }

    /// At least one direction, each a vector.
    pub(super) fn directions(
        &mut self,
        value: &Value,
        space: &Space,
        reference: &Reference,
    ) -> Option<Vec<Vector>> {
        let Some(list) = value.as_list().filter(|l| !l.items.is_empty()) else {
            self.diagnostics.error(
                value.span(),
                "a rolling contact needs at least one direction: `[d_1, ...]`, e.g. `[ground.x, ground.y]`",
            );
            return None;
        };
        let mut directions = Vec::new();
        for item in &list.items {
            let expr = self.item_expression(item.value())?;
            let direction = self.evaluator(space, reference).vector(expr)?;
            self.rule_configuration_only(&direction, expr, "a direction")
                .then_some(())?;
            directions.push(direction);
        }
        Some(directions)
    }

    // ----- holonomic constraints -------------------------------------------

    /// `name = f(q)`: the residuals and their velocity forms `(df/dq) qdot`.
    pub(super) fn holonomic(
        &mut self,
        section: Option<&&Section>,
        space: &Space,
        reference: &Reference,
        q: &[SymbolId],
    ) -> (Vec<Declared>, Vec<ExprId>, Vec<Row>) {
        let (mut names, mut residuals, mut forms) = (Vec::new(), Vec::new(), Vec::new());
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return (names, residuals, forms);
        };
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a holonomic constraint") else {
                continue;
            };
            let Some(expr) = self.item_expression(value) else {
                continue;
            };
            let unique = self.rule_unique_in_section(&names, &declared.name, declared.span);
            let Some(f) = self.evaluator(space, reference).scalar(expr) else {
                continue;
            };
            if !self.rule_configuration_only(&[f], expr, "a holonomic constraint f(q) = 0")
                || !unique
            {
                continue;
            }
            let Ok(rate) = space::time_derivative(&mut self.store, f, q) else {
                continue;
            };
            let form = match self.linear_coefficients(rate, q) {
                Ok(form) => form,
                Err(error) => {
                    self.diagnostics.error(expr.first_span(), error.to_string());
                    continue;
                }
            };
            names.push(declared);
            residuals.push(f);
            forms.push((form, rate));
        }
        (names, residuals, forms)
    }
}
