//! The integrators are written once over a state (`chaplygin_runtime::state`):
//! on a size fixed at compile time (`[f64; 2]`) and on a size known at run
//! time (`Vec<f64>`) every method takes the same steps. The forced pendulum
//! `qdot = p`, `pdot = -sin q + a cos(w t)` (canonical structure
//! `[[0, 1], [-1, 0]]`, `H = p^2/2 + 1 - cos q`, forcing `(0, a cos(w t))`)
//! is written once on slices and seen through both state types.

use chaplygin_runtime::integrate::{
    DiscreteGradient, DormandPrince, FixedStep, Midpoint, Rk4, integrate_fixed,
};
use chaplygin_runtime::nalgebra::DMatrix;
use chaplygin_runtime::state::State;
use chaplygin_runtime::system::{Energy, Jacobian, OdeSystem, Structured};

/// The forced pendulum, amplitude `A`, frequency `W`.
struct Pendulum;

const A: f64 = 0.3;
const W: f64 = 1.7;

fn forcing(t: f64) -> [f64; 2] {
    [0.0, A * (W * t).cos()]
}

fn gradient(x: &[f64]) -> [f64; 2] {
    [x[0].sin(), x[1]]
}

fn rhs(t: f64, x: &[f64]) -> [f64; 2] {
    let (g, f) = (gradient(x), forcing(t));
    [g[1] + f[0], -g[0] + f[1]]
}

fn jacobian(x: &[f64]) -> [[f64; 2]; 2] {
    [[0.0, 1.0], [-x[0].cos(), 0.0]]
}

fn energy(x: &[f64]) -> f64 {
    x[1] * x[1] / 2.0 + 1.0 - x[0].cos()
}

const STRUCTURE: [[f64; 2]; 2] = [[0.0, 1.0], [-1.0, 0.0]];

/// Implements the system's traits on the state type `$x` from the
/// functions above, `$matrix` making its matrices of row-major rows.
macro_rules! pendulum_on {
    ($x:ty, $matrix:expr) => {
        impl OdeSystem<$x> for Pendulum {
            fn rhs(&self, t: f64, x: &$x) -> $x {
                rhs(t, x.as_ref()).into()
            }
        }

        impl Jacobian<$x> for Pendulum {
            fn jacobian(&self, _t: f64, x: &$x) -> <$x as State>::Matrix {
                $matrix(jacobian(x.as_ref()))
            }
        }

        impl Energy<$x> for Pendulum {
            fn energy(&self, x: &$x) -> f64 {
                energy(x.as_ref())
            }
        }

        impl Structured<$x> for Pendulum {
            fn structure_matrix(&self, _x: &$x) -> <$x as State>::Matrix {
                $matrix(STRUCTURE)
            }
            fn energy_gradient(&self, x: &$x) -> $x {
                gradient(x.as_ref()).into()
            }
            fn forcing(&self, t: f64, _x: &$x) -> $x {
                forcing(t).into()
            }
        }
    };
}

pendulum_on!([f64; 2], |rows: [[f64; 2]; 2]| rows);
pendulum_on!(Vec<f64>, |rows: [[f64; 2]; 2]| DMatrix::from_row_slice(
    2,
    2,
    rows.as_flattened()
));

/// A large swing: 2 rad from rest.
const X0: [f64; 2] = [2.0, 0.0];

/// The states after each of 400 steps of 0.05 from `X0` on both state types.
fn both_runs<M>(method: &M) -> (Vec<[f64; 2]>, Vec<Vec<f64>>)
where
    M: FixedStep<Pendulum, [f64; 2]> + FixedStep<Pendulum, Vec<f64>>,
{
    let (h, steps) = (0.05, 400);
    let mut fixed = Vec::new();
    integrate_fixed(method, &Pendulum, (0.0, X0), h, steps, |_, x| {
        fixed.push(*x)
    })
    .unwrap();
    let mut dynamic = Vec::new();
    integrate_fixed(method, &Pendulum, (0.0, X0.to_vec()), h, steps, |_, x| {
        dynamic.push(x.clone());
    })
    .unwrap();
    (fixed, dynamic)
}

/// Every step of every fixed-step method is the same on both state types,
/// to the last bit: the same operations in the same order (nalgebra's LU
/// on a stack matrix and on a heap matrix alike for the implicit ones).
#[test]
fn every_fixed_step_method_steps_both_state_types_alike() {
    let runs = [
        ("rk4", both_runs(&Rk4)),
        ("midpoint", both_runs(&Midpoint::default())),
        ("discrete gradient", both_runs(&DiscreteGradient::default())),
    ];
    for (name, (fixed, dynamic)) in runs {
        assert_eq!(fixed.len(), 400, "{name}");
        for (step, (a, b)) in fixed.iter().zip(&dynamic).enumerate() {
            assert_eq!(a.as_slice(), b.as_slice(), "{name}, step {}", step + 1);
        }
        // the forcing moved the pendulum off its free swing's energy
        let drift = (energy(&fixed[399]) - energy(&X0)).abs();
        assert!(drift > 1e-3, "{name}: {drift:e}");
    }
}

/// Dormand-Prince's adaptive steps, their count and its dense output are the
/// same on both state types.
#[test]
fn dormand_prince_steps_both_state_types_alike() {
    let method = DormandPrince::default();
    let (mut fixed_steps, mut dynamic_steps) = (Vec::new(), Vec::new());
    let fixed = method
        .integrate_with(&Pendulum, (0.0, X0), 20.0, |step| {
            fixed_steps.push((step.end(), step.at(0.5 * (step.start() + step.end()))));
        })
        .unwrap();
    let dynamic = method
        .integrate_with(&Pendulum, (0.0, X0.to_vec()), 20.0, |step| {
            let middle = step.at(0.5 * (step.start() + step.end()));
            dynamic_steps.push((step.end(), middle));
        })
        .unwrap();
    assert_eq!(fixed.x.as_slice(), dynamic.x.as_slice());
    assert_eq!(fixed.effort, dynamic.effort);
    assert!(fixed.effort.accepted > 20, "{:?}", fixed.effort);
    for ((t, a), (s, b)) in fixed_steps.iter().zip(&dynamic_steps) {
        assert_eq!((t, a.as_slice()), (s, b.as_slice()));
    }
}
