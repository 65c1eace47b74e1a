//! The hash-consed expression store.
//!
//! Every expression lives in one [`Store`] and is named by an [`ExprId`]. Nodes
//! are interned: building the same node twice returns the same id, so equal
//! sub-expressions are shared, and children always have smaller ids than their
//! parents (the store is a topologically sorted DAG). Constructors apply only
//! cheap, always-valid rewrites (flattening, constant folding, collecting
//! `c*x + d*x` and `x^a * x^b`, sorting operands); the canonical form used for
//! exact zero tests lives in [`super::normal`], and the store's
//! [`Context`](super::context::Context) computes and memoizes each
//! expression's normal form.

mod arithmetic;
mod display;
#[cfg(test)]
mod tests;

pub use super::ids::{ExprId, SymbolId};
pub use display::Displayed;

use super::number::Rational;
use rustc_hash::{FxHashMap as HashMap, FxHashSet};
use std::fmt;

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

/// The elementary functions of one argument the engine knows (`sqrt` is
/// stored as a power 1/2, `atan2(y, x)` as a node of its own,
/// [`Node::Atan2`]).
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
    /// Inverse sine, in `[-pi/2, pi/2]`.
    Asin,
    /// Inverse cosine, in `[0, pi]`.
    Acos,
    /// Inverse tangent, in `(-pi/2, pi/2)`.
    Atan,
}

/// The functions of the model language with the number of arguments each
/// takes.
pub const FUNCTION_ARITIES: [(&str, usize); 10] = [
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("sqrt", 1),
    ("exp", 1),
    ("ln", 1),
    ("asin", 1),
    ("acos", 1),
    ("atan", 1),
    ("atan2", 2),
];

/// The functions of the model language as messages list them.
pub const FUNCTION_LIST: &str = "sin, cos, tan, sqrt, exp, ln, asin, acos, atan, atan2(y, x)";

/// The number of arguments the model-language function `name` takes
/// (`None` for a name that is no function).
pub fn arity(name: &str) -> Option<usize> {
    FUNCTION_ARITIES
        .iter()
        .find(|(known, _)| *known == name)
        .map(|&(_, count)| count)
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
            Function::Asin => "asin",
            Function::Acos => "acos",
            Function::Atan => "atan",
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
            Function::Asin => x.asin(),
            Function::Acos => x.acos(),
            Function::Atan => x.atan(),
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
    /// `atan2(y, x)`: the angle of the point `(x, y)`, in `(-pi, pi]`.
    Atan2(ExprId, ExprId),
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
    #[error("unknown function `{name}`; the functions are {FUNCTION_LIST}")]
    UnknownFunction {
        /// The name as written.
        name: String,
    },
    /// A function called with a number of arguments it does not take.
    #[error("`{name}` takes {expected} argument{}, found {found}", plural(*expected))]
    ArgumentCount {
        /// The function's name.
        name: String,
        /// How many arguments it takes.
        expected: usize,
        /// How many were given.
        found: usize,
    },
    /// A function outside its domain at a constant argument, e.g. `ln(0)`.
    #[error("{expr} is undefined")]
    Undefined {
        /// The application, printed.
        expr: String,
    },
    /// A power, sum or product of constants too large to compute exactly.
    #[error(
        "a constant of about {bits} bits, past the limit of {MAX_CONSTANT_BITS} on powers, \
         sums and products of constants; write smaller numbers"
    )]
    ConstantTooLarge {
        /// The size of the constant in bits (estimated for a power).
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
    /// The normal form needed a polynomial of higher degree in one atom, or
    /// a denominator factor of higher multiplicity, than
    /// [`super::budget::MAX_DEGREE`].
    #[error(
        "the normal form needs a power of degree above {limit} (the limit); write a lower power"
    )]
    DegreeTooLarge {
        /// The limit that was passed.
        limit: u32,
    },
}

/// The suffix of a count's noun: `s` but for one.
fn plural(count: usize) -> &'static str {
    if count == 1 { "" } else { "s" }
}

/// The largest constant, in bits (about 20,000 decimal digits), that a
/// power of a constant folds to or a sum or product built from input holds
/// ([`Store::within_constant_limit`]); larger ones are rejected rather than
/// computed.
pub const MAX_CONSTANT_BITS: u64 = 1 << 16;

/// The expression arena with its symbol table.
#[derive(Default, Clone)]
pub struct Store {
    nodes: Vec<Node>,
    interned: HashMap<Node, ExprId>,
    symbols: Vec<Symbol>,
    symbol_index: HashMap<String, SymbolId>,
    velocities: HashMap<SymbolId, SymbolId>,
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
            Node::Atan2(y, x) => vec![*y, *x],
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
}
