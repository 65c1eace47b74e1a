//! Lowering of store expressions to a [`Program`].
//!
//! Each node reachable from the outputs gets a [`Plan`]: how its value is
//! assembled from its children (a sum as a chain of `+`/`-`, a product as
//! numerator chain `/` denominator chain, a power by its
//! [`PowerForm`], a call). A divisor `x^-e` that several sums and products
//! read is not a denominator but a numerator, its reciprocal `1 / x^e`
//! computed once, as a careful hand writes `v = p / m` once and multiplies. Two passes follow, both over the DAG, never a tree:
//!
//! 1. demand, parents before children: which nodes need their own value
//!    (`plain`), and which products with a negative coefficient need the
//!    value of their magnitude (`3*b` for the term `-3*b` of a sum);
//! 2. code, children before parents: each node with plain demand is lowered
//!    once; a magnitude is lowered, once, when a sum first reads it, unless
//!    the product's own value exists, which the sum then adds instead. All
//!    instructions go through a builder that value-numbers them.
//!
//! Only demanded values are built, and each is read by its demander (a
//! magnitude and its product read the same children), so the program has no
//! dead values and emitted Rust has no unused `let`. The node shapes are not
//! trusted beyond what the evaluator relies on: constants may stand anywhere
//! in a sum or product and are folded exactly into one.

use super::cost::{BasicPower, PowerForm, tree_cost};
use super::{Constant, Instruction, IrError, Op, Program, Value};
use crate::sym::{ExprId, Function, Node, Rational, Store, SymbolId};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::cmp::Reverse;

/// Lowers `outputs` to a program whose input slot `i` holds symbol `inputs[i]`.
///
/// Fails with [`IrError::UnboundSymbol`] when an output mentions a symbol that
/// is not an input, and with [`IrError::UnknownExpression`] for an id that is
/// not in `store`. A symbol listed twice is read from its first slot.
pub fn lower(store: &Store, inputs: &[SymbolId], outputs: &[ExprId]) -> Result<Program, IrError> {
    if let Some(output) = outputs.iter().position(|o| o.index() >= store.len()) {
        return Err(IrError::UnknownExpression { output });
    }
    let order = store.reachable(outputs);
    let bound = bind_inputs(store, inputs, &order)?;
    let planner = Planner::new(store, &order);
    let demand = Demand::of(&planner, &order, outputs);
    let mut lowering = Lowering::new(&planner, &demand);
    for &(slot, id) in &bound {
        lowering.bind_input(slot, id);
    }
    for &id in &order {
        lowering.lower_node(id);
    }
    let output_values = outputs.iter().map(|&o| lowering.value(o)).collect();
    let mut input_names = vec![String::new(); inputs.len()];
    for &(slot, id) in &bound {
        if let Node::Symbol(symbol) = store.node(id) {
            input_names[slot] = store.symbol_info(*symbol).name.clone();
        }
    }
    let builder = lowering.builder;
    Ok(Program {
        input_names,
        value_count: builder.value_count as usize,
        instructions: builder.instructions,
        outputs: output_values,
        before_cse: tree_cost(store, &order, outputs),
    })
}

/// The input slot of every symbol node in `order`, sorted by slot.
fn bind_inputs(
    store: &Store,
    inputs: &[SymbolId],
    order: &[ExprId],
) -> Result<Vec<(usize, ExprId)>, IrError> {
    let mut bound = Vec::new();
    for &id in order {
        if let Node::Symbol(symbol) = store.node(id) {
            let slot =
                inputs
                    .iter()
                    .position(|s| s == symbol)
                    .ok_or_else(|| IrError::UnboundSymbol {
                        name: store.symbol_info(*symbol).name.clone(),
                    })?;
            bound.push((slot, id));
        }
    }
    bound.sort_unstable();
    Ok(bound)
}

// ----- plans ---------------------------------------------------------------

/// How a node's value is assembled from its children.
enum Plan {
    Number(Rational),
    /// A symbol: its value is bound to an input before anything is lowered.
    Symbol,
    Sum(SumPlan),
    Product(ProductPlan),
    Power {
        base: ExprId,
        form: PowerForm,
        exponent: Rational,
    },
    Call(Function, ExprId),
    Atan2(ExprId, ExprId),
}

