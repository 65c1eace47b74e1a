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
use crate::sym::{ExprId, Store, SymError, SymbolId};

/// A rigid body, or a particle (in `ground` with zero inertia).
#[derive(Clone, Debug)]
pub(in crate::model) struct Body {
    /// The frame the body is fixed in.
    pub(in crate::model) frame: FrameState,
    /// The centre of mass.
    pub(in crate::model) center: Vector,
    /// `m`.
    pub(in crate::model) mass: ExprId,
    /// `I` about the centre in the frame's axes, row-major.
    pub(in crate::model) inertia: [ExprId; 9],
}

impl Body {
    /// `T = 1/2 m v_C . v_C + 1/2 omega_F . I omega_F`.
    pub(in crate::model) fn kinetic_energy(
        &self,
        store: &mut Store,
        coordinates: &[SymbolId],
    ) -> Result<ExprId, SymError> {
        let v = velocity(store, &self.center, coordinates)?;
        let speed_squared = vector::inner(store, &v, &v);
        let translation = store.mul2(self.mass, speed_squared);
        let omega = self
            .frame
            .to_frame_axes(store, &self.frame.angular_velocity);
        let spun: Vector = [0, 1, 2].map(|row| {
            let products: Vec<ExprId> = (0..3)
                .map(|k| store.mul2(self.inertia[3 * row + k], omega[k]))
                .collect();
            store.add(&products)
        });
        let rotation = vector::inner(store, &omega, &spun);
        let twice = store.add2(translation, rotation);
        let one_half = half(store);
        Ok(store.mul2(one_half, twice))
    }

    /// `V = -m g . (C - origin)`.
    pub(in crate::model) fn potential_energy(&self, store: &mut Store, gravity: &Vector) -> ExprId {
        let height = vector::inner(store, gravity, &self.center);
        let weight = store.mul2(self.mass, height);
        store.neg(weight)
    }

    /// `v_P = v_C + omega x (P - C)` of the material point now at `point`.
    pub(in crate::model) fn material_velocity(
        &self,
        store: &mut Store,
        point: &Vector,
        coordinates: &[SymbolId],
    ) -> Result<Vector, SymError> {
        let v = velocity(store, &self.center, coordinates)?;
        let arm = vector::sub(store, point, &self.center);
        let turning = vector::cross(store, &self.frame.angular_velocity, &arm);
        Ok(vector::add(store, &v, &turning))
    }
}
