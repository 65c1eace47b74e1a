//! Unit tests of lowering, counting, printing, interpretation and emission.

use super::{IrError, Op, OperationCount, Program, RustProgram, lower};
use crate::sym::{ExprId, Function, Rational, Store, SymbolId, SymbolKind};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// A store with the given symbols, their ids and their expressions.
fn store_with(names: &[&str]) -> (Store, Vec<SymbolId>, Vec<ExprId>) {
    let mut store = Store::new();
    let symbols: Vec<SymbolId> = names
        .iter()
        .map(|n| store.declare(n, SymbolKind::Coordinate))
        .collect();
    let leaves = symbols.iter().map(|&s| store.symbol(s)).collect();
    (store, symbols, leaves)
}

fn count(program: &Program, wanted: impl Fn(&Op) -> bool) -> usize {
    program
        .instructions()
        .iter()
        .filter(|i| wanted(&i.op))
        .count()
}

fn after_cse(program: &Program) -> u64 {
    program.operation_count().after_cse
}

/// The program as `pub fn name(q: &[f64; inputs]) -> [f64; outputs]`, with
/// `q[i]` as input slot `i`.
pub(super) fn emit_function(name: &str, program: &Program, inputs: usize) -> String {
    let slots: Vec<TokenStream> = (0..inputs)
        .map(|i| {
            let i = Literal::usize_unsuffixed(i);
            quote!(q[#i])
        })
        .collect();
    let Ok(RustProgram {
        statements,
        outputs,
    }) = program.emit(&slots)
    else {
        return String::new();
    };
    let uses_inputs = count(program, |op| matches!(op, Op::Input(_))) > 0;
    let silence = (!uses_inputs).then(|| quote!(let _ = q;));
    let (name, length) = (format_ident!("{name}"), outputs.len());
    quote!(
        pub fn #name(q: &[::core::primitive::f64; #inputs]) -> [::core::primitive::f64; #length] {
            #silence
            #statements
            [#(#outputs),*]
        }
    )
    .to_string()
}

/// The program as `pub fn name(chart: usize, q: &[f64; 3]) -> [f64; m]`,
/// its outputs split into `variants` of `m` each, `chart` picking one.
fn emit_variants_function(name: &str, program: &Program, variants: &[Vec<usize>]) -> String {
    let slots: Vec<TokenStream> = (0..super::properties::SYMBOLS)
        .map(|i| {
            let i = Literal::usize_unsuffixed(i);
            quote!(q[#i])
        })
        .collect();
    let emitted = program.emit_variants(&slots, variants).unwrap();
    let arms = emitted.variants.iter().enumerate().map(|(i, variant)| {
        let (statements, outputs) = (&variant.statements, &variant.outputs);
        let i = Literal::usize_unsuffixed(i);
        quote!(#i => { #statements [#(#outputs),*] })
    });
    let (name, common) = (format_ident!("{name}"), &emitted.common);
    let (length, inputs) = (variants[0].len(), super::properties::SYMBOLS);
    quote!(
        pub fn #name(
            chart: ::core::primitive::usize,
            q: &[::core::primitive::f64; #inputs],
        ) -> [::core::primitive::f64; #length] {
            #common
            match chart {
                #(#arms,)*
                _ => [::core::primitive::f64::NAN; #length],
            }
        }
    )
    .to_string()
}

#[test]
fn sine_and_cosine_of_one_argument_share_one_sin_cos() {
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let angle = s.add2(v[0], v[1]);
    let sine = s.apply(Function::Sin, angle).unwrap();
    let cosine = s.apply(Function::Cos, angle).unwrap();
    let product = s.mul2(sine, cosine);
    let tangent = s.apply(Function::Tan, angle).unwrap();
    let program = lower(&s, &symbols, &[product, sine, tangent]).unwrap();
    assert_eq!(
        count(&program, |op| matches!(op, Op::SinCos { .. })),
        1,
        "{program}"
    );
    assert_eq!(
        count(&program, |op| matches!(op, Op::Sin(_) | Op::Cos(_))),
        0
    );
    assert_eq!(count(&program, |op| matches!(op, Op::Tan(_))), 1);
    let got = program.evaluate_vec(&[0.3, 0.4]).unwrap();
    let expected = s.evaluate_many(&[product, sine, tangent], &|id| [0.3, 0.4][id.index()]);
    assert_eq!(got, expected);
}

#[test]
fn a_square_is_one_multiplication() {
    let (mut s, symbols, v) = store_with(&["x"]);
    let square = s.mul2(v[0], v[0]);
    let program = lower(&s, &symbols, &[square]).unwrap();
    assert_eq!(
        program.to_string(),
        "t0 = in[0] (x)\nt1 = t0 * t0\nout[0] = t1\n"
    );
    assert_eq!(
        program.operation_count(),
        OperationCount {
            before_cse: 1,
            after_cse: 1
        }
    );
}

#[test]
fn a_cube_reuses_the_square() {
    let (mut s, symbols, v) = store_with(&["x"]);
    let square = s.pow(v[0], Rational::integer(2)).unwrap();
    let cube = s.pow(v[0], Rational::integer(3)).unwrap();
    let sum = s.add2(square, cube);
    let program = lower(&s, &symbols, &[sum]).unwrap();
    assert_eq!(
        count(&program, |op| matches!(op, Op::Mul(..))),
        2,
        "{program}"
    );
    assert_eq!(after_cse(&program), 3);
    assert_eq!(program.operation_count().before_cse, 4);
}

#[test]
fn a_negative_coefficient_is_subtracted() {
    let (mut s, symbols, v) = store_with(&["a", "b"]);
    let three = s.integer(3);
    let three_b = s.mul2(three, v[1]);
    let difference = s.sub(v[0], three_b);
    let program = lower(&s, &symbols, &[difference]).unwrap();
    assert_eq!(
        program.to_string(),
        "t0 = in[0] (a)\nt1 = in[1] (b)\nt2 = 3\nt3 = t1 * t2\nt4 = t0 - t3\nout[0] = t4\n"
    );
}

#[test]
fn a_lone_negation_is_neg_and_a_lone_scaled_term_keeps_its_sign() {
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let minus_x = s.neg(v[0]);
    let minus_three = s.integer(-3);
    let scaled = s.mul2(minus_three, v[1]);
    let both_negative = s.add2(minus_x, scaled);
    let program = lower(&s, &symbols, &[minus_x, scaled, both_negative]).unwrap();
    assert_eq!(
        count(&program, |op| matches!(op, Op::Neg(_))),
        1,
        "{program}"
    );
    assert!(program.to_string().contains("= -3\n"), "{program}");
    assert!(!program.to_string().contains("= 3\n"), "{program}");
    assert_eq!(after_cse(&program), 3, "{program}");
    let got = program.evaluate_vec(&[2.0, 5.0]).unwrap();
    assert_eq!(got, vec![-2.0, -15.0, -17.0]);
}

#[test]
fn negative_powers_in_a_product_share_one_division() {
    let (mut s, symbols, v) = store_with(&["a", "b", "c", "d"]);
    let c_inverse = s.pow(v[2], Rational::integer(-1)).unwrap();
    let d_inverse_square = s.pow(v[3], Rational::integer(-2)).unwrap();
    let quotient = s.mul(&[v[0], v[1], c_inverse, d_inverse_square]);
    let program = lower(&s, &symbols, &[quotient]).unwrap();
    assert_eq!(
        count(&program, |op| matches!(op, Op::Div(..))),
        1,
        "{program}"
    );
    assert_eq!(after_cse(&program), 4, "{program}");
    assert_eq!(program.operation_count().before_cse, 6);
    let got = program.evaluate_vec(&[2.0, 3.0, 4.0, 0.5]).unwrap();
    assert_eq!(got, vec![6.0]);
}

/// The snakeboard's flow, `xdot = p cos(phi) cos(theta) / m`,
/// `ydot = p cos(phi) sin(theta) / m`, `thetadot = p sin(phi) / (m r)` and
/// `pdot = -u sin(phi) / r`: `m` and `r` divide twice each, so their
/// reciprocals are taken once (two divisions, not four) and multiplied, and
/// the products share `v = p / m` and `v cos(phi)` as a hand writes them:
/// eight products in all.
#[test]
fn a_repeated_divisor_is_inverted_once() {
    let (mut s, symbols, v) = store_with(&["theta", "phi", "p", "u", "m", "r"]);
    let [theta, phi, p, u, m, r] = [v[0], v[1], v[2], v[3], v[4], v[5]];
    let minus_one = Rational::integer(-1);
    let m_inverse = s.pow(m, minus_one.clone()).unwrap();
    let r_inverse = s.pow(r, minus_one.clone()).unwrap();
    let (sin_theta, cos_theta) = (
        s.apply(Function::Sin, theta).unwrap(),
        s.apply(Function::Cos, theta).unwrap(),
    );
    let (sin_phi, cos_phi) = (
        s.apply(Function::Sin, phi).unwrap(),
        s.apply(Function::Cos, phi).unwrap(),
    );
    let minus = s.number(minus_one);
    let outputs = [
        s.mul(&[p, cos_phi, cos_theta, m_inverse]),
        s.mul(&[p, cos_phi, sin_theta, m_inverse]),
        s.mul(&[p, sin_phi, m_inverse, r_inverse]),
        s.mul(&[minus, u, sin_phi, r_inverse]),
    ];
    let program = lower(&s, &symbols, &outputs).unwrap();
    assert_eq!(
        count(&program, |op| matches!(op, Op::Div(..))),
        2,
        "{program}"
    );
    let products = count(&program, |op| matches!(op, Op::Mul(..)));
    assert_eq!(products, 8, "{program}");
    let state: [f64; 6] = [0.3, -0.7, 1.9, 0.4, 2.5, 0.8];
    let [theta, phi, p, u, m, r] = state;
    let expected = [
        p * phi.cos() * theta.cos() / m,
        p * phi.cos() * theta.sin() / m,
        p * phi.sin() / (m * r),
        -u * phi.sin() / r,
    ];
    let got = program.evaluate_vec(&state).unwrap();
    for (got, expected) in got.iter().zip(expected) {
        assert!(
            (got - expected).abs() <= 1e-15 * expected.abs(),
            "{got} {expected}"
        );
    }
}

#[test]
fn a_divisor_read_once_stays_a_division() {
    let (mut s, symbols, v) = store_with(&["a", "b", "m"]);
    let m_inverse = s.pow(v[2], Rational::integer(-1)).unwrap();
    let outputs = [s.mul(&[v[0], m_inverse]), s.mul(&[v[0], v[1]])];
    let program = lower(&s, &symbols, &outputs).unwrap();
    assert_eq!(count(&program, |op| matches!(op, Op::Div(..))), 1);
    assert_eq!(after_cse(&program), 2, "{program}");
}

#[test]
fn powers_use_division_sqrt_powi_and_powf() {
    let (mut s, symbols, v) = store_with(&["x"]);
    let exponents = [(-1, 1), (-1, 2), (1, 2), (5, 1), (-4, 1), (1, 3)];
    let powers: Vec<ExprId> = exponents
        .iter()
        .map(|&(n, d)| s.pow(v[0], Rational::new(n, d).unwrap()).unwrap())
        .collect();
    let program = lower(&s, &symbols, &powers).unwrap();
    let text = program.to_string();
    for line in [
        "t1 = 1\n",
        "t2 = t1 / t0\n",
        "t3 = sqrt(t0)\n",
        "t4 = t1 / t3\n",
    ] {
        assert!(text.contains(line), "{line:?} missing from\n{text}");
    }
    for line in ["powi(t0, 5)", "powi(t0, -4)", "powf(t0, 1/3)"] {
        assert!(text.contains(line), "{line:?} missing from\n{text}");
    }
    let got = program.evaluate_vec(&[4.0]).unwrap();
    let expected = s.evaluate_many(&powers, &|_| 4.0);
    assert_eq!(got, expected);
}

#[test]
fn constants_anywhere_in_a_product_are_folded_into_one() {
    // `Store::mul` can leave `2` after `x` (see tests/engine_findings.rs):
    // `3*sqrt(2x)^2` is `Mul[3, x, 2]` and `-sqrt(2x)^2` is `Mul[-1, x, 2]`.
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let two = s.integer(2);
    let two_x = s.mul2(two, v[0]);
    let root = s.sqrt(two_x).unwrap();
    let three = s.integer(3);
    let scaled = s.mul(&[three, root, root]);
    let minus_one = s.integer(-1);
    let negated = s.mul(&[minus_one, root, root]);
    let sum = s.add2(v[1], negated);
    let outputs = [scaled, sum];
    let program = lower(&s, &symbols, &outputs).unwrap();
    let text = program.to_string();
    assert!(text.contains("= 6\n") && text.contains("= 2\n"), "{text}");
    assert_eq!(
        count(&program, |op| matches!(op, Op::Constant(_))),
        2,
        "{text}"
    );
    assert_eq!(count(&program, |op| matches!(op, Op::Sub(..))), 1, "{text}");
    let got = program.evaluate_vec(&[0.5, 0.25]).unwrap();
    let expected = s.evaluate_many(&outputs, &|id| [0.5, 0.25][id.index()]);
    assert_eq!(got, expected);
}

#[test]
fn products_with_a_common_prefix_share_it() {
    let (mut s, symbols, v) = store_with(&["a", "b", "c", "d"]);
    let abc = s.mul(&[v[2], v[0], v[1]]);
    let abd = s.mul(&[v[0], v[3], v[1]]);
    let program = lower(&s, &symbols, &[abc, abd]).unwrap();
    assert_eq!(after_cse(&program), 3, "{program}");
    assert_eq!(program.operation_count().before_cse, 4);
}

#[test]
fn a_symbol_that_is_not_an_input_is_an_error() {
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let sum = s.add2(v[0], v[1]);
    let error = lower(&s, &symbols[..1], &[sum]).unwrap_err();
    assert_eq!(error, IrError::UnboundSymbol { name: "y".into() });
    assert_eq!(
        error.to_string(),
        "symbol `y` is used by an output but is not an input"
    );
    let foreign = Store::new();
    assert_eq!(
        lower(&foreign, &[], &[sum]).unwrap_err(),
        IrError::UnknownExpression { output: 0 }
    );
}

#[test]
fn display_prints_one_line_per_instruction_then_the_outputs() {
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let (x, y) = (v[0], v[1]);
    let sine = s.apply(Function::Sin, x).unwrap();
    let cosine = s.apply(Function::Cos, x).unwrap();
    let product = s.mul2(sine, y);
    let first = s.sub(product, cosine);
    let square = s.mul2(x, x);
    let three = s.integer(3);
    let three_sine = s.mul2(three, sine);
    let second = s.add2(square, three_sine);
    let program = lower(&s, &symbols, &[first, second]).unwrap();
    let expected = "\
t0 = in[0] (x)
t1 = in[1] (y)
t2, t3 = sin_cos(t0)
t4 = t1 * t2
t5 = t4 - t3
t6 = t0 * t0
t7 = 3
t8 = t2 * t7
t9 = t6 + t8
out[0] = t5
out[1] = t9
";
    assert_eq!(program.to_string(), expected);
}

#[test]
fn heavy_sharing_is_counted_without_expanding() {
    let (mut s, symbols, v) = store_with(&["x"]);
    let mut levels = vec![v[0]];
    for _ in 0..200 {
        let e = *levels.last().unwrap();
        let square = s.mul2(e, e);
        levels.push(s.add2(square, e));
    }
    let program = lower(&s, &symbols, &[levels[30]]).unwrap();
    let count = program.operation_count();
    assert_eq!(count.before_cse, (1 << 31) - 2);
    assert_eq!(count.after_cse, 60, "{program}");
    let saturated = lower(&s, &symbols, &[levels[200]]).unwrap();
    assert_eq!(saturated.operation_count().before_cse, u64::MAX);
    let got = program.evaluate_vec(&[1e-3]).unwrap();
    let expected = s.evaluate(levels[30], &|_| 1e-3);
    assert!((got[0] - expected).abs() <= 1e-12 * expected.abs());
}

#[test]
fn wrong_buffer_lengths_are_errors() {
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let sum = s.add2(v[0], v[1]);
    let program = lower(&s, &symbols, &[sum]).unwrap();
    let mut scratch = Vec::new();
    let mut one = [0.0];
    assert_eq!(
        program.evaluate(&[1.0], &mut scratch, &mut one),
        Err(IrError::InputCount {
            expected: 2,
            found: 1
        })
    );
    assert_eq!(
        program.evaluate(&[1.0, 2.0], &mut scratch, &mut [0.0; 2]),
        Err(IrError::OutputCount {
            expected: 1,
            found: 2
        })
    );
    program
        .evaluate(&[1.0, 2.0], &mut scratch, &mut one)
        .unwrap();
    assert_eq!(one, [3.0]);
    assert!(matches!(program.emit(&[]), Err(IrError::InputCount { .. })));
}

#[test]
fn values_read_once_are_written_into_their_reader() {
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let sine = s.apply(Function::Sin, v[0]).unwrap();
    let cosine = s.apply(Function::Cos, v[0]).unwrap();
    let product = s.mul2(sine, v[1]);
    let first = s.sub(product, cosine);
    let program = lower(&s, &symbols, &[first]).unwrap();
    let emitted = program.emit(&[quote!(q[0]), quote!(self.m)]).unwrap();
    assert_eq!(
        emitted.statements.to_string(),
        "let (t0 , t1) = q [0] . sin_cos () ;"
    );
    assert_eq!(emitted.outputs.len(), 1);
    assert_eq!(emitted.outputs[0].to_string(), "self . m * t0 - t1");
}

#[test]
fn a_value_read_twice_gets_a_let_and_trees_keep_their_grouping() {
    let (mut s, symbols, v) = store_with(&["x", "y", "z"]);
    let sum = s.add2(v[1], v[2]);
    let difference = s.sub(v[0], sum);
    let root = s.sqrt(sum).unwrap();
    let program = lower(&s, &symbols, &[difference, root]).unwrap();
    let emitted = program
        .emit(&[quote!(q[0]), quote!(q[1]), quote!(q[2])])
        .unwrap();
    assert_eq!(
        emitted.statements.to_string(),
        "let t0 = q [1] + q [2] ;",
        "{program}"
    );
    let outputs: Vec<String> = emitted.outputs.iter().map(ToString::to_string).collect();
    assert_eq!(outputs, ["q [0] - t0", "t0 . sqrt ()"]);
}

#[test]
fn a_literal_whose_method_is_called_is_typed_by_its_suffix() {
    let (mut s, symbols, v) = store_with(&["x", "y"]);
    let two = s.integer(2);
    let root = s.sqrt(two).unwrap();
    let first = s.mul2(root, v[0]);
    let second = s.mul2(root, v[1]);
    let program = lower(&s, &symbols, &[first, second]).unwrap();
    let statements = program
        .emit(&[quote!(q[0]), quote!(q[1])])
        .unwrap()
        .statements
        .to_string();
    assert_eq!(statements, "let t0 = 2f64 . sqrt () ;", "{program}");
}

/// `c*x` for awkward constants `c`, and `x^(-1/3)`, over the input `x`.
fn constants_program() -> Program {
    let (mut s, symbols, v) = store_with(&["x"]);
    let constants = [
        Rational::integer(2),
        Rational::integer(-3),
        Rational::from_decimal("1e-30").unwrap(),
        Rational::from_decimal("1e400").unwrap(),
        Rational::from_decimal("1e400").unwrap().neg(),
        Rational::new(1, 3).unwrap(),
    ];
    let mut outputs: Vec<ExprId> = constants
        .iter()
        .map(|c| {
            let c = s.number(c.clone());
            s.mul2(c, v[0])
        })
        .collect();
    outputs.push(s.pow(v[0], Rational::new(-1, 3).unwrap()).unwrap());
    lower(&s, &symbols, &outputs).unwrap()
}

#[test]
fn constants_become_valid_float_literals() {
    let source = emit_function("f", &constants_program(), 1);
    syn::parse_str::<syn::File>(&source).unwrap();
    let literals = [
        "t0 * 2.0 ,",
        "t0 * - 3.0 ,",
        "t0 * 0.000000000000000000000000000001 ,",
        "t0 * :: core :: primitive :: f64 :: INFINITY ,",
        "t0 * :: core :: primitive :: f64 :: NEG_INFINITY ,",
        "t0 * 0.3333333333333333 ,",
        "powf (- 0.3333333333333333)",
    ];
    for literal in literals {
        assert!(
            source.contains(literal),
            "{literal:?} missing from {source}"
        );
    }
}

#[test]
fn an_emitted_function_parses_as_rust() {
    let (mut s, symbols, v) = store_with(&["q0", "q1", "p0"]);
    let (q0, q1, p0) = (v[0], v[1], v[2]);
    let sine = s.apply(Function::Sin, q0).unwrap();
    let cosine = s.apply(Function::Cos, q0).unwrap();
    let sum = s.add2(q1, p0);
    let root = s.sqrt(sum).unwrap();
    let first = s.mul(&[sine, root, p0]);
    let inverse = s.pow(sum, Rational::integer(-2)).unwrap();
    let second = s.mul(&[cosine, inverse, q1]);
    let half = s.number(Rational::new(1, 2).unwrap());
    let third = s.add(&[half, first, second]);
    let program = lower(&s, &symbols, &[first, second, third]).unwrap();
    let inputs = [quote!(q[0]), quote!(q[1]), quote!(p[0])];
    let RustProgram {
        statements,
        outputs,
    } = program.emit(&inputs).unwrap();
    let source = quote!(
        fn f(q: &[f64; 2], p: &[f64; 1]) -> [f64; 3] {
            #statements
            [#(#outputs),*]
        }
    )
    .to_string();
    syn::parse_str::<syn::File>(&source).unwrap();
}

/// Compiles [`constants_program`] and 60 random programs as one crate with
/// `rustc --edition 2024 -D warnings`, in a module without the prelude where
/// the items `f64` and `core` shadow the standard ones, runs it, and compares
/// every output bit for bit with the interpreter (one rustc run, well under a second).
/// 4000 more random expressions make one long program, cut into blocks
/// ([`super::BLOCK_OPERATIONS`]), emitted whole and as two variants (its
/// first and second halves of outputs, chosen by `chart`).
#[test]
fn emitted_code_compiles_warning_free_and_matches_the_interpreter() {
    use super::properties::{SYMBOLS, build, symbol_store, tree};
    use proptest::strategy::{Strategy, ValueTree};
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let (mut store, symbols, leaves) = symbol_store();
    let mut programs = Vec::new();
    let mut every_output = Vec::new();
    for _ in 0..60 {
        let strategy = proptest::collection::vec(tree(), 1..=3);
        let trees = strategy.new_tree(&mut runner).unwrap().current();
        let outputs: Vec<ExprId> = trees
            .iter()
            .map(|t| build(&mut store, &leaves, t))
            .collect();
        programs.push(lower(&store, &symbols, &outputs).unwrap());
    }
    while every_output.len() < 4000 {
        let tree = tree().new_tree(&mut runner).unwrap().current();
        every_output.push(build(&mut store, &leaves, &tree));
    }
    let long = lower(&store, &symbols, &every_output).unwrap();
    assert!(
        long.operation_count().after_cse > 2 * super::BLOCK_OPERATIONS,
        "{}",
        long.operation_count().after_cse
    );
    let half = every_output.len() / 2;
    let variants = [(0..half).collect(), (half..2 * half).collect()];
    let mut functions = emit_function("constants", &constants_program(), 1);
    functions.extend(
        programs
            .iter()
            .enumerate()
            .map(|(i, p)| emit_function(&format!("f{i}"), p, SYMBOLS)),
    );
    functions.push_str(&emit_function("long", &long, SYMBOLS));
    functions.push_str(&emit_variants_function("charted", &long, &variants));
    let mut calls =
        String::from("for x in generated::constants(&[0.7]) { println!(\"{}\", x.to_bits()); }\n");
    calls += &(0..programs.len())
        .map(|i| format!("for x in generated::f{i}(&Q) {{ println!(\"{{}}\", x.to_bits()); }}\n"))
        .collect::<String>();
    calls += "for x in generated::long(&Q) { println!(\"{}\", x.to_bits()); }\n";
    calls += "for chart in 0..2 { for x in generated::charted(chart, &Q) { println!(\"{}\", x.to_bits()); } }\n";
    let source = format!(
        "#![deny(warnings)]\n\
         mod generated {{\n\
         #![no_implicit_prelude]\n\
         #[allow(non_camel_case_types, dead_code)] struct f64;\n\
         #[allow(dead_code)] mod core {{}}\n\
         {functions}\n}}\n\
         const Q: [f64; 3] = [0.3, -1.1, 0.7];\n\
         fn main() {{\n{calls}}}\n"
    );
    let scratch = tempfile::Builder::new()
        .prefix("chaplygin-ir-emit-check-")
        .tempdir()
        .expect("a scratch directory under the temporary directory");
    let dir = scratch.path();
    std::fs::write(dir.join("main.rs"), &source).unwrap();
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let compiled = std::process::Command::new(rustc)
        .args(["--edition", "2024", "-D", "warnings", "-o"])
        .arg(dir.join("main"))
        .arg(dir.join("main.rs"))
        .output()
        .unwrap();
    assert!(
        compiled.status.success(),
        "{}",
        String::from_utf8_lossy(&compiled.stderr)
    );
    let run = std::process::Command::new(dir.join("main"))
        .output()
        .unwrap();
    let printed: Vec<u64> = String::from_utf8_lossy(&run.stdout)
        .lines()
        .map(|line| line.parse().unwrap())
        .collect();
    let mut interpreted = constants_program().evaluate_vec(&[0.7]).unwrap();
    for program in &programs {
        interpreted.extend(program.evaluate_vec(&[0.3, -1.1, 0.7]).unwrap());
    }
    let long_values = long.evaluate_vec(&[0.3, -1.1, 0.7]).unwrap();
    interpreted.extend(&long_values);
    interpreted.extend(&long_values);
    let interpreted: Vec<u64> = interpreted.into_iter().map(f64::to_bits).collect();
    assert_eq!(printed, interpreted);
}

/// Two programs, the second reading the first's outputs and an input.
fn two_stages() -> (Program, Program) {
    let (mut s, symbols, v) = store_with(&["x", "y", "a", "b"]);
    let sine = s.apply(Function::Sin, v[0]).unwrap();
    let cosine = s.apply(Function::Cos, v[0]).unwrap();
    let first = [s.mul2(sine, v[1]), s.add2(cosine, v[1]), s.mul2(v[0], v[0])];
    let product = s.mul2(v[2], v[3]);
    let second = [s.add2(product, sine), s.sub(v[2], cosine)];
    let first = lower(&s, &symbols[..2], &first).unwrap();
    let reads = [symbols[2], symbols[3], symbols[0]];
    let second = lower(&s, &reads, &second).unwrap();
    (first, second)
}

#[test]
fn a_chain_computes_what_its_stages_compute_one_by_one() {
    use super::{Source, Stage};
    let (first, second) = two_stages();
    let names = ["x".to_string(), "y".to_string()];
    let chained = Program::chained(
        &names,
        &[
            Stage {
                program: &first,
                sources: &[Source::Input(0), Source::Input(1)],
            },
            Stage {
                program: &second,
                sources: &[
                    Source::Output {
                        stage: 0,
                        output: 0,
                    },
                    Source::Output {
                        stage: 0,
                        output: 1,
                    },
                    Source::Input(0),
                ],
            },
        ],
    )
    .unwrap();
    for point in [[0.3, -1.7], [2.5, 0.25]] {
        let between = first.evaluate_vec(&point).unwrap();
        let expected = second
            .evaluate_vec(&[between[0], between[1], point[0]])
            .unwrap();
        let got = chained.evaluate_vec(&point).unwrap();
        assert_eq!(
            got.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            expected.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
    }
    // the second stage's sine and cosine are the first's, and `x * x`,
    // which no output reads, is gone
    assert_eq!(
        count(&chained, |op| matches!(op, Op::SinCos { .. })),
        1,
        "{chained}"
    );
    assert_eq!(
        after_cse(&chained),
        after_cse(&first) - 1 + after_cse(&second) - 1
    );
}

#[test]
fn a_chain_refuses_sources_that_do_not_fit() {
    use super::{Source, Stage};
    let (first, second) = two_stages();
    let names = ["x".to_string(), "y".to_string()];
    let stage = |sources| Stage {
        program: &second,
        sources,
    };
    let too_few = Program::chained(&names, &[stage(&[Source::Input(0)])]);
    assert_eq!(
        too_few.unwrap_err(),
        IrError::InputCount {
            expected: 3,
            found: 1
        }
    );
    let later = [
        Source::Output {
            stage: 1,
            output: 0,
        },
        Source::Input(0),
        Source::Input(1),
    ];
    let first_stage = Stage {
        program: &first,
        sources: &[Source::Input(0), Source::Input(1)],
    };
    assert!(matches!(
        Program::chained(&names, &[first_stage, stage(&later)]),
        Err(IrError::UnboundSymbol { .. })
    ));
    let beyond = [Source::Input(2), Source::Input(0), Source::Input(1)];
    assert!(matches!(
        Program::chained(&names, &[stage(&beyond)]),
        Err(IrError::UnboundSymbol { .. })
    ));
}
