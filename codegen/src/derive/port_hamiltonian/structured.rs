//! The reduced form with the tool's basis, derived without expanding
//! (Duindam & Stramigioli, Theorem 1, written for `h = X^T g`).
//!
//! With `h = X^T g` for the basis `X` of D (`n x k`, its independent rows
//! the identity), `g^-1 h^T = X`, so the velocities are `qdot = X alpha` and
//! the reduced metric is the projected mass matrix:
//!
//! ```text
//! gbar_inv = X^T g X,   gbar = gbar_inv^-1,   P = gbar X^T,   P g = gbar h
//! Hbar     = 1/2 alpha^T gbar_inv alpha + V
//! ```
//!
//! The gyroscopic matrix is `Gamma = gbar S gbar` with
//! `S_ab = alpha_c dh^c(X_a, X_b)`, and the exterior derivative is taken
//! without forming its `n x n` matrices, by
//! `dh(Y, Z) = Y(h(Z)) - Z(h(Y)) - h([Y, Z])` with `h^c(X_b) = gbar_inv_cb`:
//!
//! ```text
//! S_ab = sum_c alpha_c ( X_a(gbar_inv_cb) - X_b(gbar_inv_ca) - (X^T g [X_a, X_b])_c )
//! ```
//!
//! where `X_a(f) = sum_j X_ja df/dq_j`. `S` is skew (its entries below the
//! diagonal are built as the negations of those above, the form being
//! alternating), so `Gamma` and `Jbar` are skew by construction. The flow is
//! written without the product `gbar gbar_inv`:
//!
//! ```text
//! qdot     = X alpha
//! alphadot = gbar ( -X^T dHbar/dq + S alpha + X^T B u )   (= -P dHbar/dq + Gamma dHbar/dalpha + P B u)
//! y        = B^T X alpha
//! ```
//!
//! Every matrix is a [`Matrix`] of expressions over the entries of `X` as the
//! elimination computes them ([`crate::derive::constraints::DistributionBasis`]),
//! and `gbar` is the elimination of `gbar_inv` (symmetric positive definite,
//! so its diagonal pivots never vanish), so sizes grow with the number of
//! operations rather than with expanded terms.

use super::{ReducedExpressions, RhsJacobian, reduced_energy, symbols_column, through_solve};
use crate::derive::constraints::DistributionBasis;
use crate::model::Model;
use crate::sym::{Context, ExprId, Matrix, MatrixError, SymbolId};

/// The reduced form's matrices and flow for the basis `fields` of D.
pub(super) fn derive(
    model: &Model,
    cx: &mut Context,
    basis: &DistributionBasis,
    momenta: &[SymbolId],
    inputs: &[SymbolId],
) -> Result<ReducedExpressions, MatrixError> {
    let n = model.n();
    let fields = &basis.field_expressions;
    let coordinates = model.coordinate_symbols();
    let g = model.energy_expressions.mass_matrix.clone();
    let b = model.input_matrix.to_expression_matrix(cx);
    let potential = model.energy_expressions.potential;
    let maps = Maps::of(cx, fields, &g)?;
    let alpha = symbols_column(cx, momenta);
    let u = symbols_column(cx, inputs);
    let metric_rates: Vec<Matrix<ExprId>> = coordinates
        .iter()
        .map(|&q| maps.metric_inverse.derivative(q, cx))
        .collect();
    let hamiltonian = reduced_energy(cx, &alpha, &maps.metric_inverse, potential)?;
    let mut gradient: Vec<ExprId> = coordinates
        .iter()
        .map(|&q| cx.derivative(hamiltonian, q))
        .collect();
    gradient.extend(maps.metric_inverse.mul(&alpha, cx)?.entries());
    let core = gyroscopic_core(cx, &maps, &metric_rates, &alpha, &coordinates)?;
    let structure = structure_matrix(cx, &maps, &core)?;
    let zero = cx.integer(0);
    let input_matrix = maps.projection.mul(&b, cx)?.below_zero_rows(n, zero);
    let (rhs, output) = flow(cx, &maps, &core, &gradient[..n], &alpha, &u, &b)?;
    let chain = through_solve::derive(cx, fields, &basis.speeds, &coordinates, momenta)?;
    Ok(ReducedExpressions {
        velocity_map: maps.velocities,
        momentum_map: maps.momentum_map,
        metric_inverse: maps.metric_inverse,
        metric: maps.metric,
        structure,
        input_matrix,
        hamiltonian,
        gradient,
        rhs,
        rhs_jacobian: RhsJacobian::ThroughSolve(chain),
        output,
    })
}

/// The maps between velocities and momenta for `h = X^T g`.
struct Maps {
    /// `X`, n x k: `qdot = X alpha`.
    velocities: Matrix<ExprId>,
    /// `h = X^T g`, k x n.
    basis: Matrix<ExprId>,
    /// `gbar_inv = X^T g X`, symmetric as written.
    metric_inverse: Matrix<ExprId>,
    /// `gbar`, by elimination, symmetric as written.
    metric: Matrix<ExprId>,
    /// `P = gbar X^T`.
    projection: Matrix<ExprId>,
    /// `P g = gbar h`.
    momentum_map: Matrix<ExprId>,
}

