//! What an `orient` frame adds to the model: the unit constraint of its
//! Euler parameters, and a term of the kinetic energy that vanishes on it.
//!
//! The Euler parameters `e` of `F = orient(P, e0, e1, e2, e3)` turn `F`
//! only on the unit sphere, so the tool adds the holonomic constraint
//! `F_unit: e0^2 + e1^2 + e2^2 + e3^2 - 1 = 0` to the declared ones.
//! The bodies' kinetic energy does not see the rate along `e`
//! (`omega = 2 E(e) edot` and `E e = 0`), so the mass matrix is only
//! positive semi-definite. The tool adds
//!
//! ```text
//! T_F = 1/2 mu (e . edot)^2,    mu = 4/3 tr(I_F)
//! ```
//!
//! with `I_F` the sum of the inertias of the bodies fixed in `F` about
//! their centres (`mu = 1` where that sum is zero): `2 E^T I E` has the
//! principal moments `4 I_k` as its eigenvalues on the sphere's tangent
//! space, and `mu` is their mean, so `g` becomes positive definite and no
//! worse conditioned. `T_F` vanishes with the constraint's velocity form
//! `e . edot = 0`, and its Lagrange terms
//! `d/dt dT_F/d edot - dT_F/de = mu d/dt(e . edot) e` vanish on every motion
//! that keeps the constraint: the motion is that of the bodies alone
//! (docs/MATH.md section 5; Nikravesh, *Computer-Aided Analysis of
//! Mechanical Systems*, 1988, section 6.4, for the Euler parameters'
//! kinematics).

use super::super::context::Context;
use super::contacts::velocity_form;
use super::values::Row;
use crate::model::Declared;
use crate::model::mechanism::bodies::{Body, BodyMotion};
use crate::model::mechanism::space::time_derivative;
use crate::model::mechanism::vector::{self, Vector};
use crate::model::mechanism::{FrameTurn, TurnedBy};
use crate::sym::{ExprId, Rational, SymError, SymbolId};

/// The unit constraints: each one's name, residual and velocity form.
pub(super) struct UnitConstraints {
    pub(super) names: Vec<Declared>,
    pub(super) residuals: Vec<ExprId>,
    pub(super) rows: Vec<Row>,
}

/// The Euler parameters of each `orient` frame, with its declaration.
fn oriented<'a>(
    frames: &'a [(Declared, FrameTurn)],
    q: &'a [SymbolId],
) -> impl Iterator<Item = (&'a Declared, [SymbolId; 4])> + 'a {
    frames.iter().filter_map(|(declared, turn)| match turn.by {
        TurnedBy::EulerParameters(indices) => Some((declared, indices.map(|i| q[i]))),
        TurnedBy::Angle(_) => None,
    })
}

/// `F_unit: |e|^2 - 1 = 0` of each `orient` frame `F`; a declared
/// holonomic constraint of that name is reported.
pub(super) fn unit_constraints(
    cx: &mut Context,
    frames: &[(Declared, FrameTurn)],
    declared: &[Declared],
    q: &[SymbolId],
) -> Result<UnitConstraints, SymError> {
    let mut units = UnitConstraints {
        names: Vec::new(),
        residuals: Vec::new(),
        rows: Vec::new(),
    };
    for (frame, e) in oriented(frames, q) {
        let name = format!("{}_unit", frame.name);
        if let Some(clash) = declared.iter().find(|d| d.name == name) {
            cx.diagnostics.error(
                clash.span,
                format!(
                    "`{name}` names the unit constraint the tool adds for the `orient` frame \
                     `{}`: choose another name",
                    frame.name
                ),
            );
        }
        let e = e.map(|s| cx.sym.symbol(s));
        let square = vector_square(cx, &e);
        let one = cx.sym.integer(1);
        let residual = cx.sym.sub(square, one);
        units.rows.push(velocity_form(cx, residual, q)?);
        units.residuals.push(residual);
        units.names.push(Declared {
            name,
            span: frame.span,
        });
    }
    Ok(units)
}

/// `e . e` of four entries.
fn vector_square(cx: &mut Context, e: &[ExprId; 4]) -> ExprId {
    let squares: Vec<ExprId> = e.iter().map(|&x| cx.sym.mul2(x, x)).collect();
    cx.sym.add(&squares)
}

/// `T_F = 1/2 mu (e . edot)^2` of each `orient` frame, as the motion of a
/// particle of mass `mu` moving at `e . edot` along one axis.
pub(super) fn rate_along_parameters(
    cx: &mut Context,
    frames: &[(Declared, FrameTurn)],
    bodies: &[(Declared, Body)],
    q: &[SymbolId],
) -> Result<Vec<BodyMotion>, SymError> {
    let mut motions = Vec::new();
    for (frame, e) in oriented(frames, q) {
        let values = e.map(|s| cx.sym.symbol(s));
        let half_square = vector_square(cx, &values);
        let half = cx.sym.number(Rational::HALF);
        let half_square = cx.sym.mul2(half, half_square);
        let along = time_derivative(&mut cx.sym, half_square, q)?;
        let zero = cx.sym.integer(0);
        let still: Vector = vector::zero(&mut cx.sym);
        motions.push(BodyMotion {
            mass: scale(cx, &frame.name, bodies)?,
            inertia: [zero; 9],
            velocity: [along, zero, zero],
            angular_velocity: still,
        });
    }
    Ok(motions)
}

/// `mu = 4/3 tr(I_F)` of the bodies fixed in `frame`, or 1 where that is
/// zero.
fn scale(cx: &mut Context, frame: &str, bodies: &[(Declared, Body)]) -> Result<ExprId, SymError> {
    let diagonal: Vec<ExprId> = bodies
        .iter()
        .filter(|(_, body)| body.frame_name == frame)
        .flat_map(|(_, body)| [0, 4, 8].map(|k| body.inertia[k]))
        .collect();
    let trace = cx.sym.add(&diagonal);
    if cx.sym.normal(trace)?.is_zero() {
        return Ok(cx.sym.integer(1));
    }
    let (three, four) = (cx.sym.integer(3), cx.sym.integer(4));
    let four_traces = cx.sym.mul2(four, trace);
    cx.sym.div(four_traces, three)
}
