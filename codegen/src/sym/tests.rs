//! Exact identities decided by the normal form, cross-checked numerically.

use super::{
    Context, Decision, ExprId, Function, Matrix, NumericZeroTest, RationalFunction, SymbolId,
    SymbolKind,
};
use std::collections::HashMap;

/// A store with the given coordinates and parameters declared.
struct Fixture {
    store: Context,
    symbols: HashMap<&'static str, SymbolId>,
}

impl Fixture {
    fn new(coordinates: &[&'static str], parameters: &[&'static str]) -> Fixture {
        let mut store = Context::new();
        let mut symbols = HashMap::new();
        for &name in coordinates {
            symbols.insert(name, store.declare(name, SymbolKind::Coordinate));
        }
        for &name in parameters {
            symbols.insert(name, store.declare(name, SymbolKind::Parameter));
        }
        Fixture { store, symbols }
    }

    fn var(&mut self, name: &str) -> ExprId {
        let id = self.symbols[name];
        self.store.symbol(id)
    }

    fn velocity(&mut self, name: &str) -> ExprId {
        let id = self.store.velocity_of(self.symbols[name]);
        self.store.symbol(id)
    }

    fn call(&mut self, function: Function, argument: ExprId) -> ExprId {
        self.store.apply(function, argument).unwrap()
    }

    /// Asserts zero by the normal form and by the numeric test.
    fn assert_exactly_zero(&mut self, e: ExprId) {
        let test = self.store.zero_test(e).unwrap();
        assert!(test.is_zero, "{} is not zero", self.store.display(e));
        assert_eq!(test.decided_by, Decision::NormalForm);
        assert!(self.store.numerically_zero(e, &NumericZeroTest::default()));
    }

    /// Asserts non-zero by the normal form and by the numeric test.
    fn assert_exactly_nonzero(&mut self, e: ExprId) {
        let test = self.store.zero_test(e).unwrap();
        assert!(!test.is_zero, "{} is zero", self.store.display(e));
        assert_eq!(test.decided_by, Decision::NormalForm);
        assert!(!self.store.numerically_zero(e, &NumericZeroTest::default()));
    }
}

#[test]
fn pythagoras() {
    let mut f = Fixture::new(&["q"], &[]);
    let q = f.var("q");
    let (s, c) = (f.call(Function::Sin, q), f.call(Function::Cos, q));
    let two = f.store.integer(2);
    let s2 = f.store.pow(s, 2.into()).unwrap();
    let c2 = f.store.pow(c, 2.into()).unwrap();
    let one = f.store.integer(1);
    let sum = f.store.add(&[s2, c2]);
    let e = f.store.sub(sum, one);
    f.assert_exactly_zero(e);
    let wrong = f.store.sub(sum, two);
    f.assert_exactly_nonzero(wrong);
}

/// The store's own rewrites cancel a sum against its negation, and a
/// sum's terms against a scaled sum of some of them, without normal forms;
/// a scaled sum that cancels nothing stays one term.
#[test]
fn sums_cancel_when_built() {
    let mut f = Fixture::new(&["a", "b", "c"], &[]);
    let (a, b, c) = (f.var("a"), f.var("b"), f.var("c"));
    let sine = f.call(Function::Sin, a);
    let two_b = f.store.add2(b, b);
    let pair = f.store.add(&[sine, two_b]);
    let zero = f.store.integer(0);
    assert_eq!(f.store.sub(pair, pair), zero);
    let three = f.store.add(&[sine, two_b, c]);
    assert_eq!(f.store.sub(three, pair), c);
    let doubled = f.store.add2(three, three);
    let kept = f.store.sub(doubled, pair);
    let minus_pair = f.store.neg(pair);
    assert!(f.store.children(kept).contains(&minus_pair));
    assert_eq!(f.store.display(kept).to_string().matches("sin").count(), 2);
}

#[test]
fn angle_addition() {
    let mut f = Fixture::new(&["a", "b"], &[]);
    let (a, b) = (f.var("a"), f.var("b"));
    let sum = f.store.add2(a, b);
    let left = f.call(Function::Sin, sum);
    let (sa, cb) = (f.call(Function::Sin, a), f.call(Function::Cos, b));
    let (ca, sb) = (f.call(Function::Cos, a), f.call(Function::Sin, b));
    let p1 = f.store.mul2(sa, cb);
    let p2 = f.store.mul2(ca, sb);
    let right = f.store.add2(p1, p2);
    let e = f.store.sub(left, right);
    f.assert_exactly_zero(e);
}

