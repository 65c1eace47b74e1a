//! Constraint analysis (Moore, "Nonholonomic Constraints"; MATH.md section 1).
//!
//! **Basis of D.** With `A(q) qdot = 0` (c rows), choose c dependent speeds
//! `u_r` (pivot columns of A) and write the independent ones `u_s`; then
//! `u_r = A_n u_s` with `A_n = -A_r^-1 A_s`, and the columns of `[I; A_n]`
//! (rows permuted back to the coordinates' order) are k = n - c vector fields
//! `X_1..X_k` spanning `D = ker A`. The pivots are chosen at the model's
//! default configuration (every coordinate 0, parameters at their defaults):
//! row by row, the column with the largest value there, so the pivots do not
//! vanish at the defaults and the basis is regular near them. When A loses
//! rank at the defaults (a row such as `(1 + x^2)(y xdot + x ydot)` vanishes
//! at q = 0), no choice is regular there; the pivots are then chosen by exact
//! elimination instead (the first column with a non-zero entry), which is
//! regular at almost every configuration.
//!
//! **Integrability (Frobenius).** D is integrable, i.e. the constraints are
//! holonomic in disguise, iff it is involutive: every Lie bracket
//! `[X_i, X_j] = (dX_j/dq) X_i - (dX_i/dq) X_j` of the basis lies in D again,
//! `A [X_i, X_j] = 0` (Frobenius' theorem; MATH.md 1.2; Bloch,
//! *Nonholonomic Mechanics and Control*, 2003). The test is exact: the products are normal forms
//! and each entry is decided by [`RationalFunction::is_zero`].
//!
//! **Growth vector.** With `D^1 = D` and `D^{j+1} = D^j + [D, D^j]`, the
//! exact generic ranks `(rank D^1, rank D^2, ...)` until they stop growing
//! (generic: at almost every configuration; a rank that drops on a thin set,
//! such as the snakeboard's basis at `phi = +-pi/2`, is not seen).
//! Each level brackets the basis fields with the fields the previous level
//! added (enough, since `[X, f Y] = f [X, Y] + X(f) Y`). When the growth
//! reaches n the constraints are completely nonholonomic and every
//! configuration is reachable (Chow's theorem).
//!
//! **Large models.** The exact basis grows fast with the size of a chain
//! (for N wheeled links, entries of `2 * 3^(N-2)` terms), and the brackets
//! of the growth vector faster still. Each exact step is attempted on a
//! nested derivation budget ([`crate::sym::Store::attempt`]):
//! [`EXACT_BASIS_PRODUCTS`] for the basis, [`EXACT_ANALYSIS_PRODUCTS`] for
//! Frobenius and the growth vector. Beyond them the basis is kept
//! structured (the elimination written out as expressions,
//! [`crate::sym::ExprMatrix`]) and the analysis is decided by evaluation
//! modulo a prime at random points ([`crate::sym::modular`]): a bracket
//! with `A [X_i, X_j] != 0` there proves D not integrable, and each rank at
//! the point is a proved lower bound of the generic rank; "integrable" and
//! the equality of the ranks hold with probability above `1 - 1e-15`
//! (Schwartz-Zippel). The brackets of the growth vector are then built as
//! expressions within [`STRUCTURED_GROWTH_NODES`] new nodes; a growth vector
//! cut short there is reported as such ([`ConstraintAnalysis::growth_complete`]).
//!
//! **Moore's test.** Moore ("Nonholonomic Constraints") checks each row for
//! exactness, `d a_i / d q_j = d a_j / d q_i`; a row that passes is the
//! differential of a function and is holonomic. The test misses integrating
//! factors (`(1 + x^2)(y xdot + x ydot) = 0` is holonomic but not exact), so
//! it is reported alongside Frobenius and decides nothing.

use crate::diagnostic::{Diagnostic, Diagnostics};
use crate::model::Model;
use crate::sym::modular::{self, Outside, Point, Values};
use crate::sym::{ExprId, ExprMatrix, Matrix, MatrixError, RationalFunction, SymbolId};

