//! Bodies with a known frame and centre, a scalar mass and a symmetric
//! inertia; particles; the gravity field; the bodies' energies.

use super::super::*;
use crate::model::mechanism::bodies::{Body, BodyMotion};
use crate::model::mechanism::evaluate::Reference;
use crate::model::mechanism::space::{self, GROUND, Space};
use crate::model::mechanism::vector::{self, Vector};
use crate::syntax::Item;

impl Checker {
    /// `name = body(frame, center, mass, inertia)` or `name = particle(point, mass)`.
    pub(super) fn bodies(
        &mut self,
        section: Option<&&Section>,
        space: &mut Space,
        reference: &Reference,
    ) -> Vec<(Declared, Body)> {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return Vec::new();
        };
        let mut bodies: Vec<(Declared, Body)> = Vec::new();
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a body") else {
                continue;
            };
            let names: Vec<Declared> = bodies.iter().map(|(d, _)| d.clone()).collect();
            let unique = self.rule_unique_in_section(&names, &declared.name, declared.span);
            match (unique, self.body(value, space, reference)) {
                (true, Some(body)) => bodies.push((declared, body)),
                _ => space.mark_broken(&declared.name),
            }
        }
        bodies
    }

    pub(super) fn body(
        &mut self,
        value: &Value,
        space: &Space,
        reference: &Reference,
    ) -> Option<Body> {
        let (kind, arguments) = match value {
            Value::Expr(Expr::Call {
                function,
                arguments,
                ..
            }) => (function.to_string(), arguments.as_slice()),
            _ => (String::new(), &[][..]),
        };
        match (kind.as_str(), arguments) {
            ("body", [frame, center, mass, inertia]) => {
                let frame = self.rule_frame_known(frame, space);
                let center = self.center(center, space, reference);
                let mass = self.configuration_scalar(mass, space, reference, "a mass");
                let inertia = self.inertia(inertia, space, reference);
                Some(Body {
                    frame: frame?,
                    center: center?,
                    mass: mass?,
                    inertia: inertia?,
                })
            }
            ("particle", [point, mass]) => {
                let center = self.center(point, space, reference);
                let mass = self.configuration_scalar(mass, space, reference, "a mass");
                let zero = self.store.integer(0);
                Some(Body {
                    frame: space.frame(GROUND)?.clone(),
                    center: center?,
                    mass: mass?,
                    inertia: [zero; 9],
                })
            }
            _ => {
                self.diagnostics.error(
                    value.span(),
                    "a body is `body(frame, center, mass, inertia)` or `particle(point, mass)`",
                );
                None
            }
        }
    }

    /// A body's frame is `ground` or a declared frame.
    pub(super) fn rule_frame_known(
        &mut self,
        value: &Value,
        space: &Space,
    ) -> Option<space::FrameState> {
        let ident = self.rule_frame_name(value)?;
        let frame = space.frame(&ident.to_string()).cloned();
        if frame.is_none() && !space.is_broken(&ident.to_string()) {
            self.diagnostics.error(
                ident.span(),
                format!(
                    "unknown frame `{ident}`: a body is fixed in `ground` or in a frame declared \
                     in `frames`"
                ),
            );
        }
        frame
    }

    /// A body's centre is a known point.
    pub(super) fn center(
        &mut self,
        value: &Value,
        space: &Space,
        reference: &Reference,
    ) -> Option<Vector> {
        let expr = self.item_expression(value)?;
        if let Expr::Name(ident) = expr {
            let name = ident.to_string();
            let known = space.point(&name).is_some() || space.frame(&name).is_some();
            if !known && !space.is_broken(&name) {
                self.diagnostics.error(
                    ident.span(),
                    format!("unknown point `{name}`: a centre is `origin` or a point declared in `points`"),
                );
                return None;
            }
        }
        self.evaluator(space, reference).point(expr)
    }

    /// A scalar of the configuration, e.g. a mass or an inertia entry.
    pub(super) fn configuration_scalar(
        &mut self,
        value: &Value,
        space: &Space,
        reference: &Reference,
        what: &str,
    ) -> Option<ExprId> {
        let expr = self.item_expression(value)?;
        let scalar = self.evaluator(space, reference).scalar(expr)?;
        self.rule_configuration_only(&[scalar], expr, what)
            .then_some(scalar)
    }

    /// `diag(a, b, c)` or a symmetric `[[..], [..], [..]]`.
    pub(super) fn inertia(
        &mut self,
        value: &Value,
        space: &Space,
        reference: &Reference,
    ) -> Option<[ExprId; 9]> {
        let what = "an inertia entry";
        if let Value::Expr(Expr::Call {
            function,
            arguments,
            ..
        }) = value
            && function == "diag"
            && arguments.len() == 3
        {
            let zero = self.store.integer(0);
            let mut entries = [zero; 9];
            for (i, argument) in arguments.iter().enumerate() {
                entries[4 * i] = self.configuration_scalar(argument, space, reference, what)?;
            }
            return Some(entries);
        }
        let rows = value.as_list().filter(|list| {
            list.items.len() == 3
                && list
                    .items
                    .iter()
                    .all(|row| row.value().as_list().is_some_and(|r| r.items.len() == 3))
        });
        let Some(rows) = rows else {
            self.diagnostics.error(
                value.span(),
                "an inertia is `diag(a, b, c)` or a symmetric 3 x 3 list `[[..], [..], [..]]` \
                 in the body's axes",
            );
            return None;
        };
        let entries: Vec<&Value> = rows
            .items
            .iter()
            .filter_map(|row| row.value().as_list())
            .flat_map(|row| row.items.iter().map(Item::value))
            .collect();
        let mut values = Vec::with_capacity(9);
        for entry in &entries {
            values.push(self.configuration_scalar(entry, space, reference, what));
        }
        let values: Vec<ExprId> = values.into_iter().collect::<Option<_>>()?;
        let values: [ExprId; 9] = values.try_into().ok()?;
        self.rule_symmetric_inertia(&values, &entries)
            .then_some(values)
    }

    /// An inertia matrix equals its transpose.
    pub(super) fn rule_symmetric_inertia(
        &mut self,
        values: &[ExprId; 9],
        entries: &[&Value],
    ) -> bool {
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let difference = self.store.sub(values[3 * i + j], values[3 * j + i]);
            if self.store.normal(difference).is_ok_and(|d| d.is_zero()) {
                continue;
            }
            self.diagnostics.error(
                entries[3 * i + j].span(),
                format!(
                    "an inertia matrix is symmetric: entry ({}, {}) differs from entry ({}, {})",
                    i + 1,
                    j + 1,
                    j + 1,
                    i + 1
                ),
            );
            return false;
        }
        true
    }

    /// The uniform gravity field (zero when not given).
    pub(super) fn gravity(
        &mut self,
        section: Option<&&Section>,
        space: &Space,
        reference: &Reference,
    ) -> Vector {
        let zero = vector::zero(&mut self.store);
        let Some(expr) = section.and_then(|s| self.expression(s)) else {
            return zero;
        };
        match self.evaluator(space, reference).vector(expr) {
            Some(field) if self.rule_configuration_only(&field, expr, "gravity") => field,
            _ => zero,
        }
    }

    /// `T` and `V` of the bodies: the expressions they were derived as,
    /// their normal forms, and each body's motion.
    pub(super) fn body_energies(
        &mut self,
        bodies: &[(Declared, Body)],
        gravity: &Vector,
        q: &[SymbolId],
    ) -> Option<BodyEnergies> {
        let mut motions = Vec::new();
        let mut kinetic = Vec::new();
        let mut potential = Vec::new();
        for (_, body) in bodies {
            let motion = body.motion(&mut self.store, q).ok()?;
            kinetic.push(motion.kinetic_energy(&mut self.store));
            potential.push(body.potential_energy(&mut self.store, gravity));
            motions.push(motion);
        }
        let kinetic = self.store.add(&kinetic);
        let potential = self.store.add(&potential);
        Some(BodyEnergies {
            kinetic: self.store.normal(kinetic).ok()?,
            potential: self.store.normal(potential).ok()?,
            derived_as: (kinetic, potential),
            motions,
        })
    }
}

/// The bodies' `T` and `V` in normal form, the expressions they were
/// derived as, and the bodies' motions.
pub(in crate::model::check) struct BodyEnergies {
    pub(in crate::model::check) kinetic: RationalFunction,
    pub(in crate::model::check) potential: RationalFunction,
    pub(in crate::model::check) derived_as: (ExprId, ExprId),
    pub(in crate::model::check) motions: Vec<BodyMotion>,
}
