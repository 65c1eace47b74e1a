//! The basis of D (MATH.md 1.1): `u_r = A_n u_s` with `A_n = -A_r^-1 A_s`
//! for the dependent speeds `u_r` (pivot columns of A, chosen at the
//! model's defaults, or by exact elimination where A loses rank there), and
//! the columns of `[I; A_n]` as k vector fields spanning `D = ker A`; as
//! expressions always, in normal form within [`EXACT_BASIS_PRODUCTS`].
//! With a symmetry declared and no momentum basis, the elimination runs on
//! the body rows `A(e, r)` and the basis is mapped back, `X = L [I; A_n]`
//! ([`super::body_frame`]), so no group coordinate enters a denominator.

use super::body_frame::BodyFrame;
use super::{EXACT_BASIS_PRODUCTS, Field};
use crate::model::{GroupFactor, Model};
use crate::sym::{Context, ExprId, Matrix, MatrixError, RationalFunction, SymbolId};
use chaplygin_runtime::monitor::partial_pivots;
use chaplygin_runtime::nalgebra::DMatrix;

/// A basis of the constraint distribution D and how it was chosen.
#[derive(Clone, Debug)]
pub struct DistributionBasis {
    /// `X`, n x k, as expressions: column j is the vector field `X_j`, the
    /// dependent speeds written as the elimination computes them.
    pub field_expressions: Matrix<ExprId>,
    /// `X` in exact normal form, when it fits [`EXACT_BASIS_PRODUCTS`].
    pub fields: Option<Matrix>,
    /// `S`, k x n: the independent speeds `S qdot` of a velocity, a left
    /// inverse of `X` (`S X = I`, so `qdot = X a` has `a = S qdot`): the
    /// rows `independent` of the identity, or of `L^-1 = L^T` in the body
    /// frame.
    pub speeds: Matrix<ExprId>,
    /// The coordinates whose speeds are dependent (pivot columns), in row order.
    pub dependent: Vec<usize>,
    /// The coordinates whose speeds are independent, in order: `X_j` has a 1
    /// at `independent[j]` and 0 at the other independent speeds (of the
    /// body velocity `(xi, rdot)` when [`DistributionBasis::body_frame`]).
    pub independent: Vec<usize>,
    /// The speeds are the body velocity's (the basis was chosen on the body
    /// rows and rotated back), not the coordinates' own.
    pub body_frame: bool,
}

impl DistributionBasis {
    /// How the runtime measures where this basis fits: the pivot ratio of
    /// its dependent speeds on the rows it was eliminated on, as the
    /// reduced form computes it (`elimination`).
    pub fn fit(&self, elimination: Elimination) -> ChartFit {
        let dependent = self.dependent.clone();
        match self.body_frame {
            true => ChartFit::Body(dependent, elimination),
            false => ChartFit::Coordinates(dependent, elimination),
        }
    }

    /// The names of the speeds at the coordinate indices `indices`
    /// (`speed_names` in this basis's frame).
    pub fn speed_names(&self, model: &Model, indices: &[usize]) -> Vec<String> {
        speed_names(model, indices, self.body_frame)
    }
}

/// The names of the speeds at the coordinate indices `indices`: `dot(q)`
/// for a coordinate's own speed; in the body frame, the body velocity's
/// components on each `se2(x, y, theta)` factor, `v_x_body` and `v_y_body`
/// (the velocity of the frame's origin along the body's own axes,
/// `cos(theta) dot(x) + sin(theta) dot(y)` and
/// `-sin(theta) dot(x) + cos(theta) dot(y)`) and `omega_theta` (the turning
/// rate, `dot(theta)`), named after the factor's coordinates.
pub fn speed_names(model: &Model, indices: &[usize], body_frame: bool) -> Vec<String> {
    indices
        .iter()
        .map(|&i| speed_name(model, i, body_frame))
        .collect()
}

fn speed_name(model: &Model, i: usize, body_frame: bool) -> String {
    let name = |j: usize| model.coordinates[j].declared.name.as_str();
    let factors = match (&model.symmetry, body_frame) {
        (Some(symmetry), true) => symmetry.factors.as_slice(),
        _ => &[],
    };
    for factor in factors {
        if let GroupFactor::Se2 { x, y, theta } = *factor {
            match i {
                _ if i == x || i == y => return format!("v_{}_body", name(i)),
                _ if i == theta => return format!("omega_{}", name(i)),
                _ => {}
            }
        }
    }
    format!("dot({})", name(i))
}

/// How the runtime measures where a chart of the reduced form fits, in
/// `[0, 1]` and 0 where its basis degenerates (`chaplygin_runtime::system::ReducedPortHamiltonian::chart_fit`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ChartFit {
    /// The pivot ratio of these dependent speeds on the coordinates' rows
    /// `A(q)`.
    Coordinates(Vec<usize>, Elimination),
    /// The pivot ratio of these dependent body speeds on the body rows
    /// `A(e, r)`, the rows at the group identity the basis was eliminated
    /// on (the body frame of MATH.md 4).
    Body(Vec<usize>, Elimination),
    /// A declared momentum basis: `|det[A; V^T]|` over its rows' norms.
    Declared,
}

/// How a chart's reduced form solves for its dependent speeds, which
/// decides where it degenerates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Elimination {
    /// The exact `A_r^-1 A_s`, singular only where `det A_r` vanishes:
    /// its fit is `chaplygin_runtime::monitor::pivot_ratio`.
    Exact,
    /// Gaussian elimination in order, row `i` on column `r_i` (the
    /// structured form): singular where a leading minor vanishes, its fit
    /// `chaplygin_runtime::monitor::elimination_ratio`.
    InOrder,
}

