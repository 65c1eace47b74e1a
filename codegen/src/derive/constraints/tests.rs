//! The constraint analysis against hand derivations.

use super::{Classification, ConstraintAnalysis, analyse, distribution_basis};
use crate::diagnostic::Diagnostics;
use crate::model::{Model, check};
use crate::sym::{Context, Rational};
use crate::syntax::parse_str;

fn model(source: &str) -> (Model, Context) {
    check(&parse_str(source).expect("parses")).expect("checks")
}

/// The constraint analysis of a checked model.
fn analysed((model, mut cx): (Model, Context)) -> Result<ConstraintAnalysis, Diagnostics> {
    analyse(&model, &mut cx)
}

/// A model with unit kinetic energy on `coordinates` and these constraints.
fn constrained(coordinates: &str, constraints: &str) -> (Model, Context) {
    let names: Vec<&str> = coordinates.split(',').map(str::trim).collect();
    let energy: Vec<String> = names.iter().map(|q| format!("dot({q})^2/2")).collect();
    model(&format!(
        "pub struct M {{
            coordinates: [{coordinates}],
            parameters: [r = 0.5],
            kinetic_energy: {},
            constraints: [{constraints}],
        }}",
        energy.join(" + ")
    ))
}

/// The Chaplygin sleigh of `models/sleigh.model`.
const SLEIGH: &str = r#"
pub struct Sleigh {
    coordinates: [x, y, theta],
    parameters: [m = 1.0, inertia = 0.1, a = 0.5],
    kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
        + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
    constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
}
"#;

#[test]
fn the_basis_spans_the_kernel_of_the_constraints() {
    let (snakeboard, mut cx) = model(crate::fixtures::SNAKEBOARD);
    let basis = distribution_basis(&snakeboard, &mut cx).expect("regular at the defaults");
    let fields = basis.fields.as_ref().expect("exact within the budget");
    assert_eq!(fields.columns(), 3);
    let atoms = cx.atoms().clone();
    let product = snakeboard
        .constraint_matrix
        .mul(fields, &atoms)
        .expect("fits");
    assert!(product.is_zero(), "A X must vanish exactly");
    assert_eq!(fields.rank(&atoms), 3);
    let structured =
        crate::sym::Matrix::from_expressions(&mut cx, 5, 3, basis.field_expressions.entries())
            .expect("normal forms");
    let atoms = cx.atoms().clone();
    let difference = structured.sub(fields, &atoms).expect("same shape");
    assert!(
        difference.is_zero(),
        "the elimination gives the exact basis"
    );
    // at q = 0 the front and back rows are (0, 1, r, 0, 0) and (0, 1, -r, 0, 0):
    // x has a zero column there, so y and theta are the dependent speeds.
    assert_eq!(basis.dependent, [1, 2]);
    assert_eq!(basis.independent, [0, 3, 4]);
}

/// Sleigh: D = span{(cos, sin, 0), d_theta}; their bracket (-sin, cos, 0) is
/// the forbidden sideways direction, so (2, 3) (Moore's "Chaplygin Sleigh" example shows
/// the blade row is not integrable).
#[test]
fn the_sleigh_grows_2_3() {
    let analysis = analysed(model(SLEIGH)).expect("analyses");
    assert_eq!(analysis.growth, [2, 3]);
    assert!(!analysis.integrable);
    assert_eq!(
        analysis.classification,
        Classification::CompletelyNonholonomic
    );
    assert_eq!(analysis.exact_rows, [false]);
}

/// Snakeboard (MATH.md 1.3), by hand: D = span{X = r cos d_x + r sin d_y +
/// tan(phi) d_theta, d_psi, d_phi}; `[d_phi, X] = sec^2(phi) d_theta` is new
/// (4), and `[X, sec^2(phi) d_theta]` has the sideways part
/// `sec^2(phi) r (sin d_x - cos d_y)`, new again (5).
#[test]
fn the_snakeboard_grows_3_4_5() {
    let analysis = analysed(model(crate::fixtures::SNAKEBOARD)).expect("analyses");
    assert_eq!(analysis.growth, [3, 4, 5]);
    assert!(!analysis.integrable);
    assert_eq!(
        analysis.classification,
        Classification::CompletelyNonholonomic
    );
    assert_eq!(analysis.exact_rows, [false, false]);
}

/// The Heisenberg system `zdot = x ydot`: X1 = d_x, X2 = d_y + x d_z,
/// `[X1, X2] = d_z`, so (2, 3).
#[test]
fn the_heisenberg_constraint_grows_2_3() {
    let analysis = analysed(constrained("x, y, z", "h = dot(z) - x*dot(y)")).expect("analyses");
    assert_eq!(analysis.growth, [2, 3]);
    assert!(!analysis.integrable);
}

