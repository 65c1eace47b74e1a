//! Rust expressions of single operations and the trees written in place of
//! values read once: their precedence, their width as formatted, and float
//! literals that reproduce a constant exactly.

use proc_macro2::{Delimiter, Group, Literal, TokenStream};
use quote::{ToTokens, quote};

/// How tightly an expression binds, loosest first: a binary operand of a
/// looser or equal class is parenthesized.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Binding {
    /// `a + b`, `a - b`.
    Sum,
    /// `a * b`, `a / b`.
    Product,
    /// `-a`, and a negative literal.
    Negation,
    /// A name, an input, a positive literal, a method call.
    Atom,
}

/// An expression, with what its reader needs to know to write it.
#[derive(Clone)]
pub(super) struct Expression {
    pub(super) tokens: TokenStream,
    pub(super) binding: Binding,
    /// Characters as formatted.
    pub(super) width: usize,
    /// Whether it reads a value or an input (else it is literals alone,
    /// whose type Rust cannot infer).
    pub(super) typed: bool,
}

impl Expression {
    pub(super) fn atom(tokens: TokenStream, width: usize, typed: bool) -> Expression {
        Expression {
            tokens,
            binding: Binding::Atom,
            width,
            typed,
        }
    }

    /// No tokens: the argument of a method without one.
    pub(super) fn empty() -> Expression {
        Expression::atom(TokenStream::new(), 0, true)
    }

    /// Itself, in parentheses when `parenthesize`, and its width.
    pub(super) fn grouped(self, parenthesize: bool) -> (TokenStream, usize) {
        match parenthesize {
            true => (
                Group::new(Delimiter::Parenthesis, self.tokens).into_token_stream(),
                self.width + 2,
            ),
            false => (self.tokens, self.width),
        }
    }

    /// `left operator right` at `binding`: the left operand parenthesized
    /// when it binds more loosely, the right one also when it binds alike
    /// (the operators group to the left), so that the tree is the one
    /// written.
    pub(super) fn binary(
        left: Expression,
        operator: TokenStream,
        right: Expression,
        binding: Binding,
    ) -> Expression {
        let typed = left.typed || right.typed;
        let left_parenthesized = left.binding < binding;
        let right_parenthesized = right.binding <= binding;
        let (left, left_width) = left.grouped(left_parenthesized);
        let (right, right_width) = right.grouped(right_parenthesized);
        Expression {
            tokens: quote!(#left #operator #right),
            binding,
            width: left_width + right_width + 3,
            typed,
        }
    }

    /// `-operand`, parenthesized unless it binds tighter than a negation
    /// (no `--x`).
    pub(super) fn negation(operand: Expression) -> Expression {
        let typed = operand.typed;
        let parenthesize = operand.binding <= Binding::Negation;
        let (operand, width) = operand.grouped(parenthesize);
        Expression {
            tokens: quote!(-#operand),
            binding: Binding::Negation,
            width: width + 1,
            typed,
        }
    }

    /// `receiver.method(argument)`; the receiver is an atom already.
    pub(super) fn method(
        (receiver, receiver_width): (TokenStream, usize),
        method: &str,
        argument: Expression,
    ) -> Expression {
        let width = receiver_width + method.len() + argument.width + 3;
        let method = proc_macro2::Ident::new(method, proc_macro2::Span::call_site());
        let argument = argument.tokens;
        Expression::atom(quote!(#receiver.#method(#argument)), width, true)
    }
}

/// A float expression of type `f64` that reproduces `x` exactly; with
/// `suffixed`, typed by its suffix (`2f64`), as the receiver of a method.
pub(super) fn literal(x: f64, suffixed: bool) -> Expression {
    if x.is_nan() || x.is_infinite() {
        let constant = match x {
            x if x.is_nan() => quote!(::core::primitive::f64::NAN),
            x if x > 0.0 => quote!(::core::primitive::f64::INFINITY),
            _ => quote!(::core::primitive::f64::NEG_INFINITY),
        };
        return Expression::atom(constant, 30, true);
    }
    let magnitude = match suffixed {
        true => Literal::f64_suffixed(x.abs()),
        false => Literal::f64_unsuffixed(x.abs()),
    };
    let width = magnitude.to_string().len();
    match x.is_sign_negative() {
        true if suffixed => Expression::atom(
            Group::new(Delimiter::Parenthesis, quote!(-#magnitude)).into_token_stream(),
            width + 3,
            true,
        ),
        true => Expression {
            tokens: quote!(-#magnitude),
            binding: Binding::Negation,
            width: width + 1,
            typed: false,
        },
        false => Expression::atom(magnitude.into_token_stream(), width, suffixed),
    }
}