/// The term products the exact basis of D may take.
pub const EXACT_BASIS_PRODUCTS: u64 = 1_000_000;
/// The term products the exact Frobenius test, and separately the exact
/// growth vector, may take.
pub const EXACT_ANALYSIS_PRODUCTS: u64 = 2_000_000;
/// The most expression nodes the brackets of a structured growth vector
/// may add to the store.
pub const STRUCTURED_GROWTH_NODES: usize = 400_000;

/// A vector field on the coordinates: its n components.
type Field = Vec<RationalFunction>;

/// What kind of constraints a model has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Classification {
    /// No constraints: D is the whole tangent space.
    Unconstrained,
    /// D is integrable: the constraints confine the motion to a
    /// submanifold of dimension k (Frobenius).
    Holonomic,
    /// D is not integrable, but its growth stops short of n: the motion
    /// stays on submanifolds of dimension `growth.last()` (some combination
    /// of the rows is holonomic, as for the differential drive).
    Nonholonomic,
    /// D is not integrable; its growth was cut short by the budget before
    /// it reached n or stopped, so complete nonholonomy is not decided.
    NonholonomicGrowthOpen,
    /// The growth of D reaches n: every configuration is reachable (Chow).
    CompletelyNonholonomic,
}

impl Classification {
    /// The classification in words, as the report prints it.
    pub fn describe(self) -> &'static str {
        match self {
            Classification::Unconstrained => "unconstrained",
            Classification::Holonomic => "holonomic",
            Classification::Nonholonomic => "nonholonomic",
            Classification::NonholonomicGrowthOpen => {
                "nonholonomic (complete nonholonomy not decided: the growth vector was cut short)"
            }
            Classification::CompletelyNonholonomic => "completely nonholonomic",
        }
    }
}

/// How a fact of the analysis was decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Exactly, on normal forms.
    NormalForm,
    /// By evaluation modulo a prime at random points (see the module
    /// documentation): proved where it finds a non-zero value or a rank,
    /// probable (above `1 - 1e-15`) where it finds zeros.
    Modular,
}

impl Method {
    /// The method in words, as the report prints it.
    pub fn describe(self) -> &'static str {
        match self {
            Method::NormalForm => "exactly, on normal forms",
            Method::Modular => {
                "by evaluation modulo 2^61 - 1 at random points (non-zero values and ranks \
                 proved; zeros probable, error below 1e-15)"
            }
        }
    }
}

/// Everything the constraint analysis finds.
#[derive(Clone, Debug)]
pub struct ConstraintAnalysis {
    /// The basis of D.
    pub basis: DistributionBasis,
    /// `(rank D^1, rank D^2, ...)`, strictly increasing, the first entry k.
    pub growth: Vec<usize>,
    /// False when the growth vector was cut short by the budget: later
    /// levels were not computed.
    pub growth_complete: bool,
    /// How the growth vector was decided.
    pub growth_method: Method,
    /// Frobenius: every bracket of the basis lies in D.
    pub integrable: bool,
    /// How integrability was decided.
    pub integrability_method: Method,
    /// The classification that follows from `integrable` and `growth`.
    pub classification: Classification,
    /// Moore's test, per constraint row in declared order: is the row exact?
    pub exact_rows: Vec<bool>,
}