/// `(1 + x^2)(y xdot + x ydot + zdot) = (1 + x^2) d(x y + z)`: holonomic
/// (x y + z is constant along solutions), but the row is not exact:
/// `d a_x / d y = 1 + x^2`, `d a_y / d x = 1 + 3 x^2`.
#[test]
fn an_integrating_factor_is_holonomic_though_moores_test_fails() {
    let (m, mut cx) = constrained(
        "x, y, z",
        "level = (1 + x^2)*(y*dot(x) + x*dot(y) + dot(z))",
    );
    let analysis = analyse(&m, &mut cx).expect("analyses");
    assert!(analysis.integrable);
    assert_eq!(analysis.classification, Classification::Holonomic);
    assert_eq!(analysis.growth, [2]);
    assert_eq!(analysis.exact_rows, [false]);
}

/// Without the factor the same row is exact: Moore's test agrees with Frobenius.
#[test]
fn an_exact_row_passes_moores_test() {
    let (m, mut cx) = constrained("x, y, z", "level = y*dot(x) + x*dot(y) + dot(z)");
    let analysis = analyse(&m, &mut cx).expect("analyses");
    assert!(analysis.integrable);
    assert_eq!(analysis.exact_rows, [true]);
}

/// One constraint on two coordinates leaves k = 1: a single field is always
/// integrable, whatever the factor (`(1 + x^2)(xdot - r phidot)`).
#[test]
fn one_degree_of_freedom_is_integrable() {
    let (m, mut cx) = constrained("x, phi", "roll = (1 + x^2)*(dot(x) - r*dot(phi))");
    let analysis = analyse(&m, &mut cx).expect("analyses");
    assert!(analysis.integrable);
    assert_eq!(analysis.growth, [1]);
    assert_eq!(analysis.classification, Classification::Holonomic);
    assert_eq!(analysis.exact_rows, [false]);
}

#[test]
fn deny_holonomic_rejects_integrable_constraints_on_the_first_name() {
    let source = "#[deny_holonomic]
        pub struct M {
            coordinates: [x, y, z],
            kinetic_energy: dot(x)^2/2 + dot(y)^2/2 + dot(z)^2/2,
            constraints: [level = (1 + x^2)*(y*dot(x) + x*dot(y) + dot(z))],
        }";
    let diagnostics = analysed(model(source)).expect_err("integrable is denied");
    let messages: Vec<&str> = diagnostics.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(messages.len(), 1);
    assert!(messages[0].contains("integrable"), "{}", messages[0]);
    assert!(messages[0].contains("#[deny_holonomic]"), "{}", messages[0]);
}

#[test]
fn deny_holonomic_accepts_nonholonomic_constraints() {
    let source = format!("#[deny_holonomic]\n{SLEIGH}");
    assert!(analysed(model(&source)).is_ok());
}

#[test]
fn no_constraints_is_unconstrained() {
    let (m, mut cx) =
        model("pub struct Free { coordinates: [x, y], kinetic_energy: dot(x)^2/2 + dot(y)^2/2 }");
    let analysis = analyse(&m, &mut cx).expect("analyses");
    assert_eq!(analysis.growth, [2]);
    assert!(analysis.integrable);
    assert_eq!(analysis.classification, Classification::Unconstrained);
    assert!(analysis.exact_rows.is_empty());
}

/// `(1 + x^2)(y xdot + x ydot) = (1 + x^2) d(x y)` vanishes at q = 0, so no
/// pivot is regular at the defaults: the generic pivots are used (x, the
/// first column), and the analysis goes through: holonomic, not exact.
#[test]
fn a_row_vanishing_at_the_defaults_gets_generic_pivots() {
    let (m, mut cx) = constrained("x, y, z", "level = (1 + x^2)*(y*dot(x) + x*dot(y))");
    let analysis = analyse(&m, &mut cx).expect("analyses");
    assert_eq!(analysis.basis.dependent, [0]);
    assert!(analysis.integrable);
    assert_eq!(analysis.classification, Classification::Holonomic);
    assert_eq!(analysis.exact_rows, [false]);
}

/// The analysis at random points modulo a prime against the exact one:
/// the same integrability and the same growth vector for every model
/// above, holonomic ones (one with an integrating factor) included.
#[test]
fn the_analysis_at_points_agrees_with_the_exact_analysis() {
    let models = [
        model(SLEIGH),
        model(crate::fixtures::SNAKEBOARD),
        constrained("x, y, z", "h = dot(z) - x*dot(y)"),
        constrained(
            "x, y, z",
            "level = (1 + x^2)*(y*dot(x) + x*dot(y) + dot(z))",
        ),
        constrained("x, y, z", "level = (1 + x^2)*(y*dot(x) + x*dot(y))"),
        constrained("x, phi", "roll = (1 + x^2)*(dot(x) - r*dot(phi))"),
    ];
    for (m, mut cx) in models {
        let exact = analyse(&m, &mut cx).expect("analyses");
        assert_eq!(exact.growth_method, super::Method::NormalForm);
        let basis = distribution_basis(&m, &mut cx).expect("regular");
        let integrable = super::is_involutive_at_points(&m, &mut cx, &basis).expect("in the class");
        let (growth, complete) =
            super::growth_vector_at_point(&m, &mut cx, &basis).expect("in the class");
        assert_eq!(integrable, exact.integrable, "{}", m.name);
        assert_eq!(growth, exact.growth, "{}", m.name);
        assert!(complete);
    }
}

