//! Numeric evaluation of expressions in `f64`.
//!
//! Evaluation walks the DAG once, children before parents, so a shared
//! sub-expression is computed once. It is the engine's independent numeric
//! reference: the IR interpreter, the emitted Rust and the randomized zero test
//! are all checked against it.

use super::context::Context;
use super::expr::{ExprId, Node, Store, SymbolId};

impl Store {
    /// The value of `root` with each symbol given by `value_of`.
    pub fn evaluate(&self, root: ExprId, value_of: &dyn Fn(SymbolId) -> f64) -> f64 {
        self.evaluate_many(&[root], value_of)[0]
    }

    /// The values of several roots, sharing the work on common sub-expressions.
    pub fn evaluate_many(&self, roots: &[ExprId], value_of: &dyn Fn(SymbolId) -> f64) -> Vec<f64> {
        let order = self.reachable(roots);
        let mut values =
            rustc_hash::FxHashMap::with_capacity_and_hasher(order.len(), Default::default());
        for &id in &order {
            let value = self.evaluate_node(id, &values, value_of);
            values.insert(id, value);
        }
        roots.iter().map(|r| values[r]).collect()
    }

    fn evaluate_node(
        &self,
        id: ExprId,
        values: &rustc_hash::FxHashMap<ExprId, f64>,
        value_of: &dyn Fn(SymbolId) -> f64,
    ) -> f64 {
        match self.node(id) {
            Node::Number(value) => value.to_f64(),
            Node::Symbol(symbol) => value_of(*symbol),
            Node::Add(terms) => terms.iter().map(|t| values[t]).sum(),
            Node::Mul(factors) => factors.iter().map(|f| values[f]).product(),
            Node::Pow(base, exponent) => power(values[base], exponent),
            Node::Call(function, argument) => function.apply(values[argument]),
            Node::Atan2(y, x) => values[y].atan2(values[x]),
        }
    }
}

impl Context {
    /// The value of a normal form, each atom evaluated through its expression.
    pub fn evaluate_normal(
        &mut self,
        form: &super::RationalFunction,
        value_of: &dyn Fn(SymbolId) -> f64,
    ) -> f64 {
        let atoms = form.atoms();
        let expressions: Vec<ExprId> = atoms.iter().map(|&a| self.expression_of_atom(a)).collect();
        let values = self.evaluate_many(&expressions, value_of);
        let value_of_atom = |atom| atoms.binary_search(&atom).map_or(f64::NAN, |at| values[at]);
        form.evaluate(&value_of_atom)
    }
}

/// `base^exponent`, exact for integer exponents and square roots.
pub(crate) fn power(base: f64, exponent: &super::Rational) -> f64 {
    match exponent.to_small() {
        Some((n, 1)) => match i32::try_from(n) {
            Ok(n) => base.powi(n),
            Err(_) => base.powf(n as f64),
        },
        Some((1, 2)) => base.sqrt(),
        Some((-1, 2)) => 1.0 / base.sqrt(),
        _ => base.powf(exponent.to_f64()),
    }
}

#[cfg(test)]
mod tests {
    use crate::sym::{Function, Rational, Store, SymbolKind};

    #[test]
    fn evaluates_each_node_kind() {
        let mut s = Store::new();
        let x = s.declare("x", SymbolKind::Coordinate);
        let y = s.declare("y", SymbolKind::Parameter);
        let (xe, ye) = (s.symbol(x), s.symbol(y));
        let sine = s.apply(Function::Sin, xe).unwrap();
        let root = s.sqrt(ye).unwrap();
        let cube = s.pow(xe, Rational::integer(3)).unwrap();
        let half = s.number(Rational::new(1, 2).unwrap());
        let product = s.mul(&[half, sine, root]);
        let total = s.add(&[product, cube]);
        let value = s.evaluate(total, &|id| if id == x { 0.7 } else { 2.0 });
        let expected = 0.5 * 0.7f64.sin() * 2.0f64.sqrt() + 0.7f64.powi(3);
        assert!((value - expected).abs() < 1e-15);
    }
}
