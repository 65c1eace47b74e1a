//! The Chaplygin compiler.
//!
//! A model flows one way through typed stages:
//!
//! ```text
//! tokens --syntax::parse--> ModelSyntax --model::check--> Model --derive--> analyses --emit--> Rust items
//! ```
//!
//! The symbolic engine [`sym`] holds every expression; [`ir`] lowers derived
//! expressions to straight-line code with common subexpressions shared, which
//! [`emit`] splices into allocation-free Rust. [`expand`] is what the
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

pub use build::{BuildError, Builder, generate};

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

/// A model text parsed, checked and analysed, as both doors do before emitting.
pub(crate) fn analysed_model(
    source: &str,
) -> Result<(model::Model, derive::constraints::ConstraintAnalysis), diagnostic::Diagnostics> {
    let mut model = model::check(&syntax::parse_str(source)?)?;
    let constraints = derive::constraints::analyse(&mut model)?;
    Ok((model, constraints))
}

/// A parsed model's items: checked, analysed, emitted (both doors).
fn compile(syntax: &syntax::ModelSyntax) -> Result<TokenStream, diagnostic::Diagnostics> {
    let mut model = model::check(syntax)?;
    let constraints = derive::constraints::analyse(&mut model)?;
    emit::model_items(&mut model, &constraints)
}
