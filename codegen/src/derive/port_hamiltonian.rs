//! Reduced port-Hamiltonian form (Duindam & Stramigioli, "Energy-based model
//! reduction of nonholonomic mechanical systems", Theorem 1; MATH.md section 3).
//!
//! The momenta `p = g qdot` of allowed motions lie in `g(D)`, spanned by the k
//! rows of a momentum basis `h(q)` (k x n): `p = h^T alpha`. The basis is the
//! declared one, or `h = (g X)^T` from a basis `X` of D (section 1) when none
//! is declared. With
//!
//! ```text
//! gbar_inv = h g^-1 h^T                      (k x k)
//! gbar     = gbar_inv^-1
//! P        = gbar h g^-1                     (k x n, P h^T = I)
//! Gamma_ab = alpha_c dh^c(P^T e_a, P^T e_b)  (k x k)
//! dh^c(X, Y) = X^j Y^l (d h^c_l / d q_j - d h^c_j / d q_l)
//! Hbar     = 1/2 alpha^T gbar_inv alpha + V(q)
//! ```
//!
//! the state `x = (q, alpha)` of size `s = n + k` obeys, with no multipliers
//! and no constraints left,
//!
//! ```text
//! xdot = Jbar dHbar/dx + Bbar u,   y = Bbar^T dHbar/dx,
//! Jbar = [[0, P^T], [-P, Gamma]],   Bbar = [0; P B].
//! ```
//!
//! `Jbar` is skew-symmetric, so `dHbar/dt = y . u`; the derivation proves it
//! exactly (`Jbar + Jbar^T` is zero in normal form) and fails otherwise. The
//! velocities are `qdot = g^-1 h^T alpha` and the momenta `alpha = P g qdot`.
//! Whether `gbar` is constant (free of the coordinates) and diagonal is
//! decided exactly and recorded.
//!
//! **Exact and structured.** With a declared basis every matrix is derived
//! in exact normal form ([`Exact`]). With the tool's basis the exact form is
//! attempted first, on a nested budget of [`EXACT_REDUCED_PRODUCTS`] term
//! products; when it does not fit, the form is derived structured (the
//! module `structured`): from the basis `X` of D as the elimination of the
//! constraints writes it, without expanding anything ([`ReducedExpressions`]), which
//! grows with the number of operations instead of the number of expanded
//! terms (for a chain of N wheeled links, polynomially in N instead of
//! exponentially). With the exact form, each item can be written two ways,
//! as the expanded entries or as the products of the matrices' entries (the
//! module `expressions`); [`items`] keeps the one estimated cheaper. Without the exact
//! form, `Jbar` is skew by construction and the facts on `gbar` are decided
//! at random points modulo a prime ([`crate::sym::modular`]: "not constant"
//! and "not diagonal" proved, "constant" and "diagonal" probable).

mod expressions;
pub mod items;
mod structured;
pub mod through_solve;

use super::constraints::{DistributionBasis, Elimination, Method};
use crate::model::Model;
use crate::sym::Context;
use crate::sym::modular::{self, ModularError};
use crate::sym::residues::Values;
use crate::sym::{
    Atoms, ExprId, Matrix, MatrixError, Poly, Rational, RationalFunction, SymError, SymbolId,
    SymbolKind,
};
use through_solve::ThroughSolve;

/// The term products the exact reduced form with the tool's basis may
/// take; beyond them only the structured form is derived.
pub const EXACT_REDUCED_PRODUCTS: u64 = 1_000_000;

