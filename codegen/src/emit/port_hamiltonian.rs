//! The reduced port-Hamiltonian items (MATH.md section 3,
//! [`crate::derive::port_hamiltonian`]): with the state `x = (q, alpha)` of
//! size `s = n + k`,
//!
//! ```text
//! momenta(q, qdot)              alpha = P g qdot
//! velocities(q, alpha)          qdot = g^-1 h^T alpha
//! hamiltonian(x)                Hbar = 1/2 alpha^T gbar_inv alpha + V
//! hamiltonian_gradient(x)       dHbar/dx
//! structure_matrix(x)           Jbar = [[0, P^T], [-P, Gamma]]
//! input_matrix(x)               Bbar = [0; P B]
//! reduced_rhs(x, u)             xdot = Jbar dHbar/dx + Bbar u
//! reduced_rhs_jacobian(x, u)    d xdot / dx
//! output(x)                     y = Bbar^T dHbar/dx
//! output_jacobian(x)            dy/dx
//! ```
//!
//! The derivation chose each item's form ([`crate::derive::port_hamiltonian::items`]);
//! here one table gives each item its name, arguments, shape and doc, and
//! each is lowered once.

use super::report::Section;
use super::shared::{self, Member, Shared, SharedItem};
use super::{
    Argument, Function, Lowered, coordinates, f64_type, function_body, matrix_literal, velocities,
};
mod through_solve;

pub(super) use through_solve::Solve;

use crate::derive::port_hamiltonian::items::{Item, Items};
use crate::derive::port_hamiltonian::through_solve::ThroughSolve;
use crate::derive::port_hamiltonian::{PortHamiltonian, RhsJacobian};
use crate::diagnostic::Diagnostics;
use crate::model::Model;
use crate::sym::Context;
use crate::sym::ExprId;
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

/// The reduced form in one chart of D: its number (0 for the basis the
/// other items use), its dependent speeds (none for chart 0), its
/// derivation and its items.
pub(super) struct ChartForm<'a> {
    pub(super) chart: usize,
    pub(super) dependent: &'a [usize],
    pub(super) reduced: &'a PortHamiltonian,
    pub(super) items: &'a Items,
}

impl ChartForm<'_> {
    /// The chain rule through the solve, when this chart's Jacobian takes it.
    fn through_solve(&self) -> Option<&ThroughSolve> {
        match &self.reduced.expressions.rhs_jacobian {
            RhsJacobian::ThroughSolve(chain) => Some(chain),
            RhsJacobian::Differentiated(_) => None,
        }
    }
}

/// The reduced form's functions in every chart: chart 0's ten in the order
/// they are documented, each other chart's (all but `output` and
/// `output_jacobian`, named `{item}_chart{i}`), and the bodies they share
/// ([`super::shared`]).
pub(super) struct ReducedFunctions {
    pub(super) chart0: Vec<Function>,
    pub(super) charts: Vec<Vec<Function>>,
    pub(super) shared: Vec<SharedItem>,
}

/// The functions of [`ReducedFunctions`] and the report's section on the
/// reduced form; `forms[0]` is chart 0.
pub(super) fn functions(
    model: &Model,
    cx: &mut Context,
    forms: &[ChartForm],
    solve: Solve,
) -> Result<(ReducedFunctions, Section), Diagnostics> {
    let section = report_section(cx, forms[0].reduced);
    let mut chart0 = Vec::new();
    let mut charts: Vec<Vec<Function>> = forms[1..].iter().map(|_| Vec::new()).collect();
    let mut shared_items = Vec::new();
    let through_solve = forms.iter().any(|form| form.through_solve().is_some());
    for family in families(cx, forms[0].items, through_solve) {
        let specs: Vec<&Spec> = family.iter().map(|&i| &SPECS[i]).collect();
        let in_every_chart = specs
            .iter()
            .all(|spec| !matches!(spec.item, Item::Output | Item::OutputJacobian));
        let forms = match in_every_chart {
            true => forms,
            false => &forms[..1],
        };
        let body = (specs.len() > 1 || forms.len() > 1).then(|| shared_body(model, &specs, forms));
        let shared = body.as_ref().map(|body| body.emit(model, cx)).transpose()?;
        for form in forms {
            for (index, spec) in specs.iter().enumerate() {
                let called = match (&body, &shared) {
                    (Some(body), Some(shared)) => Some((
                        body.call(index, form.chart),
                        shared.programs[form.chart][index].clone(),
                    )),
                    _ => None,
                };
                let function = emit_item(model, cx, form, spec, called)?;
                match form.chart {
                    0 => chart0.push(function),
                    chart => charts[chart - 1].push(function),
                }
            }
        }
        shared_items.extend(shared);
    }
    if through_solve {
        let spec = SPECS
            .iter()
            .find(|spec| spec.item == Item::ReducedRhsJacobian)
            .expect("a row of SPECS");
        for form in forms {
            let functions = match form.chart {
                0 => &mut chart0,
                chart => &mut charts[chart - 1],
            };
            let function = match form.through_solve() {
                Some(chain) => {
                    let velocities = functions
                        .iter()
                        .find(|function| function.name == "velocities")
                        .and_then(|function| function.lowered.as_ref())
                        .expect("velocities is emitted in every chart");
                    through_solve::function(model, cx, form, spec, chain, velocities, solve)?
                }
                None => emit_item(model, cx, form, spec, None)?,
            };
            functions.push(function);
        }
    }
    let order = |function: &Function| SPECS.iter().position(|spec| spec.name == function.name);
    chart0.sort_by_key(order);
    for functions in &mut charts {
        functions.sort_by_key(order);
    }
    Ok((
        ReducedFunctions {
            chart0,
            charts,
            shared: shared_items,
        },
        section,
    ))
}

