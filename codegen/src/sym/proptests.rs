//! Property tests on random expression trees: the normal form keeps the
//! value, and both derivatives agree with central finite differences.

use super::{
    Budget, Context, Decision, ExprId, Function, Rational, SymError, SymbolId, SymbolKind,
};
use proptest::prelude::*;

/// A recipe for a random expression over `x`, `y` (coordinates) and `m` (parameter).
#[derive(Clone, Debug)]
enum Recipe {
    Symbol(usize),
    Constant(i64, i64),
    Add(Box<Recipe>, Box<Recipe>),
    Sub(Box<Recipe>, Box<Recipe>),
    Mul(Box<Recipe>, Box<Recipe>),
    /// `a / (b^2 + 1)`: the divisor never vanishes.
    DivSafe(Box<Recipe>, Box<Recipe>),
    Pow(Box<Recipe>, i64),
    /// `sqrt(a^2 + 1)`.
    SqrtSafe(Box<Recipe>),
    Sin(Box<Recipe>),
    Cos(Box<Recipe>),
    /// `sin` of an integer combination of coordinates, to exercise expansion.
    SinOfSum(i64, i64),
    CosOfSum(i64, i64),
    Exp(Box<Recipe>),
    Atan(Box<Recipe>),
    /// `asin(a / (a^2 + 1))`: the argument stays within `[-1/2, 1/2]`.
    AsinSafe(Box<Recipe>),
    /// `acos(a / (a^2 + 1))`.
    AcosSafe(Box<Recipe>),
    Atan2(Box<Recipe>, Box<Recipe>),
}

fn recipe() -> impl Strategy<Value = Recipe> {
    let leaf = prop_oneof![
        (0usize..3).prop_map(Recipe::Symbol),
        (-5i64..6, 1i64..4).prop_map(|(n, d)| Recipe::Constant(n, d)),
        (-2i64..3, -2i64..3).prop_map(|(a, b)| Recipe::SinOfSum(a, b)),
        (-2i64..3, -2i64..3).prop_map(|(a, b)| Recipe::CosOfSum(a, b)),
    ];
    // Powers, divisors and the inverse functions (whose slopes divide by
    // their argument squared) take leaves: nested powers of trigonometric
    // sums expand exponentially in any expanded normal form, unlike the
    // expressions mechanics produces (polynomials of low degree in sin q_i,
    // cos q_i).
    let small = leaf.clone();
    leaf.prop_recursive(4, 24, 2, move |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| Recipe::Add(a.into(), b.into())),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| Recipe::Sub(a.into(), b.into())),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| Recipe::Mul(a.into(), b.into())),
            (inner.clone(), small.clone()).prop_map(|(a, b)| Recipe::DivSafe(a.into(), b.into())),
            (small.clone(), 0i64..4).prop_map(|(a, n)| Recipe::Pow(a.into(), n)),
            inner.clone().prop_map(|a| Recipe::SqrtSafe(a.into())),
            inner.clone().prop_map(|a| Recipe::Sin(a.into())),
            inner.clone().prop_map(|a| Recipe::Cos(a.into())),
            inner.prop_map(|a| Recipe::Exp(a.into())),
            small.clone().prop_map(|a| Recipe::Atan(a.into())),
            small.clone().prop_map(|a| Recipe::AsinSafe(a.into())),
            small.clone().prop_map(|a| Recipe::AcosSafe(a.into())),
            (small.clone(), small.clone()).prop_map(|(a, b)| Recipe::Atan2(a.into(), b.into())),
        ]
    })
}

struct Built {
    store: Context,
    symbols: [SymbolId; 3],
    root: ExprId,
}

fn build(recipe: &Recipe) -> Built {
    build_within(recipe, Budget::default())
}

fn build_within(recipe: &Recipe, budget: Budget) -> Built {
    let mut store = Context::with_budget(budget);
    let symbols = [
        store.declare("x", SymbolKind::Coordinate),
        store.declare("y", SymbolKind::Coordinate),
        store.declare("m", SymbolKind::Parameter),
    ];
    let root = construct(&mut store, &symbols, recipe);
    Built {
        store,
        symbols,
        root,
    }
}

fn plus_one_square(store: &mut Context, e: ExprId) -> ExprId {
    let square = store.mul2(e, e);
    let one = store.integer(1);
    store.add2(square, one)
}

