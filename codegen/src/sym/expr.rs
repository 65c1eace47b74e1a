//! The hash-consed expression store.
//!
//! Every expression lives in one [`Store`] and is named by an [`ExprId`]. Nodes
//! are interned: building the same node twice returns the same id, so equal
//! sub-expressions are shared, and children always have smaller ids than their
//! parents (the store is a topologically sorted DAG). Constructors apply only
//! cheap, always-valid rewrites (flattening, constant folding, collecting
//! `c*x + d*x` and `x^a * x^b`, sorting operands); the canonical form used for
//! exact zero tests lives in [`super::normal`].

use super::number::Rational;
use rustc_hash::{FxHashMap as HashMap, FxHashSet};
use std::fmt;

/// Handle of an expression in a [`Store`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ExprId(pub(crate) u32);

impl ExprId {
    /// Position of the node in its store (children come before parents).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Handle of a symbol in a [`Store`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SymbolId(pub(crate) u32);

impl SymbolId {
    /// Position of the symbol in its store, in declaration order.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What a symbol stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SymbolKind {
    /// A generalized coordinate `q_i`.
    Coordinate,
    /// The velocity `dot(q)` of the given coordinate.
    Velocity(SymbolId),
    /// A model parameter (mass, length, ...).
    Parameter,
    /// A reduced momentum `alpha_i` or a symmetry momentum `p_i`.
    Momentum,
    /// Anything else: inputs, time, intermediate unknowns.
    Auxiliary,
}

/// A named symbol.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Symbol {
    /// The name as the user wrote it (`dot(q)` for velocities).
    pub name: String,
    /// What the symbol stands for.
    pub kind: SymbolKind,
}

/// The elementary functions the engine knows (`sqrt` is stored as a power 1/2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Function {
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
    /// Tangent.
    Tan,
    /// Natural exponential.
    Exp,
    /// Natural logarithm.
    Ln,
}

impl Function {
    /// The name used in the model language and in printed expressions.
    pub fn name(self) -> &'static str {
        match self {
            Function::Sin => "sin",
            Function::Cos => "cos",
            Function::Tan => "tan",
            Function::Exp => "exp",
            Function::Ln => "ln",
        }
    }

    /// Applies the function to a number.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Function::Sin => x.sin(),
            Function::Cos => x.cos(),
            Function::Tan => x.tan(),
            Function::Exp => x.exp(),
            Function::Ln => x.ln(),
        }
    }
}

/// One node of the expression DAG.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// An exact rational constant.
    Number(Rational),
    /// A symbol.
    Symbol(SymbolId),
    /// A sum: at least two terms, a constant term (if any) first, the rest sorted by id.
    Add(Box<[ExprId]>),
    /// A product: at least two factors, a constant factor (if any) first, the rest sorted by id.
    Mul(Box<[ExprId]>),
    /// `base ^ exponent`, exponent neither 0 nor 1.
    Pow(ExprId, Rational),
    /// An elementary function applied to one argument.
    Call(Function, ExprId),
}

/// Errors of the symbolic engine, each printing the offending expression.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SymError {
    /// A divisor whose normal form is exactly zero.
    #[error("division by an expression that is exactly zero: {expr}")]
    DivisionByZero {
        /// The divisor, printed.
        expr: String,
    },
    /// `c^(p/q)` with `c < 0` and `q > 1`: not a real number.
    #[error("non-integer power of a negative constant: {expr}")]
    NegativeBase {
        /// The power, printed.
        expr: String,
    },
    /// A function name the engine does not know.
    #[error("unknown function `{name}`; the functions are sin, cos, tan, sqrt, exp, ln")]
    UnknownFunction {
        /// The name as written.
        name: String,
    },
    /// A function outside its domain at a constant argument, e.g. `ln(0)`.
    #[error("{expr} is undefined")]
    Undefined {
        /// The application, printed.
        expr: String,
    },
    /// An integer power of a constant too large to compute exactly.
    #[error(
        "a constant power with about {bits} bits (the limit is {MAX_CONSTANT_BITS}); \
         write a smaller number"
    )]
    ConstantTooLarge {
        /// The estimated size of the power in bits.
        bits: u64,
    },
    /// The normal form needed more polynomial term products than the
    /// derivation budget allows ([`super::budget`]).
    #[error(
        "derivation budget exceeded: the normal form needs more than {limit} polynomial \
         term products (the limit); simplify the model, e.g. avoid high powers of sums \
         of sines and cosines"
    )]
    BudgetExceeded {
        /// The limit that was exceeded.
        limit: u64,
    },
}

