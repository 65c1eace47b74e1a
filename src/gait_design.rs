//! Gait design: the shape loops of a principally kinematic model that move
//! it furthest per cycle, or per unit of the loop's length in the shape
//! coordinates, in a chosen direction (Hatton & Choset, "Geometric motion
//! planning: the local connection, Stokes' theorem, and the importance of
//! coordinate choice", 2011; docs/MATH.md 4.4; docs/INTERFACE.md section 9).
//!
//! A loop is a truncated Fourier series in each shape coordinate
//! ([`FourierLoop`]). Its displacement is integrated along the loop, and its
//! gradient in the coefficients is exact: the first variation of the
//! holonomy, the connection's curvature carried along the loop by the
//! group's adjoint ([`evaluate`]). The search ([`optimize`]) surveys random
//! loops, refines the best of them by argmin's L-BFGS with a backtracking
//! (Armijo) line search and keeps the best result; a barrier keeps every
//! loop off the set where the connection is singular.
//!
//! A model read from its text is [`Kinematic`] through
//! `driver::gait::locomotion`; for a generated struct, the trait's two
//! methods are its `connection_curvature` and `connection_divisor`, and
//! `runtime::gait::FromEquations` gives its [`Locomotion`].

mod fourier;
mod search;
mod variation;

pub use fourier::FourierLoop;
pub use search::{Design, DesignError, Optimum, SURVEY, optimize};
pub use variation::{Evaluation, Scoring, clearance, evaluate};

use crate::runtime::gait::Locomotion;

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

/// A principally kinematic model with an SE(2) symmetry at sizes known at
/// run time: its reconstruction (through [`Locomotion`], with no momenta),
/// its connection's curvature and the divisor of its connection.
pub trait Kinematic: Locomotion {
    /// `(x, y, theta)` of the curvature `F_ij(r)` on each plane of shape
    /// coordinates `(i, j)`, `i < j`, in order (`connection_curvature`).
    fn curvature(&self, r: &[f64]) -> Vec<[f64; 3]>;
    /// The connection's divisor `d(r)` and its gradient
    /// (`connection_divisor`): the connection is singular where `d = 0`.
    fn divisor(&self, r: &[f64]) -> (f64, Vec<f64>);
}
