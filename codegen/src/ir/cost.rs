//! The cost model shared by lowering and counting.
//!
//! One operation is a binary `+ - * /`, a negation, or a call (`sin`, `cos`,
//! `tan`, `exp`, `ln`, `sqrt`, `powi`, `powf`, `sin_cos`); inputs and constants
//! are free. A power is lowered according to its [`PowerForm`], and the tree
//! count charges each power what that form costs, so the two counts of
//! [`super::OperationCount`] are comparable. For example `x^3 + x^3*y`
//! written as a tree costs `2 + (2 + 1) + 1 = 6`, while the program
//! `t2 = t0*t0; t3 = t2*t0; t4 = t3*t1; t5 = t3 + t4` costs 4.
//!
//! [`estimated_weight`] prices outputs without lowering them: every node of
//! the DAG once (the store shares equal sub-expressions), each operation by
//! its [`super::Op::weight`]. It is what a derivation compares to choose
//! between forms of one item.

use crate::sym::{ExprId, Function, Node, Rational, Store};
use rustc_hash::FxHashSet as HashSet;

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
        Node::Call(..) | Node::Atan2(..) => 1,
    }
}

/// The cost of `outputs` written out as trees: what a program computing
/// them reports as [`super::OperationCount::before_cse`].
pub fn before_cse(store: &Store, outputs: &[ExprId]) -> u64 {
    tree_cost(store, &store.reachable(outputs), outputs)
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

/// The weight ([`super::Op::weight`]) of a division, a square root or a `powi`.
const SLOW_WEIGHT: u64 = 4;
/// The weight ([`super::Op::weight`]) of a call of an elementary function, `powf`
/// and `sin_cos` included.
const CALL_WEIGHT: u64 = 20;

impl BasicPower {
    /// [`BasicPower::cost`] weighted: a square root weighs [`SLOW_WEIGHT`].
    fn weight(self) -> u64 {
        match self {
            BasicPower::SquareRoot => SLOW_WEIGHT,
            other => other.cost(),
        }
    }
}

impl PowerForm {
    /// [`PowerForm::cost`] weighted by [`super::Op::weight`].
    fn weight(self) -> u64 {
        match self {
            PowerForm::Direct(power) => power.weight(),
            PowerForm::Inverse(power) => power.weight() + SLOW_WEIGHT,
            PowerForm::Powi(_) => SLOW_WEIGHT,
            PowerForm::Powf => CALL_WEIGHT,
        }
    }
}

/// The estimated weighted cost of computing `outputs`: every node reachable
/// from them once, a sum or product of `n` operands `n - 1` operations, a
/// power by its form (`PowerForm`: an inverse power one division, as if its
/// reciprocal were shared, which lowering does for a repeated divisor), a
/// call 20, the sine and cosine of one argument one `sin_cos`. It is
/// computed in one pass over the DAG, without building a program; lowering
/// also shares chain prefixes, so the program usually weighs a little less.
pub fn estimated_weight(store: &Store, outputs: &[ExprId]) -> u64 {
    let mut weight = 0u64;
    let mut sines = HashSet::default();
    let mut cosines = HashSet::default();
    for id in store.reachable(outputs) {
        weight = weight.saturating_add(match store.node(id) {
            Node::Number(_) | Node::Symbol(_) => 0,
            Node::Add(operands) | Node::Mul(operands) => operands.len().saturating_sub(1) as u64,
            Node::Pow(_, exponent) => PowerForm::of(exponent).weight(),
            Node::Call(Function::Sin, argument) if !cosines.contains(argument) => {
                sines.insert(*argument);
                CALL_WEIGHT
            }
            Node::Call(Function::Cos, argument) if !sines.contains(argument) => {
                cosines.insert(*argument);
                CALL_WEIGHT
            }
            Node::Call(Function::Sin | Function::Cos, _) => 0,
            Node::Call(..) | Node::Atan2(..) => CALL_WEIGHT,
        });
    }
    weight
}