impl ChartFit {
    /// The chart in words: its dependent speeds, or the declared basis.
    pub fn describe(&self, model: &Model) -> String {
        match self {
            ChartFit::Coordinates(dependent, _) => speed_names(model, dependent, false).join(", "),
            ChartFit::Body(dependent, _) => speed_names(model, dependent, true).join(", "),
            ChartFit::Declared => "the declared momentum basis".to_string(),
        }
    }
}

/// Chooses the dependent speeds at the defaults and solves for a basis of
/// D: as expressions always, in normal form within [`EXACT_BASIS_PRODUCTS`]
/// when the rows are written out ([`crate::sym::Matrix::is_written_out`]).
pub fn distribution_basis(
    model: &Model,
    cx: &mut Context,
) -> Result<DistributionBasis, MatrixError> {
    let dependent = pivot_columns(model, cx);
    let frame = match model.momentum_basis {
        None => BodyFrame::of(model, cx)?,
        Some(_) => None,
    };
    basis_on(model, cx, dependent, frame)
}

/// The basis of D with the speeds `dependent` solved for, on the
/// coordinates' rows `A(q)` (another chart of D, [`super::charts`]).
pub(super) fn basis_with_dependent(
    model: &Model,
    cx: &mut Context,
    dependent: Vec<usize>,
) -> Result<DistributionBasis, MatrixError> {
    basis_on(model, cx, dependent, None)
}

/// The basis of D with the body speeds `dependent` solved for, on the
/// body rows (another chart of a basis chosen in the body frame,
/// [`super::charts`]).
pub(super) fn basis_in_body_frame(
    model: &Model,
    cx: &mut Context,
    dependent: Vec<usize>,
) -> Result<DistributionBasis, MatrixError> {
    let frame = BodyFrame::of(model, cx)?;
    basis_on(model, cx, dependent, frame)
}

/// The basis of D with the speeds `dependent` solved for: on the body rows
/// when `frame` is given, on `A(q)` otherwise.
fn basis_on(
    model: &Model,
    cx: &mut Context,
    dependent: Vec<usize>,
    frame: Option<BodyFrame>,
) -> Result<DistributionBasis, MatrixError> {
    let n = model.n();
    let independent: Vec<usize> = (0..n).filter(|j| !dependent.contains(j)).collect();
    let a = match &frame {
        Some(frame) => frame.constraints.clone(),
        None => model.constraint_expressions.clone(),
    };
    let (a_r, a_s) = (
        expression_columns_at(&a, &dependent, cx),
        expression_columns_at(&a, &independent, cx),
    );
    let solved = cx.solve_in_order(&a_r, &a_s)?;
    let minus_one = cx.integer(-1);
    let a_n = solved.scale(minus_one, cx);
    let mut field_expressions = cx.zero_matrix(n, independent.len());
    let one = cx.integer(1);
    for (k, &j) in independent.iter().enumerate() {
        field_expressions.set(j, k, one);
    }
    for (row, &j) in dependent.iter().enumerate() {
        for k in 0..independent.len() {
            field_expressions.set(j, k, *a_n.get(row, k));
        }
    }
    let mut speeds = cx.zero_matrix(independent.len(), n);
    for (k, &j) in independent.iter().enumerate() {
        speeds.set(k, j, one);
    }
    if let Some(frame) = &frame {
        field_expressions = frame.to_coordinates.mul(&field_expressions, cx)?;
        speeds = speeds.mul(&frame.to_coordinates.transpose(), cx)?;
    }
    let exact_a = &model.constraint_matrix;
    let exact = |cx: &mut Context| match &frame {
        Some(frame) => {
            let body = exact_fields(
                &frame.exact_constraints(cx)?,
                &dependent,
                &independent,
                cx.atoms(),
            )?;
            frame.exact_to_coordinates(cx)?.mul(&body, cx.atoms())
        }
        None => exact_fields(exact_a, &dependent, &independent, cx.atoms()),
    };
    let fields = match exact_a.is_written_out() {
        true => cx.attempt(EXACT_BASIS_PRODUCTS, exact).transpose()?,
        false => None,
    };
    Ok(DistributionBasis {
        field_expressions,
        fields,
        speeds,
        dependent,
        independent,
        body_frame: frame.is_some(),
    })
}

/// The columns `indices` of `a`, in that order.
fn expression_columns_at(
    a: &Matrix<ExprId>,
    indices: &[usize],
    cx: &mut Context,
) -> Matrix<ExprId> {
    let mut columns = cx.zero_matrix(a.rows(), indices.len());
    for i in 0..a.rows() {
        for (k, &j) in indices.iter().enumerate() {
            columns.set(i, k, *a.get(i, j));
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
fn pivot_columns(model: &Model, cx: &mut Context) -> Vec<usize> {
    pivots_at_defaults(model, cx).unwrap_or_else(|| generic_pivots(model, cx))
}

/// Gaussian elimination with partial pivoting on A at the defaults
/// (`chaplygin_runtime::monitor::partial_pivots`): the pivot column of each
/// row is the one of largest magnitude there. `None` when a pivot vanishes
/// (A is singular at the defaults).
fn pivots_at_defaults(model: &Model, cx: &mut Context) -> Option<Vec<usize>> {
    let defaults = default_point(model);
    let values = model.constraint_matrix.evaluate(cx, &|s| defaults(s));
    let rows = DMatrix::from_row_slice(model.c(), model.n(), &values);
    let mut pivots = vec![0; model.c()];
    partial_pivots(&rows, &mut pivots).then_some(pivots)
}

/// Exact elimination on A: the pivot of each row is its first column with a
/// non-zero entry (A has full generic rank, checked by `model::check`).
fn generic_pivots(model: &Model, cx: &Context) -> Vec<usize> {
    let (n, c) = (model.n(), model.c());
    let atoms = cx.atoms();
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
