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
//! or reach `n - h` (`h` holonomic constraints `f = 0`: every `df`
//! annihilates D and, `ker df` being integrable, its brackets)
//! (generic: at almost every configuration; a rank that drops on a thin set,
//! such as the snakeboard's basis at `phi = +-pi/2`, is not seen).
//! Each level brackets the basis fields with the fields the previous level
//! added (enough, since `[X, f Y] = f [X, Y] + X(f) Y`). When the growth
//! reaches `n - h` the constraints are completely nonholonomic and every
//! configuration on the surface `f = 0` is reachable (Chow's theorem on
//! that surface; `h = 0`, the whole space, without holonomic constraints).
//!
//! **Large models.** The exact basis grows fast with the size of a chain
//! (for N wheeled links, entries of `2 * 3^(N-2)` terms), and the brackets
//! of the growth vector faster still. Each exact step is attempted on a
//! nested derivation budget ([`crate::sym::Context::attempt`]):
//! [`EXACT_BASIS_PRODUCTS`] for the basis, [`EXACT_ANALYSIS_PRODUCTS`] for
//! Frobenius and the growth vector. Beyond them the basis is kept
//! structured (the elimination written out as expressions,
//! [`crate::sym::Matrix`] of expressions) and the analysis is decided by evaluation
//! modulo a prime at random points ([`crate::sym::modular`]): a bracket
//! with `A [X_i, X_j] != 0` there proves D not integrable, and each rank at
//! the point is a proved lower bound of the generic rank; "integrable" and
//! the equality of the ranks hold with probability above `1 - 1e-15`
//! (Schwartz-Zippel). The brackets of the growth vector are then built as
//! expressions within [`STRUCTURED_GROWTH_NODES`] new nodes; a growth vector
//! cut short there is reported as such ([`ConstraintAnalysis::growth_complete`]).
//!
//! **Coordinate singularities.** Where the mass matrix loses rank (Euler
//! angles at gimbal lock) the coordinates are singular, not the mechanics;
//! [`crate::model::coordinate_sets`] names such sets.
//!
//! **Moore's test.** Moore ("Nonholonomic Constraints") checks each row for
//! exactness, `d a_i / d q_j = d a_j / d q_i`; a row that passes is the
//! differential of a function and is holonomic. The test misses integrating
//! factors (`(1 + x^2)(y xdot + x ydot) = 0` is holonomic but not exact), so
//! it is reported alongside Frobenius and decides nothing.

mod at_points;
mod basis;
mod body_frame;
pub mod charts;
mod integrals;
mod locked;

use crate::sym::Context;
use at_points::{growth_vector_at_point, is_exact_row_at_points, is_involutive_at_points};
pub use basis::{ChartFit, DistributionBasis, Elimination, default_point, distribution_basis};
pub use integrals::Integral;
pub use locked::Locked;

use crate::diagnostic::{Diagnostic, Diagnostics};
use crate::ir::{Backend, Interpreter};
use crate::model::Model;
use crate::model::coordinate_sets::{self, CoordinateSet};
use crate::sym::modular::ModularError;
use crate::sym::{Matrix, MatrixError, RationalFunction};

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
    /// The growth of D reaches n, or `n - h` with `h` holonomic
    /// constraints: every configuration (on their surface) is reachable
    /// (Chow).
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
    /// Other charts of D, where `basis` degenerates with the rows
    /// independent, and the singular sets found ([`charts`]).
    pub charts: charts::Charts,
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
    /// The combinations of rows not exact alone that are exact: integrals
    /// of the constraints ([`Integral`]).
    pub integrals: Vec<Integral>,
    /// The bodies the contacts leave unable to move.
    pub locked: Locked,
    /// Where the mass matrix loses rank: singularities of the coordinates
    /// ([`crate::model::coordinate_sets`]).
    pub coordinate_sets: Vec<CoordinateSet>,
}