/// One operand of a sum chain.
enum Summand {
    /// The node's value.
    Node(ExprId),
    /// The magnitude of a product with a negative coefficient.
    Magnitude(ExprId),
    Constant(Rational),
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Sign {
    Plus,
    Minus,
}

/// `head ± rest[0] ± rest[1] ...`, left to right.
struct SumPlan {
    head: Summand,
    rest: Vec<(Sign, Summand)>,
}

/// `coefficient * numerators / denominators`.
struct ProductPlan {
    coefficient: Rational,
    numerators: Vec<ExprId>,
    denominators: Vec<(ExprId, BasicPower)>,
}

/// A value a plan reads.
enum Need {
    Plain(ExprId),
    Magnitude(ExprId),
}

impl Plan {
    fn needs(&self) -> Vec<Need> {
        match self {
            Plan::Number(_) | Plan::Symbol => Vec::new(),
            Plan::Sum(sum) => std::iter::once(&sum.head)
                .chain(sum.rest.iter().map(|(_, summand)| summand))
                .filter_map(Summand::need)
                .collect(),
            Plan::Product(product) => product
                .numerators
                .iter()
                .chain(product.denominators.iter().map(|(base, _)| base))
                .map(|&id| Need::Plain(id))
                .collect(),
            Plan::Power { base, .. } => vec![Need::Plain(*base)],
            Plan::Call(_, argument) => vec![Need::Plain(*argument)],
            Plan::Atan2(y, x) => vec![Need::Plain(*y), Need::Plain(*x)],
        }
    }
}

impl Summand {
    fn need(&self) -> Option<Need> {
        match self {
            Summand::Node(id) => Some(Need::Plain(*id)),
            Summand::Magnitude(id) => Some(Need::Magnitude(*id)),
            Summand::Constant(_) => None,
        }
    }
}

/// Builds plans; orders chain operands so that shared ones come first.
struct Planner<'a> {
    store: &'a Store,
    /// How many sums and products each node is an operand of.
    sharing: HashMap<ExprId, usize>,
}

