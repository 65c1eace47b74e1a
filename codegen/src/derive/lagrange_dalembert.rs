//! The Lagrange-d'Alembert equations with multipliers (MATH.md section 2;
//! Moore, "Nonholonomic Constraints", the chapter's dynamical equations with
//! Lagrange multipliers; Bloch, Baillieul, Crouch & Marsden, *Nonholonomic
//! Mechanics and Control*, chapter 5, the Lagrange-d'Alembert principle):
//!
//! ```text
//! g(q) qddot + C(q, qdot) + dV/dq = A(q)^T lambda + B(q) u
//! A(q) qddot + Adot(q, qdot) qdot = 0
//! C_i        = sum_jk (dg_ij/dq_k - 1/2 dg_jk/dq_i) qdot_j qdot_k
//! Adot qdot  = sum_k d(A qdot)/dq_k qdot_k
//! ```
//!
//! `C` is computed as `d(g qdot)/dq qdot - dT/dq` with `T = 1/2 qdot^T g qdot`,
//! the same sum regrouped, on normal forms ([`Force::exact`]); the force
//! emitted ([`Force::expressions`]) is the cheaper of those written out and
//! the same terms taken on expressions: `d/dt dT/dqdot - dT/dq` of the
//! declared `T` differentiated on its DAG, and for each declared body Kane's
//! form `m J_v^T a + J_w^T (I alpha + omega x I omega)`
//! ([`crate::model::BodyMotion`]), which for the benchmark bicycle weighs a
//! twenty-fifth of the normal forms. `lambda` are the constraint forces for
//! the rows of `A` exactly as declared. Two ways to solve for `(qddot, lambda)`:
//!
//! - **symbolic**: with exact inverses (block by block, [`Matrix::solve`]),
//!   `lambda = (A g^-1 A^T)^-1 (A g^-1 (C + dV/dq - B u) - Adot qdot)` and
//!   `qddot = g^-1 (B u - C - dV/dq + A^T lambda)`;
//! - **numeric**: emit `g`, `A`, `f = B u - C - dV/dq` and `d = -Adot qdot`
//!   as straight-line code, and after them the solution of
//!   `g qddot = f + A^T lambda`, `A qddot = d` by blocks, computed on the
//!   numbers: `g = L D L^T` (unit lower `L`), `W = L^-1 A^T`, the Schur
//!   complement `S = A g^-1 A^T = W^T D^-1 W`, then
//!
//!   ```text
//!   S lambda = d - W^T D^-1 L^-1 f,   qddot = L^-T D^-1 (L^-1 f + W lambda)
//!   ```
//!
//!   with `S = L_S D_S L_S^T` likewise. `g` is positive definite, and `S`
//!   is wherever the constraint rows are independent, so neither
//!   factorization needs pivoting: the solve is written out as expressions
//!   ([`crate::sym::Store::ldl`]), skipping the structural zeros of `A`,
//!   and fails (division by a zero pivot) exactly where the equations do.
//!
//! The cheaper one is chosen ([`LagrangeDalembert::strategy`]) by the
//! weighted cost [`crate::ir::estimated_weight`] estimates on the expression
//! DAG, without lowering either (a division weighs four additions, a call of
//! `sin` twenty). Exact inverses grow
//! quickly with the size of a dense block (a 6 x 6 coupled metric with trig
//! entries does not finish in minutes), so the closed form is only derived
//! when every diagonal block of `g`, and `c`, are at most
//! [`CLOSED_FORM_LIMIT`], and within [`CLOSED_FORM_PRODUCTS`] term products;
//! otherwise the numeric strategy is taken outright.

pub mod jacobian;

use crate::ir;
use crate::model::Model;
use crate::sym::Context;
use crate::sym::{ExprId, Matrix, MatrixError, Poly, RationalFunction, SymbolId, SymbolKind};

/// How `acceleration` computes `(qddot, lambda)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// Closed-form expressions from exact symbolic inverses.
    Symbolic,
    /// The saddle-point system assembled and solved at run time.
    Numeric,
}

