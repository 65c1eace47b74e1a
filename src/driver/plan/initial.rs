//! The model's constraints held at a trajectory's first node, as rows of
//! a nonlinear program: with the first state `x_0 = (q_0, ...)` and the
//! parameters `theta` a fit estimates,
//!
//! ```text
//! c_0(x_0, theta) = (f(q_0; theta), A(q_0; theta) qdot_0) = 0,
//! ```
//!
//! the configuration constraints (`holonomic_residual`, where the model
//! declares some) and the velocity constraints (`constraint_residual`,
//! reading `(q_0, qdot_0)`: the Lagrange form's state). The collocation
//! keeps them after the first node: the formulation's accelerations hold
//! `d/dt (A qdot) = 0` and `d^2/dt^2 f = 0`, and the reduced and momentum
//! states meet `A qdot = 0` by construction. A plan holds them where its
//! start leaves free what they tie; a fit (`identify`), whose first state
//! is free, holds them all.
//!
//! Their values, Jacobian and Hessians are the programs' own and their
//! forward second derivatives along the state's and the estimates' input
//! slots ([`chaplygin_codegen::ir::Program::curvatures`]), exact.

use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::{CallError, InterpretedModel, evaluated};

/// A family of the model's constraints held at the first node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Held {
    /// `f(q_0) = 0`.
    Configuration,
    /// `A(q_0) qdot_0 = 0`.
    Velocity,
}

impl Held {
    /// The program whose outputs are the family's residuals.
    fn function(self) -> &'static str {
        match self {
            Self::Configuration => "holonomic_residual",
            Self::Velocity => "constraint_residual",
        }
    }

    /// How many of the state's first entries the program reads: `q`, or
    /// `(q, qdot)`.
    pub(super) fn reads(self, model: &InterpretedModel) -> usize {
        match self {
            Self::Configuration => model.sizes().n,
            Self::Velocity => 2 * model.sizes().n,
        }
    }

    /// The number of the family's rows.
    pub(super) fn rows(self, model: &InterpretedModel) -> usize {
        match self {
            Self::Configuration => model.names().holonomic.len(),
            Self::Velocity => model.sizes().c,
        }
    }
}

/// Every family of constraints `model` declares.
pub(super) fn declared(model: &InterpretedModel) -> Vec<Held> {
    [Held::Configuration, Held::Velocity]
        .into_iter()
        .filter(|held| held.rows(model) > 0)
        .collect()
}

/// The number of rows of `held`.
pub(super) fn rows(model: &InterpretedModel, held: &[Held]) -> usize {
    held.iter().map(|h| h.rows(model)).sum()
}

/// Row `row` of the families `held` in words: its family and its name as
/// the model declares it.
pub(super) fn row_name(model: &InterpretedModel, held: &[Held], row: usize) -> String {
    let names = model.names();
    let mut first = 0;
    for &family in held {
        let rows = family.rows(model);
        if row < first + rows {
            let (kind, declared) = match family {
                Held::Configuration => ("configuration", &names.holonomic),
                Held::Velocity => ("velocity", &names.constraints),
            };
            let r = row - first;
            return declared.get(r).map_or_else(
                || format!("{kind} constraint {r}"),
                |name| format!("{kind} constraint `{name}`"),
            );
        }
        first += rows;
    }
    format!("row {row}")
}

/// The held constraints at a point: their values, their Jacobian by the
/// state (`state` entries) and the estimated parameters (rows x (state +
/// P')) and each one's Hessian by the same.
pub(super) struct InitialTerms {
    pub(super) values: Vec<f64>,
    pub(super) jacobian: DMatrix<f64>,
    pub(super) hessians: Vec<DMatrix<f64>>,
}

/// `c_0` of the families `held` at the first state `x0` (`state`
/// entries), with its derivatives by `x0` and by the model's parameters
/// of indices `estimated`, at their current values.
pub(super) fn initial_terms(
    model: &InterpretedModel,
    held: &[Held],
    (x0, state): (&[f64], usize),
    estimated: &[usize],
) -> InitialTerms {
    let dim = state + estimated.len();
    let mut terms = InitialTerms {
        values: Vec::new(),
        jacobian: DMatrix::zeros(0, dim),
        hessians: Vec::new(),
    };
    for &family in held {
        add_terms(model, family, (x0, state), estimated, &mut terms);
    }
    terms
}

/// Appends the rows of `family`, whose arguments are the first entries of
/// the state.
fn add_terms(
    model: &InterpretedModel,
    family: Held,
    (x0, state): (&[f64], usize),
    estimated: &[usize],
    terms: &mut InitialTerms,
) {
    let (function, read) = (family.function(), family.reads(model));
    let program = model
        .programs()
        .find(|(name, _)| *name == function)
        .map(|(_, program)| program)
        .expect("a constrained model has its residual programs");
    let inputs: Vec<f64> = x0[..read]
        .iter()
        .chain(model.parameter_values())
        .copied()
        .collect();
    let seeds: Vec<usize> = (0..read)
        .chain(estimated.iter().map(|k| read + k))
        .collect();
    let curvatures =
        evaluated(
            program
                .curvatures(&inputs, &seeds)
                .map_err(|source| CallError::Program {
                    function: function.to_string(),
                    source,
                }),
        );
    let (d, dim) = (seeds.len(), terms.jacobian.ncols());
    let column = |j: usize| if j < read { j } else { state + j - read };
    let values = &curvatures.tangents.values;
    let rows = terms.jacobian.nrows();
    terms.jacobian = terms
        .jacobian
        .clone()
        .resize_vertically(rows + values.len(), 0.0);
    for (i, value) in values.iter().enumerate() {
        terms.values.push(*value);
        let mut hessian = DMatrix::zeros(dim, dim);
        for j in 0..d {
            terms.jacobian[(rows + i, column(j))] = curvatures.tangents.derivatives[i * d + j];
            for l in 0..d {
                hessian[(column(j), column(l))] = curvatures.second[(i * d + j) * d + l];
            }
        }
        terms.hessians.push(hessian);
    }
}

#[cfg(test)]
mod tests;