/// The reduced port-Hamiltonian model: exact normal forms, structured
/// expressions, or both.
#[derive(Clone, Debug)]
pub struct PortHamiltonian {
    /// The names of the reduced momenta: the declared basis rows, or
    /// `alpha1..alphak` for the tool's own basis.
    pub momentum_names: Vec<String>,
    /// The reduced momenta `alpha`, k symbols.
    pub momenta: Vec<SymbolId>,
    /// The inputs `u`, p symbols named as the model's inputs.
    pub inputs: Vec<SymbolId>,
    /// True when `h` was declared, false when the tool chose `(g X)^T`.
    pub declared_basis: bool,
    /// The reduced form as expressions, what its items are built from:
    /// the products of the exact matrices' entries, or the structured
    /// derivation's.
    pub expressions: ReducedExpressions,
    /// The exact normal forms: always for a declared basis, for the tool's
    /// basis when they fit [`EXACT_REDUCED_PRODUCTS`].
    pub exact: Option<Exact>,
    /// `gbar` does not depend on the coordinates.
    pub metric_constant: bool,
    /// `gbar` is diagonal.
    pub metric_diagonal: bool,
    /// How the two facts were decided: on the exact forms, or at random
    /// points on the structured ones.
    pub facts_method: Method,
}

impl PortHamiltonian {
    /// How the form solves for the dependent speeds: exactly, or by
    /// elimination in order (structured).
    pub fn elimination(&self) -> Elimination {
        match self.exact {
            Some(_) => Elimination::Exact,
            None => Elimination::InOrder,
        }
    }
}

/// The reduced form in exact normal form.
#[derive(Clone, Debug)]
pub struct Exact {
    /// `h`, k x n.
    pub basis: Matrix,
    /// `gbar_inv = h g^-1 h^T`, k x k.
    pub metric_inverse: Matrix,
    /// `gbar`, k x k.
    pub metric: Matrix,
    /// `P = gbar h g^-1`, k x n.
    pub projection: Matrix,
    /// `g^-1 h^T`, n x k: `qdot = g^-1 h^T alpha`.
    pub velocity_map: Matrix,
    /// `P g = gbar h`, k x n: `alpha = P g qdot`.
    pub momentum_map: Matrix,
    /// `Gamma`, k x k, linear in `alpha`.
    pub gyroscopic: Matrix,
    /// `Jbar`, s x s, skew-symmetric (proved exactly).
    pub structure: Matrix,
    /// `Bbar`, s x p.
    pub input_matrix: Matrix,
    /// `Hbar(q, alpha)`.
    pub hamiltonian: RationalFunction,
    /// `dHbar/dx`, s entries.
    pub gradient: Vec<RationalFunction>,
    /// `xdot = Jbar dHbar/dx + Bbar u`, s entries, expanded.
    pub rhs: Vec<RationalFunction>,
    /// `y = Bbar^T dHbar/dx`, p entries.
    pub output: Vec<RationalFunction>,
}

/// The reduced form as expressions, unexpanded: what emission lowers.
#[derive(Clone, Debug)]
pub struct ReducedExpressions {
    /// `g^-1 h^T`, n x k.
    pub velocity_map: Matrix<ExprId>,
    /// `P g`, k x n.
    pub momentum_map: Matrix<ExprId>,
    /// `gbar_inv`, k x k.
    pub metric_inverse: Matrix<ExprId>,
    /// `gbar`, k x k.
    pub metric: Matrix<ExprId>,
    /// `Jbar`, s x s.
    pub structure: Matrix<ExprId>,
    /// `Bbar`, s x p.
    pub input_matrix: Matrix<ExprId>,
    /// `Hbar`.
    pub hamiltonian: ExprId,
    /// `dHbar/dx`, s entries.
    pub gradient: Vec<ExprId>,
    /// `xdot`, s entries.
    pub rhs: Vec<ExprId>,
    /// `d xdot / dx`.
    pub rhs_jacobian: RhsJacobian,
    /// `y`, p entries.
    pub output: Vec<ExprId>,
}

/// How `d xdot / dx` is written.
#[derive(Clone, Debug)]
pub enum RhsJacobian {
    /// `xdot` differentiated as expressions of the state and the inputs,
    /// s x s row-major.
    Differentiated(Vec<ExprId>),
    /// By the chain rule through the Lagrange-d'Alembert solve (the
    /// structured form; module `through_solve`).
    ThroughSolve(ThroughSolve),
}

impl RhsJacobian {
    /// The s x s entries, row-major.
    pub fn entries(&self) -> &[ExprId] {
        match self {
            RhsJacobian::Differentiated(entries) => entries,
            RhsJacobian::ThroughSolve(chain) => &chain.jacobian,
        }
    }
}