/// The largest integer power of a constant folded, in bits (about 20,000
/// decimal digits); larger powers are rejected rather than computed.
pub const MAX_CONSTANT_BITS: u64 = 1 << 16;

/// A nested budget being charged instead of the store's own.
pub(crate) struct Attempt {
    trial: super::Budget,
    outer: super::Budget,
}

/// The expression arena with its symbol table.
#[derive(Default, Clone)]
pub struct Store {
    nodes: Vec<Node>,
    interned: HashMap<Node, ExprId>,
    symbols: Vec<Symbol>,
    symbol_index: HashMap<String, SymbolId>,
    velocities: HashMap<SymbolId, SymbolId>,
    pub(crate) atoms: super::poly::Atoms,
    pub(crate) normal_forms: HashMap<ExprId, super::normal::RationalFunction>,
    /// `d node / d symbol` of the nodes differentiated so far, per symbol.
    pub(crate) derivative_memo: HashMap<SymbolId, HashMap<ExprId, ExprId>>,
}

impl fmt::Debug for Store {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Store")
            .field("nodes", &self.nodes.len())
            .field("symbols", &self.symbols)
            .finish()
    }
}

impl Store {
    /// An empty store.
    pub fn new() -> Store {
        Store::default()
    }

    /// An empty store whose normal forms are charged to `budget`.
    pub fn with_budget(budget: super::Budget) -> Store {
        Store {
            atoms: super::poly::Atoms::with_budget(budget),
            ..Store::default()
        }
    }

    /// The derivation budget of this store.
    pub fn budget(&self) -> &super::Budget {
        self.atoms.budget()
    }

    /// Runs `work` on a budget of `limit` term products nested in this
    /// store's ([`super::Budget::nested`]): its result, or `None` when the
    /// nested budget ran out (the result is then truncated and dropped).
    /// The limit is cut to what this store's budget has left, so an attempt
    /// never spends it.
    pub fn attempt<T>(&mut self, limit: u64, work: impl FnOnce(&mut Store) -> T) -> Option<T> {
        let trial = self.enter_attempt(limit);
        let result = work(self);
        self.leave_attempt(trial).then_some(result)
    }

    /// Starts charging a nested budget of `limit` (see [`Store::attempt`]).
    pub(crate) fn enter_attempt(&mut self, limit: u64) -> Attempt {
        let budget = self.budget();
        let left = budget.limit().saturating_sub(budget.used());
        let trial = budget.nested(limit.min(left.saturating_sub(1)));
        let outer = self.atoms.replace_budget(trial.clone());
        Attempt { trial, outer }
    }

    /// Ends an attempt: true when it stayed within its nested budget.
    pub(crate) fn leave_attempt(&mut self, attempt: Attempt) -> bool {
        self.atoms.replace_budget(attempt.outer);
        !attempt.trial.is_exhausted()
    }

    /// The node behind an id.
    pub fn node(&self, id: ExprId) -> &Node {
        &self.nodes[id.index()]
    }

