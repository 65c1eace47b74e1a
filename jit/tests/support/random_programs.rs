//! Random straight-line programs from bytes, for the differential check of
//! the JIT against the IR's interpreter: the `jit` fuzz target
//! (`fuzz/fuzz_targets/jit.rs`, which includes this file) and its
//! fixed-seed property test (`tests/differential.rs`). The bytes drive a
//! stack machine over an expression store (the inputs `x`, `y`, `z`; small
//! rationals, powers of ten from 1e-20 to 1e20; `+ - * /`, negation,
//! integer powers from -5 to 6, square roots, rational powers, `sin`,
//! `cos`, `tan`, `exp`, `ln`, `asin`, `acos`, `atan`, `atan2`;
//! duplication, for deep chains and shared
//! subexpressions); every value left on the stack is an output, and the
//! program lowered from them (so every operation of the IR, `sin_cos`
//! pairs and shared divisors included) runs at three points: the last 24
//! bytes read as `f64` bits (NaN, infinities, subnormals, signed zeros),
//! and two fixed generic points. Native code and interpreter must agree
//! bit for bit (NaN for NaN, whatever its sign and payload).

use chaplygin_codegen::ir::{Program, lower};
use chaplygin_codegen::sym::{ExprId, Function, Node, Rational, Store, SymbolKind};
use chaplygin_jit::NativePrograms;
use std::collections::HashSet;

/// At most this many operands on the stack (and so outputs).
const STACK_LIMIT: usize = 24;

/// A value holding a constant of more bits (numerator and denominator
/// together), or a power with such an exponent, is not pushed. The JIT and the interpreter see a constant as
/// its nearest `f64`, which 4,096 bits cover with room (over- and underflow
/// included); folding larger ones exactly is the store's work, fuzzed by
/// the `normal_form` and `expand` targets, and took 60 % of this one's time
/// in big-integer gcds.
const CONSTANT_BITS: u64 = 4096;

/// Generic points every program also runs at.
const POINTS: [[f64; 3]; 2] = [[0.7, -1.3, 2.1], [-0.25, 3.5, 1e-3]];

/// Runs the program `data` builds at the three points and asserts the
/// native code gives the interpreter's bits at each.
pub fn native_matches_interpreter(data: &[u8]) {
    let (code, bits) = data.split_at(data.len().saturating_sub(24));
    let mut store = Store::new();
    let symbols = ["x", "y", "z"].map(|name| store.declare(name, SymbolKind::Coordinate));
    let inputs = symbols.map(|s| store.symbol(s));
    let outputs = build(&mut store, &inputs, code);
    if outputs.is_empty() {
        return;
    }
    let Ok(program) = lower(&store, &symbols, &outputs) else {
        return;
    };
    let native = NativePrograms::compile_verified(&[&program]).expect("every IR program compiles");
    let mut points = POINTS.to_vec();
    if let Ok(bits) = <[u8; 24]>::try_from(bits) {
        points.push(std::array::from_fn(|i| {
            f64::from_le_bytes(bits[8 * i..8 * i + 8].try_into().expect("8 bytes"))
        }));
    }
    for point in points {
        assert_native_matches_at(&program, &native, &point);
    }
}

/// Asserts that `native`, compiled from `program`, gives the interpreter's
/// bits at `point` for every output (NaN for NaN: IEEE leaves a NaN's sign
/// and payload open).
pub fn assert_native_matches_at(program: &Program, native: &NativePrograms, point: &[f64]) {
    let expected = program.evaluate_vec(point).expect("the interpreter runs");
    let mut got = vec![0.0; expected.len()];
    native
        .evaluate(0, point, &mut got)
        .expect("the native code runs");
    for (j, (&native, &interpreted)) in got.iter().zip(&expected).enumerate() {
        assert!(
            native.to_bits() == interpreted.to_bits() || (native.is_nan() && interpreted.is_nan()),
            "output {j} at {point:?}: native {native:e}, interpreter {interpreted:e}\n{program}"
        );
    }
}

/// The values the stack machine leaves from `code`, two bytes an
/// instruction (operation, argument).
fn build(store: &mut Store, inputs: &[ExprId; 3], code: &[u8]) -> Vec<ExprId> {
    let mut stack: Vec<ExprId> = Vec::new();
    let mut small = HashSet::new();
    for instruction in code.chunks(2) {
        let (op, argument) = (instruction[0], instruction.get(1).copied().unwrap_or(0));
        if let Some(value) = step(store, inputs, &mut stack, op, argument)
            && stack.len() < STACK_LIMIT
            && has_only_small_constants(store, value, &mut small)
        {
            stack.push(value);
        }
    }
    stack
}

/// True when every constant in `value`, and every power's exponent, has
/// at most [`CONSTANT_BITS`] bits. The nodes found so are added to `small`
/// and not looked at again.
fn has_only_small_constants(store: &Store, value: ExprId, small: &mut HashSet<ExprId>) -> bool {
    let unseen = store.reachable_where(&[value], |id| small.contains(&id));
    let fits = unseen.iter().all(|&id| match store.node(id) {
        Node::Number(c) | Node::Pow(_, c) => c.bits() <= CONSTANT_BITS,
        _ => true,
    });
    if fits {
        small.extend(unseen);
    }
    fits
}

/// One instruction: the value it pushes, or `None` where it does not apply
/// (too few operands, an expression the store refuses).
fn step(
    store: &mut Store,
    inputs: &[ExprId; 3],
    stack: &mut Vec<ExprId>,
    op: u8,
    argument: u8,
) -> Option<ExprId> {
    const FUNCTIONS: [Function; 8] = [
        Function::Sin,
        Function::Cos,
        Function::Tan,
        Function::Exp,
        Function::Ln,
        Function::Asin,
        Function::Acos,
        Function::Atan,
    ];
    match op % 16 {
        0 => Some(inputs[usize::from(argument % 3)]),
        1 => {
            let numerator = i64::from(argument % 17) - 8;
            let denominator = i64::from(argument / 17 % 4) + 1;
            Some(store.number(Rational::new(numerator, denominator)?))
        }
        2 => {
            // 10^k for k in -20..=20: constants far from 1
            let k = i64::from(argument % 41) - 20;
            Some(store.number(Rational::integer(10).powi(k)?))
        }
        3..=6 => {
            let (b, a) = (stack.pop()?, stack.pop()?);
            match op % 16 {
                3 => Some(store.add2(a, b)),
                4 => Some(store.sub(a, b)),
                5 => Some(store.mul2(a, b)),
                _ => store.div(a, b).ok(),
            }
        }
        7 => {
            let a = stack.pop()?;
            Some(store.neg(a))
        }
        8 => {
            let base = stack.pop()?;
            store
                .pow(base, Rational::integer(i64::from(argument % 12) - 5))
                .ok()
        }
        9 => {
            let base = stack.pop()?;
            store.pow(base, Rational::new(1, 2)?).ok()
        }
        10 => {
            let base = stack.pop()?;
            let exponent =
                Rational::new(i64::from(argument % 7) - 3, i64::from(argument / 7 % 3) + 2)?;
            store.pow(base, exponent).ok()
        }
        11..=14 => {
            let function = FUNCTIONS[usize::from(argument) % FUNCTIONS.len()];
            let operand = stack.pop()?;
            store.apply(function, operand).ok()
        }
        15 if argument.is_multiple_of(2) => {
            let (x, y) = (stack.pop()?, stack.pop()?);
            store.atan2(y, x).ok()
        }
        _ => stack.last().copied(),
    }
}
