//! Symmetry reduction: the nonholonomic momentum equation
//! (Bloch, Krishnaprasad, Marsden & Murray, "Nonholonomic mechanical systems
//! with symmetry", 1996; Koon & Marsden, "The geometric structure of
//! nonholonomic mechanics", equations (1.1)-(1.3); MATH.md section 4).
//!
//! For `G` a product of `se2(x, y, theta)` and abelian `translation(q)`,
//! `rotation(q)` factors, with shape `r` the remaining coordinates, the body
//! velocity `xi` has one entry per group coordinate, factor by factor:
//! `(cos th xdot + sin th ydot, -sin th xdot + cos th ydot, thdot)` for `se2`,
//! `qdot` for an abelian factor. The Lagrangian and the constraints are
//! G-invariant (checked exactly when the model is checked), so the reduced
//! Lagrangian and the body-frame constraints are the model's at the group
//! identity (every group coordinate 0), where `qdot = (xi, rdot)`:
//!
//! ```text
//! l(r, xi, rdot) = 1/2 (xi, rdot)^T M(0, r) (xi, rdot),   dl/dxi = II(r) xi + M_gr(r) rdot
//! A_xi(r) xi + A_r(r) rdot = 0                              (A(0, r) split by columns)
//! S = {xi : A_xi xi = 0}, basis rows e_1(r)..e_mp(r)
//! xi = -A_nh(r) rdot + e(r)^T Omega,   A_xi A_nh = A_r,   < dl/dxi(-A_nh rdot, rdot), e_i > = 0
//! I(r) = e II e^T,   p_i = < dl/dxi, e_i >,   so p = I Omega (the horizontal part carries none)
//! pdot_i = < dl/dxi, [xi, e_i] + (de_i/dr) rdot >,   with xi = -A_nh rdot + e^T I^-1 p  (1.1)
//! [(a1, b1, w1), (a2, b2, w2)] = (w2 b1 - w1 b2, w1 a2 - w2 a1, 0)   on each se(2) factor, 0 on abelian ones
//! pdot_i = rdot^T H^i rdot + rdot^T K^i p + p^T D^i p  (+ h_i(q) B(q) u with inputs)     (1.2)
//! ```
//!
//! The coefficient tensors are exact second derivatives of `pdot_i`, and the
//! derivation proves that the quadratic form they define is `pdot_i`.
//! In configuration terms the momentum is `p_i = h_i . M(q) qdot` with `h_i`
//! equal to `e_i` on the group coordinates, each se(2) factor's `(v1, v2)`
//! part rotated by `R(theta)`, and 0 on the shape.
//!
//! Normalization of `e`: start from the null-space vectors `v` of `A_xi` from
//! its reduced row echelon form (1 in a free column); for each non-zero entry
//! `v_j`, divide by it and multiply by the least common multiple of the
//! entries' denominators; keep the candidate of least total size (number of
//! terms in normal form), the first one on ties. Every entry is then a
//! polynomial in the shape's atoms and the parameters. Finally each vector
//! is divided by a constant, its largest entry at the default configuration
//! evaluated exactly there (a function of the parameters), so that entry is
//! 1 at q = 0. For the snakeboard the first step gives
//! `(r cos phi, 0, sin phi)` and the last `e = (cos phi, 0, sin phi / r)`,
//! MATH.md 4.1's normalization.
//!
//! The shape velocities must be free: when the constraints restrict `rdot`
//! on their own (`A_xi` rows dependent where `A_r`'s are not), the model is
//! not of the principal kind the momentum equation is stated for.

mod algebra;
mod curvature;
mod sensitivity;

use super::constraints::charts::{ChartsError, group_singular_points};
use super::constraints::default_point;
use super::port_hamiltonian::{column_of_symbols, fresh_symbol};
use crate::ir::Backend;
use crate::model::{GroupFactor, Model};
use crate::sym::Context;
use crate::sym::{
    Atoms, ExprId, Function, Matrix, MatrixError, Poly, Rational, RationalFunction, SymError,
    SymbolId, SymbolKind,
};
use algebra::{bracket, se2_blocks};
pub use curvature::{ConnectionQuotient, Curvature, CurvatureError};
pub use sensitivity::Sensitivity;
use std::collections::HashMap;

/// The momentum equation's coefficients for one momentum `p_i`.
#[derive(Clone, Debug)]
pub struct Coefficients {
    /// `H^i`, nr x nr, symmetric.
    pub shape: Matrix,
    /// `K^i`, nr x mp.
    pub mixed: Matrix,
    /// `D^i`, mp x mp, symmetric.
    pub momentum: Matrix,
}