/// Why the reduced form could not be derived.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PortHamiltonianError {
    /// A solve or product failed (a singular metric, say).
    #[error("reduced port-Hamiltonian form: {0}")]
    Matrix(#[from] MatrixError),
    /// The engine failed on an entry.
    #[error("reduced port-Hamiltonian form: {0}")]
    Symbolic(#[from] SymError),
    /// The structured form's facts could not be evaluated.
    #[error("reduced port-Hamiltonian form: {0}")]
    Undecided(#[from] ModularError),
    /// `Jbar + Jbar^T` is not exactly zero: a bug of the derivation.
    #[error(
        "the derived structure matrix Jbar is not skew-symmetric (entry ({row}, {column}) of Jbar + Jbar^T is not zero)"
    )]
    NotSkew {
        /// Row of the first non-zero entry.
        row: usize,
        /// Its column.
        column: usize,
    },
}

impl PortHamiltonian {
    /// The state symbols `x = (q, alpha)`.
    pub fn state(&self, model: &Model) -> Vec<SymbolId> {
        let mut state = model.coordinate_symbols();
        state.extend(&self.momenta);
        state
    }
}

/// The derivatives of `functions` by every variable of `state`, row by row.
fn state_jacobian(cx: &mut Context, state: &[SymbolId], functions: &[ExprId]) -> Vec<ExprId> {
    let by_variable: Vec<Vec<ExprId>> = state
        .iter()
        .map(|&x| cx.derivatives(functions, x))
        .collect();
    (0..functions.len())
        .flat_map(|i| by_variable.iter().map(move |column| column[i]))
        .collect()
}

/// Derives the reduced port-Hamiltonian form of `model` (Theorem 1): with a
/// declared basis exactly; with the tool's basis exactly when that fits
/// [`EXACT_REDUCED_PRODUCTS`], structured otherwise.
pub fn derive(
    model: &Model,
    cx: &mut Context,
    basis: &DistributionBasis,
) -> Result<PortHamiltonian, PortHamiltonianError> {
    let momentum_names = momentum_names(model);
    let momenta: Vec<SymbolId> = momentum_names
        .iter()
        .map(|name| fresh_symbol(cx, name, SymbolKind::Momentum))
        .collect();
    let inputs: Vec<SymbolId> = model
        .inputs
        .iter()
        .map(|input| fresh_symbol(cx, &input.name, SymbolKind::Auxiliary))
        .collect();
    let exact = match (model.momentum_basis.clone(), &basis.fields) {
        (Some(declared), _) => Some(derive_exact(
            model,
            cx,
            &declared.rows,
            None,
            &momenta,
            &inputs,
        )?),
        (None, Some(fields)) => cx
            .attempt(EXACT_REDUCED_PRODUCTS, |cx| {
                let h = fields.transpose().mul(&model.mass_matrix, cx.atoms())?;
                derive_exact(model, cx, &h, Some(fields), &momenta, &inputs)
            })
            .transpose()?,
        (None, None) => None,
    };
    let (expressions, metric_constant, metric_diagonal, facts_method) = match &exact {
        Some(exact) => {
            let constant = is_constant(model, cx, &exact.metric)?;
            let expressions = exact.expressions(model, cx, &momenta, &inputs)?;
            let diagonal = is_diagonal(&exact.metric);
            (expressions, constant, diagonal, Method::NormalForm)
        }
        None => {
            let expressions = structured::derive(model, cx, basis, &momenta, &inputs)?;
            let (constant, diagonal) = facts_at_points(model, cx, &expressions.metric_inverse)?;
            (expressions, constant, diagonal, Method::Modular)
        }
    };
    Ok(PortHamiltonian {
        momentum_names,
        momenta,
        inputs,
        declared_basis: model.momentum_basis.is_some(),
        expressions,
        exact,
        metric_constant,
        metric_diagonal,
        facts_method,
    })
}

