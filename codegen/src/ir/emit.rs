//! Emission of a [`Program`] as Rust statements.
//!
//! Each instruction becomes one `let` with an explicit type, e.g.
//! `let t3: ::core::primitive::f64 = t1 * t0;`, or
//! `let (t4, t5) = t3.sin_cos();` for [`Op::SinCos`]. The code is spliced into
//! user crates, so it names types by absolute path only (a user item called
//! `f64` or a module called `core` cannot capture it), calls only `f64`
//! methods, allocates nothing, cannot panic, and compiles warning-free: every
//! `let` is read (the program has no dead values) and every expression is a
//! single operation, so no parentheses are ever needed. Constants are `let`s of
//! float literals (`2.0`, `-0.5`, `0.000000000000000000000000000001`;
//! non-finite ones as `::core::primitive::f64::INFINITY` and friends).
//!
//! Values are named `t0, t1, ...` with [`Span::mixed_site`]: inside a
//! procedural macro they cannot clash with the caller's identifiers, and they
//! resolve among themselves and in the returned output expressions. Code
//! written out as text (e.g. from a build script) has no hygiene: there, the
//! input expressions must not mention identifiers of the form `t<n>`.

use super::{Instruction, IrError, Op, Program, Value};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{ToTokens, quote};

/// A program written out as Rust: its statements and its outputs.
#[derive(Clone, Debug)]
pub struct RustProgram {
    /// The `let` statements computing every value, in order.
    pub statements: TokenStream,
    /// One expression per output, valid after `statements`.
    pub outputs: Vec<TokenStream>,
}

impl Program {
    /// Emits the program as Rust statements; `inputs[i]` is an expression of
    /// type `f64` for input slot `i` (e.g. `q[2]`, `self.m`).
    ///
    /// Fails with [`IrError::InputCount`] unless there is one expression per
    /// input slot.
    pub fn emit(&self, inputs: &[TokenStream]) -> Result<RustProgram, IrError> {
        self.check_inputs(inputs.len())?;
        let statements = self
            .instructions
            .iter()
            .map(|instruction| statement(instruction, inputs))
            .collect();
        let outputs = self
            .outputs
            .iter()
            .map(|&value| name(value).into_token_stream())
            .collect();
        Ok(RustProgram {
            statements,
            outputs,
        })
    }
}

fn name(value: Value) -> Ident {
    Ident::new(&value.to_string(), Span::mixed_site())
}

fn statement(instruction: &Instruction, inputs: &[TokenStream]) -> TokenStream {
    let result = name(instruction.result);
    let value = expression(&instruction.op, inputs);
    match instruction.op {
        Op::SinCos { cosine, .. } => {
            let cosine = name(cosine);
            quote!(let (#result, #cosine) = #value;)
        }
        _ => quote!(let #result: ::core::primitive::f64 = #value;),
    }
}

/// The right-hand side of an instruction's `let`.
fn expression(op: &Op, inputs: &[TokenStream]) -> TokenStream {
    let n = |value: &Value| name(*value);
    match op {
        Op::Input(slot) => inputs[*slot].clone(),
        Op::Constant(c) => float_literal(c.value()),
        Op::Add(a, b) => binary(n(a), quote!(+), n(b)),
        Op::Sub(a, b) => binary(n(a), quote!(-), n(b)),
        Op::Mul(a, b) => binary(n(a), quote!(*), n(b)),
        Op::Div(a, b) => binary(n(a), quote!(/), n(b)),
        Op::Neg(a) => {
            let a = n(a);
            quote!(-#a)
        }
        Op::Powi(a, exponent) => method(n(a), "powi", Literal::i32_unsuffixed(*exponent)),
        Op::Powf(a, exponent) => method(n(a), "powf", float_literal(exponent.value())),
        Op::Sqrt(a) => method(n(a), "sqrt", TokenStream::new()),
        Op::Sin(a) => method(n(a), "sin", TokenStream::new()),
        Op::Cos(a) => method(n(a), "cos", TokenStream::new()),
        Op::Tan(a) => method(n(a), "tan", TokenStream::new()),
        Op::Exp(a) => method(n(a), "exp", TokenStream::new()),
        Op::Ln(a) => method(n(a), "ln", TokenStream::new()),
        Op::SinCos { angle, .. } => method(n(angle), "sin_cos", TokenStream::new()),
    }
}

fn binary(a: Ident, operator: TokenStream, b: Ident) -> TokenStream {
    quote!(#a #operator #b)
}

fn method(receiver: Ident, method: &str, argument: impl ToTokens) -> TokenStream {
    let method = Ident::new(method, Span::call_site());
    quote!(#receiver.#method(#argument))
}

/// A float expression of type `f64` that reproduces `x` exactly.
fn float_literal(x: f64) -> TokenStream {
    if x.is_nan() {
        return quote!(::core::primitive::f64::NAN);
    }
    if x.is_infinite() {
        return if x > 0.0 {
            quote!(::core::primitive::f64::INFINITY)
        } else {
            quote!(::core::primitive::f64::NEG_INFINITY)
        };
    }
    let magnitude = Literal::f64_unsuffixed(x.abs());
    if x.is_sign_negative() {
        quote!(-#magnitude)
    } else {
        quote!(#magnitude)
    }
}
