//! The energies: the metric from the kinetic energy or a declared mass
//! matrix, positive definite; the potential free of velocities.

use super::mechanisms::MechanismParts;
use super::*;
use crate::model::{BodyMotion, EnergyExpressions, Mechanism};
use crate::sym::ExprMatrix;

impl Checker {
    // ----- energies ------------------------------------------------------

    /// `(T, g)` from whichever of `kinetic_energy`/`mass_matrix` is given.
    pub(super) fn metric(
        &mut self,
        sections: &Sections,
        coordinates: &[Variable],
        parameters: &[Parameter],
        mechanism: &Mechanism,
    ) -> Option<(RationalFunction, Matrix)> {
        let velocities: Vec<SymbolId> = coordinates
            .iter()
            .map(|c| self.store.velocity_of(c.symbol))
            .collect();
        let declared = if let Some(section) = sections.get("kinetic_energy") {
            Some((
                section,
                self.metric_of_kinetic_energy(section, &velocities)?,
            ))
        } else if let Some(section) = sections.get("mass_matrix") {
            let g = self.declared_mass_matrix(section, coordinates.len())?;
            let t = self.quadratic_form(&g, &velocities);
            Some((section, (t, g)))
        } else {
            None
        };
        let bodies = self.hessian(&mechanism.kinetic_energy, &velocities)?;
        let atoms = self.store.atoms().clone();
        let (section, energy, g) = match declared {
            Some((section, (t, g))) => (
                section,
                t.add(&mechanism.kinetic_energy, &atoms),
                g.add(&bodies, &atoms).ok()?,
            ),
            None => (
                sections.get("bodies")?,
                mechanism.kinetic_energy.clone(),
                bodies,
            ),
        };
        // Sampling needs every coordinate and parameter value: skip it after earlier errors.
        if self.diagnostics.is_empty() {
            self.rule_positive_definite(&g, section.key.span(), coordinates, parameters);
        }
        Some((energy, g))
    }

    /// `T`, `V` and `g` as expressions: each normal form written out, or
    /// when it is large ([`crate::sym::Store::compact_expression`]) the
    /// declared part written out plus the bodies' part as it was derived:
    /// their energies, and for `g` their Kane form
    /// ([`crate::model::BodyMotion::mass_matrix`]).
    pub(super) fn energy_expressions(
        &mut self,
        (kinetic, g): (&RationalFunction, &Matrix),
        potential: &RationalFunction,
        mechanism: &MechanismParts,
        velocities: &[SymbolId],
    ) -> Option<EnergyExpressions> {
        let (bodies_kinetic, bodies_potential) = mechanism.energies_derived_as;
        let declared_kinetic = self.declared_part(kinetic, &mechanism.mechanism.kinetic_energy);
        let declared_potential =
            self.declared_part(potential, &mechanism.mechanism.potential_energy);
        let kinetic_derived_as = self.store.add2(declared_kinetic, bodies_kinetic);
        let potential_derived_as = self.store.add2(declared_potential, bodies_potential);
        let mass_matrix = if mechanism.motions.is_empty() {
            ExprMatrix::of(g, &mut self.store)
        } else {
            self.metric_derived_as(g, declared_kinetic, &mechanism.motions, velocities)?
        };
        Some(EnergyExpressions {
            kinetic: self.store.compact_expression(kinetic, kinetic_derived_as),
            potential: self
                .store
                .compact_expression(potential, potential_derived_as),
            mass_matrix,
            declared_kinetic,
            bodies: mechanism.motions.clone(),
        })
    }