    /// Number of nodes in the store.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True when no node has been built.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.interned.get(&node) {
            return id;
        }
        let id = ExprId(self.nodes.len() as u32);
        self.nodes.push(node.clone());
        self.interned.insert(node, id);
        id
    }

    // ----- symbols -------------------------------------------------------

    /// Declares (or finds) a symbol by name. A name keeps its first kind.
    pub fn declare(&mut self, name: &str, kind: SymbolKind) -> SymbolId {
        if let Some(&id) = self.symbol_index.get(name) {
            return id;
        }
        let id = SymbolId(self.symbols.len() as u32);
        self.symbols.push(Symbol {
            name: name.to_string(),
            kind,
        });
        self.symbol_index.insert(name.to_string(), id);
        id
    }

    /// The velocity symbol `dot(q)` of a coordinate, declared on first use.
    pub fn velocity_of(&mut self, coordinate: SymbolId) -> SymbolId {
        if let Some(&id) = self.velocities.get(&coordinate) {
            return id;
        }
        let name = format!("dot({})", self.symbols[coordinate.index()].name);
        let id = self.declare(&name, SymbolKind::Velocity(coordinate));
        self.velocities.insert(coordinate, id);
        id
    }

    /// A symbol's name and kind.
    pub fn symbol_info(&self, id: SymbolId) -> &Symbol {
        &self.symbols[id.index()]
    }

    /// Looks a symbol up by name.
    pub fn find_symbol(&self, name: &str) -> Option<SymbolId> {
        self.symbol_index.get(name).copied()
    }

    /// Every declared symbol, in declaration order.
    pub fn symbols(&self) -> impl Iterator<Item = (SymbolId, &Symbol)> {
        self.symbols
            .iter()
            .enumerate()
            .map(|(i, s)| (SymbolId(i as u32), s))
    }

    // ----- leaves --------------------------------------------------------

    /// The constant `value`.
    pub fn number(&mut self, value: Rational) -> ExprId {
        self.intern(Node::Number(value))
    }

    /// The integer constant `n`.
    pub fn integer(&mut self, n: i64) -> ExprId {
        self.number(Rational::integer(n))
    }

    /// The expression made of one symbol.
    pub fn symbol(&mut self, id: SymbolId) -> ExprId {
        self.intern(Node::Symbol(id))
    }

    /// The constant value of a number node.
    pub fn as_number(&self, id: ExprId) -> Option<&Rational> {
        match self.node(id) {
            Node::Number(value) => Some(value),
            _ => None,
        }
    }

    // ----- sums ----------------------------------------------------------

    /// `a + b`.
    pub fn add2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.add(&[a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let minus_b = self.neg(b);
        self.add(&[a, minus_b])
    }

    /// `-a`.
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        let minus_one = self.integer(-1);
        self.mul(&[minus_one, a])
    }

    /// The sum of `terms`, flattened, with like terms `c*x + d*x` collected.
    pub fn add(&mut self, terms: &[ExprId]) -> ExprId {
        let mut constant = Rational::ZERO;
        let mut coefficients: Vec<(ExprId, Rational)> = Vec::new();
        let mut positions: HashMap<ExprId, usize> = HashMap::default();
        let mut pending: Vec<ExprId> = terms.to_vec();
        while let Some(term) = pending.pop() {
            match self.node(term) {
                Node::Number(value) => constant = constant.add(value),
                Node::Add(children) => pending.extend(children.iter().copied()),
                _ => {
                    let (coefficient, rest) = self.split_coefficient(term);
                    match positions.get(&rest) {
                        Some(&at) => coefficients[at].1 = coefficients[at].1.add(&coefficient),
                        None => {
                            positions.insert(rest, coefficients.len());
                            coefficients.push((rest, coefficient));
                        }
                    }
                }
            }
        }
        let mut children: Vec<ExprId> = coefficients
            .into_iter()
            .filter(|(_, c)| !c.is_zero())
            .map(|(rest, c)| self.scale(rest, c))
            .collect();
        children.sort_unstable();
        if !constant.is_zero() {
            children.insert(0, self.number(constant));
        }
        match children.len() {
            0 => self.integer(0),
            1 => children[0],
            _ => self.intern(Node::Add(children.into_boxed_slice())),
        }
    }

    /// Splits `c * rest` into its constant coefficient and the rest.
    fn split_coefficient(&mut self, term: ExprId) -> (Rational, ExprId) {
        if let Node::Mul(factors) = self.node(term)
            && let Node::Number(c) = self.node(factors[0])
        {
            let c = c.clone();
            let rest = factors[1..].to_vec();
            let rest = if rest.len() == 1 {
                rest[0]
            } else {
                self.intern(Node::Mul(rest.into_boxed_slice()))
            };
            return (c, rest);
        }
        (Rational::ONE, term)
    }

    /// `c * rest` where `rest` carries no constant factor.
    fn scale(&mut self, rest: ExprId, c: Rational) -> ExprId {
        if c.is_one() {
            return rest;
        }
        let c = self.number(c);
        self.mul(&[c, rest])
    }

    // ----- products ------------------------------------------------------

    /// `a * b`.
    pub fn mul2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.mul(&[a, b])
    }

    /// The product of `factors`, flattened, with `x^a * x^b = x^(a+b)` collected.
    pub fn mul(&mut self, factors: &[ExprId]) -> ExprId {
        let mut constant = Rational::ONE;
        let mut exponents: Vec<(ExprId, Rational)> = Vec::new();
        let mut positions: HashMap<ExprId, usize> = HashMap::default();
        let mut pending: Vec<ExprId> = factors.to_vec();
        while let Some(factor) = pending.pop() {
            let (base, exponent) = match self.node(factor) {
                Node::Number(value) => {
                    constant = constant.mul(value);
                    continue;
                }
                Node::Mul(children) => {
                    pending.extend(children.iter().copied());
                    continue;
                }
                Node::Pow(base, exponent) => (*base, exponent.clone()),
                _ => (factor, Rational::ONE),
            };
            match positions.get(&base) {
                Some(&at) => exponents[at].1 = exponents[at].1.add(&exponent),
                None => {
                    positions.insert(base, exponents.len());
                    exponents.push((base, exponent));
                }
            }
        }
        if constant.is_zero() {
            return self.integer(0);
        }
        let mut children = Vec::with_capacity(exponents.len() + 1);
        let mut distributed = false;
        for (base, exponent) in exponents {
            let power = self.pow_of_collected(base, exponent);
            match self.node(power) {
                Node::Number(value) => constant = constant.mul(value),
                Node::Mul(_) => {
                    distributed = true;
                    children.push(power);
                }
                _ => children.push(power),
            }
        }
        if distributed {
            // An integer power of a product, e.g. sqrt(2x)^2 = 2x, was
            // distributed: collect its factors with the others once more.
            children.push(self.number(constant));
            return self.mul(&children);
        }
        if constant.is_zero() {
            return self.integer(0);
        }
        children.sort_unstable();
        if !constant.is_one() {
            children.insert(0, self.number(constant));
        }
        match children.len() {
            0 => self.integer(1),
            1 => children[0],
            _ => self.intern(Node::Mul(children.into_boxed_slice())),
        }
    }

    /// Rebuilds a collected power; a constant base that cannot be folded exactly
    /// (e.g. `2^(1/2)`) is kept as a power node, which is always valid here
    /// because constructors never produce a negative base with a fractional exponent.
    fn pow_of_collected(&mut self, base: ExprId, exponent: Rational) -> ExprId {
        match self.pow(base, exponent.clone()) {
            Ok(power) => power,
            Err(_) => self.intern(Node::Pow(base, exponent)),
        }
    }

    /// `a / b`. Fails when `b` is the constant zero; a divisor that is zero only
    /// after simplification is caught by the normal form.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> Result<ExprId, SymError> {
        let inverse = self.pow(b, Rational::integer(-1))?;
        Ok(self.mul(&[a, inverse]))
    }

    // ----- powers --------------------------------------------------------

    /// `base ^ exponent` for a rational exponent.
    pub fn pow(&mut self, base: ExprId, exponent: Rational) -> Result<ExprId, SymError> {
        if exponent.is_zero() {
            return Ok(self.integer(1));
        }
        if exponent.is_one() {
            return Ok(base);
        }
        match self.node(base).clone() {
            Node::Number(value) => self.pow_of_number(&value, exponent),
            _ => Ok(self.pow_of_expression(base, exponent)),
        }
    }

    /// `base ^ exponent` for a non-constant base: never fails.
    pub(crate) fn pow_of_expression(&mut self, base: ExprId, exponent: Rational) -> ExprId {
        if exponent.is_zero() {
            return self.integer(1);
        }
        if exponent.is_one() {
            return base;
        }
        match self.node(base).clone() {
            Node::Pow(inner, inner_exponent) if exponent.is_integer() => {
                self.pow_of_expression(inner, inner_exponent.mul(&exponent))
            }
            Node::Mul(factors) if exponent.is_integer() => {
                let powers: Vec<ExprId> = factors
                    .iter()
                    .map(|&f| self.pow_of_collected(f, exponent.clone()))
                    .collect();
                self.mul(&powers)
            }
            _ => self.intern(Node::Pow(base, exponent)),
        }
    }

    fn pow_of_number(&mut self, value: &Rational, exponent: Rational) -> Result<ExprId, SymError> {
        if value.is_zero() && exponent.is_negative() {
            return Err(SymError::DivisionByZero {
                expr: "0".to_string(),
            });
        }
        if let Some(n) = exponent.to_i64() {
            let bits = value.bits().saturating_mul(n.unsigned_abs());
            if bits > MAX_CONSTANT_BITS && value.abs() != Rational::ONE {
                return Err(SymError::ConstantTooLarge { bits });
            }
        }
        if let Some(folded) = exponent.to_i64().and_then(|n| value.powi(n)) {
            return Ok(self.number(folded));
        }
        if value.is_negative() {
            return Err(SymError::NegativeBase {
                expr: format!("({value})^({exponent})"),
            });
        }
        let (numerator, denominator) = match exponent.to_small() {
            Some(parts) => parts,
            None => {
                let base = self.number(value.clone());
                return Ok(self.intern(Node::Pow(base, exponent)));
            }
        };
        let root = u32::try_from(denominator)
            .ok()
            .and_then(|d| value.exact_root(d));
        if let Some(power) = root.and_then(|r| r.powi(numerator)) {
            return Ok(self.number(power));
        }
        let base = self.number(value.clone());
        Ok(self.intern(Node::Pow(base, exponent)))
    }

    /// `sqrt(x)`, stored as `x^(1/2)`.
    pub fn sqrt(&mut self, x: ExprId) -> Result<ExprId, SymError> {
        self.pow(x, Rational::new(1, 2).unwrap_or(Rational::ONE))
    }

    // ----- functions -----------------------------------------------------

    /// Applies a function by its model-language name (`sin cos tan sqrt exp ln`).
    pub fn apply_named(&mut self, name: &str, argument: ExprId) -> Result<ExprId, SymError> {
        let function = match name {
            "sin" => Function::Sin,
            "cos" => Function::Cos,
            "tan" => Function::Tan,
            "exp" => Function::Exp,
            "ln" => Function::Ln,
            "sqrt" => return self.sqrt(argument),
            _ => {
                return Err(SymError::UnknownFunction {
                    name: name.to_string(),
                });
            }
        };
        self.apply(function, argument)
    }

    /// `function(argument)`, folding the exact constant cases
    /// (`sin 0 = 0`, `cos 0 = 1`, `tan 0 = 0`, `exp 0 = 1`, `ln 1 = 0`).
    pub fn apply(&mut self, function: Function, argument: ExprId) -> Result<ExprId, SymError> {
        if let Node::Number(value) = self.node(argument) {
            if value.is_zero() {
                return match function {
                    Function::Sin | Function::Tan => Ok(self.integer(0)),
                    Function::Cos | Function::Exp => Ok(self.integer(1)),
                    Function::Ln => Err(SymError::Undefined {
                        expr: "ln(0)".to_string(),
                    }),
                };
            }
            if function == Function::Ln && value.is_one() {
                return Ok(self.integer(0));
            }
            if function == Function::Ln && value.is_negative() {
                return Err(SymError::Undefined {
                    expr: format!("ln({value})"),
                });
            }
        }
        Ok(self.intern(Node::Call(function, argument)))
    }

    /// `function(argument)` for an argument known not to be a constant.
    pub(crate) fn apply_to_expression(&mut self, function: Function, argument: ExprId) -> ExprId {
        self.intern(Node::Call(function, argument))
    }

    // ----- inspection ----------------------------------------------------

    /// The nodes reachable from `roots`, children before parents.
    pub fn reachable(&self, roots: &[ExprId]) -> Vec<ExprId> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<ExprId> = roots.to_vec();
        let mut found = Vec::new();
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut seen[id.index()], true) {
                continue;
            }
            found.push(id);
            stack.extend(self.children(id));
        }
        found.sort_unstable();
        found
    }

    /// The nodes reachable from `roots` without passing through a node
    /// that is `known`, children before parents (ascending ids).
    pub fn reachable_where(&self, roots: &[ExprId], known: impl Fn(ExprId) -> bool) -> Vec<ExprId> {
        let mut seen = FxHashSet::default();
        let mut stack: Vec<ExprId> = roots.to_vec();
        let mut found = Vec::new();
        while let Some(id) = stack.pop() {
            if known(id) || !seen.insert(id) {
                continue;
            }
            found.push(id);
            stack.extend(self.children(id));
        }
        found.sort_unstable();
        found
    }

    /// The direct children of a node.
    pub fn children(&self, id: ExprId) -> Vec<ExprId> {
        match self.node(id) {
            Node::Number(_) | Node::Symbol(_) => Vec::new(),
            Node::Add(items) | Node::Mul(items) => items.to_vec(),
            Node::Pow(base, _) => vec![*base],
            Node::Call(_, argument) => vec![*argument],
        }
    }

    /// True when `id` mentions the symbol.
    pub fn depends_on(&self, id: ExprId, symbol: SymbolId) -> bool {
        self.reachable(&[id])
            .into_iter()
            .any(|n| matches!(self.node(n), Node::Symbol(s) if *s == symbol))
    }

    /// The symbols an expression mentions, sorted.
    pub fn free_symbols(&self, id: ExprId) -> Vec<SymbolId> {
        let mut symbols: Vec<SymbolId> = self
            .reachable(&[id])
            .into_iter()
            .filter_map(|n| match self.node(n) {
                Node::Symbol(s) => Some(*s),
                _ => None,
            })
            .collect();
        symbols.sort_unstable();
        symbols.dedup();
        symbols
    }

    /// A printable view of an expression (`m*r^2 - sin(phi)`).
    pub fn display(&self, id: ExprId) -> Displayed<'_> {
        Displayed { store: self, id }
    }
}

