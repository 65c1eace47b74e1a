//! Bodies shared by items: one private function computes the values of
//! several items, in every chart of D the model has, and each public item
//! calls it and keeps its own part.
//!
//! The reduced form in chart `i` differs from chart 0 only through the
//! basis of D, so most of its operations (the metric, its derivatives, the
//! constraint rows) are the same: lowered together, the operations every
//! chart needs are written once and a `match` on the chart computes the rest
//! ([`crate::ir::Program::emit_variants`]); no chart computes a value it
//! does not read. Items of one chart that share most of their operations
//! (the benchmark bicycle's gradient, structure matrix and right-hand side)
//! are computed together when that costs each of them little more than
//! itself ([`families`]).
//!
//! ```text
//! fn reduced_rhs_shared(&self, chart: usize, x: &[f64; s], u: &[f64; p]) -> ([f64; s], [[f64; s]; s], [f64; s]) {
//!     let t0 = ...;                       // what every chart reads
//!     match chart {
//!         0 => { ...; ([..], [[..]], [..]) }
//!         _ => { ...; ([..], [[..]], [..]) }
//!     }
//! }
//! pub fn structure_matrix(&self, x: &[f64; s]) -> [[f64; s]; s] {
//!     self.reduced_rhs_shared(0, x, &[0.0; p]).1
//! }
//! ```

use super::{Argument, Lowered, f64_type};
use crate::diagnostic::Diagnostics;
use crate::ir::{self, OperationCount};
use crate::model::Model;
use crate::sym::{Context, ExprId};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{ToTokens, format_ident, quote};

/// The most a member may cost more, computed with its family, than alone:
/// 15 % of its own estimated weight.
pub(crate) const SHARING_SLACK: f64 = 0.15;

/// How a member's return value is made from its outputs' expressions.
pub(crate) type Assemble<'a> = Box<dyn Fn(&[TokenStream]) -> TokenStream + 'a>;

/// One item computed by a shared body.
pub(crate) struct Member<'a> {
    /// The arguments it takes, by name (a subset of the body's).
    pub(crate) arguments: Vec<&'static str>,
    /// Its return type.
    pub(crate) returns: TokenStream,
    /// Its outputs in each chart.
    pub(crate) outputs: Vec<&'a [ExprId]>,
    /// Its return value from its outputs' expressions.
    pub(crate) assemble: Assemble<'a>,
}

/// A shared body: its name, its arguments in each chart (the same names and
/// lengths, each chart's symbols), and its members.
pub(crate) struct Shared<'a> {
    pub(crate) name: Ident,
    pub(crate) doc: String,
    pub(crate) arguments: Vec<Vec<Argument>>,
    pub(crate) members: Vec<Member<'a>>,
}

/// A shared body: its name, its item (none for a model that is not
/// emitted as Rust), its operation counts, and the program each member
/// runs in each chart.
pub(crate) struct SharedItem {
    pub(crate) name: String,
    pub(crate) item: TokenStream,
    pub(crate) operations: OperationCount,
    /// `programs[chart][member]`: the body's program pruned to the member's
    /// outputs in that chart ([`ir::Program::pruned`]), its inputs the
    /// member's arguments then the parameters: what the interpreter and
    /// the JIT run, to the same bits as the body.
    pub(crate) programs: Vec<Vec<Lowered>>,
}

/// The body's program, the positions of each chart's outputs in it, and
/// the owner of each input slot (an argument by name, or a parameter).
struct LoweredBody {
    program: ir::Program,
    charts: Vec<Vec<usize>>,
    sources: Vec<TokenStream>,
    owners: Vec<Option<&'static str>>,
}

