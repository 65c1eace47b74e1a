//! A plan replayed: its first state integrated under its inputs, applied
//! between the nodes as the scheme assumes them, and compared with its
//! nodes.
//!
//! A plan that passes the KKT check is an optimum of the discrete problem,
//! not necessarily a motion of the model: where the constraints lose rank
//! between two nodes (the snakeboard's wheels crossing `phi = pi/2`), the
//! scheme's one step may move the state where no trajectory goes. The
//! replay integrates
//!
//! ```text
//! d(q, qdot)/dt = (qdot, qddot(q, qdot, u(t))),   (q, qdot)(0) = the plan's first node,
//! u(t) = (1 - s) u_i + s u_{i+1}   (Hermite-Simpson, s = (t - t_i)/h),
//! u(t) = u_i                       (midpoint rule: held from the left),
//! u(t) = u_{i+1}                   (backward Euler: held from the right),
//! ```
//!
//! on `t_i <= t <= t_{i+1}` (see [`super::transcription`]), by RK4 with
//! [`SUBSTEPS`] steps an interval: its error, `O((h / SUBSTEPS)^4)`, lies
//! far below the schemes' own. A plan in the reduced form is replayed in
//! it, `d(q, alpha)/dt = f(q, alpha, u(t))` in chart 0, and one in the
//! momentum form in its `(q, rdot, p)`.
//!
//! Each state variable's departure from the plan, `|x_j(t_i) - x_{i,j}|`,
//! is measured against its scale: its range over the plan's nodes,
//! `r_j = max_i x_{i,j} - min_i x_{i,j}`, but at least
//! [`Replay::SHARE_OF_KIND`] of the largest range among the variables of
//! its kind (the coordinates, or the velocities or momenta), so that a variable that
//! barely moves (the upright disk's lean rate) is not judged by its own
//! tiny range alone. A plan whose largest relative departure exceeds the
//! tolerance is not a motion of the model. The scheme's own error shrinks
//! with the step (as `h^2` for the midpoint rule); a jump across a
//! singular configuration does not: replayed, the variable that jumped
//! stays where it was, a whole range away.

use super::Scheme;
use super::form::Form;
use super::transcription::share;
use crate::driver::formulation::Formulation;
use crate::driver::interpreted::{
    InputLaw, InterpretedDalembert, InterpretedMomentum, InterpretedReduced,
};
use crate::runtime::integrate::{Rk4, integrate_fixed};
use crate::runtime::record::Table;
use crate::runtime::simulate::RunTimeSized;
use chaplygin_codegen::interpret::InterpretedModel;
use std::cell::Cell;
use std::rc::Rc;
use std::time::Instant;

/// RK4 steps per interval of the plan.
pub const SUBSTEPS: usize = 40;

/// One state variable's departure from the plan at one node.
#[derive(Clone, Debug, PartialEq)]
pub struct Departure {
    /// The variable's name (a coordinate or `dot(q)`).
    pub variable: String,
    /// The node.
    pub node: usize,
    /// Its time.
    pub t: f64,
    /// `|x_j(t_i) - x_{i,j}|` (infinite where the replay stopped before).
    pub size: f64,
    /// `size` over the variable's scale (see the module's docs).
    pub relative: f64,
}

/// A plan's replay against its nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Replay {
    /// The largest relative departure over every node.
    pub largest: Departure,
    /// The largest relative departure at the last node.
    pub at_end: Departure,
    /// What `largest.relative` may reach.
    pub tolerance: f64,
    /// The time the replay took.
    pub seconds: f64,
}

impl Replay {
    /// The tolerance unless given. The midpoint rule's error on the
    /// coarse plans of the tests departs by at most 0.073 of a scale (the
    /// upright disk's lean rate on 41 nodes; the sideways snakeboard's
    /// heading by 0.042), a plan that jumps within one interval by about
    /// 1 (the unbounded sideways snakeboard's `dot(y)`, 1.00).
    pub const TOLERANCE: f64 = 0.25;
    /// The share of its kind's largest range below which a variable's
    /// scale does not fall.
    pub const SHARE_OF_KIND: f64 = 0.1;
    /// The smallest scale, where nothing of a kind moves.
    pub const SMALLEST_SCALE: f64 = 1e-9;

    /// Whether the replay stays within its tolerance.
    pub fn within(&self) -> bool {
        self.largest.relative <= self.tolerance
    }

    /// As `plan.json` holds it.
    pub fn to_json(&self) -> serde_json::Value {
        let departure = |d: &Departure| {
            serde_json::json!({
                "variable": d.variable,
                "node": d.node,
                "t": d.t,
                "departure": finite_or_null(d.size),
                "relative": finite_or_null(d.relative),
            })
        };
        serde_json::json!({
            "integrator": format!("rk4, {SUBSTEPS} steps per interval"),
            "largest": departure(&self.largest),
            "end": departure(&self.at_end),
            "tolerance": self.tolerance,
            "within": self.within(),
            "seconds": self.seconds,
        })
    }
}

/// `value`, or JSON's null for an infinite one.
fn finite_or_null(value: f64) -> serde_json::Value {
    if value.is_finite() {
        value.into()
    } else {
        serde_json::Value::Null
    }
}