#[test]
fn tangent_times_cosine_is_sine() {
    let mut f = Fixture::new(&["phi"], &[]);
    let phi = f.var("phi");
    let (t, c, s) = (
        f.call(Function::Tan, phi),
        f.call(Function::Cos, phi),
        f.call(Function::Sin, phi),
    );
    let product = f.store.mul2(t, c);
    let e = f.store.sub(product, s);
    f.assert_exactly_zero(e);
}

#[test]
fn double_angle_and_negated_arguments() {
    let mut f = Fixture::new(&["x", "y"], &[]);
    let (x, y) = (f.var("x"), f.var("y"));
    let two = f.store.integer(2);
    let two_x = f.store.mul2(two, x);
    let sin_2x = f.call(Function::Sin, two_x);
    let (s, c) = (f.call(Function::Sin, x), f.call(Function::Cos, x));
    let expected = f.store.mul(&[two, s, c]);
    let e = f.store.sub(sin_2x, expected);
    f.assert_exactly_zero(e);
    let x_minus_y = f.store.sub(x, y);
    let y_minus_x = f.store.sub(y, x);
    let c1 = f.call(Function::Cos, x_minus_y);
    let c2 = f.call(Function::Cos, y_minus_x);
    let e = f.store.sub(c1, c2);
    f.assert_exactly_zero(e);
}

#[test]
fn cancellation_through_sine_free_denominators() {
    // (1 - cos^2 q) / sin q - sin q = 0 needs the conjugate of the denominator.
    let mut f = Fixture::new(&["q"], &["m"]);
    let (q, m) = (f.var("q"), f.var("m"));
    let (s, c) = (f.call(Function::Sin, q), f.call(Function::Cos, q));
    let one = f.store.integer(1);
    let c2 = f.store.pow(c, 2.into()).unwrap();
    let numerator = f.store.sub(one, c2);
    let ratio = f.store.div(numerator, s).unwrap();
    let e = f.store.sub(ratio, s);
    f.assert_exactly_zero(e);
    // m sin q / (m + m cos q) simplifies to a quotient with no m left.
    let numerator = f.store.mul2(m, s);
    let mc = f.store.mul2(m, c);
    let denominator = f.store.add2(m, mc);
    let ratio = f.store.div(numerator, denominator).unwrap();
    let form = f.store.normal(ratio).unwrap();
    let m_atom = f.store.symbol_atom(f.symbols["m"]);
    assert!(!form.atoms().contains(&m_atom), "m should cancel: {form:?}");
}

#[test]
fn division_by_an_exact_zero_is_an_error() {
    let mut f = Fixture::new(&["q"], &[]);
    let q = f.var("q");
    let (s, c) = (f.call(Function::Sin, q), f.call(Function::Cos, q));
    let s2 = f.store.pow(s, 2.into()).unwrap();
    let c2 = f.store.pow(c, 2.into()).unwrap();
    let one = f.store.integer(1);
    let sum = f.store.add(&[s2, c2]);
    let zero = f.store.sub(sum, one);
    let ratio = f.store.div(q, zero).unwrap();
    let error = f.store.normal(ratio).unwrap_err();
    assert!(
        matches!(error, super::SymError::DivisionByZero { .. }),
        "{error}"
    );
}

#[test]
fn kernels_outside_the_class_fall_back_to_numbers() {
    let mut f = Fixture::new(&["x"], &[]);
    let x = f.var("x");
    // exp(2 ln x) - x^2 is zero, but exp and ln are opaque kernels.
    let ln = f.call(Function::Ln, x);
    let two = f.store.integer(2);
    let twice = f.store.mul2(two, ln);
    let e_twice = f.call(Function::Exp, twice);
    let x2 = f.store.pow(x, 2.into()).unwrap();
    let e = f.store.sub(e_twice, x2);
    let test = f.store.zero_test(e).unwrap();
    assert_eq!(test.decided_by, Decision::Numeric);
    assert!(test.is_zero);
    let e_plus = f.store.add2(e, x);
    assert!(!f.store.zero_test(e_plus).unwrap().is_zero);
}

