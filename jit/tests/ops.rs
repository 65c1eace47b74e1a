//! Every operation of the IR, compiled natively, gives the bits the
//! interpreter gives, at inputs that include zeros, signed zeros,
//! infinities, NaN and values outside each function's domain (where both
//! give NaN).

use crate::support::random_programs::assert_native_matches_at;
use chaplygin_codegen::ir::{Op, Program, lower};
use chaplygin_codegen::sym::{ExprId, Function, Rational, Store, SymbolKind};
use chaplygin_jit::NativePrograms;

/// The inputs `(x, y)` every program is run at.
const INPUTS: [[f64; 2]; 10] = [
    [0.3, -1.7],
    [-2.5, 0.0],
    [1e300, -1e-300],
    [0.0, -0.0],
    [-0.0, 4.0],
    [f64::INFINITY, 2.0],
    [f64::NEG_INFINITY, -3.0],
    [f64::NAN, 1.0],
    [-0.75, 3.25],
    [710.0, -0.5],
];

/// The program of the outputs `build` makes from the symbols `x` and `y`.
fn program(build: impl FnOnce(&mut Store, ExprId, ExprId) -> Vec<ExprId>) -> Program {
    let mut store = Store::new();
    let symbols = [
        store.declare("x", SymbolKind::Coordinate),
        store.declare("y", SymbolKind::Coordinate),
    ];
    let (x, y) = (store.symbol(symbols[0]), store.symbol(symbols[1]));
    let outputs = build(&mut store, x, y);
    lower(&store, &symbols, &outputs).expect("the outputs lower")
}

/// Asserts that `program` has an operation `wanted` and that its native code
/// agrees with the interpreter at every input of [`INPUTS`].
fn assert_native_matches(program: &Program, wanted: impl Fn(&Op) -> bool) {
    assert!(
        program.instructions().iter().any(|i| wanted(&i.op)),
        "the program lacks the operation tested:\n{program}"
    );
    let native = NativePrograms::compile_verified(&[program]).expect("the program compiles");
    for inputs in INPUTS {
        assert_native_matches_at(program, &native, &inputs);
    }
}

fn power(store: &mut Store, base: ExprId, numerator: i64, denominator: i64) -> ExprId {
    let exponent = Rational::new(numerator, denominator).expect("a nonzero denominator");
    store.pow(base, exponent).expect("the power exists")
}

fn apply(store: &mut Store, function: Function, argument: ExprId) -> ExprId {
    store
        .apply(function, argument)
        .expect("the function applies")
}

#[test]
fn inputs_and_constants() {
    let program = program(|s, x, y| {
        let c = s.number(Rational::new(3, 7).expect("3/7"));
        vec![x, y, c, x]
    });
    assert_native_matches(&program, |op| matches!(op, Op::Constant(_)));
    assert_native_matches(&program, |op| matches!(op, Op::Input(_)));
}

#[test]
fn addition() {
    let program = program(|s, x, y| vec![s.add2(x, y)]);
    assert_native_matches(&program, |op| matches!(op, Op::Add(..)));
}

#[test]
fn subtraction() {
    let program = program(|s, x, y| vec![s.sub(x, y)]);
    assert_native_matches(&program, |op| matches!(op, Op::Sub(..)));
}

#[test]
fn multiplication() {
    let program = program(|s, x, y| vec![s.mul2(x, y)]);
    assert_native_matches(&program, |op| matches!(op, Op::Mul(..)));
}

#[test]
fn division() {
    let program = program(|s, x, y| vec![s.div(x, y).expect("x / y")]);
    assert_native_matches(&program, |op| matches!(op, Op::Div(..)));
}

