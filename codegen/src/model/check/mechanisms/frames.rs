//! Frames turned from `ground` about `x`, `y` or `z` without cycles, and
//! points, each `origin` or a point plus or minus vectors.

use super::super::*;
use super::FrameDeclaration;
use crate::model::mechanism::evaluate::{Reference, axis_index};
use crate::model::mechanism::space::{self, Space};
use crate::syntax::Item;
use proc_macro2::Ident;

impl Checker {
    /// The frames, resolved from `ground` in dependency order.
    pub(super) fn frames(
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
    pub(super) fn frame_declaration<'a>(&mut self, item: &'a Item) -> Option<FrameDeclaration<'a>> {
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
    pub(super) fn rule_frame_name<'a>(&mut self, value: &'a Value) -> Option<&'a Ident> {
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
    pub(super) fn rule_axis(&mut self, value: &Value) -> Option<usize> {
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
    pub(super) fn rule_frame_parent_known(
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

    pub(super) fn rotated_frame(
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
    pub(super) fn points(
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
}
