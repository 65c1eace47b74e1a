//! What each of the reduced form's ten items computes (MATH.md section 3),
//! written as the derivation chooses.
//!
//! ```text
//! momenta            alpha = P g qdot             hamiltonian           Hbar
//! velocities         qdot = g^-1 h^T alpha        hamiltonian_gradient  dHbar/dx
//! structure_matrix   Jbar                         input_matrix          Bbar
//! reduced_rhs        xdot = Jbar dHbar/dx + Bbar u
//! reduced_rhs_jacobian  d xdot / dx               output                y = Bbar^T dHbar/dx
//! output_jacobian    dy/dx
//! ```
//!
//! Every item has its structured writing: the sum of products of the
//! factors' entries ([`PortHamiltonian::expressions`], computed with the
//! reduced form; for the gradient and the Jacobians, that writing
//! differentiated as an expression). When the exact form was derived it
//! also has the expanded normal form. Of the two, the one
//! whose weighted cost [`ir::estimated_weight`] estimates lower on the
//! expression DAG is kept, the structured one on ties: expanded normal
//! forms are often longer, and lose accuracy to cancellation. Nothing is
//! lowered to choose; emission lowers the chosen outputs once. The
//! snakeboard's `reduced_rhs` is the structured form, the sleigh's the
//! expanded one.

use super::{Exact, PortHamiltonian, PortHamiltonianError, state_jacobian};
use crate::ir;
use crate::model::Model;
use crate::sym::{Context, ExprId, Matrix, Poly, RationalFunction, SymbolId};

/// The ten items, in the order they are emitted and documented.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Item {
    /// `alpha = P g qdot`, k entries.
    Momenta,
    /// `qdot = g^-1 h^T alpha`, n entries.
    Velocities,
    /// `Hbar`, one entry.
    Hamiltonian,
    /// `dHbar/dx`, s entries.
    HamiltonianGradient,
    /// `Jbar`, s x s row-major.
    StructureMatrix,
    /// `Bbar`, s x p row-major.
    InputMatrix,
    /// `xdot`, s entries.
    ReducedRhs,
    /// `d xdot / dx`, s x s row-major.
    ReducedRhsJacobian,
    /// `y`, p entries.
    Output,
    /// `dy/dx`, p x s row-major.
    OutputJacobian,
}

impl Item {
    /// Every item, in order.
    pub const ALL: [Item; 10] = [
        Item::Momenta,
        Item::Velocities,
        Item::Hamiltonian,
        Item::HamiltonianGradient,
        Item::StructureMatrix,
        Item::InputMatrix,
        Item::ReducedRhs,
        Item::ReducedRhsJacobian,
        Item::Output,
        Item::OutputJacobian,
    ];
}

/// One item's outputs in each form it has.
#[derive(Clone, Debug)]
pub struct Candidates {
    /// The structured form's outputs.
    pub structured: Vec<ExprId>,
    /// The expanded normal forms' outputs, when the exact form was derived.
    pub expanded: Option<Vec<ExprId>>,
}

impl Candidates {
    /// The form with the lower estimated weighted cost, the structured one on ties.
    pub fn chosen(self, cx: &Context) -> Vec<ExprId> {
        match self.expanded {
            Some(expanded)
                if ir::estimated_weight(cx, &expanded)
                    < ir::estimated_weight(cx, &self.structured) =>
            {
                expanded
            }
            _ => self.structured,
        }
    }
}

/// The chosen outputs of the ten items, indexed by [`Item`].
#[derive(Clone, Debug)]
pub struct Items(Vec<Vec<ExprId>>);

impl Items {
    /// The outputs of `item`.
    pub fn outputs(&self, item: Item) -> &[ExprId] {
        &self.0[item as usize]
    }
}

/// The ten items of `reduced`, each in its cheaper form.
pub fn items(
    model: &Model,
    cx: &mut Context,
    reduced: &PortHamiltonian,
) -> Result<Items, PortHamiltonianError> {
    let chosen = candidates(model, cx, reduced)?
        .into_iter()
        .map(|candidates| candidates.chosen(cx))
        .collect();
    Ok(Items(chosen))
}

/// The two writings of every item, in [`Item::ALL`]'s order.
pub fn candidates(
    model: &Model,
    cx: &mut Context,
    reduced: &PortHamiltonian,
) -> Result<Vec<Candidates>, PortHamiltonianError> {
    Item::ALL
        .iter()
        .map(|&item| {
            let structured = structured(model, cx, reduced, item)?;
            let expanded = match &reduced.exact {
                Some(exact) => Some(expanded(model, cx, reduced, exact, item)?),
                None => None,
            };
            Ok(Candidates {
                structured,
                expanded,
            })
        })
        .collect()
}

/// `item` in the structured form.
fn structured(
    model: &Model,
    cx: &mut Context,
    reduced: &PortHamiltonian,
    item: Item,
) -> Result<Vec<ExprId>, PortHamiltonianError> {
    let expressions = &reduced.expressions;
    Ok(match item {
        Item::Momenta => {
            let qdot = symbol_expressions(cx, &model.velocities);
            product(cx, &expressions.momentum_map, qdot)?
        }
        Item::Velocities => {
            let alpha = symbol_expressions(cx, &reduced.momenta);
            product(cx, &expressions.velocity_map, alpha)?
        }
        Item::Hamiltonian => vec![expressions.hamiltonian],
        Item::HamiltonianGradient => expressions.gradient.clone(),
        Item::StructureMatrix => expressions.structure.entries().to_vec(),
        Item::InputMatrix => expressions.input_matrix.entries().to_vec(),
        Item::ReducedRhs => expressions.rhs.clone(),
        Item::ReducedRhsJacobian => expressions.rhs_jacobian.entries().to_vec(),
        Item::Output => expressions.output.clone(),
        Item::OutputJacobian => state_jacobian(cx, &reduced.state(model), &expressions.output),
    })
}

