//! Control laws `u = f(t, x)`: what closes a model's input port in a
//! formulation (the `Reduced`, `Dalembert` and `Momentum` adapters of the
//! `system` module). A [`Constant`], an open-loop closure `u(t)`, a state
//! [`Feedback`] `u(t, x)`, or a [`ChartFeedback`] that also reads the chart
//! of D a reduced state is given in; implicit integrators also use the
//! law's Jacobian `du/dx`. Controllers with a state and an energy of their
//! own are in the `control` module.
//!
//! A law of the mechanics `u(t, q, qdot)` closes every formulation through
//! the map from its state to the configuration and velocity:
//!
//! ```text
//! Dalembert, x = (q, qdot):    Feedback(|t, x| law(t, q, qdot))
//! Reduced, x = (q, alpha):     ChartFeedback(|chart, t, x| law(t, q, model.chart_velocities(chart, q, alpha)))
//! Momentum, x = (q, rdot, p):  Feedback(|t, x| law(t, q, model.reconstructed_velocity(q, rdot, p)))
//! ```
//!
//! The reduced form's velocity depends on the chart its momenta are given
//! in, which changes during a run; [`Controller::chart_input`] hands the
//! law the active one. `Observed::configuration_velocity` (module
//! `simulate`) is the same map for what observes a run.

use crate::linalg::central_difference_jacobian;

/// A control law `u = f(t, x)` with `P` inputs on a state of size `D`.
pub trait Controller<const D: usize, const P: usize> {
    /// The input at time `t` and state `x`.
    fn input(&self, t: f64, x: &[f64; D]) -> [f64; P];

    /// `du/dx`: row `l` holds the derivatives of `u_l`. By default central
    /// differences of [`Controller::input`]; implicit integrators use it in
    /// their Newton iteration only.
    fn input_jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; P] {
        central_difference_jacobian(|x| self.input(t, x), x)
    }

    /// The input at time `t` and the reduced state `x` given in chart
    /// `chart` of D (`system::ReducedPortHamiltonian::charts`), as the
    /// reduced form asks for it. By default [`Controller::input`]: a law
    /// that reads the state alike in every chart.
    fn chart_input(&self, _chart: usize, t: f64, x: &[f64; D]) -> [f64; P] {
        self.input(t, x)
    }

    /// `du/dx` of [`Controller::chart_input`]; by default
    /// [`Controller::input_jacobian`].
    fn chart_input_jacobian(&self, _chart: usize, t: f64, x: &[f64; D]) -> [[f64; D]; P] {
        self.input_jacobian(t, x)
    }
}

/// A constant input, `u(t, x) = u`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constant<const P: usize>(pub [f64; P]);

impl<const D: usize, const P: usize> Controller<D, P> for Constant<P> {
    fn input(&self, _t: f64, _x: &[f64; D]) -> [f64; P] {
        self.0
    }

    fn input_jacobian(&self, _t: f64, _x: &[f64; D]) -> [[f64; D]; P] {
        [[0.0; D]; P]
    }
}

/// An open-loop input `u(t)`: any `Fn(f64) -> [f64; P]`.
impl<F: Fn(f64) -> [f64; P], const D: usize, const P: usize> Controller<D, P> for F {
    fn input(&self, t: f64, _x: &[f64; D]) -> [f64; P] {
        self(t)
    }

    fn input_jacobian(&self, _t: f64, _x: &[f64; D]) -> [[f64; D]; P] {
        [[0.0; D]; P]
    }
}

/// A state feedback `u(t, x)` given as a closure
/// `Fn(f64, &[f64; D]) -> [f64; P]`; its Jacobian is taken by central
/// differences.
#[derive(Clone, Copy, Debug)]
pub struct Feedback<F>(pub F);

impl<F: Fn(f64, &[f64; D]) -> [f64; P], const D: usize, const P: usize> Controller<D, P>
    for Feedback<F>
{
    fn input(&self, t: f64, x: &[f64; D]) -> [f64; P] {
        (self.0)(t, x)
    }
}

/// A feedback of a reduced state that reads the chart of D the state is
/// given in, `Fn(usize, f64, &[f64; D]) -> [f64; P]` of `(chart, t, x)`,
/// such as a law of the configuration and velocity (see the module
/// documentation). Outside a reduced form it reads chart 0. Its Jacobian is
/// taken by central differences in the chart.
#[derive(Clone, Copy, Debug)]
pub struct ChartFeedback<F>(pub F);

impl<F: Fn(usize, f64, &[f64; D]) -> [f64; P], const D: usize, const P: usize> Controller<D, P>
    for ChartFeedback<F>
{
    fn input(&self, t: f64, x: &[f64; D]) -> [f64; P] {
        self.chart_input(0, t, x)
    }

    fn input_jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; P] {
        self.chart_input_jacobian(0, t, x)
    }

    fn chart_input(&self, chart: usize, t: f64, x: &[f64; D]) -> [f64; P] {
        (self.0)(chart, t, x)
    }

    fn chart_input_jacobian(&self, chart: usize, t: f64, x: &[f64; D]) -> [[f64; D]; P] {
        central_difference_jacobian(|x| (self.0)(chart, t, x), x)
    }
}