/// Moore's mixed-partials test on one constraint row `sum_i a_i(q) qdot_i`:
/// true when every `d a_i / d q_j - d a_j / d q_i` is exactly zero.
fn mixed_partials_agree(f: &mut Fixture, row: ExprId, coordinates: &[&str]) -> bool {
    let coefficients: Vec<ExprId> = coordinates
        .iter()
        .map(|name| {
            let velocity = f.store.velocity_of(f.symbols[name]);
            f.store.derivative(row, velocity)
        })
        .collect();
    for (i, &a_i) in coefficients.iter().enumerate() {
        for (j, &a_j) in coefficients.iter().enumerate().skip(i + 1) {
            let d_ai = f.store.derivative(a_i, f.symbols[coordinates[j]]);
            let d_aj = f.store.derivative(a_j, f.symbols[coordinates[i]]);
            let difference = f.store.sub(d_ai, d_aj);
            let exact = f.store.zero_test(difference).unwrap();
            let numeric = f
                .store
                .numerically_zero(difference, &NumericZeroTest::default());
            assert_eq!(exact.is_zero, numeric, "exact and numeric tests disagree");
            if !exact.is_zero {
                return false;
            }
        }
    }
    true
}

#[test]
fn moore_mixed_partials_sleigh_fails_four_bar_passes() {
    let mut f = Fixture::new(&["x", "y", "theta"], &[]);
    let theta = f.var("theta");
    let (s, c) = (f.call(Function::Sin, theta), f.call(Function::Cos, theta));
    let (xd, yd) = (f.velocity("x"), f.velocity("y"));
    let minus_s_xd = {
        let p = f.store.mul2(s, xd);
        f.store.neg(p)
    };
    let c_yd = f.store.mul2(c, yd);
    let sleigh = f.store.add2(minus_s_xd, c_yd);
    assert!(!mixed_partials_agree(&mut f, sleigh, &["x", "y", "theta"]));

    // Four-bar loop closure: la cos q1 + lb cos(q1+q2) + lc cos(q1+q2+q3) - ln = 0,
    // differentiated in time by the engine.
    let mut g = Fixture::new(&["q1", "q2", "q3"], &["la", "lb", "lc", "ln"]);
    let (q1, q2, q3) = (g.var("q1"), g.var("q2"), g.var("q3"));
    let (la, lb, lc, ln) = (g.var("la"), g.var("lb"), g.var("lc"), g.var("ln"));
    let a12 = g.store.add2(q1, q2);
    let a123 = g.store.add(&[q1, q2, q3]);
    let cos1 = g.call(Function::Cos, q1);
    let cos12 = g.call(Function::Cos, a12);
    let cos123 = g.call(Function::Cos, a123);
    let terms = [
        g.store.mul2(la, cos1),
        g.store.mul2(lb, cos12),
        g.store.mul2(lc, cos123),
        g.store.neg(ln),
    ];
    let closure = g.store.add(&terms);
    let mut rate_terms = Vec::new();
    for name in ["q1", "q2", "q3"] {
        let partial = g.store.derivative(closure, g.symbols[name]);
        let velocity = g.velocity(name);
        rate_terms.push(g.store.mul2(partial, velocity));
    }
    let rate = g.store.add(&rate_terms);
    assert!(mixed_partials_agree(&mut g, rate, &["q1", "q2", "q3"]));
}

/// The snakeboard metric of MATH.md 3.1, row-major, with `J = Jt + m r^2`.
fn snakeboard_metric(f: &mut Fixture) -> Vec<ExprId> {
    let (m, r, jt, jw) = (f.var("m"), f.var("r"), f.var("jt"), f.var("jw"));
    let r2 = f.store.pow(r, 2.into()).unwrap();
    let mr2 = f.store.mul2(m, r2);
    let j = f.store.add2(jt, mr2);
    let zero = f.store.integer(0);
    #[rustfmt::skip]
    let g = vec![
        m, zero, zero, zero, zero,
        zero, m, zero, zero, zero,
        zero, zero, j, jt, zero,
        zero, zero, jt, jt, zero,
        zero, zero, zero, zero, jw,
    ];
    g
}