#[test]
fn negation() {
    let program = program(|s, x, _| vec![s.neg(x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Neg(_)));
}

#[test]
fn square_root_and_its_nan_below_zero() {
    let program = program(|s, x, y| vec![power(s, x, 1, 2), power(s, y, 1, 2)]);
    assert_native_matches(&program, |op| matches!(op, Op::Sqrt(_)));
    let native = NativePrograms::compile_verified(&[&program]).expect("the program compiles");
    let mut outputs = [0.0; 2];
    native
        .evaluate(0, &[-4.0, 9.0], &mut outputs)
        .expect("the native code runs");
    let expected = program
        .evaluate_vec(&[-4.0, 9.0])
        .expect("the interpreter runs");
    assert!(outputs[0].is_nan() && expected[0].is_nan());
    assert_eq!(outputs[1].to_bits(), expected[1].to_bits());
}

#[test]
fn integer_power_with_a_positive_exponent() {
    let program = program(|s, x, _| vec![power(s, x, 7, 1)]);
    assert_native_matches(&program, |op| matches!(op, Op::Powi(_, n) if *n > 0));
}

#[test]
fn integer_power_with_a_negative_exponent() {
    let program = program(|s, x, y| {
        let inverse = power(s, x, -5, 1);
        vec![s.add2(inverse, y)]
    });
    assert_native_matches(&program, |op| matches!(op, Op::Powi(_, n) if *n < 0));
}

#[test]
fn rational_power() {
    let program = program(|s, x, y| vec![power(s, x, 1, 3), power(s, y, -5, 2)]);
    assert_native_matches(&program, |op| matches!(op, Op::Powf(..)));
}

#[test]
fn sine() {
    let program = program(|s, x, _| vec![apply(s, Function::Sin, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Sin(_)));
}

#[test]
fn cosine() {
    let program = program(|s, x, _| vec![apply(s, Function::Cos, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Cos(_)));
}

#[test]
fn sine_and_cosine_of_one_angle() {
    let program = program(|s, x, y| {
        let angle = s.add2(x, y);
        let sine = apply(s, Function::Sin, angle);
        let cosine = apply(s, Function::Cos, angle);
        vec![s.mul2(sine, y), cosine, sine]
    });
    assert_native_matches(&program, |op| matches!(op, Op::SinCos { .. }));
}

#[test]
fn tangent() {
    let program = program(|s, x, _| vec![apply(s, Function::Tan, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Tan(_)));
}

#[test]
fn exponential() {
    let program = program(|s, x, _| vec![apply(s, Function::Exp, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Exp(_)));
}

#[test]
fn logarithm() {
    let program = program(|s, x, _| vec![apply(s, Function::Ln, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Ln(_)));
}

#[test]
fn inverse_sine() {
    let program = program(|s, x, _| vec![apply(s, Function::Asin, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Asin(_)));
}

#[test]
fn inverse_cosine() {
    let program = program(|s, x, _| vec![apply(s, Function::Acos, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Acos(_)));
}

#[test]
fn inverse_tangent() {
    let program = program(|s, x, _| vec![apply(s, Function::Atan, x)]);
    assert_native_matches(&program, |op| matches!(op, Op::Atan(_)));
}

/// `atan2(y, x)` and `atan2(x, y)`: the native code passes the ordinate
/// first, as the interpreter does.
#[test]
fn two_argument_inverse_tangent() {
    let program = program(|s, x, y| {
        vec![
            s.atan2(y, x).expect("not at the origin"),
            s.atan2(x, y).expect("not at the origin"),
        ]
    });
    assert_native_matches(&program, |op| matches!(op, Op::Atan2(..)));
}

/// Every operation at once, with values read far from their definitions:
/// the spilled and reloaded values give the same bits.
#[test]
fn a_long_program_that_reuses_early_values() {
    let program = program(|s, x, y| {
        let sine = apply(s, Function::Sin, x);
        let cosine = apply(s, Function::Cos, x);
        let mut terms = vec![sine, cosine];
        for k in 1..60 {
            let power = power(s, y, k % 9 + 2, 1);
            let scaled = s.mul2(terms[terms.len() - 1], power);
            let shifted = s.add2(scaled, terms[(k as usize * 7) % terms.len()]);
            terms.push(shifted);
        }
        let exponential = apply(s, Function::Exp, y);
        let root = power(s, x, 1, 2);
        terms.extend([
            s.mul2(exponential, sine),
            s.div(root, cosine).expect("a quotient"),
        ]);
        terms
    });
    assert_native_matches(&program, |op| matches!(op, Op::SinCos { .. }));
}
