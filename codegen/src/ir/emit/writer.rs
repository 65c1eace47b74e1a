//! Instructions written as statements: values read once written in place,
//! the others bound by `let`, and a long program's straight line cut into
//! blocks ([`super::BLOCK_OPERATIONS`]).

use super::expression::{Binding, Expression, literal};
use super::{NAME_WIDTH, WIDTH};
use crate::ir::{Instruction, Op, Program, Value};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{ToTokens, quote};
use std::rc::Rc;

/// What a value is while the instructions are written.
#[derive(Clone)]
enum State {
    /// Not yet defined.
    Pending,
    /// Bound by a `let` to this name.
    Named(Ident),
    /// A constant, written as a literal wherever it is read.
    Constant(f64),
    /// Read once: written into its reader.
    Inline(Expression),
    /// Written into its reader already.
    Spent,
}

#[derive(Clone)]
pub(super) struct Writer<'a> {
    inputs: &'a [TokenStream],
    /// Reads of each value by instructions and outputs.
    reads: Rc<[u32]>,
    states: Vec<State>,
    pub(super) next_name: u32,
    /// Operations between two block boundaries; `None` writes one block.
    block: Option<u64>,
    /// Operations written since the last boundary.
    since_boundary: u64,
    pub(super) statements: TokenStream,
}

impl<'a> Writer<'a> {
    pub(super) fn new(program: &Program, inputs: &'a [TokenStream], block: Option<u64>) -> Self {
        let mut reads = vec![0u32; program.value_count];
        for instruction in &program.instructions {
            for operand in instruction.op.operands() {
                reads[operand.index()] += 1;
            }
        }
        for output in &program.outputs {
            reads[output.index()] += 1;
        }
        Writer {
            inputs,
            reads: reads.into(),
            states: vec![State::Pending; program.value_count],
            next_name: 0,
            block,
            since_boundary: 0,
            statements: TokenStream::new(),
        }
    }

