//! The rules of the model language, one function each.
//!
//! [`check`] walks the sections in dependency order (names, definitions,
//! mechanism, energies, constraints, inputs, momentum basis, symmetry,
//! drawing), lowering each expression into the model's context. Each rule is a
//! function `check_*` of a [`Context`](context::Context) (the symbolic context, the
//! names earlier sections declared, the diagnostics so far) and of what
//! earlier sections produced. A rule that fails records a diagnostic on the
//! offending token and the walk goes on, so every error of a model is
//! reported at once; a section whose inputs failed is skipped rather than
//! reported again.

mod constraints;
mod context;
mod drawing;
mod energy;
mod inputs;
mod items;
mod mechanisms;
mod momentum_basis;
mod names;
mod redundant;
mod rows;
mod section;
mod sections;
mod symmetry;
mod velocities;

use super::drawing::DrawnItem;
use super::invariance::Invariants;
use super::mechanism::evaluate::Reference;
use super::mechanism::space::Space;
use super::mechanism::{Drawing, Mechanism};
use super::{
    Declared, EnergyExpressions, Model, MomentumBasis, Options, Parameter, RedundantRow, Symmetry,
    Variable,
};
use crate::diagnostic::Diagnostics;
use crate::sym::{self, Budget, ExprId, Matrix, RationalFunction, SymbolId};
use crate::syntax::ModelSyntax;
use context::Context;
use mechanisms::MechanismParts;
use section::{Section, Sections};

/// Checks a parsed model and builds its symbolic form: the model and the
/// context holding its expressions.
pub fn check(syntax: &ModelSyntax) -> Result<(Model, sym::Context), Diagnostics> {
    check_within(syntax, Budget::default())
}

/// [`check`], charging the model's normal forms to `budget`.
pub fn check_within(
    syntax: &ModelSyntax,
    budget: Budget,
) -> Result<(Model, sym::Context), Diagnostics> {
    let mut cx = Context::within(budget);
    let sections = sections::given_sections(&mut cx, syntax);
    if !sections.contains(Section::Coordinates) {
        // Every expression would mention undeclared names: report the cause only.
        return Err(cx.diagnostics);
    }
    let checked = checked_sections(&mut cx, syntax, &sections);
    if !cx.diagnostics.is_empty() {
        return Err(cx.diagnostics);
    }
    model(cx, syntax, checked)
}

/// What the sections produced; `None` where a section (or one it needs)
/// failed.
struct Checked {
    options: Options,
    coordinates: Vec<Variable>,
    velocities: Vec<SymbolId>,
    parameters: Vec<Parameter>,
    mechanism: Option<MechanismParts>,
    energy: Option<(RationalFunction, Matrix)>,
    potential_energy: Option<RationalFunction>,
    constraints: Option<redundant::Rows>,
    inputs: Option<(Vec<Declared>, Matrix)>,
    momentum_basis: Option<MomentumBasis>,
    symmetry: Option<Symmetry>,
    energy_expressions: Option<EnergyExpressions>,
    drawing: Option<Vec<DrawnItem<ExprId>>>,
}

/// Every section, checked in dependency order.
fn checked_sections(cx: &mut Context, syntax: &ModelSyntax, sections: &Sections) -> Checked {
    let options = sections::check_attributes(cx, syntax);
    let coordinates = names::coordinates(cx, sections.get(Section::Coordinates));
    let parameters = names::parameters(cx, sections.get(Section::Parameters));
    names::definitions(cx, sections.get(Section::Define));
    let mechanism = mechanisms::mechanism(cx, sections, &coordinates, &parameters);
    let (energy, potential_energy, constraints) = match &mechanism {
        Some(parts) => (
            energy::metric(cx, sections, &coordinates, &parameters, &parts.mechanism),
            energy::potential(cx, sections.get(Section::PotentialEnergy), &parts.mechanism),
            constraints::constraints(cx, sections, (&coordinates, &parameters), parts),
        ),
        None => (None, None, None),
    };
    let inputs = inputs::inputs(cx, sections.get(Section::Inputs), &coordinates);
    let momentum_basis = match (&energy, &constraints) {
        (Some((_, g)), Some(rows)) => momentum_basis::momentum_basis(
            cx,
            sections.get(Section::MomentumBasis),
            g,
            &rows.matrix,
            coordinates.len(),
        ),
        _ => None,
    };
    let symmetry = symmetry::symmetry(cx, sections.get(Section::Symmetry), &coordinates);
    let velocities: Vec<SymbolId> = coordinates
        .iter()
        .map(|c| cx.sym.velocity_of(c.symbol))
        .collect();
    let energy_expressions = match (&energy, &potential_energy, &mechanism) {
        (Some((kinetic, g)), Some(potential), Some(parts)) => {
            energy::energy_expressions(cx, (kinetic, g), potential, parts, &velocities)
        }
        _ => None,
    };
    let drawing = mechanism
        .as_ref()
        .and_then(|parts| check_drawing(cx, sections, parts, &parameters));
    let checked = Checked {
        options,
        coordinates,
        velocities,
        parameters,
        mechanism,
        energy,
        potential_energy,
        constraints,
        inputs,
        momentum_basis,
        symmetry,
        energy_expressions,
        drawing,
    };
    check_symmetry_invariance(cx, &checked);
    checked
}

