//! The `model!` procedural macro: a thin shim over [`chaplygin_codegen::expand`],
//! re-exported by the `chaplygin` crate (the guide, `docs/guide/` in the
//! repository: "The model language").

#![warn(missing_docs)]

/// Declares a mechanical model and generates its simulator items.
///
/// See the `chaplygin` crate for the language and the generated API.
#[proc_macro]
pub fn model(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    chaplygin_codegen::expand(input.into()).into()
}
