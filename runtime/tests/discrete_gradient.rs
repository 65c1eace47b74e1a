//! Gonzalez's discrete-gradient method on the pendulum, whose energy
//! `H = p^2/2 + 1 - cos q` is not quadratic: the energy is kept to round-off
//! where the implicit midpoint rule keeps it only to `O(h^2)`, and the
//! method converges with order 2 against an RK4 reference with a step 100
//! times finer.

use chaplygin_runtime::integrate::{DiscreteGradient, FixedStep, Midpoint, Rk4, integrate_fixed};
use chaplygin_runtime::system::{Energy, Jacobian, OdeSystem, Structured};

/// `qdot = p`, `pdot = -sin q`, with the canonical structure `[[0, 1], [-1, 0]]`.
pub(crate) struct Pendulum;

impl OdeSystem<[f64; 2]> for Pendulum {
    fn rhs(&self, _t: f64, x: &[f64; 2]) -> [f64; 2] {
        [x[1], -x[0].sin()]
    }
}

impl Jacobian<[f64; 2]> for Pendulum {
    fn jacobian(&self, _t: f64, x: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-x[0].cos(), 0.0]]
    }
}

impl Energy<[f64; 2]> for Pendulum {
    fn energy(&self, x: &[f64; 2]) -> f64 {
        x[1] * x[1] / 2.0 + 1.0 - x[0].cos()
    }
}

impl Structured<[f64; 2]> for Pendulum {
    fn structure_matrix(&self, _x: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-1.0, 0.0]]
    }
    fn energy_gradient(&self, x: &[f64; 2]) -> [f64; 2] {
        [x[0].sin(), x[1]]
    }
    fn forcing(&self, _t: f64, _x: &[f64; 2]) -> [f64; 2] {
        [0.0, 0.0]
    }
}

/// A large swing: 2 rad from rest.
pub(crate) const X0: [f64; 2] = [2.0, 0.0];

fn worst_energy_error<M: FixedStep<Pendulum, [f64; 2]>>(method: &M, h: f64, steps: usize) -> f64 {
    let h0 = Pendulum.energy(&X0);
    let mut worst = 0.0f64;
    integrate_fixed(method, &Pendulum, (0.0, X0), h, steps, |_, x| {
        worst = worst.max((Pendulum.energy(x) - h0).abs() / h0);
    })
    .unwrap();
    worst
}

#[test]
fn the_discrete_gradient_keeps_a_non_quadratic_energy() {
    let (h, steps) = (0.1, 10_000);
    let gradient = worst_energy_error(&DiscreteGradient::default(), h, steps);
    let midpoint = worst_energy_error(&Midpoint::default(), h, steps);
    println!(
        "pendulum from q = 2, h = {h}, {steps} steps: relative energy error \
         discrete gradient {gradient:.3e}, midpoint {midpoint:.3e}"
    );
    assert!(gradient <= 1e-13, "{gradient:e}");
    assert!(midpoint >= 1e-5, "{midpoint:e}");
}

#[test]
fn the_discrete_gradient_converges_with_order_2() {
    let t_end = 4.0;
    let reference = integrate_fixed(&Rk4, &Pendulum, (0.0, X0), 1e-4, 40_000, |_, _| {}).unwrap();
    let error = |steps: usize| {
        let h = t_end / steps as f64;
        let x = integrate_fixed(
            &DiscreteGradient::default(),
            &Pendulum,
            (0.0, X0),
            h,
            steps,
            |_, _| {},
        )
        .unwrap();
        (x[0] - reference[0]).hypot(x[1] - reference[1])
    };
    let errors: Vec<f64> = [40, 80, 160, 320].into_iter().map(error).collect();
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        println!(
            "discrete gradient: error {:.3e} -> {:.3e}, order {order:.3}",
            pair[0], pair[1]
        );
        assert!((order - 2.0).abs() <= 0.1, "order {order}");
    }
}