    /// Writes one instruction, after a block boundary when the current
    /// block is full.
    pub(super) fn instruction(&mut self, instruction: &Instruction) {
        if let Some(block) = self.block
            && self.since_boundary >= block
        {
            self.statements.extend(block_boundary());
            self.since_boundary = 0;
        }
        self.since_boundary += instruction.op.cost();
        let result = instruction.result;
        match &instruction.op {
            Op::Constant(c) => self.states[result.index()] = State::Constant(c.value()),
            &Op::SinCos { angle, cosine } => {
                let (angle, _) = self.method_receiver(angle);
                let (sine, cosine_name) = (self.fresh_name(), self.fresh_name());
                let statement = quote!(let (#sine, #cosine_name) = #angle.sin_cos(););
                self.statements.extend(statement);
                self.states[result.index()] = State::Named(sine);
                self.states[cosine.index()] = State::Named(cosine_name);
            }
            op => {
                let expression = self.expression(op);
                match self.reads[result.index()] {
                    1 => self.states[result.index()] = State::Inline(expression),
                    _ => self.bind(result, expression),
                }
            }
        }
    }

    /// The expression of an output, after the instructions.
    pub(super) fn output(&mut self, value: Value) -> TokenStream {
        self.operand(value).tokens
    }

    /// A `let` binding `value` to `expression`.
    fn bind(&mut self, value: Value, expression: Expression) {
        let name = self.fresh_name();
        let tokens = expression.tokens;
        self.statements.extend(match expression.typed {
            true => quote!(let #name = #tokens;),
            false => quote!(let #name: ::core::primitive::f64 = #tokens;),
        });
        self.states[value.index()] = State::Named(name);
    }

    fn fresh_name(&mut self) -> Ident {
        let name = Ident::new(&format!("t{}", self.next_name), Span::mixed_site());
        self.next_name += 1;
        name
    }

    /// The value as its reader writes it: its name, its literal, or its
    /// expression (which the value gives up).
    fn operand(&mut self, value: Value) -> Expression {
        let state = std::mem::replace(&mut self.states[value.index()], State::Spent);
        let (expression, kept) = match state {
            State::Named(name) => {
                let width = name.to_string().len();
                let expression = Expression::atom(name.to_token_stream(), width, true);
                (expression, State::Named(name))
            }
            State::Constant(x) => (literal(x, false), State::Constant(x)),
            State::Inline(expression) => (expression, State::Spent),
            State::Pending | State::Spent => unreachable!("{value} read before it is defined"),
        };
        self.states[value.index()] = kept;
        expression
    }

    /// The width `value` adds to its reader: its expression's when it is
    /// written in place, else a name's.
    fn inline_width(&self, value: Value) -> usize {
        match &self.states[value.index()] {
            State::Inline(expression) => expression.width,
            _ => NAME_WIDTH,
        }
    }

    /// Binds `value` by a `let` if it is still to be written in place.
    fn bind_inline(&mut self, value: Value) {
        match std::mem::replace(&mut self.states[value.index()], State::Spent) {
            State::Inline(expression) => self.bind(value, expression),
            state => self.states[value.index()] = state,
        }
    }

    /// `value` read by an expression that may grow to `room` characters
    /// around it: written in place if it fits, else bound by a `let` first.
    fn fitted(&mut self, value: Value, room: usize) -> Expression {
        if self.inline_width(value) > room {
            self.bind_inline(value);
        }
        self.operand(value)
    }

    /// The receiver of a method call, and its width: parenthesized unless
    /// an atom, a literal suffixed with its type, and an expression of
    /// literals alone (`(10.0 * 10.0).sin()` does not compile) bound by a
    /// typed `let`.
    fn method_receiver(&mut self, value: Value) -> (TokenStream, usize) {
        match &self.states[value.index()] {
            State::Constant(x) => {
                let receiver = literal(*x, true);
                return (receiver.tokens, receiver.width);
            }
            State::Inline(expression) if !expression.typed => self.bind_inline(value),
            _ => {}
        }
        let receiver = self.fitted(value, WIDTH);
        let parenthesize = receiver.binding < Binding::Atom;
        receiver.grouped(parenthesize)
    }

    fn expression(&mut self, op: &Op) -> Expression {
        match op {
            &Op::Input(slot) => {
                let tokens = self.inputs[slot].clone();
                let width = tokens.to_string().replace(' ', "").len();
                Expression::atom(tokens, width, true)
            }
            Op::Constant(_) | Op::SinCos { .. } => unreachable!("written by `instruction`"),
            &Op::Add(a, b) => self.binary(a, quote!(+), b, Binding::Sum),
            &Op::Sub(a, b) => self.binary(a, quote!(-), b, Binding::Sum),
            &Op::Mul(a, b) => self.binary(a, quote!(*), b, Binding::Product),
            &Op::Div(a, b) => self.binary(a, quote!(/), b, Binding::Product),
            &Op::Neg(a) => {
                let operand = self.fitted(a, WIDTH - 3);
                Expression::negation(operand)
            }
            &Op::Powi(a, exponent) => {
                let exponent = Literal::i32_unsuffixed(exponent);
                let width = exponent.to_string().len();
                let exponent = Expression::atom(exponent.into_token_stream(), width, true);
                self.method(a, "powi", exponent)
            }
            Op::Powf(a, exponent) => self.method(*a, "powf", literal(exponent.value(), false)),
            &Op::Sqrt(a) => self.method(a, "sqrt", Expression::empty()),
            &Op::Sin(a) => self.method(a, "sin", Expression::empty()),
            &Op::Cos(a) => self.method(a, "cos", Expression::empty()),
            &Op::Tan(a) => self.method(a, "tan", Expression::empty()),
            &Op::Exp(a) => self.method(a, "exp", Expression::empty()),
            &Op::Ln(a) => self.method(a, "ln", Expression::empty()),
            &Op::Asin(a) => self.method(a, "asin", Expression::empty()),
            &Op::Acos(a) => self.method(a, "acos", Expression::empty()),
            &Op::Atan(a) => self.method(a, "atan", Expression::empty()),
            &Op::Atan2(y, x) => {
                let x = self.fitted(x, WIDTH / 2);
                self.method(y, "atan2", x)
            }
        }
    }

    /// `a operator b`; operands that together would be wider than
    /// [`WIDTH`] are bound by `let`s, the wider first.
    fn binary(
        &mut self,
        a: Value,
        operator: TokenStream,
        b: Value,
        binding: Binding,
    ) -> Expression {
        while self.inline_width(a) + self.inline_width(b) + 3 > WIDTH {
            let inline = |value: Value| matches!(self.states[value.index()], State::Inline(_));
            let wider = match (inline(a), inline(b)) {
                (false, false) => break,
                (true, false) => a,
                (false, true) => b,
                (true, true) if self.inline_width(a) >= self.inline_width(b) => a,
                (true, true) => b,
            };
            self.bind_inline(wider);
        }
        let (left, right) = (self.operand(a), self.operand(b));
        Expression::binary(left, operator, right, binding)
    }

    fn method(&mut self, receiver: Value, method: &str, argument: Expression) -> Expression {
        let receiver = self.method_receiver(receiver);
        Expression::method(receiver, method, argument)
    }
}

/// The end of one basic block and the start of the next: a branch on a
/// value the optimizer cannot see through, never taken. The values
/// computed before it stay in registers; rustc's backend then works on
/// blocks of bounded length.
fn block_boundary() -> TokenStream {
    quote!(if ::core::hint::black_box(false) {
        ::core::hint::black_box(());
    })
}
