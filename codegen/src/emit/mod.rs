//! Emission of a checked model as Rust items.
//!
//! For a model with n coordinates, c constraints and p inputs this emits the
//! parameter struct (`Copy`, `Debug`, `PartialEq`, `Default` from the
//! declared defaults), the name and size constants, and
//!
//! ```text
//! mass_matrix(q)                  g(q)
//! energy(q, qdot)                 T + V = 1/2 qdot^T g qdot + V(q)
//! constraint_matrix(q)            A(q)
//! constraint_residual(q, qdot)    A(q) qdot
//! acceleration(q, qdot, u)        (qddot, lambda), Lagrange-d'Alembert
//! acceleration_jacobian(q, qdot, u)  its exact Jacobians (see `linearization`)
//! REPORT                          the derivation report (see [`report`])
//! ```
//!
//! the mechanism items of `mechanism` (`FRAMES`, `POINTS`, `HOLONOMIC`,
//! `orientations`, `positions`, `holonomic_residual`, `holonomic_jacobian`)
//!
//! and the reduced port-Hamiltonian items of `port_hamiltonian` (MATH.md
//! section 3), for a model with a symmetry the momentum-equation items of
//! `momentum` (MATH.md section 4), and the impls of the runtime's
//! formulation traits (`traits`) through which the runtime's integrators run
//! the model.
//!
//! Each function body is one [`crate::ir::Program`]: straight-line `let`s over
//! `f64` with common subexpressions shared, no allocation, no panics, types
//! named by absolute paths (`::core::primitive::f64`), so the items compile
//! under `#![deny(warnings)]` whatever the caller has in scope.

mod domain;
mod kinematics;
mod lagrange_dalembert;
mod linearization;
mod mechanism;
mod momentum;
mod port_hamiltonian;
pub mod report;
mod shared;
mod traits;

pub(crate) use mechanism::DRAWING;

use crate::derive::Derivation;
use crate::derive::constraints::{ChartFit, ConstraintAnalysis};
use crate::diagnostic::Diagnostics;
use crate::ir::{self, OperationCount};
use crate::model::Model;
use crate::sym::Context;
use crate::sym::{ExprId, SymbolId};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

/// One argument array of an emitted function (`q`, `qdot`, `x`, `u`): its
/// elements are these symbols, in order.
#[derive(Clone)]
pub(crate) struct Argument {
    pub(crate) name: &'static str,
    pub(crate) symbols: Vec<SymbolId>,
}

/// One emitted function: its name, its item, its operation counts, and the
/// program its body was emitted from (none for a body that calls other
/// items).
pub(crate) struct Function {
    pub(crate) name: &'static str,
    pub(crate) item: TokenStream,
    pub(crate) operations: OperationCount,
    pub(crate) lowered: Option<Lowered>,
}

