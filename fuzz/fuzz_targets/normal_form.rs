//! Random expressions built from the fuzz bytes by a small stack machine
//! (symbols `x`, `y`, `m`, small rationals, `+ - * /`, integer powers,
//! `sin`, `cos`, `tan`) through the normal form: a rational function or a
//! symbolic error, never a panic; and where the expression and its normal
//! form both evaluate to finite numbers at a fixed point, they agree.

#![no_main]

use chaplygin_codegen::sym::{
    Atom, AtomId, Budget, Context, ExprId, Function, Node, Poly, Rational, RationalFunction, Store,
    SymbolId, SymbolKind,
};
use libfuzzer_sys::fuzz_target;
use std::collections::HashMap;

/// The evaluation point: generic values, away from the zeros of `cos`.
const POINT: [f64; 3] = [0.7, -1.3, 2.1];

/// A small budget keeps each input fast; exceeding it is an accepted outcome.
const BUDGET: u64 = 200_000;

/// At most this many operands on the stack.
const STACK_LIMIT: usize = 32;

/// The tolerance per unit of rounding (a unit being `f64::EPSILON` or
/// less), a margin of some 1e7 over the first-order bounds.
const MARGIN: f64 = 1e-9;

fuzz_target!(|data: &[u8]| {
    let mut cx = Context::with_budget(Budget::new(BUDGET));
    let symbols = [
        cx.declare("x", SymbolKind::Coordinate),
        cx.declare("y", SymbolKind::Coordinate),
        cx.declare("m", SymbolKind::Parameter),
    ];
    let Some(root) = build(&mut cx, &symbols, data) else {
        return;
    };
    let Ok(form) = cx.normal(root) else {
        return;
    };
    let value_of = |symbol: SymbolId| POINT[symbols.iter().position(|&s| s == symbol).unwrap_or(0)];
    let tree = cx.evaluate(root, &value_of);
    let normal = cx.evaluate_normal(&form, &value_of);
    if !tree.is_finite() || !normal.is_finite() || !exact_class(&cx, &form) {
        return;
    }
    let atom_value = |atom: AtomId| atom_value(&cx, &symbols, atom);
    if !evaluates_in_range(&form, &atom_value) {
        return;
    }
    // Evaluating a polynomial in floating point gives a relative error of at
    // most about (terms + degree) * f64::EPSILON times its condition number
    // `sum |terms| / |value|`; the error of a quotient is the sum of those of
    // its factors, each times its multiplicity. The tree's own evaluation
    // adds its own, of the same order for the small trees built here. A
    // relative 1e-9 per unit of condition leaves a margin of more than 1e4
    // over that bound for polynomials of up to a few hundred terms, and still
    // catches any wrong coefficient (a change by a rational multiple of a
    // monomial's value, far above the bound at a generic point). The tree's
    // own rounding is bounded by a running error analysis of its evaluation
    // (`tree_error`), which follows cancellation in its sums: `x - (x -
    // x^100)` keeps one or two correct bits of `x^100`, and a negative power
    // of it none.
    //
    // That bound is linear in the factors' relative errors, so it holds while
    // each denominator factor is known to better than half its value. Where a
    // factor's rounding can reach its value (1e-9 per unit of condition, a
    // half or more: `(1 - cos(m)^2)^300 x^24 - y` expanded, say, whose terms
    // are some 1e25 times its value), its floating value is mostly rounding
    // and so is the quotient's: the two values are not compared.
    let denominator_conditions: Vec<(f64, u32)> = (form.denominator().iter())
        .map(|(factor, k)| (condition(factor, &atom_value), *k))
        .collect();
    // A condition that is not a number (a term beyond `f64`) says the same.
    let unknown = |condition: f64| condition.is_nan() || MARGIN * condition >= 0.5;
    if (denominator_conditions.iter()).any(|&(condition, _)| unknown(condition)) {
        return;
    }
    // The numerator's rounding, `condition * |numerator|`, is the magnitude
    // of its terms, which stays a number where cancellation leaves its
    // floating value 0: `(cos(m) + sin(m))^36` expanded, say.
    let denominator_condition: f64 = (denominator_conditions.iter())
        .map(|&(condition, k)| f64::from(k) * condition)
        .sum();
    let numerator_rounding =
        magnitude(form.numerator(), &atom_value) / denominator_value(&form, &atom_value).abs();
    if numerator_rounding.is_nan() {
        return;
    }
    let normal_rounding = numerator_rounding + (1.0 + denominator_condition) * normal.abs();
    let tolerance = MARGIN * (normal_rounding + tree_error(&cx, root, &value_of));
    assert!(
        (tree - normal).abs() <= tolerance,
        "tree {tree} != normal form {normal} (tolerance {tolerance}) for {}",
        cx.display(root)
    );
});

