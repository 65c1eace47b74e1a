//! Rigid bodies and particles: their energies and the slip velocity of a
//! material point.
//!
//! A body fixed in frame `F` with centre of mass `C`, mass `m` and inertia
//! `I` about `C` in `F`'s axes has, with `v_C = dC/dt` and
//! `omega_F = R_F^T omega` its angular velocity in its own axes (König's
//! theorem),
//!
//! ```text
//! T = 1/2 m v_C . v_C + 1/2 omega_F . I omega_F
//! V = -m g . (C - origin)                      in a uniform field g
//! ```
//!
//! and its material point now at `P` moves with `v_P = v_C + omega x (P - C)`:
//! rolling without slipping at `P` is `d . v_P = 0` for each direction `d`
//! (Neimark and Fufaev, *Dynamics of Nonholonomic Systems*, 1972, ch. 1).
//! A particle is a body with no angular velocity and no inertia.

use super::space::{FrameState, half, velocity};
use super::vector::{self, Vector};
use crate::sym::{Context, ExprId, SymError, SymbolId};

/// A rigid body, or a particle (in `ground` with zero inertia).
#[derive(Clone, Debug)]
pub(in crate::model) struct Body {
    /// The frame the body is fixed in, and its name.
    pub(in crate::model) frame: FrameState,
    pub(in crate::model) frame_name: String,
    /// The centre of mass.
    pub(in crate::model) center: Vector,
    /// `m`.
    pub(in crate::model) mass: ExprId,
    /// `I` about the centre in the frame's axes, row-major.
    pub(in crate::model) inertia: [ExprId; 9],
    /// True for a `particle(point, mass)`.
    pub(in crate::model) particle: bool,
}

impl Body {
    /// `v_C` and `omega_F`, as [`BodyMotion`].
    pub(in crate::model) fn motion(
        &self,
        cx: &mut Context,
        coordinates: &[SymbolId],
    ) -> Result<BodyMotion, SymError> {
        let velocity = velocity(cx, &self.center, coordinates)?;
        let angular_velocity = self.frame.own_axes_angular_velocity(cx);
        Ok(BodyMotion {
            mass: self.mass,
            inertia: self.inertia,
            velocity,
            angular_velocity,
        })
    }

    pub(in crate::model) fn potential_energy(&self, cx: &mut Context, gravity: &Vector) -> ExprId {
        let height = vector::inner(cx, gravity, &self.center);
        let weight = cx.mul2(self.mass, height);
        cx.neg(weight)
    }

    /// `v_P = v_C + omega x (P - C)` of the material point now at `point`.
    pub(in crate::model) fn material_velocity(
        &self,
        cx: &mut Context,
        point: &Vector,
        coordinates: &[SymbolId],
    ) -> Result<Vector, SymError> {
        let v = velocity(cx, &self.center, coordinates)?;
        let arm = vector::sub(cx, point, &self.center);
        let turning = vector::cross(cx, &self.frame.angular_velocity, &arm);
        Ok(vector::add(cx, &v, &turning))
    }
}

/// What the equations of motion read of a body: `m`, `I` about the centre
/// in the body's axes, the centre's velocity `v_C` (ground axes) and the
/// angular velocity `omega_F` (the body's axes), both linear in `qdot`.
///
/// With the partial velocities `J_v = d v_C / d qdot`, `J_w = d omega_F / d
/// qdot` and the rates at `qddot = 0`, `a = sum_k (d v_C / d q_k) qdot_k`
/// and `alpha = sum_k (d omega_F / d q_k) qdot_k`, the body's part of
/// Lagrange's equations is Kane's (Kane & Levinson, *Dynamics: Theory and
/// Applications*, 1985, ch. 6; Moore, "Nonholonomic Constraints"):
///
/// ```text
/// d/dt dT/dqdot - dT/dq = g_b qddot + m J_v^T a + J_w^T (I alpha + omega_F x I omega_F)
/// g_b = m J_v^T J_v + J_w^T I J_w
/// ```
///
/// each a handful of derivatives of `v_C` and `omega_F`, where the same
/// terms from `T` take second derivatives of the whole energy.
#[derive(Clone, Debug)]
pub struct BodyMotion {
    /// `m`.
    pub mass: ExprId,
    /// `I` about the centre in the body's axes, row-major.
    pub inertia: [ExprId; 9],
    /// `v_C` in ground axes.
    pub velocity: Vector,
    /// `omega_F` in the body's axes.
    pub angular_velocity: Vector,
}