/// The exact form for the momentum basis `h`: with `fields`, the tool's
/// basis `h = X^T g` of the basis `X` of D.
fn derive_exact(
    model: &Model,
    cx: &mut Context,
    h: &Matrix,
    fields: Option<&Matrix>,
    momenta: &[SymbolId],
    inputs: &[SymbolId],
) -> Result<Exact, PortHamiltonianError> {
    let alpha = column_of_symbols(cx, momenta)?;
    let maps = match fields {
        Some(fields) => Maps::of_own_basis(cx, fields, h)?,
        None => Maps::of(model, cx, h)?,
    };
    let gyroscopic = gyroscopic(model, cx, h, &maps, &alpha)?;
    let structure = maps.projection.skew_structure(
        &gyroscopic,
        RationalFunction::zero(),
        RationalFunction::neg,
    );
    prove_skew(&structure, cx.atoms())?;
    let input_matrix = maps
        .projection
        .mul(&model.input_matrix, cx.atoms())?
        .below_zero_rows(model.n(), RationalFunction::zero());
    let flow = Flow::of(model, cx, &maps, &structure, &input_matrix, momenta, inputs)?;
    Ok(Exact {
        basis: h.clone(),
        metric_inverse: maps.metric_inverse,
        metric: maps.metric,
        projection: maps.projection,
        velocity_map: maps.velocity_map,
        momentum_map: maps.momentum_map,
        gyroscopic,
        structure,
        input_matrix,
        hamiltonian: flow.hamiltonian,
        gradient: flow.gradient,
        rhs: flow.rhs,
        output: flow.output,
    })
}

/// Whether `gbar` is constant and diagonal, from `gbar_inv` at random
/// points: a non-zero derivative or off-diagonal entry there proves "no".
fn facts_at_points(
    model: &Model,
    cx: &mut Context,
    metric_inverse: &Matrix<ExprId>,
) -> Result<(bool, bool), ModularError> {
    let mut rates = Vec::new();
    for q in model.coordinate_symbols() {
        rates.extend(cx.derivatives(metric_inverse.entries(), q));
    }
    let k = metric_inverse.rows();
    let off_diagonal: Vec<ExprId> = (0..k * k)
        .filter(|at| at / k != at % k)
        .map(|at| metric_inverse.entries()[at])
        .collect();
    let facts = modular::at_defined_points(modular::SEEDS.len(), |point| {
        let mut values = Values::at(point);
        let constant = values.of(cx, &rates)?.iter().all(|&v| v == 0);
        let diagonal = values.of(cx, &off_diagonal)?.iter().all(|&v| v == 0);
        Ok((constant, diagonal))
    })?;
    Ok(facts
        .iter()
        .fold((true, true), |(c, d), &(constant, diagonal)| {
            (c && constant, d && diagonal)
        }))
}

/// The configuration-dependent maps between velocities and reduced momenta.
struct Maps {
    velocity_map: Matrix,
    metric_inverse: Matrix,
    metric: Matrix,
    projection: Matrix,
    momentum_map: Matrix,
}

impl Maps {
    /// `g^-1 h^T`, `gbar_inv = h g^-1 h^T`, `gbar`, `P = gbar h g^-1` and `P g`.
    fn of(model: &Model, cx: &Context, h: &Matrix) -> Result<Maps, MatrixError> {
        let atoms = cx.atoms();
        let g_inverse = model.mass_matrix.inverse(atoms)?;
        let velocity_map = g_inverse.mul(&h.transpose(), atoms)?;
        let metric_inverse = h.mul(&velocity_map, atoms)?;
        let metric = metric_inverse.inverse(atoms)?;
        let projection = metric.mul(h, atoms)?.mul(&g_inverse, atoms)?;
        let momentum_map = projection.mul(&model.mass_matrix, atoms)?;
        Ok(Maps {
            velocity_map,
            metric_inverse,
            metric,
            projection,
            momentum_map,
        })
    }
}