/// Why the analysis failed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum AnalysisError {
    /// The engine failed on a matrix.
    #[error(transparent)]
    Matrix(#[from] MatrixError),
    /// The model is too large for normal forms and its expressions are
    /// outside the class evaluated modulo a prime.
    #[error("the constraint analysis is too large for normal forms, and {0}")]
    Undecided(#[from] Outside),
}

/// Analyses the constraints; with `#[deny_holonomic]`, integrable
/// constraints are an error spanned on the first constraint's name.
pub fn analyse(model: &mut Model) -> Result<ConstraintAnalysis, Diagnostics> {
    let analysis =
        derive_analysis(model).map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    deny_holonomic(model, &analysis)?;
    Ok(analysis)
}

fn derive_analysis(model: &mut Model) -> Result<ConstraintAnalysis, AnalysisError> {
    let basis = distribution_basis(model)?;
    let (integrable, integrability_method) = integrability(model, &basis)?;
    let (growth, growth_complete, growth_method) = growth(model, &basis)?;
    let classification = classify(model, integrable, &growth, growth_complete);
    let exact_rows = exact_rows(model)?;
    Ok(ConstraintAnalysis {
        basis,
        growth,
        growth_complete,
        growth_method,
        integrable,
        integrability_method,
        classification,
        exact_rows,
    })
}

/// Frobenius, exactly when the exact basis and the brackets fit their
/// budgets, else at random points.
fn integrability(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<(bool, Method), AnalysisError> {
    if let Some(fields) = &basis.fields {
        let fields = columns_of(fields);
        let exact = model.attempt(EXACT_ANALYSIS_PRODUCTS, |model| {
            is_involutive(model, &fields)
        });
        if let Some(integrable) = exact {
            return Ok((integrable?, Method::NormalForm));
        }
    }
    Ok((is_involutive_at_points(model, basis)?, Method::Modular))
}

/// The growth vector, exactly when it fits its budget, else at a random
/// point; `(growth, complete, method)`.
fn growth(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<(Vec<usize>, bool, Method), AnalysisError> {
    if let Some(fields) = &basis.fields {
        let fields = columns_of(fields);
        let exact = model.attempt(EXACT_ANALYSIS_PRODUCTS, |model| {
            growth_vector(model, &fields)
        });
        if let Some(growth) = exact {
            return Ok((growth?, true, Method::NormalForm));
        }
    }
    let (growth, complete) = growth_vector_at_point(model, basis)?;
    Ok((growth, complete, Method::Modular))
}

/// `#[deny_holonomic]` and integrable constraints: an error on the first
/// constraint's name. A model without constraints has nothing to deny.
fn deny_holonomic(model: &Model, analysis: &ConstraintAnalysis) -> Result<(), Diagnostics> {
    let Some(first) = model.constraints.first() else {
        return Ok(());
    };
    if model.options.deny_holonomic && analysis.integrable {
        let message = "the constraints are integrable (holonomic: every Lie bracket of D \
                       lies in D, Frobenius), and `#[deny_holonomic]` forbids that";
        return Err(Diagnostic::new(first.span, message).into());
    }
    Ok(())
}

fn classify(model: &Model, integrable: bool, growth: &[usize], complete: bool) -> Classification {
    if model.c() == 0 {
        Classification::Unconstrained
    } else if integrable {
        Classification::Holonomic
    } else if growth.last() == Some(&model.n()) {
        Classification::CompletelyNonholonomic
    } else if complete {
        Classification::Nonholonomic
    } else {
        Classification::NonholonomicGrowthOpen
    }
}

/// Frobenius: `A [X_i, X_j] = 0` exactly for every pair of basis fields.
fn is_involutive(model: &mut Model, fields: &[Field]) -> Result<bool, MatrixError> {
    for (i, x) in fields.iter().enumerate() {
        for y in &fields[i + 1..] {
            let bracket = bracket(model, x, y)?;
            let atoms = model.store.atoms().clone();
            let column = Matrix::new(bracket.len(), 1, bracket)?;
            if !model.constraint_matrix.mul(&column, &atoms)?.is_zero() {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// The ranks of `D^1, D^2, ...` until they stop growing (or reach n).
fn growth_vector(model: &mut Model, basis: &[Field]) -> Result<Vec<usize>, MatrixError> {
    let mut span = Vec::new();
    let mut newest = independent_additions(model, &mut span, basis.to_vec())?;
    let mut growth = vec![span.len()];
    while span.len() < model.n() && !newest.is_empty() {
        let brackets = brackets_with(model, basis, &newest)?;
        newest = independent_additions(model, &mut span, brackets)?;
        if newest.is_empty() {
            break;
        }
        growth.push(span.len());
    }
    Ok(growth)
}

/// Every `[X, Y]` with X a basis field and Y one of `newest`.
fn brackets_with(
    model: &mut Model,
    basis: &[Field],
    newest: &[Field],
) -> Result<Vec<Field>, MatrixError> {
    let mut brackets = Vec::with_capacity(basis.len() * newest.len());
    for x in basis {
        for y in newest {
            brackets.push(bracket(model, x, y)?);
        }
    }
    Ok(brackets)
}

/// Moves into `span` each candidate that raises its exact rank; returns those.
fn independent_additions(
    model: &Model,
    span: &mut Vec<Field>,
    candidates: Vec<Field>,
) -> Result<Vec<Field>, MatrixError> {
    let mut added = Vec::new();
    for candidate in candidates {
        span.push(candidate);
        if rank_of_fields(model, span)? == span.len() {
            added.push(span[span.len() - 1].clone());
        } else {
            span.pop();
        }
    }
    Ok(added)
}

/// The exact generic rank of the fields (as columns of an n x m matrix).
fn rank_of_fields(model: &Model, fields: &[Field]) -> Result<usize, MatrixError> {
    let n = model.n();
    let mut matrix = Matrix::zeros(n, fields.len());
    for (j, field) in fields.iter().enumerate() {
        for (i, entry) in field.iter().enumerate() {
            matrix.set(i, j, entry.clone());
        }
    }
    Ok(matrix.rank(model.store.atoms()))
}

fn bracket(
    model: &mut Model,
    x: &[RationalFunction],
    y: &[RationalFunction],
) -> Result<Field, MatrixError> {
    let coordinates = model.coordinate_symbols();
    model.store.lie_bracket(x, y, &coordinates)
}

/// Frobenius at random points: `A [X_i, X_j]` evaluated modulo a prime at
/// two points; a non-zero value proves D not integrable.
fn is_involutive_at_points(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<bool, AnalysisError> {
    let fields = expression_columns(&basis.field_expressions);
    let rows = ExprMatrix::of(&model.constraint_matrix, &mut model.store);
    let mut products = Vec::new();
    for (i, x) in fields.iter().enumerate() {
        for y in &fields[i + 1..] {
            let bracket = ExprMatrix::column(expression_bracket(model, x, y));
            products.extend_from_slice(rows.mul(&bracket, &mut model.store)?.entries());
        }
    }
    for seed in modular::SEEDS {
        let values = Values::at(Point::new(seed)).of(&model.store, &products)?;
        if values.iter().any(|&v| v != 0) {
            return Ok(false);
        }
    }
    Ok(true)
}

/// The growth vector from ranks at a random point, with the brackets built
/// as expressions; `(growth, complete)`, incomplete when the brackets of
/// the next level would exceed [`STRUCTURED_GROWTH_NODES`] new nodes.
fn growth_vector_at_point(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<(Vec<usize>, bool), AnalysisError> {
    let start = model.store.len();
    let fields = expression_columns(&basis.field_expressions);
    let mut span = SpanAtPoint::new(model.n(), Point::new(modular::SEEDS[0]));
    let mut newest = span.additions(model, fields.clone())?;
    let mut growth = vec![span.rank()];
    while span.rank() < model.n() && !newest.is_empty() {
        let mut brackets = Vec::with_capacity(fields.len() * newest.len());
        for x in &fields {
            for y in &newest {
                if model.store.len() - start > STRUCTURED_GROWTH_NODES {
                    return Ok((growth, false));
                }
                brackets.push(expression_bracket(model, x, y));
            }
        }
        newest = span.additions(model, brackets)?;
        if newest.is_empty() {
            break;
        }
        growth.push(span.rank());
    }
    Ok((growth, true))
}

/// Fields kept for their values at a point, which are independent there.
struct SpanAtPoint {
    n: usize,
    /// The kept fields' values, row after row.
    values: Vec<u64>,
    /// The values of every node evaluated at the point.
    at_point: Values,
}

impl SpanAtPoint {
    fn new(n: usize, point: Point) -> SpanAtPoint {
        SpanAtPoint {
            n,
            values: Vec::new(),
            at_point: Values::at(point),
        }
    }

    fn rank(&self) -> usize {
        self.values.len() / self.n.max(1)
    }

    /// Keeps each candidate whose value at `point` raises the rank; returns those.
    fn additions(
        &mut self,
        model: &Model,
        candidates: Vec<Vec<ExprId>>,
    ) -> Result<Vec<Vec<ExprId>>, Outside> {
        let mut added = Vec::new();
        for candidate in candidates {
            let values = self.at_point.of(&model.store, &candidate)?;
            let before = self.values.len();
            self.values.extend_from_slice(&values);
            let fields = self.rank();
            if modular::rank(self.values.clone(), fields, self.n) == fields {
                added.push(candidate);
            } else {
                self.values.truncate(before);
            }
        }
        Ok(added)
    }
}

fn expression_bracket(model: &mut Model, x: &[ExprId], y: &[ExprId]) -> Vec<ExprId> {
    let coordinates = model.coordinate_symbols();
    model.store.lie_bracket_of_expressions(x, y, &coordinates)
}

fn expression_columns(matrix: &ExprMatrix) -> Vec<Vec<ExprId>> {
    (0..matrix.columns())
        .map(|j| matrix.column_entries(j))
        .collect()
}

fn columns_of(matrix: &Matrix) -> Vec<Field> {
    (0..matrix.columns())
        .map(|j| {
            (0..matrix.rows())
                .map(|i| matrix.get(i, j).clone())
                .collect()
        })
        .collect()
}

/// Moore's mixed-partials test, per row: `d a_i / d q_j = d a_j / d q_i`.
fn exact_rows(model: &mut Model) -> Result<Vec<bool>, MatrixError> {
    let coordinates = model.coordinate_symbols();
    let rows = model.constraint_matrix.rows();
    let mut exact = Vec::with_capacity(rows);
    for row in 0..rows {
        let entries: Field = (0..model.n())
            .map(|j| model.constraint_matrix.get(row, j).clone())
            .collect();
        let jacobian = model.store.jacobian(&entries, &coordinates)?;
        let asymmetry = jacobian.sub(&jacobian.transpose(), model.store.atoms())?;
        exact.push(asymmetry.is_zero());
    }
    Ok(exact)
}

/// A basis of the constraint distribution D and how it was chosen.
#[derive(Clone, Debug)]
pub struct DistributionBasis {
    /// `X`, n x k, as expressions: column j is the vector field `X_j`, the
    /// dependent speeds written as the elimination computes them.
    pub field_expressions: ExprMatrix,
    /// `X` in exact normal form, when it fits [`EXACT_BASIS_PRODUCTS`].
    pub fields: Option<Matrix>,
    /// The coordinates whose speeds are dependent (pivot columns), in row order.
    pub dependent: Vec<usize>,
    /// The coordinates whose speeds are independent, in order: `X_j` has a 1
    /// at `independent[j]` and 0 at the other independent speeds.
    pub independent: Vec<usize>,
}

/// Chooses the dependent speeds at the defaults and solves for a basis of
/// D: as expressions always, in normal form within [`EXACT_BASIS_PRODUCTS`].
pub fn distribution_basis(model: &mut Model) -> Result<DistributionBasis, MatrixError> {
    let n = model.n();
    let dependent = pivot_columns(model);
    let independent: Vec<usize> = (0..n).filter(|j| !dependent.contains(j)).collect();
    let a = ExprMatrix::of(&model.constraint_matrix, &mut model.store);
    let (a_r, a_s) = (
        expression_columns_at(&a, &dependent, &mut model.store),
        expression_columns_at(&a, &independent, &mut model.store),
    );
    let solved = model.store.solve_in_order(&a_r, &a_s)?;
    let minus_one = model.store.integer(-1);
    let a_n = solved.scale(minus_one, &mut model.store);
    let mut field_expressions = ExprMatrix::zeros(&mut model.store, n, independent.len());
    let one = model.store.integer(1);
    for (k, &j) in independent.iter().enumerate() {
        field_expressions.set(j, k, one);
    }
    for (row, &j) in dependent.iter().enumerate() {
        for k in 0..independent.len() {
            field_expressions.set(j, k, a_n.get(row, k));
        }
    }
    let exact_a = &model.constraint_matrix;
    let fields = model
        .store
        .attempt(EXACT_BASIS_PRODUCTS, |store| {
            exact_fields(exact_a, &dependent, &independent, store.atoms())
        })
        .transpose()?;
    Ok(DistributionBasis {
        field_expressions,
        fields,
        dependent,
        independent,
    })
}

/// The columns `indices` of `a`, in that order.
fn expression_columns_at(
    a: &ExprMatrix,
    indices: &[usize],
    store: &mut crate::sym::Store,
) -> ExprMatrix {
    let mut columns = ExprMatrix::zeros(store, a.rows(), indices.len());
    for i in 0..a.rows() {
        for (k, &j) in indices.iter().enumerate() {
            columns.set(i, k, a.get(i, j));
        }
    }
    columns
}

/// `X = [I; -A_r^-1 A_s]` (rows permuted back) in normal form.
fn exact_fields(
    a: &Matrix,
    dependent: &[usize],
    independent: &[usize],
    atoms: &crate::sym::Atoms,
) -> Result<Matrix, MatrixError> {
    let c = a.rows();
    let columns = |indices: &[usize]| {
        let mut m = Matrix::zeros(c, indices.len());
        for i in 0..c {
            for (k, &j) in indices.iter().enumerate() {
                m.set(i, k, a.get(i, j).clone());
            }
        }
        m
    };
    let a_n = columns(dependent)
        .solve(&columns(independent), atoms)?
        .neg();
    let mut fields = Matrix::zeros(a.columns(), independent.len());
    for (k, &j) in independent.iter().enumerate() {
        fields.set(j, k, RationalFunction::one());
    }
    for (row, &j) in dependent.iter().enumerate() {
        for k in 0..independent.len() {
            fields.set(j, k, a_n.get(row, k).clone());
        }
    }
    Ok(fields)
}

/// The dependent speeds: pivots at the defaults when A has full rank there,
/// generic pivots otherwise.
fn pivot_columns(model: &mut Model) -> Vec<usize> {
    pivots_at_defaults(model).unwrap_or_else(|| generic_pivots(model))
}

/// A pivot smaller than this, relative to A's largest entry at the defaults,
/// counts as vanishing there (the choice only needs to be regular; the solve
/// that follows is exact).
const VANISHING_PIVOT: f64 = 1e-9;

/// Gaussian elimination with partial pivoting on A at the defaults: the
/// pivot column of each row is the one of largest magnitude there. `None`
/// when a pivot vanishes (A is singular at the defaults).
fn pivots_at_defaults(model: &mut Model) -> Option<Vec<usize>> {
    let (n, c) = (model.n(), model.c());
    let defaults = default_point(model);
    let mut values = model
        .constraint_matrix
        .evaluate(&mut model.store, &|s| defaults(s));
    let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut pivots: Vec<usize> = Vec::with_capacity(c);
    for row in 0..c {
        let column = (0..n).filter(|j| !pivots.contains(j)).max_by(|&a, &b| {
            values[row * n + a]
                .abs()
                .total_cmp(&values[row * n + b].abs())
        })?;
        let pivot = values[row * n + column];
        let regular = pivot.abs() > VANISHING_PIVOT * scale;
        if !regular {
            return None;
        }
        for below in row + 1..c {
            let factor = values[below * n + column] / pivot;
            for j in 0..n {
                values[below * n + j] -= factor * values[row * n + j];
            }
        }
        pivots.push(column);
    }
    Some(pivots)
}

/// Exact elimination on A: the pivot of each row is its first column with a
/// non-zero entry (A has full generic rank, checked by `model::check`).
fn generic_pivots(model: &Model) -> Vec<usize> {
    let (n, c) = (model.n(), model.c());
    let atoms = model.store.atoms();
    let mut rows: Vec<Field> = (0..c)
        .map(|i| {
            (0..n)
                .map(|j| model.constraint_matrix.get(i, j).clone())
                .collect()
        })
        .collect();
    let mut pivots = Vec::with_capacity(c);
    for row in 0..c {
        let Some(column) = (0..n).find(|&j| !pivots.contains(&j) && !rows[row][j].is_zero()) else {
            break;
        };
        let pivot_row = rows[row].clone();
        for below in &mut rows[row + 1..] {
            let Some(factor) = below[column].div(&pivot_row[column], atoms) else {
                continue;
            };
            for (entry, p) in below.iter_mut().zip(&pivot_row) {
                *entry = entry.sub(&factor.mul(p, atoms), atoms);
            }
        }
        pivots.push(column);
    }
    pivots
}

/// The default configuration: coordinates 0, parameters at their defaults.
pub fn default_point(model: &Model) -> impl Fn(SymbolId) -> f64 + use<> {
    let parameters: Vec<(SymbolId, f64)> = model
        .parameters
        .iter()
        .map(|p| (p.variable.symbol, p.default.to_f64()))
        .collect();
    move |s| {
        parameters
            .iter()
            .find(|(p, _)| *p == s)
            .map_or(0.0, |(_, v)| *v)
    }
}

#[cfg(test)]
mod tests;