    /// `g_ij` written out, or when large as `d^2 T / d qdot_i d qdot_j` of
    /// the declared `T` plus the bodies' Kane form.
    fn metric_derived_as(
        &mut self,
        g: &Matrix,
        declared_kinetic: ExprId,
        bodies: &[BodyMotion],
        velocities: &[SymbolId],
    ) -> Option<ExprMatrix> {
        let rates: Vec<ExprId> = velocities
            .iter()
            .map(|&v| self.store.derivative(declared_kinetic, v))
            .collect();
        let n = velocities.len();
        let mut entries = vec![self.store.integer(0); n * n];
        for (j, &vj) in velocities.iter().enumerate() {
            for (i, declared) in self.store.derivatives(&rates, vj).into_iter().enumerate() {
                entries[i * n + j] = declared;
            }
        }
        for body in bodies {
            let body_entries = body.mass_matrix(&mut self.store, velocities);
            for (entry, body_entry) in entries.iter_mut().zip(body_entries) {
                *entry = self.store.add2(*entry, body_entry);
            }
        }
        for (index, entry) in entries.iter_mut().enumerate() {
            *entry = self
                .store
                .compact_expression(g.get(index / n, index % n), *entry);
        }
        ExprMatrix::new(n, n, entries).ok()
    }

    /// The declared part of an energy, `total - bodies`, written out.
    fn declared_part(&mut self, total: &RationalFunction, bodies: &RationalFunction) -> ExprId {
        let declared = total.sub(bodies, self.store.atoms());
        self.store.expression_of(&declared)
    }

    pub(super) fn metric_of_kinetic_energy(
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
        let g = self.hessian(&energy, velocities)?;
        Some((energy, g))
    }

    /// `g_ij = d^2 T / d qdot_i d qdot_j`.
    fn hessian(&mut self, energy: &RationalFunction, velocities: &[SymbolId]) -> Option<Matrix> {
        let mut entries = Vec::with_capacity(velocities.len().pow(2));
        for &vi in velocities {
            let first = self.store.derivative_of_normal(energy, vi).ok()?;
            for &vj in velocities {
                entries.push(self.store.derivative_of_normal(&first, vj).ok()?);
            }
        }
        Matrix::new(velocities.len(), velocities.len(), entries).ok()
    }

    /// `T = 1/2 qdot^T g qdot`.
    pub(super) fn quadratic_form(
        &mut self,
        g: &Matrix,
        velocities: &[SymbolId],
    ) -> RationalFunction {
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
        sum.scale(&Rational::HALF)
    }

    /// A declared mass matrix is n x n, free of velocities, and symmetric.
    pub(super) fn declared_mass_matrix(&mut self, section: &Section, n: usize) -> Option<Matrix> {
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
    pub(super) fn row_of_expressions<'a>(
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
    pub(super) fn rule_symmetric(&mut self, g: &Matrix, spans: &[Span]) -> bool {
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
    pub(super) fn rule_positive_definite(
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

    /// `V`: the declared potential (default 0) plus the bodies' in the gravity field.
    pub(super) fn potential(
        &mut self,
        section: Option<&&Section>,
        mechanism: &Mechanism,
    ) -> Option<RationalFunction> {
        let declared = match section {
            Some(section) => {
                let expr = self.expression(section)?;
                self.velocity_free(
                    expr,
                    "the potential energy depends on the configuration only: no velocities",
                )?
            }
            None => RationalFunction::zero(),
        };
        Some(declared.add(&mechanism.potential_energy, self.store.atoms()))
    }

    /// An expression free of velocities, in normal form.
    pub(super) fn velocity_free(&mut self, expr: &Expr, rule: &str) -> Option<RationalFunction> {
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
    pub(super) fn rule_velocity_degree(
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
    pub(super) fn velocity_degrees(&mut self, form: &RationalFunction) -> Option<Vec<u32>> {
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
    pub(super) fn offending_term(&mut self, expr: &Expr, degree: u32) -> Option<Span> {
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
}

/// The terms of a sum, with the signs dropped.
pub(super) fn top_level_terms<'a>(expr: &'a Expr, terms: &mut Vec<&'a Expr>) {
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

/// The span of the first `dot(...)` in an expression.
pub(super) fn first_velocity_span(expr: &Expr) -> Option<Span> {
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
pub(super) fn value_velocity_span(value: &Value) -> Option<Span> {
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
pub(super) fn failed_cholesky_minor(values: &[f64], n: usize) -> Option<usize> {
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