/// The closed-form solution, as n x 1 and c x 1 columns.
#[derive(Clone, Debug)]
pub struct ClosedForm {
    /// `qddot(q, qdot, u)`.
    pub accelerations: Matrix,
    /// `lambda(q, qdot, u)`, one per declared constraint row.
    pub multipliers: Matrix,
}

/// The pieces of `[[g, A^T], [A, 0]] [qddot; -lambda] = [force; drift]`.
#[derive(Clone, Debug)]
pub struct SaddlePointSystem {
    /// `g(q)`, n x n.
    pub mass_matrix: Matrix,
    /// `A(q)`, c x n.
    pub constraint_matrix: Matrix,
    /// `B u - C - dV/dq`, n x 1.
    pub force: Force,
    /// `-Adot qdot`, c x 1.
    pub drift: Drift,
}

/// `-Adot qdot`: exact normal forms within [`EXACT_DRIFT_PRODUCTS`] when
/// the rows are written out ([`Matrix::is_written_out`]), else expressions
/// (the square root in a rolling wheel's contact point makes the normal
/// forms of its rows' derivatives too large to form).
#[derive(Clone, Debug)]
pub enum Drift {
    /// Normal forms.
    Exact(Matrix),
    /// Expressions, `-sum_jk d A_ij/dq_k qdot_j qdot_k`.
    Structured(Matrix<ExprId>),
}

impl Drift {
    /// The normal forms, when exact.
    pub fn exact(&self) -> Option<&Matrix> {
        match self {
            Drift::Exact(drift) => Some(drift),
            Drift::Structured(_) => None,
        }
    }

    /// The entries as expressions.
    pub fn expressions(&self, cx: &mut Context) -> Matrix<ExprId> {
        match self {
            Drift::Exact(drift) => drift.to_expression_matrix(cx),
            Drift::Structured(drift) => drift.clone(),
        }
    }
}

/// `B u - C - dV/dq`: its normal forms when they fit
/// [`EXACT_FORCE_PRODUCTS`] and `g` is written out ([`Matrix::is_written_out`];
/// the force's normal forms come from `g`'s derivatives), and the expressions
/// `acceleration` computes it by: the normal forms written out, or the derivatives of the energies
/// taken on the DAG they were derived as ([`crate::model::EnergyExpressions`]),
/// whichever [`crate::ir::estimated_weight`] finds cheaper (a mechanism's
/// `T` expanded is far larger than its bodies' sum, and so are the normal
/// forms of its derivatives).
#[derive(Clone, Debug)]
pub struct Force {
    /// The normal forms, n x 1, when within budget.
    pub exact: Option<Matrix>,
    /// The expressions emitted, n x 1.
    pub expressions: Matrix<ExprId>,
}

/// The factors of the solve by blocks (see the module documentation),
/// taken once and reused for every right-hand side: `acceleration`'s and
/// the columns of its Jacobian ([`jacobian`]).
#[derive(Clone, Debug)]
pub struct BlockFactors {
    /// `L` of `g = L D L^T`, n x n, unit lower-triangular.
    lower: Matrix<ExprId>,
    /// `D`, the pivots of `g`.
    pivots: Vec<ExprId>,
    /// `W = L^-1 A^T`, n x c.
    w: Matrix<ExprId>,
    /// `D^-1 W`.
    w_scaled: Matrix<ExprId>,
    /// `L_S` of the Schur complement `S = W^T D^-1 W = L_S D_S L_S^T`, c x c.
    schur_lower: Matrix<ExprId>,
    /// `D_S`, the pivots of `S`.
    schur_pivots: Vec<ExprId>,
}

/// The term products the exact `B u - C - dV/dq` may take.
pub const EXACT_FORCE_PRODUCTS: u64 = 2_000_000;

/// The term products the exact `Adot qdot` may take.
pub const EXACT_DRIFT_PRODUCTS: u64 = 2_000_000;

