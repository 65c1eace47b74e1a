//! Constraint rows: declared (linear and homogeneous in the velocities) or
//! the annihilator of a declared distribution; independent.

use super::mechanisms::MechanismParts;
use super::*;
use crate::sym::ExprMatrix;

/// The term products the exact rank confirming a dependent row may take.
const EXACT_RANK_PRODUCTS: u64 = 2_000_000;

impl Checker {
    // ----- constraints ---------------------------------------------------

    /// `(names, A, A as expressions)`: the declared rows (or a
    /// distribution's annihilator), then the mechanism's contact and
    /// holonomic rows; independent together.
    pub(super) fn constraints(
        &mut self,
        sections: &Sections,
        n: usize,
        mechanism: &MechanismParts,
    ) -> Option<(Vec<Declared>, Matrix, ExprMatrix)> {
        let (mut names, declared) = self.declared_constraints(sections, n)?;
        let mut entries = declared.entries().to_vec();
        let mut expressions: Vec<ExprId> = entries
            .iter()
            .map(|entry| self.store.expression_of(entry))
            .collect();
        for (declared, (coefficients, derived_as)) in mechanism.names.iter().zip(&mechanism.rows) {
            if !self.rule_unique_in_section(&names, &declared.name, declared.span) {
                return None;
            }
            expressions.extend(self.entry_expressions(coefficients, *derived_as));
            entries.extend(coefficients.iter().cloned());
            names.push(declared.clone());
        }
        let a = Matrix::new(names.len(), n, entries).ok()?;
        let a_expressions = ExprMatrix::new(names.len(), n, expressions).ok()?;
        self.rule_independent_rows(&a, &names, "constraint")
            .then_some((names, a, a_expressions))
    }

    /// The entries of a derived row as expressions
    /// ([`Store::compact_expression`]): each normal form written out, or the
    /// derivative of the expression the row was derived as in that velocity.
    fn entry_expressions(
        &mut self,
        entries: &[RationalFunction],
        derived_as: ExprId,
    ) -> Vec<ExprId> {
        let velocities = self.velocity_symbols();
        entries
            .iter()
            .zip(velocities)
            .map(|(entry, velocity)| {
                let derivative = self.store.derivative(derived_as, velocity);
                self.store.compact_expression(entry, derivative)
            })
            .collect()
    }

    /// The coefficients of a linear form in the velocities, in coordinate order.
    fn velocity_coefficients(&mut self, form: &RationalFunction) -> Option<Vec<RationalFunction>> {
        let velocities: Vec<SymbolId> = self.velocity_symbols();
        velocities
            .into_iter()
            .map(|v| self.store.derivative_of_normal(form, v).ok())
            .collect()
    }

    /// The rows of `constraints` or `distribution` (none: c = 0).
    fn declared_constraints(
        &mut self,
        sections: &Sections,
        n: usize,
    ) -> Option<(Vec<Declared>, Matrix)> {
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
        Some((names, a))
    }

    /// One constraint: linear and homogeneous in the velocities; its row of A.
    pub(super) fn constraint_row(&mut self, expr: &Expr) -> Option<Vec<RationalFunction>> {
        let id = self.lower(expr)?;
        let form = self.normal(id, expr.first_span())?;
        if !self.rule_velocity_degree(&form, expr, 1, "a constraint must be linear and homogeneous in the velocities (every term exactly one velocity times a function of the configuration)") {
            return None;
        }
        self.velocity_coefficients(&form)
    }

    pub(super) fn velocity_symbols(&self) -> Vec<SymbolId> {
        self.store
            .symbols()
            .filter(|(_, s)| matches!(s.kind, SymbolKind::Velocity(_)))
            .map(|(id, _)| id)
            .collect()
    }

    /// Rows of A (or of a momentum basis) are independent: each row adds rank.
    pub(super) fn rule_independent_rows(
        &mut self,
        m: &Matrix,
        names: &[Declared],
        what: &str,
    ) -> bool {
        let Some(dependent) = self.first_dependent_row(m) else {
            return true;
        };
        self.diagnostics.error(
            names[dependent].span,
            format!(
                "{what} `{}` depends on the ones before it: the rows must be linearly independent",
                names[dependent].name
            ),
        );
        false
    }

    /// The first row of `m` in the span of the rows before it. Ranks at
    /// random points modulo a prime ([`crate::sym::modular`]) prove the
    /// rows before it independent; the row they find no rank for is
    /// confirmed by the exact rank within [`EXACT_RANK_PRODUCTS`] (beyond it,
    /// by two random points: wrong with probability below `1e-15`).
    fn first_dependent_row(&mut self, m: &Matrix) -> Option<usize> {
        let proved_full = self
            .store
            .prefixes_of_full_rank_at_points(m)
            .unwrap_or_else(|_| vec![false; m.rows()]);
        (0..m.rows()).filter(|&i| !proved_full[i]).find(|&i| {
            let prefix = Matrix::new(
                i + 1,
                m.columns(),
                m.entries()[..(i + 1) * m.columns()].to_vec(),
            );
            let Ok(prefix) = prefix else { return false };
            self.store
                .attempt(EXACT_RANK_PRODUCTS, |store| prefix.rank(store.atoms()))
                .is_none_or(|rank| rank < i + 1)
        })
    }

    /// A distribution: k independent vector fields of length n, no velocities;
    /// the constraint rows are a basis of its annihilator.
    pub(super) fn annihilator_of_distribution(
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
}