impl<'a> Planner<'a> {
    fn new(store: &'a Store, order: &[ExprId]) -> Planner<'a> {
        let mut sharing = HashMap::default();
        for &id in order {
            if let Node::Add(operands) | Node::Mul(operands) = store.node(id) {
                for &operand in operands.iter() {
                    *sharing.entry(operand).or_insert(0) += 1;
                }
            }
        }
        Planner { store, sharing }
    }

    /// Whether `id` is an operand of more than one sum or product. A shared
    /// inverse power `x^-e` is computed once as `1 / x^e` and multiplied,
    /// rather than divided by in every product: one division for all.
    fn is_shared(&self, id: ExprId) -> bool {
        self.sharing.get(&id).is_some_and(|&count| count > 1)
    }

    /// Most shared first, then by id: chains with a common prefix share it.
    fn chain_order(&self, id: ExprId) -> (Reverse<usize>, ExprId) {
        (Reverse(self.sharing.get(&id).copied().unwrap_or(0)), id)
    }

    fn plan(&self, id: ExprId) -> Plan {
        match self.store.node(id) {
            Node::Number(value) => Plan::Number(value.clone()),
            Node::Symbol(_) => Plan::Symbol,
            Node::Add(terms) => Plan::Sum(self.sum_plan(terms)),
            Node::Mul(factors) => Plan::Product(self.product_plan(factors)),
            Node::Pow(base, exponent) => Plan::Power {
                base: *base,
                form: PowerForm::of(exponent),
                exponent: exponent.clone(),
            },
            Node::Call(function, argument) => Plan::Call(*function, *argument),
            Node::Atan2(y, x) => Plan::Atan2(*y, *x),
        }
    }

    fn sum_plan(&self, terms: &[ExprId]) -> SumPlan {
        let mut constant = Rational::ZERO;
        let mut summands = Vec::with_capacity(terms.len());
        for &term in terms {
            match self.store.node(term) {
                Node::Number(value) => constant = constant.add(value),
                Node::Mul(factors) if self.coefficient(factors).is_negative() => {
                    summands.push((Sign::Minus, term));
                }
                _ => summands.push((Sign::Plus, term)),
            }
        }
        summands.sort_by_key(|&(_, term)| self.chain_order(term));
        let mut summands: Vec<(Sign, Summand)> = summands
            .into_iter()
            .map(|(sign, term)| match sign {
                Sign::Plus => (sign, Summand::Node(term)),
                Sign::Minus => (sign, Summand::Magnitude(term)),
            })
            .collect();
        if !constant.is_zero() {
            let sign = if constant.is_negative() {
                Sign::Minus
            } else {
                Sign::Plus
            };
            summands.push((sign, Summand::Constant(constant.abs())));
        }
        let head = take_head(&mut summands);
        SumPlan {
            head,
            rest: summands,
        }
    }

    fn coefficient(&self, factors: &[ExprId]) -> Rational {
        factors
            .iter()
            .filter_map(|&f| self.store.as_number(f))
            .fold(Rational::ONE, |product, c| product.mul(c))
    }

    fn product_plan(&self, factors: &[ExprId]) -> ProductPlan {
        let mut numerators = Vec::with_capacity(factors.len());
        let mut denominators = Vec::new();
        for &factor in factors {
            match self.store.node(factor) {
                Node::Number(_) => {}
                Node::Pow(base, exponent) => match PowerForm::of(exponent) {
                    PowerForm::Inverse(basic) if !self.is_shared(factor) => {
                        denominators.push((*base, basic));
                    }
                    _ => numerators.push(factor),
                },
                _ => numerators.push(factor),
            }
        }
        numerators.sort_by_key(|&id| self.chain_order(id));
        denominators.sort_by_key(|&(base, _)| self.chain_order(base));
        ProductPlan {
            coefficient: self.coefficient(factors),
            numerators,
            denominators,
        }
    }
}

/// Removes the first added summand to start the chain; when every summand is
/// subtracted, the first one starts it with its own (negative) value.
fn take_head(summands: &mut Vec<(Sign, Summand)>) -> Summand {
    if summands.is_empty() {
        return Summand::Constant(Rational::ZERO);
    }
    let at = summands
        .iter()
        .position(|(sign, _)| *sign == Sign::Plus)
        .unwrap_or(0);
    match summands.remove(at) {
        (Sign::Plus, summand) => summand,
        (Sign::Minus, Summand::Magnitude(id) | Summand::Node(id)) => Summand::Node(id),
        (Sign::Minus, Summand::Constant(c)) => Summand::Constant(c.neg()),
    }
}

// ----- demand --------------------------------------------------------------

/// Which nodes need their value (the magnitudes needed only matter while
/// demand flows down: they are built lazily, see [`Lowering::magnitude`]).
struct Demand {
    plain: HashSet<ExprId>,
    /// `(sin u, cos u)` pairs, both needed, keyed by `u`.
    sin_cos: HashMap<ExprId, (ExprId, ExprId)>,
}

impl Demand {
    fn of(planner: &Planner, order: &[ExprId], outputs: &[ExprId]) -> Demand {
        let mut plain: HashSet<ExprId> = outputs.iter().copied().collect();
        let mut magnitude = HashSet::default();
        for &id in order.iter().rev() {
            if !plain.contains(&id) && !magnitude.contains(&id) {
                continue;
            }
            for need in planner.plan(id).needs() {
                match need {
                    Need::Plain(child) => plain.insert(child),
                    Need::Magnitude(child) => magnitude.insert(child),
                };
            }
        }
        let sin_cos = sin_cos_pairs(planner.store, order, &plain);
        Demand { plain, sin_cos }
    }
}

/// Arguments whose sine and cosine are both needed.
fn sin_cos_pairs(
    store: &Store,
    order: &[ExprId],
    plain: &HashSet<ExprId>,
) -> HashMap<ExprId, (ExprId, ExprId)> {
    let mut sines = HashMap::default();
    let mut cosines = HashMap::default();
    for &id in order.iter().filter(|id| plain.contains(id)) {
        match store.node(id) {
            Node::Call(Function::Sin, argument) => sines.insert(*argument, id),
            Node::Call(Function::Cos, argument) => cosines.insert(*argument, id),
            _ => None,
        };
    }
    sines
        .into_iter()
        .filter_map(|(argument, sine)| Some((argument, (sine, *cosines.get(&argument)?))))
        .collect()
}

// ----- code ----------------------------------------------------------------

/// Appends instructions, reusing the value of an equal earlier instruction.
#[derive(Default)]
struct Builder {
    instructions: Vec<Instruction>,
    numbering: HashMap<Op, Value>,
    value_count: u32,
}

impl Builder {
    fn fresh(&mut self) -> Value {
        let value = Value(self.value_count);
        self.value_count += 1;
        value
    }

