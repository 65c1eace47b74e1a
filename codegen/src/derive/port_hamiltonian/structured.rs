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
//! Every matrix is an [`ExprMatrix`] over the entries of `X` as the
//! elimination computes them ([`crate::derive::constraints::DistributionBasis`]),
//! and `gbar` is the elimination of `gbar_inv` (symmetric positive definite,
//! so its diagonal pivots never vanish), so sizes grow with the number of
//! operations rather than with expanded terms.

use super::Forms;
use crate::model::Model;
use crate::sym::{ExprId, ExprMatrix, MatrixError, Rational, Store, SymbolId};

/// The reduced form's matrices and flow for the basis `fields` of D.
pub(super) fn derive(
    model: &mut Model,
    fields: &ExprMatrix,
    momenta: &[SymbolId],
    inputs: &[SymbolId],
) -> Result<Forms, MatrixError> {
    let n = model.n();
    let coordinates = model.coordinate_symbols();
    let store = &mut model.store;
    let g = model.energy_expressions.mass_matrix.clone();
    let b = ExprMatrix::of(&model.input_matrix, store);
    let potential = model.energy_expressions.potential;
    let maps = Maps::of(store, fields, &g)?;
    let alpha = symbols_column(store, momenta);
    let u = symbols_column(store, inputs);
    let metric_rates: Vec<ExprMatrix> = coordinates
        .iter()
        .map(|&q| maps.metric_inverse.derivative(q, store))
        .collect();
    let hamiltonian = hamiltonian(store, &alpha, &maps.metric_inverse, potential)?;
    let mut gradient: Vec<ExprId> = coordinates
        .iter()
        .map(|&q| store.derivative(hamiltonian, q))
        .collect();
    gradient.extend(maps.metric_inverse.mul(&alpha, store)?.entries());
    let core = gyroscopic_core(store, &maps, &metric_rates, &alpha, &coordinates)?;
    let structure = structure_matrix(store, &maps, &core)?;
    let input_matrix = reduced_input_matrix(store, &maps, &b, n)?;
    let (rhs, output) = flow(store, &maps, &core, &gradient[..n], &alpha, &u, &b)?;
    Ok(Forms {
        velocity_map: maps.velocities,
        momentum_map: maps.momentum_map,
        metric_inverse: maps.metric_inverse,
        metric: maps.metric,
        structure,
        input_matrix,
        hamiltonian,
        gradient,
        rhs,
        output,
    })
}

/// The maps between velocities and momenta for `h = X^T g`.
struct Maps {
    /// `X`, n x k: `qdot = X alpha`.
    velocities: ExprMatrix,
    /// `h = X^T g`, k x n.
    basis: ExprMatrix,
    /// `gbar_inv = X^T g X`, symmetric as written.
    metric_inverse: ExprMatrix,
    /// `gbar`, by elimination, symmetric as written.
    metric: ExprMatrix,
    /// `P = gbar X^T`.
    projection: ExprMatrix,
    /// `P g = gbar h`.
    momentum_map: ExprMatrix,
}

