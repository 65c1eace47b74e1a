use super::{Momentum, MomentumError, derive};
use crate::ir::Interpreter;
use crate::model::{Model, check};
use crate::sym::Context;
use crate::sym::zero::SplitMix;
use crate::sym::{Matrix, RationalFunction, SymbolId};
use crate::syntax::parse_str;
use std::collections::HashMap;

const SLEIGH: &str = include_str!("../../../../models/sleigh.model");

fn derived(source: &str) -> (Model, Context, Momentum) {
    let (model, mut cx) = check(&parse_str(source).expect("parses")).expect("checks");
    let momentum = derive(&model, &mut cx, &Interpreter).expect("derives");
    (model, cx, momentum)
}

/// Values of the named symbols, the parameters at their defaults.
fn point(model: &Model, values: &[(SymbolId, f64)]) -> impl Fn(SymbolId) -> f64 + use<> {
    let mut all: HashMap<SymbolId, f64> = model
        .parameters
        .iter()
        .map(|p| (p.variable.symbol, p.default.to_f64()))
        .collect();
    all.extend(values.iter().copied());
    move |s| all.get(&s).copied().unwrap_or(0.0)
}

fn evaluate(
    cx: &mut Context,
    entries: &[RationalFunction],
    at: &dyn Fn(SymbolId) -> f64,
) -> Vec<f64> {
    Matrix::new(entries.len(), 1, entries.to_vec())
        .expect("a column")
        .evaluate(cx, at)
}

fn coordinate(model: &Model, name: &str) -> usize {
    model
        .coordinates
        .iter()
        .position(|c| c.declared.name == name)
        .expect("declared")
}

fn close(actual: f64, expected: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
        "{what}: {actual} vs {expected}"
    );
}

/// Snakeboard (m = 1, r = 0.5, jt = 0.3 by default): the tool's basis is
/// MATH.md 4.1's `e = (cos phi, 0, sin phi / r)`, and its hand-derived
/// momentum equation, reconstruction and coefficient tensors follow.
#[test]
fn snakeboard_matches_the_hand_derivation() {
    let (model, mut cx, momentum) = derived(crate::fixtures::SNAKEBOARD);
    let (m, r, jt) = (1.0, 0.5, 0.3);
    let [psi, phi] = [coordinate(&model, "psi"), coordinate(&model, "phi")];
    assert_eq!(momentum.shape, vec![psi, phi]);
    assert_eq!(momentum.momenta.len(), 1);
    assert!(
        momentum.input_coupling.is_zero(),
        "the inputs act on the shape"
    );
    let mut random = SplitMix::new(5);
    for _ in 0..1000 {
        let (phi_value, psidot, phidot, p) = (
            random.uniform(-3.0, 3.0),
            random.uniform(-2.0, 2.0),
            random.uniform(-2.0, 2.0),
            random.uniform(-2.0, 2.0),
        );
        let at = point(
            &model,
            &[
                (model.coordinates[phi].symbol, phi_value),
                (model.coordinates[psi].symbol, random.uniform(-3.0, 3.0)),
                (momentum.shape_velocities[0], psidot),
                (momentum.shape_velocities[1], phidot),
                (momentum.momenta[0], p),
            ],
        );
        let (sin, cos) = phi_value.sin_cos();
        let basis = momentum.basis.evaluate(&mut cx, &at);
        for (actual, expected) in basis.iter().zip([cos, 0.0, sin / r]) {
            close(*actual, expected, "e");
        }
        let delta = m * r * r + jt * sin * sin;
        let pdot_hand =
            m * r * jt * cos / delta * psidot * phidot + jt * sin * cos / delta * phidot * p;
        close(evaluate(&mut cx, &momentum.rhs, &at)[0], pdot_hand, "pdot");
        let v1 = r * cos * (r * p - jt * sin * psidot) / delta;
        let xi = evaluate(&mut cx, &momentum.body_velocity, &at);
        for (actual, expected) in xi.iter().zip([v1, 0.0, v1 * sin / cos / r]) {
            close(*actual, expected, "xi");
        }
        let h = m * r * jt * cos / (2.0 * delta);
        let tensors = &momentum.coefficients[0];
        let shape = tensors.shape.evaluate(&mut cx, &at);
        for (actual, expected) in shape.iter().zip([0.0, h, h, 0.0]) {
            close(*actual, expected, "H");
        }
        let mixed = tensors.mixed.evaluate(&mut cx, &at);
        for (actual, expected) in mixed.iter().zip([0.0, jt * sin * cos / delta]) {
            close(*actual, expected, "K");
        }
        assert!(tensors.momentum.is_zero(), "D = 0");
    }
}

