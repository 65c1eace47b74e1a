//! Inputs the fuzz targets (`fuzz/`, see `FUZZING.md`) found to hang or
//! crash the engine, each kept as a test of its fix.

use chaplygin_codegen::generate;
use chaplygin_codegen::sym::{
    Budget, Context, ExprId, MAX_DEGREE, Node, Rational, Store, SymError, SymbolKind,
};

/// `normal_form` timeout: `(-6)^4` raised to the 4th power again and again
/// reaches `6^(4^9)`, a 677,000-bit constant whose exact folding took minutes.
/// `6^(4^k)` has `4^k * log2(6)` bits: 42,353 for k = 7 (under the limit of
/// 65,536), 169,413 for k = 8 (over it), so exactly seven folds succeed.
#[test]
fn a_tower_of_constant_powers_is_rejected_not_computed() {
    let mut store = Store::new();
    let mut power = store.integer(6);
    let mut folds = 0;
    let error = loop {
        match store.pow(power, Rational::integer(4)) {
            Ok(next) => {
                power = next;
                folds += 1;
            }
            Err(error) => break error,
        }
    };
    assert_eq!(folds, 7);
    assert!(
        matches!(error, SymError::ConstantTooLarge { .. }),
        "{error:?}"
    );
}

/// The same tower written in a model is one diagnostic.
#[test]
fn a_model_with_a_tower_of_constant_powers_is_diagnosed() {
    let text = "pub struct Tower { coordinates: [x], \
                kinetic_energy: ((((((((((6^4)^4)^4)^4)^4)^4)^4)^4)^4)*dot(x)^2) }";
    let diagnostics = generate(text).expect_err("the constant is too large");
    let rendered = diagnostics.render("tower.model");
    assert!(rendered.contains("a constant of about"), "{rendered}");
}

/// A sum or product of constants is held to the same limit as a power:
/// squaring `a = 7^14000` (39,304 bits) by products, `b = a*a` and on,
/// doubled its bits at each definition, and the compile ran for more than
/// a minute. `a*a` itself, 78,607 bits, is the one diagnostic, on its `*`.
#[test]
fn a_model_squaring_a_big_constant_by_products_is_diagnosed() {
    let text = "pub struct Squares { coordinates: [x], define: [a = 7^14000, b = a*a, \
                c = b*b, d = c*c, e = d*d, f = e*e, g = f*f, h = g*g, i = h*h, j = i*i, \
                k = j*j, l = k*k, n = l*l], kinetic_energy: (1 + n)*dot(x)^2 }";
    assert_constant_too_large_at(text, "*a,");
}

/// Sums too: `2^-20000 + 3^-20000`, each under the limit, has the product
/// of their coprime denominators for its own, 83,400 bits in all, and is
/// diagnosed on its `+` instead of being squared on for more than a minute.
#[test]
fn a_model_adding_constants_with_big_coprime_denominators_is_diagnosed() {
    let text = "pub struct Sums { coordinates: [x], define: [a = 2^-20000, b = 3^-20000, \
                c = a + b, d = c*c, e = d*d, f = e*e, g = f*f, h = g*g, i = h*h, j = i*i, \
                k = j*j, l = k*k, n = l*l], kinetic_energy: (1 + n)*dot(x)^2 }";
    assert_constant_too_large_at(text, "+ b");
}

/// The constant factor of a product is held to the limit as a constant is:
/// `p = x*a` squared is `a^2 x^2`, whose factor `a^2` has 78,607 bits.
/// Squared on, the constant took a minute to reach a mass matrix that is not
/// positive definite in `f64`.
#[test]
fn a_model_squaring_a_coordinate_times_a_big_constant_is_diagnosed() {
    let text = "pub struct Scaled { coordinates: [x], define: [a = 7^14000, p = x*a, \
                q = p*p, r = q*q, s = r*r, t = s*s, u = t*t, v = u*u, w = v*v, z = w*w, \
                zz = z*z, zzz = zz*zz], kinetic_energy: (1 + zzz)*dot(x)^2 }";
    assert_constant_too_large_at(text, "*p,");
}