/// The derived equations, both solutions, and which one is emitted.
#[derive(Clone, Debug)]
pub struct LagrangeDalembert {
    /// The input symbols `u`, named as the model's inputs.
    pub inputs: Vec<SymbolId>,
    /// The closed-form solution, when [`CLOSED_FORM_LIMIT`] allowed deriving it.
    pub closed_form: Option<ClosedForm>,
    /// The system solved numerically.
    pub saddle_point: SaddlePointSystem,
    /// The factors its solve by blocks reuses for every right-hand side.
    pub block_factors: BlockFactors,
    /// `qddot` then `lambda`, the system's solution by blocks, as
    /// expressions over its pieces.
    pub numeric_solution: Vec<ExprId>,
    /// The estimated weighted costs ([`crate::ir::estimated_weight`]) of the
    /// closed form (when derived) and of the numeric solution, which decide
    /// the strategy.
    pub weighted_costs: (Option<u64>, u64),
    /// The cheaper of the two (symbolic on a tie; numeric without a closed form).
    pub strategy: Strategy,
}

/// Why the derivation failed (an internal error: checked models have a
/// positive definite `g` and full-rank `A`).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DerivationError {
    /// A symbolic matrix operation failed.
    #[error(transparent)]
    Matrix(#[from] MatrixError),
}

/// The largest diagonal block of `g`, and the largest `c`, for which the
/// closed form is derived.
pub const CLOSED_FORM_LIMIT: usize = 4;

/// The term products the closed form may take (a nested budget,
/// [`crate::sym::Context::attempt`]); beyond them only the run-time system is
/// derived.
pub const CLOSED_FORM_PRODUCTS: u64 = 1_000_000;

/// Derives both solutions (the closed form within [`CLOSED_FORM_LIMIT`] and
/// [`CLOSED_FORM_PRODUCTS`]) and chooses the cheaper.
pub fn derive(model: &Model, cx: &mut Context) -> Result<LagrangeDalembert, DerivationError> {
    let inputs = declare_inputs(model, cx);
    let terms = Terms::of(model, cx, &inputs)?;
    let saddle_point = terms.saddle_point(model, cx);
    let block_factors = BlockFactors::of(model, cx)?;
    let numeric_solution = saddle_point.solution_by_blocks(&block_factors, cx)?;
    let numeric_weight = ir::estimated_weight(cx, &numeric_solution);
    let closed_form = if closed_form_is_tractable(model) {
        cx.attempt(CLOSED_FORM_PRODUCTS, |cx| terms.closed_form(model, cx))
            .transpose()?
            .flatten()
    } else {
        None
    };
    let symbolic_weight = closed_form.as_ref().map(|closed_form| {
        let outputs = closed_form.outputs(cx);
        ir::estimated_weight(cx, &outputs)
    });
    let strategy = match symbolic_weight {
        Some(weight) if weight <= numeric_weight => Strategy::Symbolic,
        _ => Strategy::Numeric,
    };
    Ok(LagrangeDalembert {
        inputs,
        closed_form,
        saddle_point,
        block_factors,
        numeric_solution,
        weighted_costs: (symbolic_weight, numeric_weight),
        strategy,
    })
}

/// Whether every diagonal block of `g`, and `c`, are within [`CLOSED_FORM_LIMIT`].
fn closed_form_is_tractable(model: &Model) -> bool {
    let largest_block = model
        .mass_matrix
        .diagonal_blocks()
        .iter()
        .map(Vec::len)
        .max()
        .unwrap_or(0);
    largest_block <= CLOSED_FORM_LIMIT && model.c() <= CLOSED_FORM_LIMIT
}

/// `u`: one auxiliary symbol per input, named as declared.
fn declare_inputs(model: &Model, cx: &mut Context) -> Vec<SymbolId> {
    model
        .inputs
        .iter()
        .map(|input| cx.declare(&input.name, SymbolKind::Auxiliary))
        .collect()
}

/// The terms of the equations, as columns.
struct Terms {
    /// `B u - C - dV/dq`, n x 1.
    force: Force,
    /// `Adot qdot`, c x 1, when its normal forms fit [`EXACT_DRIFT_PRODUCTS`].
    constraint_drift: Option<Matrix>,
}

impl Terms {
    fn of(model: &Model, cx: &mut Context, inputs: &[SymbolId]) -> Result<Terms, DerivationError> {
        let atoms = cx.atoms().clone();
        let velocity = symbol_column(cx, &model.velocities)?;
        let force = Force::of(model, cx, inputs)?;
        let exact_drift = |cx: &mut Context| {
            let residual = model.constraint_matrix.mul(&velocity, &atoms)?;
            directional_derivative(model, cx, &residual, &velocity)
        };
        let constraint_drift = match model.constraint_matrix.is_written_out() {
            true => cx.attempt(EXACT_DRIFT_PRODUCTS, exact_drift).transpose()?,
            false => None,
        };
        Ok(Terms {
            force,
            constraint_drift,
        })
    }

