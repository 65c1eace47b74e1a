//! The rules of the model language, one function each.
//!
//! [`check`] walks the sections in dependency order (names, definitions,
//! energies, constraints, inputs, momentum basis, symmetry), lowering each
//! expression into the model's store. A rule that fails records a diagnostic
//! on the offending token and the walk goes on, so every error of a model is
//! reported at once; a section whose inputs failed is skipped rather than
//! reported again.

use super::invariance::{Invariants, first_broken};
use super::lower::{Binding, FUNCTIONS, Lowerer, Scope};
use super::{Declared, GroupFactor, Model, MomentumBasis, Options, Parameter, Symmetry, Variable};
use crate::diagnostic::Diagnostics;
use crate::sym::zero::SplitMix;
use crate::sym::{
    Atom, Budget, ExprId, Matrix, Rational, RationalFunction, Store, SymbolId, SymbolKind,
};
use crate::syntax::{BinaryOperator, Expr, Item, List, ModelSyntax, Section, Value};
use proc_macro2::Span;
use std::collections::HashMap;

mod constraints;
mod energy;
mod inputs;
mod mechanisms;
mod momentum_basis;
mod names;
mod sections;
mod symmetry;

/// Every section the language knows, in the order the documentation lists them.
const SECTIONS: [&str; 17] = [
    "coordinates",
    "parameters",
    "define",
    "kinetic_energy",
    "mass_matrix",
    "potential_energy",
    "constraints",
    "distribution",
    "inputs",
    "momentum_basis",
    "symmetry",
    "frames",
    "points",
    "bodies",
    "gravity",
    "no_slip",
    "holonomic",
];

/// Where the mechanism sections start in [`SECTIONS`].
const FIRST_MECHANISM_SECTION: usize = 11;

/// Keywords that cannot name a parameter (parameters become struct fields).
const KEYWORDS: [&str; 51] = [
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub",
    "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "gen", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield",
];

/// Random configurations at which positive definiteness is sampled.
const DEFINITENESS_SAMPLES: usize = 24;

/// Checks a parsed model and builds its symbolic form.
pub fn check(syntax: &ModelSyntax) -> Result<Model, Diagnostics> {
    check_within(syntax, Budget::default())
}

/// [`check`], charging the model's normal forms to `budget`.
pub fn check_within(syntax: &ModelSyntax, budget: Budget) -> Result<Model, Diagnostics> {
    let mut checker = Checker {
        store: Store::with_budget(budget),
        ..Checker::default()
    };
    let sections = checker.sections(syntax);
    if !sections.contains_key("coordinates") {
        // Every expression would mention undeclared names: report the cause only.
        return Err(checker.diagnostics);
    }
    let options = checker.options(syntax);
    let coordinates = checker.coordinates(sections.get("coordinates"));
    let parameters = checker.parameters(sections.get("parameters"));
    checker.definitions(sections.get("define"));
    let mechanism = checker.mechanism(&sections, &coordinates, &parameters);
    let (energy, potential_energy, constraints) = match &mechanism {
        Some(parts) => (
            checker.metric(&sections, &coordinates, &parameters, &parts.mechanism),
            checker.potential(sections.get("potential_energy"), &parts.mechanism),
            checker.constraints(&sections, coordinates.len(), parts),
        ),
        None => (None, None, None),
    };
    let inputs = checker.inputs(sections.get("inputs"), &coordinates);
    let momentum_basis = match (&energy, &constraints) {
        (Some((_, g)), Some((_, a, _))) => {
            checker.momentum_basis(sections.get("momentum_basis"), g, a, coordinates.len())
        }
        _ => None,
    };
    let symmetry = checker.symmetry(sections.get("symmetry"), &coordinates);
    let velocities: Vec<SymbolId> = coordinates
        .iter()
        .map(|c| checker.store.velocity_of(c.symbol))
        .collect();
    let energy_expressions = match (&energy, &potential_energy, &mechanism) {
        (Some((kinetic, g)), Some(potential), Some(parts)) => {
            checker.energy_expressions((kinetic, g), potential, parts, &velocities)
        }
        _ => None,
    };
    if let (
        Some(symmetry),
        Some((kinetic_energy, _)),
        Some(potential_energy),
        Some((_, a, a_expressions)),
        Some(expressions),
    ) = (
        &symmetry,
        &energy,
        &potential_energy,
        &constraints,
        &energy_expressions,
    ) {
        checker.rule_invariant(
            symmetry,
            &Invariants {
                coordinates: &coordinates,
                velocities: &velocities,
                kinetic_energy: (kinetic_energy, expressions.kinetic),
                potential_energy: (potential_energy, expressions.potential),
                constraint_matrix: a,
                constraint_expressions: a_expressions,
            },
        );
    }
    if !checker.diagnostics.is_empty() {
        return Err(checker.diagnostics);
    }
    let (
        Some((kinetic_energy, mass_matrix)),
        Some(potential_energy),
        Some((constraint_names, constraint_matrix, constraint_expressions)),
        Some((input_names, input_matrix)),
        Some(mechanism),
        Some(energy_expressions),
    ) = (
        energy,
        potential_energy,
        constraints,
        inputs,
        mechanism,
        energy_expressions,
    )
    else {
        checker.diagnostics.error(
            syntax.name.span(),
            "the model could not be checked (an earlier error was not reported)",
        );
        return Err(checker.diagnostics);
    };
    Ok(Model {
        name: syntax.name.clone(),
        docs: syntax.docs.clone(),
        visibility: syntax.visibility.clone(),
        options,
        store: checker.store,
        emits_rust: true,
        coordinates,
        velocities,
        parameters,
        kinetic_energy,
        potential_energy,
        mass_matrix,
        energy_expressions,
        constraints: constraint_names,
        constraint_matrix,
        constraint_expressions,
        inputs: input_names,
        input_matrix,
        momentum_basis,
        symmetry,
        mechanism: mechanism.mechanism,
    })
}

#[derive(Default)]
struct Checker {
    store: Store,
    scope: Scope,
    diagnostics: Diagnostics,
    /// Names declared so far, with what they are and where.
    declared: HashMap<String, (&'static str, Span)>,
}

type Sections<'a> = HashMap<String, &'a Section>;

impl Checker {
    fn lowerer(&mut self) -> Lowerer<'_> {
        Lowerer {
            store: &mut self.store,
            scope: &self.scope,
            diagnostics: &mut self.diagnostics,
        }
    }

    fn lower(&mut self, expr: &Expr) -> Option<ExprId> {
        self.lowerer().lower(expr)
    }

    fn normal(&mut self, id: ExprId, span: Span) -> Option<RationalFunction> {
        match self.store.normal(id) {
            Ok(form) => Some(form),
            Err(error) => {
                self.diagnostics.error(span, error.to_string());
                None
            }
        }
    }

    fn list<'a>(&mut self, section: &'a Section) -> Option<&'a List> {
        let list = section.value.as_list();
        if list.is_none() {
            self.diagnostics.error(
                section.value.span(),
                format!("section `{}` takes a list `[...]`", section.key),
            );
        }
        list
    }

    fn expression<'a>(&mut self, section: &'a Section) -> Option<&'a Expr> {
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
