//! Frames and points: orientations, angular velocities and positions.
//!
//! A frame `f = rotate(p, axis, angle)` is turned from its parent by
//! `angle` about the parent's `axis`: its rotation matrix in ground axes is
//! `R_f = R_p R_axis(angle)` with the elementary right-handed rotations
//!
//! ```text
//! R_x(a) = [[1, 0, 0], [0, c, -s], [0, s, c]]
//! R_y(a) = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
//! R_z(a) = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
//! ```
//!
//! and its angular velocity in ground axes `omega_f = omega_p + (d angle/dt) R_p e_axis`
//! (angular velocities of a chain of rotations add; e.g. Greenwood,
//! *Advanced Dynamics*, 2003, section 2.3). The columns of `R_f` are the unit
//! vectors `f.x`, `f.y`, `f.z`. `ground` has `R = I`, `omega = 0`; `origin`
//! is at zero.

use super::vector::{self, Vector};
use crate::sym::{Context, ExprId, Function, Rational, SymError, SymbolId};

/// A frame's orientation and angular velocity, both in ground axes.
#[derive(Clone, Debug)]
pub(in crate::model) struct FrameState {
    /// `R`, row-major: column `j` is the frame's unit vector `j`.
    pub(in crate::model) rotation: [ExprId; 9],
    /// `omega`.
    pub(in crate::model) angular_velocity: Vector,
}

impl FrameState {
    /// The unit vector along axis `axis` (0, 1, 2 for x, y, z).
    pub(in crate::model) fn axis(&self, axis: usize) -> Vector {
        [0, 1, 2].map(|row| self.rotation[3 * row + axis])
    }

    /// `R^T a`: a ground-axes vector in this frame's axes.
    pub(in crate::model) fn to_frame_axes(&self, cx: &mut Context, a: &Vector) -> Vector {
        [0, 1, 2].map(|axis| {
            let column = self.axis(axis);
            vector::inner(cx, &column, a)
        })
    }
}

/// The frames and points declared so far, `ground` and `origin` first.
#[derive(Debug)]
pub(in crate::model) struct Space {
    frames: Vec<(String, FrameState)>,
    points: Vec<(String, Vector)>,
    /// Frames, points and bodies whose declarations failed: their uses are
    /// not reported again.
    broken: Vec<String>,
}

/// The name of the inertial frame.
pub(in crate::model) const GROUND: &str = "ground";
/// The name of the inertial frame's origin.
pub(in crate::model) const ORIGIN: &str = "origin";

impl Space {
    /// `ground` and `origin` alone.
    pub(in crate::model) fn new(cx: &mut Context) -> Space {
        let (zero, one) = (cx.integer(0), cx.integer(1));
        let rotation = [one, zero, zero, zero, one, zero, zero, zero, one];
        let ground = FrameState {
            rotation,
            angular_velocity: vector::zero(cx),
        };
        Space {
            frames: vec![(GROUND.to_string(), ground)],
            points: vec![(ORIGIN.to_string(), vector::zero(cx))],
            broken: Vec::new(),
        }
    }

    /// A frame by name.
    pub(in crate::model) fn frame(&self, name: &str) -> Option<&FrameState> {
        self.frames.iter().find(|(n, _)| n == name).map(|(_, f)| f)
    }

    /// A point's position by name.
    pub(in crate::model) fn point(&self, name: &str) -> Option<&Vector> {
        self.points.iter().find(|(n, _)| n == name).map(|(_, p)| p)
    }

    /// Records a frame.
    pub(in crate::model) fn add_frame(&mut self, name: &str, frame: FrameState) {
        self.frames.push((name.to_string(), frame));
    }

    /// Records a point.
    pub(in crate::model) fn add_point(&mut self, name: &str, position: Vector) {
        self.points.push((name.to_string(), position));
    }

    /// Records a declaration that failed.
    pub(in crate::model) fn mark_broken(&mut self, name: &str) {
        self.broken.push(name.to_string());
    }

    /// True when `name` was declared but its declaration failed.
    pub(in crate::model) fn is_broken(&self, name: &str) -> bool {
        self.broken.iter().any(|b| b == name)
    }

    /// The declared frames (without `ground`), in resolution order.
    pub(in crate::model) fn declared_frames(&self) -> &[(String, FrameState)] {
        &self.frames[1..]
    }

    /// The declared points (without `origin`), in order.
    pub(in crate::model) fn declared_points(&self) -> &[(String, Vector)] {
        &self.points[1..]
    }
}

/// The frame turned from `parent` by `angle` about the parent's `axis`.
pub(in crate::model) fn rotated(
    cx: &mut Context,
    parent: &FrameState,
    axis: usize,
    angle: ExprId,
    coordinates: &[SymbolId],
) -> Result<FrameState, SymError> {
    let elementary = elementary_rotation(cx, axis, angle)?;
    let rotation = std::array::from_fn(|entry| {
        let (row, column) = (entry / 3, entry % 3);
        let products: Vec<ExprId> = (0..3)
            .map(|k| cx.mul2(parent.rotation[3 * row + k], elementary[3 * k + column]))
            .collect();
        cx.add(&products)
    });
    let rate = time_derivative(cx, angle, coordinates)?;
    let turn = vector::scale(cx, rate, &parent.axis(axis));
    Ok(FrameState {
        rotation,
        angular_velocity: vector::add(cx, &parent.angular_velocity, &turn),
    })
}

/// `R_axis(angle)`, row-major.
fn elementary_rotation(
    cx: &mut Context,
    axis: usize,
    angle: ExprId,
) -> Result<[ExprId; 9], SymError> {
    let (zero, one) = (cx.integer(0), cx.integer(1));
    let c = cx.apply(Function::Cos, angle)?;
    let s = cx.apply(Function::Sin, angle)?;
    let minus_s = cx.neg(s);
    Ok(match axis {
        0 => [one, zero, zero, zero, c, minus_s, zero, s, c],
        1 => [c, zero, s, zero, one, zero, minus_s, zero, c],
        _ => [c, minus_s, zero, s, c, zero, zero, zero, one],
    })
}

/// `d e / dt = sum_i (d e / d q_i) qdot_i` of an expression of the
/// configuration, differentiated on its DAG: the partials share the
/// expression's own sub-expressions instead of expanding them.
pub(in crate::model) fn time_derivative(
    cx: &mut Context,
    expression: ExprId,
    coordinates: &[SymbolId],
) -> Result<ExprId, SymError> {
    let zero = cx.integer(0);
    let mut terms = Vec::with_capacity(coordinates.len());
    for &coordinate in coordinates {
        let partial = cx.derivative(expression, coordinate);
        if partial == zero {
            continue;
        }
        let velocity = cx.velocity_of(coordinate);
        let velocity = cx.symbol(velocity);
        terms.push(cx.mul2(partial, velocity));
    }
    Ok(cx.add(&terms))
}

/// The velocity `d p / dt` of a position.
pub(in crate::model) fn velocity(
    cx: &mut Context,
    position: &Vector,
    coordinates: &[SymbolId],
) -> Result<Vector, SymError> {
    let mut components = *position;
    for component in &mut components {
        *component = time_derivative(cx, *component, coordinates)?;
    }
    Ok(components)
}

/// One half, for the energies.
pub(in crate::model) fn half(cx: &mut Context) -> ExprId {
    cx.number(Rational::HALF)
}