/// The share of an interval's first (`j = 0`) and last node's inputs at
/// `s` of the way through it, as `scheme` applies them.
fn input_share(scheme: Scheme, j: usize, s: f64) -> f64 {
    match scheme {
        Scheme::HermiteSimpson => share(j, s),
        Scheme::Midpoint | Scheme::BackwardEuler => share(j, scheme.stages()[0].inputs_at),
    }
}

/// The state (`(q, qdot)`, `(q, alpha)` or `(q, rdot, p)`) at each of
/// `table`'s nodes, integrated in `form` from its first under its inputs
/// as `scheme` applies them, by [`SUBSTEPS`] RK4 steps an interval; NaN
/// from the interval where the integration fails on (everywhere, for a
/// model without the form).
pub fn replayed_states(
    (model, form): (&InterpretedModel, Form),
    scheme: Scheme,
    table: &Table,
) -> Vec<Vec<f64>> {
    replayed_states_by((model, form), scheme, table, SUBSTEPS)
}

/// [`replayed_states`] by `substeps` RK4 steps an interval.
pub fn replayed_states_by(
    (model, form): (&InterpretedModel, Form),
    scheme: Scheme,
    table: &Table,
    substeps: usize,
) -> Vec<Vec<f64>> {
    let (s, p) = (form.state(model), model.sizes().p);
    let t = table.column("t").unwrap_or_default();
    let inputs: Vec<Vec<f64>> = (table.rows.iter())
        .map(|row| row[1 + s..1 + s + p].to_vec())
        .collect();
    let interval = Rc::new(Cell::new((0, 0.0, 1.0)));
    let current = Rc::clone(&interval);
    let law = move |time: f64, _: &[f64], _: &[f64], u: &mut [f64]| {
        let (i, start, h) = current.get();
        let s = (time - start) / h;
        for (k, value) in u.iter_mut().enumerate() {
            *value = input_share(scheme, 0, s) * inputs[i][k]
                + input_share(scheme, 1, s) * inputs[i + 1][k];
        }
    };
    let inputs = InputLaw {
        law: Box::new(law),
        reads_state: false,
    };
    let formulation: Box<dyn Formulation> = match form {
        Form::Lagrange => Box::new(InterpretedDalembert {
            model: model.clone(),
            inputs,
        }),
        Form::Reduced => Box::new(InterpretedReduced::new(model.clone(), inputs)),
        Form::Momentum => match InterpretedMomentum::new(model.clone(), inputs) {
            Ok(momentum) => Box::new(momentum),
            Err(_) => return vec![vec![f64::NAN; s]; t.len()],
        },
    };
    let system = RunTimeSized(&*formulation);
    let mut states = vec![table.rows[0][1..1 + s].to_vec()];
    for (i, window) in t.windows(2).enumerate() {
        let h = window[1] - window[0];
        interval.set((i, window[0], h));
        let from = states[i].clone();
        let step = h / substeps as f64;
        let reached = integrate_fixed(&Rk4, &system, (window[0], from), step, substeps, |_, _| {})
            .unwrap_or_else(|_| vec![f64::NAN; s]);
        states.push(reached);
    }
    states
}

/// The replay of `table`, a plan of `model` in `form` by `scheme`,
/// allowed to depart by `tolerance` of each variable's range.
pub fn replay(
    (model, form): (&InterpretedModel, Form),
    scheme: Scheme,
    table: &Table,
    tolerance: f64,
) -> Replay {
    let started = Instant::now();
    let states = replayed_states((model, form), scheme, table);
    let width = states[0].len();
    let scales = scales(table, width, model.sizes().n);
    let departure = |node: usize| {
        (0..width)
            .map(|j| {
                let size = (states[node][j] - table.rows[node][1 + j]).abs();
                let size = if size.is_nan() { f64::INFINITY } else { size };
                Departure {
                    variable: table.columns[1 + j].clone(),
                    node,
                    t: table.rows[node][0],
                    size,
                    relative: size / scales[j],
                }
            })
            .fold(None, larger)
            .expect("a state")
    };
    let at_end = departure(states.len() - 1);
    let largest = (0..states.len())
        .map(departure)
        .fold(None, larger)
        .expect("a node");
    Replay {
        largest,
        at_end,
        tolerance,
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// Each of the first `width` variables' scale over `table`'s nodes: its
/// range, at least [`Replay::SHARE_OF_KIND`] of the largest range of its
/// kind (the first `n`, the coordinates; the rest).
fn scales(table: &Table, width: usize, n: usize) -> Vec<f64> {
    let ranges: Vec<f64> = (0..width)
        .map(|j| {
            let column = table.rows.iter().map(|row| row[1 + j]);
            let (lo, hi) = column.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
            hi - lo
        })
        .collect();
    let largest = |kind: &[f64]| kind.iter().copied().fold(0.0, f64::max);
    let kinds = [largest(&ranges[..n]), largest(&ranges[n..])];
    (ranges.iter().enumerate())
        .map(|(j, range)| {
            let kind = kinds[usize::from(j >= n)];
            range
                .max(Replay::SHARE_OF_KIND * kind)
                .max(Replay::SMALLEST_SCALE)
        })
        .collect()
}

/// The relatively larger of two departures, the first where they tie.
fn larger(so_far: Option<Departure>, next: Departure) -> Option<Departure> {
    match so_far {
        Some(d) if d.relative >= next.relative => Some(d),
        _ => Some(next),
    }
}