impl Maps {
    fn of(
        cx: &mut Context,
        fields: &Matrix<ExprId>,
        g: &Matrix<ExprId>,
    ) -> Result<Maps, MatrixError> {
        let x_transposed = fields.transpose();
        let basis = x_transposed.mul(g, cx)?;
        let metric_inverse = symmetric(&basis.mul(fields, cx)?);
        let identity = cx.identity_matrix(fields.columns());
        let metric = symmetric(&cx.solve_in_order(&metric_inverse, &identity)?);
        let projection = metric.mul(&x_transposed, cx)?;
        let momentum_map = metric.mul(&basis, cx)?;
        Ok(Maps {
            velocities: fields.clone(),
            basis,
            metric_inverse,
            metric,
            projection,
            momentum_map,
        })
    }
}

/// `xdot = (X alpha, gbar (-X^T dHbar/dq + S alpha + X^T B u))` and
/// `y = B^T X alpha`.
fn flow(
    cx: &mut Context,
    maps: &Maps,
    core: &Matrix<ExprId>,
    force_gradient: &[ExprId],
    alpha: &Matrix<ExprId>,
    u: &Matrix<ExprId>,
    b: &Matrix<ExprId>,
) -> Result<(Vec<ExprId>, Vec<ExprId>), MatrixError> {
    let x_transposed = maps.velocities.transpose();
    let velocities = maps.velocities.mul(alpha, cx)?;
    let minus_one = cx.integer(-1);
    let potential_force = x_transposed
        .mul(&Matrix::column(force_gradient.to_vec()), cx)?
        .scale(minus_one, cx);
    let applied = x_transposed.mul(&b.mul(u, cx)?, cx)?;
    let gyroscopic_force = core.mul(alpha, cx)?;
    let bracket = potential_force
        .add(&gyroscopic_force, cx)?
        .add(&applied, cx)?;
    let momentum_rates = maps.metric.mul(&bracket, cx)?;
    let mut rhs = velocities.entries().to_vec();
    rhs.extend(momentum_rates.entries());
    let output = b.transpose().mul(&velocities, cx)?.entries().to_vec();
    Ok((rhs, output))
}

/// `S_ab = sum_c alpha_c (X_a(gbar_inv_cb) - X_b(gbar_inv_ca) - (h [X_a, X_b])_c)`
/// for `a < b`, mirrored with the opposite sign.
fn gyroscopic_core(
    cx: &mut Context,
    maps: &Maps,
    metric_rates: &[Matrix<ExprId>],
    alpha: &Matrix<ExprId>,
    coordinates: &[SymbolId],
) -> Result<Matrix<ExprId>, MatrixError> {
    let (x, h) = (&maps.velocities, &maps.basis);
    let k = x.columns();
    let mut core = cx.zero_matrix(k, k);
    for a in 0..k {
        for b in a + 1..k {
            let bracket = cx.lie_bracket_of_expressions(
                &x.column_entries(a),
                &x.column_entries(b),
                coordinates,
            );
            let along_bracket = h.mul(&Matrix::column(bracket), cx)?;
            let mut terms = Vec::with_capacity(k);
            for c in 0..k {
                let ab = directional(cx, x, a, metric_rates, c, b);
                let ba = directional(cx, x, b, metric_rates, c, a);
                let form = cx.sub(ab, ba);
                let form = cx.sub(form, *along_bracket.get(c, 0));
                terms.push(cx.mul2(*alpha.get(c, 0), form));
            }
            let entry = cx.add(&terms);
            let opposite = cx.neg(entry);
            core.set(a, b, entry);
            core.set(b, a, opposite);
        }
    }
    Ok(core)
}

/// `X_a(gbar_inv_cb) = sum_j X_ja d gbar_inv_cb / dq_j`.
fn directional(
    cx: &mut Context,
    x: &Matrix<ExprId>,
    a: usize,
    metric_rates: &[Matrix<ExprId>],
    c: usize,
    b: usize,
) -> ExprId {
    let mut terms = Vec::new();
    for (j, rate) in metric_rates.iter().enumerate() {
        let (along, derivative) = (*x.get(j, a), *rate.get(c, b));
        if !cx.is_zero_constant(along) && !cx.is_zero_constant(derivative) {
            terms.push(cx.mul2(along, derivative));
        }
    }
    cx.add(&terms)
}

/// The matrix with its upper triangle mirrored below the diagonal.
fn symmetric(matrix: &Matrix<ExprId>) -> Matrix<ExprId> {
    let mut mirrored = matrix.clone();
    for a in 0..matrix.rows() {
        for b in a + 1..matrix.columns() {
            mirrored.set(b, a, *matrix.get(a, b));
        }
    }
    mirrored
}

/// The matrix with its upper triangle negated below the diagonal and zeros
/// on it (the matrix is skew as a function; this makes it so as written).
fn skew_part(cx: &mut Context, matrix: &Matrix<ExprId>) -> Matrix<ExprId> {
    let mut skew = cx.zero_matrix(matrix.rows(), matrix.columns());
    for a in 0..matrix.rows() {
        for b in a + 1..matrix.columns() {
            let entry = *matrix.get(a, b);
            skew.set(a, b, entry);
            skew.set(b, a, cx.neg(entry));
        }
    }
    skew
}

/// `Jbar = [[0, P^T], [-P, Gamma]]` with `Gamma = gbar S gbar`, each lower
/// entry the negation of its upper one.
fn structure_matrix(
    cx: &mut Context,
    maps: &Maps,
    core: &Matrix<ExprId>,
) -> Result<Matrix<ExprId>, MatrixError> {
    let sandwiched = maps.metric.mul(core, cx)?.mul(&maps.metric, cx)?;
    let gyroscopic = skew_part(cx, &sandwiched);
    let zero = cx.integer(0);
    Ok(maps
        .projection
        .skew_structure(&gyroscopic, zero, |&entry| cx.neg(entry)))
}
