//! Property tests: random expression trees built through the store's own
//! constructors, lowered, and checked against the store's independent
//! evaluator ([`Store::evaluate_many`]), the cost model and the program's
//! structural invariants.

use super::{Op, Program, lower};
use crate::sym::{ExprId, Function, Node, Rational, Store, SymbolId, SymbolKind};
use proptest::prelude::*;
use std::collections::HashSet;

/// Number of symbols the random trees draw from.
pub(super) const SYMBOLS: usize = 3;

/// A random expression, before it is built into a store.
#[derive(Clone, Debug)]
pub(super) enum Tree {
    Symbol(usize),
    Number(i64, i64),
    Add(Vec<Tree>),
    Mul(Vec<Tree>),
    Pow(Box<Tree>, i64),
    /// `sqrt(t^2 + 1)`: a square root of a positive expression.
    SqrtOfPositive(Box<Tree>),
    Call(Function, Box<Tree>),
    /// `atan2(y, x)`.
    Atan2(Box<Tree>, Box<Tree>),
}

fn function() -> impl Strategy<Value = Function> {
    prop_oneof![
        Just(Function::Sin),
        Just(Function::Cos),
        Just(Function::Tan),
        Just(Function::Exp),
        Just(Function::Atan),
    ]
}

/// Trees of depth at most 5 over [`SYMBOLS`] symbols.
pub(super) fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        (0..SYMBOLS).prop_map(Tree::Symbol),
        (-4i64..=4, 1i64..=3).prop_map(|(n, d)| Tree::Number(n, d)),
    ];
    leaf.prop_recursive(5, 40, 3, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 2..=3).prop_map(Tree::Add),
            prop::collection::vec(inner.clone(), 2..=3).prop_map(Tree::Mul),
            (inner.clone(), -3i64..=4).prop_map(|(t, e)| Tree::Pow(Box::new(t), e)),
            inner
                .clone()
                .prop_map(|t| Tree::SqrtOfPositive(Box::new(t))),
            (function(), inner.clone()).prop_map(|(f, t)| Tree::Call(f, Box::new(t))),
            (inner.clone(), inner).prop_map(|(y, x)| Tree::Atan2(Box::new(y), Box::new(x))),
        ]
    })
}

/// A store with the symbols `x0, x1, ...`.
pub(super) fn symbol_store() -> (Store, Vec<SymbolId>, Vec<ExprId>) {
    let mut store = Store::new();
    let symbols: Vec<SymbolId> = (0..SYMBOLS)
        .map(|i| store.declare(&format!("x{i}"), SymbolKind::Coordinate))
        .collect();
    let leaves = symbols.iter().map(|&s| store.symbol(s)).collect();
    (store, symbols, leaves)
}

/// Builds a tree with the store's constructors; an operation the store
/// rejects (`0^-1`) yields its operand instead.
pub(super) fn build(store: &mut Store, leaves: &[ExprId], tree: &Tree) -> ExprId {
    match tree {
        Tree::Symbol(i) => leaves[*i],
        Tree::Number(n, d) => store.number(Rational::new(*n, *d).unwrap_or(Rational::ONE)),
        Tree::Add(terms) => {
            let terms: Vec<ExprId> = terms.iter().map(|t| build(store, leaves, t)).collect();
            store.add(&terms)
        }
        Tree::Mul(factors) => {
            let factors: Vec<ExprId> = factors.iter().map(|t| build(store, leaves, t)).collect();
            store.mul(&factors)
        }
        Tree::Pow(base, exponent) => {
            let base = build(store, leaves, base);
            store
                .pow(base, Rational::integer(*exponent))
                .unwrap_or(base)
        }
        Tree::SqrtOfPositive(inner) => {
            let inner = build(store, leaves, inner);
            let square = store.mul2(inner, inner);
            let one = store.integer(1);
            let positive = store.add2(square, one);
            store.sqrt(positive).unwrap_or(positive)
        }
        Tree::Call(function, argument) => {
            let argument = build(store, leaves, argument);
            store.apply(*function, argument).unwrap_or(argument)
        }
        Tree::Atan2(y, x) => {
            let (y, x) = (build(store, leaves, y), build(store, leaves, x));
            store.atan2(y, x).unwrap_or(y)
        }
    }
}

/// First-order bound on how far rounding can move each node's value, in
/// units of the machine epsilon: every operation rounds its result, and an
/// error in an operand is scaled by the derivative. Near a cancellation this
/// exceeds `|value|`, and two correct evaluations in different orders may
/// differ by that much.
pub(super) fn rounding_scale(
    store: &Store,
    roots: &[ExprId],
    value_of: &dyn Fn(SymbolId) -> f64,
) -> Vec<f64> {
    let order = store.reachable(roots);
    let values = store.evaluate_many(&order, value_of);
    let at = |id: ExprId| order.binary_search(&id).map_or(f64::NAN, |i| values[i]);
    let mut scale: Vec<f64> = Vec::with_capacity(order.len());
    for (i, &id) in order.iter().enumerate() {
        let s = |child: ExprId| order.binary_search(&child).map_or(f64::NAN, |j| scale[j]);
        let scaled = |derivative: f64, child: ExprId| {
            let error = s(child);
            if error == 0.0 {
                0.0
            } else {
                derivative.abs() * error
            }
        };
        let own = values[i].abs();
        let node_scale = match store.node(id) {
            Node::Number(_) | Node::Symbol(_) => 0.0,
            Node::Add(terms) => terms.iter().map(|&t| s(t) + at(t).abs()).sum::<f64>() + own,
            Node::Mul(factors) => {
                let others = |k: usize| -> f64 {
                    factors
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != k)
                        .map(|(_, &f)| at(f).abs())
                        .product()
                };
                let spread: f64 = factors
                    .iter()
                    .enumerate()
                    .map(|(k, &f)| scaled(others(k), f))
                    .sum();
                spread + factors.len() as f64 * own
            }
            Node::Pow(base, exponent) => {
                let e = exponent.to_f64();
                scaled(e * at(*base).powf(e - 1.0), *base) + 2.0 * own
            }
            Node::Call(function, argument) => {
                let u = at(*argument);
                let derivative = match function {
                    Function::Sin => u.cos(),
                    Function::Cos => u.sin(),
                    Function::Tan => 1.0 + values[i] * values[i],
                    Function::Exp => values[i],
                    Function::Ln => 1.0 / u,
                    Function::Asin | Function::Acos => 1.0 / (1.0 - u * u).sqrt(),
                    Function::Atan => 1.0 / (1.0 + u * u),
                };
                scaled(derivative, *argument) + own
            }
            Node::Atan2(y, x) => {
                let (u, v) = (at(*y), at(*x));
                let radius_square = u * u + v * v;
                scaled(v / radius_square, *y) + scaled(u / radius_square, *x) + own
            }
        };
        scale.push(node_scale);
    }
    roots
        .iter()
        .map(|&r| order.binary_search(&r).map_or(f64::NAN, |i| scale[i]))
        .collect()
}

