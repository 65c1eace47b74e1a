//! The configuration-level items: `mass_matrix`, `energy`,
//! `constraint_matrix`, `constraint_residual`.

use super::{Function, coordinates, f64_type, function_body, matrix_literal, velocities};
use crate::diagnostic::Diagnostics;
use crate::model::Model;
use crate::sym::Context;
use crate::sym::Matrix;
use quote::quote;

/// The four functions, in the order they are documented.
pub(super) fn functions(model: &Model, cx: &mut Context) -> Result<Vec<Function>, Diagnostics> {
    Ok(vec![
        mass_matrix(model, cx)?,
        energy(model, cx)?,
        constraint_matrix(model, cx)?,
        constraint_residual(model, cx)?,
    ])
}

fn mass_matrix(model: &Model, cx: &mut Context) -> Result<Function, Diagnostics> {
    let n = model.n();
    let outputs = model.energy_expressions.mass_matrix.entries().to_vec();
    let body = function_body(model, cx, &[coordinates(model)], &outputs, |values| {
        matrix_literal(values, n)
    })?;
    let f64 = f64_type();
    let q = body.argument("q");
    let (statements, operations, lowered) = (body.statements, body.operations, body.lowered);
    let item = quote! {
        /// The mass matrix `g(q)`.
        pub fn mass_matrix(&self, #q: &[#f64; #n]) -> [[#f64; #n]; #n] {
            #statements
        }
    };
    Ok(Function {
        name: "mass_matrix",
        item,
        operations,
        lowered: Some(lowered),
    })
}

fn energy(model: &Model, cx: &mut Context) -> Result<Function, Diagnostics> {
    let n = model.n();
    let energies = &model.energy_expressions;
    let outputs = vec![cx.add2(energies.kinetic, energies.potential)];
    let arguments = [coordinates(model), velocities(model)];
    let body = function_body(
        model,
        cx,
        &arguments,
        &outputs,
        |values| quote!(#(#values)*),
    )?;
    let f64 = f64_type();
    let (q, qdot) = (body.argument("q"), body.argument("qdot"));
    let (statements, operations, lowered) = (body.statements, body.operations, body.lowered);
    let item = quote! {
        /// The total energy `T + V`.
        pub fn energy(&self, #q: &[#f64; #n], #qdot: &[#f64; #n]) -> #f64 {
            #statements
        }
    };
    Ok(Function {
        name: "energy",
        item,
        operations,
        lowered: Some(lowered),
    })
}

fn constraint_matrix(model: &Model, cx: &mut Context) -> Result<Function, Diagnostics> {
    let (n, c) = (model.n(), model.c());
    let outputs = model.constraint_expressions.entries().to_vec();
    let body = function_body(model, cx, &[coordinates(model)], &outputs, |values| {
        matrix_literal(values, n)
    })?;
    let f64 = f64_type();
    let q = body.argument("q");
    let (statements, operations, lowered) = (body.statements, body.operations, body.lowered);
    let item = quote! {
        /// The constraint rows `A(q)`, in declared order: allowed velocities satisfy `A(q) qdot = 0`.
        pub fn constraint_matrix(&self, #q: &[#f64; #n]) -> [[#f64; #n]; #c] {
            #statements
        }
    };
    Ok(Function {
        name: "constraint_matrix",
        item,
        operations,
        lowered: Some(lowered),
    })
}

fn constraint_residual(model: &Model, cx: &mut Context) -> Result<Function, Diagnostics> {
    let (n, c) = (model.n(), model.c());
    let a = &model.constraint_expressions;
    let velocity_column = Matrix::column(model.velocities.iter().map(|&v| cx.symbol(v)).collect());
    let outputs = a
        .mul(&velocity_column, cx)
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?
        .entries()
        .to_vec();
    let arguments = [coordinates(model), velocities(model)];
    let body = function_body(
        model,
        cx,
        &arguments,
        &outputs,
        |values| quote!([#(#values),*]),
    )?;
    let f64 = f64_type();
    let (q, qdot) = (body.argument("q"), body.argument("qdot"));
    let (statements, operations, lowered) = (body.statements, body.operations, body.lowered);
    let item = quote! {
        /// The constraint residual `A(q) qdot`: zero for allowed velocities.
        pub fn constraint_residual(&self, #q: &[#f64; #n], #qdot: &[#f64; #n]) -> [#f64; #c] {
            #statements
        }
    };
    Ok(Function {
        name: "constraint_residual",
        item,
        operations,
        lowered: Some(lowered),
    })
}
