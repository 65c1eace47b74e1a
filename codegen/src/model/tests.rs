//! The checker on the snakeboard of MATH.md 3.1 and on broken models.

mod orientation;

use super::{Model, check};
use crate::fixtures::SNAKEBOARD;
use crate::sym::Context;
use crate::sym::{Function, Matrix};
use crate::syntax::parse_str;

fn checked(source: &str) -> (Model, Context) {
    let syntax = parse_str(source).expect("parses");
    check(&syntax).unwrap_or_else(|e| panic!("{}", e.render("test.model")))
}

fn errors(source: &str) -> String {
    let syntax = parse_str(source).expect("parses");
    check(&syntax)
        .map(|_| ())
        .expect_err("must be rejected")
        .render("m.model")
}

/// The paper's basis of D (MATH.md 3.1) as a 5 x 3 matrix in the model's context:
/// `r cos(theta) d_x + r sin(theta) d_y + tan(phi) d_theta`, `d_psi`, `d_phi`.
fn papers_distribution(cx: &mut Context) -> Matrix {
    let symbol = |cx: &mut Context, name: &str| {
        let id = cx.find_symbol(name).expect("declared");
        cx.symbol(id)
    };
    let (r, theta, phi) = (symbol(cx, "r"), symbol(cx, "theta"), symbol(cx, "phi"));
    let cos_theta = cx.apply(Function::Cos, theta).expect("cos");
    let sin_theta = cx.apply(Function::Sin, theta).expect("sin");
    let tan_phi = cx.apply(Function::Tan, phi).expect("tan");
    let (zero, one) = (cx.integer(0), cx.integer(1));
    let rolling = [
        cx.mul2(r, cos_theta),
        cx.mul2(r, sin_theta),
        tan_phi,
        zero,
        zero,
    ];
    let mut entries = Vec::new();
    for (i, &component) in rolling.iter().enumerate() {
        let psi = if i == 3 { one } else { zero };
        let phi = if i == 4 { one } else { zero };
        entries.extend([component, psi, phi]);
    }
    Matrix::from_expressions(cx, 5, 3, &entries).expect("5 x 3")
}

#[test]
fn snakeboard_metric_is_the_hand_derived_g() {
    let (model, cx) = checked(SNAKEBOARD);
    assert_eq!((model.n(), model.c(), model.k(), model.p()), (5, 2, 3, 2));
    assert!(model.mass_matrix.is_symmetric());
    // MATH.md 3.1: g = [[m,0,0,0,0],[0,m,0,0,0],[0,0,J,Jt,0],[0,0,Jt,Jt,0],[0,0,0,0,Jw]],
    // J = Jt + m r^2, at parameter values other than the defaults.
    let [m, r, jt, jw] = [1.7, 0.45, 0.31, 0.07];
    let j = jt + m * r * r;
    let expected = [
        [m, 0.0, 0.0, 0.0, 0.0],
        [0.0, m, 0.0, 0.0, 0.0],
        [0.0, 0.0, j, jt, 0.0],
        [0.0, 0.0, jt, jt, 0.0],
        [0.0, 0.0, 0.0, 0.0, jw],
    ];
    let mut cx = cx.clone();
    let names: Vec<String> = ["m", "r", "jt", "jw"].map(String::from).to_vec();
    let lookup = cx.clone();
    let value_of = |s| {
        let name = &lookup.symbol_info(s).name;
        names
            .iter()
            .position(|n| n == name)
            .map_or(0.3, |i| [m, r, jt, jw][i])
    };
    let numbers = model.mass_matrix.evaluate(&mut cx, &value_of);
    for (i, row) in expected.iter().enumerate() {
        for (k, value) in row.iter().enumerate() {
            assert!((numbers[i * 5 + k] - value).abs() < 1e-15, "g[{i}][{k}]");
        }
    }
}