/// The items of [`SPECS`] by index, grouped into families that share a
/// body ([`shared::families`]): those of the state `x` (and inputs `u`)
/// may share, `momenta` and `velocities` take other arguments and stand
/// alone; with `through_solve`, `reduced_rhs_jacobian` is emitted apart
/// (module `through_solve`).
fn families(cx: &Context, items: &Items, through_solve: bool) -> Vec<Vec<usize>> {
    let of_state =
        |spec: &Spec| matches!(spec.arguments, Arguments::State | Arguments::StateInputs);
    let apart = |spec: &Spec| through_solve && spec.item == Item::ReducedRhsJacobian;
    let sharing: Vec<usize> = (0..SPECS.len())
        .filter(|&i| of_state(&SPECS[i]) && !apart(&SPECS[i]))
        .collect();
    let outputs: Vec<&[ExprId]> = sharing
        .iter()
        .map(|&i| items.outputs(SPECS[i].item))
        .collect();
    let mut families: Vec<Vec<usize>> = shared::families(cx, &outputs)
        .into_iter()
        .map(|family| family.into_iter().map(|i| sharing[i]).collect())
        .collect();
    families.extend(
        (0..SPECS.len())
            .filter(|&i| !of_state(&SPECS[i]))
            .map(|i| vec![i]),
    );
    families
}

/// The body the items `specs` share in the charts `forms`.
fn shared_body<'a>(model: &'a Model, specs: &[&Spec], forms: &'a [ChartForm]) -> Shared<'a> {
    let widest = specs
        .iter()
        .map(|spec| spec.arguments)
        .max_by_key(|arguments| arguments.of(model, forms[0].reduced).len())
        .unwrap_or(Arguments::State);
    let names: Vec<&str> = specs.iter().map(|spec| spec.name).collect();
    let charts = match forms.len() {
        1 => String::new(),
        _ => " in chart `chart` (0, the basis the other items use, to the last chart of \
              `CHARTS`)"
            .to_string(),
    };
    Shared {
        name: Ident::new(&format!("{}_shared", names.join("_")), Span::call_site()),
        doc: format!(
            "`{}`{charts}, computed together: the operations they share are written once.",
            names.join("`, `")
        ),
        arguments: forms
            .iter()
            .map(|form| widest.of(model, form.reduced))
            .collect(),
        members: specs
            .iter()
            .map(|spec| {
                let size = move |size: Size| size.of(model, forms[0].reduced);
                let shape = spec.shape;
                Member {
                    arguments: spec
                        .arguments
                        .of(model, forms[0].reduced)
                        .iter()
                        .map(|argument| argument.name)
                        .collect(),
                    returns: signature(model, forms[0].reduced, spec).0.returns,
                    outputs: forms
                        .iter()
                        .map(|form| form.items.outputs(spec.item))
                        .collect(),
                    assemble: Box::new(move |values: &[TokenStream]| {
                        assembled(shape, values, size)
                    }),
                }
            })
            .collect(),
    }
}