/// In a mechanism's points, vectors scaled by a big constant twice, and the
/// inner product of a vector with a big component with itself, are held to
/// the limit as scalars are; squared on through the points, the constants
/// were folded into code for 18 s.
#[test]
fn a_mechanism_squaring_a_big_constant_is_diagnosed() {
    let points = [
        ("p = origin + a*(a*ground.x)", "*(a*ground.x)"),
        (
            "p = origin + inner(o - origin, o - origin)*ground.x",
            "inner(o - origin",
        ),
    ];
    for (point, at) in points {
        let text = format!(
            "pub struct Points {{ coordinates: [x], parameters: [m = 1.0], \
             define: [a = 7^14000], frames: [f = rotate(ground, z, x)], \
             points: [o = origin + a*ground.x, {point}, \
             q = origin + inner(p - origin, p - origin)*ground.x, \
             r = origin + inner(q - origin, q - origin)*ground.x, \
             s = origin + inner(r - origin, r - origin)*ground.x, \
             t = origin + inner(s - origin, s - origin)*ground.x, \
             u = origin + inner(t - origin, t - origin)*ground.x, \
             w = origin + inner(u - origin, u - origin)*ground.x, \
             y = origin + inner(w - origin, w - origin)*ground.x, \
             z = origin + inner(y - origin, y - origin)*ground.x], \
             bodies: [b = body(f, z, m, diag(1, 1, 1))] }}"
        );
        assert_constant_too_large_at(&text, at);
    }
}

/// Asserts that `text`, one line, is diagnosed with one constant too large,
/// at the token where `at` (found once in `text`) begins.
fn assert_constant_too_large_at(text: &str, at: &str) {
    let diagnostics = generate(text).expect_err("a constant is too large");
    let rendered = diagnostics.render("model");
    let column = text.find(at).expect("`at` is in the text") + 1;
    assert_eq!(diagnostics.len(), 1, "{rendered}");
    assert!(
        rendered.starts_with(&format!("model:1:{column}: error: a constant of about ")),
        "{rendered}"
    );
}

/// `normal_form` wrong value: the normal form of `(x^412316860416 - x)^3`
/// squared `x` on to `x^(2^32)`, past its `u32` exponents, which wrapped to
/// `x^0`, and so expanded `(1 - x)^3`: 0.027 at `x = 0.7` for the tree's
/// -0.343. A degree past `MAX_DEGREE` is now an error.
#[test]
fn a_power_past_the_degree_limit_is_rejected_not_wrapped() {
    let (mut cx, x) = context_with_x();
    let power = |cx: &mut Context, base, n: i64| cx.pow(base, Rational::integer(n)).unwrap();
    let high = power(&mut cx, x, 412_316_860_416);
    let difference = cx.sub(high, x);
    let cube = power(&mut cx, difference, 3);
    let degree_too_large = Err(SymError::DegreeTooLarge { limit: MAX_DEGREE });
    assert_eq!(cx.normal(cube), degree_too_large);

    let (mut cx, x) = context_with_x();
    let at_the_limit = power(&mut cx, x, i64::from(MAX_DEGREE));
    let form = cx
        .normal(at_the_limit)
        .expect("the limit itself is allowed");
    assert_eq!(cx.evaluate_normal(&form, &|_| 1.0), 1.0);
    assert_eq!(form.numerator().degree_in(form.atoms()[0]), MAX_DEGREE);
}

/// The same bound on a denominator factor's multiplicity: `(x + 1)^-80000`
/// squares the factor's multiplicity up past `MAX_DEGREE`.
#[test]
fn a_denominator_past_the_degree_limit_is_rejected() {
    let (mut cx, x) = context_with_x();
    let one = cx.integer(1);
    let sum = cx.add2(x, one);
    let power = cx.pow(sum, Rational::integer(-80_000)).unwrap();
    assert_eq!(
        cx.normal(power),
        Err(SymError::DegreeTooLarge { limit: MAX_DEGREE })
    );
}

/// In a model, the degree past the limit is one diagnostic.
#[test]
fn a_model_with_a_power_past_the_degree_limit_is_diagnosed() {
    let text = "pub struct High { coordinates: [x], \
                kinetic_energy: (1 + (x^412316860416 - x)^2)*dot(x)^2 }";
    let diagnostics = generate(text).expect_err("the degree is too high");
    let rendered = diagnostics.render("high.model");
    assert!(
        rendered.contains("the normal form needs a power of degree above 65536"),
        "{rendered}"
    );
}

