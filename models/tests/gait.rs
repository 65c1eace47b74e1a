//! The three-link kinematic snake's local connection and its curvature
//! (MATH.md section 4.3): against the hand derivation in the model's
//! documentation, central differences, Stokes' theorem, the curvature times
//! the area of small loops, and the configuration-level constraints
//! integrated on their own.

use crate::common::Random;
use chaplygin::jit::JitModel;
use chaplygin::runtime::gait::{self, Cycle, FromEquations, ShapeLoop};
use chaplygin_codegen::interpret::InterpretedModel;
use chaplygin_models::three_link_snake::ThreeLinkSnake;
use nalgebra::{SMatrix, SVector};
use std::f64::consts::PI;

/// `A(r)` (3 x 2, `xi = -A rdot`) from the module documentation.
fn hand_connection(snake: &ThreeLinkSnake, r: [f64; 2]) -> [[f64; 2]; 3] {
    let ((s1, c1), (s2, c2)) = (r[0].sin_cos(), r[1].sin_cos());
    let h = snake.l / 2.0;
    let d = h * (s1 * (1.0 + c2) - s2 * (1.0 + c1));
    [
        [h * h * (1.0 + c2) / d, h * h * (1.0 + c1) / d],
        [0.0, 0.0],
        [h * s2 / d, h * s1 / d],
    ]
}

/// A shape at least `margin` (in `|d| / (l/2)`) from the singular set.
fn regular_shape(random: &mut Random, margin: f64) -> [f64; 2] {
    loop {
        let r = [random.uniform(-2.5, 2.5), random.uniform(-2.5, 2.5)];
        let ((s1, c1), (s2, c2)) = (r[0].sin_cos(), r[1].sin_cos());
        if (s1 * (1.0 + c2) - s2 * (1.0 + c1)).abs() > margin {
            return r;
        }
    }
}

fn close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance * (1.0 + expected.abs()),
        "{what}: {actual} vs {expected}"
    );
}

/// `nonholonomic_connection` and `body_velocity` equal the hand
/// derivation, and stay finite on the line `a1 = -a2` where the engine's
/// normal form of the same connection divides 0 by 0.
#[test]
fn connection_matches_the_hand_derivation() {
    let snake = ThreeLinkSnake::default();
    let mut random = Random::new(43);
    let mut shapes: Vec<[f64; 2]> = (0..200).map(|_| regular_shape(&mut random, 0.05)).collect();
    shapes.extend([[0.7, -0.7], [-1.3, 1.3], [0.25, -0.25]]);
    for r in shapes {
        let hand = hand_connection(&snake, r);
        let emitted = snake.nonholonomic_connection(&r);
        let rdot = [random.uniform(-1.0, 1.0), random.uniform(-1.0, 1.0)];
        let xi = snake.body_velocity(&r, &rdot, &[]);
        for k in 0..3 {
            for j in 0..2 {
                close(emitted[k][j], hand[k][j], 1e-12, "A");
            }
            let expected = -(hand[k][0] * rdot[0] + hand[k][1] * rdot[1]);
            close(xi[k], expected, 1e-12, "xi");
        }
    }
}

/// `F = -(dA_2/da1 - dA_1/da2) + [A_1, A_2]` with se(2)'s bracket.
fn curvature_by_differences(snake: &ThreeLinkSnake, r: [f64; 2]) -> [f64; 3] {
    let h = 1e-5;
    let at = |da1: f64, da2: f64| hand_connection(snake, [r[0] + da1, r[1] + da2]);
    let a = at(0.0, 0.0);
    let (plus1, minus1, plus2, minus2) = (at(h, 0.0), at(-h, 0.0), at(0.0, h), at(0.0, -h));
    let exterior: [f64; 3] = std::array::from_fn(|k| {
        let d2_d1 = (plus1[k][1] - minus1[k][1]) / (2.0 * h);
        let d1_d2 = (plus2[k][0] - minus2[k][0]) / (2.0 * h);
        -(d2_d1 - d1_d2)
    });
    let column = |j: usize| (a[0][j], a[1][j], a[2][j]);
    let ((a1, b1, w1), (a2, b2, w2)) = (column(0), column(1));
    let bracket = [w2 * b1 - w1 * b2, w1 * a2 - w2 * a1, 0.0];
    std::array::from_fn(|k| exterior[k] + bracket[k])
}

