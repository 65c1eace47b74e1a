//! The `acceleration` item: the Lagrange-d'Alembert equations solved for
//! `(qddot, lambda)` ([`crate::derive::lagrange_dalembert`]), either as
//! closed-form expressions or as straight-line code computing `g`, `A`,
//! `B u - C - dV/dq` and `-Adot qdot` and then solving the saddle-point
//! system by blocks on those numbers.

use super::report::Section;
use super::{Argument, Function, coordinates, f64_type, function_body, velocities};
use crate::derive::lagrange_dalembert::{LagrangeDalembert, Strategy};
use crate::diagnostic::Diagnostics;
use crate::model::Model;
use crate::sym::Context;
use crate::sym::ExprId;
use proc_macro2::TokenStream;
use quote::quote;

/// `acceleration(&self, q, qdot, u)`, with the derivation's chosen strategy.
pub(super) fn acceleration(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
) -> Result<(Function, Section), Diagnostics> {
    let item = acceleration_with(model, cx, derivation, derivation.strategy)?;
    Ok((item, report_section(derivation)))
}

/// What the report says of the solve: the strategy and both estimated costs.
fn report_section(derivation: &LagrangeDalembert) -> Section {
    let mut section = Section::new("Lagrange-d'Alembert equations (qddot, lambda)");
    let chosen = match derivation.strategy {
        Strategy::Symbolic => "closed form (exact symbolic inverses)",
        Strategy::Numeric => {
            "numeric solve of the saddle-point system at run time (by blocks: L D L^T of g \
             and of A g^-1 A^T)"
        }
    };
    section.line(format!("solve: {chosen}"));
    let (symbolic_weight, numeric_weight) = derivation.weighted_costs;
    let symbolic_weight = symbolic_weight.map_or("-".to_string(), |w| w.to_string());
    section.line(format!(
        "estimated weighted cost (a division 4, a call 20): closed form {symbolic_weight}, \
         numeric solve {numeric_weight}"
    ));
    section
}

/// `acceleration` with the given strategy.
pub(crate) fn acceleration_with(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
    strategy: Strategy,
) -> Result<Function, Diagnostics> {
    let (n, c, p) = (model.n(), model.c(), model.p());
    let outputs = solution_expressions(model, cx, derivation, strategy)?;
    let arguments = [
        coordinates(model),
        velocities(model),
        Argument {
            name: "u",
            symbols: derivation.inputs.clone(),
        },
    ];
    let body = function_body(model, cx, &arguments, &outputs, |values| {
        solution(values, n)
    })?;
    let f64 = f64_type();
    let (q, qdot, u) = (
        body.argument("q"),
        body.argument("qdot"),
        body.argument("u"),
    );
    let (statements, operations, lowered) = (body.statements, body.operations, body.lowered);
    let method = match strategy {
        Strategy::Symbolic => "Computed in closed form from exact symbolic inverses.",
        Strategy::Numeric => {
            "Computed by solving `g qddot = B u - C - dV/dq + A^T lambda`, `A qddot = -Adot qdot` \
             numerically by blocks: `g = L D L^T` and the Schur complement `A g^-1 A^T` likewise \
             (not finite where the constraint rows are dependent)."
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

/// The exact expressions of `(qddot, lambda)` that `strategy` computes.
pub(super) fn solution_expressions(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
    strategy: Strategy,
) -> Result<Vec<ExprId>, Diagnostics> {
    Ok(match strategy {
        Strategy::Symbolic => derivation
            .closed_form
            .as_ref()
            .ok_or_else(|| {
                Diagnostics::internal(model.name.span(), "the closed form was not derived")
            })?
            .outputs(cx),
        Strategy::Numeric => derivation.numeric_solution.clone(),
    })
}

/// `(qddot, lambda)` from the solution's n + c values.
fn solution(values: &[TokenStream], n: usize) -> TokenStream {
    let (accelerations, multipliers) = values.split_at(n);
    quote!(([#(#accelerations),*], [#(#multipliers),*]))
}

#[cfg(test)]
mod tests {
    use super::acceleration_with;
    use crate::derive::lagrange_dalembert::{Strategy, derive};
    use crate::model::check;
    use crate::syntax::parse_str;

    /// Either strategy, forced, emits one valid method, which calls no
    /// solver: the numeric one's solve is written out.
    #[test]
    fn both_strategies_emit_a_method() {
        let (model, mut cx) =
            check(&parse_str(crate::fixtures::SNAKEBOARD).expect("parses")).expect("checks");
        let derivation = derive(&model, &mut cx).expect("derives");
        for strategy in [Strategy::Symbolic, Strategy::Numeric] {
            let tokens = acceleration_with(&model, &mut cx, &derivation, strategy)
                .expect("emits")
                .item;
            let method: syn::ImplItemFn = syn::parse2(tokens.clone()).expect("a method");
            assert_eq!(method.sig.ident, "acceleration");
            assert_eq!(method.sig.inputs.len(), 4);
            let calls_solver = tokens
                .to_string()
                .contains(":: chaplygin :: runtime :: linalg");
            assert!(!calls_solver, "{strategy:?}");
        }
    }
}