/// Why the analysis failed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum AnalysisError {
    /// The engine failed on a matrix.
    #[error(transparent)]
    Matrix(#[from] MatrixError),
    /// The charts of D could not be found.
    #[error(transparent)]
    Charts(#[from] charts::ChartsError),
    /// The model is too large for normal forms and its expressions are
    /// outside the class evaluated modulo a prime.
    #[error("the constraint analysis is too large for normal forms, and {0}")]
    Undecided(#[from] ModularError),
}

/// Analyses the constraints, the charts' search on the interpreter
/// ([`analyse_on`]).
pub fn analyse(model: &Model, cx: &mut Context) -> Result<ConstraintAnalysis, Diagnostics> {
    analyse_on(model, cx, &Interpreter)
}

/// Analyses the constraints, the charts' search running its programs on
/// the engines `backend` makes; with `#[deny_holonomic]`, integrable
/// constraints are an error spanned on the first constraint's name.
pub fn analyse_on(
    model: &Model,
    cx: &mut Context,
    backend: &dyn Backend,
) -> Result<ConstraintAnalysis, Diagnostics> {
    let analysis = derive_analysis(model, cx, backend)
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    deny_holonomic(model, &analysis)?;
    Ok(analysis)
}

fn derive_analysis(
    model: &Model,
    cx: &mut Context,
    backend: &dyn Backend,
) -> Result<ConstraintAnalysis, AnalysisError> {
    let basis = distribution_basis(model, cx)?;
    let charts = charts::alternative_charts(model, cx, &basis, backend)?;
    let (integrable, integrability_method) = integrability(model, cx, &basis)?;
    let (growth, growth_complete, growth_method) = growth(model, cx, &basis)?;
    let classification = classify(model, integrable, &growth, growth_complete);
    let exact_rows = exact_rows(model, cx)?;
    let integrals = integrals::integrals(model, cx, &exact_rows);
    let locked = locked::locked_bodies(model, cx, &basis);
    let coordinate_sets = coordinate_sets::coordinate_sets(model, cx).map_err(MatrixError::from)?;
    Ok(ConstraintAnalysis {
        basis,
        charts,
        growth,
        growth_complete,
        growth_method,
        integrable,
        integrability_method,
        classification,
        exact_rows,
        integrals,
        locked,
        coordinate_sets,
    })
}

/// Frobenius, exactly when the exact basis and the brackets fit their
/// budgets, else at random points.
fn integrability(
    model: &Model,
    cx: &mut Context,
    basis: &DistributionBasis,
) -> Result<(bool, Method), AnalysisError> {
    if let Some(fields) = &basis.fields {
        let fields = columns_of(fields);
        let exact = cx.attempt(EXACT_ANALYSIS_PRODUCTS, |cx| {
            is_involutive(model, cx, &fields)
        });
        if let Some(integrable) = exact {
            return Ok((integrable?, Method::NormalForm));
        }
    }
    Ok((is_involutive_at_points(model, cx, basis)?, Method::Modular))
}

/// The growth vector, exactly when it fits its budget, else at a random
/// point; `(growth, complete, method)`.
fn growth(
    model: &Model,
    cx: &mut Context,
    basis: &DistributionBasis,
) -> Result<(Vec<usize>, bool, Method), AnalysisError> {
    if let Some(fields) = &basis.fields {
        let fields = columns_of(fields);
        let exact = cx.attempt(EXACT_ANALYSIS_PRODUCTS, |cx| {
            growth_vector(model, cx, &fields)
        });
        if let Some(growth) = exact {
            return Ok((growth?, true, Method::NormalForm));
        }
    }
    let (growth, complete) = growth_vector_at_point(model, cx, basis)?;
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
    } else if growth.last() == Some(&reachable_bound(model)) {
        Classification::CompletelyNonholonomic
    } else if complete {
        Classification::Nonholonomic
    } else {
        Classification::NonholonomicGrowthOpen
    }
}

/// Frobenius: `A [X_i, X_j] = 0` exactly for every pair of basis fields.
fn is_involutive(model: &Model, cx: &mut Context, fields: &[Field]) -> Result<bool, MatrixError> {
    for (i, x) in fields.iter().enumerate() {
        for y in &fields[i + 1..] {
            let bracket = bracket(model, cx, x, y)?;
            let atoms = cx.atoms().clone();
            let column = Matrix::new(bracket.len(), 1, bracket)?;
            if !model.constraint_matrix.mul(&column, &atoms)?.is_zero() {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// The ranks of `D^1, D^2, ...` until they stop growing (or reach n).
fn growth_vector(
    model: &Model,
    cx: &mut Context,
    basis: &[Field],
) -> Result<Vec<usize>, MatrixError> {
    let mut span = Vec::new();
    let mut newest = independent_additions(model, cx, &mut span, basis.to_vec())?;
    let mut growth = vec![span.len()];
    while span.len() < reachable_bound(model) && !newest.is_empty() {
        let brackets = brackets_with(model, cx, basis, &newest)?;
        newest = independent_additions(model, cx, &mut span, brackets)?;
        if newest.is_empty() {
            break;
        }
        growth.push(span.len());
    }
    Ok(growth)
}

/// The largest rank the growth of D can reach: `n - h` with `h` holonomic
/// constraints. Each `df` annihilates D, and `ker df` is integrable, so it
/// annihilates every bracket of D too: the motion stays on `f = const`.
pub(super) fn reachable_bound(model: &Model) -> usize {
    model.n() - model.mechanism.holonomic.len()
}

/// Every `[X, Y]` with X a basis field and Y one of `newest`.
fn brackets_with(
    model: &Model,
    cx: &mut Context,
    basis: &[Field],
    newest: &[Field],
) -> Result<Vec<Field>, MatrixError> {
    let mut brackets = Vec::with_capacity(basis.len() * newest.len());
    for x in basis {
        for y in newest {
            brackets.push(bracket(model, cx, x, y)?);
        }
    }
    Ok(brackets)
}

/// Moves into `span` each candidate that raises its exact rank; returns those.
fn independent_additions(
    model: &Model,
    cx: &Context,
    span: &mut Vec<Field>,
    candidates: Vec<Field>,
) -> Result<Vec<Field>, MatrixError> {
    let mut added = Vec::new();
    for candidate in candidates {
        span.push(candidate);
        if rank_of_fields(model, cx, span)? == span.len() {
            added.push(span[span.len() - 1].clone());
        } else {
            span.pop();
        }
    }
    Ok(added)
}

/// The exact generic rank of the fields (as columns of an n x m matrix).
fn rank_of_fields(model: &Model, cx: &Context, fields: &[Field]) -> Result<usize, MatrixError> {
    let n = model.n();
    let mut matrix = Matrix::zeros(n, fields.len());
    for (j, field) in fields.iter().enumerate() {
        for (i, entry) in field.iter().enumerate() {
            matrix.set(i, j, entry.clone());
        }
    }
    Ok(matrix.rank(cx.atoms()))
}

fn bracket(
    model: &Model,
    cx: &mut Context,
    x: &[RationalFunction],
    y: &[RationalFunction],
) -> Result<Field, MatrixError> {
    let coordinates = model.coordinate_symbols();
    cx.lie_bracket(x, y, &coordinates)
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

/// Moore's mixed-partials test, per row: `d a_i / d q_j = d a_j / d q_i`,
/// exactly within [`EXACT_ANALYSIS_PRODUCTS`] when the row's normal forms
/// are written out ([`RationalFunction::is_written_out`]), else at random points on
/// the expressions the row was derived as.
fn exact_rows(model: &Model, cx: &mut Context) -> Result<Vec<bool>, AnalysisError> {
    (0..model.constraint_matrix.rows())
        .map(|row| {
            let entries: Field = (0..model.n())
                .map(|j| model.constraint_matrix.get(row, j).clone())
                .collect();
            let written_out = entries.iter().all(RationalFunction::is_written_out);
            let exact = written_out
                .then(|| {
                    cx.attempt(EXACT_ANALYSIS_PRODUCTS, |cx| {
                        let coordinates = model.coordinate_symbols();
                        let jacobian = cx.jacobian(&entries, &coordinates)?;
                        let asymmetry = jacobian.sub(&jacobian.transpose(), cx.atoms())?;
                        Ok::<bool, MatrixError>(asymmetry.is_zero())
                    })
                })
                .flatten();
            match exact {
                Some(decided) => Ok(decided?),
                None => {
                    let expressions = model.constraint_expressions.row_entries(row);
                    is_exact_row_at_points(model, cx, &expressions)
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
