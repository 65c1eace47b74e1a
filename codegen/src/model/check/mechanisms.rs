//! Mechanism sections: frames turned from `ground` without cycles about
//! `x`, `y` or `z`, points, bodies with a known frame and centre and a
//! symmetric inertia, gravity, rolling contacts with at least one direction
//! on a declared body, and holonomic constraints free of velocities. Every
//! value has the type its place asks for (scalar, vector or point) and
//! depends on the configuration only.

use super::energy::first_velocity_span;
use super::*;
use crate::model::mechanism::Mechanism;
use crate::model::mechanism::bodies::Body;
use crate::model::mechanism::evaluate::{Evaluator, Reference, axis_index};
use crate::model::mechanism::space::{self, GROUND, ORIGIN, Space};
use crate::model::mechanism::vector::{self, Vector};
use crate::syntax::Item;
use proc_macro2::Ident;

/// A mechanism and the constraint rows it contributes (contacts, then the
/// holonomic constraints' velocity forms).
pub(super) struct MechanismParts {
    pub(super) mechanism: Mechanism,
    pub(super) names: Vec<Declared>,
    pub(super) rows: Vec<RationalFunction>,
}

/// A frame's declaration: `name = rotate(parent, axis, angle)`.
struct FrameDeclaration<'a> {
    declared: Declared,
    parent: &'a Ident,
    axis: usize,
    angle: &'a Expr,
}

impl Checker {
    /// The mechanism sections, or `None` after reporting.
    pub(super) fn mechanism(
        &mut self,
        sections: &Sections,
        coordinates: &[Variable],
        parameters: &[Parameter],
    ) -> Option<MechanismParts> {
        let q: Vec<SymbolId> = coordinates.iter().map(|c| c.symbol).collect();
        if !SECTIONS[FIRST_MECHANISM_SECTION..]
            .iter()
            .any(|s| sections.contains_key(*s))
        {
            return Some(MechanismParts {
                mechanism: Mechanism::none(),
                names: Vec::new(),
                rows: Vec::new(),
            });
        }
        let reference = Reference(
            parameters
                .iter()
                .map(|p| (p.variable.symbol, p.default.to_f64()))
                .collect(),
        );
        for (name, kind) in [(GROUND, "predeclared frame"), (ORIGIN, "predeclared point")] {
            self.declared
                .entry(name.to_string())
                .or_insert((kind, Span::call_site()));
        }
        let errors_before = self.diagnostics.len();
        let mut space = Space::new(&mut self.store);
        let frames = self.frames(sections.get("frames"), &mut space, &reference, &q);
        let points = self.points(sections.get("points"), &mut space, &reference);
        let bodies = self.bodies(sections.get("bodies"), &mut space, &reference);
        let gravity = self.gravity(sections.get("gravity"), &space, &reference);
        let (contacts, mut rows) =
            self.contacts(sections.get("no_slip"), &space, &reference, &bodies, &q);
        let (holonomic, residual, velocity_forms) =
            self.holonomic(sections.get("holonomic"), &space, &reference, &q);
        if self.diagnostics.len() > errors_before {
            return None;
        }
        rows.extend(velocity_forms);
        let (kinetic_energy, potential_energy) = self.body_energies(&bodies, &gravity, &q)?;
        let orientations = self.normal_rows(
            space
                .declared_frames()
                .iter()
                .map(|(_, f)| f.rotation.to_vec()),
            9,
        )?;
        let positions =
            self.normal_rows(space.declared_points().iter().map(|(_, p)| p.to_vec()), 3)?;
        let holonomic_residual = self.normal_rows(residual.into_iter().map(|f| vec![f]), 1)?;
        let names = contacts.iter().chain(&holonomic).cloned().collect();
        Some(MechanismParts {
            mechanism: Mechanism {
                frames,
                orientations,
                points,
                positions,
                kinetic_energy,
                potential_energy,
                contacts,
                holonomic,
                holonomic_residual,
            },
            names,
            rows,
        })
    }

