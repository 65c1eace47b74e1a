//! The Chaplygin compiler, which the `chaplygin` crate's `model!` and
//! build scripts run (the guide, `docs/guide/` in the repository: "How it
//! works").
//!
//! A model flows one way through typed stages:
//!
//! ```text
//! tokens --syntax::parse--> ModelSyntax --model::check--> Model --derive--> analyses --emit--> Rust items
//! ```
//!
//! The symbolic engine [`sym`] holds every expression; [`derive`](mod@derive) decides
//! what each item computes (by costs estimated on the expression DAG);
//! [`ir`] lowers those expressions to straight-line code with common
//! subexpressions shared, which [`emit`] splices into allocation-free Rust. [`expand`] is what the
//! `chaplygin::model!` macro calls; [`Builder`] is the build-script door for
//! `.model` files. [`document`] lays out a model's derivation as text, LaTeX
//! or JSON; [`interpret`] runs a model text through the IR interpreter
//! without compiling Rust.

#![warn(missing_docs)]

mod build;
pub mod derive;
pub mod diagnostic;
pub mod document;
pub mod emit;
pub mod interpret;
pub mod ir;
pub mod model;
pub mod sym;
pub mod syntax;

#[cfg(test)]
mod fixtures;

pub use build::{BuildError, Builder, formatted, generate, generate_within};

use proc_macro2::TokenStream;

/// Expands the body of a `chaplygin::model! { ... }` invocation: the model's
/// items, or one `compile_error!` per problem, each spanned on its token.
pub fn expand(tokens: TokenStream) -> TokenStream {
    match try_expand(tokens) {
        Ok(items) => items,
        Err(diagnostics) => diagnostics.to_compile_errors(),
    }
}

/// [`expand`], keeping the diagnostics.
pub fn try_expand(tokens: TokenStream) -> Result<TokenStream, diagnostic::Diagnostics> {
    compile(&syntax::parse(tokens)?)
}

/// A model parsed, checked and analysed: the model, the context holding its
/// expressions, and its constraint analysis.
pub(crate) struct Analysed {
    pub(crate) model: model::Model,
    pub(crate) cx: sym::Context,
    pub(crate) constraints: derive::constraints::ConstraintAnalysis,
}

/// A model text parsed, checked and analysed within the default derivation
/// budget, as both doors do before emitting, the analysis's numeric search
/// on the engines `backend` makes. The model's context keeps charging that
/// budget: callers deriving more check [`over_budget`].
pub(crate) fn analysed_model(
    source: &str,
    backend: &dyn ir::Backend,
) -> Result<Analysed, diagnostic::Diagnostics> {
    let syntax = syntax::parse_str(source)?;
    let budget = sym::Budget::default();
    let outcome = model::check_within(&syntax, budget.clone()).and_then(|(model, mut cx)| {
        let constraints = derive::constraints::analyse_on(&model, &mut cx, backend)?;
        Ok(Analysed {
            model,
            cx,
            constraints,
        })
    });
    within_budget(&syntax, &budget, outcome)
}

/// The budget diagnostic, on the model's name, when the derivations on
/// `model` in `cx` after [`analysed_model`] spent its budget.
pub(crate) fn over_budget(
    model: &model::Model,
    cx: &sym::Context,
) -> Result<(), diagnostic::Diagnostics> {
    let Some(error) = cx.budget().error() else {
        return Ok(());
    };
    let message = error.to_string();
    Err(diagnostic::Diagnostic::new(model.name.span(), message).into())
}

/// A parsed model's items: checked, analysed, emitted (both doors), within
/// the default derivation budget ([`sym::budget`]).
fn compile(syntax: &syntax::ModelSyntax) -> Result<TokenStream, diagnostic::Diagnostics> {
    compile_within(syntax, sym::Budget::default())
}

/// [`compile`] within `budget`. When the budget runs out, the result is one
/// diagnostic stating it: on the first expression whose normal form ran out,
/// or on the model's name when the derivations after the checks ran out.
fn compile_within(
    syntax: &syntax::ModelSyntax,
    budget: sym::Budget,
) -> Result<TokenStream, diagnostic::Diagnostics> {
    let outcome = model::check_within(syntax, budget.clone()).and_then(|(model, mut cx)| {
        let constraints = derive::constraints::analyse(&model, &mut cx)?;
        let derivation = derive::derivation(&model, &mut cx, &constraints, &ir::Interpreter)?;
        emit::model_items(&model, &mut cx, &constraints, &derivation)
    });
    within_budget(syntax, &budget, outcome)
}

/// `outcome`, or, when `budget` ran out, one diagnostic stating it: on the
/// first expression whose normal form ran out, or on the model's name when
/// the derivations after the checks ran out.
fn within_budget<T>(
    syntax: &syntax::ModelSyntax,
    budget: &sym::Budget,
    outcome: Result<T, diagnostic::Diagnostics>,
) -> Result<T, diagnostic::Diagnostics> {
    let Some(error) = budget.error() else {
        return outcome;
    };
    let message = error.to_string();
    let span = outcome
        .err()
        .and_then(|diagnostics| {
            diagnostics
                .iter()
                .find(|diagnostic| diagnostic.message == message)
                .map(|diagnostic| diagnostic.span)
        })
        .unwrap_or_else(|| syntax.name.span());
    Err(diagnostic::Diagnostic::new(span, message).into())
}
