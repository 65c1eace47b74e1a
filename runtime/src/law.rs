//! Control laws `u = f(t, x)`: what closes a model's input port in a
//! formulation (the `Reduced`, `Dalembert` and `Momentum` adapters of the
//! `system` module). A [`Constant`], an open-loop closure `u(t)`, or a state
//! [`Feedback`] `u(t, x)`; implicit integrators also use the law's Jacobian
//! `du/dx`. Controllers with a state and an energy of their own are in the
//! `control` module.

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
