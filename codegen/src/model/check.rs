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

/// Every section the language knows, in the order the documentation lists them.
const SECTIONS: [&str; 11] = [
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
];

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
    let energy = checker.metric(&sections, &coordinates, &parameters);
    let potential_energy = checker.potential(sections.get("potential_energy"));
    let constraints = checker.constraints(&sections, coordinates.len());
    let inputs = checker.inputs(sections.get("inputs"), &coordinates);
    let momentum_basis = match (&energy, &constraints) {
        (Some((_, g)), Some((_, a))) => {
            checker.momentum_basis(sections.get("momentum_basis"), g, a, coordinates.len())
        }
        _ => None,
    };
    let symmetry = checker.symmetry(sections.get("symmetry"), &coordinates);
    if let (Some(symmetry), Some((kinetic_energy, _)), Some(potential_energy), Some((_, a))) =
        (&symmetry, &energy, &potential_energy, &constraints)
    {
        let velocities: Vec<SymbolId> = coordinates
            .iter()
            .map(|c| checker.store.velocity_of(c.symbol))
            .collect();
        checker.rule_invariant(
            symmetry,
            &Invariants {
                coordinates: &coordinates,
                velocities: &velocities,
                kinetic_energy,
                potential_energy,
                constraint_matrix: a,
            },
        );
    }
    if !checker.diagnostics.is_empty() {
        return Err(checker.diagnostics);
    }
    let (
        Some((kinetic_energy, mass_matrix)),
        Some(potential_energy),
        Some((constraint_names, constraint_matrix)),
        Some((input_names, input_matrix)),
    ) = (energy, potential_energy, constraints, inputs)
    else {
        checker.diagnostics.error(
            syntax.name.span(),
            "the model could not be checked (an earlier error was not reported)",
        );
        return Err(checker.diagnostics);
    };
    let velocities = coordinates
        .iter()
        .map(|c| checker.store.velocity_of(c.symbol))
        .collect();
    Ok(Model {
        name: syntax.name.clone(),
        docs: syntax.docs.clone(),
        visibility: syntax.visibility.clone(),
        options,
        store: checker.store,
        coordinates,
        velocities,
        parameters,
        kinetic_energy,
        potential_energy,
        mass_matrix,
        constraints: constraint_names,
        constraint_matrix,
        inputs: input_names,
        input_matrix,
        momentum_basis,
        symmetry,
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

    // ----- sections ------------------------------------------------------

    fn sections<'a>(&mut self, syntax: &'a ModelSyntax) -> Sections<'a> {
        let mut sections: Sections<'a> = HashMap::new();
        for section in &syntax.sections {
            let key = section.key.to_string();
            if !self.rule_known_section(section) || !self.rule_section_once(&sections, section) {
                continue;
            }
            sections.insert(key, section);
        }
        self.rule_required_sections(&sections, syntax);
        self.rule_exclusive_sections(&sections, "kinetic_energy", "mass_matrix");
        self.rule_exclusive_sections(&sections, "constraints", "distribution");
        sections
    }

    /// A section name is one the language knows.
    fn rule_known_section(&mut self, section: &Section) -> bool {
        let key = section.key.to_string();
        let known = SECTIONS.contains(&key.as_str());
        if !known {
            self.diagnostics.error(
                section.key.span(),
                format!(
                    "unknown section `{key}`; the sections are {}",
                    SECTIONS.join(", ")
                ),
            );
        }
        known
    }

    /// A section is given at most once.
    fn rule_section_once(&mut self, sections: &Sections, section: &Section) -> bool {
        let key = section.key.to_string();
        let fresh = !sections.contains_key(&key);
        if !fresh {
            self.diagnostics.error(
                section.key.span(),
                format!("section `{key}` is given twice"),
            );
        }
        fresh
    }

    /// `coordinates` and one of `kinetic_energy`/`mass_matrix` are required.
    fn rule_required_sections(&mut self, sections: &Sections, syntax: &ModelSyntax) {
        if !sections.contains_key("coordinates") {
            self.diagnostics.error(
                syntax.name.span(),
                "missing section `coordinates`: a model declares its generalized coordinates",
            );
        }
        if !sections.contains_key("kinetic_energy") && !sections.contains_key("mass_matrix") {
            self.diagnostics.error(
                syntax.name.span(),
                "missing section `kinetic_energy` (or `mass_matrix`): a model declares its \
                 kinetic energy",
            );
        }
    }

    /// Two alternative sections are not both given.
    fn rule_exclusive_sections(&mut self, sections: &Sections, first: &str, second: &str) {
        if let (Some(_), Some(later)) = (sections.get(first), sections.get(second)) {
            self.diagnostics.error(
                later.key.span(),
                format!("`{first}` and `{second}` are alternatives: give only one of them"),
            );
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

    // ----- attributes ----------------------------------------------------

    /// Attributes are doc comments or `#[deny_holonomic]`.
    fn options(&mut self, syntax: &ModelSyntax) -> Options {
        let mut options = Options::default();
        for attribute in &syntax.attributes {
            match attribute.name.to_string().as_str() {
                "deny_holonomic" if attribute.tokens.is_empty() => options.deny_holonomic = true,
                name => self.diagnostics.error(
                    attribute.name.span(),
                    format!(
                        "unknown attribute `{name}`: a model takes doc comments and \
                         `#[deny_holonomic]`"
                    ),
                ),
            }
        }
        options
    }

    // ----- names ---------------------------------------------------------

    /// A name is declared once, among coordinates, parameters and definitions,
    /// and is not a function name.
    fn rule_fresh_name(&mut self, name: &str, span: Span, kind: &'static str) -> bool {
        if FUNCTIONS.contains(&name) || name == "dot" {
            self.diagnostics.error(
                span,
                format!("`{name}` is a function of the model language and cannot name a {kind}"),
            );
            return false;
        }
        if let Some(&(first, _)) = self.declared.get(name) {
            let message = if kind == "parameter" && first == "coordinate" {
                format!("`{name}` is a coordinate and cannot also be used as a parameter")
            } else if first == kind {
                format!("`{name}` is declared twice as a {kind}")
            } else {
                format!("`{name}` is declared twice: first as a {first}, again as a {kind}")
            };
            self.diagnostics.error(span, message);
            return false;
        }
        self.declared.insert(name.to_string(), (kind, span));
        true
    }

    /// Names of constraints, inputs and momentum-basis rows are unique in their section.
    fn rule_unique_in_section(&mut self, names: &[Declared], name: &str, span: Span) -> bool {
        let unique = !names.iter().any(|d| d.name == name);
        if !unique {
            self.diagnostics
                .error(span, format!("`{name}` is declared twice in this section"));
        }
        unique
    }

    /// A list item is `name = value`.
    fn named_item<'a>(&mut self, item: &'a Item, what: &str) -> Option<(Declared, &'a Value)> {
        match item {
            Item::Named { name, value } => Some((
                Declared {
                    name: name.to_string(),
                    span: name.span(),
                },
                value,
            )),
            Item::Plain(value) => {
                self.diagnostics
                    .error(value.span(), format!("expected `name = ...` for {what}"));
                None
            }
        }
    }

    fn coordinates(&mut self, section: Option<&&Section>) -> Vec<Variable> {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return Vec::new();
        };
        if list.items.is_empty() {
            self.diagnostics
                .error(list.span, "a model needs at least one coordinate");
        }
        let mut coordinates = Vec::new();
        for item in &list.items {
            let Item::Plain(Value::Expr(Expr::Name(ident))) = item else {
                self.diagnostics.error(
                    item.span(),
                    "a coordinate is declared by its name alone, e.g. `theta`",
                );
                continue;
            };
            let name = ident.to_string();
            if !self.rule_fresh_name(&name, ident.span(), "coordinate") {
                continue;
            }
            // The nodes of the symbols are made in declaration order, so that
            // printed products list their factors in that order however the
            // derivations proceed.
            let symbol = self.store.declare(&name, SymbolKind::Coordinate);
            let velocity = self.store.velocity_of(symbol);
            self.store.symbol(symbol);
            self.store.symbol(velocity);
            self.scope.bind(&name, Binding::Coordinate(symbol));
            coordinates.push(Variable {
                declared: Declared {
                    name,
                    span: ident.span(),
                },
                symbol,
            });
        }
        coordinates
    }

    fn parameters(&mut self, section: Option<&&Section>) -> Vec<Parameter> {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return Vec::new();
        };
        let mut parameters = Vec::new();
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a parameter and its default")
            else {
                continue;
            };
            let default = self.rule_numeric_default(value);
            let field_ok = self.rule_field_name(&declared);
            if !self.rule_fresh_name(&declared.name, declared.span, "parameter") || !field_ok {
                continue;
            }
            // Declared even when its default is wrong, so its uses are not reported too.
            let symbol = self.store.declare(&declared.name, SymbolKind::Parameter);
            self.store.symbol(symbol);
            self.scope.bind(&declared.name, Binding::Parameter(symbol));
            let Some(default) = default else { continue };
            parameters.push(Parameter {
                variable: Variable { declared, symbol },
                default,
            });
        }
        parameters
    }

    /// A parameter's default is a number literal, possibly negated.
    fn rule_numeric_default(&mut self, value: &Value) -> Option<Rational> {
        let parsed = match value {
            Value::Expr(Expr::Number { literal, .. }) => Rational::from_decimal(literal),
            Value::Expr(Expr::Negate { operand, .. }) => match operand.as_ref() {
                Expr::Number { literal, .. } => Rational::from_decimal(literal).map(|r| r.neg()),
                _ => None,
            },
            _ => None,
        };
        if parsed.is_none() {
            let coordinate = match value {
                Value::Expr(Expr::Name(name)) => self
                    .declared
                    .get(&name.to_string())
                    .is_some_and(|(kind, _)| *kind == "coordinate"),
                _ => false,
            };
            let message = if coordinate {
                "a parameter's default must be a number, and this is a coordinate (parameters are \
                 constants), e.g. `m = 1.0` or `g = -9.81`"
            } else {
                "a parameter's default must be a number, e.g. `m = 1.0` or `g = -9.81`"
            };
            self.diagnostics.error(value.span(), message);
        }
        parsed
    }

    /// A parameter name can be a struct field (not a Rust keyword).
    fn rule_field_name(&mut self, declared: &Declared) -> bool {
        let ok = !KEYWORDS.contains(&declared.name.as_str());
        if !ok {
            self.diagnostics.error(
                declared.span,
                format!(
                    "`{}` is a Rust keyword and cannot name a parameter (parameters become \
                     struct fields)",
                    declared.name
                ),
            );
        }
        ok
    }

    fn definitions(&mut self, section: Option<&&Section>) {
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return;
        };
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a definition") else {
                continue;
            };
            let Some(expr) = self.item_expression(value) else {
                continue;
            };
            let lowered = self.lower(expr);
            if !self.rule_fresh_name(&declared.name, declared.span, "definition") {
                continue;
            }
            // A definition that failed is still declared, so its uses are not reported too.
            let id = lowered.unwrap_or_else(|| {
                let placeholder = self.store.declare(&declared.name, SymbolKind::Auxiliary);
                self.store.symbol(placeholder)
            });
            self.scope.bind(&declared.name, Binding::Definition(id));
        }
    }

    fn item_expression<'a>(&mut self, value: &'a Value) -> Option<&'a Expr> {
        let expr = value.as_expr();
        if expr.is_none() {
            self.diagnostics
                .error(value.span(), "expected an expression, found a list");
        }
        expr
    }

    // ----- energies ------------------------------------------------------

    /// `(T, g)` from whichever of `kinetic_energy`/`mass_matrix` is given.
    fn metric(
        &mut self,
        sections: &Sections,
        coordinates: &[Variable],
        parameters: &[Parameter],
    ) -> Option<(RationalFunction, Matrix)> {
        let velocities: Vec<SymbolId> = coordinates
            .iter()
            .map(|c| self.store.velocity_of(c.symbol))
            .collect();
        let (section, energy, g) = if let Some(section) = sections.get("kinetic_energy") {
            let (t, g) = self.metric_of_kinetic_energy(section, &velocities)?;
            (section, t, g)
        } else {
            let section = sections.get("mass_matrix")?;
            let g = self.declared_mass_matrix(section, coordinates.len())?;
            let t = self.quadratic_form(&g, &velocities);
            (section, t, g)
        };
        // Sampling needs every coordinate and parameter value: skip it after earlier errors.
        if self.diagnostics.is_empty() {
            self.rule_positive_definite(&g, section.key.span(), coordinates, parameters);
        }
        Some((energy, g))
    }

    fn metric_of_kinetic_energy(
        &mut self,
        section: &Section,
        velocities: &[SymbolId],
    ) -> Option<(RationalFunction, Matrix)> {
        let expr = self.expression(section)?;
        let id = self.lower(expr)?;
        let energy = self.normal(id, expr.first_span())?;
        if !self.rule_velocity_degree(&energy, expr, 2, "the kinetic energy must be quadratic in the velocities (every term a product of exactly two velocities)") {
            return None;
        }
        let mut entries = Vec::with_capacity(velocities.len().pow(2));
        for &vi in velocities {
            let first = self.store.derivative_of_normal(&energy, vi).ok()?;
            for &vj in velocities {
                entries.push(self.store.derivative_of_normal(&first, vj).ok()?);
            }
        }
        Some((
            energy,
            Matrix::new(velocities.len(), velocities.len(), entries).ok()?,
        ))
    }

    /// `T = 1/2 qdot^T g qdot`.
    fn quadratic_form(&mut self, g: &Matrix, velocities: &[SymbolId]) -> RationalFunction {
        let atoms: Vec<RationalFunction> = velocities
            .iter()
            .map(|&v| {
                let atom = self.store.symbol_atom(v);
                RationalFunction::from_poly(crate::sym::Poly::atom(atom))
            })
            .collect();
        let table = self.store.atoms().clone();
        let mut sum = RationalFunction::zero();
        for (i, vi) in atoms.iter().enumerate() {
            for (j, vj) in atoms.iter().enumerate() {
                let term = g.get(i, j).mul(&vi.mul(vj, &table), &table);
                sum = sum.add(&term, &table);
            }
        }
        sum.scale(&Rational::new(1, 2).unwrap_or(Rational::ONE))
    }

    /// A declared mass matrix is n x n, free of velocities, and symmetric.
    fn declared_mass_matrix(&mut self, section: &Section, n: usize) -> Option<Matrix> {
        let list = self.list(section)?;
        if list.items.len() != n {
            self.diagnostics.error(
                list.span,
                format!(
                    "the mass matrix must be {n} x {n} (one row per coordinate), found {} rows",
                    list.items.len()
                ),
            );
            return None;
        }
        let mut entries = Vec::with_capacity(n * n);
        let mut spans = Vec::with_capacity(n * n);
        for item in &list.items {
            let row = self.row_of_expressions(item, n, "a mass-matrix row")?;
            for expr in row {
                let form = self.velocity_free(
                    expr,
                    "the mass matrix depends on the configuration only: no velocities",
                )?;
                entries.push(form);
                spans.push(expr.first_span());
            }
        }
        let g = Matrix::new(n, n, entries).ok()?;
        self.rule_symmetric(&g, &spans).then_some(g)
    }

    /// A row `[e_1, ..., e_n]` of exactly `n` expressions.
    fn row_of_expressions<'a>(
        &mut self,
        item: &'a Item,
        n: usize,
        what: &str,
    ) -> Option<Vec<&'a Expr>> {
        let Some(list) = item.value().as_list() else {
            self.diagnostics.error(
                item.span(),
                format!("{what} is a list `[...]` of {n} expressions"),
            );
            return None;
        };
        if list.items.len() != n {
            self.diagnostics.error(
                list.span,
                format!(
                    "{what} must have {n} entries (one per coordinate), found {}",
                    list.items.len()
                ),
            );
            return None;
        }
        list.items
            .iter()
            .map(|entry| match entry.value().as_expr() {
                Some(expr) if entry.name().is_none() => Some(expr),
                _ => {
                    self.diagnostics
                        .error(entry.span(), format!("an entry of {what} is an expression"));
                    None
                }
            })
            .collect()
    }

    /// The mass matrix equals its transpose.
    fn rule_symmetric(&mut self, g: &Matrix, spans: &[Span]) -> bool {
        let n = g.rows();
        for i in 0..n {
            for j in i + 1..n {
                if g.get(i, j).sub(g.get(j, i), self.store.atoms()).is_zero() {
                    continue;
                }
                self.diagnostics.error(
                    spans[i * n + j],
                    format!("the mass matrix must be symmetric: entry ({}, {}) differs from entry ({}, {})", i + 1, j + 1, j + 1, i + 1),
                );
                return false;
            }
        }
        true
    }

    /// The metric is positive definite at the default parameters at a sample
    /// of random configurations. Singular sets of measure zero, such as
    /// `r = 0` of polar coordinates, are coordinate singularities, not errors,
    /// and random samples do not land on them.
    fn rule_positive_definite(
        &mut self,
        g: &Matrix,
        span: Span,
        coordinates: &[Variable],
        parameters: &[Parameter],
    ) {
        let mut generator = SplitMix::new(0x9d2c_5680);
        let n = coordinates.len();
        for _ in 0..DEFINITENESS_SAMPLES {
            let configuration: Vec<f64> = (0..n).map(|_| generator.uniform(-3.0, 3.0)).collect();
            let value_of = |s: SymbolId| {
                coordinates
                    .iter()
                    .position(|c| c.symbol == s)
                    .map(|i| configuration[i])
                    .or_else(|| {
                        parameters
                            .iter()
                            .find(|p| p.variable.symbol == s)
                            .map(|p| p.default.to_f64())
                    })
                    .unwrap_or(f64::NAN)
            };
            let values = g.evaluate(&mut self.store, &value_of);
            if let Some(minor) = failed_cholesky_minor(&values, n) {
                let at: Vec<String> = coordinates
                    .iter()
                    .zip(&configuration)
                    .map(|(c, v)| format!("{} = {v:.3}", c.declared.name))
                    .collect();
                self.diagnostics.error(
                    span,
                    format!(
                        "the mass matrix is not positive definite at the default parameters: at \
                         {} its leading {minor} x {minor} block is not positive definite",
                        at.join(", ")
                    ),
                );
                return;
            }
        }
    }

    fn potential(&mut self, section: Option<&&Section>) -> Option<RationalFunction> {
        let Some(section) = section else {
            return Some(RationalFunction::zero());
        };
        let expr = self.expression(section)?;
        self.velocity_free(
            expr,
            "the potential energy depends on the configuration only: no velocities",
        )
    }

    /// An expression free of velocities, in normal form.
    fn velocity_free(&mut self, expr: &Expr, rule: &str) -> Option<RationalFunction> {
        let id = self.lower(expr)?;
        let has_velocity = self
            .store
            .free_symbols(id)
            .iter()
            .any(|&s| matches!(self.store.symbol_info(s).kind, SymbolKind::Velocity(_)));
        if has_velocity {
            let span = first_velocity_span(expr).unwrap_or_else(|| expr.first_span());
            self.diagnostics.error(span, rule.to_string());
            return None;
        }
        self.normal(id, expr.first_span())
    }

    /// Every term of the numerator has velocity degree `degree`, and no
    /// velocity sits in a denominator or inside a function.
    fn rule_velocity_degree(
        &mut self,
        form: &RationalFunction,
        expr: &Expr,
        degree: u32,
        rule: &str,
    ) -> bool {
        if self.velocity_degrees(form) == Some(vec![degree]) || (form.is_zero() && degree == 1) {
            return true;
        }
        let span = self
            .offending_term(expr, degree)
            .unwrap_or_else(|| expr.first_span());
        self.diagnostics.error(span, rule.to_string());
        false
    }

    /// The distinct velocity degrees of the numerator's terms, or `None` when
    /// velocities enter non-polynomially.
    fn velocity_degrees(&mut self, form: &RationalFunction) -> Option<Vec<u32>> {
        let denominator_atoms: Vec<_> = form
            .denominator()
            .iter()
            .flat_map(|(f, _)| f.atoms())
            .collect();
        let mut velocity_atoms = Vec::new();
        for atom in form.atoms() {
            match self.store.atoms().get(atom).clone() {
                Atom::Symbol(s)
                    if matches!(self.store.symbol_info(s).kind, SymbolKind::Velocity(_)) =>
                {
                    if denominator_atoms.contains(&atom) {
                        return None;
                    }
                    velocity_atoms.push(atom);
                }
                _ => {
                    let expression = self.store.expression_of_atom(atom);
                    let inside = self.store.free_symbols(expression);
                    if inside
                        .iter()
                        .any(|&s| matches!(self.store.symbol_info(s).kind, SymbolKind::Velocity(_)))
                    {
                        return None;
                    }
                }
            }
        }
        let mut degrees: Vec<u32> = form
            .numerator()
            .terms()
            .iter()
            .map(|(m, _)| velocity_atoms.iter().map(|&a| m.exponent(a)).sum())
            .collect();
        degrees.sort_unstable();
        degrees.dedup();
        Some(degrees)
    }

    /// The first top-level term of `expr` whose velocity degree is wrong.
    fn offending_term(&mut self, expr: &Expr, degree: u32) -> Option<Span> {
        let mut terms = Vec::new();
        top_level_terms(expr, &mut terms);
        for term in terms {
            let mut scratch = Diagnostics::default();
            let id = Lowerer {
                store: &mut self.store,
                scope: &self.scope,
                diagnostics: &mut scratch,
            }
            .lower(term)?;
            let form = self.store.normal(id).ok()?;
            if self.velocity_degrees(&form) != Some(vec![degree]) {
                return Some(term.first_span());
            }
        }
        None
    }

    // ----- constraints ---------------------------------------------------

    /// `(names, A)` from `constraints` or `distribution` (none: c = 0).
    fn constraints(&mut self, sections: &Sections, n: usize) -> Option<(Vec<Declared>, Matrix)> {
        if let Some(section) = sections.get("distribution") {
            return self.annihilator_of_distribution(section, n);
        }
        let Some(section) = sections.get("constraints") else {
            return Some((Vec::new(), Matrix::zeros(0, n)));
        };
        let list = self.list(section)?;
        let mut names: Vec<Declared> = Vec::new();
        let mut rows = Vec::new();
        let mut ok = true;
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "a constraint") else {
                ok = false;
                continue;
            };
            ok &= self.rule_unique_in_section(&names, &declared.name, declared.span);
            match self
                .item_expression(value)
                .and_then(|e| self.constraint_row(e))
            {
                Some(row) => rows.extend(row),
                None => ok = false,
            }
            names.push(declared);
        }
        if !ok {
            return None;
        }
        let a = Matrix::new(names.len(), n, rows).ok()?;
        self.rule_independent_rows(&a, &names, "constraint")
            .then_some((names, a))
    }

    /// One constraint: linear and homogeneous in the velocities; its row of A.
    fn constraint_row(&mut self, expr: &Expr) -> Option<Vec<RationalFunction>> {
        let id = self.lower(expr)?;
        let form = self.normal(id, expr.first_span())?;
        if !self.rule_velocity_degree(&form, expr, 1, "a constraint must be linear and homogeneous in the velocities (every term exactly one velocity times a function of the configuration)") {
            return None;
        }
        let velocities: Vec<SymbolId> = self.velocity_symbols();
        velocities
            .into_iter()
            .map(|v| self.store.derivative_of_normal(&form, v).ok())
            .collect()
    }

    fn velocity_symbols(&self) -> Vec<SymbolId> {
        self.store
            .symbols()
            .filter(|(_, s)| matches!(s.kind, SymbolKind::Velocity(_)))
            .map(|(id, _)| id)
            .collect()
    }

    /// Rows of A (or of a momentum basis) are independent: each row adds rank.
    fn rule_independent_rows(&mut self, m: &Matrix, names: &[Declared], what: &str) -> bool {
        let atoms = self.store.atoms().clone();
        for (i, name) in names.iter().enumerate().take(m.rows()) {
            let upto = Matrix::new(
                i + 1,
                m.columns(),
                m.entries()[..(i + 1) * m.columns()].to_vec(),
            );
            if upto.is_ok_and(|u| u.rank(&atoms) < i + 1) {
                self.diagnostics.error(
                    name.span,
                    format!(
                        "{what} `{}` depends on the ones before it: the rows must be linearly independent",
                        name.name
                    ),
                );
                return false;
            }
        }
        true
    }

    /// A distribution: k independent vector fields of length n, no velocities;
    /// the constraint rows are a basis of its annihilator.
    fn annihilator_of_distribution(
        &mut self,
        section: &Section,
        n: usize,
    ) -> Option<(Vec<Declared>, Matrix)> {
        let list = self.list(section)?;
        let mut names: Vec<Declared> = Vec::new();
        let mut entries = Vec::new();
        for item in &list.items {
            let (declared, _) = self.named_item(item, "a vector field of the distribution")?;
            let row = self.row_of_expressions(item, n, "a distribution vector")?;
            for expr in row {
                entries.push(self.velocity_free(
                    expr,
                    "a distribution vector depends on the configuration only: no velocities",
                )?);
            }
            names.push(declared);
        }
        let fields = Matrix::new(names.len(), n, entries).ok()?;
        if !self.rule_independent_rows(&fields, &names, "distribution vector") {
            return None;
        }
        let annihilator = fields.null_space(self.store.atoms()).ok()?;
        let constraint_names = (1..=annihilator.rows())
            .map(|i| Declared {
                name: format!("c{i}"),
                span: section.key.span(),
            })
            .collect();
        Some((constraint_names, annihilator))
    }

    // ----- inputs --------------------------------------------------------

    /// `(names, B)`: each input a force on a coordinate or a column of B.
    fn inputs(
        &mut self,
        section: Option<&&Section>,
        coordinates: &[Variable],
    ) -> Option<(Vec<Declared>, Matrix)> {
        let n = coordinates.len();
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return (section.is_none()).then(|| (Vec::new(), Matrix::zeros(n, 0)));
        };
        let mut names: Vec<Declared> = Vec::new();
        let mut columns = Vec::new();
        let mut ok = true;
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "an input") else {
                ok = false;
                continue;
            };
            ok &= self.rule_unique_in_section(&names, &declared.name, declared.span);
            match self.input_column(item, value, coordinates) {
                Some(column) => columns.push(column),
                None => ok = false,
            }
            names.push(declared);
        }
        if !ok {
            return None;
        }
        let p = names.len();
        let mut b = Matrix::zeros(n, p);
        for (j, column) in columns.into_iter().enumerate() {
            for (i, entry) in column.into_iter().enumerate() {
                b.set(i, j, entry);
            }
        }
        Some((names, b))
    }

    /// An input names a coordinate, or gives a column of n velocity-free entries.
    fn input_column(
        &mut self,
        item: &Item,
        value: &Value,
        coordinates: &[Variable],
    ) -> Option<Vec<RationalFunction>> {
        let n = coordinates.len();
        if let Value::Expr(Expr::Name(ident)) = value {
            let name = ident.to_string();
            let Some(index) = coordinates.iter().position(|c| c.declared.name == name) else {
                self.diagnostics.error(
                    ident.span(),
                    format!("an input acts on a coordinate, and `{name}` is not a coordinate (or give a column `[b_1, ..., b_n]`)"),
                );
                return None;
            };
            return Some(
                (0..n)
                    .map(|i| {
                        if i == index {
                            RationalFunction::one()
                        } else {
                            RationalFunction::zero()
                        }
                    })
                    .collect(),
            );
        }
        if value.as_list().is_none() {
            self.diagnostics.error(
                value.span(),
                "an input is a coordinate's name or a column `[b_1, ..., b_n]`",
            );
            return None;
        }
        let row = self.row_of_expressions(item, n, "an input column")?;
        row.into_iter()
            .map(|expr| {
                self.velocity_free(
                    expr,
                    "an input column depends on the configuration only: no velocities",
                )
            })
            .collect()
    }

    // ----- momentum basis ------------------------------------------------

    /// A declared momentum basis: k = n - c independent rows spanning g(D),
    /// i.e. `A g^-1 h^T = 0` exactly.
    fn momentum_basis(
        &mut self,
        section: Option<&&Section>,
        g: &Matrix,
        a: &Matrix,
        n: usize,
    ) -> Option<MomentumBasis> {
        let section = section?;
        let list = self.list(section)?;
        let k = n - a.rows();
        if list.items.len() != k {
            self.diagnostics.error(
                section.key.span(),
                format!(
                    "the momentum basis needs k = n - c = {n} - {} = {k} rows, found {}",
                    a.rows(),
                    list.items.len()
                ),
            );
            return None;
        }
        let mut names = Vec::new();
        let mut entries = Vec::new();
        for item in &list.items {
            let (declared, _) = self.named_item(item, "a momentum-basis row")?;
            let row = self.row_of_expressions(item, n, "a momentum-basis row")?;
            for expr in row {
                entries.push(self.velocity_free(
                    expr,
                    "a momentum-basis row depends on the configuration only: no velocities",
                )?);
            }
            names.push(declared);
        }
        let h = Matrix::new(k, n, entries).ok()?;
        if !self.rule_independent_rows(&h, &names, "momentum-basis row") {
            return None;
        }
        self.rule_spans_momenta(&h, g, a, &names)
            .then_some(MomentumBasis { names, rows: h })
    }

    /// Each row of h lies in g(D): the column `A g^-1 h_i^T` is exactly zero.
    fn rule_spans_momenta(
        &mut self,
        h: &Matrix,
        g: &Matrix,
        a: &Matrix,
        names: &[Declared],
    ) -> bool {
        let atoms = self.store.atoms().clone();
        let Ok(product) = g
            .inverse(&atoms)
            .and_then(|inverse| a.mul(&inverse, &atoms))
            .and_then(|ag| ag.mul(&h.transpose(), &atoms))
        else {
            return false;
        };
        for (j, name) in names.iter().enumerate() {
            if (0..product.rows()).any(|i| !product.get(i, j).is_zero()) {
                self.diagnostics.error(
                    name.span,
                    format!(
                        "momentum-basis row `{}` is not in g(D): the momenta of allowed motions \
                         satisfy A g^-1 h^T = 0, and this row's column is not zero",
                        name.name
                    ),
                );
                return false;
            }
        }
        true
    }

    // ----- symmetry ------------------------------------------------------

    /// The Lagrangian and the constraints are invariant under the declared group.
    fn rule_invariant(&mut self, symmetry: &Symmetry, model: &Invariants) {
        match first_broken(&mut self.store, symmetry, model) {
            Ok(None) => {}
            Ok(Some(broken)) => self.diagnostics.error(
                symmetry.span,
                format!(
                    "{} not invariant under the declared symmetry group: the momentum \
                     equation needs the Lagrangian and the constraints to be invariant",
                    broken.describe()
                ),
            ),
            Err(error) => self.diagnostics.error(symmetry.span, error.to_string()),
        }
    }

    /// A symmetry is a product of `se2(x, y, theta)`, `translation(q)` and
    /// `rotation(q)` of distinct coordinates.
    fn symmetry(
        &mut self,
        section: Option<&&Section>,
        coordinates: &[Variable],
    ) -> Option<Symmetry> {
        let section = section?;
        let expr = self.expression(section)?;
        let mut calls = Vec::new();
        product_factors(expr, &mut calls);
        let mut factors = Vec::new();
        let mut used: Vec<usize> = Vec::new();
        for factor in calls {
            let Expr::Call {
                function,
                arguments,
                ..
            } = factor
            else {
                self.diagnostics.error(
                    factor.first_span(),
                    "a symmetry is a product of se2(x, y, theta), translation(q) and rotation(q)",
                );
                return None;
            };
            let indices = self.group_coordinates(function, arguments, coordinates, &mut used)?;
            factors.push(match (function.to_string().as_str(), indices.as_slice()) {
                ("se2", &[x, y, theta]) => GroupFactor::Se2 { x, y, theta },
                ("translation", &[q]) => GroupFactor::Translation(q),
                ("rotation", &[q]) => GroupFactor::Rotation(q),
                _ => return None,
            });
        }
        Some(Symmetry {
            factors,
            span: expr.first_span(),
        })
    }

    /// The coordinates a group factor acts on: known group, right arity,
    /// declared and not used by another factor.
    fn group_coordinates(
        &mut self,
        function: &proc_macro2::Ident,
        arguments: &[Value],
        coordinates: &[Variable],
        used: &mut Vec<usize>,
    ) -> Option<Vec<usize>> {
        let arity = match function.to_string().as_str() {
            "se2" => 3,
            "translation" | "rotation" => 1,
            other => {
                self.diagnostics.error(function.span(), format!("unknown symmetry group `{other}`: the groups are se2(x, y, theta), translation(q) and rotation(q)"));
                return None;
            }
        };
        if arguments.len() != arity {
            self.diagnostics.error(
                function.span(),
                format!(
                    "`{function}` acts on {arity} coordinate(s), found {}",
                    arguments.len()
                ),
            );
            return None;
        }
        let mut indices = Vec::with_capacity(arity);
        for argument in arguments {
            let found = match argument {
                Value::Expr(Expr::Name(ident)) => {
                    coordinates.iter().position(|c| *ident == c.declared.name)
                }
                _ => None,
            };
            match found {
                Some(index) if !used.contains(&index) => {
                    used.push(index);
                    indices.push(index);
                }
                Some(_) => {
                    self.diagnostics.error(
                        argument.span(),
                        "a coordinate appears twice in the symmetry group",
                    );
                    return None;
                }
                None => {
                    self.diagnostics.error(argument.span(), "a symmetry acts on coordinates: this is not one of the model's coordinates");
                    return None;
                }
            }
        }
        Some(indices)
    }
}