#[test]
fn snakeboard_constraints_annihilate_the_papers_distribution_exactly() {
    let (model, mut cx) = checked(SNAKEBOARD);
    let fields = papers_distribution(&mut cx);
    let atoms = cx.atoms().clone();
    let product = model
        .constraint_matrix
        .mul(&fields, &atoms)
        .expect("2x5 * 5x3");
    assert!(product.is_zero(), "A X = {product:?}");
}

#[test]
fn a_declared_distribution_yields_constraints_with_the_same_kernel() {
    let text = SNAKEBOARD
        .replace("constraints: [", "distribution: [ rolling = [r*cos(theta), r*sin(theta), tan(phi), 0, 0], torso = [0, 0, 0, 1, 0], wheels = [0, 0, 0, 0, 1] ], ignored: [")
        .replace("ignored: [", "")
        .replace("front = -sin(theta + phi)*dot(x) + cos(theta + phi)*dot(y) + r*cos(phi)*dot(theta),\n        back  = -sin(theta - phi)*dot(x) + cos(theta - phi)*dot(y) - r*cos(phi)*dot(theta),\n    ],\n", "");
    let (model, mut cx) = checked(&text);
    assert_eq!(
        model
            .constraints
            .iter()
            .map(|c| c.name.as_str())
            .collect::<Vec<_>>(),
        ["c1", "c2"]
    );
    let fields = papers_distribution(&mut cx);
    let atoms = cx.atoms().clone();
    assert!(
        model
            .constraint_matrix
            .mul(&fields, &atoms)
            .expect("fits")
            .is_zero()
    );
    assert_eq!(model.constraint_matrix.rank(&atoms), 2);
}

#[test]
fn snakeboard_momentum_basis_is_accepted_and_a_wrong_one_rejected() {
    let (model, _) = checked(SNAKEBOARD);
    let basis = model.momentum_basis.as_ref().expect("declared");
    assert_eq!(basis.rows.rows(), 3);
    let broken = SNAKEBOARD.replace("torso  = [0, 0, 1, 1, 0]", "torso  = [0, 0, 1, 0, 0]");
    let message = errors(&broken);
    assert!(
        message.contains("momentum-basis row `torso` is not in g(D)"),
        "{message}"
    );
    assert!(message.contains("m.model:17:9"), "{message}");
}

#[test]
fn every_error_of_a_model_is_reported_with_its_position() {
    let source = "struct Bad {
    coordinates: [x, y],
    parameters: [m = 1.0, x = 2.0],
    kinetic_energy: m/2*dot(x)^2 + m*dot(y),
    potential_energy: dot(x),
    constraints: [c = dot(x)^2],
    inputs: [u = m],
}";
    let message = errors(source);
    for expected in [
        "m.model:3:27: error: `x` is a coordinate and cannot also be used as a parameter",
        "m.model:4:36: error: the kinetic energy must be quadratic",
        "m.model:5:23: error: the potential energy depends on the configuration only",
        "m.model:6:23: error: a constraint must be linear and homogeneous",
        "m.model:7:18: error: an input acts on a coordinate, and `m` is not a coordinate",
    ] {
        assert!(
            message.contains(expected),
            "missing `{expected}` in\n{message}"
        );
    }
}

#[test]
fn definiteness_symmetry_and_dependence_are_checked() {
    let negative = "struct N { coordinates: [x, y], parameters: [m = -1.0], kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) }";
    assert!(errors(negative).contains("not positive definite"));
    let asymmetric = "struct A { coordinates: [x, y], mass_matrix: [[1, x], [0, 1]] }";
    assert!(errors(asymmetric).contains("entry (1, 2) differs from entry (2, 1)"));
    let dependent = "struct D { coordinates: [x, y, theta], kinetic_energy: dot(x)^2 + dot(y)^2 + dot(theta)^2,
        constraints: [a = -sin(theta)*dot(x) + cos(theta)*dot(y), b = 2*(-sin(theta)*dot(x) + cos(theta)*dot(y))] }";
    assert!(errors(dependent).contains("constraint `b` depends on the ones before it"));
    // A zero row is named as constraining nothing: a velocity row of
    // zeros, and a configuration constraint on the parameters alone.
    let nothing = "constrains nothing: its row is zero in the velocities";
    let zero_row = "struct Z { coordinates: [x, y], kinetic_energy: dot(x)^2 + dot(y)^2,
        constraints: [a = dot(x), b = 0*dot(y)] }";
    assert!(errors(zero_row).contains(&format!("constraint `b` {nothing}")));
    let on_parameters = "struct P { coordinates: [x, y], parameters: [l = 1.0],
        kinetic_energy: dot(x)^2 + dot(y)^2, holonomic: [fixed = l - 1] }";
    let message = errors(on_parameters);
    assert!(
        message.contains(&format!("constraint `fixed` {nothing}")),
        "{message}"
    );
    let unknown = "struct U { coordinates: [x], kinetic_enrgy: dot(x)^2 }";
    let message = errors(unknown);
    assert!(
        message.contains("unknown section `kinetic_enrgy`"),
        "{message}"
    );
    assert!(
        message.contains("missing section `kinetic_energy`"),
        "{message}"
    );
}

