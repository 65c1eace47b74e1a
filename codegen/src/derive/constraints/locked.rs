//! Bodies the contacts leave unable to move (docs/INTERFACE.md section 4).
//!
//! A body's centre velocity `v_C(q, qdot)` and angular velocity
//! `omega(q, qdot)` are linear in the velocities. The body cannot move when
//! both vanish on every allowed velocity, that is on every field of the
//! basis of D:
//!
//! ```text
//! sum_i (d v_C / d qdot_i) X_ij = 0  and  sum_i (d omega / d qdot_i) X_ij = 0,   j = 1..k.
//! ```
//!
//! Parallel-steered front wheels leave a car's chassis so: its only
//! motion left is the steering. A coordinate moves when some field has a
//! non-zero entry in its row. Both are decided by evaluation modulo a prime
//! at random points ([`crate::sym::modular`]): a non-zero value proves that
//! a body or a coordinate moves; zeros at every point are probable, wrong
//! with probability below `1e-15`.

use super::DistributionBasis;
use crate::model::Model;
use crate::sym::modular::{self, ModularError};
use crate::sym::residues::Values;
use crate::sym::{Context, ExprId};

/// The bodies that cannot move and the coordinates that can.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Locked {
    /// The names of the bodies every allowed velocity leaves at rest.
    pub bodies: Vec<String>,
    /// The coordinates some allowed velocity moves, by index.
    pub moving: Vec<usize>,
}

impl Locked {
    /// The locked bodies in words, and why: `None` when none is.
    pub fn describe(&self, model: &Model) -> Option<String> {
        if self.bodies.is_empty() {
            return None;
        }
        let moving: Vec<&str> = (self.moving.iter())
            .map(|&i| model.coordinates[i].declared.name.as_str())
            .collect();
        let why = match moving.is_empty() {
            true => "no velocity is allowed at all".to_string(),
            false => format!("every allowed velocity moves only {}", moving.join(", ")),
        };
        Some(format!("{} ({why})", self.bodies.join(", ")))
    }
}

/// The bodies left unable to move; none when a body's motion is outside
/// the class evaluated modulo a prime.
pub(super) fn locked_bodies(model: &Model, cx: &mut Context, basis: &DistributionBasis) -> Locked {
    let names: Vec<String> = (model.mechanism.drawing.iter())
        .flat_map(|drawing| drawing.bodies.iter().map(|body| body.name.clone()))
        .collect();
    // The declared bodies' motions come first, in order; the motions after
    // them (an `orient` frame's unit-norm term) are no bodies.
    let motions = &model.energy_expressions.bodies;
    let bodies = &motions[..names.len().min(motions.len())];
    if bodies.is_empty() || model.c() == 0 {
        return Locked::default();
    }
    let (n, k) = (model.n(), model.k());
    let fields = &basis.field_expressions;
    let mut roots: Vec<ExprId> = fields.entries().to_vec();
    for body in bodies {
        for component in body.velocity.iter().chain(&body.angular_velocity) {
            let rates: Vec<ExprId> = (model.velocities.iter())
                .map(|&velocity| cx.derivative(*component, velocity))
                .collect();
            roots.extend((0..k).map(|j| along_field(cx, &rates, fields.column_entries(j))));
        }
    }
    let Ok(values) = values_at_points(cx, &roots) else {
        return Locked::default();
    };
    let moves = |at: usize| values.iter().any(|point| point[at] != 0);
    let per_body = 6 * k;
    Locked {
        bodies: (0..bodies.len())
            .filter(|&b| !(0..per_body).any(|i| moves(n * k + b * per_body + i)))
            .map(|b| names[b].clone())
            .collect(),
        moving: (0..n)
            .filter(|&i| (0..k).any(|j| moves(i * k + j)))
            .collect(),
    }
}

/// `sum_i rates_i field_i`.
fn along_field(cx: &mut Context, rates: &[ExprId], field: Vec<ExprId>) -> ExprId {
    let terms: Vec<ExprId> = rates
        .iter()
        .zip(field)
        .map(|(&rate, entry)| cx.mul2(rate, entry))
        .collect();
    cx.add(&terms)
}

/// The values of `roots` at the derivations' random points.
fn values_at_points(cx: &Context, roots: &[ExprId]) -> Result<Vec<Vec<u64>>, ModularError> {
    modular::at_defined_points(modular::SEEDS.len(), |point| {
        Values::at(point).of(cx, roots)
    })
}