/// The reduced momentum form: every matrix in exact normal form.
#[derive(Clone, Debug)]
pub struct Momentum {
    /// Indices of the shape coordinates `r`, in declared order.
    pub shape: Vec<usize>,
    /// The shape velocities `rdot` (the model's velocity symbols).
    pub shape_velocities: Vec<SymbolId>,
    /// The momenta `p1..pmp`.
    pub momenta: Vec<SymbolId>,
    /// `e(r)`, mp x dg (dg the group's dimension): a basis of S as rows.
    pub basis: Matrix,
    /// `II(r)`, dg x dg: the body-frame inertia of the group directions.
    pub body_inertia: Matrix,
    /// `I(r) = e II e^T`, mp x mp.
    pub locked_inertia: Matrix,
    /// `A_nh(r)`, dg x nr.
    pub connection: Matrix,
    /// `A_nh` as `N / d` by Cramer's rule, finite wherever it is defined.
    pub connection_quotient: ConnectionQuotient,
    /// For a principally kinematic model (no momenta), the curvature of
    /// `A_nh` on each plane of shape coordinates.
    pub curvature: Option<Curvature>,
    /// For a principally kinematic model, configurations (all n
    /// coordinates, the group at its identity) found where the connection
    /// is singular.
    pub singular_shapes: Vec<Vec<f64>>,
    /// `p(q, qdot) = h M(q) qdot`, mp entries.
    pub momentum: Vec<RationalFunction>,
    /// `pdot(r, rdot, p)`, mp entries.
    pub rhs: Vec<RationalFunction>,
    /// `xi(r, rdot, p) = -A_nh rdot + e^T I^-1 p`, dg entries.
    pub body_velocity: Vec<RationalFunction>,
    /// The Jacobians of `rhs` and of `body_velocity` in `(r, rdot, p)`.
    pub sensitivity: Sensitivity,
    /// `e^T I^-1 p`, dg entries: `xi` without its horizontal part.
    pub vertical_velocity: Vec<RationalFunction>,
    /// `H^i, K^i, D^i` for each momentum.
    pub coefficients: Vec<Coefficients>,
    /// `h(q) B(q)`, mp x p: the inputs' contribution `pdot += h B u` (the
    /// input forces paired with `h_i`); `rhs` is the unforced equation. Zero
    /// when the inputs act on the shape only.
    pub input_coupling: Matrix,
}

