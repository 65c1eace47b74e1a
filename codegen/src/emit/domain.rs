//! `DOMAIN` and `domain`: the guards of the model's own expressions
//! ([`crate::model::domain`]) and their values at a configuration, which a
//! run reads where a step fails (`chaplygin_runtime::system::Domain`).

use super::report::Section;
use super::{Function, coordinates, f64_type, function_body};
use crate::diagnostic::Diagnostics;
use crate::model::Model;
use crate::model::domain::Guarded;
use crate::sym::Context;
use chaplygin_runtime::system::Guard;
use proc_macro2::TokenStream;
use quote::quote;

/// The `DOMAIN` constant: each guard's description and what must hold.
pub(super) fn constant(guards: &[Guarded]) -> TokenStream {
    let count = guards.len();
    let entries = guards.iter().map(|guarded| {
        let description = &guarded.description;
        let guard = match guarded.guard {
            Guard::Positive => quote!(::chaplygin::runtime::system::Guard::Positive),
            Guard::NonZero => quote!(::chaplygin::runtime::system::Guard::NonZero),
        };
        quote!((#description, #guard))
    });
    quote! {
        /// The model's own expressions that must stay defined (square
        /// roots, logarithms, divisions, tangents): each described, with
        /// what must hold; `domain` gives their values.
        pub const DOMAIN: [(&'static ::core::primitive::str, ::chaplygin::runtime::system::Guard); #count] =
            [#(#entries),*];
    }
}

/// `domain(q)`: the guarded expressions' values.
pub(super) fn function(
    model: &Model,
    cx: &mut Context,
    guards: &[Guarded],
) -> Result<Function, Diagnostics> {
    let (n, m) = (model.n(), guards.len());
    let outputs: Vec<_> = guards.iter().map(|guarded| guarded.expression).collect();
    let body = function_body(
        model,
        cx,
        &[coordinates(model)],
        &outputs,
        |values| quote!([#(#values),*]),
    )?;
    let f64 = f64_type();
    let q = body.argument("q");
    let statements = body.statements;
    let item = quote! {
        /// The values of the expressions `DOMAIN` guards, in its order.
        pub fn domain(&self, #q: &[#f64; #n]) -> [#f64; #m] {
            #statements
        }
    };
    Ok(Function {
        name: "domain",
        item,
        operations: body.operations,
        lowered: Some(body.lowered),
    })
}

/// The report's section on the guards.
pub(super) fn report(guards: &[Guarded]) -> Section {
    let mut section = Section::new("Domain (where the model's own expressions are defined)");
    if guards.is_empty() {
        section.line("no square root, logarithm, division or tangent of the coordinates");
    }
    for guarded in guards {
        section.line(guarded.description.clone());
    }
    section
}