impl Maps {
    /// [`Maps::of`] for the tool's own basis `h = X^T g` of a basis `X` of
    /// D, without inverting `g`: `g^-1 h^T = X`, `gbar_inv = X^T g X`,
    /// `P = gbar X^T` and `P g = gbar h`. Only the `k x k` matrix
    /// `X^T g X` is inverted, where `Maps::of` inverts the `n x n` `g` (for a
    /// dense trigonometric `g`, e.g. a chain of links, the difference
    /// between seconds and hours).
    fn of_own_basis(cx: &Context, fields: &Matrix, h: &Matrix) -> Result<Maps, MatrixError> {
        let atoms = cx.atoms();
        let velocity_map = fields.clone();
        let metric_inverse = h.mul(fields, atoms)?;
        let metric = metric_inverse.inverse(atoms)?;
        let projection = metric.mul(&fields.transpose(), atoms)?;
        let momentum_map = metric.mul(h, atoms)?;
        Ok(Maps {
            velocity_map,
            metric_inverse,
            metric,
            projection,
            momentum_map,
        })
    }
}

/// The energy and the port-Hamiltonian flow it generates.
struct Flow {
    hamiltonian: RationalFunction,
    gradient: Vec<RationalFunction>,
    rhs: Vec<RationalFunction>,
    output: Vec<RationalFunction>,
}

impl Flow {
    /// `Hbar`, `dHbar/dx`, `Jbar dHbar/dx + Bbar u` and `Bbar^T dHbar/dx`.
    fn of(
        model: &Model,
        cx: &mut Context,
        maps: &Maps,
        structure: &Matrix,
        input_matrix: &Matrix,
        momenta: &[SymbolId],
        inputs: &[SymbolId],
    ) -> Result<Flow, PortHamiltonianError> {
        let alpha = column_of_symbols(cx, momenta)?;
        let u = column_of_symbols(cx, inputs)?;
        let atoms = cx.atoms().clone();
        let hamiltonian = quadratic_form(&alpha, &maps.metric_inverse, &atoms)?
            .scale(&Rational::HALF)
            .add(&model.potential_energy, &atoms);
        let mut state = model.coordinate_symbols();
        state.extend(momenta);
        let gradient = cx
            .jacobian(std::slice::from_ref(&hamiltonian), &state)?
            .transpose();
        let atoms = cx.atoms().clone();
        let rhs = structure
            .mul(&gradient, &atoms)?
            .add(&input_matrix.mul(&u, &atoms)?, &atoms)?;
        let output = input_matrix.transpose().mul(&gradient, &atoms)?;
        Ok(Flow {
            hamiltonian,
            gradient: gradient.entries().to_vec(),
            rhs: rhs.entries().to_vec(),
            output: output.entries().to_vec(),
        })
    }
}

/// The names of the reduced momenta: the declared basis rows', else
/// `alpha1..alphak` for the tool's own basis `h = (g X)^T` (k rows).
pub fn momentum_names(model: &Model) -> Vec<String> {
    match &model.momentum_basis {
        Some(declared) => declared.names.iter().map(|d| d.name.clone()).collect(),
        None => (1..=model.k()).map(|i| format!("alpha{i}")).collect(),
    }
}

/// The symbol called `name` if it is new or already of this kind, else a
/// primed variant (`name'`, `name''`, ...) that is: an input or momentum
/// never captures a parameter or coordinate of the same name.
pub(super) fn fresh_symbol(cx: &mut Context, name: &str, kind: SymbolKind) -> SymbolId {
    let mut candidate = name.to_string();
    loop {
        let symbol = cx.declare(&candidate, kind);
        if cx.symbol_info(symbol).kind == kind {
            return symbol;
        }
        candidate.push('\'');
    }
}

/// The column of the symbols as polynomials.
pub(super) fn column_of_symbols(
    cx: &mut Context,
    symbols: &[SymbolId],
) -> Result<Matrix, MatrixError> {
    let entries = symbols
        .iter()
        .map(|&s| RationalFunction::from_poly(Poly::atom(cx.symbol_atom(s))))
        .collect();
    Matrix::new(symbols.len(), 1, entries)
}