impl Shared<'_> {
    /// The body, lowered once for every member in every chart, and each
    /// member's pruned program.
    pub(crate) fn emit(&self, model: &Model, cx: &Context) -> Result<SharedItem, Diagnostics> {
        let internal = |e: ir::IrError| Diagnostics::internal(model.name.span(), e);
        let lowered = self.lower(model, cx).map_err(internal)?;
        let programs = self.programs(model, cx, &lowered).map_err(internal)?;
        let item = match model.emits_rust {
            true => self.item(&lowered).map_err(internal)?,
            false => TokenStream::new(),
        };
        Ok(SharedItem {
            name: self.name.to_string(),
            item,
            operations: lowered.program.operation_count(),
            programs,
        })
    }

    fn lower(&self, model: &Model, cx: &Context) -> Result<LoweredBody, ir::IrError> {
        let arguments: Vec<Argument> = self.arguments.iter().flatten().cloned().collect();
        let (symbols, sources, owners) = super::slots(model, &arguments);
        let mut outputs = Vec::new();
        let mut charts = Vec::new();
        for chart in 0..self.arguments.len() {
            let start = outputs.len();
            for member in &self.members {
                outputs.extend_from_slice(member.outputs[chart]);
            }
            charts.push((start..outputs.len()).collect::<Vec<_>>());
        }
        Ok(LoweredBody {
            program: ir::lower(cx, &symbols, &outputs)?,
            charts,
            sources,
            owners,
        })
    }

    /// Each member's program in each chart, read from its own arguments.
    fn programs(
        &self,
        model: &Model,
        cx: &Context,
        body: &LoweredBody,
    ) -> Result<Vec<Vec<Lowered>>, ir::IrError> {
        let family = &self.arguments[0];
        let parameters = model.parameters.len();
        let mut programs = Vec::with_capacity(body.charts.len());
        for (chart, positions) in body.charts.iter().enumerate() {
            let mut start = 0;
            let mut members = Vec::with_capacity(self.members.len());
            for member in &self.members {
                let own: Vec<&Argument> = family
                    .iter()
                    .filter(|argument| member.arguments.contains(&argument.name))
                    .collect();
                let slots = member_slots(&self.arguments, &own, parameters);
                let outputs = member.outputs[chart];
                let positions = &positions[start..start + outputs.len()];
                start += outputs.len();
                let before_cse = ir::before_cse(cx, outputs);
                members.push(Lowered {
                    program: body.program.pruned(positions, &slots, before_cse)?,
                    arguments: own
                        .iter()
                        .map(|argument| (argument.name, argument.symbols.len()))
                        .collect(),
                });
            }
            programs.push(members);
        }
        Ok(programs)
    }

    /// The private function computing every member in every chart.
    fn item(&self, body: &LoweredBody) -> Result<TokenStream, ir::IrError> {
        let emitted = body.program.emit_variants(&body.sources, &body.charts)?;
        let read = super::read_arguments(&body.program, &body.owners);
        let arms: Vec<TokenStream> = emitted
            .variants
            .into_iter()
            .map(|variant| {
                let values = self.returned(&variant.outputs);
                let statements = variant.statements;
                quote!({ #statements #values })
            })
            .collect();
        let common = emitted.common;
        let body = match arms.as_slice() {
            [only] => quote!(#common #only),
            _ => {
                let last = arms.len() - 1;
                let numbered = arms[..last].iter().enumerate().map(|(i, arm)| {
                    let i = Literal::usize_unsuffixed(i);
                    quote!(#i => #arm)
                });
                let last = &arms[last];
                quote!(#common match chart { #(#numbered,)* _ => #last })
            }
        };
        let (name, doc) = (&self.name, &self.doc);
        let chart = (self.arguments.len() > 1).then(|| quote!(chart: ::core::primitive::usize,));
        let f64 = f64_type();
        let parameters = self.arguments[0].iter().map(|argument| {
            let spelled = match read.contains(&argument.name) {
                true => format_ident!("{}", argument.name),
                false => format_ident!("_{}", argument.name),
            };
            let length = argument.symbols.len();
            quote!(#spelled: &[#f64; #length])
        });
        let returns = self.members.iter().map(|member| &member.returns);
        let returns = match self.members.len() {
            1 => quote!(#(#returns)*),
            _ => quote!((#(#returns),*)),
        };
        Ok(quote! {
            #[doc = #doc]
            fn #name(&self, #chart #(#parameters),*) -> #returns {
                #body
            }
        })
    }

    /// The members' return values from one chart's outputs, as a tuple when
    /// there are several.
    fn returned(&self, outputs: &[TokenStream]) -> TokenStream {
        let mut rest = outputs;
        let values: Vec<TokenStream> = self
            .members
            .iter()
            .map(|member| {
                let (own, after) = rest.split_at(member.outputs[0].len());
                rest = after;
                (member.assemble)(own)
            })
            .collect();
        match values.as_slice() {
            [only] => only.clone(),
            _ => quote!((#(#values),*)),
        }
    }

    /// The body of member `index` in chart `chart`: a call of the shared
    /// function, the member's arguments passed on and the others zero.
    pub(crate) fn call(&self, index: usize, chart: usize) -> TokenStream {
        let name = &self.name;
        let member = &self.members[index];
        let chart = (self.arguments.len() > 1).then(|| {
            let chart = Literal::usize_unsuffixed(chart);
            quote!(#chart,)
        });
        let arguments = self.arguments[0].iter().map(|argument| {
            match member.arguments.contains(&argument.name) {
                true => Ident::new(argument.name, Span::call_site()).into_token_stream(),
                false => {
                    let length = argument.symbols.len();
                    quote!(&[0.0; #length])
                }
            }
        });
        let call = quote!(self.#name(#chart #(#arguments),*));
        match self.members.len() {
            1 => call,
            _ => {
                let index = Literal::usize_unsuffixed(index);
                quote!(#call.#index)
            }
        }
    }
}

/// Where a member reads each of the body's input slots: the body's slots
/// are each chart's arguments (`family`, element by element) then the
/// parameters; the member's are its own arguments `own`, then the
/// parameters. An element means the same in every chart (`x[3]`).
fn member_slots(
    family: &[Vec<Argument>],
    own: &[&Argument],
    parameters: usize,
) -> Vec<Option<usize>> {
    let mut offsets = Vec::with_capacity(own.len());
    let mut length = 0;
    for argument in own {
        offsets.push((argument.name, length));
        length += argument.symbols.len();
    }
    let mut slots = Vec::new();
    for argument in family.iter().flatten() {
        let offset = offsets
            .iter()
            .find(|(name, _)| *name == argument.name)
            .map(|&(_, offset)| offset);
        slots.extend((0..argument.symbols.len()).map(|i| offset.map(|offset| offset + i)));
    }
    slots.extend((0..parameters).map(|j| Some(length + j)));
    slots
}

/// Groups items (by index) whose outputs `outputs[i]` share most of their
/// operations: an item joins a family when computing the family's union
/// costs each member at most [`SHARING_SLACK`] more than it costs alone,
/// by estimated weight ([`ir::estimated_weight`]). The heaviest items are
/// placed first; an item that joins none, or computes nothing, is a family
/// of its own.
pub(crate) fn families(cx: &Context, outputs: &[&[ExprId]]) -> Vec<Vec<usize>> {
    let weight = |ids: &[ExprId]| ir::estimated_weight(cx, ids) as f64;
    let weights: Vec<f64> = outputs.iter().map(|ids| weight(ids)).collect();
    let mut order: Vec<usize> = (0..outputs.len()).collect();
    order.sort_by(|&a, &b| weights[b].total_cmp(&weights[a]).then(a.cmp(&b)));
    let mut families: Vec<Vec<usize>> = Vec::new();
    for item in order {
        let joined = families
            .iter_mut()
            .filter(|_| weights[item] > 0.0)
            .find(|family| {
                let union: Vec<ExprId> = family
                    .iter()
                    .chain([&item])
                    .flat_map(|&i| outputs[i].iter().copied())
                    .collect();
                let lightest = family
                    .iter()
                    .chain([&item])
                    .map(|&i| weights[i])
                    .fold(f64::INFINITY, f64::min);
                weight(&union) <= (1.0 + SHARING_SLACK) * lightest
            });
        match joined {
            Some(family) => family.push(item),
            None => families.push(vec![item]),
        }
    }
    for family in &mut families {
        family.sort_unstable();
    }
    families.sort();
    families
}
