//! Gait design (docs/MATH.md 4.4) on the three-link kinematic snake and on
//! the snakeboard, which carries momentum: the exact gradients of a loop's
//! displacement, length and barrier against central differences of the
//! integrated values, and the curvature's route against forward
//! sensitivities; the optimum a stationary point of its cost that beats
//! 1000 random loops of the same harmonics off the singular set.

use crate::support::snakeboard_gait::hand_derived_cycle;
use chaplygin::driver::catalog::{Source, built_in};
use chaplygin::driver::engine::{EngineChoice, Loaded, load};
use chaplygin::driver::gait::locomotion;
use chaplygin::gait_design::{
    Cost, Design, Direction, Evaluation, FourierLoop, GaitModel, Optimum, Scoring, by_curvature,
    by_sensitivities, clearances, evaluate, optimize,
};
use chaplygin::runtime::gait::{self, ShapeLoop};
use std::f64::consts::PI;

fn loaded(name: &str) -> Loaded {
    let source = Source::BuiltIn(built_in(name).expect("built in"));
    load(&source, EngineChoice::Jit).expect("derives")
}

fn snake() -> Loaded {
    loaded("three-link-snake")
}

/// The clearance where the barrier starts for the snake (l = 1): a quarter
/// of `max |d| = (l/2) 3 sqrt(3) / 2`, as `Design::default()`'s margin.
fn scoring(direction: Direction, cost: Cost, steps: usize) -> Scoring {
    Scoring {
        direction,
        cost,
        steps,
        clearance: 0.25 * 0.5 * 1.5 * 3f64.sqrt(),
        limit: PI,
        limit_band: 0.25 * PI,
        barrier_weight: 1.0,
    }
}

/// A loop of two harmonics from its coefficients.
fn two_harmonics(coefficients: &[f64]) -> FourierLoop {
    FourierLoop {
        period: 2.0 * PI,
        harmonics: 2,
        coefficients: coefficients.to_vec(),
    }
}

/// `(x, y, theta, L, B)` of an evaluation.
fn values(e: &Evaluation) -> [f64; 5] {
    let [x, y, theta] = e.displacement;
    [x, y, theta, e.length, e.barrier]
}

/// The exact gradients of `(x, y, theta, L, B)`, one row per coefficient.
fn gradients(at: &Evaluation) -> Vec<[f64; 5]> {
    (at.displacement_gradient.iter().enumerate())
        .map(|(m, &[x, y, theta])| [x, y, theta, at.length_gradient[m], at.barrier_gradient[m]])
        .collect()
}

/// Asserts that each of `(x, y, theta, L, B)`'s exact gradient at
/// `shape_loop` equals central differences to 1e-6 of its largest entry;
/// returns the barrier.
fn assert_gradients(body: &dyn GaitModel, shape_loop: &FourierLoop, scoring: &Scoring) -> f64 {
    let at = evaluate(body, shape_loop, scoring);
    let h = 1e-6;
    for (m, exact) in gradients(&at).iter().enumerate() {
        let moved = |delta: f64| {
            let mut shifted = shape_loop.clone();
            shifted.coefficients[m] += delta;
            values(&evaluate(body, &shifted, scoring))
        };
        let (plus, minus) = (moved(h), moved(-h));
        for q in 0..5 {
            let difference = (plus[q] - minus[q]) / (2.0 * h);
            let scale = exact.iter().fold(1e-3_f64, |s, v| s.max(v.abs()));
            assert!(
                (exact[q] - difference).abs() <= 1e-6 * scale,
                "coefficient {m}, value {q}: exact {} vs differences {difference}",
                exact[q]
            );
        }
    }
    at.barrier
}

/// The snake's gradients (by its curvature) equal central differences, for
/// a loop outside the barrier and one inside it.
#[test]
fn gradients_equal_central_differences() {
    let loaded = snake();
    let body = locomotion(&loaded.model, &loaded.label).expect("a gait model");
    let scoring = scoring(Direction::Forward, Cost::Length, 1000);
    let loops = [
        [1.0, 0.2, -0.1, 0.03, 0.02, -0.8, 0.1, 0.15, -0.03, 0.04],
        [-1.1, 0.1, 1.3, 0.0, 0.05, 1.0, -1.2, 0.55, 0.02, 0.0],
    ];
    let barriers = loops.map(|c| assert_gradients(&body, &two_harmonics(&c), &scoring));
    assert!(barriers[0] == 0.0 && barriers[1] > 0.0, "{barriers:?}");
}