/// A chain of six wheeled links (n = 8): the exact brackets of the growth
/// vector exceed their budget, so the growth is decided at a random point
/// with the brackets of the structured basis, and D is still found
/// completely nonholonomic; the structured basis annihilates A at a point.
#[test]
fn a_long_chain_is_analysed_at_points() {
    let (chain, mut cx) = model(&crate::fixtures::chain_of_links(6));
    let analysis = analyse(&chain, &mut cx).expect("analyses");
    assert_eq!(analysis.growth_method, super::Method::Modular);
    assert!(!analysis.integrable);
    // k = 2 fields, one bracket outside D (not integrable), growing strictly
    // to n = 8: every configuration of the chain is reachable
    assert_eq!(analysis.growth[..2], [2, 3]);
    assert!(analysis.growth.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(analysis.growth.last(), Some(&8));
    assert_eq!(
        analysis.classification,
        Classification::CompletelyNonholonomic
    );
    let rows = chain.constraint_matrix.to_expression_matrix(&mut cx);
    let product = rows
        .mul(&analysis.basis.field_expressions, &mut cx)
        .expect("fits");
    let values = cx
        .evaluate_modular(product.entries(), &crate::sym::modular::Point::new(5))
        .expect("in the class");
    assert!(values.iter().all(|&v| v == 0), "A X = 0 at the point");
}

/// With the symmetry declared, the basis is chosen on the body rows and
/// rotated back: it spans `ker A` exactly, and no denominator of it holds
/// a group coordinate, so it is regular at every heading (the coordinate
/// elimination's `tan(theta)` for the sleigh is gone).
#[test]
fn the_body_frame_basis_has_no_group_coordinate_in_a_denominator() {
    let sleigh = include_str!("../../../../models/sleigh.model");
    let racer = include_str!("../../../../tests/models/roller_racer.model");
    for (source, rank) in [(sleigh, 2), (racer, 2)] {
        let (m, mut cx) = model(source);
        let basis = distribution_basis(&m, &mut cx).expect("regular");
        assert!(basis.body_frame);
        let fields = basis.fields.clone().expect("exact within the budget");
        let atoms = cx.atoms().clone();
        let product = m.constraint_matrix.mul(&fields, &atoms).expect("fits");
        assert!(product.is_zero(), "A X must vanish exactly");
        assert_eq!(fields.rank(&atoms), rank);
        let group: Vec<_> = ["x", "y", "theta"]
            .iter()
            .map(|name| {
                let index = m.coordinates.iter().position(|q| q.declared.name == *name);
                m.coordinates[index.expect("declared")].symbol
            })
            .collect();
        for entry in fields.entries() {
            let denominator = entry
                .reciprocal_of_denominator()
                .inverse(&atoms)
                .expect("non-zero");
            let denominator = cx.expression_of(&denominator);
            for &q in &group {
                assert!(!cx.depends_on(denominator, q));
            }
        }
    }
}

/// Moore's test at random points agrees with the exact one: a sleigh's
/// blade row is not exact, `d(x^2 + y^2) = 2 x dot(x) + 2 y dot(y)` is.
#[test]
fn moores_test_at_points_agrees_with_the_exact_test() {
    let (model, mut cx) = constrained(
        "x, y, theta",
        "blade = -sin(theta)*dot(x) + cos(theta)*dot(y), circle = 2*x*dot(x) + 2*y*dot(y)",
    );
    let exact = super::exact_rows(&model, &mut cx).expect("decided");
    assert_eq!(exact, [false, true]);
    for (row, expected) in exact.iter().enumerate() {
        let entries: Vec<_> = (0..model.n())
            .map(|j| *model.constraint_expressions.get(row, j))
            .collect();
        let at_points = super::at_points::is_exact_row_at_points(&model, &mut cx, &entries)
            .expect("in the class");
        assert_eq!(at_points, *expected, "row {row}");
    }
}

/// The benchmark bicycle: 8 coordinates, four rolling rows and the front
/// contact's height, so 3 speeds are free (lean, steer, forward); its
/// brackets reach every direction the height constraint allows, n - 1 = 7,
/// and the growth is complete there though it never reaches n: completely
/// nonholonomic on the constraint's surface (Chow's theorem there).
#[test]
fn the_bicycles_growth_stops_at_its_holonomic_constraint() {
    let (bicycle, mut cx) = model(include_str!("../../../../models/bicycle.model"));
    let analysis = analyse(&bicycle, &mut cx).expect("analysed");
    assert_eq!(analysis.growth.first(), Some(&3));
    assert_eq!(analysis.growth.last(), Some(&7));
    assert!(analysis.growth_complete);
    assert!(!analysis.integrable);
    assert_eq!(
        analysis.classification,
        Classification::CompletelyNonholonomic
    );
}

/// A differential-drive robot: its wheels' rolling rows
/// `cos(theta) xdot + sin(theta) ydot -+ b thetadot - r phidot` differ by
/// the differential of `-2 b theta - r phi_l + r phi_r` (by hand), the
/// integral that keeps its reachable dimension at 4 of 5.
#[test]
fn the_wheels_rolling_rows_of_a_differential_drive_give_an_integral() {
    let (m, mut cx) = model(
        "pub struct Drive {
            coordinates: [x, y, theta, phi_l, phi_r],
            parameters: [b = 0.3, r = 0.1],
            kinetic_energy: (dot(x)^2 + dot(y)^2 + dot(theta)^2 + dot(phi_l)^2 + dot(phi_r)^2)/2,
            constraints: [
                left = cos(theta)*dot(x) + sin(theta)*dot(y) - b*dot(theta) - r*dot(phi_l),
                right = cos(theta)*dot(x) + sin(theta)*dot(y) + b*dot(theta) - r*dot(phi_r),
                lateral = -sin(theta)*dot(x) + cos(theta)*dot(y),
            ],
        }",
    );
    let analysis = analyse(&m, &mut cx).expect("analyses");
    assert_eq!(analysis.growth.last(), Some(&4));
    let [integral] = &analysis.integrals[..] else {
        panic!("one integral: {:?}", analysis.integrals)
    };
    let (one, minus_one) = (Rational::integer(1), Rational::integer(-1));
    assert_eq!(integral.rows, [(0, one), (1, minus_one)]);
    let symbol = |cx: &mut Context, name: &str| {
        let coordinates = m
            .coordinates
            .iter()
            .map(|q| (q.declared.name.as_str(), q.symbol));
        let parameters =
            (m.parameters.iter()).map(|p| (p.variable.declared.name.as_str(), p.variable.symbol));
        let (_, id) = coordinates
            .chain(parameters)
            .find(|(n, _)| *n == name)
            .expect("declared");
        cx.symbol(id)
    };
    let (b, r) = (symbol(&mut cx, "b"), symbol(&mut cx, "r"));
    let (theta, phi_l, phi_r) = (
        symbol(&mut cx, "theta"),
        symbol(&mut cx, "phi_l"),
        symbol(&mut cx, "phi_r"),
    );
    let two = cx.number(Rational::integer(-2));
    let terms = [
        cx.mul(&[two, b, theta]),
        cx.mul(&[r, phi_l]),
        cx.mul(&[r, phi_r]),
    ];
    let minus_r_phi_l = cx.neg(terms[1]);
    let by_hand = cx.add(&[terms[0], minus_r_phi_l, terms[2]]);
    let found = integral.function.expect("constant entries: written out");
    let difference = cx.sub(found, by_hand);
    assert!(cx.normal(difference).expect("normal form").is_zero());
}