/// `p = <dL/dqdot, cos phi cos theta d_x + cos phi sin theta d_y + (sin phi / r) d_theta>`
/// (MATH.md 4.1), from the Lagrangian by hand.
#[test]
fn snakeboard_momentum_of_the_state() {
    let (model, mut cx, momentum) = derived(crate::fixtures::SNAKEBOARD);
    let (m, r, jt) = (1.0, 0.5, 0.3);
    let j = jt + m * r * r;
    let mut random = SplitMix::new(6);
    for _ in 0..1000 {
        let q: Vec<f64> = (0..5).map(|_| random.uniform(-3.0, 3.0)).collect();
        let qdot: Vec<f64> = (0..5).map(|_| random.uniform(-2.0, 2.0)).collect();
        let mut values: Vec<(SymbolId, f64)> = model
            .coordinates
            .iter()
            .map(|c| c.symbol)
            .zip(q.iter().copied())
            .collect();
        values.extend(model.velocities.iter().copied().zip(qdot.iter().copied()));
        let at = point(&model, &values);
        let p = evaluate(&mut cx, &momentum.momentum, &at)[0];
        let (theta, phi) = (q[2], q[4]);
        let hand = phi.cos() * m * (theta.cos() * qdot[0] + theta.sin() * qdot[1])
            + phi.sin() / r * (j * qdot[2] + jt * qdot[3]);
        close(p, hand, "p");
    }
}

/// The sleigh has no shape: `pdot = p^T D p`, the Euler-Poincare-Suslov form,
/// with the tool's basis `e1 = (1, 0, 0)`, `e2 = (0, 0, 1)` of `v2 = 0`.
/// By hand (l = m/2 ((v1)^2 + (v2 + a w)^2) + inertia/2 w^2, v2 = 0):
/// `p1 = m v1`, `p2 = (inertia + m a^2) w`, `p1dot = m a w^2`,
/// `p2dot = -m a v1 w`.
#[test]
fn sleigh_is_euler_poincare_suslov() {
    let (model, mut cx, momentum) = derived(SLEIGH);
    let (m, inertia, a) = (1.0, 0.1, 0.5);
    assert!(momentum.shape.is_empty());
    let mut random = SplitMix::new(7);
    for _ in 0..1000 {
        let (p1, p2) = (random.uniform(-2.0, 2.0), random.uniform(-2.0, 2.0));
        let at = point(
            &model,
            &[(momentum.momenta[0], p1), (momentum.momenta[1], p2)],
        );
        let (v1, w) = (p1 / m, p2 / (inertia + m * a * a));
        let rhs = evaluate(&mut cx, &momentum.rhs, &at);
        close(rhs[0], m * a * w * w, "p1dot");
        close(rhs[1], -m * a * v1 * w, "p2dot");
        let xi = evaluate(&mut cx, &momentum.body_velocity, &at);
        for (actual, expected) in xi.iter().zip([v1, 0.0, w]) {
            close(*actual, expected, "xi");
        }
    }
}

#[test]
fn a_model_without_symmetry_is_refused() {
    let source = SLEIGH.replace("    symmetry: se2(x, y, theta),\n", "");
    let (model, mut cx) = check(&parse_str(&source).expect("parses")).expect("checks");
    assert_eq!(
        derive(&model, &mut cx, &Interpreter).err(),
        Some(MomentumError::NoSymmetry)
    );
}