fn construct(store: &mut Context, symbols: &[SymbolId; 3], recipe: &Recipe) -> ExprId {
    let go = |store: &mut Context, r: &Recipe| construct(store, symbols, r);
    match recipe {
        Recipe::Symbol(i) => store.symbol(symbols[*i]),
        Recipe::Constant(n, d) => store.number(Rational::new(*n, *d).unwrap_or(Rational::ONE)),
        Recipe::Add(a, b) => {
            let (a, b) = (go(store, a), go(store, b));
            store.add2(a, b)
        }
        Recipe::Sub(a, b) => {
            let (a, b) = (go(store, a), go(store, b));
            store.sub(a, b)
        }
        Recipe::Mul(a, b) => {
            let (a, b) = (go(store, a), go(store, b));
            store.mul2(a, b)
        }
        Recipe::DivSafe(a, b) => {
            let a = go(store, a);
            let b = go(store, b);
            let divisor = plus_one_square(store, b);
            store
                .div(a, divisor)
                .expect("b^2 + 1 is never the constant zero")
        }
        Recipe::Pow(a, n) => {
            let a = go(store, a);
            store
                .pow(a, Rational::integer(*n))
                .expect("non-negative power")
        }
        Recipe::SqrtSafe(a) => {
            let a = go(store, a);
            let radicand = plus_one_square(store, a);
            store.sqrt(radicand).expect("positive radicand")
        }
        Recipe::Sin(a) | Recipe::Cos(a) | Recipe::Exp(a) | Recipe::Atan(a) => {
            let a = go(store, a);
            let function = match recipe {
                Recipe::Sin(_) => Function::Sin,
                Recipe::Cos(_) => Function::Cos,
                Recipe::Atan(_) => Function::Atan,
                _ => Function::Exp,
            };
            store
                .apply(function, a)
                .expect("sin, cos, exp, atan are total")
        }
        Recipe::AsinSafe(a) | Recipe::AcosSafe(a) => {
            let a = go(store, a);
            let divisor = plus_one_square(store, a);
            let ratio = store.div(a, divisor).expect("a^2 + 1 is never zero");
            let function = match recipe {
                Recipe::AsinSafe(_) => Function::Asin,
                _ => Function::Acos,
            };
            store
                .apply(function, ratio)
                .expect("the ratio lies in [-1/2, 1/2]")
        }
        Recipe::Atan2(a, b) => {
            let (a, b) = (go(store, a), go(store, b));
            let divisor = plus_one_square(store, b);
            store.atan2(a, divisor).expect("b^2 + 1 is never zero")
        }
        Recipe::SinOfSum(p, q) | Recipe::CosOfSum(p, q) => {
            let (x, y) = (store.symbol(symbols[0]), store.symbol(symbols[1]));
            let (p, q) = (store.integer(*p), store.integer(*q));
            let (px, qy) = (store.mul2(p, x), store.mul2(q, y));
            let sum = store.add2(px, qy);
            let function = if matches!(recipe, Recipe::SinOfSum(..)) {
                Function::Sin
            } else {
                Function::Cos
            };
            store.apply(function, sum).expect("sin, cos are total")
        }
    }
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs()).max(1.0)
}

