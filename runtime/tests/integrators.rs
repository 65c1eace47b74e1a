//! The integrators against closed-form solutions: measured convergence
//! orders on the harmonic oscillator, Dormand-Prince's global error against
//! its tolerance, exact energy of the midpoint rule, and the structured
//! errors on a solution that blows up in finite time.

use chaplygin_runtime::Error;
use chaplygin_runtime::integrate::{
    DenseStep, DormandPrince, FixedStep, Midpoint, Rk4, integrate_fixed,
};
use chaplygin_runtime::system::{Energy, Jacobian, OdeSystem};

/// `qdot = p, pdot = -q`, `H = (q^2 + p^2)/2`: a skew structure with a
/// quadratic energy; from `(q0, p0)` the solution is
/// `q = q0 cos t + p0 sin t`, `p = p0 cos t - q0 sin t`.
struct Oscillator;

impl OdeSystem<[f64; 2]> for Oscillator {
    fn rhs(&self, _t: f64, x: &[f64; 2]) -> [f64; 2] {
        [x[1], -x[0]]
    }
}

impl Jacobian<[f64; 2]> for Oscillator {
    fn jacobian(&self, _t: f64, _x: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-1.0, 0.0]]
    }
}

impl Energy<[f64; 2]> for Oscillator {
    fn energy(&self, x: &[f64; 2]) -> f64 {
        (x[0] * x[0] + x[1] * x[1]) / 2.0
    }
}

const X0: [f64; 2] = [1.0, 0.5];

fn exact(t: f64) -> [f64; 2] {
    flow(&X0, t)
}

/// The state a time `t` after `x`.
fn flow(x: &[f64; 2], t: f64) -> [f64; 2] {
    let (s, c) = t.sin_cos();
    [x[0] * c + x[1] * s, x[1] * c - x[0] * s]
}