/// `y xdot + zdot` and `-x ydot + zdot` are not exact, but their difference
/// is `d(x y)`: an integral whose entries depend on the coordinates, named
/// by its rows alone.
#[test]
fn an_exact_combination_with_varying_entries_is_named_by_its_rows() {
    let (m, mut cx) = constrained("x, y, z", "a = y*dot(x) + dot(z), c = -x*dot(y) + dot(z)");
    let analysis = analyse(&m, &mut cx).expect("analyses");
    assert_eq!(analysis.exact_rows, [false, false]);
    let [integral] = &analysis.integrals[..] else {
        panic!("one integral: {:?}", analysis.integrals)
    };
    assert_eq!(
        integral.rows,
        [(0, Rational::integer(1)), (1, Rational::integer(-1))]
    );
    assert_eq!(integral.function, None);
    assert_eq!(
        integral.describe(&m, &cx),
        "a - c is the differential of a function"
    );
}

/// The snakeboard's rows combine to no exact form: no integral, and its
/// growth reaches n.
#[test]
fn the_snakeboard_has_no_integral() {
    let (snakeboard, mut cx) = model(include_str!("../../../../models/snakeboard.model"));
    let analysis = analyse(&snakeboard, &mut cx).expect("analysed");
    assert!(analysis.integrals.is_empty());
}