impl BodyMotion {
    /// `T = 1/2 m v_C . v_C + 1/2 omega_F . I omega_F`.
    pub(in crate::model) fn kinetic_energy(&self, cx: &mut Context) -> ExprId {
        let speed_squared = vector::inner(cx, &self.velocity, &self.velocity);
        let translation = cx.mul2(self.mass, speed_squared);
        let spun = self.spun(cx, &self.angular_velocity);
        let rotation = vector::inner(cx, &self.angular_velocity, &spun);
        let twice = cx.add2(translation, rotation);
        let one_half = half(cx);
        cx.mul2(one_half, twice)
    }

    /// `I w`.
    fn spun(&self, cx: &mut Context, w: &Vector) -> Vector {
        [0, 1, 2].map(|row| {
            let products: Vec<ExprId> = (0..3)
                .map(|k| cx.mul2(self.inertia[3 * row + k], w[k]))
                .collect();
            cx.add(&products)
        })
    }

    /// `J_v` and `J_w`: column `i` the derivatives in `velocities[i]`.
    fn partial_velocities(&self, cx: &mut Context, velocities: &[SymbolId]) -> Vec<[Vector; 2]> {
        velocities
            .iter()
            .map(|&v| {
                let translation = self.velocity.map(|e| cx.derivative(e, v));
                let rotation = self.angular_velocity.map(|e| cx.derivative(e, v));
                [translation, rotation]
            })
            .collect()
    }

    /// `g_b`, `n x n` row-major.
    pub fn mass_matrix(&self, cx: &mut Context, velocities: &[SymbolId]) -> Vec<ExprId> {
        let partials = self.partial_velocities(cx, velocities);
        let spun: Vec<Vector> = partials
            .iter()
            .map(|[_, rotation]| self.spun(cx, rotation))
            .collect();
        let n = velocities.len();
        let mut entries = Vec::with_capacity(n * n);
        for [translation_i, rotation_i] in &partials {
            for ([translation_j, _], spun_j) in partials.iter().zip(&spun) {
                let along = vector::inner(cx, translation_i, translation_j);
                let along = cx.mul2(self.mass, along);
                let about = vector::inner(cx, rotation_i, spun_j);
                entries.push(cx.add2(along, about));
            }
        }
        entries
    }

    /// `m J_v^T a + J_w^T (I alpha + omega_F x I omega_F)`: the body's
    /// velocity terms of `d/dt dT/dqdot - dT/dq` (see the type's documentation).
    pub fn velocity_terms(
        &self,
        cx: &mut Context,
        coordinates: &[SymbolId],
        velocities: &[SymbolId],
    ) -> Result<Vec<ExprId>, SymError> {
        let acceleration = velocity(cx, &self.velocity, coordinates)?;
        let acceleration = vector::scale(cx, self.mass, &acceleration);
        let angular_acceleration = velocity(cx, &self.angular_velocity, coordinates)?;
        let spun_rate = self.spun(cx, &angular_acceleration);
        let momentum = self.spun(cx, &self.angular_velocity);
        let gyroscopic = vector::cross(cx, &self.angular_velocity, &momentum);
        let torque = vector::add(cx, &spun_rate, &gyroscopic);
        Ok(self
            .partial_velocities(cx, velocities)
            .iter()
            .map(|[translation, rotation]| {
                let along = vector::inner(cx, translation, &acceleration);
                let about = vector::inner(cx, rotation, &torque);
                cx.add2(along, about)
            })
            .collect())
    }
}
