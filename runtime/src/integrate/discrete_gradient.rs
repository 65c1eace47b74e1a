//! Gonzalez's discrete-gradient method for port-Hamiltonian systems
//! `xdot = J(x) dH/dx + F(t, x)` ([`Structured`]): O. Gonzalez, "Time
//! integration and discrete Hamiltonian systems", *J. Nonlinear Sci.* 6
//! (1996) 449-467; R. McLachlan, G. Quispel & N. Robidoux, "Geometric
//! integration using discrete gradients", *Phil. Trans. R. Soc. A* 357
//! (1999) 1021-1045.
//!
//! One step `x -> X` solves, with the midpoint `m = (x + X)/2`,
//!
//! ```text
//! X = x + h ( J(m) gradH(x, X) + F(t + h/2, m) ),
//! gradH(x, X) = dH/dx(m) + (H(X) - H(x) - dH/dx(m) . d) / |d|^2  d,   d = X - x,
//! ```
//!
//! whose discrete gradient satisfies `gradH . (X - x) = H(X) - H(x)` for
//! any `H`. With `J(m)` skew, `H(X) - H(x) = h gradH . F`: without forcing
//! the energy is conserved up to the Newton tolerance and round-off, for
//! energies that are not quadratic (a potential), where the implicit
//! midpoint rule only keeps it to `O(h^2)`. Order 2, symmetric. For a
//! quadratic `H` it is the implicit midpoint rule.
//!
//! Newton's method uses `I - h/2 df/dx(m)` as the Jacobian of the step
//! equation (exact for quadratic `H`); the correction term's derivative is
//! left out, which slows convergence a little but not the step it finds.

use super::newton::{Equation, Settings, solve_root};
use super::{Error, FixedStep, NonFiniteCause, StepAt, newton_failure};
use crate::state::State;
use crate::system::{Jacobian, Structured};

/// The discrete-gradient method with its Newton iteration's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscreteGradient {
    /// Newton stops when its update is at most `tolerance * max(1, |X|)`.
    pub tolerance: f64,
    /// Newton iterations allowed per step.
    pub max_iterations: usize,
}

impl Default for DiscreteGradient {
    /// `tolerance = 1e-13`, `max_iterations = 50`.
    fn default() -> Self {
        Self {
            tolerance: 1e-13,
            max_iterations: 50,
        }
    }
}

impl<S: Structured<X> + Jacobian<X>, X: State> FixedStep<S, X> for DiscreteGradient {
    const ORDER: u32 = 2;

    fn step_counting(
        &self,
        system: &S,
        t: f64,
        x: &X,
        h: f64,
        iterations: &mut usize,
    ) -> Result<X, Error> {
        let tm = t + h / 2.0;
        let settings = Settings {
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
        };
        let at = StepAt {
            t,
            h,
            x: x.as_ref(),
        };
        let energy = at.finite([system.energy(x)], NonFiniteCause::Energy)?[0];
        let start = at.finite(
            explicit_midpoint(system, t, x, h),
            NonFiniteCause::RightHandSide,
        )?;
        let midpoint = |next: &X| x.with_entries(|i| (x[i] + next[i]) / 2.0);
        let equation = Equation {
            scale: h / 2.0,
            residual: |next: &X| {
                let m = midpoint(next);
                let gradient = discrete_gradient(system, energy, x, next, &m);
                let (j, forcing) = (system.structure_matrix(&m), system.forcing(tm, &m));
                x.with_entries(|i| {
                    let flow: f64 = (0..gradient.as_ref().len())
                        .map(|k| X::entry(&j, i, k) * gradient[k])
                        .sum();
                    next[i] - x[i] - h * (flow + forcing[i])
                })
            },
            matrix: |next: &X| system.jacobian(tm, &midpoint(next)),
        };
        let next = solve_root(start, settings, equation, iterations)
            .map_err(|failure| newton_failure(failure, t, h, x.as_ref()))?;
        at.finite(next, NonFiniteCause::NewState)
    }
}

/// The explicit midpoint step, Newton's starting point.
fn explicit_midpoint<S: Structured<X>, X: State>(system: &S, t: f64, x: &X, h: f64) -> X {
    let f = system.rhs(t, x);
    let half = x.with_entries(|i| x[i] + h / 2.0 * f[i]);
    let g = system.rhs(t + h / 2.0, &half);
    x.with_entries(|i| x[i] + h * g[i])
}

/// Gonzalez's midpoint discrete gradient `gradH(x, X)`; `energy = H(x)`.
/// When `|X - x|` is at round-off level the correction is 0/0 and the
/// midpoint gradient is returned.
fn discrete_gradient<S: Structured<X>, X: State>(
    system: &S,
    energy: f64,
    x: &X,
    next: &X,
    m: &X,
) -> X {
    let mut gradient = system.energy_gradient(m);
    let d = x.with_entries(|i| next[i] - x[i]);
    let squared: f64 = d.as_ref().iter().map(|v| v * v).sum();
    let scale = x.as_ref().iter().fold(1.0_f64, |s, v| s.max(v.abs()));
    if squared <= (f64::EPSILON * scale).powi(2) {
        return gradient;
    }
    let slope: f64 = gradient
        .as_ref()
        .iter()
        .zip(d.as_ref())
        .map(|(g, v)| g * v)
        .sum();
    let correction = (system.energy(next) - energy - slope) / squared;
    for (g, v) in gradient.as_mut().iter_mut().zip(d.as_ref()) {
        *g += correction * v;
    }
    gradient
}