/// On the snake, forward sensitivities through the exact Jacobians give
/// the displacement the curvature's route integrates, to 1e-12, and its
/// gradient to 1e-6 of the largest entry (the two routes discretize the
/// same derivative differently: Simpson's rule on the curvature, RK4 on
/// the variational equations).
#[test]
fn the_curvature_and_forward_sensitivities_agree() {
    let loaded = snake();
    let body = locomotion(&loaded.model, &loaded.label).expect("a gait model");
    let scoring = scoring(Direction::Forward, Cost::Length, 1000);
    let shape_loop = two_harmonics(&[0.9, 0.3, -0.2, 0.05, 0.04, -0.6, 0.2, 0.25, -0.05, 0.0]);
    let (curvature, sensitivities) = (
        by_curvature(&body, &shape_loop, &scoring),
        by_sensitivities(&body, &shape_loop, &scoring),
    );
    for c in 0..3 {
        let (a, b) = (curvature.displacement[c], sensitivities.displacement[c]);
        assert!((a - b).abs() < 1e-12, "displacement {c}: {a} vs {b}");
    }
    let (a, b) = (gradients(&curvature), gradients(&sensitivities));
    let scale = a.iter().flatten().fold(0.0_f64, |s, v| s.max(v.abs()));
    for (m, (a, b)) in a.iter().zip(&b).enumerate() {
        for q in 0..3 {
            assert!(
                (a[q] - b[q]).abs() <= 1e-6 * scale,
                "coefficient {m}, value {q}: curvature {} vs sensitivities {}",
                a[q],
                b[q]
            );
        }
    }
}

/// The snakeboard, which carries momentum: from rest, the gait `psi = 0.8
/// sin t`, `phi = 0.5 cos t` moves it as the hand-derived equations of
/// MATH.md 4.1 do (to 1e-10), and the gradients by forward sensitivities
/// equal central differences, for a loop outside the barrier and one
/// inside it.
#[test]
fn the_snakeboards_gradients_equal_central_differences() {
    let loaded = loaded("snakeboard");
    let body = locomotion(&loaded.model, &loaded.label).expect("a gait model");
    let divisor = |phi: f64| body.divisor(&[0.0, phi]).0.abs();
    let scoring = Scoring {
        clearance: 0.25 * divisor(0.0),
        ..scoring(Direction::Forward, Cost::Length, 1000)
    };
    let classic = FourierLoop {
        period: 2.0 * PI,
        harmonics: 1,
        coefficients: vec![0.0, 0.0, 0.8, 0.0, 0.5, 0.0],
    };
    let moved = evaluate(&body, &classic, &scoring).displacement;
    let hand = hand_derived_cycle(1000);
    for c in 0..3 {
        assert!((moved[c] - hand[c]).abs() < 1e-10, "{moved:?} vs {hand:?}");
    }
    let loops = [
        [0.3, 0.2, 0.9, 0.1, -0.05, 0.1, 0.3, 0.4, 0.05, 0.1],
        [-0.5, 0.6, 0.2, 0.0, 0.3, 1.05, 0.3, 0.1, 0.0, 0.0],
    ];
    let barriers = loops.map(|c| assert_gradients(&body, &two_harmonics(&c), &scoring));
    assert!(barriers[0] == 0.0 && barriers[1] > 0.0, "{barriers:?}");
}

/// A loop like the optimizer's starts, with wider ranges: each centre in
/// `[-2, 2]`, each first-harmonic amplitude in `[-1.5, 1.5]`.
struct Loops(u64);