/// The program of a function body and its layout: input slots are the
/// elements of each argument array in order, then the parameters in
/// declared order.
#[derive(Clone)]
pub(crate) struct Lowered {
    pub(crate) program: ir::Program,
    pub(crate) arguments: Vec<(&'static str, usize)>,
}

/// A model's items, its emitted functions and its report text.
pub(crate) struct EmittedModel {
    pub(crate) items: TokenStream,
    pub(crate) functions: Vec<Function>,
    /// The reduced items of each other chart of D (chart 1, 2, ...).
    pub(crate) chart_functions: Vec<Vec<Function>>,
    /// The guards of the model's own expressions ([`crate::model::domain`]).
    pub(crate) guards: Vec<crate::model::domain::Guarded>,
    /// The momentum basis's divisors that depend on the parameters alone,
    /// described (`BASIS_DIVISORS`).
    pub(crate) basis_divisors: Vec<String>,
    /// How every chart derived at build time fits, chart 0 (the model's
    /// own basis) first; only chart 0 without other charts.
    pub(crate) charts: Vec<ChartFit>,
    pub(crate) report: String,
}

/// The Rust items of a checked, analysed and derived model.
pub fn model_items(
    model: &Model,
    cx: &mut Context,
    constraints: &ConstraintAnalysis,
    derivation: &Derivation,
) -> Result<TokenStream, Diagnostics> {
    emit(model, cx, constraints, derivation).map(|emitted| emitted.items)
}

/// [`model_items`], keeping the functions and the report.
pub(crate) fn emit(
    model: &Model,
    cx: &mut Context,
    constraints: &ConstraintAnalysis,
    derivation: &Derivation,
) -> Result<EmittedModel, Diagnostics> {
    let definition = parameter_struct(model);
    let constants = constants(model);
    let mechanism_constants = mechanism::constants(model);
    let mut guards = crate::model::domain::guards(model, cx)
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    let coordinate_sets = constraints.coordinate_sets.iter();
    guards.extend(coordinate_sets.map(|set| set.guarded(model, cx)));
    let mut functions = kinematics::functions(model, cx)?;
    functions.extend(mechanism::functions(model, cx)?);
    functions.push(domain::function(model, cx, &guards)?);
    let (acceleration, solve_report) =
        lagrange_dalembert::acceleration(model, cx, &derivation.lagrange_dalembert)?;
    let acceleration_jacobian =
        linearization::acceleration_jacobian(model, cx, &derivation.lagrange_dalembert)?;
    let solve_programs = [&acceleration, &acceleration_jacobian]
        .map(|function| function.lowered.clone().expect("the solve has a program"));
    functions.extend([acceleration, acceleration_jacobian]);
    let forms: Vec<port_hamiltonian::ChartForm> = std::iter::once(port_hamiltonian::ChartForm {
        chart: 0,
        dependent: &[],
        reduced: &derivation.reduced,
        items: &derivation.reduced_items,
    })
    .chain(
        derivation
            .charts
            .iter()
            .enumerate()
            .map(|(i, chart)| port_hamiltonian::ChartForm {
                chart: i + 1,
                dependent: &chart.dependent,
                reduced: &chart.reduced,
                items: &chart.items,
            }),
    )
    .collect();
    let solve = port_hamiltonian::Solve {
        acceleration: &solve_programs[0],
        jacobian: &solve_programs[1],
    };
    let (reduced, mut reduced_report) = port_hamiltonian::functions(model, cx, &forms, solve)?;
    functions.extend(reduced.chart0);
    let chart_functions = reduced.charts;
    let primary = match derivation.reduced.declared_basis {
        true => ChartFit::Declared,
        false => constraints.basis.fit(derivation.reduced.elimination()),
    };
    let charts: Vec<ChartFit> = std::iter::once(primary)
        .chain(derivation.charts.iter().map(|chart| chart.fit.clone()))
        .collect();
    if let Some(line) = charts_line(model, &charts) {
        reduced_report.line(line);
    }
    let mut sections = vec![domain::report(&guards), solve_report, reduced_report];
    let mut basis_divisors = Vec::new();
    let mut divisors_constant = TokenStream::new();
    if let Some(momentum) = &derivation.momentum {
        basis_divisors = momentum::divisors(model, cx, momentum)
            .into_iter()
            .map(|(description, _)| description)
            .collect();
        divisors_constant = momentum::divisors_constant(model, cx, momentum);
        let (reduction, reduction_report) = momentum::functions(model, cx, momentum, &functions)?;
        functions.extend(reduction);
        sections.push(reduction_report);
    } else if model.symmetry.is_some() {
        sections.push(momentum::omitted());
    }
    let report = report_text(
        model,
        cx,
        constraints,
        sections,
        &functions,
        &reduced.shared,
    );
    let report_item = report_constant(&report);
    let items = reduced.shared.iter().map(|shared| &shared.item).chain(
        functions
            .iter()
            .chain(chart_functions.iter().flatten())
            .map(|f| &f.item),
    );
    let name = &model.name;
    let chart_constant = traits::charts_constant(model, &charts);
    let domain_constant = domain::constant(&guards);
    let implementations = traits::implementations(model, &charts, derivation.momentum.is_some());
    let linearization = linearization::implementation(model);
    let items = quote! {
        #definition
        #[allow(
            clippy::possible_missing_comma,
            reason = "a `model!` expansion's tokens all carry the macro's span, whose \
                      lines clippy's layout check misreads in the returned arrays"
        )]
        impl #name {
            #constants
            #mechanism_constants
            #report_item
            #chart_constant
            #domain_constant
            #divisors_constant
            #(#items)*
        }
        #implementations
        #linearization
    };
    functions.extend(mechanism::drawing(model, cx)?);
    Ok(EmittedModel {
        items,
        guards,
        basis_divisors,
        functions,
        chart_functions,
        charts,
        report,
    })
}

/// The report's line on the charts of D, the dependent speeds of each;
/// none with one chart.
fn charts_line(model: &Model, charts: &[ChartFit]) -> Option<String> {
    if charts.len() == 1 {
        return None;
    }
    let listed: Vec<String> = charts
        .iter()
        .enumerate()
        .map(|(i, fit)| format!("{i}: {}", fit.describe(model)))
        .collect();
    Some(format!(
        "charts (dependent speeds; the runtime switches where the active one degenerates): {}",
        listed.join("; ")
    ))
}