#[test]
fn snakeboard_metric_inverse_equals_the_hand_inverse() {
    let mut f = Fixture::new(&["x", "y", "theta", "psi", "phi"], &["m", "r", "jt", "jw"]);
    let g_entries = snakeboard_metric(&mut f);
    let g = Matrix::from_expressions(&mut f.store, 5, 5, &g_entries).unwrap();
    assert_eq!(
        g.diagonal_blocks(),
        vec![vec![0], vec![1], vec![2, 3], vec![4]]
    );
    let inverse = g.inverse(f.store.atoms()).unwrap();

    // Hand inverse: diag(1/m, 1/m, [[1/(m r^2), -1/(m r^2)], [-1/(m r^2), J/(Jt m r^2)]], 1/jw).
    let (m, r, jt, jw) = (f.var("m"), f.var("r"), f.var("jt"), f.var("jw"));
    let one = f.store.integer(1);
    let r2 = f.store.pow(r, 2.into()).unwrap();
    let mr2 = f.store.mul2(m, r2);
    let j = f.store.add2(jt, mr2);
    let inv_m = f.store.div(one, m).unwrap();
    let inv_mr2 = f.store.div(one, mr2).unwrap();
    let minus_inv_mr2 = f.store.neg(inv_mr2);
    let jt_mr2 = f.store.mul2(jt, mr2);
    let j_over = f.store.div(j, jt_mr2).unwrap();
    let inv_jw = f.store.div(one, jw).unwrap();
    let zero = f.store.integer(0);
    #[rustfmt::skip]
    let expected = [
        inv_m, zero, zero, zero, zero,
        zero, inv_m, zero, zero, zero,
        zero, zero, inv_mr2, minus_inv_mr2, zero,
        zero, zero, minus_inv_mr2, j_over, zero,
        zero, zero, zero, zero, inv_jw,
    ];
    let computed = inverse.to_expressions(&mut f.store);
    for (&c, &e) in computed.iter().zip(&expected) {
        let difference = f.store.sub(c, e);
        f.assert_exactly_zero(difference);
    }
    let product = g.mul(&inverse, f.store.atoms()).unwrap();
    assert_eq!(product, Matrix::identity(5));
    let determinant = g.determinant(f.store.atoms()).unwrap();
    let det = f.store.expression_of(&determinant);
    let expected_det = f.store.mul(&[m, m, jt, mr2, jw]);
    let difference = f.store.sub(det, expected_det);
    f.assert_exactly_zero(difference);
}

#[test]
fn dense_solve_and_determinant_match_cofactors() {
    let mut f = Fixture::new(&["a", "b"], &["k"]);
    let (a, b, k) = (f.var("a"), f.var("b"), f.var("k"));
    let (sa, cb) = (f.call(Function::Sin, a), f.call(Function::Cos, b));
    let one = f.store.integer(1);
    let two = f.store.integer(2);
    let kb = f.store.mul2(k, b);
    let k_plus_1 = f.store.add2(k, one);
    #[rustfmt::skip]
    let entries = [
        k_plus_1, sa, two,
        cb, k, one,
        a, kb, sa,
    ];
    let m = Matrix::from_expressions(&mut f.store, 3, 3, &entries).unwrap();
    let det = m.determinant(f.store.atoms()).unwrap();
    // cofactor expansion along the first row
    let cofactor = |f: &mut Fixture, p: ExprId, q: ExprId, r: ExprId, s: ExprId| {
        let ps = f.store.mul2(p, s);
        let qr = f.store.mul2(q, r);
        f.store.sub(ps, qr)
    };
    let m11 = cofactor(&mut f, k, one, kb, sa);
    let m12 = cofactor(&mut f, cb, one, a, sa);
    let m13 = cofactor(&mut f, cb, k, a, kb);
    let t1 = f.store.mul2(k_plus_1, m11);
    let t2 = f.store.mul2(sa, m12);
    let t3 = f.store.mul2(two, m13);
    let minus_t2 = f.store.neg(t2);
    let expected = f.store.add(&[t1, minus_t2, t3]);
    let computed = f.store.expression_of(&det);
    let difference = f.store.sub(computed, expected);
    f.assert_exactly_zero(difference);

    let inverse = m.inverse(f.store.atoms()).unwrap();
    assert_eq!(
        m.mul(&inverse, f.store.atoms()).unwrap(),
        Matrix::identity(3)
    );
    assert_eq!(m.rank(f.store.atoms()), 3);
}