    /// `lambda = (A g^-1 A^T)^-1 (-A g^-1 f - Adot qdot)`, `qddot = g^-1 (f + A^T lambda)`.
    fn closed_form(&self, model: &Model, cx: &Context) -> Result<Option<ClosedForm>, MatrixError> {
        let (Some(constraint_drift), Some(force)) = (&self.constraint_drift, &self.force.exact)
        else {
            return Ok(None);
        };
        let atoms = cx.atoms();
        let (g, a) = (&model.mass_matrix, &model.constraint_matrix);
        let a_transpose = a.transpose();
        let g_inverse_a_transpose = g.solve(&a_transpose, atoms)?;
        let g_inverse_force = g.solve(force, atoms)?;
        let schur = a.mul(&g_inverse_a_transpose, atoms)?;
        let schur_rhs = a
            .mul(&g_inverse_force, atoms)?
            .add(constraint_drift, atoms)?
            .neg();
        let multipliers = schur.solve(&schur_rhs, atoms)?;
        let accelerations =
            g_inverse_force.add(&g_inverse_a_transpose.mul(&multipliers, atoms)?, atoms)?;
        Ok(Some(ClosedForm {
            accelerations,
            multipliers,
        }))
    }

    fn saddle_point(&self, model: &Model, cx: &mut Context) -> SaddlePointSystem {
        let drift = match &self.constraint_drift {
            Some(drift) => Drift::Exact(drift.neg()),
            None => Drift::Structured(structured_drift(model, cx)),
        };
        SaddlePointSystem {
            mass_matrix: model.mass_matrix.clone(),
            constraint_matrix: model.constraint_matrix.clone(),
            force: self.force.clone(),
            drift,
        }
    }
}

impl ClosedForm {
    /// `qddot` then `lambda`, as expressions.
    pub fn outputs(&self, cx: &mut Context) -> Vec<ExprId> {
        let mut outputs = self.accelerations.to_expressions(cx);
        outputs.extend(self.multipliers.to_expressions(cx));
        outputs
    }
}

impl SaddlePointSystem {
    /// `qddot` then `lambda` by blocks (see the module documentation), as
    /// expressions over the system's pieces and `factors`.
    pub fn solution_by_blocks(
        &self,
        factors: &BlockFactors,
        cx: &mut Context,
    ) -> Result<Vec<ExprId>, MatrixError> {
        let drift = self.drift.expressions(cx);
        let (accelerations, multipliers) = factors.solve(cx, &self.force.expressions, &drift)?;
        let mut outputs = accelerations.entries().to_vec();
        outputs.extend(multipliers.entries());
        Ok(outputs)
    }

    /// `g` and `A` row-major, then `force`, then `drift`, as expressions.
    pub fn outputs(&self, model: &Model, cx: &mut Context) -> Vec<ExprId> {
        let mut outputs = self.mass_matrix.to_expressions(cx);
        outputs.extend(model.constraint_expressions.entries());
        outputs.extend(self.force.expressions.entries());
        outputs.extend(self.drift.expressions(cx).entries());
        outputs
    }
}

impl BlockFactors {
    /// The factors of `g` and of the Schur complement `A g^-1 A^T`, over
    /// the expressions of the model's `g` and `A`.
    pub fn of(model: &Model, cx: &mut Context) -> Result<BlockFactors, MatrixError> {
        let g = &model.energy_expressions.mass_matrix;
        let a = &model.constraint_expressions;
        let (lower, pivots) = cx.ldl(g)?;
        let w = cx.forward_substitution(&lower, &a.transpose());
        let w_scaled = cx.divide_rows(&w, &pivots)?;
        let schur = symmetric_product(cx, &w, &w_scaled)?;
        let (schur_lower, schur_pivots) = cx.ldl(&schur)?;
        Ok(BlockFactors {
            lower,
            pivots,
            w,
            w_scaled,
            schur_lower,
            schur_pivots,
        })
    }

