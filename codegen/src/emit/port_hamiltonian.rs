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
//! Where an output is a product of derived matrices, two forms are lowered:
//! the expanded normal form, and the structured sum of products of the
//! factors' entries (for the gradient and the Jacobian, the structured form
//! differentiated as an expression). The one with fewer operations is
//! emitted: expanded normal forms are often longer, and lose accuracy to
//! cancellation. The snakeboard's `reduced_rhs` is the structured form (16
//! operations against 20), the sleigh's the expanded one (19 against 29).

use super::report::Section;
use super::{Argument, Function, coordinates, f64_type, function_body, matrix_literal, velocities};
use crate::derive::constraints::DistributionBasis;
use crate::derive::port_hamiltonian::{Exact, Forms, PortHamiltonian, derive};
use crate::diagnostic::Diagnostics;
use crate::ir;
use crate::model::Model;
use crate::sym::{ExprId, ExprMatrix, Matrix, RationalFunction, SymbolId};
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

/// The ten functions, in the order they are documented, and the report's
/// section on the reduced form.
pub(super) fn functions(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<(Vec<Function>, Section), Diagnostics> {
    let reduced = derive(model, basis).map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    let forms = reduced
        .forms(model)
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    let section = report_section(model, &reduced);
    let emitters: [Emitter; 10] = [
        momenta,
        velocities_of_momenta,
        hamiltonian,
        hamiltonian_gradient,
        structure_matrix,
        input_matrix,
        reduced_rhs,
        reduced_rhs_jacobian,
        output,
        output_jacobian,
    ];
    let functions = emitters
        .iter()
        .map(|emit| emit(model, &reduced, &forms))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((functions, section))
}

/// What the report says of the reduced form (MATH.md section 3).
fn report_section(model: &mut Model, reduced: &PortHamiltonian) -> Section {
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
    match reduced.exact() {
        Some(exact) => {
            let gbar = exact.metric.to_expressions(&mut model.store);
            let k = reduced.momenta.len();
            for (i, row) in gbar.chunks(k.max(1)).enumerate() {
                let entries: Vec<String> = row
                    .iter()
                    .map(|&e| model.store.display(e).to_string())
                    .collect();
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
                "derived structured (the exact form exceeds its derivation budget): \
                 gbar_inv = X^T g X and gbar by elimination, not expanded; \
                 Jbar skew-symmetric: yes (by construction)",
            );
        }
    }
    section
}

type Emitter = fn(&mut Model, &PortHamiltonian, &Forms) -> Result<Function, Diagnostics>;

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
    signature: Signature,
    outputs: &[ExprId],
    assemble: impl Fn(&[TokenStream]) -> TokenStream,
) -> Result<Function, Diagnostics> {
    let body = function_body(model, &signature.arguments, outputs, assemble)?;
    let f64 = f64_type();
    let parameters = signature.arguments.iter().map(|argument| {
        let name = body.argument(argument.name);
        let length = argument.symbols.len();
        quote!(#name: &[#f64; #length])
    });
    let (doc, returns, statements) = (&signature.doc, &signature.returns, &body.statements);
    let name = Ident::new(signature.name, Span::call_site());
    let item = quote! {
        #[doc = #doc]
        pub fn #name(&self, #(#parameters),*) -> #returns {
            #statements
        }
    };
    Ok(Function {
        name: signature.name,
        item,
        operations: body.operations,
        lowered: Some(body.lowered),
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

// ----- expressions ------------------------------------------------------------

fn expressions_of(model: &mut Model, forms: &[RationalFunction]) -> Vec<ExprId> {
    forms
        .iter()
        .map(|form| model.store.expression_of(form))
        .collect()
}

fn symbol_expressions(model: &mut Model, symbols: &[SymbolId]) -> Vec<ExprId> {
    symbols.iter().map(|&s| model.store.symbol(s)).collect()
}

/// `matrix * column` expanded to normal forms, as expressions.
fn expanded_product(
    model: &mut Model,
    matrix: &Matrix,
    column: &[RationalFunction],
) -> Result<Vec<ExprId>, Diagnostics> {
    let column = Matrix::new(column.len(), 1, column.to_vec())
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    let atoms = model.store.atoms().clone();
    let product = matrix
        .mul(&column, &atoms)
        .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
    Ok(expressions_of(model, product.entries()))
}

fn symbol_forms(model: &mut Model, symbols: &[SymbolId]) -> Vec<RationalFunction> {
    symbols
        .iter()
        .map(|&s| {
            let atom = model.store.symbol_atom(s);
            RationalFunction::from_poly(crate::sym::Poly::atom(atom))
        })
        .collect()
}

/// The candidate with the smallest weighted cost once lowered
/// ([`ir::Program::weighted_cost`]; the first on ties).
fn cheapest(
    model: &Model,
    arguments: &[Argument],
    candidates: Vec<Vec<ExprId>>,
) -> Result<Vec<ExprId>, Diagnostics> {
    let inputs = program_inputs(model, arguments);
    let mut best: Option<(u64, Vec<ExprId>)> = None;
    for candidate in candidates {
        let program = ir::lower(&model.store, &inputs, &candidate)
            .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
        let cost = program.weighted_cost();
        if best.as_ref().is_none_or(|(lowest, _)| cost < *lowest) {
            best = Some((cost, candidate));
        }
    }
    Ok(best.map(|(_, outputs)| outputs).unwrap_or_default())
}

/// A program's input symbols: the arguments' elements, then the parameters.
fn program_inputs(model: &Model, arguments: &[Argument]) -> Vec<SymbolId> {
    let mut inputs: Vec<SymbolId> = arguments
        .iter()
        .flat_map(|a| a.symbols.iter().copied())
        .collect();
    inputs.extend(model.parameter_symbols());
    inputs
}

// ----- the items --------------------------------------------------------------

/// The candidates of an item: the form's expressions, then, for an exact
/// form, the expanded ones.
fn candidates(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
    of_forms: impl Fn(&mut Model, &Forms) -> Result<Vec<ExprId>, Diagnostics>,
    of_exact: impl Fn(&mut Model, &Exact) -> Result<Vec<ExprId>, Diagnostics>,
) -> Result<Vec<Vec<ExprId>>, Diagnostics> {
    let mut candidates = vec![of_forms(model, forms)?];
    if let Some(exact) = reduced.exact() {
        candidates.push(of_exact(model, exact)?);
    }
    Ok(candidates)
}

/// The cheapest of an item's [`candidates`].
fn chosen(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
    arguments: &[Argument],
    of_forms: impl Fn(&mut Model, &Forms) -> Result<Vec<ExprId>, Diagnostics>,
    of_exact: impl Fn(&mut Model, &Exact) -> Result<Vec<ExprId>, Diagnostics>,
) -> Result<Vec<ExprId>, Diagnostics> {
    let candidates = candidates(model, reduced, forms, of_forms, of_exact)?;
    cheapest(model, arguments, candidates)
}

/// `matrix * column` of a form, as expressions.
fn product(
    model: &mut Model,
    matrix: &ExprMatrix,
    column: Vec<ExprId>,
) -> Result<Vec<ExprId>, Diagnostics> {
    let column = ExprMatrix::column(column);
    matrix
        .mul(&column, &mut model.store)
        .map(|product| product.entries().to_vec())
        .map_err(|e| Diagnostics::internal(model.name.span(), e))
}

/// The derivatives of `functions` by every state variable, row by row.
fn state_jacobian(
    model: &mut Model,
    reduced: &PortHamiltonian,
    functions: &[ExprId],
) -> Vec<ExprId> {
    let state = reduced.state(model);
    let by_variable: Vec<Vec<ExprId>> = state
        .iter()
        .map(|&x| model.store.derivatives(functions, x))
        .collect();
    (0..functions.len())
        .flat_map(|i| by_variable.iter().map(move |column| column[i]))
        .collect()
}

fn momenta(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let (n, k) = (model.n(), reduced.momenta.len());
    let velocities_symbols = model.velocities.clone();
    let qdot = symbol_expressions(model, &velocities_symbols);
    let qdot_forms = symbol_forms(model, &velocities_symbols);
    let arguments = vec![coordinates(model), velocities(model)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |model, forms| product(model, &forms.momentum_map, qdot.clone()),
        |model, exact| expanded_product(model, &exact.momentum_map, &qdot_forms),
    )?;
    let signature = Signature {
        name: "momenta",
        doc: format!(
            "The reduced momenta `alpha = P g qdot` ({}) of a velocity `qdot` allowed by the \
             constraints, `{n}` velocities to `{k}` momenta.",
            reduced.momentum_names.join(", ")
        ),
        arguments,
        returns: vector_type(k),
    };
    item(model, signature, &outputs, vector_literal)
}

fn velocities_of_momenta(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let n = model.n();
    let alpha = symbol_expressions(model, &reduced.momenta);
    let alpha_forms = symbol_forms(model, &reduced.momenta);
    let arguments = vec![coordinates(model), momenta_argument(reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |model, forms| product(model, &forms.velocity_map, alpha.clone()),
        |model, exact| expanded_product(model, &exact.velocity_map, &alpha_forms),
    )?;
    let signature = Signature {
        name: "velocities",
        doc: "The velocities `qdot = g^-1 h^T alpha` of reduced momenta `alpha`: they satisfy \
              the constraints, and `momenta` maps them back to `alpha`."
            .to_string(),
        arguments,
        returns: vector_type(n),
    };
    item(model, signature, &outputs, vector_literal)
}

fn hamiltonian(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let arguments = vec![state_argument(model, reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |_, forms| Ok(vec![forms.hamiltonian]),
        |model, exact| {
            Ok(expressions_of(
                model,
                std::slice::from_ref(&exact.hamiltonian),
            ))
        },
    )?;
    let signature = Signature {
        name: "hamiltonian",
        doc: format!(
            "The reduced energy `Hbar = 1/2 alpha^T gbar_inv alpha + V(q)` at the state {}.",
            state_names(model, reduced)
        ),
        arguments,
        returns: f64_type(),
    };
    item(model, signature, &outputs, |values| quote!(#(#values)*))
}

fn hamiltonian_gradient(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let s = reduced.state(model).len();
    let arguments = vec![state_argument(model, reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |_, forms| Ok(forms.gradient.clone()),
        |model, exact| Ok(expressions_of(model, &exact.gradient)),
    )?;
    let signature = Signature {
        name: "hamiltonian_gradient",
        doc: format!(
            "The gradient `dHbar/dx` of the reduced energy at the state {}.",
            state_names(model, reduced)
        ),
        arguments,
        returns: vector_type(s),
    };
    item(model, signature, &outputs, vector_literal)
}

fn structure_matrix(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let s = reduced.state(model).len();
    let arguments = vec![state_argument(model, reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |_, forms| Ok(forms.structure.entries().to_vec()),
        |model, exact| Ok(expressions_of(model, exact.structure.entries())),
    )?;
    let signature = Signature {
        name: "structure_matrix",
        doc: format!(
            "The skew-symmetric structure matrix `Jbar = [[0, P^T], [-P, Gamma]]` at the state {}.",
            state_names(model, reduced)
        ),
        arguments,
        returns: matrix_type(s, s),
    };
    item(model, signature, &outputs, |values| {
        matrix_literal(values, s)
    })
}

fn input_matrix(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let (s, p) = (reduced.state(model).len(), reduced.inputs.len());
    let arguments = vec![state_argument(model, reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |_, forms| Ok(forms.input_matrix.entries().to_vec()),
        |model, exact| Ok(expressions_of(model, exact.input_matrix.entries())),
    )?;
    let signature = Signature {
        name: "input_matrix",
        doc: format!(
            "The reduced input matrix `Bbar = [0; P B]` at the state {}.",
            state_names(model, reduced)
        ),
        arguments,
        returns: matrix_type(s, p),
    };
    item(model, signature, &outputs, |values| {
        rows_literal(values, s, p)
    })
}

fn reduced_rhs(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let s = reduced.state(model).len();
    let arguments = vec![state_argument(model, reduced), inputs_argument(reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |_, forms| Ok(forms.rhs.clone()),
        |model, exact| Ok(expressions_of(model, &exact.rhs)),
    )?;
    let signature = Signature {
        name: "reduced_rhs",
        doc: format!(
            "The reduced equations of motion `xdot = Jbar dHbar/dx + Bbar u` at the state {} \
             and inputs {}; no constraints or multipliers remain.",
            state_names(model, reduced),
            input_names(model)
        ),
        arguments,
        returns: vector_type(s),
    };
    item(model, signature, &outputs, vector_literal)
}

fn reduced_rhs_jacobian(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let s = reduced.state(model).len();
    let arguments = vec![state_argument(model, reduced), inputs_argument(reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |model, forms| Ok(state_jacobian(model, reduced, &forms.rhs)),
        |model, exact| {
            let state = reduced.state(model);
            let jacobian = model
                .store
                .jacobian(&exact.rhs, &state)
                .map_err(|e| Diagnostics::internal(model.name.span(), e))?;
            Ok(expressions_of(model, jacobian.entries()))
        },
    )?;
    let signature = Signature {
        name: "reduced_rhs_jacobian",
        doc: format!(
            "The Jacobian `d xdot / dx` of `reduced_rhs` at the state {} and inputs `u`, \
             derived symbolically: row i holds the derivatives of `xdot_i`.",
            state_names(model, reduced)
        ),
        arguments,
        returns: matrix_type(s, s),
    };
    item(model, signature, &outputs, |values| {
        matrix_literal(values, s)
    })
}

fn output(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let p = reduced.inputs.len();
    let arguments = vec![state_argument(model, reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |_, forms| Ok(forms.output.clone()),
        |model, exact| Ok(expressions_of(model, &exact.output)),
    )?;
    let signature = Signature {
        name: "output",
        doc: format!(
            "The power-conjugate output `y = Bbar^T dHbar/dx` (equal to `B^T qdot`) at the state \
             {}: `dHbar/dt = y . u`.",
            state_names(model, reduced)
        ),
        arguments,
        returns: vector_type(p),
    };
    item(model, signature, &outputs, vector_literal)
}

fn output_jacobian(
    model: &mut Model,
    reduced: &PortHamiltonian,
    forms: &Forms,
) -> Result<Function, Diagnostics> {
    let (p, s) = (reduced.inputs.len(), reduced.state(model).len());
    let arguments = vec![state_argument(model, reduced)];
    let outputs = chosen(
        model,
        reduced,
        forms,
        &arguments,
        |model, forms| Ok(state_jacobian(model, reduced, &forms.output)),
        |model, exact| {
            let output = expressions_of(model, &exact.output);
            Ok(state_jacobian(model, reduced, &output))
        },
    )?;
    let signature = Signature {
        name: "output_jacobian",
        doc: format!(
            "The Jacobian `dy/dx` of `output` at the state {}, derived symbolically: row i \
             holds the derivatives of `y_i`.",
            state_names(model, reduced)
        ),
        arguments,
        returns: matrix_type(p, s),
    };
    item(model, signature, &outputs, |values| {
        rows_literal(values, p, s)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::derive::constraints::distribution_basis;
    use crate::model::check;
    use crate::syntax::parse_str;

    const SLEIGH: &str = include_str!("../../../models/sleigh.model");

    fn derived(source: &str) -> (Model, PortHamiltonian) {
        let mut model = check(&parse_str(source).expect("parses")).expect("checks");
        let basis = distribution_basis(&mut model).expect("regular at the defaults");
        let reduced = derive(&mut model, &basis).expect("derives");
        (model, reduced)
    }

    fn lowered(model: &Model, arguments: &[Argument], outputs: &[ExprId]) -> ir::Program {
        ir::lower(&model.store, &program_inputs(model, arguments), outputs).expect("lowers")
    }

    fn cost(model: &Model, arguments: &[Argument], outputs: &[ExprId]) -> u64 {
        lowered(model, arguments, outputs)
            .operation_count()
            .after_cse
    }

    fn weight(model: &Model, arguments: &[Argument], outputs: &[ExprId]) -> u64 {
        lowered(model, arguments, outputs).weighted_cost()
    }

    /// The operation counts of the candidates of `reduced_rhs` and of its
    /// Jacobian: one per form, then the expanded one.
    fn rhs_costs(model: &mut Model, reduced: &PortHamiltonian) -> [Vec<u64>; 2] {
        let arguments = vec![state_argument(model, reduced), inputs_argument(reduced)];
        let forms = reduced.forms(model).expect("forms");
        let rhs = candidates(
            model,
            reduced,
            &forms,
            |_, forms| Ok(forms.rhs.clone()),
            |model, exact| Ok(expressions_of(model, &exact.rhs)),
        )
        .expect("derives");
        let jacobians = candidates(
            model,
            reduced,
            &forms,
            |model, forms| Ok(state_jacobian(model, reduced, &forms.rhs)),
            |model, exact| {
                let state = reduced.state(model);
                let jacobian = model.store.jacobian(&exact.rhs, &state).expect("fits");
                Ok(expressions_of(model, jacobian.entries()))
            },
        )
        .expect("derives");
        [rhs, jacobians].map(|candidates| {
            candidates
                .iter()
                .map(|outputs| cost(model, &arguments, outputs))
                .collect()
        })
    }

    #[test]
    fn the_cheaper_form_of_each_product_is_emitted() {
        for (name, source) in [
            ("snakeboard", crate::fixtures::SNAKEBOARD),
            ("sleigh", SLEIGH),
        ] {
            let (mut model, reduced) = derived(source);
            let [rhs, jacobian] = rhs_costs(&mut model, &reduced);
            println!("{name}: reduced_rhs candidates {rhs:?}");
            println!("{name}: reduced_rhs_jacobian candidates {jacobian:?}");
            let expected = 2;
            assert_eq!(rhs.len(), expected);
            let arguments = vec![state_argument(&model, &reduced), inputs_argument(&reduced)];
            let forms = reduced.forms(&mut model).expect("forms");
            let candidates = candidates(
                &mut model,
                &reduced,
                &forms,
                |_, forms| Ok(forms.rhs.clone()),
                |model, exact| Ok(expressions_of(model, &exact.rhs)),
            )
            .expect("derives");
            let weights: Vec<u64> = candidates
                .iter()
                .map(|outputs| weight(&model, &arguments, outputs))
                .collect();
            let chosen = cheapest(&model, &arguments, candidates).expect("lowers");
            let lowest = weights.iter().min().copied();
            assert_eq!(Some(weight(&model, &arguments, &chosen)), lowest);
        }
    }

    #[test]
    fn every_item_has_the_interface_signature() {
        let mut model =
            check(&parse_str(crate::fixtures::SNAKEBOARD).expect("parses")).expect("checks");
        let basis = distribution_basis(&mut model).expect("regular");
        let items: Vec<String> = functions(&mut model, &basis)
            .expect("emits")
            .0
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
