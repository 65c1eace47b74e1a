//! Mechanism sections: frames turned from `ground` without cycles about
//! `x`, `y` or `z`, points, bodies with a known frame and centre and a
//! symmetric inertia, gravity, rolling contacts with at least one direction
//! on a declared body, and holonomic constraints free of velocities. Every
//! value has the type its place asks for (scalar, vector or point) and
//! depends on the configuration only.

mod bodies;
mod contacts;
mod frames;

use super::energy::first_velocity_span;
use super::*;
use crate::model::mechanism::bodies::BodyMotion;
use crate::model::mechanism::evaluate::{Evaluator, Reference};
use crate::model::mechanism::space::{GROUND, ORIGIN, Space};
use crate::model::mechanism::{Mechanism, MechanismExpressions};
use crate::sym::{ExprMatrix, SymError};
use proc_macro2::Ident;

/// A mechanism and the constraint rows it contributes (contacts, then the
/// holonomic constraints' velocity forms).
pub(super) struct MechanismParts {
    pub(super) mechanism: Mechanism,
    pub(super) names: Vec<Declared>,
    /// Each row's linear form in the velocities ([`Row`]).
    pub(super) rows: Vec<Row>,
    /// The expressions the bodies' `T` and `V` were derived as.
    pub(super) energies_derived_as: (ExprId, ExprId),
    /// Each body's motion, for Kane's form of its inertia forces.
    pub(super) motions: Vec<BodyMotion>,
}

/// A row linear in the velocities: the normal form of each velocity's
/// coefficient, in coordinate order, and the expression it was derived as.
pub(super) type Row = (Vec<RationalFunction>, ExprId);

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
            let zero = self.store.integer(0);
            return Some(MechanismParts {
                mechanism: Mechanism::none(),
                names: Vec::new(),
                rows: Vec::new(),
                energies_derived_as: (zero, zero),
                motions: Vec::new(),
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
        let energies = self.body_energies(&bodies, &gravity, &q)?;
        let orientations: Vec<ExprId> = space
            .declared_frames()
            .iter()
            .flat_map(|(_, f)| f.rotation.to_vec())
            .collect();
        let positions: Vec<ExprId> = space
            .declared_points()
            .iter()
            .flat_map(|(_, p)| p.to_vec())
            .collect();
        let (orientations, orientation_expressions) = self.normal_rows(&orientations, 9)?;
        let (positions, position_expressions) = self.normal_rows(&positions, 3)?;
        let (holonomic_residual, residual_expressions) = self.normal_rows(&residual, 1)?;
        let names = contacts.iter().chain(&holonomic).cloned().collect();
        Some(MechanismParts {
            mechanism: Mechanism {
                frames,
                orientations,
                points,
                positions,
                kinetic_energy: energies.kinetic,
                potential_energy: energies.potential,
                contacts,
                holonomic,
                holonomic_residual,
                expressions: MechanismExpressions {
                    orientations: orientation_expressions,
                    positions: position_expressions,
                    holonomic_residual: residual_expressions,
                },
            },
            names,
            rows,
            energies_derived_as: energies.derived_as,
            motions: energies.motions,
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

    /// Rows of `width` entries: their normal forms, and the expressions to
    /// compute them by ([`crate::sym::Store::compact_expression`]).
    fn normal_rows(&mut self, entries: &[ExprId], width: usize) -> Option<(Matrix, ExprMatrix)> {
        let mut forms = Vec::with_capacity(entries.len());
        let mut expressions = Vec::with_capacity(entries.len());
        for &id in entries {
            let form = self.store.normal(id).ok()?;
            expressions.push(self.store.compact_expression(&form, id));
            forms.push(form);
        }
        let rows = entries.len() / width;
        Some((
            Matrix::new(rows, width, forms).ok()?,
            ExprMatrix::new(rows, width, expressions).ok()?,
        ))
    }

    /// The normal forms of the coefficients of `form`, linear in the
    /// velocities of `q`: `d form / d qdot_j` taken on its DAG, then each in
    /// normal form (the whole row's normal form, a rolling wheel's square
    /// root in every term, is never formed).
    fn linear_coefficients(
        &mut self,
        form: ExprId,
        q: &[SymbolId],
    ) -> Result<Vec<RationalFunction>, SymError> {
        q.iter()
            .map(|&coordinate| {
                let velocity = self.store.velocity_of(coordinate);
                let coefficient = self.store.derivative(form, velocity);
                self.store.normal(coefficient)
            })
            .collect()
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
}
