//! Gait design on the three-link kinematic snake (docs/MATH.md 4.4): the
//! exact gradients of a loop's displacement, length and barrier against
//! central differences of the integrated values; the optimum a stationary
//! point of its cost that beats 1000 random loops of the same harmonics
//! off the singular set.

use chaplygin::driver::catalog::{Source, built_in};
use chaplygin::driver::engine::{EngineChoice, Loaded, load};
use chaplygin::driver::gait::locomotion;
use chaplygin::gait_design::{
    Cost, Design, Direction, Evaluation, FourierLoop, Kinematic, Scoring, clearance, evaluate,
    optimize,
};
use std::f64::consts::PI;

fn snake() -> Loaded {
    let source = Source::BuiltIn(built_in("three-link-snake").expect("built in"));
    load(&source, EngineChoice::Jit).expect("derives")
}

/// The clearance where the barrier starts for the snake (l = 1): a quarter
/// of `max |d| = (l/2) 3 sqrt(3) / 2`, as `Design::default()`'s margin.
fn scoring(direction: Direction, cost: Cost, steps: usize) -> Scoring {
    Scoring {
        direction,
        cost,
        steps,
        clearance: 0.25 * 0.5 * 1.5 * 3f64.sqrt(),
        barrier_weight: 1.0,
    }
}

/// `(x, y, theta, L, B)` of an evaluation.
fn values(e: &Evaluation) -> [f64; 5] {
    let [x, y, theta] = e.displacement;
    [x, y, theta, e.length, e.barrier]
}

/// Each of `(x, y, theta, L, B)`'s exact gradient equals central
/// differences to 1e-6 of its largest entry, for a loop outside the
/// barrier and one inside it.
#[test]
fn gradients_equal_central_differences() {
    let loaded = snake();
    let body = locomotion(&loaded.model, &loaded.label).expect("a gait model");
    let scoring = scoring(Direction::Forward, Cost::Length, 1000);
    let loops = [
        vec![1.0, 0.2, -0.1, 0.03, 0.02, -0.8, 0.1, 0.15, -0.03, 0.04],
        vec![-1.1, 0.1, 1.3, 0.0, 0.05, 1.0, -1.2, 0.55, 0.02, 0.0],
    ];
    let mut barriers = Vec::new();
    for coefficients in loops {
        let shape_loop = FourierLoop {
            period: 2.0 * PI,
            harmonics: 2,
            coefficients,
        };
        let at = evaluate(&body, &shape_loop, &scoring);
        barriers.push(at.barrier);
        let exact: Vec<[f64; 5]> = (0..shape_loop.coefficients.len())
            .map(|m| {
                let [x, y, theta] = at.displacement_gradient[m];
                [x, y, theta, at.length_gradient[m], at.barrier_gradient[m]]
            })
            .collect();
        let h = 1e-6;
        for (m, exact) in exact.iter().enumerate() {
            let moved = |delta: f64| {
                let mut shifted = shape_loop.clone();
                shifted.coefficients[m] += delta;
                values(&evaluate(&body, &shifted, &scoring))
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
    }
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
    let random = random_loops(&body, 1000);
    for direction in [Direction::Forward, Direction::Rotate] {
        let design = Design {
            direction,
            starts: 4,
            ..Design::default()
        };
        let optimum = optimize(&body, &design).expect("an optimum");
        let scoring = optimum.scoring;
        let gradient = optimum.evaluation.cost_gradient(&scoring);
        let largest = gradient.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
        assert!(largest < 1e-6, "{direction:?}: gradient {gradient:?}");
        let best = optimum.efficiency();
        let best_random = (random.iter())
            .map(|at| at.efficiency(&scoring))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            best > best_random,
            "{direction:?}: optimum {best} vs the best random loop {best_random}"
        );
    }
}

/// The evaluations (200 RK4 steps) of the first `count` random loops whose
/// clearance is at least 2 at the default design's margin.
fn random_loops(body: &dyn Kinematic, count: usize) -> Vec<Evaluation> {
    let scoring = scoring(Direction::Forward, Cost::Length, 200);
    let mut loops = Loops(0x9e37_79b9_7f4a_7c15);
    let mut found = Vec::with_capacity(count);
    while found.len() < count {
        let candidate = loops.next();
        if clearance(body, &candidate, &scoring, 200) < 2.0 {
            continue;
        }
        let at = evaluate(body, &candidate, &scoring);
        if at.clearance >= 2.0 && at.displacement.iter().all(|v| v.is_finite()) {
            found.push(at);
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