/// True when every atom is a symbol or the sine or cosine of a symbol: then
/// each atom's value is one correctly rounded library call away from exact.
fn exact_class(cx: &Context, form: &RationalFunction) -> bool {
    form.atoms().iter().all(|&atom| match cx.atoms().get(atom) {
        Atom::Symbol(_) => true,
        Atom::Sin(argument) | Atom::Cos(argument) => {
            matches!(cx.node(*argument), Node::Symbol(_))
        }
        Atom::Kernel(_) => false,
    })
}

/// The value of an atom of the exact class at [`POINT`].
fn atom_value(cx: &Context, symbols: &[SymbolId; 3], atom: AtomId) -> f64 {
    let at = |symbol: &SymbolId| POINT[symbols.iter().position(|s| s == symbol).unwrap_or(0)];
    let of_argument = |argument: &ExprId| match cx.node(*argument) {
        Node::Symbol(symbol) => at(symbol),
        _ => f64::NAN,
    };
    match cx.atoms().get(atom) {
        Atom::Symbol(symbol) => at(symbol),
        Atom::Sin(argument) => of_argument(argument).sin(),
        Atom::Cos(argument) => of_argument(argument).cos(),
        Atom::Kernel(_) => f64::NAN,
    }
}

/// True when the normal form's numerator, each denominator factor's power
/// and their product stay in the normal range of `f64` (or are zero): past
/// it (a denominator factor of 3e111 cubed, say), its floating value is not
/// its value rounded.
fn evaluates_in_range(form: &RationalFunction, atom_value: &dyn Fn(AtomId) -> f64) -> bool {
    let in_range = |value: f64| value == 0.0 || value.is_normal();
    in_range(form.numerator().evaluate(atom_value))
        && factor_powers(form, atom_value).all(in_range)
        && in_range(denominator_value(form, atom_value))
}

/// Each denominator factor's value raised to its multiplicity.
fn factor_powers(
    form: &RationalFunction,
    atom_value: &dyn Fn(AtomId) -> f64,
) -> impl Iterator<Item = f64> {
    (form.denominator().iter()).map(|(factor, k)| factor.evaluate(atom_value).powi(*k as i32))
}

/// The denominator's value: the product of [`factor_powers`].
fn denominator_value(form: &RationalFunction, atom_value: &dyn Fn(AtomId) -> f64) -> f64 {
    factor_powers(form, atom_value).product()
}

/// `sum |c m(point)| / |p(point)|`: how much rounding in the terms is
/// magnified; `NaN` where a term leaves the normal range of `f64` (its
/// coefficient, `2^-1440` say, or its value under- or overflows), whose
/// rounding is then no longer relative to it.
fn condition(p: &Poly, atom_value: &dyn Fn(AtomId) -> f64) -> f64 {
    let magnitude = magnitude(p, atom_value);
    if magnitude == 0.0 {
        return 0.0;
    }
    magnitude / p.evaluate(atom_value).abs()
}

/// `sum |c m(point)|`, or `NaN` where a term leaves the normal range of
/// `f64`.
fn magnitude(p: &Poly, atom_value: &dyn Fn(AtomId) -> f64) -> f64 {
    let magnitudes: Vec<f64> = (p.terms().iter())
        .map(|(monomial, coefficient)| {
            monomial
                .factors()
                .iter()
                .fold(coefficient.to_f64().abs(), |product, &(atom, exponent)| {
                    product * atom_value(atom).abs().powi(exponent as i32)
                })
        })
        .collect();
    if magnitudes.iter().any(|m| !m.is_normal()) {
        return f64::NAN;
    }
    magnitudes.iter().sum()
}