/// Prints an expression with the fewest parentheses the grammar needs.
pub struct Displayed<'a> {
    store: &'a Store,
    id: ExprId,
}

/// Binding strength used by the printer: sum < product < power < atom.
const SUM: u8 = 1;
const PRODUCT: u8 = 2;
const POWER: u8 = 3;

impl Displayed<'_> {
    fn write(&self, f: &mut fmt::Formatter<'_>, id: ExprId, context: u8) -> fmt::Result {
        let strength = self.strength(id);
        if strength < context {
            write!(f, "(")?;
            self.write_node(f, id)?;
            write!(f, ")")
        } else {
            self.write_node(f, id)
        }
    }

    fn strength(&self, id: ExprId) -> u8 {
        match self.store.node(id) {
            Node::Add(_) => SUM,
            Node::Mul(_) => PRODUCT,
            Node::Number(v) if v.is_negative() => SUM,
            Node::Number(v) if !v.is_integer() => PRODUCT,
            Node::Pow(_, exponent) if exponent.is_negative() => PRODUCT,
            Node::Pow(..) => POWER,
            _ => POWER + 1,
        }
    }

    fn write_node(&self, f: &mut fmt::Formatter<'_>, id: ExprId) -> fmt::Result {
        let store = self.store;
        match store.node(id) {
            Node::Number(value) => write!(f, "{value}"),
            Node::Symbol(symbol) => write!(f, "{}", store.symbol_info(*symbol).name),
            Node::Add(terms) => self.write_sum(f, terms),
            Node::Mul(factors) => self.write_product(f, factors),
            Node::Pow(_, exponent) if exponent.is_negative() => {
                write!(f, "1/")?;
                self.write_reciprocal(f, id, POWER)
            }
            Node::Pow(base, exponent) => {
                self.write(f, *base, POWER + 1)?;
                if exponent.is_integer() && !exponent.is_negative() {
                    write!(f, "^{exponent}")
                } else {
                    write!(f, "^({exponent})")
                }
            }
            Node::Call(function, argument) => {
                write!(f, "{}(", function.name())?;
                self.write(f, *argument, 0)?;
                write!(f, ")")
            }
        }
    }

    fn write_sum(&self, f: &mut fmt::Formatter<'_>, terms: &[ExprId]) -> fmt::Result {
        for (i, &term) in terms.iter().enumerate() {
            let negated = self.negated_term(term);
            match (i, negated.is_some()) {
                (0, true) => write!(f, "-")?,
                (0, false) => {}
                (_, true) => write!(f, " - ")?,
                (_, false) => write!(f, " + ")?,
            }
            match negated {
                Some(NegatedTerm::Number(value)) => write!(f, "{value}")?,
                Some(NegatedTerm::Product(coefficient, rest)) => {
                    if !coefficient.is_one() {
                        write!(f, "{coefficient}*")?;
                    }
                    self.write_factors(f, rest)?;
                }
                None => self.write(f, term, SUM)?,
            }
        }
        Ok(())
    }

    fn negated_term<'s>(&'s self, term: ExprId) -> Option<NegatedTerm<'s>> {
        match self.store.node(term) {
            Node::Number(v) if v.is_negative() => Some(NegatedTerm::Number(v.neg())),
            Node::Mul(factors) => match self.store.node(factors[0]) {
                Node::Number(v) if v.is_negative() => {
                    Some(NegatedTerm::Product(v.neg(), &factors[1..]))
                }
                _ => None,
            },
            _ => None,
        }
    }

    fn write_product(&self, f: &mut fmt::Formatter<'_>, factors: &[ExprId]) -> fmt::Result {
        if let Node::Number(v) = self.store.node(factors[0])
            && v == &Rational::integer(-1)
        {
            write!(f, "-")?;
            return self.write_factors(f, &factors[1..]);
        }
        self.write_factors(f, factors)
    }

    /// `a*b/(c*d^2)`: factors with negative exponents form the denominator.
    fn write_factors(&self, f: &mut fmt::Formatter<'_>, factors: &[ExprId]) -> fmt::Result {
        let (denominator, numerator): (Vec<ExprId>, Vec<ExprId>) = factors.iter().partition(
            |&&factor| matches!(self.store.node(factor), Node::Pow(_, e) if e.is_negative()),
        );
        if numerator.is_empty() {
            write!(f, "1")?;
        }
        self.write_joined(f, &numerator, PRODUCT + 1, |display, f, factor, context| {
            display.write(f, factor, context)
        })?;
        match denominator.as_slice() {
            [] => Ok(()),
            [single] => {
                write!(f, "/")?;
                self.write_reciprocal(f, *single, POWER)
            }
            _ => {
                write!(f, "/(")?;
                self.write_joined(f, &denominator, PRODUCT + 1, Displayed::write_reciprocal)?;
                write!(f, ")")
            }
        }
    }

    fn write_joined(
        &self,
        f: &mut fmt::Formatter<'_>,
        factors: &[ExprId],
        context: u8,
        write_one: fn(&Self, &mut fmt::Formatter<'_>, ExprId, u8) -> fmt::Result,
    ) -> fmt::Result {
        for (i, &factor) in factors.iter().enumerate() {
            if i > 0 {
                write!(f, "*")?;
            }
            write_one(self, f, factor, context)?;
        }
        Ok(())
    }

    /// `base^(-e)` written as `base^e`, for use after a `/`.
    fn write_reciprocal(
        &self,
        f: &mut fmt::Formatter<'_>,
        factor: ExprId,
        context: u8,
    ) -> fmt::Result {
        let Node::Pow(base, exponent) = self.store.node(factor) else {
            return self.write(f, factor, context);
        };
        let positive = exponent.neg();
        if positive.is_one() {
            return self.write(f, *base, context.max(PRODUCT + 1));
        }
        self.write(f, *base, POWER + 1)?;
        if positive.is_integer() {
            write!(f, "^{positive}")
        } else {
            write!(f, "^({positive})")
        }
    }
}