/// What the report says of the reduced form (MATH.md section 3).
fn report_section(cx: &mut Context, reduced: &PortHamiltonian) -> Section {
    let mut section = Section::new("Reduced port-Hamiltonian form (Duindam & Stramigioli)");
    let origin = if reduced.declared_basis {
        "declared"
    } else {
        "the tool's own, h = (g X)^T"
    };
    section.line(format!(
        "momentum basis: {origin}; momenta {}",
        reduced.momentum_names.join(", ")
    ));
    let yes_no = |flag: bool| if flag { "yes" } else { "no" };
    section.line(format!(
        "gbar = (h g^-1 h^T)^-1 constant: {}, diagonal: {}",
        yes_no(reduced.metric_constant),
        yes_no(reduced.metric_diagonal)
    ));
    match &reduced.exact {
        Some(exact) => {
            let gbar = exact.metric.to_expressions(cx);
            let k = reduced.momenta.len();
            for (i, row) in gbar.chunks(k.max(1)).enumerate() {
                let entries: Vec<String> = row.iter().map(|&e| cx.display(e).to_string()).collect();
                section.line(format!("  gbar row {}: [{}]", i + 1, entries.join(", ")));
            }
            section.line(format!(
                "Gamma = 0: {}; Jbar skew-symmetric: yes (decided exactly)",
                yes_no(exact.gyroscopic.is_zero())
            ));
        }
        None => {
            section.line(format!(
                "gbar facts decided {}",
                reduced.facts_method.describe()
            ));
            section.line(
                "derived structured (the exact form is too large to derive): \
                 gbar_inv = X^T g X and gbar by elimination, not expanded; \
                 Jbar skew-symmetric: yes (by construction); d xdot/dx by the chain rule \
                 through acceleration_jacobian at qdot = X alpha",
            );
        }
    }
    section
}

/// What an emitted function looks like from outside.
pub(super) struct Signature {
    pub(super) name: &'static str,
    pub(super) doc: String,
    pub(super) arguments: Vec<Argument>,
    pub(super) returns: TokenStream,
}

/// The function computing `outputs`, assembled into its return value by `assemble`.
pub(super) fn item(
    model: &Model,
    cx: &Context,
    signature: Signature,
    outputs: &[ExprId],
    assemble: impl Fn(&[TokenStream]) -> TokenStream,
) -> Result<Function, Diagnostics> {
    let name = Ident::new(signature.name, Span::call_site());
    named_item(model, cx, signature, name, outputs, assemble, None)
}

/// [`item`] emitted under the name `name`; with `called`, its body is
/// that expression (a call of a shared body) and its program the one given
/// (the shared body's, pruned to the item).
fn named_item(
    model: &Model,
    cx: &Context,
    signature: Signature,
    name: Ident,
    outputs: &[ExprId],
    assemble: impl Fn(&[TokenStream]) -> TokenStream,
    called: Option<(TokenStream, Lowered)>,
) -> Result<Function, Diagnostics> {
    let (body, statements, read) = match called {
        None => {
            let body = function_body(model, cx, &signature.arguments, outputs, assemble)?;
            let read = |argument: &Argument| body.argument(argument.name);
            let read: Vec<Ident> = signature.arguments.iter().map(read).collect();
            (body.lowered, body.statements, read)
        }
        Some((call, lowered)) => {
            let read = signature
                .arguments
                .iter()
                .map(|argument| Ident::new(argument.name, Span::call_site()))
                .collect();
            (lowered, call, read)
        }
    };
    let f64 = f64_type();
    let parameters = signature
        .arguments
        .iter()
        .zip(read)
        .map(|(argument, name)| {
            let length = argument.symbols.len();
            quote!(#name: &[#f64; #length])
        });
    let (doc, returns) = (&signature.doc, &signature.returns);
    let item = quote! {
        #[doc = #doc]
        pub fn #name(&self, #(#parameters),*) -> #returns {
            #statements
        }
    };
    Ok(Function {
        name: signature.name,
        item,
        operations: body.program.operation_count(),
        lowered: Some(body),
    })
}

// ----- arguments and shapes --------------------------------------------------

fn momenta_argument(reduced: &PortHamiltonian) -> Argument {
    Argument {
        name: "alpha",
        symbols: reduced.momenta.clone(),
    }
}

fn state_argument(model: &Model, reduced: &PortHamiltonian) -> Argument {
    Argument {
        name: "x",
        symbols: reduced.state(model),
    }
}