/// The drawing section's items (none without it) in the mechanism's space
/// (`ground` and `origin` alone without one), or `None` after reporting.
fn check_drawing(
    cx: &mut Context,
    sections: &Sections,
    parts: &MechanismParts,
    parameters: &[Parameter],
) -> Option<Vec<DrawnItem<ExprId>>> {
    let Some(section) = sections.get(Section::Drawing) else {
        return Some(Vec::new());
    };
    let plain;
    let space = match &parts.space {
        Some(space) => space,
        None => {
            plain = Space::new(&mut cx.sym);
            &plain
        }
    };
    let reference = Reference::at_defaults(parameters);
    let place = drawing::Place {
        space,
        reference: &reference,
    };
    drawing::drawing(cx, section, &place)
}

/// The invariance under the declared symmetry, once everything it needs
/// was checked.
fn check_symmetry_invariance(cx: &mut Context, checked: &Checked) {
    if let (
        Some(symmetry),
        Some((kinetic_energy, _)),
        Some(potential_energy),
        Some(rows),
        Some(expressions),
    ) = (
        &checked.symmetry,
        &checked.energy,
        &checked.potential_energy,
        &checked.constraints,
        &checked.energy_expressions,
    ) {
        symmetry::check_invariant(
            cx,
            symmetry,
            &Invariants {
                coordinates: &checked.coordinates,
                velocities: &checked.velocities,
                kinetic_energy: (kinetic_energy, expressions.kinetic),
                potential_energy: (potential_energy, expressions.potential),
                constraint_matrix: &rows.matrix,
                constraint_expressions: &rows.expressions,
            },
        );
    }
}

/// The checked model, from sections that all passed.
fn model(
    cx: Context,
    syntax: &ModelSyntax,
    checked: Checked,
) -> Result<(Model, sym::Context), Diagnostics> {
    let Context {
        mut sym,
        mut diagnostics,
        ..
    } = cx;
    let (
        Some((kinetic_energy, mass_matrix)),
        Some(potential_energy),
        Some(rows),
        Some((input_names, input_matrix)),
        Some(mechanism),
        Some(energy_expressions),
        Some(items),
    ) = (
        checked.energy,
        checked.potential_energy,
        checked.constraints,
        checked.inputs,
        checked.mechanism,
        checked.energy_expressions,
        checked.drawing,
    )
    else {
        diagnostics.error(
            syntax.name.span(),
            "the model could not be checked (an earlier error was not reported)",
        );
        return Err(diagnostics);
    };
    let model = Model {
        name: syntax.name.clone(),
        docs: syntax.docs.clone(),
        visibility: syntax.visibility.clone(),
        options: checked.options,
        emits_rust: true,
        coordinates: checked.coordinates,
        velocities: checked.velocities,
        parameters: checked.parameters,
        kinetic_energy,
        potential_energy,
        mass_matrix,
        energy_expressions,
        mechanism: with_items(
            without_rows(mechanism.mechanism, &rows.redundant),
            items,
            &mut sym,
        ),
        constraints: rows.names,
        constraint_matrix: rows.matrix,
        constraint_expressions: rows.expressions,
        redundant_rows: rows.redundant,
        inputs: input_names,
        input_matrix,
        momentum_basis: checked.momentum_basis,
        symmetry: checked.symmetry,
    };
    Ok((model, sym))
}

/// The mechanism without its redundant contact rows.
fn without_rows(mut mechanism: Mechanism, redundant: &[RedundantRow]) -> Mechanism {
    (mechanism.contacts).retain(|contact| !redundant.iter().any(|r| r.name == contact.name));
    mechanism
}

/// The mechanism, its drawing joined by the drawing section's `items`.
fn with_items(
    mut mechanism: Mechanism,
    items: Vec<DrawnItem<ExprId>>,
    sym: &mut sym::Context,
) -> Mechanism {
    match &mut mechanism.drawing {
        Some(drawing) => drawing.items = items,
        None if !items.is_empty() => {
            mechanism.drawing = Some(Drawing::of_items(items, sym.integer(0)));
        }
        None => {}
    }
    mechanism
}