/// The terms of a sum, with the signs dropped.
fn top_level_terms<'a>(expr: &'a Expr, terms: &mut Vec<&'a Expr>) {
    match expr {
        Expr::Binary {
            operator: BinaryOperator::Add | BinaryOperator::Subtract,
            left,
            right,
            ..
        } => {
            top_level_terms(left, terms);
            top_level_terms(right, terms);
        }
        Expr::Negate { operand, .. } => top_level_terms(operand, terms),
        _ => terms.push(expr),
    }
}

/// The factors of a product.
fn product_factors<'a>(expr: &'a Expr, factors: &mut Vec<&'a Expr>) {
    match expr {
        Expr::Binary {
            operator: BinaryOperator::Multiply,
            left,
            right,
            ..
        } => {
            product_factors(left, factors);
            product_factors(right, factors);
        }
        _ => factors.push(expr),
    }
}

/// The span of the first `dot(...)` in an expression.
fn first_velocity_span(expr: &Expr) -> Option<Span> {
    match expr {
        Expr::Call { function, .. } if function == "dot" => Some(function.span()),
        Expr::Call { arguments, .. } => arguments.iter().find_map(value_velocity_span),
        Expr::Negate { operand, .. } | Expr::Field { base: operand, .. } => {
            first_velocity_span(operand)
        }
        Expr::Binary { left, right, .. } => {
            first_velocity_span(left).or_else(|| first_velocity_span(right))
        }
        Expr::Number { .. } | Expr::Name(_) => None,
    }
}

/// The span of the first `dot(...)` in an expression or list.
fn value_velocity_span(value: &Value) -> Option<Span> {
    match value {
        Value::Expr(expr) => first_velocity_span(expr),
        Value::List(list) => list
            .items
            .iter()
            .find_map(|item| value_velocity_span(item.value())),
    }
}

/// The size of the first leading block whose Cholesky pivot is not positive
/// (or not finite), if any.
fn failed_cholesky_minor(values: &[f64], n: usize) -> Option<usize> {
    let mut l = vec![0.0f64; n * n];
    for j in 0..n {
        let mut pivot = values[j * n + j];
        for k in 0..j {
            pivot -= l[j * n + k] * l[j * n + k];
        }
        if !(pivot > 0.0 && pivot.is_finite()) {
            return Some(j + 1);
        }
        let root = pivot.sqrt();
        l[j * n + j] = root;
        for i in j + 1..n {
            let mut sum = values[i * n + j];
            for k in 0..j {
                sum -= l[i * n + k] * l[j * n + k];
            }
            l[i * n + j] = sum / root;
        }
    }
    None
}
