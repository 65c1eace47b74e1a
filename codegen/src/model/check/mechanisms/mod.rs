//! Mechanism sections: frames turned from `ground` without cycles about
//! `x`, `y` or `z` or by Euler parameters (each `orient` frame adding its
//! unit constraint and the kinetic energy along `e`: `orientation`),
//! points, bodies with a known frame and centre and a symmetric inertia,
//! gravity, rolling contacts with at least one direction on a declared
//! body, and holonomic constraints free of velocities. Every value has the
//! type its place asks for (scalar, vector or point) and depends on the
//! configuration only.

mod bodies;
mod contacts;
pub(super) mod frames;
mod orientation;
pub(super) mod values;

use values::Row;

use super::context::Context;
use super::section::{Section, Sections};
use crate::model::mechanism::bodies::Body;
use crate::model::mechanism::bodies::BodyMotion;
use crate::model::mechanism::evaluate::Reference;
use crate::model::mechanism::space::{GROUND, ORIGIN, Space};
use crate::model::mechanism::{Drawing, DrawnBody, Mechanism, MechanismExpressions};
use crate::model::{Declared, Parameter, Variable};
use crate::sym::{ExprId, Matrix, SymbolId};
use proc_macro2::Span;

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
    /// The frames and points, which the drawing section may use (`None`
    /// without mechanism sections: `ground` and `origin` alone).
    pub(super) space: Option<Space>,
}

impl MechanismParts {
    /// The parts of a model that declares no mechanism.
    fn none(cx: &mut Context) -> MechanismParts {
        let zero = cx.sym.integer(0);
        MechanismParts {
            mechanism: Mechanism::none(),
            names: Vec::new(),
            rows: Vec::new(),
            energies_derived_as: (zero, zero),
            motions: Vec::new(),
            space: None,
        }
    }
}

/// The mechanism sections, or `None` after reporting.
pub(super) fn mechanism(
    cx: &mut Context,
    sections: &Sections,
    coordinates: &[Variable],
    parameters: &[Parameter],
) -> Option<MechanismParts> {
    let q: Vec<SymbolId> = coordinates.iter().map(|c| c.symbol).collect();
    if !sections.any_mechanism() {
        return Some(MechanismParts::none(cx));
    }
    let reference = Reference::at_defaults(parameters);
    for (name, kind) in [(GROUND, "predeclared frame"), (ORIGIN, "predeclared point")] {
        cx.declared
            .entry(name.to_string())
            .or_insert((kind, Span::call_site()));
    }
    let errors_before = cx.diagnostics.len();
    let mut space = Space::new(&mut cx.sym);
    let section = |section| sections.get(section);
    let frames = frames::frames(cx, section(Section::Frames), &mut space, &reference, &q);
    let points = frames::points(cx, section(Section::Points), &mut space, &reference);
    let bodies = bodies::bodies(cx, section(Section::Bodies), &mut space, &reference);
    let gravity = bodies::gravity(cx, section(Section::Gravity), &space, &reference);
    let contacts::Contacts {
        names: contacts,
        mut rows,
        drawn: drawn_contacts,
    } = contacts::contacts(
        cx,
        section(Section::NoSlip),
        &space,
        &reference,
        &bodies,
        &q,
    );
    let (mut holonomic, mut residual, velocity_forms) =
        contacts::holonomic(cx, section(Section::Holonomic), &space, &reference, &q);
    let units = orientation::unit_constraints(cx, &frames, &holonomic, &q).ok()?;
    if cx.diagnostics.len() > errors_before {
        return None;
    }
    rows.extend(velocity_forms.into_iter().chain(units.rows));
    holonomic.extend(units.names);
    residual.extend(units.residuals);
    let along_parameters = orientation::rate_along_parameters(cx, &frames, &bodies, &q).ok()?;
    let energies = bodies::body_energies(cx, &bodies, along_parameters, &gravity, &q)?;
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
    let (orientations, orientation_expressions) = normal_rows(cx, &orientations, 9)?;
    let (positions, position_expressions) = normal_rows(cx, &positions, 3)?;
    let (holonomic_residual, residual_expressions) = normal_rows(cx, &residual, 1)?;
    let names = contacts.iter().chain(&holonomic).cloned().collect();
    let drawing = Drawing {
        gravity,
        bodies: bodies.iter().map(drawn_body).collect(),
        contacts: drawn_contacts,
        items: Vec::new(),
    };
    let (frames, turns) = frames.into_iter().unzip();
    Some(MechanismParts {
        mechanism: Mechanism {
            frames,
            turns,
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
            drawing: Some(drawing),
        },
        names,
        rows,
        energies_derived_as: energies.derived_as,
        motions: energies.motions,
        space: Some(space),
    })
}

/// A body as drawing it needs.
fn drawn_body((declared, body): &(Declared, Body)) -> DrawnBody {
    DrawnBody {
        name: declared.name.clone(),
        particle: body.particle,
        center: body.center,
        rotation: body.frame.rotation,
        mass: body.mass,
        inertia: body.inertia,
    }
}

/// Rows of `width` entries: their normal forms, and the expressions to
/// compute them by ([`crate::sym::Context::compact_expression`]).
fn normal_rows(
    cx: &mut Context,
    entries: &[ExprId],
    width: usize,
) -> Option<(Matrix, Matrix<ExprId>)> {
    let mut forms = Vec::with_capacity(entries.len());
    let mut expressions = Vec::with_capacity(entries.len());
    for &id in entries {
        let form = cx.sym.normal(id).ok()?;
        expressions.push(cx.sym.compact_expression(&form, id));
        forms.push(form);
    }
    let rows = entries.len() / width;
    Some((
        Matrix::new(rows, width, forms).ok()?,
        Matrix::new(rows, width, expressions).ok()?,
    ))
}