    fn push(&mut self, op: Op) -> Value {
        let op = match op {
            Op::Add(a, b) => Op::Add(a.min(b), a.max(b)),
            Op::Mul(a, b) => Op::Mul(a.min(b), a.max(b)),
            op => op,
        };
        if let Some(&value) = self.numbering.get(&op) {
            return value;
        }
        let result = self.fresh();
        self.numbering.insert(op.clone(), result);
        self.instructions.push(Instruction { op, result });
        result
    }

    fn constant(&mut self, value: Rational) -> Value {
        self.push(Op::Constant(Constant::new(value)))
    }

    fn sin_cos(&mut self, angle: Value) -> (Value, Value) {
        let sine = self.fresh();
        let cosine = self.fresh();
        let op = Op::SinCos { angle, cosine };
        self.instructions.push(Instruction { op, result: sine });
        (sine, cosine)
    }

    /// `values[0] * values[1] * ...`, left to right; `None` for no values.
    fn product_chain(&mut self, values: &[Value]) -> Option<Value> {
        let (&first, rest) = values.split_first()?;
        Some(
            rest.iter()
                .fold(first, |acc, &v| self.push(Op::Mul(acc, v))),
        )
    }

    fn basic_power(&mut self, base: Value, power: BasicPower) -> Value {
        match power {
            BasicPower::Identity => base,
            BasicPower::Square => self.push(Op::Mul(base, base)),
            BasicPower::Cube => {
                let square = self.push(Op::Mul(base, base));
                self.push(Op::Mul(square, base))
            }
            BasicPower::SquareRoot => self.push(Op::Sqrt(base)),
        }
    }
}

/// Pass 2: the values of demanded nodes and magnitudes, children first.
struct Lowering<'a> {
    planner: &'a Planner<'a>,
    demand: &'a Demand,
    builder: Builder,
    values: HashMap<ExprId, Value>,
    magnitudes: HashMap<ExprId, Value>,
}

