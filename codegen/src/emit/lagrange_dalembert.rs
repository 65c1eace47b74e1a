//! The `acceleration` item: the Lagrange-d'Alembert equations solved for
//! `(qddot, lambda)` ([`crate::derive::lagrange_dalembert`]), either as
//! closed-form expressions or by assembling
//! `[[g, A^T], [A, 0]] [qddot; -lambda] = [B u - C - dV/dq; -Adot qdot]` and
//! calling `::chaplygin::runtime::linalg::solve` (so a crate using the
//! numeric form depends on `chaplygin` under that name).

use super::report::Section;
use super::{Argument, Function, coordinates, f64_type, function_body, internal, velocities};
use crate::derive::lagrange_dalembert::{LagrangeDalembert, Strategy, derive};
use crate::diagnostic::Diagnostics;
use crate::model::Model;
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

/// `acceleration(&self, q, qdot, u)`, with the derivation's chosen strategy.
pub(super) fn acceleration(model: &mut Model) -> Result<(Function, Section), Diagnostics> {
    let derivation = derive(model).map_err(|e| internal(model, e))?;
    let strategy = derivation.strategy;
    let item = acceleration_with(model, &derivation, strategy)?;
    Ok((item, report_section(&derivation)))
}

/// What the report says of the solve: the strategy and both operation counts.
fn report_section(derivation: &LagrangeDalembert) -> Section {
    let mut section = Section::new("Lagrange-d'Alembert equations (qddot, lambda)");
    let chosen = match derivation.strategy {
        Strategy::Symbolic => "closed form (exact symbolic inverses)",
        Strategy::Numeric => "numeric solve of the saddle-point system at run time",
    };
    section.line(format!("solve: {chosen}"));
    let symbolic = derivation
        .symbolic_operations
        .map_or("not derived (too large)".to_string(), |n| n.to_string());
    section.line(format!(
        "operations after CSE: closed form {symbolic}, numeric solve {}",
        derivation.numeric_operations
    ));
    section
}

/// Builds the returned `(qddot, lambda)` from the emitted outputs, given n and c.
type Assembly = fn(&[TokenStream], usize, usize) -> TokenStream;

/// `acceleration` with the given strategy.
pub(crate) fn acceleration_with(
    model: &mut Model,
    derivation: &LagrangeDalembert,
    strategy: Strategy,
) -> Result<Function, Diagnostics> {
    let (n, c, p) = (model.n(), model.c(), model.p());
    let (outputs, assemble): (_, Assembly) = match strategy {
        Strategy::Symbolic => {
            let solution = derivation
                .closed_form
                .as_ref()
                .ok_or_else(|| internal(model, "the closed form was not derived"))?;
            (solution.outputs(model), closed_form)
        }
        Strategy::Numeric => (derivation.saddle_point.outputs(model), saddle_point),
    };
    let arguments = [
        coordinates(model),
        velocities(model),
        Argument {
            name: "u",
            symbols: derivation.inputs.clone(),
        },
    ];
    let body = function_body(model, &arguments, &outputs, |values| assemble(values, n, c))?;
    let f64 = f64_type();
    let (q, qdot, u) = (
        body.argument("q"),
        body.argument("qdot"),
        body.argument("u"),
    );
    let (statements, operations, mut lowered) = (body.statements, body.operations, body.lowered);
    if strategy == Strategy::Numeric {
        lowered.assembly = super::Assembly::SaddlePoint;
    }
    let method = match strategy {
        Strategy::Symbolic => "Computed in closed form from exact symbolic inverses.",
        Strategy::Numeric => {
            "Computed by solving `[[g, A^T], [A, 0]] [qddot; -lambda] = [B u - C - dV/dq; -Adot qdot]` \
             with `chaplygin::runtime::linalg::solve` (NaN where the system is singular)."
        }
    };
    let item = quote! {
        /// The Lagrange-d'Alembert equations solved for the accelerations and the
        /// constraint forces: `(qddot, lambda)` with
        /// `g qddot + C(q, qdot) + dV/dq = A^T lambda + B u` and
        /// `A qddot + Adot qdot = 0`, `lambda` for the constraint rows as declared.
        ///
        #[doc = #method]
        pub fn acceleration(
            &self,
            #q: &[#f64; #n],
            #qdot: &[#f64; #n],
            #u: &[#f64; #p],
        ) -> ([#f64; #n], [#f64; #c]) {
            #statements
        }
    };
    Ok(Function {
        name: "acceleration",
        item,
        operations,
        lowered: Some(lowered),
    })
}

/// `(qddot, lambda)` from the closed form's n + c values.
fn closed_form(values: &[TokenStream], n: usize, _c: usize) -> TokenStream {
    let (accelerations, multipliers) = values.split_at(n);
    quote!(([#(#accelerations),*], [#(#multipliers),*]))
}

/// Assembles and solves the saddle-point system from `g` (n*n values), `A`
/// (c*n), the force (n) and the drift (c).
fn saddle_point(values: &[TokenStream], n: usize, c: usize) -> TokenStream {
    let (g, rest) = values.split_at(n * n);
    let (a, rest) = rest.split_at(c * n);
    let (force, drift) = rest.split_at(n);
    let zero = quote!(0.0);
    let g_rows = (0..n).map(|i| {
        let transposed = (0..c).map(|r| &a[r * n + i]);
        let row = &g[i * n..(i + 1) * n];
        quote!([#(#row,)* #(#transposed),*])
    });
    let a_rows = (0..c).map(|r| {
        let row = &a[r * n..(r + 1) * n];
        let zeros = std::iter::repeat_n(&zero, c);
        quote!([#(#row,)* #(#zeros),*])
    });
    let size = n + c;
    let solution = Ident::new("solution", Span::mixed_site());
    let accelerations = (0..n).map(|i| quote!(#solution[#i]));
    let multipliers = (n..size).map(|i| quote!(-#solution[#i]));
    quote! {
        let #solution = ::chaplygin::runtime::linalg::solve::<#size>(
            [#(#g_rows,)* #(#a_rows),*],
            [#(#force,)* #(#drift),*],
        );
        ([#(#accelerations),*], [#(#multipliers),*])
    }
}

#[cfg(test)]
mod tests {
    use super::acceleration_with;
    use crate::derive::lagrange_dalembert::{Strategy, derive};
    use crate::model::check;
    use crate::syntax::parse_str;

    /// Either strategy, forced, emits one valid method; only the numeric one
    /// calls the runtime's solver.
    #[test]
    fn both_strategies_emit_a_method() {
        let mut model =
            check(&parse_str(crate::fixtures::SNAKEBOARD).expect("parses")).expect("checks");
        let derivation = derive(&mut model).expect("derives");
        for strategy in [Strategy::Symbolic, Strategy::Numeric] {
            let tokens = acceleration_with(&mut model, &derivation, strategy)
                .expect("emits")
                .item;
            let method: syn::ImplItemFn = syn::parse2(tokens.clone()).expect("a method");
            assert_eq!(method.sig.ident, "acceleration");
            assert_eq!(method.sig.inputs.len(), 4);
            let calls_solver = tokens
                .to_string()
                .contains(":: chaplygin :: runtime :: linalg :: solve :: < 7usize >");
            assert_eq!(calls_solver, strategy == Strategy::Numeric, "{strategy:?}");
        }
    }
}
