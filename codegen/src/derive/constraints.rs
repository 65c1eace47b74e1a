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
//! **Moore's test.** Moore ("Nonholonomic Constraints") checks each row for
//! exactness, `d a_i / d q_j = d a_j / d q_i`; a row that passes is the
//! differential of a function and is holonomic. The test misses integrating
//! factors (`(1 + x^2)(y xdot + x ydot) = 0` is holonomic but not exact), so
//! it is reported alongside Frobenius and decides nothing.

use crate::diagnostic::{Diagnostic, Diagnostics};
use crate::emit::internal;
use crate::model::Model;
use crate::sym::{Matrix, MatrixError, RationalFunction, SymbolId};

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
            Classification::CompletelyNonholonomic => "completely nonholonomic",
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
    /// Frobenius: every bracket of the basis lies in D.
    pub integrable: bool,
    /// The classification that follows from `integrable` and `growth`.
    pub classification: Classification,
    /// Moore's test, per constraint row in declared order: is the row exact?
    pub exact_rows: Vec<bool>,
}

/// Analyses the constraints; with `#[deny_holonomic]`, integrable
/// constraints are an error spanned on the first constraint's name.
pub fn analyse(model: &mut Model) -> Result<ConstraintAnalysis, Diagnostics> {
    let analysis = derive_analysis(model).map_err(|e| internal(model, e))?;
    deny_holonomic(model, &analysis)?;
    Ok(analysis)
}

fn derive_analysis(model: &mut Model) -> Result<ConstraintAnalysis, MatrixError> {
    let basis = distribution_basis(model)?;
    let fields = columns_of(&basis.fields);
    let integrable = is_involutive(model, &fields)?;
    let growth = growth_vector(model, &fields)?;
    let classification = classify(model, integrable, &growth);
    let exact_rows = exact_rows(model)?;
    Ok(ConstraintAnalysis {
        basis,
        growth,
        integrable,
        classification,
        exact_rows,
    })
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

fn classify(model: &Model, integrable: bool, growth: &[usize]) -> Classification {
    if model.c() == 0 {
        Classification::Unconstrained
    } else if integrable {
        Classification::Holonomic
    } else if growth.last() == Some(&model.n()) {
        Classification::CompletelyNonholonomic
    } else {
        Classification::Nonholonomic
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
    /// `X`, n x k: column j is the vector field `X_j`.
    pub fields: Matrix,
    /// The coordinates whose speeds are dependent (pivot columns), in row order.
    pub dependent: Vec<usize>,
    /// The coordinates whose speeds are independent, in order: `X_j` has a 1
    /// at `independent[j]` and 0 at the other independent speeds.
    pub independent: Vec<usize>,
}

/// Chooses the dependent speeds at the defaults and solves for a basis of D.
pub fn distribution_basis(model: &mut Model) -> Result<DistributionBasis, MatrixError> {
    let (n, c) = (model.n(), model.c());
    let dependent = pivot_columns(model);
    let independent: Vec<usize> = (0..n).filter(|j| !dependent.contains(j)).collect();
    let atoms = model.store.atoms().clone();
    let a = &model.constraint_matrix;
    let columns = |indices: &[usize]| {
        let mut m = Matrix::zeros(c, indices.len());
        for i in 0..c {
            for (k, &j) in indices.iter().enumerate() {
                m.set(i, k, a.get(i, j).clone());
            }
        }
        m
    };
    let a_n = columns(&dependent)
        .solve(&columns(&independent), &atoms)?
        .neg();
    let mut fields = Matrix::zeros(n, independent.len());
    for (k, &j) in independent.iter().enumerate() {
        fields.set(j, k, RationalFunction::one());
    }
    for (row, &j) in dependent.iter().enumerate() {
        for k in 0..independent.len() {
            fields.set(j, k, a_n.get(row, k).clone());
        }
    }
    Ok(DistributionBasis {
        fields,
        dependent,
        independent,
    })
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