impl<'a> Lowering<'a> {
    fn new(planner: &'a Planner<'a>, demand: &'a Demand) -> Lowering<'a> {
        Lowering {
            planner,
            demand,
            builder: Builder::default(),
            values: HashMap::default(),
            magnitudes: HashMap::default(),
        }
    }

    fn bind_input(&mut self, slot: usize, id: ExprId) {
        if self.demand.plain.contains(&id) {
            let value = self.builder.push(Op::Input(slot));
            self.values.insert(id, value);
        }
    }

    /// The value of a node lowered earlier (the demand pass guarantees it).
    fn value(&self, id: ExprId) -> Value {
        self.values[&id]
    }

    fn lower_node(&mut self, id: ExprId) {
        if self.demand.plain.contains(&id) && !self.values.contains_key(&id) {
            let value = self.plain(id);
            self.values.insert(id, value);
        }
    }

    /// The value of `|c| * rest` for a product `c * rest` with `c < 0`.
    fn magnitude(&mut self, id: ExprId) -> Value {
        if let Some(&magnitude) = self.magnitudes.get(&id) {
            return magnitude;
        }
        let magnitude = match self.planner.plan(id) {
            Plan::Product(product) => self.product(&product, product.coefficient.abs()),
            _ => self.plain(id),
        };
        self.magnitudes.insert(id, magnitude);
        magnitude
    }

    fn plain(&mut self, id: ExprId) -> Value {
        match self.planner.plan(id) {
            Plan::Number(value) => self.builder.constant(value),
            Plan::Symbol => self.value(id),
            Plan::Sum(sum) => self.sum(&sum),
            Plan::Product(product) => self.product(&product, product.coefficient.clone()),
            Plan::Power {
                base,
                form,
                exponent,
            } => self.power(self.value(base), form, exponent),
            Plan::Call(function, argument) => self.call(id, function, argument),
            Plan::Atan2(y, x) => {
                let (y, x) = (self.value(y), self.value(x));
                self.builder.push(Op::Atan2(y, x))
            }
        }
    }

    fn summand(&mut self, summand: &Summand) -> Value {
        match summand {
            Summand::Node(id) => self.value(*id),
            Summand::Magnitude(id) => self.magnitude(*id),
            Summand::Constant(c) => self.builder.constant(c.clone()),
        }
    }

    fn sum(&mut self, sum: &SumPlan) -> Value {
        let mut total = self.summand(&sum.head);
        for (sign, summand) in &sum.rest {
            let (sign, operand) = self.signed_operand(*sign, summand);
            total = match sign {
                Sign::Plus => self.builder.push(Op::Add(total, operand)),
                Sign::Minus => self.builder.push(Op::Sub(total, operand)),
            };
        }
        total
    }

    /// A summand after the head: `+ c*rest` rather than `- |c|*rest` when
    /// `c*rest` is computed anyway.
    fn signed_operand(&mut self, sign: Sign, summand: &Summand) -> (Sign, Value) {
        match summand {
            Summand::Magnitude(id) if self.values.contains_key(id) => (Sign::Plus, self.value(*id)),
            _ => (sign, self.summand(summand)),
        }
    }

    /// `coefficient * numerators / denominators`, constants last so that
    /// `3*a*b` shares `a*b`; `-1 * rest` is `-(rest)`.
    fn product(&mut self, product: &ProductPlan, coefficient: Rational) -> Value {
        if coefficient.is_zero() {
            return self.builder.constant(coefficient);
        }
        let minus_one = Rational::integer(-1);
        if coefficient == minus_one && !product.numerators.is_empty() {
            let magnitude = self.product(product, Rational::ONE);
            return self.builder.push(Op::Neg(magnitude));
        }
        let mut numerators: Vec<Value> = product
            .numerators
            .iter()
            .map(|&id| self.value(id))
            .collect();
        if !coefficient.is_one() {
            numerators.push(self.builder.constant(coefficient.clone()));
        }
        let denominators: Vec<Value> = product
            .denominators
            .iter()
            .map(|&(base, power)| self.builder.basic_power(self.value(base), power))
            .collect();
        let numerator = self.builder.product_chain(&numerators);
        match (numerator, self.builder.product_chain(&denominators)) {
            (Some(numerator), None) => numerator,
            (numerator, Some(denominator)) => {
                let numerator = numerator.unwrap_or_else(|| self.builder.constant(Rational::ONE));
                self.builder.push(Op::Div(numerator, denominator))
            }
            (None, None) => self.builder.constant(coefficient),
        }
    }

    fn power(&mut self, base: Value, form: PowerForm, exponent: Rational) -> Value {
        match form {
            PowerForm::Direct(power) => self.builder.basic_power(base, power),
            PowerForm::Inverse(power) => {
                let denominator = self.builder.basic_power(base, power);
                let one = self.builder.constant(Rational::ONE);
                self.builder.push(Op::Div(one, denominator))
            }
            PowerForm::Powi(n) => self.builder.push(Op::Powi(base, n)),
            PowerForm::Powf => self.builder.push(Op::Powf(base, Constant::new(exponent))),
        }
    }

    fn call(&mut self, id: ExprId, function: Function, argument: ExprId) -> Value {
        let angle = self.value(argument);
        let paired = matches!(function, Function::Sin | Function::Cos);
        if let Some(&(sine_node, cosine_node)) =
            self.demand.sin_cos.get(&argument).filter(|_| paired)
        {
            let (sine, cosine) = self.builder.sin_cos(angle);
            self.values.insert(sine_node, sine);
            self.values.insert(cosine_node, cosine);
            return if id == sine_node { sine } else { cosine };
        }
        let op = match function {
            Function::Sin => Op::Sin(angle),
            Function::Cos => Op::Cos(angle),
            Function::Tan => Op::Tan(angle),
            Function::Exp => Op::Exp(angle),
            Function::Ln => Op::Ln(angle),
            Function::Asin => Op::Asin(angle),
            Function::Acos => Op::Acos(angle),
            Function::Atan => Op::Atan(angle),
        };
        self.builder.push(op)
    }
}
