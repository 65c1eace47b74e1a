//! Mechanisms: a model declared by frames, points, bodies and contacts.
//!
//! The sections `frames`, `points`, `bodies`, `gravity`, `no_slip` and
//! `holonomic` (docs/INTERFACE.md section 4) are turned into exact symbolic
//! objects that join the energy-level ones: the bodies' kinetic and
//! potential energies ([`bodies`]) add to the declared `T` and `V`; each
//! `no_slip` direction gives the constraint row `d . v_P = 0`, and each
//! holonomic constraint `f(q) = 0` its velocity form `(df/dq) qdot = 0`.
//! Orientations come from the rotation chain and velocities from exact
//! differentiation (the module `space`), so everything downstream (constraint
//! analysis, the formulations, the documents) works unchanged.

pub mod bodies;
pub(super) mod evaluate;
pub(super) mod space;
pub(super) mod vector;

#[cfg(test)]
mod tests;

use super::Declared;
use super::drawing::DrawnItem;
use crate::sym::{ExprId, Matrix, RationalFunction};

/// What a model's mechanism sections declare, in normal form.
#[derive(Clone, Debug)]
pub struct Mechanism {
    /// The declared frames (not `ground`), in the order they were resolved.
    pub frames: Vec<Declared>,
    /// How each of them is turned from its parent, in the same order.
    pub turns: Vec<FrameTurn>,
    /// Each frame's rotation matrix in ground axes, row-major: `nf x 9`.
    pub orientations: Matrix,
    /// The declared points (not `origin`), in order.
    pub points: Vec<Declared>,
    /// Each point's position `P - origin` in ground axes: `np x 3`.
    pub positions: Matrix,
    /// The bodies' kinetic energy (part of the model's `T`).
    pub kinetic_energy: RationalFunction,
    /// The bodies' potential energy in the gravity field (part of `V`).
    pub potential_energy: RationalFunction,
    /// The names of the rolling-contact rows (part of the constraints).
    pub contacts: Vec<Declared>,
    /// The names of the holonomic constraints.
    pub holonomic: Vec<Declared>,
    /// `f(q)`, one row each: `h x 1`.
    pub holonomic_residual: Matrix,
    /// The same orientations, positions and residuals as the emitted code
    /// computes them.
    pub expressions: MechanismExpressions,
    /// What drawing the model needs: the gravity field, the bodies, the
    /// contacts and the drawing section's items ([`Drawing`]); `None`
    /// without mechanism sections and without a drawing section.
    pub drawing: Option<Drawing>,
}

/// How a declared frame is turned from its parent.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameTurn {
    /// The parent's name: `ground` or a declared frame.
    pub parent: String,
    /// What turns it.
    pub by: TurnedBy,
}

/// What turns a frame from its parent.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TurnedBy {
    /// `rotate(parent, axis, angle)`: the indices of the coordinates the
    /// angle reads.
    Angle(Vec<usize>),
    /// `orient(parent, e0, e1, e2, e3)`: the indices of the four
    /// coordinates.
    EulerParameters([usize; 4]),
}

/// What drawing a model needs, as expressions of the coordinates and the
/// parameters, in ground axes: a mechanism's gravity, bodies and contacts,
/// and the items of the `drawing:` section; the interpreter's `drawing(q)`
/// computes them.
#[derive(Clone, Debug)]
pub struct Drawing {
    /// The uniform gravity field `g` (zero when not declared).
    pub gravity: [ExprId; 3],
    /// The bodies and particles, in declared order.
    pub bodies: Vec<DrawnBody>,
    /// The `no_slip` contacts, each once whatever its number of
    /// directions, in declared order.
    pub contacts: Vec<DrawnContact>,
    /// The items of the `drawing:` section, in order.
    pub items: Vec<DrawnItem<ExprId>>,
}

impl Drawing {
    /// The drawing of a model without bodies: its `drawing:` section's
    /// items alone.
    pub fn of_items(items: Vec<DrawnItem<ExprId>>, zero: ExprId) -> Drawing {
        Drawing {
            gravity: [zero; 3],
            bodies: Vec::new(),
            contacts: Vec::new(),
            items,
        }
    }
}

/// A body or a particle, as drawing it needs.
#[derive(Clone, Debug)]
pub struct DrawnBody {
    /// Its declared name.
    pub name: String,
    /// True for a `particle(point, mass)`.
    pub particle: bool,
    /// Its centre `C - origin`.
    pub center: [ExprId; 3],
    /// Its frame's rotation matrix, row-major (the identity for a particle).
    pub rotation: [ExprId; 9],
    /// Its mass.
    pub mass: ExprId,
    /// Its inertia about the centre in its frame's axes, row-major.
    pub inertia: [ExprId; 9],
}

/// A `no_slip(body, point, [...])` contact, as drawing it needs.
#[derive(Clone, Debug)]
pub struct DrawnContact {
    /// Its declared name.
    pub name: String,
    /// The index of its body in [`Drawing::bodies`].
    pub body: usize,
    /// The contact point `P - origin`.
    pub point: [ExprId; 3],
}

/// A mechanism's orientations, positions and holonomic residuals as
/// expressions ([`crate::sym::Context::compact_expression`]): each normal
/// form written out, or when large the expression it was derived as along
/// the rotation chain (equal to it).
#[derive(Clone, Debug)]
pub struct MechanismExpressions {
    /// `nf x 9`, as [`Mechanism::orientations`].
    pub orientations: Matrix<ExprId>,
    /// `np x 3`, as [`Mechanism::positions`].
    pub positions: Matrix<ExprId>,
    /// `h x 1`, as [`Mechanism::holonomic_residual`].
    pub holonomic_residual: Matrix<ExprId>,
}

impl Mechanism {
    /// A model without mechanism sections.
    pub fn none() -> Mechanism {
        Mechanism {
            frames: Vec::new(),
            turns: Vec::new(),
            orientations: Matrix::zeros(0, 9),
            points: Vec::new(),
            positions: Matrix::zeros(0, 3),
            kinetic_energy: RationalFunction::zero(),
            potential_energy: RationalFunction::zero(),
            contacts: Vec::new(),
            holonomic: Vec::new(),
            holonomic_residual: Matrix::zeros(0, 1),
            expressions: MechanismExpressions {
                orientations: Matrix::empty(9),
                positions: Matrix::empty(3),
                holonomic_residual: Matrix::empty(1),
            },
            drawing: None,
        }
    }

    /// True when any mechanism section was given.
    pub fn is_declared(&self) -> bool {
        !(self.frames.is_empty()
            && self.points.is_empty()
            && self.kinetic_energy.is_zero()
            && self.potential_energy.is_zero()
            && self.contacts.is_empty()
            && self.holonomic.is_empty())
    }
}
