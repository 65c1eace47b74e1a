//! What linearization needs of a model: the exact Jacobians of
//! `acceleration` and its symmetry, as items and as the runtime's
//! `::chaplygin::runtime::linearize::Linearization` trait.
//!
//! ```text
//! acceleration_jacobian(q, qdot, u)   (d qddot/dq, d qddot/dqdot, d qddot/du)
//! ```
//!
//! The Jacobians are the exact derivatives of the expressions `acceleration`
//! is emitted from ([`crate::derive::lagrange_dalembert::jacobian`]): the
//! closed form differentiated, or the solve by blocks differentiated
//! implicitly (the same saddle-point system, solved with the same factors,
//! for one right-hand side per variable), whichever `acceleration` computes
//! (MATH.md section 2), so they agree with `acceleration` to round-off
//! wherever it is defined. Linearizing the Lagrange-d'Alembert flow
//! `d(q, qdot)/dt = (qdot, qddot(q, qdot, u))` needs nothing else (MATH.md
//! section 6).

use super::lagrange_dalembert::solution_expressions;
use super::{Argument, Function, coordinates, f64_type, function_body, velocities};
use crate::derive::lagrange_dalembert::LagrangeDalembert;
use crate::derive::lagrange_dalembert::jacobian;
use crate::diagnostic::Diagnostics;
use crate::model::{GroupFactor, Model};
use crate::sym::Context;
use crate::sym::{ExprId, Matrix, SymbolId, SymbolKind};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// `acceleration_jacobian(&self, q, qdot, u)`, the exact Jacobians of the
/// expressions the derivation chose to emit `acceleration` from.
pub(super) fn acceleration_jacobian(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
) -> Result<Function, Diagnostics> {
    let (n, p) = (model.n(), model.p());
    let solution = solution_expressions(model, cx, derivation, derivation.strategy)?;
    let inputs = input_symbols(model, cx);
    let coordinates_argument = coordinates(model);
    let velocities_argument = velocities(model);
    let variables = [
        coordinates_argument.symbols.as_slice(),
        &velocities_argument.symbols,
        &inputs,
    ]
    .concat();
    let jacobian = jacobian::acceleration_jacobian(model, cx, derivation, &solution, &variables)
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    let outputs = by_variables(&jacobian, n, p);
    let arguments = [
        coordinates_argument,
        velocities_argument,
        Argument {
            name: "u",
            symbols: inputs,
        },
    ];
    let body = function_body(model, cx, &arguments, &outputs, |values| {
        let (by_q, rest) = values.split_at(n * n);
        let (by_qdot, by_u) = rest.split_at(n * n);
        let (by_q, by_qdot, by_u) = (
            super::matrix_literal(by_q, n),
            super::matrix_literal(by_qdot, n),
            rows_literal(by_u, n, p),
        );
        quote!((#by_q, #by_qdot, #by_u))
    })?;
    let f64 = f64_type();
    let (q, qdot, u) = (
        body.argument("q"),
        body.argument("qdot"),
        body.argument("u"),
    );
    let statements = body.statements;
    let item = quote! {
        /// The exact Jacobians of `acceleration`'s `qddot`:
        /// `(d qddot/dq, d qddot/dqdot, d qddot/du)`, row `i` holding the
        /// derivatives of `qddot_i`, derived symbolically from the expressions
        /// `acceleration` computes.
        pub fn acceleration_jacobian(
            &self,
            #q: &[#f64; #n],
            #qdot: &[#f64; #n],
            #u: &[#f64; #p],
        ) -> ::chaplygin::runtime::linearize::AccelerationJacobian<#n, #p> {
            #statements
        }
    };
    Ok(Function {
        name: "acceleration_jacobian",
        item,
        operations: body.operations,
        lowered: Some(body.lowered),
    })
}

/// The entries of `d qddot / d(q, qdot, u)` (n x (2n + p)) as its three
/// blocks, each row-major: by `q`, by `qdot`, by `u`.
fn by_variables(jacobian: &Matrix<ExprId>, n: usize, p: usize) -> Vec<ExprId> {
    let rows: Vec<usize> = (0..n).collect();
    [0..n, n..2 * n, 2 * n..2 * n + p]
        .into_iter()
        .flat_map(|block| {
            let columns: Vec<usize> = block.collect();
            jacobian.submatrix(&rows, &columns).entries().to_vec()
        })
        .collect()
}

/// An `rows x columns` array of `values` row-major, also when `columns` is 0.
fn rows_literal(values: &[TokenStream], rows: usize, columns: usize) -> TokenStream {
    let rows = (0..rows).map(|i| {
        let row = &values[i * columns..(i + 1) * columns];
        quote!([#(#row),*])
    });
    quote!([#(#rows),*])
}

/// The input symbols `u`, named as the model's inputs (the symbols
/// `acceleration` was derived with: declaring a name again returns its symbol).
fn input_symbols(model: &Model, cx: &mut Context) -> Vec<SymbolId> {
    let names: Vec<String> = model.inputs.iter().map(|i| i.name.clone()).collect();
    names
        .iter()
        .map(|name| cx.declare(name, SymbolKind::Auxiliary))
        .collect()
}

/// `impl ::chaplygin::runtime::linearize::Linearization<n, c, p>`: the
/// symmetry's factors, `mass_matrix`, `constraint_matrix` and `acceleration_jacobian`.
pub(super) fn implementation(model: &Model) -> TokenStream {
    let name = &model.name;
    let f64 = f64_type();
    let (n, c, p) = (model.n(), model.c(), model.p());
    let linearize = quote!(::chaplygin::runtime::linearize);
    let factors = model
        .symmetry
        .iter()
        .flat_map(|symmetry| &symmetry.factors)
        .map(|factor| {
            let at = |i: usize| Literal::usize_unsuffixed(i);
            match *factor {
                GroupFactor::Se2 { x, y, theta } => {
                    let (x, y, theta) = (at(x), at(y), at(theta));
                    quote!(#linearize::GroupFactor::Se2 { x: #x, y: #y, theta: #theta })
                }
                GroupFactor::Translation(i) => {
                    let i = at(i);
                    quote!(#linearize::GroupFactor::Translation(#i))
                }
                GroupFactor::Rotation(i) => {
                    let i = at(i);
                    quote!(#linearize::GroupFactor::Rotation(#i))
                }
            }
        });
    quote! {
        impl #linearize::Linearization<#n, #c, #p> for #name {
            fn symmetry(&self) -> &[#linearize::GroupFactor] {
                &[#(#factors),*]
            }
            fn mass_matrix(&self, q: &[#f64; #n]) -> [[#f64; #n]; #n] {
                #name::mass_matrix(self, q)
            }
            fn constraint_matrix(&self, q: &[#f64; #n]) -> [[#f64; #n]; #c] {
                #name::constraint_matrix(self, q)
            }
            fn acceleration_jacobian(
                &self,
                q: &[#f64; #n],
                qdot: &[#f64; #n],
                u: &[#f64; #p],
            ) -> #linearize::AccelerationJacobian<#n, #p> {
                #name::acceleration_jacobian(self, q, qdot, u)
            }
        }
    }
}