/// The sleigh with the abelian group of translations: shape `theta`, S spanned
/// by `e = (cos theta, sin theta)` (the blade's direction). By hand, on D:
/// `p = m (cos theta xdot + sin theta ydot)`, the horizontal part is zero,
/// `pdot = m a thetadot^2` (H = m a, K = 0, D = 0), `xi = e p / m`.
#[test]
fn sleigh_under_translations() {
    let source = SLEIGH.replace("se2(x, y, theta)", "translation(x) * translation(y)");
    let (model, mut cx, momentum) = derived(&source);
    let (m, a) = (1.0, 0.5);
    assert_eq!(momentum.shape, vec![coordinate(&model, "theta")]);
    assert!(momentum.connection.is_zero());
    let mut random = SplitMix::new(8);
    for _ in 0..1000 {
        let q: Vec<f64> = (0..3).map(|_| random.uniform(-3.0, 3.0)).collect();
        let qdot: Vec<f64> = (0..3).map(|_| random.uniform(-2.0, 2.0)).collect();
        let p = random.uniform(-2.0, 2.0);
        let mut values: Vec<(SymbolId, f64)> = model
            .coordinates
            .iter()
            .map(|c| c.symbol)
            .zip(q.iter().copied())
            .collect();
        values.extend(model.velocities.iter().copied().zip(qdot.iter().copied()));
        values.push((momentum.momenta[0], p));
        let at = point(&model, &values);
        let (sin, cos) = q[2].sin_cos();
        let expected = m * (cos * qdot[0] + sin * qdot[1]);
        close(evaluate(&mut cx, &momentum.momentum, &at)[0], expected, "p");
        close(
            evaluate(&mut cx, &momentum.rhs, &at)[0],
            m * a * qdot[2] * qdot[2],
            "pdot",
        );
        let xi = evaluate(&mut cx, &momentum.body_velocity, &at);
        close(xi[0], cos * p / m, "xdot");
        close(xi[1], sin * p / m, "ydot");
        let shape = momentum.coefficients[0].shape.evaluate(&mut cx, &at);
        close(shape[0], m * a, "H");
    }
    assert!(momentum.coefficients[0].mixed.is_zero());
    assert!(momentum.coefficients[0].momentum.is_zero());
}

/// The vertical rolling disk (m = 1, R = 0.5, J_axle = 0.125, J_vertical =
/// 0.0625) under `se2(x, y, theta) * rotation(phi)`: no shape, S spanned by
/// `(0, 0, 1, 0)` (turning) and `(R, 0, 0, 1)` (rolling). By hand, both
/// momenta are conserved: `p1 = J_vertical thetadot`,
/// `p2 = m R (cos theta xdot + sin theta ydot) + J_axle phidot`, and
/// `xi = (R nu, 0, p1 / J_vertical, nu)` with `nu = p2 / (m R^2 + J_axle)`.
/// With the inputs (torques on `theta` and `phi`), `pdot = h B u = u`.
#[test]
fn rolling_disk_under_se2_and_rotation() {
    let source = r#"
        pub struct RollingDisk {
            coordinates: [x, y, theta, phi],
            parameters: [m = 1.0, r = 0.5, j_axle = 0.125, j_vertical = 0.0625],
            kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + j_axle/2*dot(phi)^2
                + j_vertical/2*dot(theta)^2,
            potential_energy: 0,
            constraints: [
                roll_x = dot(x) - r*cos(theta)*dot(phi),
                roll_y = dot(y) - r*sin(theta)*dot(phi),
            ],
            inputs: [u_steer = theta, u_drive = phi],
            symmetry: se2(x, y, theta) * rotation(phi),
        }
    "#;
    let (model, mut cx, momentum) = derived(source);
    let (m, r, j_axle, j_vertical) = (1.0, 0.5, 0.125, 0.0625);
    assert!(momentum.shape.is_empty());
    assert_eq!(momentum.momenta.len(), 2);
    assert!(momentum.rhs.iter().all(RationalFunction::is_zero));
    assert_eq!(
        momentum.input_coupling,
        Matrix::identity(2),
        "the steering torque drives p1, the driving torque p2"
    );
    let mut random = SplitMix::new(9);
    for _ in 0..1000 {
        let q: Vec<f64> = (0..4).map(|_| random.uniform(-3.0, 3.0)).collect();
        let qdot: Vec<f64> = (0..4).map(|_| random.uniform(-2.0, 2.0)).collect();
        let p = [random.uniform(-2.0, 2.0), random.uniform(-2.0, 2.0)];
        let mut values: Vec<(SymbolId, f64)> = model
            .coordinates
            .iter()
            .map(|c| c.symbol)
            .zip(q.iter().copied())
            .collect();
        values.extend(model.velocities.iter().copied().zip(qdot.iter().copied()));
        values.extend(momentum.momenta.iter().copied().zip(p));
        let at = point(&model, &values);
        let (sin, cos) = q[2].sin_cos();
        let state = evaluate(&mut cx, &momentum.momentum, &at);
        close(state[0], j_vertical * qdot[2], "p1");
        close(
            state[1],
            m * r * (cos * qdot[0] + sin * qdot[1]) + j_axle * qdot[3],
            "p2",
        );
        let nu = p[1] / (m * r * r + j_axle);
        let xi = evaluate(&mut cx, &momentum.body_velocity, &at);
        for (actual, expected) in xi.iter().zip([r * nu, 0.0, p[0] / j_vertical, nu]) {
            close(*actual, expected, "xi");
        }
    }
}