/// `connection_curvature` equals central differences of the hand
/// connection with the bracket added.
#[test]
fn curvature_matches_differences_of_the_hand_connection() {
    let snake = ThreeLinkSnake::default();
    let mut random = Random::new(44);
    for _ in 0..200 {
        let r = regular_shape(&mut random, 0.2);
        let expected = curvature_by_differences(&snake, r);
        let emitted = snake.connection_curvature(&r);
        let scale = expected.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        for k in 0..3 {
            assert!(
                (emitted[k][0] - expected[k]).abs() <= 1e-7 * scale,
                "F[{k}] at {r:?}: {} vs {}",
                emitted[k][0],
                expected[k]
            );
        }
    }
}

/// The curvature item is the same compiled by rustc, JIT-compiled and
/// interpreted, to 1e-12 relative to the largest entry.
#[test]
fn curvature_is_the_same_on_every_engine() {
    let snake = ThreeLinkSnake::default();
    let text = chaplygin_models::three_link_snake::MODEL_TEXT;
    let jit = JitModel::from_source(text).expect("derives and compiles");
    let interpreted = InterpretedModel::from_source(text).expect("derives");
    let mut random = Random::new(45);
    for _ in 0..100 {
        let r = regular_shape(&mut random, 0.05);
        let compiled = snake.connection_curvature(&r).concat();
        let scale = compiled.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        for engine in [
            jit.call("connection_curvature", &[&r]),
            interpreted.call("connection_curvature", &[&r]),
        ] {
            let values = engine.expect("evaluates");
            for (a, b) in compiled.iter().zip(&values) {
                assert!((a - b).abs() <= 1e-12 * scale, "{compiled:?} vs {values:?}");
            }
        }
    }
}

/// One cycle of the circle of radius `radius` about `centre`,
/// counterclockwise in the plane `(a1, a2)`, period `2 pi`.
fn circle_cycle(snake: &ThreeLinkSnake, centre: [f64; 2], radius: f64, steps: usize) -> Cycle {
    let circle = |t: f64| {
        let (sin, cos) = t.sin_cos();
        (
            vec![centre[0] + radius * cos, centre[1] + radius * sin],
            vec![-radius * sin, radius * cos],
        )
    };
    let shape_loop = ShapeLoop {
        shape: &circle,
        period: 2.0 * PI,
    };
    let body = FromEquations::new(snake, [0, 1, 2]);
    let mut cycles = gait::run(
        &body,
        &shape_loop,
        (&[0.0; 5], &[]),
        (1, steps),
        &mut |_, _| {},
    );
    cycles.remove(0)
}

/// The integral of `connection_curvature` over the disk of radius
/// `radius` about `centre`: in polar coordinates, the trapezoid rule in the
/// angle (spectrally accurate for a periodic integrand) and Simpson's rule
/// in the radius.
fn curvature_over_disk(snake: &ThreeLinkSnake, centre: [f64; 2], radius: f64) -> [f64; 3] {
    let (angles, radii) = (256, 200);
    let mut total = [0.0; 3];
    for i in 0..angles {
        let (sin, cos) = (2.0 * PI * i as f64 / angles as f64).sin_cos();
        for j in 0..=radii {
            let rho = radius * j as f64 / radii as f64;
            let weight = match j {
                0 => 1.0,
                j if j == radii => 1.0,
                j if j % 2 == 1 => 4.0,
                _ => 2.0,
            } * radius
                / (3.0 * radii as f64)
                * rho
                * 2.0
                * PI
                / angles as f64;
            let f = snake.connection_curvature(&[centre[0] + rho * cos, centre[1] + rho * sin]);
            for k in 0..3 {
                total[k] += weight * f[k][0];
            }
        }
    }
    total
}

/// Stokes: se(2)'s bracket has no rotation part, so the rotation over a
/// loop is exactly the curvature's rotation entry integrated over the
/// enclosed area.
#[test]
fn rotation_over_a_loop_is_the_curvature_over_its_area() {
    let snake = ThreeLinkSnake::default();
    for (centre, radius) in [([0.8, -0.3], 0.35), ([-0.4, 0.9], 0.5)] {
        let turned = circle_cycle(&snake, centre, radius, 4000).displacement[2];
        let integral = curvature_over_disk(&snake, centre, radius)[2];
        assert!(integral.abs() > 1e-2, "a loop that turns: {integral}");
        assert!(
            (turned - integral).abs() < 1e-8,
            "theta {turned} vs the curvature's integral {integral}"
        );
    }
}

