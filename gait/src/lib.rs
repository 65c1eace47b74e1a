//! Gait design: the shape loops of a model with an SE(2) symmetry that move
//! it furthest per cycle, or per unit of the loop's length in the shape
//! coordinates, in a chosen direction (Hatton & Choset, "Geometric motion
//! planning: the local connection, Stokes' theorem, and the importance of
//! coordinate choice", 2011; Ostrowski & Burdick, "The geometric mechanics
//! of undulatory robotic locomotion", 1998; docs/MATH.md 4.4;
//! docs/INTERFACE.md section 9).
//!
//! A loop is a truncated Fourier series in each shape coordinate
//! ([`FourierLoop`]), run from zero momentum. Its displacement is
//! integrated along the loop, and its gradient in the coefficients is
//! exact ([`evaluate`]): for a principally kinematic model, the first
//! variation of the holonomy, the connection's curvature carried along the
//! loop by the group's adjoint ([`by_curvature`]); for a model that carries
//! momentum, forward sensitivities through the exact Jacobians of the
//! momentum equation and the reconstruction ([`by_sensitivities`]). The
//! search ([`optimize`]) surveys random loops, refines the best of them by
//! argmin's L-BFGS with a backtracking (Armijo) line search and keeps the
//! best result; a barrier keeps every loop off the set where the
//! connection is singular.
//!
//! A model read from its text is a [`GaitModel`] through
//! `driver::gait::locomotion`; for a generated struct, the trait's methods
//! are its `connection_divisor`, `body_velocity_jacobian`,
//! `momentum_rhs_jacobian` and `connection_curvature`, and
//! `runtime::gait::FromEquations` gives its [`Locomotion`].

mod fourier;
mod score;
mod search;
mod sensitivity;
mod variation;

pub use fourier::FourierLoop;
pub use score::{Evaluation, Scoring, clearances};
pub use search::{Design, DesignError, Optimum, SURVEY, optimize};
pub use sensitivity::by_sensitivities;
pub use variation::by_curvature;

use chaplygin_runtime::gait::Locomotion;

/// The component of the displacement a gait maximizes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Direction {
    /// `x`, along the body's heading at the start.
    Forward,
    /// `y`, to its left.
    Lateral,
    /// `theta`, counterclockwise.
    Rotate,
}

impl Direction {
    /// The entry of `(x, y, theta)`.
    pub fn index(self) -> usize {
        match self {
            Direction::Forward => 0,
            Direction::Lateral => 1,
            Direction::Rotate => 2,
        }
    }
}

/// What the displacement is divided by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Cost {
    /// The loop's length in the shape coordinates: displacement per unit
    /// of shape motion.
    Length,
    /// Nothing: displacement per cycle.
    None,
}

/// A model with an SE(2) symmetry at sizes known at run time, as a gait
/// moves it: its momentum equation and reconstruction (through
/// [`Locomotion`]), their Jacobians, the divisor of its connection and, for
/// a principally kinematic model, its connection's curvature.
pub trait GaitModel: Locomotion {
    /// The connection's divisor `d(r)` and its gradient
    /// (`connection_divisor`): the connection is singular where `d = 0`.
    fn divisor(&self, r: &[f64]) -> (f64, Vec<f64>);
    /// The Jacobians of the `se2` factor's body velocity and of the
    /// momentum equation at `(r, rdot, p)`.
    fn jacobians(&self, r: &[f64], rdot: &[f64], p: &[f64]) -> Jacobians;
    /// For a principally kinematic model, `(x, y, theta)` of the curvature
    /// `F_ij(r)` on each plane of shape coordinates `(i, j)`, `i < j`, in
    /// order (`connection_curvature`); `None` for a model that carries
    /// momentum.
    fn curvature(&self, r: &[f64]) -> Option<Vec<[f64; 3]>>;
}

/// The Jacobians of the reconstruction and the momentum equation, each row
/// over the columns `r`, then `rdot`, then `p` (`body_velocity_jacobian`,
/// `momentum_rhs_jacobian`).
#[derive(Clone, Debug, PartialEq)]
pub struct Jacobians {
    /// `d xi / d(r, rdot, p)` of the `se2` factor's `(v1, v2, omega)`.
    pub body_velocity: [Vec<f64>; 3],
    /// `d pdot / d(r, rdot, p)`, one row per momentum.
    pub momentum: Vec<Vec<f64>>,
}

/// `shape_loop`'s displacement, length and barrier on `model`, with their
/// exact gradients: by the curvature for a principally kinematic model,
/// by forward sensitivities otherwise.
pub fn evaluate(model: &dyn GaitModel, shape_loop: &FourierLoop, scoring: &Scoring) -> Evaluation {
    let kinematic = model.momentum_count() == 0;
    match kinematic && model.curvature(&shape_loop.shape(0.0).0).is_some() {
        true => by_curvature(model, shape_loop, scoring),
        false => by_sensitivities(model, shape_loop, scoring),
    }
}