/// `jit` stack overflow: five constants raised to the 7776th power, summed,
/// and the sum squared, a constant of 82,767 and 71,306 bits (numerator and
/// denominator, by Python's `fractions`) whose continued fraction has
/// 41,614 partial quotients; `num_rational`'s hash, which the store's
/// hash-consing called, walked them one stack frame each and overflowed a
/// test thread's stack.
#[test]
fn a_square_of_a_sum_of_large_constant_powers_is_folded() {
    let mut store = Store::new();
    let powers: Vec<ExprId> = [(3, 4), (2, 3), (5, 4), (7, 8), (5, 3)]
        .into_iter()
        .map(|(n, d)| {
            let base = store.number(Rational::new(n, d).expect("a fraction"));
            store
                .pow(base, Rational::integer(7776))
                .expect("within the limit")
        })
        .collect();
    let sum = powers[1..]
        .iter()
        .fold(powers[0], |sum, &power| store.add2(sum, power));
    let square = store.mul2(sum, sum);
    let Node::Number(value) = store.node(square) else {
        panic!("constants fold to a constant");
    };
    assert_eq!(value.bits(), 82_767 + 71_306);
}

/// `jit` timeout: a rational power of a perfect power, `4^(p/2) = 2^p`, was
/// folded whatever the size of `p` (the limit on constant powers held for
/// integer exponents only); `p = 3^30`, some 2e14 bits, now fails at once.
#[test]
fn a_rational_power_of_a_perfect_power_is_limited_too() {
    let mut store = Store::new();
    let four = store.integer(4);
    let huge = Rational::new(3_i64.pow(30), 2).expect("a fraction");
    assert!(matches!(
        store.pow(four, huge),
        Err(SymError::ConstantTooLarge { .. })
    ));
    let small = store
        .pow(four, Rational::new(5, 2).expect("a fraction"))
        .expect("within the limit");
    assert_eq!(store.as_number(small), Some(&Rational::integer(32)));
}

/// `normal_form` timeout: `-2 + x^-3/(y^-3 + x^5/(x + 7^-1875) +
/// (x^5 + 1)^-75)` ran for minutes in the exact divisions of its sum, whose
/// coefficients carry 7^1875 (5,264 bits): their steps were charged by terms
/// alone. Weighted by the coefficients' words as products are, they spend
/// the target's budget of 200,000 at once.
#[test]
fn an_exact_division_with_big_coefficients_is_charged_for_them() {
    let mut cx = Context::with_budget(Budget::new(200_000));
    let x = cx.declare("x", SymbolKind::Coordinate);
    let (x, y) = (cx.symbol(x), cx.declare("y", SymbolKind::Coordinate));
    let y = cx.symbol(y);
    let power = |cx: &mut Context, base, n: i64| cx.pow(base, Rational::integer(n)).unwrap();
    let tiny = cx.number(Rational::integer(-7).powi(-1875).expect("nonzero"));
    let shifted = cx.add2(x, tiny);
    let fifth = power(&mut cx, x, 5);
    let quotient = cx.div(fifth, shifted).unwrap();
    let one = cx.integer(1);
    let sum = cx.add2(fifth, one);
    let far = power(&mut cx, sum, -75);
    let inverse_cube = power(&mut cx, y, -3);
    let inner = cx.add2(inverse_cube, quotient);
    let denominator = cx.add2(inner, far);
    let inverse = power(&mut cx, x, -3);
    let ratio = cx.div(inverse, denominator).unwrap();
    let minus_two = cx.integer(-2);
    let whole = cx.add2(minus_two, ratio);
    assert_eq!(
        cx.normal(whole),
        Err(SymError::BudgetExceeded { limit: 200_000 })
    );
}

/// A fresh context with the coordinate `x`, and `x`.
fn context_with_x() -> (Context, ExprId) {
    let mut cx = Context::new();
    let x = cx.declare("x", SymbolKind::Coordinate);
    let x = cx.symbol(x);
    (cx, x)
}