fn inputs_argument(reduced: &PortHamiltonian) -> Argument {
    Argument {
        name: "u",
        symbols: reduced.inputs.clone(),
    }
}

pub(super) fn vector_type(length: usize) -> TokenStream {
    let f64 = f64_type();
    quote!([#f64; #length])
}

pub(super) fn matrix_type(rows: usize, columns: usize) -> TokenStream {
    let f64 = f64_type();
    quote!([[#f64; #columns]; #rows])
}

pub(super) fn vector_literal(values: &[TokenStream]) -> TokenStream {
    quote!([#(#values),*])
}

/// A `rows x columns` array literal, also when `columns` is 0.
pub(super) fn rows_literal(values: &[TokenStream], rows: usize, columns: usize) -> TokenStream {
    if columns == 0 {
        let empty = (0..rows).map(|_| quote!([]));
        return quote!([#(#empty),*]);
    }
    matrix_literal(values, columns)
}

/// `x = (q_1, ..., q_n, alpha_1, ..., alpha_k)` by name, for the docs.
fn state_names(model: &Model, reduced: &PortHamiltonian) -> String {
    let names: Vec<&str> = model
        .coordinates
        .iter()
        .map(|c| c.declared.name.as_str())
        .chain(reduced.momentum_names.iter().map(String::as_str))
        .collect();
    format!("`x = ({})`", names.join(", "))
}

/// `u = (u_1, ..., u_p)` by name, for the docs.
fn input_names(model: &Model) -> String {
    if model.inputs.is_empty() {
        return "`u` (the model has none)".to_string();
    }
    let names: Vec<&str> = model.inputs.iter().map(|i| i.name.as_str()).collect();
    format!("`u = ({})`", names.join(", "))
}

// ----- the items --------------------------------------------------------------

/// The arguments an item reads.
#[derive(Clone, Copy)]
enum Arguments {
    /// `(q, qdot)`.
    CoordinatesVelocities,
    /// `(q, alpha)`.
    CoordinatesMomenta,
    /// `(x)`.
    State,
    /// `(x, u)`.
    StateInputs,
}

/// A size of the reduced form.
#[derive(Clone, Copy)]
enum Size {
    N,
    K,
    S,
    P,
}

/// What an item returns.
#[derive(Clone, Copy)]
enum Shape {
    Scalar,
    Vector(Size),
    Matrix(Size, Size),
}

/// One row of the table: an item's name, arguments, shape and doc.
struct Spec {
    item: Item,
    name: &'static str,
    arguments: Arguments,
    shape: Shape,
    doc: fn(&Model, &PortHamiltonian) -> String,
}

const SPECS: [Spec; 10] = [
    Spec {
        item: Item::Momenta,
        name: "momenta",
        arguments: Arguments::CoordinatesVelocities,
        shape: Shape::Vector(Size::K),
        doc: |model, reduced| {
            format!(
                "The reduced momenta `alpha = P g qdot` ({}) of a velocity `qdot` allowed by the \
                 constraints, `{}` velocities to `{}` momenta.",
                reduced.momentum_names.join(", "),
                model.n(),
                reduced.momenta.len()
            )
        },
    },
    Spec {
        item: Item::Velocities,
        name: "velocities",
        arguments: Arguments::CoordinatesMomenta,
        shape: Shape::Vector(Size::N),
        doc: |_, _| {
            "The velocities `qdot = g^-1 h^T alpha` of reduced momenta `alpha`: they satisfy \
             the constraints, and `momenta` maps them back to `alpha`."
                .to_string()
        },
    },
    Spec {
        item: Item::Hamiltonian,
        name: "hamiltonian",
        arguments: Arguments::State,
        shape: Shape::Scalar,
        doc: |model, reduced| {
            format!(
                "The reduced energy `Hbar = 1/2 alpha^T gbar_inv alpha + V(q)` at the state {}.",
                state_names(model, reduced)
            )
        },
    },
    Spec {
        item: Item::HamiltonianGradient,
        name: "hamiltonian_gradient",
        arguments: Arguments::State,
        shape: Shape::Vector(Size::S),
        doc: |model, reduced| {
            format!(
                "The gradient `dHbar/dx` of the reduced energy at the state {}.",
                state_names(model, reduced)
            )
        },
    },
    Spec {
        item: Item::StructureMatrix,
        name: "structure_matrix",
        arguments: Arguments::State,
        shape: Shape::Matrix(Size::S, Size::S),
        doc: |model, reduced| {
            format!(
                "The skew-symmetric structure matrix `Jbar = [[0, P^T], [-P, Gamma]]` at the \
                 state {}.",
                state_names(model, reduced)
            )
        },
    },
    Spec {
        item: Item::InputMatrix,
        name: "input_matrix",
        arguments: Arguments::State,
        shape: Shape::Matrix(Size::S, Size::P),
        doc: |model, reduced| {
            format!(
                "The reduced input matrix `Bbar = [0; P B]` at the state {}.",
                state_names(model, reduced)
            )
        },
    },
    Spec {
        item: Item::ReducedRhs,
        name: "reduced_rhs",
        arguments: Arguments::StateInputs,
        shape: Shape::Vector(Size::S),
        doc: |model, reduced| {
            format!(
                "The reduced equations of motion `xdot = Jbar dHbar/dx + Bbar u` at the state {} \
                 and inputs {}; no constraints or multipliers remain.",
                state_names(model, reduced),
                input_names(model)
            )
        },
    },
    Spec {
        item: Item::ReducedRhsJacobian,
        name: "reduced_rhs_jacobian",
        arguments: Arguments::StateInputs,
        shape: Shape::Matrix(Size::S, Size::S),
        doc: |model, reduced| {
            format!(
                "The Jacobian `d xdot / dx` of `reduced_rhs` at the state {} and inputs `u`, \
                 derived symbolically: row i holds the derivatives of `xdot_i`.",
                state_names(model, reduced)
            )
        },
    },
    Spec {
        item: Item::Output,
        name: "output",
        arguments: Arguments::State,
        shape: Shape::Vector(Size::P),
        doc: |model, reduced| {
            format!(
                "The power-conjugate output `y = Bbar^T dHbar/dx` (equal to `B^T qdot`) at the \
                 state {}: `dHbar/dt = y . u`.",
                state_names(model, reduced)
            )
        },
    },
    Spec {
        item: Item::OutputJacobian,
        name: "output_jacobian",
        arguments: Arguments::State,
        shape: Shape::Matrix(Size::P, Size::S),
        doc: |model, reduced| {
            format!(
                "The Jacobian `dy/dx` of `output` at the state {}, derived symbolically: row i \
                 holds the derivatives of `y_i`.",
                state_names(model, reduced)
            )
        },
    },
];

impl Size {
    fn of(self, model: &Model, reduced: &PortHamiltonian) -> usize {
        match self {
            Size::N => model.n(),
            Size::K => reduced.momenta.len(),
            Size::S => model.n() + reduced.momenta.len(),
            Size::P => reduced.inputs.len(),
        }
    }
}

impl Arguments {
    fn of(self, model: &Model, reduced: &PortHamiltonian) -> Vec<Argument> {
        match self {
            Arguments::CoordinatesVelocities => vec![coordinates(model), velocities(model)],
            Arguments::CoordinatesMomenta => vec![coordinates(model), momenta_argument(reduced)],
            Arguments::State => vec![state_argument(model, reduced)],
            Arguments::StateInputs => {
                vec![state_argument(model, reduced), inputs_argument(reduced)]
            }
        }
    }
}

/// The item of one row of [`SPECS`] in the chart of `form`, named
/// `{item}_chart{i}` beyond chart 0; with `called`, its body calls a
/// shared body, whose program pruned to the item it runs.
fn emit_item(
    model: &Model,
    cx: &Context,
    form: &ChartForm,
    spec: &Spec,
    called: Option<(TokenStream, Lowered)>,
) -> Result<Function, Diagnostics> {
    let (signature, name, shape) = chart_signature(model, form, spec);
    let size = |size: Size| size.of(model, form.reduced);
    let outputs = form.items.outputs(spec.item);
    named_item(
        model,
        cx,
        signature,
        name,
        outputs,
        |values| assembled(shape, values, size),
        called,
    )
}

/// The signature, name and shape of one row of [`SPECS`] in the chart of
/// `form`: named `{item}_chart{i}` beyond chart 0, its doc naming the
/// chart's dependent speeds.
fn chart_signature(model: &Model, form: &ChartForm, spec: &Spec) -> (Signature, Ident, Shape) {
    let (mut signature, shape) = signature(model, form.reduced, spec);
    let mut name = Ident::new(spec.name, Span::call_site());
    if form.chart > 0 {
        let speeds: Vec<String> = form
            .dependent
            .iter()
            .map(|&j| format!("dot({})", model.coordinates[j].declared.name))
            .collect();
        signature.doc = format!(
            "In chart {} (dependent speeds {}): {}",
            form.chart,
            speeds.join(", "),
            signature.doc
        );
        name = Ident::new(
            &format!("{}_chart{}", spec.name, form.chart),
            Span::call_site(),
        );
    }
    (signature, name, shape)
}

/// The signature of one row of [`SPECS`], and its shape.
fn signature(model: &Model, reduced: &PortHamiltonian, spec: &Spec) -> (Signature, Shape) {
    let size = |size: Size| size.of(model, reduced);
    let returns = match spec.shape {
        Shape::Scalar => f64_type(),
        Shape::Vector(length) => vector_type(size(length)),
        Shape::Matrix(rows, columns) => matrix_type(size(rows), size(columns)),
    };
    let signature = Signature {
        name: spec.name,
        doc: (spec.doc)(model, reduced),
        arguments: spec.arguments.of(model, reduced),
        returns,
    };
    (signature, spec.shape)
}

/// The return value of an item of `shape` from its values.
fn assembled(shape: Shape, values: &[TokenStream], size: impl Fn(Size) -> usize) -> TokenStream {
    match shape {
        Shape::Scalar => quote!(#(#values)*),
        Shape::Vector(_) => vector_literal(values),
        Shape::Matrix(rows, columns) => rows_literal(values, size(rows), size(columns)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::derive::constraints::distribution_basis;
    use crate::derive::lagrange_dalembert;
    use crate::derive::port_hamiltonian::{derive, items::items};
    use crate::model::check;
    use crate::syntax::parse_str;

    #[test]
    fn every_item_has_the_interface_signature() {
        let (model, mut cx) =
            check(&parse_str(crate::fixtures::SNAKEBOARD).expect("parses")).expect("checks");
        let basis = distribution_basis(&model, &mut cx).expect("regular");
        let reduced = derive(&model, &mut cx, &basis).expect("derives");
        let chosen = items(&model, &mut cx, &reduced).expect("derives");
        let form = ChartForm {
            chart: 0,
            dependent: &[],
            reduced: &reduced,
            items: &chosen,
        };
        let derivation = lagrange_dalembert::derive(&model, &mut cx).expect("derives");
        let programs = [
            super::super::lagrange_dalembert::acceleration(&model, &mut cx, &derivation)
                .expect("emits")
                .0,
            super::super::linearization::acceleration_jacobian(&model, &mut cx, &derivation)
                .expect("emits"),
        ]
        .map(|function| function.lowered.expect("a program"));
        let solve = Solve {
            acceleration: &programs[0],
            jacobian: &programs[1],
        };
        let items: Vec<String> = functions(&model, &mut cx, &[form], solve)
            .expect("emits")
            .0
            .chart0
            .iter()
            .map(|function| function.item.to_string().replace(' ', ""))
            .collect();
        let f64 = "::core::primitive::f64";
        let expected = [
            format!("pubfnmomenta(&self,q:&[{f64};5usize],qdot:&[{f64};5usize])->[{f64};3usize]"),
            format!(
                "pubfnvelocities(&self,q:&[{f64};5usize],alpha:&[{f64};3usize])->[{f64};5usize]"
            ),
            format!("pubfnhamiltonian(&self,x:&[{f64};8usize])->{f64}"),
            format!("pubfnhamiltonian_gradient(&self,x:&[{f64};8usize])->[{f64};8usize]"),
            format!("pubfnstructure_matrix(&self,x:&[{f64};8usize])->[[{f64};8usize];8usize]"),
            format!("pubfninput_matrix(&self,x:&[{f64};8usize])->[[{f64};2usize];8usize]"),
            format!("pubfnreduced_rhs(&self,x:&[{f64};8usize],u:&[{f64};2usize])->[{f64};8usize]"),
            format!(
                "pubfnreduced_rhs_jacobian(&self,x:&[{f64};8usize],u:&[{f64};2usize])->[[{f64};8usize];8usize]"
            ),
            format!("pubfnoutput(&self,x:&[{f64};8usize])->[{f64};2usize]"),
            format!("pubfnoutput_jacobian(&self,x:&[{f64};8usize])->[[{f64};8usize];2usize]"),
        ];
        assert_eq!(items.len(), expected.len());
        for (item, signature) in items.iter().zip(&expected) {
            assert!(
                item.contains(signature.as_str()),
                "{signature} not in {item}"
            );
        }
    }
}
