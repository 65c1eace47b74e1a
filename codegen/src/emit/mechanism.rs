//! The mechanism items: `FRAMES`, `POINTS`, `HOLONOMIC`,
//! `orientations(q)` (each frame's rotation matrix in ground axes),
//! `positions(q)` (each point in ground axes), `holonomic_residual(q)`
//! (`f(q)`) and `holonomic_jacobian(q)` (`df/dq`, by exact
//! differentiation). A model without mechanism sections has them empty.
//!
//! The interpreter alone (not the emitted Rust) has `drawing(q)`, what
//! drawing a mechanism's bodies and a drawing section's items needs
//! ([`DRAWING`]).

use super::{Function, coordinates, f64_type, function_body, matrix_literal};
use crate::diagnostic::Diagnostics;
use crate::model::Model;
use crate::sym::Context;
use crate::sym::ExprId;
use proc_macro2::TokenStream;
use quote::quote;

/// The name constants.
pub(super) fn constants(model: &Model) -> TokenStream {
    let mechanism = &model.mechanism;
    let frames = names_constant(
        "FRAMES",
        "The declared frames, in the order of `orientations`.",
        mechanism.frames.iter().map(|d| d.name.as_str()).collect(),
    );
    let points = names_constant(
        "POINTS",
        "The declared points, in the order of `positions`.",
        mechanism.points.iter().map(|d| d.name.as_str()).collect(),
    );
    let holonomic = names_constant(
        "HOLONOMIC",
        "The holonomic constraints `f(q) = 0`, in declared order.",
        mechanism
            .holonomic
            .iter()
            .map(|d| d.name.as_str())
            .collect(),
    );
    quote!(#frames #points #holonomic)
}

fn names_constant(name: &str, doc: &str, names: Vec<&str>) -> TokenStream {
    let count = names.len();
    let ident = proc_macro2::Ident::new(name, proc_macro2::Span::call_site());
    quote! {
        #[doc = #doc]
        pub const #ident: [&'static ::core::primitive::str; #count] = [#(#names),*];
    }
}

/// The four functions.
pub(super) fn functions(model: &Model, cx: &mut Context) -> Result<Vec<Function>, Diagnostics> {
    let jacobian = holonomic_jacobian_matrix(model, cx)?;
    Ok(vec![
        orientations(model, cx)?,
        positions(model, cx)?,
        holonomic_residual(model, cx)?,
        holonomic_jacobian(model, cx, &jacobian)?,
    ])
}

fn orientations(model: &Model, cx: &mut Context) -> Result<Function, Diagnostics> {
    let (n, frames) = (model.n(), model.mechanism.frames.len());
    let outputs = model.mechanism.expressions.orientations.entries().to_vec();
    let body = function_body(model, cx, &[coordinates(model)], &outputs, |values| {
        let matrices = values.chunks(9).map(|entries| matrix_literal(entries, 3));
        quote!([#(#matrices),*])
    })?;
    let f64 = f64_type();
    let q = body.argument("q");
    let statements = body.statements;
    let item = quote! {
        /// Each frame's rotation matrix in ground axes, in the order of
        /// `FRAMES`: its columns are the frame's unit vectors `x`, `y`, `z`.
        pub fn orientations(&self, #q: &[#f64; #n]) -> [[[#f64; 3]; 3]; #frames] {
            #statements
        }
    };
    Ok(Function {
        name: "orientations",
        item,
        operations: body.operations,
        lowered: Some(body.lowered),
    })
}

fn positions(model: &Model, cx: &mut Context) -> Result<Function, Diagnostics> {
    let (n, points) = (model.n(), model.mechanism.points.len());
    let outputs = model.mechanism.expressions.positions.entries().to_vec();
    let body = function_body(model, cx, &[coordinates(model)], &outputs, |values| {
        matrix_literal(values, 3)
    })?;
    let f64 = f64_type();
    let q = body.argument("q");
    let statements = body.statements;
    let item = quote! {
        /// Each point's position `P - origin` in ground axes, in the order of `POINTS`.
        pub fn positions(&self, #q: &[#f64; #n]) -> [[#f64; 3]; #points] {
            #statements
        }
    };
    Ok(Function {
        name: "positions",
        item,
        operations: body.operations,
        lowered: Some(body.lowered),
    })
}

fn holonomic_residual(model: &Model, cx: &mut Context) -> Result<Function, Diagnostics> {
    let (n, h) = (model.n(), model.mechanism.holonomic.len());
    let outputs = model
        .mechanism
        .expressions
        .holonomic_residual
        .entries()
        .to_vec();
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
        /// The holonomic constraints' residuals `f(q)`, in the order of `HOLONOMIC`.
        pub fn holonomic_residual(&self, #q: &[#f64; #n]) -> [#f64; #h] {
            #statements
        }
    };
    Ok(Function {
        name: "holonomic_residual",
        item,
        operations: body.operations,
        lowered: Some(body.lowered),
    })
}

/// `df/dq`, `h x n`, by exact differentiation: each entry's normal form
/// written out, or when large the derivative of the expression the residual
/// is computed by ([`crate::sym::Context::compact_expression`]).
fn holonomic_jacobian_matrix(model: &Model, cx: &mut Context) -> Result<Vec<ExprId>, Diagnostics> {
    let residual = model.mechanism.holonomic_residual.clone();
    let computed = model.mechanism.expressions.holonomic_residual.clone();
    let mut entries = Vec::new();
    for (f, &computed) in residual.entries().iter().zip(computed.entries()) {
        for coordinate in model.coordinate_symbols() {
            let partial = cx
                .derivative_of_normal(f, coordinate)
                .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
            let derived_as = cx.derivative(computed, coordinate);
            entries.push(cx.compact_expression(&partial, derived_as));
        }
    }
    Ok(entries)
}

fn holonomic_jacobian(
    model: &Model,
    cx: &mut Context,
    outputs: &[ExprId],
) -> Result<Function, Diagnostics> {
    let (n, h) = (model.n(), model.mechanism.holonomic.len());
    let body = function_body(model, cx, &[coordinates(model)], outputs, |values| {
        matrix_literal(values, n)
    })?;
    let f64 = f64_type();
    let q = body.argument("q");
    let statements = body.statements;
    let item = quote! {
        /// `df/dq`: one row per holonomic constraint, one column per coordinate.
        pub fn holonomic_jacobian(&self, #q: &[#f64; #n]) -> [[#f64; #n]; #h] {
            #statements
        }
    };
    Ok(Function {
        name: "holonomic_jacobian",
        item,
        operations: body.operations,
        lowered: Some(body.lowered),
    })
}

/// The name of the interpreted function `drawing(q)`: the gravity field
/// (3 values), then for each body its centre (3), its frame's rotation
/// matrix row-major (9), its mass (1) and its inertia row-major (9), then
/// for each `no_slip` contact its point (3), then for each item of the
/// drawing section its values in the order `Figure::values` lists them,
/// all in ground axes.
pub(crate) const DRAWING: &str = "drawing";

/// `drawing(q)` for the interpreter, `None` for emitted Rust and for a model
/// with neither bodies nor drawing items.
pub(super) fn drawing(model: &Model, cx: &Context) -> Result<Option<Function>, Diagnostics> {
    let Some(drawing) = model.mechanism.drawing.as_ref() else {
        return Ok(None);
    };
    if model.emits_rust || (drawing.bodies.is_empty() && drawing.items.is_empty()) {
        return Ok(None);
    }
    let mut outputs = drawing.gravity.to_vec();
    for body in &drawing.bodies {
        outputs.extend(body.center);
        outputs.extend(body.rotation);
        outputs.push(body.mass);
        outputs.extend(body.inertia);
    }
    for contact in &drawing.contacts {
        outputs.extend(contact.point);
    }
    for item in &drawing.items {
        outputs.extend(item.figure.values());
    }
    let body = function_body(model, cx, &[coordinates(model)], &outputs, |_| {
        TokenStream::new()
    })?;
    Ok(Some(Function {
        name: DRAWING,
        item: TokenStream::new(),
        operations: body.operations,
        lowered: Some(body.lowered),
    }))
}