/// A loop of area `pi eps^2` about `r` moves the body by `F(r) pi eps^2`
/// up to `O(eps^3)`: halving `eps` divides the error by at least 2^2.5.
#[test]
fn small_loops_move_by_the_curvature_times_the_area() {
    let snake = ThreeLinkSnake::default();
    let centre = [0.9, -0.4];
    let f = snake.connection_curvature(&centre);
    let errors: Vec<f64> = [0.08, 0.04, 0.02]
        .iter()
        .map(|&eps| {
            let moved = circle_cycle(&snake, centre, eps, 2000).displacement;
            let area = PI * eps * eps;
            let error = (0..3)
                .map(|k| (moved[k] - f[k][0] * area).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(error < 0.1 * area * f[0][0].abs(), "eps {eps}: {moved:?}");
            error
        })
        .collect();
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!(order > 2.5, "errors {errors:?}: order {order}");
    }
}

/// The configuration's velocity from the constraints alone: `A(q) qdot =
/// 0` with the joint rates prescribed, solved numerically.
fn constrained_velocity(snake: &ThreeLinkSnake, q: &[f64; 5], rdot: [f64; 2]) -> [f64; 5] {
    let rows = snake.constraint_matrix(q);
    let mut system = SMatrix::<f64, 5, 5>::zeros();
    for (i, row) in rows.iter().enumerate() {
        for (j, &entry) in row.iter().enumerate() {
            system[(i, j)] = entry;
        }
    }
    system[(3, 3)] = 1.0;
    system[(4, 4)] = 1.0;
    let rhs = SVector::<f64, 5>::from([0.0, 0.0, 0.0, rdot[0], rdot[1]]);
    let qdot = system.lu().solve(&rhs).expect("a regular shape");
    std::array::from_fn(|i| qdot[i])
}

/// A figure-eight loop's displacement from the connection equals the
/// configuration-level constraints integrated with the same RK4 steps.
#[test]
fn a_loop_moves_the_snake_as_its_constraints_do() {
    let snake = ThreeLinkSnake::default();
    let law = |t: f64| {
        (
            [0.8 + 0.35 * t.cos(), -0.3 + 0.25 * (2.0 * t).sin()],
            [-0.35 * t.sin(), 0.5 * (2.0 * t).cos()],
        )
    };
    let shape = |t: f64| {
        let (r, rdot) = law(t);
        (r.to_vec(), rdot.to_vec())
    };
    let steps = 2000;
    let body = FromEquations::new(&snake, [0, 1, 2]);
    let shape_loop = ShapeLoop {
        shape: &shape,
        period: 2.0 * PI,
    };
    let cycle = gait::run(
        &body,
        &shape_loop,
        (&[0.0; 5], &[]),
        (1, steps),
        &mut |_, _| {},
    );
    let rate = |t: f64, q: &[f64; 5]| constrained_velocity(&snake, q, law(t).1);
    let h = 2.0 * PI / steps as f64;
    let mut q = [0.0, 0.0, 0.0, law(0.0).0[0], law(0.0).0[1]];
    for k in 0..steps {
        let t = k as f64 * h;
        let moved = |q: &[f64; 5], k: &[f64; 5], s: f64| -> [f64; 5] {
            std::array::from_fn(|i| q[i] + s * k[i])
        };
        let k1 = rate(t, &q);
        let k2 = rate(t + h / 2.0, &moved(&q, &k1, h / 2.0));
        let k3 = rate(t + h / 2.0, &moved(&q, &k2, h / 2.0));
        let k4 = rate(t + h, &moved(&q, &k3, h));
        q = std::array::from_fn(|i| q[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    let expected = gait::relative(&[0.0; 3], &[q[0], q[1], q[2]]);
    assert!(expected[0].abs() > 1e-2, "a loop that moves: {expected:?}");
    for k in 0..3 {
        assert!(
            (cycle[0].displacement[k] - expected[k]).abs() < 1e-8,
            "{:?} vs {expected:?}",
            cycle[0].displacement
        );
    }
}