    fn evaluator<'a>(&'a mut self, space: &'a Space, reference: &'a Reference) -> Evaluator<'a> {
        Evaluator {
            lowerer: Lowerer {
                store: &mut self.store,
                scope: &self.scope,
                diagnostics: &mut self.diagnostics,
            },
            space,
            reference,
        }
    }

    /// Rows of normal forms, `width` entries each.
    fn normal_rows(
        &mut self,
        rows: impl Iterator<Item = Vec<ExprId>>,
        width: usize,
    ) -> Option<Matrix> {
        let mut entries = Vec::new();
        for row in rows {
            for id in row {
                entries.push(self.store.normal(id).ok()?);
            }
        }
        Matrix::new(entries.len() / width, width, entries).ok()
    }

    /// Values in mechanism sections depend on the configuration only.
    fn rule_configuration_only(&mut self, values: &[ExprId], expr: &Expr, what: &str) -> bool {
        let has_velocity = values.iter().any(|&id| {
            self.store
                .free_symbols(id)
                .iter()
                .any(|&s| matches!(self.store.symbol_info(s).kind, SymbolKind::Velocity(_)))
        });
        if has_velocity {
            let span = first_velocity_span(expr).unwrap_or_else(|| expr.first_span());
            self.diagnostics.error(
                span,
                format!("{what} depends on the configuration only: no velocities"),
            );
        }
        !has_velocity
    }

    // ----- frames ---------------------------------------------------------

    /// The frames, resolved from `ground` in dependency order.
    fn frames(
        &mut self,
        section: Option<&&Section>,
        space: &mut Space,
        reference: &Reference,
        q: &[SymbolId],
    ) -> Vec<Declared> {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return Vec::new();
        };
        let mut pending: Vec<FrameDeclaration> = list
            .items
            .iter()
            .filter_map(|item| self.frame_declaration(item))
            .collect();
        let mut resolved = Vec::new();
        while let Some(ready) = pending
            .iter()
            .position(|f| space.frame(&f.parent.to_string()).is_some())
        {
            let frame = pending.remove(ready);
            if let Some(state) = self.rotated_frame(&frame, space, reference, q) {
                space.add_frame(&frame.declared.name, state);
                resolved.push(frame.declared);
            } else {
                space.mark_broken(&frame.declared.name);
            }
        }
        let written: Vec<String> = list
            .items
            .iter()
            .filter_map(|item| item.name().map(ToString::to_string))
            .collect();
        for (index, frame) in pending.iter().enumerate() {
            self.rule_frame_parent_known(index, frame, &pending, &written);
        }
        for name in &written {
            if space.frame(name).is_none() {
                space.mark_broken(name);
            }
        }
        resolved
    }

    /// `name = rotate(parent, x|y|z, angle)` with a fresh name.
    fn frame_declaration<'a>(&mut self, item: &'a Item) -> Option<FrameDeclaration<'a>> {
        let (declared, value) = self.named_item(item, "a frame")?;
        let call = match value {
            Value::Expr(Expr::Call {
                function,
                arguments,
                ..
            }) if function == "rotate" && arguments.len() == 3 => Some(arguments),
            _ => None,
        };
        let Some([parent, axis, angle]) = call.map(Vec::as_slice) else {
            self.diagnostics.error(
                value.span(),
                "a frame is `name = rotate(parent, x|y|z, angle)`",
            );
            return None;
        };
        let fresh = self.rule_fresh_name(&declared.name, declared.span, "frame");
        let parent = self.rule_frame_name(parent);
        let axis = self.rule_axis(axis);
        let angle = angle.as_expr();
        Some(FrameDeclaration {
            declared,
            parent: parent?,
            axis: axis?,
            angle: angle.filter(|_| fresh)?,
        })
    }

    /// A frame's parent is named by an identifier.
    fn rule_frame_name<'a>(&mut self, value: &'a Value) -> Option<&'a Ident> {
        match value {
            Value::Expr(Expr::Name(ident)) => Some(ident),
            _ => {
                self.diagnostics
                    .error(value.span(), "expected a frame's name, e.g. `ground`");
                None
            }
        }
    }

    /// A rotation is about the parent's `x`, `y` or `z` axis.
    fn rule_axis(&mut self, value: &Value) -> Option<usize> {
        let axis = match value {
            Value::Expr(Expr::Name(ident)) => axis_index(ident),
            _ => None,
        };
        if axis.is_none() {
            self.diagnostics.error(
                value.span(),
                "a frame turns about its parent's `x`, `y` or `z` axis",
            );
        }
        axis
    }

    /// A frame that never resolved has an unknown parent, or is part of a
    /// cycle (reported once, at the cycle's first frame); a frame below a
    /// broken declaration is not reported again.
    fn rule_frame_parent_known(
        &mut self,
        index: usize,
        frame: &FrameDeclaration,
        pending: &[FrameDeclaration],
        written: &[String],
    ) {
        let position = |name: &str| pending.iter().position(|f| f.declared.name == name);
        let parent = frame.parent.to_string();
        if position(&parent).is_none() {
            if !written.contains(&parent) {
                self.diagnostics.error(
                    frame.parent.span(),
                    format!(
                        "unknown frame `{parent}`: a frame is turned from `ground` or from a \
                         frame declared in `frames`"
                    ),
                );
            }
            return;
        }
        let mut cycle = vec![index];
        let mut next = position(&parent);
        while let Some(member) = next.filter(|m| !cycle.contains(m)) {
            cycle.push(member);
            next = position(&pending[member].parent.to_string());
        }
        if next == Some(index) && cycle.iter().all(|&member| member >= index) {
            let names: Vec<&str> = cycle
                .iter()
                .chain([&index])
                .map(|&member| pending[member].declared.name.as_str())
                .collect();
            self.diagnostics.error(
                frame.parent.span(),
                format!(
                    "the frames form a cycle ({}): each frame is turned from a parent on a \
                     chain that must start at `ground`",
                    names.join(" <- ")
                ),
            );
        }
    }

    fn rotated_frame(
        &mut self,
        frame: &FrameDeclaration,
        space: &Space,
        reference: &Reference,
        q: &[SymbolId],
    ) -> Option<space::FrameState> {
        let angle = self.evaluator(space, reference).scalar(frame.angle)?;
        if !self.rule_configuration_only(&[angle], frame.angle, "a frame's angle") {
            return None;
        }
        let parent = space.frame(&frame.parent.to_string())?;
        match space::rotated(&mut self.store, parent, frame.axis, angle, q) {
            Ok(state) => Some(state),
            Err(error) => {
                self.diagnostics
                    .error(frame.angle.first_span(), error.to_string());
                None
            }
        }
    }

    // ----- points ---------------------------------------------------------

    /// The points, each `origin` or a point plus or minus vectors.
    fn points(
        &mut self,
        section: Option<&&Section>,
        space: &mut Space,
        reference: &Reference,
    ) -> Vec<Declared> {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return Vec::new();
        };
        let mut declared_points = Vec::new();
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a point") else {
                continue;
            };
            let Some(expr) = self.item_expression(value) else {
                continue;
            };
            let position = self.evaluator(space, reference).point(expr);
            if !self.rule_fresh_name(&declared.name, declared.span, "point") {
                continue;
            }
            match position {
                Some(position) if self.rule_configuration_only(&position, expr, "a point") => {
                    space.add_point(&declared.name, position);
                    declared_points.push(declared);
                }
                _ => space.mark_broken(&declared.name),
            }
        }
        declared_points
    }

    // ----- bodies ---------------------------------------------------------

    /// `name = body(frame, center, mass, inertia)` or `name = particle(point, mass)`.
    fn bodies(
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

    fn body(&mut self, value: &Value, space: &Space, reference: &Reference) -> Option<Body> {
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
    fn rule_frame_known<'s>(
        &mut self,
        value: &Value,
        space: &'s Space,
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
    fn center(&mut self, value: &Value, space: &Space, reference: &Reference) -> Option<Vector> {
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
    fn configuration_scalar(
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
    fn inertia(
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
    fn rule_symmetric_inertia(&mut self, values: &[ExprId; 9], entries: &[&Value]) -> bool {
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
    fn gravity(
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

    /// `T` and `V` of the bodies, in normal form.
    fn body_energies(
        &mut self,
        bodies: &[(Declared, Body)],
        gravity: &Vector,
        q: &[SymbolId],
    ) -> Option<(RationalFunction, RationalFunction)> {
        let mut kinetic = Vec::new();
        let mut potential = Vec::new();
        for (_, body) in bodies {
            kinetic.push(body.kinetic_energy(&mut self.store, q).ok()?);
            potential.push(body.potential_energy(&mut self.store, gravity));
        }
        let kinetic = self.store.add(&kinetic);
        let potential = self.store.add(&potential);
        Some((
            self.store.normal(kinetic).ok()?,
            self.store.normal(potential).ok()?,
        ))
    }

    // ----- contacts -------------------------------------------------------

    /// `name = no_slip(body, point, [d_1, ...])`: one row `d_i . v_P` each.
    fn contacts(
        &mut self,
        section: Option<&&Section>,
        space: &Space,
        reference: &Reference,
        bodies: &[(Declared, Body)],
        q: &[SymbolId],
    ) -> (Vec<Declared>, Vec<RationalFunction>) {
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

    /// The slip velocities `d_i . v_P` of one contact, in normal form.
    fn contact(
        &mut self,
        value: &Value,
        space: &Space,
        reference: &Reference,
        bodies: &[(Declared, Body)],
        q: &[SymbolId],
    ) -> Option<Vec<RationalFunction>> {
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
                self.store.normal(slip).ok()
            })
            .collect()
    }

    fn contact_form<T>(&mut self, span: Span) -> Option<T> {
        self.diagnostics.error(
            span,
            "a rolling contact is `name = no_slip(body, point, [direction, ...])`",
        );
        None
    }

    /// A contact names a declared body.
    fn rule_body_known<'b>(
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
    fn directions(
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
    fn holonomic(
        &mut self,
        section: Option<&&Section>,
        space: &Space,
        reference: &Reference,
        q: &[SymbolId],
    ) -> (Vec<Declared>, Vec<ExprId>, Vec<RationalFunction>) {
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
            let Some(form) = self.normal(rate, expr.first_span()) else {
                continue;
            };
            names.push(declared);
            residuals.push(f);
            forms.push(form);
        }
        (names, residuals, forms)
    }
}