enum NegatedTerm<'a> {
    Number(Rational),
    Product(Rational, &'a [ExprId]),
}

impl fmt::Display for Displayed<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, self.id, 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn store_with(names: &[&str]) -> (Store, Vec<ExprId>) {
        let mut store = Store::new();
        let ids = names
            .iter()
            .map(|n| {
                let s = store.declare(n, SymbolKind::Coordinate);
                store.symbol(s)
            })
            .collect();
        (store, ids)
    }

    #[test]
    fn equal_expressions_share_one_node() {
        let (mut s, v) = store_with(&["x", "y"]);
        let a = s.add2(v[0], v[1]);
        let b = s.add2(v[1], v[0]);
        assert_eq!(a, b);
        let before = s.len();
        let c = s.add2(v[0], v[1]);
        assert_eq!(c, a);
        assert_eq!(s.len(), before);
        for id in s.reachable(&[a]) {
            assert!(s.children(id).iter().all(|c| c < &id));
        }
    }

    #[test]
    fn like_terms_and_powers_collect() {
        let (mut s, v) = store_with(&["x"]);
        let two = s.integer(2);
        let two_x = s.mul2(two, v[0]);
        let sum = s.add(&[v[0], two_x, v[0]]);
        assert_eq!(s.display(sum).to_string(), "4*x");
        let cancelled = s.sub(sum, sum);
        assert_eq!(s.as_number(cancelled), Some(&Rational::ZERO));
        let square = s.mul2(v[0], v[0]);
        assert_eq!(s.display(square).to_string(), "x^2");
        let inverse = s.div(v[0], square).unwrap();
        assert_eq!(s.display(inverse).to_string(), "1/x");
        let three = s.integer(3);
        let ratio = s.div(three, square).unwrap();
        assert_eq!(s.display(ratio).to_string(), "3/x^2");
    }

    #[test]
    fn constant_powers_fold_exactly_or_fail_cleanly() {
        let mut s = Store::new();
        let nine = s.integer(9);
        let half = Rational::new(1, 2).unwrap();
        let three = s.pow(nine, half.clone()).unwrap();
        assert_eq!(s.as_number(three), Some(&Rational::integer(3)));
        let two = s.integer(2);
        let root_two = s.pow(two, half.clone()).unwrap();
        assert!(matches!(s.node(root_two), Node::Pow(..)));
        let half_again = half.clone();
        let product = s.mul2(root_two, root_two);
        assert_eq!(s.as_number(product), Some(&Rational::integer(2)));
        let minus_four = s.integer(-4);
        assert!(matches!(
            s.pow(minus_four, half_again),
            Err(SymError::NegativeBase { .. })
        ));
        let zero = s.integer(0);
        let one = s.integer(1);
        assert!(matches!(
            s.div(one, zero),
            Err(SymError::DivisionByZero { .. })
        ));
        assert!(matches!(
            s.apply_named("sinh", one),
            Err(SymError::UnknownFunction { .. })
        ));
        assert!(matches!(
            s.apply(Function::Ln, zero),
            Err(SymError::Undefined { .. })
        ));
    }

    #[test]
    fn distributed_powers_of_products_collect_again() {
        let (mut s, v) = store_with(&["x"]);
        let two = s.integer(2);
        let two_x = s.mul2(two, v[0]);
        let root = s.sqrt(two_x).unwrap();
        let square = s.mul2(root, root);
        assert_eq!(square, two_x);
        let cancelled = s.sub(square, two_x);
        assert_eq!(s.as_number(cancelled), Some(&Rational::ZERO));
        let three = s.integer(3);
        let triple = s.mul(&[three, root, root, v[0]]);
        assert_eq!(s.display(triple).to_string(), "6*x^2");
    }

    #[test]
    fn display_prints_signs_and_parentheses() {
        let (mut s, v) = store_with(&["x", "y"]);
        let sum = s.add2(v[0], v[1]);
        let minus_y = s.neg(v[1]);
        let difference = s.add2(v[0], minus_y);
        let product = s.mul2(sum, difference);
        let text = s.display(product).to_string();
        assert!(
            text == "(x + y)*(x - y)" || text == "(x - y)*(x + y)",
            "{text}"
        );
        let sine = s.apply(Function::Sin, sum).unwrap();
        assert_eq!(s.display(sine).to_string(), "sin(x + y)");
    }
}