/// `Gamma = sum_c alpha_c P W^c P^T` with `W^c_jl = d h^c_l/d q_j - d h^c_j/d q_l`,
/// so that `Gamma_ab = alpha_c dh^c(P^T e_a, P^T e_b)`.
///
/// With `P = gbar h g^-1 = gbar V^T` (`V = g^-1 h^T`, `g` symmetric) it is
/// computed as `gbar (sum_c alpha_c V^T W^c V) gbar`: the `k x k` sum first,
/// one sandwich by `gbar` last, so the large common denominator of `gbar`
/// enters once instead of through every `n x n` product.
fn gyroscopic(
    model: &Model,
    cx: &mut Context,
    h: &Matrix,
    maps: &Maps,
    alpha: &Matrix,
) -> Result<Matrix, MatrixError> {
    let coordinates = model.coordinate_symbols();
    let k = h.rows();
    let velocity_map = &maps.velocity_map;
    let mut inner = Matrix::zeros(k, k);
    for c in 0..k {
        let row: Vec<RationalFunction> = (0..h.columns()).map(|l| h.get(c, l).clone()).collect();
        // jacobian (l, j) = d h^c_l / d q_j, so W^c = jacobian^T - jacobian
        let jacobian = cx.jacobian(&row, &coordinates)?;
        let atoms = cx.atoms().clone();
        let exterior = jacobian.transpose().sub(&jacobian, &atoms)?;
        if exterior.is_zero() {
            continue;
        }
        let term = velocity_map
            .transpose()
            .mul(&exterior, &atoms)?
            .mul(velocity_map, &atoms)?;
        inner = inner.add(&term.scale(alpha.get(c, 0), &atoms), &atoms)?;
    }
    let atoms = cx.atoms();
    if inner.is_zero() {
        return Ok(inner);
    }
    maps.metric.mul(&inner, atoms)?.mul(&maps.metric, atoms)
}

/// `Hbar = 1/2 alpha^T gbar_inv alpha + V` as an expression.
fn reduced_energy(
    cx: &mut Context,
    alpha: &Matrix<ExprId>,
    metric_inverse: &Matrix<ExprId>,
    potential: ExprId,
) -> Result<ExprId, MatrixError> {
    let twice_kinetic = *alpha
        .transpose()
        .mul(&metric_inverse.mul(alpha, cx)?, cx)?
        .get(0, 0);
    let half = cx.number(Rational::HALF);
    let kinetic = cx.mul2(half, twice_kinetic);
    Ok(cx.add2(kinetic, potential))
}

/// The symbols as a column of expressions.
fn symbols_column(cx: &mut Context, symbols: &[SymbolId]) -> Matrix<ExprId> {
    Matrix::column(symbols.iter().map(|&s| cx.symbol(s)).collect())
}

/// Fails unless `Jbar + Jbar^T` is exactly zero.
fn prove_skew(structure: &Matrix, atoms: &Atoms) -> Result<(), PortHamiltonianError> {
    let sum = structure.add(&structure.transpose(), atoms)?;
    let size = sum.rows();
    match (0..size * size).find(|&at| !sum.get(at / size, at % size).is_zero()) {
        Some(at) => Err(PortHamiltonianError::NotSkew {
            row: at / size,
            column: at % size,
        }),
        None => Ok(()),
    }
}

/// `v^T M v` for a column `v`.
fn quadratic_form(v: &Matrix, m: &Matrix, atoms: &Atoms) -> Result<RationalFunction, MatrixError> {
    let product = v.transpose().mul(&m.mul(v, atoms)?, atoms)?;
    Ok(product.get(0, 0).clone())
}

/// True when no entry depends on a coordinate (exact derivatives).
fn is_constant(model: &Model, cx: &mut Context, matrix: &Matrix) -> Result<bool, MatrixError> {
    let coordinates = model.coordinate_symbols();
    let derivatives = cx.jacobian(matrix.entries(), &coordinates)?;
    Ok(derivatives.is_zero())
}

/// True when every off-diagonal entry is exactly zero.
fn is_diagonal(matrix: &Matrix) -> bool {
    (0..matrix.rows()).all(|i| (0..matrix.columns()).all(|j| i == j || matrix.get(i, j).is_zero()))
}

#[cfg(test)]
mod tests;
