//! `reduced_rhs_jacobian` in a chart whose flow's Jacobian goes through the
//! solve ([`crate::derive::port_hamiltonian::through_solve`]): the function
//! computes `qdot = velocities(q, alpha)`, calls `acceleration_jacobian`
//! (and `acceleration` when the chain rule reads `qddot`) at `(q, qdot, u)`,
//! and then the chain rule's entries, so the solve's Jacobian is written
//! once for the whole model.
//!
//! Its program for the interpreter and the JIT is those functions'
//! programs chained ([`crate::ir::Program::chained`]): the same operations
//! on the same values, so the same bits as the compiled calls.

use super::{ChartForm, Spec, chart_signature};
use crate::derive::port_hamiltonian::through_solve::ThroughSolve;
use crate::diagnostic::Diagnostics;
use crate::emit::{Argument, Function, Lowered, f64_type, function_body, matrix_literal};
use crate::ir::{Program, Source, Stage};
use crate::model::Model;
use crate::sym::Context;
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

/// The programs of `acceleration` and `acceleration_jacobian`.
#[derive(Clone, Copy)]
pub(in crate::emit) struct Solve<'a> {
    pub(in crate::emit) acceleration: &'a Lowered,
    pub(in crate::emit) jacobian: &'a Lowered,
}

/// `reduced_rhs_jacobian` of `spec` in the chart of `form`, whose
/// `velocities` has the program `velocities`.
pub(super) fn function(
    model: &Model,
    cx: &Context,
    form: &ChartForm,
    spec: &Spec,
    chain: &ThroughSolve,
    velocities: &Lowered,
    solve: Solve,
) -> Result<Function, Diagnostics> {
    let (mut signature, name, _) = chart_signature(model, form, spec);
    let (n, k) = (model.n(), form.reduced.momenta.len());
    let s = n + k;
    let arguments = [
        super::state_argument(model, form.reduced),
        argument("qddot", &chain.accelerations),
        argument("dqddot_dq", &chain.by_coordinates),
        argument("dqddot_dqdot", &chain.by_velocities),
    ];
    let body = function_body(model, cx, &arguments, &chain.jacobian, |values| {
        matrix_literal(values, s)
    })?;
    let reads_accelerations = body.reads("qddot");
    let velocities_call = match form.chart {
        0 => Ident::new("velocities", Span::call_site()),
        chart => Ident::new(&format!("velocities_chart{chart}"), Span::call_site()),
    };
    let accelerations =
        reads_accelerations.then(|| quote!(let (qddot, _) = self.acceleration(&q, &qdot, u);));
    let (by_q, by_qdot) = (body.argument("dqddot_dq"), body.argument("dqddot_dqdot"));
    let statements = body.statements;
    let f64 = f64_type();
    let prelude = quote! {
        let q: [#f64; #n] = ::core::array::from_fn(|i| x[i]);
        let alpha: [#f64; #k] = ::core::array::from_fn(|i| x[#n + i]);
        let qdot = self.#velocities_call(&q, &alpha);
        #accelerations
        let (#by_q, #by_qdot, _) = self.acceleration_jacobian(&q, &qdot, u);
        let #by_q = #by_q.as_flattened();
        let #by_qdot = #by_qdot.as_flattened();
        #statements
    };
    signature.doc = format!(
        "{} Assembled by the chain rule from `acceleration_jacobian` at \
         `qdot = {velocities_call}(q, alpha)` (MATH.md section 3).",
        signature.doc
    );
    let chained = chained(model, cx, form, velocities, solve, &body.lowered)?;
    let mut function = super::named_item(
        model,
        cx,
        signature,
        name,
        &chain.jacobian,
        |_| TokenStream::new(),
        Some((prelude, chained)),
    )?;
    function.operations = body.operations;
    Ok(function)
}

fn argument(name: &'static str, symbols: &[crate::sym::SymbolId]) -> Argument {
    Argument {
        name,
        symbols: symbols.to_vec(),
    }
}

/// The program of the whole function, with the arguments `x` and `u`:
/// `velocities`, `acceleration`, `acceleration_jacobian`, then the chain
/// rule's program `chain`.
fn chained(
    model: &Model,
    cx: &Context,
    form: &ChartForm,
    velocities: &Lowered,
    solve: Solve,
    chain: &Lowered,
) -> Result<Lowered, Diagnostics> {
    let (n, k, p) = (model.n(), form.reduced.momenta.len(), model.p());
    let s = n + k;
    let parameters = model.parameter_symbols();
    let names: Vec<String> = form
        .reduced
        .state(model)
        .iter()
        .chain(&form.reduced.inputs)
        .chain(&parameters)
        .map(|&symbol| cx.symbol_info(symbol).name.clone())
        .collect();
    let parameter = |m: usize| Source::Input(s + p + m);
    let state = |i: usize| Source::Input(i);
    let input = |i: usize| Source::Input(s + i);
    let qdot = |i: usize| Source::Output {
        stage: 0,
        output: i,
    };
    let velocity_sources = sources(velocities, &[&|i| state(i), &|c| state(n + c)], &parameter);
    let solve_sources =
        |program: &Lowered| sources(program, &[&|i| state(i), &qdot, &input], &parameter);
    let (acceleration_sources, jacobian_sources) = (
        solve_sources(solve.acceleration),
        solve_sources(solve.jacobian),
    );
    let from = |stage: usize, offset: usize| {
        move |i: usize| Source::Output {
            stage,
            output: offset + i,
        }
    };
    let chain_sources = sources(
        chain,
        &[&state, &from(1, 0), &from(2, 0), &from(2, n * n)],
        &parameter,
    );
    let program = Program::chained(
        &names,
        &[
            stage(velocities, &velocity_sources),
            stage(solve.acceleration, &acceleration_sources),
            stage(solve.jacobian, &jacobian_sources),
            stage(chain, &chain_sources),
        ],
    )
    .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    Ok(Lowered {
        program,
        arguments: vec![("x", s), ("u", p)],
    })
}

/// The source of each input slot of `lowered`: element `i` of its
/// argument `a` from `arguments[a](i)`, parameter `m` from `parameter(m)`.
fn sources(
    lowered: &Lowered,
    arguments: &[&dyn Fn(usize) -> Source],
    parameter: &dyn Fn(usize) -> Source,
) -> Vec<Source> {
    let mut sources: Vec<Source> = lowered
        .arguments
        .iter()
        .zip(arguments)
        .flat_map(|(&(_, length), source)| (0..length).map(source))
        .collect();
    let count = lowered.program.input_count();
    sources.extend((0..count.saturating_sub(sources.len())).map(parameter));
    sources.truncate(count);
    sources
}

fn stage<'a>(lowered: &'a Lowered, sources: &'a [Source]) -> Stage<'a> {
    Stage {
        program: &lowered.program,
        sources,
    }
}