    /// `(qddot, lambda)` solving `g qddot = force + A^T lambda`,
    /// `A qddot = drift` column by column: for `k` columns of `force`
    /// (n x k) and `drift` (c x k), `qddot` is n x k and `lambda` c x k.
    pub fn solve(
        &self,
        cx: &mut Context,
        force: &Matrix<ExprId>,
        drift: &Matrix<ExprId>,
    ) -> Result<(Matrix<ExprId>, Matrix<ExprId>), MatrixError> {
        let z = cx.forward_substitution(&self.lower, force);
        let reduced_drift = drift.sub(&self.w_scaled.transpose().mul(&z, cx)?, cx)?;
        let y = cx.forward_substitution(&self.schur_lower, &reduced_drift);
        let y = cx.divide_rows(&y, &self.schur_pivots)?;
        let multipliers = cx.back_substitution(&self.schur_lower, &y);
        let moved = z.add(&self.w.mul(&multipliers, cx)?, cx)?;
        let moved = cx.divide_rows(&moved, &self.pivots)?;
        let accelerations = cx.back_substitution(&self.lower, &moved);
        Ok((accelerations, multipliers))
    }
}

/// `u^T v` for two n x c matrices, symmetric because `v` is `u` with its
/// rows scaled: the upper triangle is computed and mirrored.
fn symmetric_product(
    cx: &mut Context,
    u: &Matrix<ExprId>,
    v: &Matrix<ExprId>,
) -> Result<Matrix<ExprId>, MatrixError> {
    let size = u.columns();
    let mut product = cx.zero_matrix(size, size);
    for i in 0..size {
        for j in i..size {
            let row = Matrix::column(u.column_entries(i)).transpose();
            let entry = row.mul(&Matrix::column(v.column_entries(j)), cx)?;
            product.set(i, j, *entry.get(0, 0));
            product.set(j, i, *entry.get(0, 0));
        }
    }
    Ok(product)
}

/// The column of the given symbols.
fn symbol_column(cx: &mut Context, symbols: &[SymbolId]) -> Result<Matrix, MatrixError> {
    let entries: Vec<RationalFunction> = symbols
        .iter()
        .map(|&s| RationalFunction::from_poly(Poly::atom(cx.symbol_atom(s))))
        .collect();
    Matrix::new(entries.len(), 1, entries)
}

impl Force {
    /// The exact force within [`EXACT_FORCE_PRODUCTS`] when `g` is written
    /// out, and the cheaper of its written-out and structured expressions.
    fn of(model: &Model, cx: &mut Context, inputs: &[SymbolId]) -> Result<Force, DerivationError> {
        let exact = match model.mass_matrix.is_written_out() {
            true => cx
                .attempt(EXACT_FORCE_PRODUCTS, |cx| exact_force(model, cx, inputs))
                .transpose()?,
            false => None,
        };
        let structured = structured_force(model, cx, inputs)?;
        let expressions = match &exact {
            Some(exact) => {
                let written = exact.to_expression_matrix(cx);
                let weight = |m: &Matrix<ExprId>| ir::estimated_weight(cx, m.entries());
                if weight(&written) <= weight(&structured) {
                    written
                } else {
                    structured
                }
            }
            None => structured,
        };
        Ok(Force { exact, expressions })
    }
}

/// `B u - C - dV/dq` in normal form, with `C = d(g qdot)/dq qdot - dT/dq`.
fn exact_force(
    model: &Model,
    cx: &mut Context,
    inputs: &[SymbolId],
) -> Result<Matrix, DerivationError> {
    let atoms = cx.atoms().clone();
    let velocity = symbol_column(cx, &model.velocities)?;
    let input = symbol_column(cx, inputs)?;
    let applied = model.input_matrix.mul(&input, &atoms)?;
    let momentum = model.mass_matrix.mul(&velocity, &atoms)?;
    let transport = directional_derivative(model, cx, &momentum, &velocity)?;
    let kinetic = &model.kinetic_energy;
    let potential = &model.potential_energy;
    let energy_gradient =
        gradient(model, cx, kinetic)?.sub(&gradient(model, cx, potential)?, &atoms)?;
    Ok(applied
        .sub(&transport, &atoms)?
        .add(&energy_gradient, &atoms)?)
}