#[test]
fn ranks_exact_and_numeric_and_singular_solves() {
    let mut f = Fixture::new(&["q"], &[]);
    let q = f.var("q");
    let (s, c) = (f.call(Function::Sin, q), f.call(Function::Cos, q));
    let one = f.store.integer(1);
    let two = f.store.integer(2);
    // third row = sin q * first + cos q * second
    let s2 = f.store.mul2(s, two);
    let third_a = f.store.add2(s, c);
    let third_b = f.store.add2(s2, c);
    let zero = f.store.integer(0);
    #[rustfmt::skip]
    let entries = [
        one, two,
        one, one,
        third_a, third_b,
        zero, zero,
    ];
    let m = Matrix::from_expressions(&mut f.store, 4, 2, &entries).unwrap();
    assert_eq!(m.rank(f.store.atoms()), 2);
    #[rustfmt::skip]
    let square = [
        one, s, c,
        s, one, c,
        third_a, third_a, c,
    ];
    let m = Matrix::from_expressions(&mut f.store, 3, 3, &square).unwrap();
    let numeric = m.rank_at(&mut f.store, &|_| 0.7, 1e-12);
    let exact = m.rank(f.store.atoms());
    assert_eq!(numeric, exact);
}

#[test]
fn sleigh_lie_bracket_leaves_the_distribution() {
    let mut f = Fixture::new(&["x", "y", "theta"], &[]);
    let theta = f.var("theta");
    let (s, c) = (f.call(Function::Sin, theta), f.call(Function::Cos, theta));
    let (zero, one) = (f.store.integer(0), f.store.integer(1));
    let to_forms = |f: &mut Fixture, v: &[ExprId]| -> Vec<RationalFunction> {
        v.iter().map(|&e| f.store.normal(e).unwrap()).collect()
    };
    let x1 = to_forms(&mut f, &[c, s, zero]);
    let x2 = to_forms(&mut f, &[zero, zero, one]);
    let coordinates: Vec<SymbolId> = ["x", "y", "theta"].iter().map(|n| f.symbols[n]).collect();
    let bracket = f.store.lie_bracket(&x1, &x2, &coordinates).unwrap();
    let expected = to_forms(&mut f, &[s, zero, zero]);
    let minus_c = f.store.neg(c);
    let expected_y = f.store.normal(minus_c).unwrap();
    assert_eq!(bracket[0], expected[0]);
    assert_eq!(bracket[1], expected_y);
    assert!(bracket[2].is_zero());
    let mut columns = Vec::new();
    for i in 0..3 {
        columns.extend([x1[i].clone(), x2[i].clone(), bracket[i].clone()]);
    }
    let span = Matrix::new(3, 3, columns).unwrap();
    assert_eq!(span.rank(f.store.atoms()), 3);
}

#[test]
fn substitution_rebuilds_and_reports_exact_zero_divisors() {
    let mut f = Fixture::new(&["x", "y"], &[]);
    let (x, y) = (f.var("x"), f.var("y"));
    let two = f.store.integer(2);
    let x2 = f.store.pow(x, 2.into()).unwrap();
    let two_x = f.store.mul2(two, x);
    let e = f.store.sub(x2, two_x);
    let one = f.store.integer(1);
    let y_plus_1 = f.store.add2(y, one);
    let replacements = HashMap::from([(f.symbols["x"], y_plus_1)]);
    let substituted = f.store.substitute(e, &replacements).unwrap();
    // (y + 1)^2 - 2 (y + 1) = y^2 - 1
    let y2 = f.store.pow(y, 2.into()).unwrap();
    let expected = f.store.sub(y2, one);
    assert!(f.store.equal(substituted, expected).unwrap());
    let inverse = f.store.div(one, x).unwrap();
    let zero = HashMap::from([(f.symbols["x"], f.store.integer(0))]);
    assert!(matches!(
        f.store.substitute(inverse, &zero),
        Err(super::SymError::DivisionByZero { .. })
    ));
}
