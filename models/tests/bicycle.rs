//! The benchmark bicycle of Meijaard, Papadopoulos, Ruina and Schwab (2007),
//! compiled from `models/bicycle.model`: its linearization about upright
//! straight running against the closed form of the paper's appendix
//! (written out independently from the 25 parameters in
//! `support/benchmark_bicycle.rs`), its exact Jacobians against central
//! differences, its formulations against each other, and the interpreter's
//! programs of the same text against the compiled functions.

use crate::common::{assert_close, check_jacobians};
use crate::support::benchmark_bicycle::BenchmarkParameters;
use chaplygin::runtime::linalg::central_difference_jacobian;
use chaplygin::runtime::linearize::point::configuration;
use chaplygin::runtime::linearize::{Compiled, OperatingPoint, linearize};
use chaplygin_codegen::interpret::InterpretedModel;
use chaplygin_models::bicycle::{Bicycle, MODEL_TEXT};

/// Upright straight running at `v`: `dot(theta_r) = -v / rR`, lean, steer
/// and their rates zero, the rest solved from the constraints.
fn upright(model: &Compiled<'_, Bicycle, 8, 5, 2, 1>, bicycle: &Bicycle, v: f64) -> OperatingPoint {
    let mut coordinates = [None; 8];
    coordinates[3] = Some(0.0);
    coordinates[5] = Some(0.0);
    let mut velocities = [None; 8];
    velocities[3] = Some(0.0);
    velocities[5] = Some(0.0);
    velocities[6] = Some(-v / bicycle.rR);
    OperatingPoint::solve(model, &coordinates, &velocities).expect("upright running")
}

/// At v = 0, 1, ..., 10 m/s the compiled bicycle's non-zero eigenvalues
/// (the fifth, zero, is the front wheel's conserved spin rate) are the
/// paper's closed form to 1e-9 relative.
#[test]
fn the_compiled_bicycles_eigenvalues_are_the_papers() {
    let bicycle = Bicycle::default();
    let model = Compiled::holonomic(&bicycle);
    let reference = BenchmarkParameters::benchmark();
    for step in 0..=10 {
        let v = f64::from(step);
        let point = upright(&model, &bicycle, v);
        let linear = linearize(&model, &point, &[0.0, 0.0], &[]).expect("a relative equilibrium");
        let nonzero: Vec<_> = linear
            .eigenvalues
            .iter()
            .copied()
            .filter(|&s| !linear.is_zero(s))
            .collect();
        assert_eq!(nonzero.len(), 4, "at v = {v}: {:?}", linear.eigenvalues);
        for s in reference.eigenvalues(v) {
            let closest = nonzero
                .iter()
                .map(|d| (d - s).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                closest <= 1e-9 * s.norm(),
                "at v = {v}: {s} is {closest:e} from {nonzero:?}"
            );
        }
    }
}

/// A configuration on `f(q) = 0`, leaning and steered: the pitch solved by
/// the runtime from the front contact's height.
fn leaning(bicycle: &Bicycle) -> [f64; 8] {
    let model = Compiled::holonomic(bicycle);
    let mut given = [0.4, -0.2, 0.3, 0.15, 0.0, -0.25, 1.1, -0.6].map(Some);
    given[4] = None;
    let q = configuration(&model, &given).expect("the pitch solved");
    let residual = bicycle.holonomic_residual(&std::array::from_fn(|i| q[i]));
    assert!(residual[0].abs() < 1e-12, "{residual:?}");
    std::array::from_fn(|i| q[i])
}

/// The exact `acceleration_jacobian` and `holonomic_jacobian` are the
/// central differences of `acceleration` and `holonomic_residual`, leaning,
/// steered and rolling.
#[test]
fn the_compiled_jacobians_are_the_derivatives() {
    let bicycle = Bicycle::default();
    let q = leaning(&bicycle);
    let qdot = [1.2, -0.3, 0.4, 0.3, 0.05, -0.4, -10.0, -8.0];
    check_jacobians(&bicycle, q, qdot, [0.7, -0.2]);
    assert_close(
        &bicycle.holonomic_jacobian(&q),
        &central_difference_jacobian(|q| bicycle.holonomic_residual(q), &q),
        "df/dq",
    );
}

/// In both charts of D, `reduced_rhs_jacobian` (the chain rule through
/// `acceleration_jacobian`) is the central differences of `reduced_rhs`
/// (the structured reduced form, which does not solve the
/// Lagrange-d'Alembert system), leaning, steered and rolling.
#[test]
fn the_reduced_jacobians_are_the_derivatives_of_the_reduced_flow() {
    let bicycle = Bicycle::default();
    let q = leaning(&bicycle);
    let qdot = bicycle.velocities(&q, &[0.3, -0.4, -10.0]);
    let u = [0.7, -0.2];
    let state = |alpha: [f64; 3]| -> [f64; 11] {
        std::array::from_fn(|i| if i < 8 { q[i] } else { alpha[i - 8] })
    };
    let x = state(bicycle.momenta(&q, &qdot));
    assert_close(
        &bicycle.reduced_rhs_jacobian(&x, &u),
        &central_difference_jacobian(|x| bicycle.reduced_rhs(x, &u), &x),
        "d xdot/dx in chart 0",
    );
    let x = state(bicycle.momenta_chart1(&q, &qdot));
    assert_close(
        &bicycle.reduced_rhs_jacobian_chart1(&x, &u),
        &central_difference_jacobian(|x| bicycle.reduced_rhs_chart1(x, &u), &x),
        "d xdot/dx in chart 1",
    );
}

/// The interpreter runs the programs the compiled functions were emitted
/// from: the same numbers, to round-off, at a leaning, rolling state.
#[test]
fn the_interpreted_bicycle_computes_what_the_compiled_one_does() {
    let bicycle = Bicycle::default();
    let interpreted = InterpretedModel::from_source(MODEL_TEXT).expect("derives");
    let q = leaning(&bicycle);
    let qdot = [1.2, -0.3, 0.4, 0.3, 0.05, -0.4, -10.0, -8.0];
    let u = [0.7, -0.2];
    let (qddot, lambda) = bicycle.acceleration(&q, &qdot, &u);
    let (interpreted_qddot, interpreted_lambda) =
        interpreted.acceleration(&q, &qdot, &u).expect("runs");
    let compiled: Vec<f64> = qddot.iter().chain(&lambda).copied().collect();
    let run: Vec<f64> = interpreted_qddot
        .iter()
        .chain(&interpreted_lambda)
        .copied()
        .collect();
    for (c, i) in compiled.iter().zip(&run) {
        assert!(
            (c - i).abs() <= 1e-12 * (1.0 + c.abs()),
            "{compiled:?} vs {run:?}"
        );
    }
    let energy = bicycle.energy(&q, &qdot);
    let interpreted_energy = interpreted.energy(&q, &qdot).expect("runs");
    assert!((energy - interpreted_energy).abs() <= 1e-12 * energy.abs());
}
