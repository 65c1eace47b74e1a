//! Tests of the expression store: sharing, collection, folding, printing.

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
        s.apply_named("sinh", &[one]),
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