/// Why the momentum equation could not be derived.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MomentumError {
    /// A solve or product failed (a singular locked inertia, say).
    #[error("momentum equation: {0}")]
    Matrix(#[from] MatrixError),
    /// The engine failed on an entry.
    #[error("momentum equation: {0}")]
    Symbolic(#[from] SymError),
    /// The model declares no symmetry.
    #[error("the momentum equation needs a `symmetry` declaration")]
    NoSymmetry,
    /// The constraints restrict the shape velocities on their own.
    #[error(
        "the constraints restrict the shape velocities: the momentum equation needs D + T(orbit) = TQ"
    )]
    ShapeConstrained,
    /// The connection's quotient or curvature failed its proof: a bug.
    #[error("momentum equation: {0}")]
    Curvature(#[from] CurvatureError),
    /// The search for the connection's singular set failed.
    #[error("the connection's singular set: {0}")]
    Charts(#[from] ChartsError),
    /// `pdot` is not the quadratic form of its coefficients: a bug.
    #[error("momentum equation {0} is not quadratic in the shape velocities and momenta")]
    NotQuadratic(usize),
}

/// Derives the momentum equation and the reconstruction of `model`, the
/// search for the connection's singular set running its program on the
/// engine `backend` makes.
pub fn derive(
    model: &Model,
    cx: &mut Context,
    backend: &dyn Backend,
) -> Result<Momentum, MomentumError> {
    let symmetry = model.symmetry.as_ref().ok_or(MomentumError::NoSymmetry)?;
    let (factors, group) = (symmetry.factors.clone(), symmetry.group_coordinates());
    let shape: Vec<usize> = (0..model.n()).filter(|i| !group.contains(i)).collect();
    let body = BodyForm::of(model, cx, &group, &shape)?;
    let basis = body_basis(&body.constraints_group, cx.atoms())?;
    let basis = unit_at_defaults(model, cx, &basis)?;
    let shape_velocities: Vec<SymbolId> = shape.iter().map(|&i| model.velocities[i]).collect();
    let momenta: Vec<SymbolId> = (1..=basis.rows())
        .map(|i| fresh_symbol(cx, &format!("p{i}"), SymbolKind::Momentum))
        .collect();
    let rdot = column_of_symbols(cx, &shape_velocities)?;
    let p = column_of_symbols(cx, &momenta)?;
    let atoms = cx.atoms().clone();
    let shape_symbols: Vec<SymbolId> = shape.iter().map(|&i| model.coordinates[i].symbol).collect();
    let (connection, connection_quotient) = connection(cx, &body, &basis, &shape_symbols)?;
    let (curvature, singular_shapes) = match momenta.is_empty() {
        true => (
            Some(curvature::curvature(
                cx,
                &connection_quotient,
                &connection,
                &shape_symbols,
                &factors,
            )?),
            group_singular_points(model, cx, backend)?,
        ),
        false => (None, Vec::new()),
    };
    let locked_inertia = basis
        .mul(&body.inertia, &atoms)?
        .mul(&basis.transpose(), &atoms)?;
    let (vertical, xi) = reconstruction(&basis, &locked_inertia, &connection, &rdot, &p, &atoms)?;
    let rhs = momentum_rhs(cx, &body, &basis, &xi, &rdot, &shape_symbols, &factors)?;
    let coefficients = rhs
        .iter()
        .enumerate()
        .map(|(i, pdot)| coefficients(cx, i, pdot, &shape_velocities, &momenta))
        .collect::<Result<Vec<_>, _>>()?;
    let (momentum, input_coupling) = configuration_terms(model, cx, &basis, &factors, &group)?;
    let pieces = sensitivity::Pieces {
        arguments: [shape_symbols, shape_velocities.clone(), momenta.clone()].concat(),
        shape: shape.len(),
        rhs: &rhs,
        quotient: &connection_quotient,
        vertical: vertical.entries(),
    };
    let sensitivity = sensitivity::sensitivity(cx, &pieces)?;
    Ok(Momentum {
        shape,
        shape_velocities,
        momenta,
        basis,
        body_inertia: body.inertia,
        locked_inertia,
        connection,
        connection_quotient,
        curvature,
        singular_shapes,
        momentum,
        rhs,
        body_velocity: xi.entries().to_vec(),
        vertical_velocity: vertical.entries().to_vec(),
        sensitivity,
        coefficients,
        input_coupling,
    })
}

/// `e^T I^-1 p`, the part of the body velocity the momenta carry, and
/// `xi = -A_nh rdot + e^T I^-1 p` (Koon & Marsden 1.1).
fn reconstruction(
    basis: &Matrix,
    locked_inertia: &Matrix,
    connection: &Matrix,
    rdot: &Matrix,
    p: &Matrix,
    atoms: &Atoms,
) -> Result<(Matrix, Matrix), MatrixError> {
    let omega = locked_inertia.solve(p, atoms)?;
    let vertical = basis.transpose().mul(&omega, atoms)?;
    let xi = vertical.sub(&connection.mul(rdot, atoms)?, atoms)?;
    Ok((vertical, xi))
}

/// The model at the group identity, split into group and shape blocks.
struct BodyForm {
    /// `II`, dg x dg.
    inertia: Matrix,
    /// `M_gr`, dg x nr.
    coupling: Matrix,
    /// `A_xi`, c x dg.
    constraints_group: Matrix,
    /// `A_r`, c x nr.
    constraints_shape: Matrix,
}

impl BodyForm {
    fn of(
        model: &Model,
        cx: &mut Context,
        group: &[usize],
        shape: &[usize],
    ) -> Result<BodyForm, SymError> {
        let identity: HashMap<SymbolId, ExprId> = group
            .iter()
            .map(|&i| (model.coordinates[i].symbol, cx.integer(0)))
            .collect();
        let mass = at(cx, &model.mass_matrix, &identity)?;
        let constraints = at(cx, &model.constraint_matrix, &identity)?;

        let rows: Vec<usize> = (0..constraints.rows()).collect();
        Ok(BodyForm {
            inertia: mass.submatrix(group, group),
            coupling: mass.submatrix(group, shape),
            constraints_group: constraints.submatrix(&rows, group),
            constraints_shape: constraints.submatrix(&rows, shape),
        })
    }
}

/// `matrix` with the symbols replaced, in normal form.
fn at(
    cx: &mut Context,
    matrix: &Matrix,
    replacements: &HashMap<SymbolId, ExprId>,
) -> Result<Matrix, SymError> {
    let mut result = Matrix::zeros(matrix.rows(), matrix.columns());
    for i in 0..matrix.rows() {
        for j in 0..matrix.columns() {
            let expression = cx.expression_of(matrix.get(i, j));
            let replaced = cx.substitute(expression, replacements)?;
            result.set(i, j, cx.normal(replaced)?);
        }
    }
    Ok(result)
}

/// The basis of `S = {xi : A_xi xi = 0}` with the module's normalization.
fn body_basis(constraints_group: &Matrix, atoms: &Atoms) -> Result<Matrix, MatrixError> {
    let mut basis = constraints_group.null_space(atoms)?;
    for i in 0..basis.rows() {
        let row: Vec<RationalFunction> = (0..basis.columns())
            .map(|j| basis.get(i, j).clone())
            .collect();
        let row = without_atom_factors(&normalized(&row, atoms), atoms);
        for (j, entry) in row.into_iter().enumerate() {
            basis.set(i, j, entry);
        }
    }
    Ok(basis)
}

/// Each basis vector divided by a constant (a function of the parameters
/// only): its entry of largest magnitude at the default configuration
/// (coordinates 0, parameters at their defaults), evaluated there exactly.
/// That entry is then 1 at q = 0 for every parameter value.
fn unit_at_defaults(model: &Model, cx: &mut Context, basis: &Matrix) -> Result<Matrix, SymError> {
    let defaults = default_point(model);
    let at_zero: HashMap<SymbolId, ExprId> = model
        .coordinate_symbols()
        .into_iter()
        .map(|q| (q, cx.integer(0)))
        .collect();
    let mut scaled = basis.clone();
    for i in 0..basis.rows() {
        let values: Vec<f64> = (0..basis.columns())
            .map(|j| cx.evaluate_normal(basis.get(i, j), &defaults))
            .collect();
        let Some(largest) = (0..values.len())
            .filter(|&j| values[j].is_finite())
            .max_by(|&a, &b| values[a].abs().total_cmp(&values[b].abs()))
        else {
            continue;
        };
        let entry = cx.expression_of(basis.get(i, largest));
        let constant = cx.substitute(entry, &at_zero)?;
        let constant = cx.normal(constant)?;
        let atoms = cx.atoms().clone();
        for j in 0..basis.columns() {
            if let Some(value) = basis.get(i, j).div(&constant, &atoms) {
                scaled.set(i, j, value);
            }
        }
    }
    Ok(scaled)
}

/// Of the vectors `v / v_j` (one per non-zero entry) with their denominators
/// cleared, the one of least total size; the first on ties.
fn normalized(vector: &[RationalFunction], atoms: &Atoms) -> Vec<RationalFunction> {
    vector
        .iter()
        .filter_map(|pivot| {
            let scaled: Option<Vec<RationalFunction>> =
                vector.iter().map(|entry| entry.div(pivot, atoms)).collect();
            scaled.map(|scaled| cleared(&scaled, atoms))
        })
        .min_by_key(|candidate| candidate.iter().map(RationalFunction::size).sum::<usize>())
        .unwrap_or_else(|| vector.to_vec())
}

/// `vector` divided by each atom (a shape coordinate, a sine or a cosine, a
/// parameter) that divides every entry exactly, as often as it does: a
/// factor common to all entries vanishes where the vector does not
/// degenerate as a direction (the roller racer's `sin(phi)`, its third
/// entry `cos(phi)^2 - 1` being `-sin(phi)^2` in the engine's normal form).
fn without_atom_factors(vector: &[RationalFunction], atoms: &Atoms) -> Vec<RationalFunction> {
    let mut vector = vector.to_vec();
    let mut candidates: Vec<_> = vector.iter().flat_map(RationalFunction::atoms).collect();
    candidates.sort_unstable();
    candidates.dedup();
    for atom in candidates {
        let factor = RationalFunction::from_poly(Poly::atom(atom));
        while let Some(divided) = divided_exactly(&vector, &factor, atoms) {
            vector = divided;
        }
    }
    vector
}

/// Every entry of `vector` over `factor`, when each is a polynomial again
/// and not all are zero.
fn divided_exactly(
    vector: &[RationalFunction],
    factor: &RationalFunction,
    atoms: &Atoms,
) -> Option<Vec<RationalFunction>> {
    if vector.iter().all(RationalFunction::is_zero) {
        return None;
    }
    vector
        .iter()
        .map(|entry| {
            let quotient = entry.div(factor, atoms)?;
            quotient.as_polynomial().is_some().then_some(quotient)
        })
        .collect()
}

/// `vector` times the least common multiple of its entries' denominators.
fn cleared(vector: &[RationalFunction], atoms: &Atoms) -> Vec<RationalFunction> {
    let mut scale = RationalFunction::one();
    for entry in vector {
        let scaled = entry.mul(&scale, atoms);
        if let Some(denominator) = scaled.reciprocal_of_denominator().inverse(atoms) {
            scale = scale.mul(&denominator, atoms);
        }
    }
    vector
        .iter()
        .map(|entry| entry.mul(&scale, atoms))
        .collect()
}

/// `A_nh`: the horizontal velocity `-A_nh rdot` satisfies the independent
/// rows of the body constraints and carries no momentum; fails when the
/// remaining constraint rows then fail (shape velocities constrained).
/// With it, its quotient by Cramer's rule in the `shape` symbols.
fn connection(
    cx: &mut Context,
    body: &BodyForm,
    basis: &Matrix,
    shape: &[SymbolId],
) -> Result<(Matrix, ConnectionQuotient), MomentumError> {
    let atoms = &cx.atoms().clone();
    let independent = independent_rows(&body.constraints_group, atoms);
    let group_rows: Vec<usize> = (0..basis.columns()).collect();
    let shape_columns: Vec<usize> = (0..body.coupling.columns()).collect();
    let system = stack(
        &body.constraints_group.submatrix(&independent, &group_rows),
        &basis.mul(&body.inertia, atoms)?,
    );
    let rhs = stack(
        &body
            .constraints_shape
            .submatrix(&independent, &shape_columns),
        &basis.mul(&body.coupling, atoms)?,
    );
    if system.rows() != basis.columns() {
        return Err(MomentumError::ShapeConstrained);
    }
    let connection = system.solve(&rhs, atoms)?;
    let residual = body
        .constraints_group
        .mul(&connection, atoms)?
        .sub(&body.constraints_shape, atoms)?;
    if !residual.is_zero() {
        return Err(MomentumError::ShapeConstrained);
    }
    let quotient = curvature::connection_quotient(cx, (&system, &rhs), &connection, shape)?;
    Ok((connection, quotient))
}

/// Indices of a maximal set of independent rows, chosen greedily in order.
fn independent_rows(matrix: &Matrix, atoms: &Atoms) -> Vec<usize> {
    let columns: Vec<usize> = (0..matrix.columns()).collect();
    let mut chosen = Vec::new();
    for i in 0..matrix.rows() {
        chosen.push(i);
        if matrix.submatrix(&chosen, &columns).rank(atoms) < chosen.len() {
            chosen.pop();
        }
    }
    chosen
}

/// `top` above `bottom` (same number of columns).
fn stack(top: &Matrix, bottom: &Matrix) -> Matrix {
    let mut result = Matrix::zeros(top.rows() + bottom.rows(), top.columns());
    for j in 0..top.columns() {
        for i in 0..top.rows() {
            result.set(i, j, top.get(i, j).clone());
        }
        for i in 0..bottom.rows() {
            result.set(top.rows() + i, j, bottom.get(i, j).clone());
        }
    }
    result
}

/// `pdot_i = < II xi + M_gr rdot, [xi, e_i] + (de_i/dr) rdot >`.
fn momentum_rhs(
    cx: &mut Context,
    body: &BodyForm,
    basis: &Matrix,
    xi: &Matrix,
    rdot: &Matrix,
    shape_symbols: &[SymbolId],
    factors: &[GroupFactor],
) -> Result<Vec<RationalFunction>, MatrixError> {
    let atoms = cx.atoms().clone();
    let mu = body
        .inertia
        .mul(xi, &atoms)?
        .add(&body.coupling.mul(rdot, &atoms)?, &atoms)?;
    let mut rhs = Vec::with_capacity(basis.rows());
    for i in 0..basis.rows() {
        let e: Vec<RationalFunction> = (0..basis.columns())
            .map(|j| basis.get(i, j).clone())
            .collect();
        let rate = cx.jacobian(&e, shape_symbols)?.mul(rdot, &atoms)?;
        let direction = Matrix::new(e.len(), 1, bracket(xi.entries(), &e, factors, &atoms))?
            .add(&rate, &atoms)?;
        rhs.push(mu.transpose().mul(&direction, &atoms)?.get(0, 0).clone());
    }
    Ok(rhs)
}

/// `H^i, K^i, D^i` by exact second derivatives, proven to reproduce `pdot_i`.
fn coefficients(
    cx: &mut Context,
    index: usize,
    pdot: &RationalFunction,
    rdot: &[SymbolId],
    momenta: &[SymbolId],
) -> Result<Coefficients, MomentumError> {
    let half = Rational::HALF;
    let by_rdot = cx.jacobian(std::slice::from_ref(pdot), rdot)?;
    let by_p = cx.jacobian(std::slice::from_ref(pdot), momenta)?;
    let shape = halved(cx.jacobian(by_rdot.entries(), rdot)?, &half);
    let mixed = cx.jacobian(by_rdot.entries(), momenta)?;
    let momentum = halved(cx.jacobian(by_p.entries(), momenta)?, &half);
    let atoms = cx.atoms().clone();
    let rdot_column = column_of_symbols(cx, rdot)?;
    let p_column = column_of_symbols(cx, momenta)?;
    let form = quadratic(&rdot_column, &shape, &rdot_column, &atoms)?
        .add(&quadratic(&rdot_column, &mixed, &p_column, &atoms)?, &atoms)
        .add(&quadratic(&p_column, &momentum, &p_column, &atoms)?, &atoms);
    if !form.sub(pdot, &atoms).is_zero() {
        return Err(MomentumError::NotQuadratic(index));
    }
    Ok(Coefficients {
        shape,
        mixed,
        momentum,
    })
}

fn halved(matrix: Matrix, half: &Rational) -> Matrix {
    let mut result = matrix.clone();
    for i in 0..matrix.rows() {
        for j in 0..matrix.columns() {
            result.set(i, j, matrix.get(i, j).scale(half));
        }
    }
    result
}

/// `left^T matrix right` for columns `left`, `right`.
fn quadratic(
    left: &Matrix,
    matrix: &Matrix,
    right: &Matrix,
    atoms: &Atoms,
) -> Result<RationalFunction, MatrixError> {
    if left.rows() == 0 || right.rows() == 0 {
        return Ok(RationalFunction::zero());
    }
    Ok(left
        .transpose()
        .mul(matrix, atoms)?
        .mul(right, atoms)?
        .get(0, 0)
        .clone())
}

/// `p(q, qdot) = h M qdot` and the inputs' term `h B`.
fn configuration_terms(
    model: &Model,
    cx: &mut Context,
    basis: &Matrix,
    factors: &[GroupFactor],
    group: &[usize],
) -> Result<(Vec<RationalFunction>, Matrix), MomentumError> {
    let h = spatial_basis(model, cx, basis, factors, group)?;
    let qdot = column_of_symbols(cx, &model.velocities)?;
    let atoms = cx.atoms().clone();
    let momentum = h.mul(&model.mass_matrix, &atoms)?.mul(&qdot, &atoms)?;
    let input_coupling = h.mul(&model.input_matrix, &atoms)?;
    Ok((momentum.entries().to_vec(), input_coupling))
}

/// `h(q)`, mp x n: `h_i` is `e_i` on the group coordinates, each se(2)
/// factor's `(v1, v2)` part rotated by `R(theta)`, and 0 on the shape, so
/// that `p = h M(q) qdot`.
fn spatial_basis(
    model: &Model,
    cx: &mut Context,
    basis: &Matrix,
    factors: &[GroupFactor],
    group: &[usize],
) -> Result<Matrix, SymError> {
    let mut h = Matrix::zeros(basis.rows(), model.n());
    for i in 0..basis.rows() {
        for (j, &coordinate) in group.iter().enumerate() {
            h.set(i, coordinate, basis.get(i, j).clone());
        }
    }
    for (o, theta) in se2_blocks(factors) {
        let theta = cx.symbol(model.coordinates[theta].symbol);
        let cos = cx.apply(Function::Cos, theta)?;
        let sin = cx.apply(Function::Sin, theta)?;
        let (cos, sin) = (cx.normal(cos)?, cx.normal(sin)?);
        let atoms = cx.atoms().clone();
        for i in 0..basis.rows() {
            let (a, b) = (basis.get(i, o), basis.get(i, o + 1));
            let x = cos.mul(a, &atoms).sub(&sin.mul(b, &atoms), &atoms);
            let y = sin.mul(a, &atoms).add(&cos.mul(b, &atoms), &atoms);
            h.set(i, group[o], x);
            h.set(i, group[o + 1], y);
        }
    }
    Ok(h)
}

#[cfg(test)]
mod tests;