/// The sleigh with a given potential, constraint, kinetic energy and group.
fn sleigh_with(potential: &str, constraint: &str, kinetic: &str, group: &str) -> String {
    format!(
        "struct S {{ coordinates: [x, y, theta], parameters: [m = 1.0, inertia = 0.1, a = 0.5, slope = 0.1],
        kinetic_energy: {kinetic}, potential_energy: {potential},
        constraints: [blade = {constraint}], symmetry: {group} }}"
    )
}

const SLEIGH_T: &str = "m/2*((dot(x) - a*sin(theta)*dot(theta))^2 + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2";
const BLADE: &str = "-sin(theta)*dot(x) + cos(theta)*dot(y)";

#[test]
fn the_group_must_preserve_the_lagrangian_and_the_constraints() {
    // SE(2) is a symmetry of the flat sleigh
    checked(&sleigh_with("0", BLADE, SLEIGH_T, "se2(x, y, theta)"));
    // on an incline rising along x, translations along y remain a symmetry, SE(2) does not
    let slope = "m*sin(slope)*(x + a*cos(theta))";
    checked(&sleigh_with(slope, BLADE, SLEIGH_T, "translation(y)"));
    let message = errors(&sleigh_with(slope, BLADE, SLEIGH_T, "se2(x, y, theta)"));
    assert!(
        message.contains("the potential energy is not invariant"),
        "{message}"
    );
    // an anisotropic kinetic energy breaks rotations
    let anisotropic = "m/2*(dot(x)^2 + 2*dot(y)^2) + inertia/2*dot(theta)^2";
    let message = errors(&sleigh_with("0", BLADE, anisotropic, "se2(x, y, theta)"));
    assert!(
        message.contains("the kinetic energy is not invariant"),
        "{message}"
    );
    // a blade fixed in the world frame (no motion along x) is not carried along by rotations
    let message = errors(&sleigh_with("0", "dot(x)", SLEIGH_T, "se2(x, y, theta)"));
    assert!(
        message.contains("the constraints are not invariant"),
        "{message}"
    );
    // but it is by translations
    checked(&sleigh_with(
        "0",
        "dot(x)",
        SLEIGH_T,
        "translation(x) * translation(y)",
    ));
}

/// The regular momentum basis the sleigh's documentation recommends,
/// `(g X)^T` for `X = (cos, sin, 0), (0, 0, 1)`, spans g(D) exactly.
#[test]
fn the_sleighs_documented_momentum_basis_is_accepted() {
    let source = sleigh_with("0", BLADE, SLEIGH_T, "se2(x, y, theta)").replace(
        "symmetry:",
        "momentum_basis: [forward = [cos(theta), sin(theta), 0], \
         turning = [-m*a*sin(theta), m*a*cos(theta), inertia + m*a^2]], symmetry:",
    );
    let (model, _) = checked(&source);
    assert_eq!(model.momentum_basis.expect("declared").names.len(), 2);
    let wrong = source.replace("inertia + m*a^2]]", "inertia]]");
    assert!(errors(&wrong).contains("momentum-basis row `turning` is not in g(D)"));
}