impl Loops {
    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        low + (high - low) * (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn next(&mut self) -> FourierLoop {
        let mut coefficients = vec![0.0; 6];
        for i in 0..2 {
            coefficients[3 * i] = self.uniform(-2.0, 2.0);
            coefficients[3 * i + 1] = self.uniform(-1.5, 1.5);
            coefficients[3 * i + 2] = self.uniform(-1.5, 1.5);
        }
        FourierLoop {
            period: 2.0 * PI,
            harmonics: 1,
            coefficients,
        }
    }
}

/// For forward motion and for rotation per unit length: the optimum's
/// cost gradient vanishes to 1e-6, and its efficiency beats each of 1000
/// random loops of one harmonic that keep off the singular set and out of
/// the barrier (clearance at least 2, where the optimum's cost is its
/// efficiency's negative).
#[test]
fn the_optimum_is_stationary_and_beats_random_loops() {
    let loaded = snake();
    let body = locomotion(&loaded.model, &loaded.label).expect("a gait model");
    let random = random_efficiencies(&body, &scoring(Direction::Forward, Cost::Length, 200), 1000);
    for direction in [Direction::Forward, Direction::Rotate] {
        let design = Design {
            direction,
            starts: 4,
            ..Design::default()
        };
        let optimum = optimize(&body, &design).expect("an optimum");
        assert_stationary_and_best(&optimum, &random);
    }
}

/// The snakeboard from rest, forward: the optimum (one harmonic) is
/// stationary and beats 1000 random loops, as for the snake.
#[test]
fn the_snakeboards_optimum_is_stationary_and_beats_random_loops() {
    let loaded = loaded("snakeboard");
    let body = locomotion(&loaded.model, &loaded.label).expect("a gait model");
    let design = Design {
        starts: 2,
        ..Design::default()
    };
    let optimum = optimize(&body, &design).expect("an optimum");
    let random = random_efficiencies(&body, &optimum.scoring, 1000);
    assert_stationary_and_best(&optimum, &random);
}

/// Asserts that the `optimum`'s cost gradient vanishes to 1e-6 and that
/// its efficiency beats each of the `random` loops' (`(x, y, theta)` per
/// unit length).
fn assert_stationary_and_best(optimum: &Optimum, random: &[[f64; 3]]) {
    let scoring = optimum.scoring;
    let direction = scoring.direction;
    let gradient = optimum.evaluation.cost_gradient(&scoring);
    let largest = gradient.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
    assert!(largest < 1e-6, "{direction:?}: gradient {gradient:?}");
    let best = optimum.efficiency();
    let best_random = (random.iter())
        .map(|moved| moved[direction.index()])
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        best > best_random,
        "{direction:?}: optimum {best} vs the best random loop {best_random}"
    );
}

/// The displacement per unit length `(x, y, theta) / L` of the first
/// `count` random loops whose clearance at `scoring`'s margin is at least
/// 2 at 200 points: from rest, 200 RK4 steps of `runtime::gait::run`, the
/// length by the midpoint rule on 200 points.
fn random_efficiencies(body: &dyn GaitModel, scoring: &Scoring, count: usize) -> Vec<[f64; 3]> {
    let mut loops = Loops(0x9e37_79b9_7f4a_7c15);
    let mut found = Vec::with_capacity(count);
    let (q0, p0) = (
        vec![0.0; body.coordinate_count()],
        vec![0.0; body.momentum_count()],
    );
    while found.len() < count {
        let candidate = loops.next();
        if clearances(body, &candidate, scoring, 200).any(|s| s < 2.0) {
            continue;
        }
        let law = |t: f64| candidate.shape(t);
        let shape_loop = ShapeLoop {
            shape: &law,
            period: candidate.period,
        };
        let cycle = gait::run(body, &shape_loop, (&q0, &p0), (1, 200), &mut |_, _| {});
        let h = candidate.period / 200.0;
        let length: f64 = (0..200)
            .map(|k| {
                let rdot = candidate.shape((k as f64 + 0.5) * h).1;
                h * rdot.iter().map(|v| v * v).sum::<f64>().sqrt()
            })
            .sum();
        let moved = cycle[0].displacement.map(|v| v / length);
        if moved.iter().all(|v| v.is_finite()) {
            found.push(moved);
        }
    }
    found
}

/// The snake's divisor is `d = (l/2) (s1 (1 + c2) - s2 (1 + c1))` by hand,
/// with its gradient.
#[test]
fn the_divisor_is_the_hand_derived_one() {
    let loaded = snake();
    let body = locomotion(&loaded.model, &loaded.label).expect("a gait model");
    for r in [[0.3_f64, -1.2], [2.0, 0.5], [-0.7, -0.7]] {
        let ((s1, c1), (s2, c2)) = (r[0].sin_cos(), r[1].sin_cos());
        let d = 0.5 * (s1 * (1.0 + c2) - s2 * (1.0 + c1));
        let gradient = [
            0.5 * (c1 * (1.0 + c2) + s2 * s1),
            0.5 * (-s1 * s2 - c2 * (1.0 + c1)),
        ];
        let (value, found) = body.divisor(&r);
        assert!((value - d).abs() < 1e-14, "{value} vs {d}");
        for k in 0..2 {
            assert!(
                (found[k] - gradient[k]).abs() < 1e-14,
                "{found:?} vs {gradient:?}"
            );
        }
    }
}