/// A first-order bound on the error of evaluating the tree at the point in
/// floating point, in units of one operation's relative rounding: a running
/// error analysis (Higham, *Accuracy and Stability of Numerical
/// Algorithms*, 2nd ed., section 3.3). Every constant, input and result
/// adds its own magnitude; every operation carries its operands' errors
/// times its partial derivatives, and a sum the magnitudes of its terms.
/// Infinite where a value on the way leaves the normal range of `f64` (a
/// constant beyond it, say) or underflows to 0, its rounding then no longer
/// relative: the final value then bears no bound.
fn tree_error(store: &Store, root: ExprId, value_of: &dyn Fn(SymbolId) -> f64) -> f64 {
    let nodes = store.reachable(&[root]);
    let values = store.evaluate_many(&nodes, value_of);
    if values
        .iter()
        .any(|&value| value != 0.0 && !value.is_normal())
    {
        return f64::INFINITY;
    }
    let mut bounds: HashMap<ExprId, (f64, f64)> = HashMap::new();
    for (&id, &value) in nodes.iter().zip(&values) {
        let operand = |child: &ExprId| bounds[child];
        if value == 0.0 && underflowed(store.node(id), &|child| operand(child).0) {
            return f64::INFINITY;
        }
        if !linear_enough(store.node(id), &|child| operand(child)) {
            return f64::INFINITY;
        }
        let carried = match store.node(id) {
            Node::Number(_) | Node::Symbol(_) => 0.0,
            Node::Add(terms) => terms
                .iter()
                .map(|t| operand(t).0.abs() + operand(t).1)
                .sum(),
            Node::Mul(factors) => {
                let carried: f64 = (0..factors.len())
                    .map(|i| {
                        let others: f64 = (factors.iter().enumerate())
                            .filter(|&(j, _)| j != i)
                            .map(|(_, f)| operand(f).0.abs())
                            .product();
                        operand(&factors[i]).1 * others
                    })
                    .sum();
                carried + factors.len() as f64 * value.abs()
            }
            Node::Pow(base, exponent) => {
                let (b, error) = operand(base);
                let p = exponent.to_f64();
                (p * b.powf(p - 1.0)).abs() * error + p.abs() * value.abs()
            }
            Node::Call(function, argument) => {
                let (a, error) = operand(argument);
                let slope = match function {
                    Function::Sin => a.cos(),
                    Function::Cos => a.sin(),
                    Function::Tan => 1.0 + a.tan().powi(2),
                    Function::Exp => a.exp(),
                    Function::Ln => 1.0 / a,
                    Function::Asin | Function::Acos => 1.0 / (1.0 - a * a).sqrt(),
                    Function::Atan => 1.0 / (1.0 + a * a),
                };
                slope.abs() * error
            }
            Node::Atan2(y, x) => {
                let ((b, y_error), (a, x_error)) = (operand(y), operand(x));
                (a.abs() * y_error + b.abs() * x_error) / (a * a + b * b)
            }
        };
        bounds.insert(id, (value, carried + value.abs()));
    }
    let bound = bounds[&root].1;
    if bound.is_nan() { f64::INFINITY } else { bound }
}

/// True while every operand of a product or power is known, at the margin,
/// to better than half its value, where the first-order bound holds: past
/// it, `1/(m - (tan(x) - (tan(x) - m)))` say, the operand is rounding (here
/// 4.4e-16 for an exact 0 plus a tiny constant) and so is the result.
fn linear_enough(node: &Node, operand: &dyn Fn(&ExprId) -> (f64, f64)) -> bool {
    let known = |child: &ExprId| {
        let (value, error) = operand(child);
        MARGIN * error <= 0.5 * value.abs()
    };
    match node {
        Node::Mul(factors) => factors.iter().all(known),
        Node::Pow(base, _) => known(base),
        Node::Number(_) | Node::Symbol(_) | Node::Add(_) | Node::Call(..) | Node::Atan2(..) => true,
    }
}

/// True when a node whose value is 0 has underflowed: a nonzero constant,
/// a product or power of nonzero operands (`0.7^3125`, some 1e-484), or an
/// exponential. Its rounding is then all of its value.
fn underflowed(node: &Node, operand_value: &dyn Fn(&ExprId) -> f64) -> bool {
    match node {
        Node::Number(constant) => !constant.is_zero(),
        Node::Mul(factors) => factors.iter().all(|factor| operand_value(factor) != 0.0),
        Node::Pow(base, _) => operand_value(base) != 0.0,
        Node::Call(function, _) => matches!(function, Function::Exp),
        Node::Symbol(_) | Node::Add(_) | Node::Atan2(..) => false,
    }
}

/// Runs the bytes as stack-machine instructions; the top of the stack is the
/// expression. `None` when the bytes build nothing or an operation is
/// rejected (a division by an exact zero, a constant past the store's
/// limit).
fn build(store: &mut Store, symbols: &[SymbolId; 3], data: &[u8]) -> Option<ExprId> {
    let mut stack: Vec<ExprId> = Vec::new();
    let mut bytes = data.iter().copied();
    while let Some(op) = bytes.next() {
        let argument = bytes.next().unwrap_or(0);
        let pushed = match op % 11 {
            0 => store.symbol(symbols[usize::from(argument % 3)]),
            1 => {
                let numerator = i64::from(argument % 17) - 8;
                let denominator = i64::from(argument / 17 % 4) + 1;
                store.number(Rational::new(numerator, denominator)?)
            }
            2..=5 => {
                let (Some(b), Some(a)) = (stack.pop(), stack.pop()) else {
                    continue;
                };
                let value = match op % 11 {
                    2 => store.add2(a, b),
                    3 => store.sub(a, b),
                    4 => store.mul2(a, b),
                    _ => store.div(a, b).ok()?,
                };
                store.within_constant_limit(value).ok()?
            }
            6 => {
                let base = stack.pop()?;
                let exponent = i64::from(argument % 9) - 3;
                store.pow(base, Rational::integer(exponent)).ok()?
            }
            7..=9 => {
                let function =
                    [Function::Sin, Function::Cos, Function::Tan][usize::from(op % 11 - 7)];
                let operand = stack.pop()?;
                store.apply(function, operand).ok()?
            }
            _ => *stack.last()?,
        };
        if stack.len() < STACK_LIMIT {
            stack.push(pushed);
        }
    }
    stack.pop()
}