fn distance(a: &[f64; 2], b: &[f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// `xdot = x^2`, `x(0) = 1`: `x = 1/(1 - t)`, infinite at `t = 1`.
struct BlowUp;

impl OdeSystem<[f64; 1]> for BlowUp {
    fn rhs(&self, _t: f64, x: &[f64; 1]) -> [f64; 1] {
        [x[0] * x[0]]
    }
}

impl Jacobian<[f64; 1]> for BlowUp {
    fn jacobian(&self, _t: f64, x: &[f64; 1]) -> [[f64; 1]; 1] {
        [[2.0 * x[0]]]
    }
}

/// `xdot = a x`: the midpoint rule's step `X = x (1 + h a/2) / (1 - h a/2)`
/// has a pole at `h a = 2`, where Newton's matrix `1 - h a/2` is zero.
struct Growth(f64);

impl OdeSystem<[f64; 1]> for Growth {
    fn rhs(&self, _t: f64, x: &[f64; 1]) -> [f64; 1] {
        [self.0 * x[0]]
    }
}

impl Jacobian<[f64; 1]> for Growth {
    fn jacobian(&self, _t: f64, _x: &[f64; 1]) -> [[f64; 1]; 1] {
        [[self.0]]
    }
}

/// Global errors at `t = 2` for `h = 0.2 / 2^i`, and the slopes of
/// `log2(error)` between successive halvings.
fn measured_orders<M: FixedStep<Oscillator, [f64; 2]>>(method: &M) -> ([f64; 4], [f64; 3]) {
    let errors: [f64; 4] = core::array::from_fn(|i| {
        let steps = 10 << i;
        let h = 2.0 / steps as f64;
        let end = integrate_fixed(method, &Oscillator, (0.0, X0), h, steps, |_, _| {}).unwrap();
        distance(&end, &exact(2.0))
    });
    let slopes = core::array::from_fn(|i| (errors[i] / errors[i + 1]).log2());
    (errors, slopes)
}

#[test]
fn rk4_converges_with_order_4() {
    let (errors, slopes) = measured_orders(&Rk4);
    println!("RK4 errors {errors:?}, orders {slopes:.4?}");
    for slope in slopes {
        assert!((slope - 4.0).abs() <= 0.2, "{slopes:?}");
    }
}

#[test]
fn midpoint_converges_with_order_2_and_keeps_the_energy() {
    let (errors, slopes) = measured_orders(&Midpoint::default());
    println!("midpoint errors {errors:?}, orders {slopes:.4?}");
    for slope in slopes {
        assert!((slope - 2.0).abs() <= 0.1, "{slopes:?}");
    }
    let h0 = Oscillator.energy(&X0);
    let mut worst = 0.0f64;
    let observe = |_: f64, x: &[f64; 2]| worst = worst.max((Oscillator.energy(x) - h0).abs() / h0);
    integrate_fixed(
        &Midpoint::default(),
        &Oscillator,
        (0.0, X0),
        0.1,
        10_000,
        observe,
    )
    .unwrap();
    println!("midpoint: relative energy error over 10^4 steps {worst:.3e}");
    assert!(worst <= 1e-13, "{worst:e}");
}

#[test]
fn dormand_prince_global_error_tracks_its_tolerance() {
    let mut previous = f64::INFINITY;
    for tolerance in [1e-4, 1e-6, 1e-8, 1e-10] {
        let method = DormandPrince {
            rtol: tolerance,
            atol: tolerance,
            ..Default::default()
        };
        let end = method.integrate(&Oscillator, (0.0, X0), 10.0).unwrap();
        let error = distance(&end.x, &exact(10.0));
        println!(
            "Dormand-Prince tol {tolerance:e}: error {error:.3e} ({:.2} tol), {} accepted, {} rejected",
            error / tolerance,
            end.effort.accepted,
            end.effort.rejected
        );
        // within a decade of the tolerance, and proportional to it: 100 times
        // tighter gives at least 50 times smaller
        assert!(
            error <= 10.0 * tolerance && error < previous / 50.0,
            "{error:e}"
        );
        previous = error;
    }
}

#[test]
fn dormand_prince_integrates_backward() {
    let method = DormandPrince {
        rtol: 1e-10,
        atol: 1e-10,
        ..Default::default()
    };
    let end = method.integrate(&Oscillator, (0.0, X0), -3.0).unwrap();
    assert!(distance(&end.x, &exact(-3.0)) <= 1e-9, "{:?}", end.x);
}

#[test]
fn a_blow_up_gives_structured_errors() {
    let error = integrate_fixed(&Rk4, &BlowUp, (0.0, [1.0]), 0.1, 20, |_, _| {}).unwrap_err();
    assert!(
        matches!(error, Error::NonFinite { t, .. } if t > 1.0 && t <= 2.0 + 1e-12),
        "{error}"
    );
    let error = DormandPrince::default()
        .integrate(&BlowUp, (0.0, [1.0]), 2.0)
        .unwrap_err();
    assert!(
        matches!(error, Error::StepSizeUnderflow { t, .. } | Error::NonFinite { t, .. } if (t - 1.0).abs() < 1e-2),
        "{error}"
    );
    let one = Midpoint {
        max_iterations: 1,
        ..Default::default()
    };
    let error = one.step(&BlowUp, 0.0, &[1.0], 0.1).unwrap_err();
    assert!(
        matches!(error, Error::NewtonFailure { iterations: 1, .. }),
        "{error}"
    );
    // the midpoint rule has no solution past the blow-up: Newton fails
    let error = Midpoint::default()
        .step(&BlowUp, 0.0, &[1.0], 3.0)
        .unwrap_err();
    assert!(
        matches!(error, Error::NewtonFailure { .. } | Error::NonFinite { .. }),
        "{error}"
    );
}

#[test]
fn a_singular_newton_matrix_is_a_structured_error_not_nan() {
    // h a = 0.5 * 4 = 2: 1 - h a/2 = 0 exactly.
    let error = Midpoint::default()
        .step(&Growth(4.0), 1.5, &[1.0], 0.5)
        .unwrap_err();
    assert_eq!(
        error,
        Error::SingularJacobian {
            t: 1.5,
            h: 0.5,
            iteration: 1,
            state: vec![1.0],
        }
    );
    assert!(
        error.to_string().contains("singular Newton matrix"),
        "{error}"
    );
    // Beside the pole the step is the closed form.
    let next = Midpoint::default()
        .step(&Growth(4.0), 1.5, &[1.0], 0.25)
        .unwrap();
    assert!((next[0] - 1.5 / 0.5).abs() < 1e-12, "{next:?}");
}

#[test]
fn dormand_prince_dense_output_follows_the_solution_between_steps() {
    let tolerance = 1e-8;
    let method = DormandPrince {
        rtol: tolerance,
        atol: tolerance,
        ..Default::default()
    };
    let (mut worst, mut local, mut covered) = (0.0f64, 0.0f64, 0.0);
    let observe = |step: &DenseStep<[f64; 2]>| {
        assert_eq!(step.start(), covered, "steps follow each other");
        covered = step.end();
        let first = step.at(step.start());
        for i in 0..=10 {
            let t = step.start() + (step.end() - step.start()) * f64::from(i) / 10.0;
            worst = worst.max(distance(&step.at(t), &exact(t)));
            // against the exact solution through the step's own start
            local = local.max(distance(&step.at(t), &flow(&first, t - step.start())));
        }
    };
    let end = method
        .integrate_with(&Oscillator, (0.0, X0), 10.0, observe)
        .unwrap();
    println!(
        "dense output, tol {tolerance:e}: largest error between steps {worst:.3e}, \
         largest error within one step {local:.3e}"
    );
    assert_eq!(covered, 10.0);
    assert!(
        worst <= 10.0 * tolerance && local <= tolerance,
        "{worst:e} {local:e}"
    );
    assert!(
        distance(&end.x, &exact(10.0)) <= worst,
        "the ends are among the points checked"
    );
}

#[test]
fn unreachable_tolerances_give_an_error_not_a_hang() {
    let zero = DormandPrince {
        rtol: 0.0,
        atol: 0.0,
        ..Default::default()
    };
    let error = zero.integrate(&Oscillator, (0.0, X0), 1.0).unwrap_err();
    assert!(
        matches!(error, Error::StepSizeUnderflow { t: 0.0, .. }),
        "{error}"
    );
    let few = DormandPrince {
        max_steps: 3,
        ..Default::default()
    };
    let error = few.integrate(&Oscillator, (0.0, X0), 100.0).unwrap_err();
    assert!(
        matches!(error, Error::TooManySteps { steps: 3, .. }),
        "{error}"
    );
}
