//! The Jacobian of the structured reduced flow by the chain rule through
//! the Lagrange-d'Alembert solve (MATH.md sections 3 and 6).
//!
//! With the tool's basis `h = X^T g`, the momenta are the independent
//! speeds: `qdot = X alpha` and `alpha = S qdot` for the left inverse `S`
//! of `X` ([`crate::derive::constraints::DistributionBasis::speeds`]). The
//! reduced flow is then the constrained flow in those speeds,
//!
//! ```text
//! qdot     = v(q, alpha) = X(q) alpha
//! alphadot = S(q) a(q, v, u) + w(q, alpha),   w = sum_j (dS/dq_j) v_j v
//! ```
//!
//! with `a = qddot` the accelerations `acceleration` computes, and its
//! Jacobian follows from `acceleration_jacobian`'s `(da/dq, da/dqdot)` at
//! `(q, v, u)`:
//!
//! ```text
//! d qdot / dq_j         = dv/dq_j                 d qdot / dalpha = X
//! d alphadot / dq_j     = S (da/dq_j + da/dqdot dv/dq_j) + (dS/dq_j) a + dw/dq_j
//! d alphadot / dalpha_c = S da/dqdot X_c + dw/dalpha_c
//! ```
//!
//! Written over symbols standing for `a`, `da/dq` and `da/dqdot`, these
//! entries are small (the derivatives of `X` and `S` and a few products);
//! the emitted function computes `v` with `velocities`, calls
//! `acceleration_jacobian` (and `acceleration` when `a` is read), and then
//! these entries. Differentiating the structured `alphadot` instead would
//! differentiate `gbar` and the second derivatives of `X` through the
//! elimination: for the benchmark bicycle about ten times the operations.

use crate::sym::{Context, ExprId, Matrix, MatrixError, SymbolId, SymbolKind};

/// `d xdot / dx` over symbols for the solve's results at `qdot = X alpha`.
#[derive(Clone, Debug)]
pub struct ThroughSolve {
    /// `a = qddot`, n symbols.
    pub accelerations: Vec<SymbolId>,
    /// `da/dq`, n x n row-major symbols.
    pub by_coordinates: Vec<SymbolId>,
    /// `da/dqdot`, n x n row-major symbols.
    pub by_velocities: Vec<SymbolId>,
    /// `d xdot / dx`, s x s row-major, expressions of the state, the
    /// parameters and the symbols above.
    pub jacobian: Vec<ExprId>,
}

/// The chain rule above for the basis `fields` (`X`, n x k) with left
/// inverse `speeds` (`S`, k x n).
pub fn derive(
    cx: &mut Context,
    fields: &Matrix<ExprId>,
    speeds: &Matrix<ExprId>,
    coordinates: &[SymbolId],
    momenta: &[SymbolId],
) -> Result<ThroughSolve, MatrixError> {
    let n = coordinates.len();
    let symbols = |cx: &mut Context, name: &str, count: usize| -> Vec<SymbolId> {
        (0..count)
            .map(|i| super::fresh_symbol(cx, &format!("{name}[{i}]"), SymbolKind::Auxiliary))
            .collect()
    };
    let accelerations = symbols(cx, "qddot", n);
    let by_coordinates = symbols(cx, "dqddot_dq", n * n);
    let by_velocities = symbols(cx, "dqddot_dqdot", n * n);
    let a = super::symbols_column(cx, &accelerations);
    let by_q = Matrix::new(n, n, symbol_entries(cx, &by_coordinates))?;
    let by_qdot = Matrix::new(n, n, symbol_entries(cx, &by_velocities))?;
    let alpha = super::symbols_column(cx, momenta);
    let v = fields.mul(&alpha, cx)?;
    let correction = speed_correction(cx, speeds, &v, coordinates)?;
    let speeds_by_qdot = speeds.mul(&by_qdot, cx)?;
    let mut columns = Vec::with_capacity(n + momenta.len());
    for (j, &q) in coordinates.iter().enumerate() {
        let v_rate = v.derivative(q, cx);
        let direct = speeds.mul(&Matrix::column(by_q.column_entries(j)), cx)?;
        let through_v = speeds_by_qdot.mul(&v_rate, cx)?;
        let moving_speeds = speeds.derivative(q, cx).mul(&a, cx)?;
        let momentum_rate = direct
            .add(&through_v, cx)?
            .add(&moving_speeds, cx)?
            .add(&correction.derivative(q, cx), cx)?;
        columns.push(stacked(&v_rate, &momentum_rate));
    }
    for (c, &alpha_c) in momenta.iter().enumerate() {
        let field = Matrix::column(fields.column_entries(c));
        let momentum_rate = speeds_by_qdot
            .mul(&field, cx)?
            .add(&correction.derivative(alpha_c, cx), cx)?;
        columns.push(stacked(&field, &momentum_rate));
    }
    let s = columns.len();
    let jacobian = (0..s)
        .flat_map(|i| columns.iter().map(move |column| column[i]))
        .collect();
    Ok(ThroughSolve {
        accelerations,
        by_coordinates,
        by_velocities,
        jacobian,
    })
}

/// `w = sum_j (dS/dq_j) v_j v`, k x 1: `d(S qdot)/dt - S qddot`.
fn speed_correction(
    cx: &mut Context,
    speeds: &Matrix<ExprId>,
    v: &Matrix<ExprId>,
    coordinates: &[SymbolId],
) -> Result<Matrix<ExprId>, MatrixError> {
    let mut correction = cx.zero_matrix(speeds.rows(), 1);
    for (j, &q) in coordinates.iter().enumerate() {
        let rate = speeds.derivative(q, cx);
        if rate
            .entries()
            .iter()
            .all(|&entry| cx.is_zero_constant(entry))
        {
            continue;
        }
        let along = rate.mul(v, cx)?.scale(*v.get(j, 0), cx);
        correction = correction.add(&along, cx)?;
    }
    Ok(correction)
}

fn symbol_entries(cx: &mut Context, symbols: &[SymbolId]) -> Vec<ExprId> {
    symbols.iter().map(|&s| cx.symbol(s)).collect()
}

/// The column `(top; bottom)` as entries.
fn stacked(top: &Matrix<ExprId>, bottom: &Matrix<ExprId>) -> Vec<ExprId> {
    top.entries()
        .iter()
        .chain(bottom.entries())
        .copied()
        .collect()
}