/// `item` from the expanded normal forms of `exact`.
fn expanded(
    model: &Model,
    cx: &mut Context,
    reduced: &PortHamiltonian,
    exact: &Exact,
    item: Item,
) -> Result<Vec<ExprId>, PortHamiltonianError> {
    Ok(match item {
        Item::Momenta => {
            let qdot = symbol_forms(cx, &model.velocities);
            expanded_product(cx, &exact.momentum_map, qdot)?
        }
        Item::Velocities => {
            let alpha = symbol_forms(cx, &reduced.momenta);
            expanded_product(cx, &exact.velocity_map, alpha)?
        }
        Item::Hamiltonian => expressions_of(cx, std::slice::from_ref(&exact.hamiltonian)),
        Item::HamiltonianGradient => expressions_of(cx, &exact.gradient),
        Item::StructureMatrix => expressions_of(cx, exact.structure.entries()),
        Item::InputMatrix => expressions_of(cx, exact.input_matrix.entries()),
        Item::ReducedRhs => expressions_of(cx, &exact.rhs),
        Item::ReducedRhsJacobian => {
            let state = reduced.state(model);
            let jacobian = cx.jacobian(&exact.rhs, &state)?;
            expressions_of(cx, jacobian.entries())
        }
        Item::Output => expressions_of(cx, &exact.output),
        Item::OutputJacobian => {
            let output = expressions_of(cx, &exact.output);
            state_jacobian(cx, &reduced.state(model), &output)
        }
    })
}

fn expressions_of(cx: &mut Context, forms: &[RationalFunction]) -> Vec<ExprId> {
    forms.iter().map(|form| cx.expression_of(form)).collect()
}

fn symbol_expressions(cx: &mut Context, symbols: &[SymbolId]) -> Vec<ExprId> {
    symbols.iter().map(|&s| cx.symbol(s)).collect()
}

fn symbol_forms(cx: &mut Context, symbols: &[SymbolId]) -> Vec<RationalFunction> {
    symbols
        .iter()
        .map(|&s| RationalFunction::from_poly(Poly::atom(cx.symbol_atom(s))))
        .collect()
}

/// `matrix * column` of a form, as expressions.
fn product(
    cx: &mut Context,
    matrix: &Matrix<ExprId>,
    column: Vec<ExprId>,
) -> Result<Vec<ExprId>, PortHamiltonianError> {
    let product = matrix.mul(&Matrix::column(column), cx)?;
    Ok(product.entries().to_vec())
}

/// `matrix * column` expanded to normal forms, as expressions.
fn expanded_product(
    cx: &mut Context,
    matrix: &Matrix,
    column: Vec<RationalFunction>,
) -> Result<Vec<ExprId>, PortHamiltonianError> {
    let column = Matrix::new(column.len(), 1, column)?;
    let atoms = cx.atoms().clone();
    let product = matrix.mul(&column, &atoms)?;
    Ok(expressions_of(cx, product.entries()))
}

#[cfg(test)]
mod tests {
    use super::{Item, candidates};
    use crate::derive::constraints::distribution_basis;
    use crate::derive::port_hamiltonian::derive;
    use crate::ir;
    use crate::model::check;
    use crate::sym::{Context, ExprId, SymbolId};
    use crate::syntax::parse_str;

    const SLEIGH: &str = include_str!("../../../../models/sleigh.model");

    /// The weighted cost of `outputs` once lowered, every symbol an input.
    fn lowered_weight(cx: &Context, inputs: &[SymbolId], outputs: &[ExprId]) -> u64 {
        ir::lower(cx, inputs, outputs)
            .expect("lowers")
            .weighted_cost()
    }

    /// Where the two forms differ by more than a tenth in lowered weight,
    /// the DAG estimate keeps the one that lowers cheaper: the snakeboard's
    /// `reduced_rhs` structured, the sleigh's expanded.
    #[test]
    fn the_estimate_keeps_the_form_that_lowers_cheaper() {
        for (name, source, rhs_expanded) in [
            ("snakeboard", crate::fixtures::SNAKEBOARD, false),
            ("sleigh", SLEIGH, true),
        ] {
            let (model, mut cx) = check(&parse_str(source).expect("parses")).expect("checks");
            let basis = distribution_basis(&model, &mut cx).expect("regular at the defaults");
            let reduced = derive(&model, &mut cx, &basis).expect("derives");
            let mut inputs = reduced.state(&model);
            inputs.extend(&model.velocities);
            inputs.extend(&reduced.inputs);
            inputs.extend(model.parameter_symbols());
            let candidates = candidates(&model, &mut cx, &reduced).expect("derives");
            for (item, candidates) in Item::ALL.iter().zip(candidates) {
                let expanded = candidates.expanded.clone().expect("exact form derived");
                let weights = [&candidates.structured, &expanded]
                    .map(|outputs| lowered_weight(&cx, &inputs, outputs));
                let chosen = candidates.chosen(&cx);
                let kept_expanded = chosen == expanded;
                println!("{name} {item:?}: lowered {weights:?}, expanded kept: {kept_expanded}");
                if *item == Item::ReducedRhs {
                    assert_eq!(kept_expanded, rhs_expanded, "{name}");
                }
                let [structured, expanded] = weights.map(|w| w as f64);
                if (structured - expanded).abs() > 0.1 * structured.min(expanded) {
                    assert_eq!(kept_expanded, expanded < structured, "{name} {item:?}");
                }
            }
        }
    }
}