/// The values of `exact` and `computed` at one random point, entry by
/// entry, to 1e-12 relative.
fn assert_same_values(cx: &mut Context, exact: &Matrix, computed: &Matrix<crate::sym::ExprId>) {
    let mut random = crate::sym::zero::SplitMix::new(7);
    let values: std::collections::HashMap<_, f64> = cx
        .symbols()
        .map(|(id, _)| (id, random.uniform(-1.0, 1.0)))
        .collect();
    let value_of = |s| values[&s];
    for i in 0..exact.rows() {
        for j in 0..exact.columns() {
            let expected = cx.evaluate_normal(exact.get(i, j), &value_of);
            let found = cx.evaluate(*computed.get(i, j), &value_of);
            assert!(
                (expected - found).abs() <= 1e-12 * (1.0 + expected.abs()),
                "[{i}][{j}]: {expected} vs {found}"
            );
        }
    }
}

/// The benchmark bicycle's rows as the emitted code computes them (the
/// rolling rows' entries as the expressions they were derived as) take the
/// values of their exact normal forms, at a fraction of the weight of the
/// normal forms written out.
#[test]
fn the_bicycles_rows_keep_their_derivation_and_its_values() {
    let (model, mut cx) = checked(include_str!("../../../models/bicycle.model"));
    let (exact, computed) = (
        model.constraint_matrix.clone(),
        model.constraint_expressions.clone(),
    );
    assert_same_values(&mut cx, &exact, &computed);
    let expanded = model.constraint_matrix.to_expressions(&mut cx);
    let written_out = crate::ir::estimated_weight(&cx, &expanded);
    let kept = crate::ir::estimated_weight(&cx, model.constraint_expressions.entries());
    assert!(kept * 2 < written_out, "{kept} vs {written_out}");
}
/// Kane's form of the bodies' metric, `sum m J_v^T J_v + J_w^T I J_w`,
/// has the normal forms of `d^2 T / d qdot^2` of the bodies' `T`, exactly,
/// for bodies turning in three dimensions (the leaning disk, the caster
/// robot's wheels and fork) and a particle (the sleigh's).
#[test]
fn the_bodies_kane_metric_is_the_hessian_of_their_energy() {
    for source in [
        include_str!("../../../models/rolling_disk_3d.model"),
        include_str!("../../../models/caster_robot.model"),
        include_str!("../../../models/sleigh_bodies.model"),
        include_str!("../../../models/chaplygin_ball.model"),
    ] {
        let (model, mut cx) = checked(source);
        let velocities = model.velocities.clone();
        let n = velocities.len();
        let kinetic = model.mechanism.kinetic_energy.clone();
        let rates = cx
            .jacobian(std::slice::from_ref(&kinetic), &velocities)
            .expect("fits");
        let hessian = cx.jacobian(rates.entries(), &velocities).expect("fits");
        let mut kane = vec![cx.integer(0); n * n];
        for body in model.energy_expressions.bodies.clone() {
            let entries = body.mass_matrix(&mut cx, &velocities);
            for (sum, entry) in kane.iter_mut().zip(entries) {
                *sum = cx.add2(*sum, entry);
            }
        }
        for (index, &entry) in kane.iter().enumerate() {
            let form = cx.normal(entry).expect("fits");
            let exact = hessian.get(index / n, index % n);
            let difference = form.sub(exact, cx.atoms());
            assert!(difference.is_zero(), "{}: g[{index}]", model.name);
        }
    }
}

/// The benchmark bicycle's `g` as the emitted code computes it (its large
/// entries in Kane's form) takes the values of its exact normal forms.
#[test]
fn the_bicycles_metric_as_computed_takes_its_exact_values() {
    let (model, mut cx) = checked(include_str!("../../../models/bicycle.model"));
    let (exact, computed) = (
        model.mass_matrix.clone(),
        model.energy_expressions.mass_matrix.clone(),
    );
    assert_same_values(&mut cx, &exact, &computed);
}