fn point(values: [f64; 3], symbols: [SymbolId; 3]) -> impl Fn(SymbolId) -> f64 {
    move |s| {
        symbols
            .iter()
            .position(|&t| t == s)
            .map_or(0.0, |i| values[i])
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x0c4a_91f9),
        ..ProptestConfig::default()
    })]

    #[test]
    fn normal_form_preserves_the_value(r in recipe(), x in 0.2f64..1.5, y in -1.0f64..1.0, m in 0.5f64..2.0) {
        let mut built = build(&r);
        let at = point([x, y, m], built.symbols);
        let original = built.store.evaluate(built.root, &at);
        prop_assume!(original.is_finite() && original.abs() < 1e8);
        let simplified = built.store.simplify(built.root).expect("no division by zero in recipes");
        let value = built.store.evaluate(simplified, &at);
        prop_assert!(close(original, value, 1e-8), "{original} vs {value}");
    }

    #[test]
    fn tree_derivative_matches_central_differences(r in recipe(), x in 0.2f64..1.5, y in -1.0f64..1.0, m in 0.5f64..2.0) {
        let mut built = build(&r);
        let symbols = built.symbols;
        let h = 1e-5;
        let value_at = |built: &Built, dx: f64| built.store.evaluate(built.root, &point([x + dx, y, m], symbols));
        let difference = (value_at(&built, h) - value_at(&built, -h)) / (2.0 * h);
        prop_assume!(difference.is_finite() && difference.abs() < 1e4 && value_at(&built, 0.0).abs() < 1e4);
        let tree = built.store.derivative(built.root, symbols[0]);
        let tree_value = built.store.evaluate(tree, &point([x, y, m], symbols));
        prop_assert!(close(tree_value, difference, 1e-5), "tree {tree_value} vs fd {difference}");
    }

    /// The normal form's own differentiation (atom by atom, quotient rule on
    /// the factored denominator) equals the tree derivative: exactly on the
    /// normal form's class, numerically where kernels (`sqrt`, `exp`) enter.
    #[test]
    fn normal_form_derivative_equals_tree_derivative(r in recipe()) {
        let mut built = build(&r);
        let x = built.symbols[0];
        let tree = built.store.derivative(built.root, x);
        let form = built.store.normal(built.root).expect("recipes are well defined");
        let d_form = built.store.derivative_of_normal(&form, x).expect("derivative exists");
        let rebuilt = built.store.expression_of(&d_form);
        let difference = built.store.sub(tree, rebuilt);
        let test = built.store.zero_test(difference).expect("difference is well defined");
        prop_assert!(test.is_zero, "{:?}", test);
        if !recipe_has_kernels(&r) {
            prop_assert_eq!(test.decided_by, Decision::NormalForm);
        }
    }

    /// A budget never changes a normal form: within any limit the result is
    /// the unlimited one or `BudgetExceeded`, and the unlimited run's count
    /// is exactly the smallest limit that suffices.
    #[test]
    fn a_budget_gives_the_normal_form_or_budget_exceeded(r in recipe(), share in 0.0f64..1.0) {
        let unlimited = Budget::new(u64::MAX / 2);
        let mut reference = build_within(&r, unlimited.clone());
        let expected = reference.store.normal(reference.root).expect("recipes are well defined");
        let limit = (unlimited.used() as f64 * share) as u64;
        let mut limited = build_within(&r, Budget::new(limit));
        match limited.store.normal(limited.root) {
            Ok(form) => {
                prop_assert_eq!(form, expected);
                prop_assert!(limit >= unlimited.used());
            }
            Err(error) => {
                prop_assert_eq!(error, SymError::BudgetExceeded { limit });
                prop_assert!(limit < unlimited.used());
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x6d0d_0a17),
        ..ProptestConfig::default()
    })]

    /// Evaluation modulo a prime agrees with the normal form: an expression
    /// and its normal form have the same residue at a random point, and the
    /// residue is zero exactly when the normal form is.
    #[test]
    fn modular_values_agree_with_the_normal_form(r in recipe(), seed in 0u64..1000) {
        let mut built = build(&r);
        let point = super::modular::Point::new(seed);
        let original = built.store.evaluate_modular(&[built.root], &point);
        prop_assume!(original.is_ok(), "outside the class");
        let original = original.unwrap_or_default();
        let form = built.store.normal(built.root).expect("recipes are well defined");
        let simplified = built.store.expression_of(&form);
        match built.store.evaluate_modular(&[simplified], &point) {
            Ok(value) => prop_assert_eq!(value, original.clone()),
            Err(super::modular::ModularError::Undefined { .. }) => {}
            Err(outside) => prop_assert!(false, "the normal form left the class: {outside}"),
        }
        prop_assert_eq!(form.is_zero(), original[0] == 0);
    }
}

/// True when the recipe uses `sqrt`, `exp` or an inverse function, whose
/// kernels lie outside the exact class (`sqrt(u)^2 = u` is applied by the
/// normal form, but whether `u` is a square, which a zero test would need,
/// is not decided).
fn recipe_has_kernels(recipe: &Recipe) -> bool {
    match recipe {
        Recipe::SqrtSafe(_)
        | Recipe::Exp(_)
        | Recipe::Atan(_)
        | Recipe::AsinSafe(_)
        | Recipe::AcosSafe(_)
        | Recipe::Atan2(..) => true,
        Recipe::Symbol(_) | Recipe::Constant(..) | Recipe::SinOfSum(..) | Recipe::CosOfSum(..) => {
            false
        }
        Recipe::Add(a, b) | Recipe::Sub(a, b) | Recipe::Mul(a, b) | Recipe::DivSafe(a, b) => {
            recipe_has_kernels(a) || recipe_has_kernels(b)
        }
        Recipe::Pow(a, _) | Recipe::Sin(a) | Recipe::Cos(a) => recipe_has_kernels(a),
    }
}