/// The roller racer's body constraints at the identity are `v2 = 0` and
/// `-sin(phi) v1 + (d1 cos(phi) - d2) omega = 0` (the front axle's row with
/// `rdot = 0`), so S is spanned by `(d2 - d1 cos(phi), 0, -sin(phi))`, which
/// vanishes nowhere for `d1 != d2`; scaled to 1 at the defaults, by
/// `d2 - d1`. The null space of the elimination carries a factor `sin(phi)`
/// in every entry; it is divided out.
#[test]
fn the_racers_momentum_basis_has_no_removable_factor() {
    let (model, mut cx, momentum) =
        derived(include_str!("../../../../tests/models/roller_racer.model"));
    let expected: Vec<RationalFunction> =
        ["(d2 - d1*cos(phi))/(d2 - d1)", "0", "-sin(phi)/(d2 - d1)"]
            .iter()
            .map(|text| model.normal_of_text(&mut cx, text).expect("parses"))
            .collect();
    let atoms = cx.atoms().clone();
    for (entry, expected) in momentum.basis.entries().iter().zip(&expected) {
        assert!(entry.sub(expected, &atoms).is_zero());
    }
}

/// A group of more dimensions than `CRAMER_LIMIT` (eight translations of
/// free particles beside a shape) keeps the normal form's connection, over
/// 1, instead of expanding 8! cofactors.
#[test]
fn a_large_group_keeps_the_normal_form_connection() {
    let coordinates: Vec<String> = (1..=8).map(|i| format!("x{i}")).collect();
    let energy: Vec<String> = coordinates.iter().map(|x| format!("dot({x})^2")).collect();
    let factors: Vec<String> = coordinates
        .iter()
        .map(|x| format!("translation({x})"))
        .collect();
    let source = format!(
        "pub struct Particles {{\n    coordinates: [{}, s],\n    parameters: [m = 1.0],\n    \
         kinetic_energy: m/2*({} + dot(s)^2),\n    potential_energy: 0,\n    \
         constraints: [],\n    symmetry: {},\n}}\n",
        coordinates.join(", "),
        energy.join(" + "),
        factors.join(" * ")
    );
    let (_, _cx, momentum) = derived(&source);
    assert_eq!(momentum.basis.columns(), 8);
    const { assert!(super::curvature::CRAMER_LIMIT < 8) };
    assert_eq!(
        momentum.connection_quotient.denominator,
        RationalFunction::one()
    );
    assert_eq!(momentum.connection_quotient.numerators, momentum.connection);
}