/// `B u - d/dt(dT/dqdot) + dT/dq - dV/dq` at `qddot = 0` as expressions:
/// for the declared part of `T`, the time derivative
/// `sum_k d(dT/dqdot)/dq_k qdot_k` and the gradients taken on the DAG of its
/// expression; for each declared body, Kane's form of the same terms
/// ([`crate::model::BodyMotion::velocity_terms`]).
fn structured_force(
    model: &Model,
    cx: &mut Context,
    inputs: &[SymbolId],
) -> Result<Matrix<ExprId>, MatrixError> {
    let coordinates = model.coordinate_symbols();
    let energies = &model.energy_expressions;
    let (kinetic, potential) = (energies.declared_kinetic, energies.potential);
    let b = model.input_matrix.to_expression_matrix(cx);
    let u = Matrix::column(inputs.iter().map(|&s| cx.symbol(s)).collect());
    let applied = b.mul(&u, cx)?;
    let momenta: Vec<ExprId> = model
        .velocities
        .iter()
        .map(|&v| cx.derivative(kinetic, v))
        .collect();
    let mut lost: Vec<Vec<ExprId>> = vec![Vec::new(); coordinates.len()];
    for (&q, &v) in coordinates.iter().zip(&model.velocities) {
        let velocity = cx.symbol(v);
        for (i, rate) in cx.derivatives(&momenta, q).into_iter().enumerate() {
            lost[i].push(cx.mul2(rate, velocity));
        }
    }
    for body in &energies.bodies {
        let terms = body.velocity_terms(cx, &coordinates, &model.velocities)?;
        for (lost, term) in lost.iter_mut().zip(terms) {
            lost.push(term);
        }
    }
    let entries = coordinates
        .iter()
        .zip(lost)
        .enumerate()
        .map(|(i, (&q, mut lost))| {
            lost.push(cx.derivative(potential, q));
            let lost = cx.add(&lost);
            let kinetic_rate = cx.derivative(kinetic, q);
            let gained = cx.add2(*applied.get(i, 0), kinetic_rate);
            cx.sub(gained, lost)
        })
        .collect();
    Ok(Matrix::column(entries))
}

/// `d f/dq` as an n x 1 column.
fn gradient(
    model: &Model,
    cx: &mut Context,
    f: &RationalFunction,
) -> Result<Matrix, DerivationError> {
    let coordinates = model.coordinate_symbols();
    let row = cx.jacobian(std::slice::from_ref(f), &coordinates)?;
    Ok(row.transpose())
}

/// `-Adot qdot = -sum_k d(A qdot)/dq_k qdot_k` as expressions.
fn structured_drift(model: &Model, cx: &mut Context) -> Matrix<ExprId> {
    let coordinates = model.coordinate_symbols();
    let a = &model.constraint_expressions;
    let velocities: Vec<ExprId> = model.velocities.iter().map(|&v| cx.symbol(v)).collect();
    let entries = (0..a.rows())
        .map(|i| {
            let terms: Vec<ExprId> = (0..a.columns())
                .map(|j| cx.mul2(*a.get(i, j), velocities[j]))
                .collect();
            let residual = cx.add(&terms);
            let rates: Vec<ExprId> = coordinates
                .iter()
                .zip(&velocities)
                .map(|(&q, &velocity)| {
                    let rate = cx.derivative(residual, q);
                    cx.mul2(rate, velocity)
                })
                .collect();
            let rate = cx.add(&rates);
            cx.neg(rate)
        })
        .collect();
    Matrix::column(entries)
}

/// `sum_k d column/dq_k qdot_k`: the rate of change of `column(q)` along `qdot`.
fn directional_derivative(
    model: &Model,
    cx: &mut Context,
    column: &Matrix,
    velocity: &Matrix,
) -> Result<Matrix, DerivationError> {
    let coordinates = model.coordinate_symbols();
    let jacobian = cx.jacobian(column.entries(), &coordinates)?;
    Ok(jacobian.mul(velocity, &cx.atoms().clone())?)
}

#[cfg(test)]
mod tests;