/// Values are defined before they are read, every value is read or output,
/// and slots and indices are in range.
pub(super) fn check_structure(program: &Program) -> Result<(), TestCaseError> {
    let mut defined = HashSet::new();
    let mut read = HashSet::new();
    for instruction in program.instructions() {
        for operand in instruction.op.operands() {
            prop_assert!(
                defined.contains(&operand),
                "{operand} read before defined:\n{program}"
            );
            read.insert(operand);
        }
        if let Op::Input(slot) = instruction.op {
            prop_assert!(slot < program.input_count());
        }
        let mut results = vec![instruction.result];
        if let Op::SinCos { cosine, .. } = instruction.op {
            results.push(cosine);
        }
        for result in results {
            prop_assert!(result.index() < program.value_count());
            prop_assert!(defined.insert(result), "{result} defined twice");
        }
    }
    read.extend(program.outputs().iter().copied());
    prop_assert_eq!(defined.len(), program.value_count());
    prop_assert_eq!(&read, &defined, "dead values in\n{}", program);
    Ok(())
}

/// Points where the symbols take values in `[-2, 2]`.
fn points() -> impl Strategy<Value = Vec<[f64; SYMBOLS]>> {
    prop::collection::vec(prop::array::uniform3(-2.0f64..2.0), 3)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 512,
        max_global_rejects: 10_000,
        ..ProptestConfig::default()
    })]

    #[test]
    fn interpreter_matches_the_store_evaluator(
        trees in prop::collection::vec(tree(), 1..=3),
        points in points(),
    ) {
        let (mut store, symbols, leaves) = symbol_store();
        let outputs: Vec<ExprId> = trees.iter().map(|t| build(&mut store, &leaves, t)).collect();
        let program = lower(&store, &symbols, &outputs).map_err(|e| TestCaseError::fail(e.to_string()))?;
        check_structure(&program)?;
        let mut scratch = Vec::new();
        let mut got = vec![0.0; outputs.len()];
        for point in points {
            let value_of = |s: SymbolId| point[s.index()];
            let expected = store.evaluate_many(&outputs, &value_of);
            let scale = rounding_scale(&store, &outputs, &value_of);
            program.evaluate(&point, &mut scratch, &mut got).map_err(|e| TestCaseError::fail(e.to_string()))?;
            for ((&want, &have), &scale) in expected.iter().zip(&got).zip(&scale) {
                if !want.is_finite() || want.abs() > 1e12 || !scale.is_finite() {
                    continue;
                }
                let tolerance = 1e-12 * want.abs().max(scale);
                prop_assert!(
                    (want - have).abs() <= tolerance,
                    "at {point:?}: reference {want}, interpreter {have}, scale {scale}\n{program}"
                );
            }
        }
    }

    #[test]
    fn sharing_never_costs_more(trees in prop::collection::vec(tree(), 1..=3)) {
        let (mut store, symbols, leaves) = symbol_store();
        let outputs: Vec<ExprId> = trees.iter().map(|t| build(&mut store, &leaves, t)).collect();
        let program = lower(&store, &symbols, &outputs).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let count = program.operation_count();
        prop_assert!(count.after_cse <= count.before_cse, "{count:?}\n{program}");
    }

    #[test]
    fn a_subtree_used_twice_is_computed_once(tree in tree()) {
        let (mut store, symbols, leaves) = symbol_store();
        let shared = build(&mut store, &leaves, &tree);
        prop_assume!(!matches!(store.node(shared), Node::Number(_) | Node::Symbol(_)));
        let sine = store.apply(Function::Sin, shared).unwrap_or(shared);
        let exponential = store.apply(Function::Exp, shared).unwrap_or(shared);
        let product = store.mul2(sine, exponential);
        let whole = store.add2(product, leaves[0]);
        let program = lower(&store, &symbols, &[whole]).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let count = program.operation_count();
        prop_assert!(count.after_cse < count.before_cse, "{count:?}\n{program}");
    }

    #[test]
    fn emitted_code_parses(trees in prop::collection::vec(tree(), 1..=3)) {
        let (mut store, symbols, leaves) = symbol_store();
        let outputs: Vec<ExprId> = trees.iter().map(|t| build(&mut store, &leaves, t)).collect();
        let program = lower(&store, &symbols, &outputs).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let source = super::tests::emit_function("f", &program, SYMBOLS);
        prop_assert!(syn::parse_str::<syn::File>(&source).is_ok(), "{source}");
    }
}