impl Maps {
    fn of(store: &mut Store, fields: &ExprMatrix, g: &ExprMatrix) -> Result<Maps, MatrixError> {
        let x_transposed = fields.transpose();
        let basis = x_transposed.mul(g, store)?;
        let metric_inverse = symmetric(&basis.mul(fields, store)?);
        let identity = ExprMatrix::identity(store, fields.columns());
        let metric = symmetric(&store.solve_in_order(&metric_inverse, &identity)?);
        let projection = metric.mul(&x_transposed, store)?;
        let momentum_map = metric.mul(&basis, store)?;
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

/// `Bbar = [0; P B]`, s x p.
fn reduced_input_matrix(
    store: &mut Store,
    maps: &Maps,
    b: &ExprMatrix,
    n: usize,
) -> Result<ExprMatrix, MatrixError> {
    let reduced = maps.projection.mul(b, store)?;
    let k = reduced.rows();
    let mut input_matrix = ExprMatrix::zeros(store, n + k, b.columns());
    for a in 0..k {
        for j in 0..b.columns() {
            input_matrix.set(n + a, j, reduced.get(a, j));
        }
    }
    Ok(input_matrix)
}

/// `xdot = (X alpha, gbar (-X^T dHbar/dq + S alpha + X^T B u))` and
/// `y = B^T X alpha`.
fn flow(
    store: &mut Store,
    maps: &Maps,
    core: &ExprMatrix,
    force_gradient: &[ExprId],
    alpha: &ExprMatrix,
    u: &ExprMatrix,
    b: &ExprMatrix,
) -> Result<(Vec<ExprId>, Vec<ExprId>), MatrixError> {
    let x_transposed = maps.velocities.transpose();
    let velocities = maps.velocities.mul(alpha, store)?;
    let minus_one = store.integer(-1);
    let potential_force = x_transposed
        .mul(&ExprMatrix::column(force_gradient.to_vec()), store)?
        .scale(minus_one, store);
    let applied = x_transposed.mul(&b.mul(u, store)?, store)?;
    let gyroscopic_force = core.mul(alpha, store)?;
    let bracket = potential_force
        .add(&gyroscopic_force, store)?
        .add(&applied, store)?;
    let momentum_rates = maps.metric.mul(&bracket, store)?;
    let mut rhs = velocities.entries().to_vec();
    rhs.extend(momentum_rates.entries());
    let output = b.transpose().mul(&velocities, store)?.entries().to_vec();
    Ok((rhs, output))
}

/// `S_ab = sum_c alpha_c (X_a(gbar_inv_cb) - X_b(gbar_inv_ca) - (h [X_a, X_b])_c)`
/// for `a < b`, mirrored with the opposite sign.
fn gyroscopic_core(
    store: &mut Store,
    maps: &Maps,
    metric_rates: &[ExprMatrix],
    alpha: &ExprMatrix,
    coordinates: &[SymbolId],
) -> Result<ExprMatrix, MatrixError> {
    let (x, h) = (&maps.velocities, &maps.basis);
    let k = x.columns();
    let mut core = ExprMatrix::zeros(store, k, k);
    for a in 0..k {
        for b in a + 1..k {
            let bracket = store.lie_bracket_of_expressions(
                &x.column_entries(a),
                &x.column_entries(b),
                coordinates,
            );
            let along_bracket = h.mul(&ExprMatrix::column(bracket), store)?;
            let mut terms = Vec::with_capacity(k);
            for c in 0..k {
                let ab = directional(store, x, a, metric_rates, c, b);
                let ba = directional(store, x, b, metric_rates, c, a);
                let form = store.sub(ab, ba);
                let form = store.sub(form, along_bracket.get(c, 0));
                terms.push(store.mul2(alpha.get(c, 0), form));
            }
            let entry = store.add(&terms);
            let opposite = store.neg(entry);
            core.set(a, b, entry);
            core.set(b, a, opposite);
        }
    }
    Ok(core)
}

/// `X_a(gbar_inv_cb) = sum_j X_ja d gbar_inv_cb / dq_j`.
fn directional(
    store: &mut Store,
    x: &ExprMatrix,
    a: usize,
    metric_rates: &[ExprMatrix],
    c: usize,
    b: usize,
) -> ExprId {
    let mut terms = Vec::new();
    for (j, rate) in metric_rates.iter().enumerate() {
        let (along, derivative) = (x.get(j, a), rate.get(c, b));
        if !store.is_zero_constant(along) && !store.is_zero_constant(derivative) {
            terms.push(store.mul2(along, derivative));
        }
    }
    store.add(&terms)
}

/// `1/2 alpha^T gbar_inv alpha + V`.
fn hamiltonian(
    store: &mut Store,
    alpha: &ExprMatrix,
    metric_inverse: &ExprMatrix,
    potential: ExprId,
) -> Result<ExprId, MatrixError> {
    let twice_kinetic = alpha
        .transpose()
        .mul(&metric_inverse.mul(alpha, store)?, store)?
        .get(0, 0);
    let half = store.number(Rational::HALF);
    let kinetic = store.mul2(half, twice_kinetic);
    Ok(store.add2(kinetic, potential))
}

/// The matrix with its upper triangle mirrored below the diagonal.
fn symmetric(matrix: &ExprMatrix) -> ExprMatrix {
    let mut mirrored = matrix.clone();
    for a in 0..matrix.rows() {
        for b in a + 1..matrix.columns() {
            mirrored.set(b, a, matrix.get(a, b));
        }
    }
    mirrored
}

/// The matrix with its upper triangle negated below the diagonal and zeros
/// on it (the matrix is skew as a function; this makes it so as written).
fn skew_part(store: &mut Store, matrix: &ExprMatrix) -> ExprMatrix {
    let mut skew = ExprMatrix::zeros(store, matrix.rows(), matrix.columns());
    for a in 0..matrix.rows() {
        for b in a + 1..matrix.columns() {
            let entry = matrix.get(a, b);
            skew.set(a, b, entry);
            skew.set(b, a, store.neg(entry));
        }
    }
    skew
}

/// `Jbar = [[0, P^T], [-P, Gamma]]` with `Gamma = gbar S gbar`, each lower
/// entry the negation of its upper one.
fn structure_matrix(
    store: &mut Store,
    maps: &Maps,
    core: &ExprMatrix,
) -> Result<ExprMatrix, MatrixError> {
    let sandwiched = maps.metric.mul(core, store)?.mul(&maps.metric, store)?;
    let gyroscopic = skew_part(store, &sandwiched);
    let projection = &maps.projection;
    let (k, n) = (projection.rows(), projection.columns());
    let mut structure = ExprMatrix::zeros(store, n + k, n + k);
    for a in 0..k {
        for j in 0..n {
            let entry = projection.get(a, j);
            structure.set(j, n + a, entry);
            structure.set(n + a, j, store.neg(entry));
        }
        for b in 0..k {
            structure.set(n + a, n + b, gyroscopic.get(a, b));
        }
    }
    Ok(structure)
}

fn symbols_column(store: &mut Store, symbols: &[SymbolId]) -> ExprMatrix {
    ExprMatrix::column(symbols.iter().map(|&s| store.symbol(s)).collect())
}