fn report_text(
    model: &Model,
    cx: &mut Context,
    constraints: &ConstraintAnalysis,
    derivations: Vec<report::Section>,
    functions: &[Function],
    shared: &[shared::SharedItem],
) -> String {
    let mut report = report::Report::new(model.name.to_string());
    report.push(report::constraints(model, cx, constraints));
    for section in derivations {
        report.push(section);
    }
    report.push(report::operations(functions, shared));
    report.render()
}

fn report_constant(text: &str) -> TokenStream {
    quote! {
        /// The derivation report: sizes, the basis of D, integrability,
        /// growth vector, classification, the reduced port-Hamiltonian
        /// form's metric and structure, the momentum equation's
        /// coefficients (with a symmetry), operation counts.
        pub const REPORT: &'static ::core::primitive::str = #text;
    }
}

pub(crate) fn f64_type() -> TokenStream {
    quote!(::core::primitive::f64)
}

/// The model's struct, one field per parameter under the name declared
/// (`rR`, `IBxx` in the benchmark bicycle's notation: no snake-case lint).
fn parameter_struct(model: &Model) -> TokenStream {
    let name = &model.name;
    let visibility = &model.visibility;
    let docs = model.docs.iter().map(|line| quote!(#[doc = #line]));
    let f64 = f64_type();
    let fields: Vec<Ident> = model
        .parameters
        .iter()
        .map(|p| Ident::new(&p.variable.declared.name, p.variable.declared.span))
        .collect();
    let field_docs = model.parameters.iter().map(|p| {
        format!(
            "Parameter `{}` (default {}).",
            p.variable.declared.name,
            p.default.to_f64()
        )
    });
    let defaults = model
        .parameters
        .iter()
        .map(|p| Literal::f64_unsuffixed(p.default.to_f64()));
    quote! {
        #(#docs)*
        #[derive(::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq)]
        #[allow(non_snake_case)]
        #visibility struct #name {
            #(#[doc = #field_docs] pub #fields: #f64,)*
        }

        impl ::core::default::Default for #name {
            fn default() -> Self {
                Self { #(#fields: #defaults,)* }
            }
        }
    }
}

fn constants(model: &Model) -> TokenStream {
    let names = |list: Vec<&str>| {
        let count = list.len();
        (
            quote!([&'static ::core::primitive::str; #count]),
            quote!([#(#list),*]),
        )
    };
    let (coordinates_type, coordinates) = names(
        model
            .coordinates
            .iter()
            .map(|c| c.declared.name.as_str())
            .collect(),
    );
    let (parameters_type, parameters) = names(
        model
            .parameters
            .iter()
            .map(|p| p.variable.declared.name.as_str())
            .collect(),
    );
    let (inputs_type, inputs) = names(model.inputs.iter().map(|i| i.name.as_str()).collect());
    let (constraints_type, constraints) =
        names(model.constraints.iter().map(|c| c.name.as_str()).collect());
    let momentum_names = crate::derive::port_hamiltonian::momentum_names(model);
    let (momenta_type, momenta) = names(momentum_names.iter().map(String::as_str).collect());
    let (n, c, k, p) = (model.n(), model.c(), model.k(), model.p());
    let s = n + k;
    quote! {
        /// The coordinates, in order.
        pub const COORDINATES: #coordinates_type = #coordinates;
        /// The parameters, in order.
        pub const PARAMETERS: #parameters_type = #parameters;
        /// The inputs, in order.
        pub const INPUTS: #inputs_type = #inputs;
        /// The constraints, in declared order.
        pub const CONSTRAINTS: #constraints_type = #constraints;
        /// The momenta `alpha` of the reduced state `x = (q, alpha)`: the
        /// declared momentum basis's row names, else `alpha1, ..., alphak`.
        pub const MOMENTA: #momenta_type = #momenta;
        /// Number of coordinates `n`.
        pub const N: ::core::primitive::usize = #n;
        /// Number of constraints `c`.
        pub const C: ::core::primitive::usize = #c;
        /// Degrees of freedom in velocity, `k = n - c`.
        pub const K: ::core::primitive::usize = #k;
        /// Number of inputs `p`.
        pub const P: ::core::primitive::usize = #p;
        /// Size of the reduced state `(q, alpha)`, `s = n + k`.
        pub const S: ::core::primitive::usize = #s;
    }
}

pub(crate) fn coordinates(model: &Model) -> Argument {
    Argument {
        name: "q",
        symbols: model.coordinate_symbols(),
    }
}

pub(crate) fn velocities(model: &Model) -> Argument {
    Argument {
        name: "qdot",
        symbols: model.velocities.clone(),
    }
}

pub(crate) fn matrix_literal(values: &[TokenStream], columns: usize) -> TokenStream {
    let rows = values.chunks(columns.max(1)).map(|row| quote!([#(#row),*]));
    quote!([#(#rows),*])
}

/// A function body, which argument arrays it reads, what it costs, and
/// its program.
pub(crate) struct Body {
    pub(crate) statements: TokenStream,
    pub(crate) operations: OperationCount,
    pub(crate) lowered: Lowered,
    used: Vec<&'static str>,
}

impl Body {
    /// The name to give argument `name` in the signature: itself, or with a
    /// leading underscore when the body does not read it (no unused warnings).
    pub(crate) fn argument(&self, name: &'static str) -> Ident {
        let spelled = if self.reads(name) {
            name.to_string()
        } else {
            format!("_{name}")
        };
        Ident::new(&spelled, Span::call_site())
    }

    /// Whether the body reads argument `name`.
    pub(crate) fn reads(&self, name: &'static str) -> bool {
        self.used.contains(&name)
    }
}

/// The input slots of a function: the elements of each argument array in
/// order, then the parameters; the expression each is read from (`q[2]`,
/// `self.m`), and the argument owning it.
fn slots(
    model: &Model,
    arguments: &[Argument],
) -> (Vec<SymbolId>, Vec<TokenStream>, Vec<Option<&'static str>>) {
    let mut symbols = Vec::new();
    let mut sources = Vec::new();
    let mut owners = Vec::new();
    for argument in arguments {
        let array = Ident::new(argument.name, Span::call_site());
        for (i, &symbol) in argument.symbols.iter().enumerate() {
            let i = Literal::usize_unsuffixed(i);
            symbols.push(symbol);
            sources.push(quote!(#array[#i]));
            owners.push(Some(argument.name));
        }
    }
    for parameter in &model.parameters {
        let field = format_ident!("{}", parameter.variable.declared.name);
        symbols.push(parameter.variable.symbol);
        sources.push(quote!(self.#field));
        owners.push(None);
    }
    (symbols, sources, owners)
}

/// The program computing `outputs` from the arguments and the parameters,
/// with its layout.
pub(crate) fn lowered(
    model: &Model,
    cx: &Context,
    arguments: &[Argument],
    outputs: &[ExprId],
) -> Result<Lowered, Diagnostics> {
    let (symbols, _, _) = slots(model, arguments);
    let program = ir::lower(cx, &symbols, outputs)
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    Ok(Lowered {
        program,
        arguments: arguments
            .iter()
            .map(|argument| (argument.name, argument.symbols.len()))
            .collect(),
    })
}

/// Lowers `outputs` with the arguments and the parameters (`self.name`) as
/// inputs, and assembles the returned value with `result`.
pub(crate) fn function_body(
    model: &Model,
    cx: &Context,
    arguments: &[Argument],
    outputs: &[ExprId],
    result: impl Fn(&[TokenStream]) -> TokenStream,
) -> Result<Body, Diagnostics> {
    let (_, sources, owners) = slots(model, arguments);
    let lowered = lowered(model, cx, arguments, outputs)?;
    let program = &lowered.program;
    let emitted = match model.emits_rust {
        true => program
            .emit(&sources)
            .map_err(|e| Diagnostics::internal(model.name.span(), e))?,
        false => ir::RustProgram {
            statements: TokenStream::new(),
            outputs: vec![TokenStream::new(); outputs.len()],
        },
    };
    let statements = emitted.statements;
    let value = result(&emitted.outputs);
    Ok(Body {
        statements: quote!(#statements #value),
        operations: program.operation_count(),
        used: read_arguments(program, &owners),
        lowered,
    })
}

/// The arguments whose elements `program` reads, given the owner of each
/// input slot.
pub(crate) fn read_arguments(
    program: &ir::Program,
    owners: &[Option<&'static str>],
) -> Vec<&'static str> {
    let mut used: Vec<&'static str> = program
        .instructions()
        .iter()
        .filter_map(|i| match i.op {
            ir::Op::Input(slot) => owners[slot],
            _ => None,
        })
        .collect();
    used.sort_unstable();
    used.dedup();
    used
}
