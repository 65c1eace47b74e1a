//! The cost model shared by lowering and counting.
//!
//! One operation is a binary `+ - * /`, a negation, or a call (`sin`, `cos`,
//! `tan`, `exp`, `ln`, `sqrt`, `powi`, `powf`, `sin_cos`); inputs and constants
//! are free. A power is lowered according to its [`PowerForm`], and the tree
//! count charges each power what that form costs, so the two counts of
//! [`super::OperationCount`] are comparable. For example `x^3 + x^3*y`
//! written as a tree costs `2 + (2 + 1) + 1 = 6`, while the program
//! `t2 = t0*t0; t3 = t2*t0; t4 = t3*t1; t5 = t3 + t4` costs 4.

use crate::sym::{ExprId, Node, Rational, Store};

/// A power computed with at most two multiplications or one square root.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum BasicPower {
    /// `x^1 = x`.
    Identity,
    /// `x^2 = x*x`.
    Square,
    /// `x^3 = (x*x)*x`.
    Cube,
    /// `x^(1/2) = sqrt(x)`.
    SquareRoot,
}

impl BasicPower {
    fn cost(self) -> u64 {
        match self {
            BasicPower::Identity => 0,
            BasicPower::Square | BasicPower::SquareRoot => 1,
            BasicPower::Cube => 2,
        }
    }
}

/// How `x^exponent` is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum PowerForm {
    /// `x^e` for a basic exponent `e`.
    Direct(BasicPower),
    /// `1 / x^e` for a basic exponent `e`; inside a product, `x^e` joins the
    /// denominator instead.
    Inverse(BasicPower),
    /// `x.powi(n)`.
    Powi(i32),
    /// `x.powf(e)`.
    Powf,
}

impl PowerForm {
    /// The form used for `exponent`.
    pub(super) fn of(exponent: &Rational) -> PowerForm {
        match exponent.to_small() {
            Some((1, 1)) => PowerForm::Direct(BasicPower::Identity),
            Some((2, 1)) => PowerForm::Direct(BasicPower::Square),
            Some((3, 1)) => PowerForm::Direct(BasicPower::Cube),
            Some((1, 2)) => PowerForm::Direct(BasicPower::SquareRoot),
            Some((-1, 1)) => PowerForm::Inverse(BasicPower::Identity),
            Some((-2, 1)) => PowerForm::Inverse(BasicPower::Square),
            Some((-3, 1)) => PowerForm::Inverse(BasicPower::Cube),
            Some((-1, 2)) => PowerForm::Inverse(BasicPower::SquareRoot),
            Some((n, 1)) => i32::try_from(n).map_or(PowerForm::Powf, PowerForm::Powi),
            _ => PowerForm::Powf,
        }
    }

    fn cost(self) -> u64 {
        match self {
            PowerForm::Direct(basic) => basic.cost(),
            PowerForm::Inverse(basic) => basic.cost() + 1,
            PowerForm::Powi(_) | PowerForm::Powf => 1,
        }
    }
}

/// The cost of one node written out on its own, its children not included.
fn node_cost(node: &Node) -> u64 {
    match node {
        Node::Number(_) | Node::Symbol(_) => 0,
        Node::Add(operands) | Node::Mul(operands) => operands.len().saturating_sub(1) as u64,
        Node::Pow(_, exponent) => PowerForm::of(exponent).cost(),
        Node::Call(..) => 1,
    }
}

/// The cost of `outputs` written out as trees, by memoized arithmetic on the
/// DAG: a node's tree cost is its own cost plus its children's tree costs.
/// `order` must be `store.reachable(outputs)`.
pub(super) fn tree_cost(store: &Store, order: &[ExprId], outputs: &[ExprId]) -> u64 {
    let mut costs = std::collections::HashMap::with_capacity(order.len());
    for &id in order {
        let children: u64 = store
            .children(id)
            .iter()
            .map(|child| costs.get(child).copied().unwrap_or(0))
            .fold(0, u64::saturating_add);
        costs.insert(id, node_cost(store.node(id)).saturating_add(children));
    }
    outputs
        .iter()
        .map(|output| costs.get(output).copied().unwrap_or(0))
        .fold(0, u64::saturating_add)
}
