//! Optimal control by direct collocation (docs/INTERFACE.md section 13):
//! inputs and a trajectory over `[0, T]` that meet the start and goal
//! conditions and the bounds, and minimize a running cost
//!
//! ```text
//! minimize  integral_0^T L(t, q, qdot, u) dt + Phi(T, q(T), qdot(T))   (default L = sum u^2, Phi = 0)
//! subject to  d(q, qdot)/dt = (qdot, qddot(q, qdot, u)),  given q, qdot at 0 and T,
//!             lo <= q, qdot, u <= hi at every node,
//! ```
//!
//! over a given duration `T` or, with `--free-duration`, over `T > 0` too.
//!
//! - [`transcription`]: the plan as a nonlinear program on the nodes'
//!   states and inputs, its derivatives exact;
//! - `hessian`: the exact Hessian of that program's Lagrangian, from the
//!   cost's and the model's second derivatives;
//! - [`nlp`]: that program, and the solvers behind one trait;
//! - [`kkt`]: the solver's answer verified by the KKT conditions from the
//!   exact derivatives: an answer that fails them is an error;
//! - [`replay`]: the plan's inputs integrated from its start and compared
//!   with its nodes: a plan the model does not follow is an error too
//!   ([`PlanError::Departs`], the plan kept for inspection).
//!
//! A solve from the default guess that ends unverified is solved again
//! once with the inputs nudged, which breaks the symmetry a default guess
//! may have ([`Restart`]).
//!
//! [`plan_watched`] tells an observer of each of the solver's iterations;
//! an observer that stops the solve gets the last iterate back, with its
//! KKT residuals, as [`PlanError::Interrupted`].
//!
//! The dynamics are the Lagrange-d'Alembert equations in `x = (q, qdot)`
//! (`simulate --formulation lagrange`), with `--formulation reduced` the
//! reduced port-Hamiltonian form in `x = (q, alpha)`, or with
//! `--formulation momentum` the nonholonomic momentum equation in `x =
//! (q, rdot, p)` ([`form`]), whose variables are the columns of
//! `trajectory.csv`. The velocity
//! constraints `A(q) qdot = 0` and the
//! configuration constraints `f(q) = 0` are invariants of that flow: a
//! model with either starts from a state that meets them, and the scheme
//! keeps them to its order (`plan.csv`'s `constraint_residual` and
//! `holonomic_residual`). A start given whole is checked to meet them; a
//! start that leaves some of what they tie free is held to them by rows
//! of the program at the first node (`initial`).

pub mod form;
mod hessian;
pub mod identify;
mod initial;
pub mod kkt;
pub mod nlp;
pub mod replay;
mod resolve;
pub mod transcription;

use super::Failure;
use super::engine::Loaded;
use super::simulate::FormulationChoice;
use crate::runtime::record::Table;
use form::Form;
use kkt::Residuals;
use nlp::{Nlp, Observer, Solution, Solver};
use replay::Replay;
use std::ops::ControlFlow;
use std::time::Instant;
pub use transcription::Scheme;

/// A plan's duration, grid, scheme, conditions, cost, bounds and
/// parameters.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct Request {
    /// The duration `T`, or with `--free-duration` its first guess.
    #[cfg_attr(feature = "cli", arg(long))]
    pub duration: f64,
    /// Makes `T` an unknown, at least a tenth of `--duration`.
    #[cfg_attr(feature = "cli", arg(long))]
    pub free_duration: bool,
    /// The number of nodes `N` (at least 2), `T / (N - 1)` apart.
    #[cfg_attr(feature = "cli", arg(long))]
    pub nodes: usize,
    /// The collocation scheme.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = Scheme::Midpoint))]
    pub scheme: Scheme,
    /// The dynamics' formulation: the Lagrange-d'Alembert form in `(q,
    /// dot(q))`, the reduced form in `(q, alpha)` (chart 0), or the
    /// momentum equation in `(q, dot(r), p)`; the start, goal and bounds
    /// name `q` and `dot(q)` in each.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = FormulationChoice::Lagrange))]
    pub formulation: FormulationChoice,
    /// A coordinate `q=EXPR` or velocity `dot(q)=EXPR` at `t = 0`, an
    /// expression of the parameters (repeatable); what is not given is
    /// free.
    #[cfg_attr(feature = "cli", arg(long = "start", value_parser = super::simulate::expression_assignment))]
    pub start: Vec<(String, String)>,
    /// A coordinate or velocity at `t = T`, as `--start` (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "goal", value_parser = super::simulate::expression_assignment))]
    pub goal: Vec<(String, String)>,
    /// The running cost, an expression of `t`, the coordinates, velocities
    /// `dot(q)`, inputs and parameters [default: the sum of the inputs
    /// squared].
    #[cfg_attr(feature = "cli", arg(long, value_name = "EXPR"))]
    pub minimize: Option<String>,
    /// A cost added at `t = T`, an expression of `t`, the coordinates,
    /// velocities `dot(q)` and parameters.
    #[cfg_attr(feature = "cli", arg(long, value_name = "EXPR"))]
    pub final_cost: Option<String>,
    /// `NAME=LO:HI` bounds an input, coordinate or velocity at every node;
    /// either end may be empty (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "bound", value_parser = super::simulate::expression_assignment))]
    pub bounds: Vec<(String, String)>,
    /// A model parameter, `NAME=VALUE` (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "param", value_parser = super::simulate::assignment))]
    pub params: Vec<(String, f64)>,
    /// A CSV with `t` and any of `plan.csv`'s columns, interpolated onto
    /// the nodes as the first guess (held beyond its ends); the rest start
    /// from the start and goal interpolated, else 0.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.csv"))]
    pub guess: Option<std::path::PathBuf>,
    /// The solver's tolerance; the KKT conditions are verified to 100
    /// times it.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = Request::TOL))]
    pub tol: f64,
}

impl Request {
    /// The solver's tolerance unless given.
    pub const TOL: f64 = 1e-8;
    /// How many times the solver's tolerance the KKT residuals may reach.
    pub const VERIFIED: f64 = 100.0;
    /// The shortest free duration, as a fraction of its first guess.
    pub const SHORTEST: f64 = 0.1;
    /// The solver's iterations at most.
    pub const MAX_ITERATIONS: usize = 3000;
    /// The amplitude of the inputs' nudge when a solve from the default
    /// guess ends unverified ([`Restart`]).
    pub const NUDGE: f64 = 1e-2;
}

/// Why a plan was not made.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// The solver's answer fails the KKT conditions.
    #[error(
        "no verified optimum: the solver says {status} after {iterations} iterations, but the KKT \
         residuals are primal {primal:.1e}, dual {dual:.1e}, complementarity {complementarity:.1e} \
         (allowed {allowed:.1e}){violation}",
        primal = residuals.primal,
        dual = residuals.dual,
        complementarity = residuals.complementarity
    )]
    NotVerified {
        /// The solver's word.
        status: String,
        /// Its iterations.
        iterations: usize,
        /// The residuals computed.
        residuals: Residuals,
        /// What they may reach.
        allowed: f64,
        /// Where the primal residual is beyond it, `; the largest
        /// violation: ` and the constraint furthest from holding, in words;
        /// else empty.
        violation: String,
    },
    /// The observer stopped the solve: the last iterate, not an optimum,
    /// its report's status `interrupted`.
    #[error("{}", interrupted(.0.report.iterations, &.0.report.kkt))]
    Interrupted(Box<Plan>),
    /// The model's functions are not finite at the solver's answer.
    #[error(
        "no verified optimum: the solver says {status} after {iterations} iterations, at a point \
         where the model's equations are not finite"
    )]
    NotFinite {
        /// The solver's word.
        status: String,
        /// Its iterations.
        iterations: usize,
    },
    /// A verified optimum of the discrete problem whose inputs, replayed,
    /// do not move the model along it: the plan, its report's replay
    /// saying where it departs most.
    #[error(
        "the plan is not a motion of the model: its inputs, replayed from its start, are off \
         the plan at node {node} (t = {t:.4}) by {size:.3e} in `{variable}`, {relative:.2} of \
         its scale (allowed {tolerance}); bound the coordinates away from where the \
         constraints lose rank, or take more nodes{higher}",
        higher = higher_order(.0.report.scheme),
        variable = .0.report.replay.largest.variable,
        size = .0.report.replay.largest.size,
        node = .0.report.replay.largest.node,
        t = .0.report.replay.largest.t,
        relative = .0.report.replay.largest.relative,
        tolerance = .0.report.replay.tolerance
    )]
    Departs(Box<Plan>),
    /// A formulation the model does not have.
    #[error("--formulation {asked}: {reason}")]
    Formulation {
        /// The formulation asked for.
        asked: &'static str,
        /// Why the model does not have it.
        reason: String,
    },
    /// A reduced plan with a node where chart 0 does not fit.
    #[error(
        "the reduced plan leaves chart 0 of the constraints at node {node} (t = {t:.4}), where \
         simulate would change charts: plan with --formulation lagrange, which needs no chart"
    )]
    LeavesChart {
        /// The node.
        node: usize,
        /// Its time.
        t: f64,
    },
    /// A free duration at its lower bound: the optimum may lie below it.
    #[error(
        "the free duration stopped at its lower bound {shortest}, a tenth of --duration: \
         guess a shorter --duration"
    )]
    ShortestDuration {
        /// The lower bound.
        shortest: f64,
    },
}

/// What `plan.json` reports.
#[derive(Clone, Debug)]
pub struct Report {
    /// The cost at the optimum.
    pub objective: f64,
    /// `T`.
    pub duration: f64,
    /// `N`.
    pub nodes: usize,
    /// The scheme.
    pub scheme: Scheme,
    /// The formulation the nodes' states are in.
    pub formulation: Form,
    /// The chart of the reduced form's state, for a model with
    /// constraints.
    pub chart: Option<usize>,
    /// The solver's name.
    pub solver: &'static str,
    /// Its iterations.
    pub iterations: usize,
    /// The time the solve took.
    pub seconds: f64,
    /// The solver's word on the outcome.
    pub status: String,
    /// The KKT residuals, computed from the exact derivatives.
    pub kkt: Residuals,
    /// The plan's inputs replayed from its start.
    pub replay: Replay,
    /// The solve from the default guess that ended unverified, where the
    /// plan was solved again with the inputs nudged.
    pub restart: Option<Restart>,
}

/// A solve from the default guess that ended unverified. The plan is then
/// solved again from that guess with each input moved by [`Request::NUDGE`]
/// `sin(pi t / T)`. The default guess holds what the start and goal leave
/// free at 0, and a model symmetric under a reflection (the trailing
/// racer, mirrored about its heading) has Newton's method keep such a
/// guess's motions symmetric: where every way to the goal breaks the
/// symmetry (the racer driven straight ahead from rest, which it can only
/// do by wiggling), the solve stalls. The nudge breaks the symmetry; a
/// plan verified from the default guess is never solved again.
#[derive(Clone, Debug, PartialEq)]
pub struct Restart {
    /// The solver's word on the solve from the default guess.
    pub status: String,
    /// Its iterations.
    pub iterations: usize,
    /// Its time, in seconds.
    pub seconds: f64,
}

impl Report {
    /// The status of a solve its observer stopped.
    pub const INTERRUPTED: &'static str = "interrupted";

    /// As `plan.json` holds it.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "objective": self.objective,
            "duration": self.duration,
            "nodes": self.nodes,
            "scheme": self.scheme.name(),
            "formulation": self.formulation.name(),
            "chart": self.chart,
            "chart_reason": self.chart.map(|_| form::CHART_REASON),
            "solver": self.solver,
            "iterations": self.iterations,
            "seconds": self.seconds,
            "status": self.status,
            "kkt": {
                "primal": self.kkt.primal,
                "dual": self.kkt.dual,
                "complementarity": self.kkt.complementarity,
            },
            "replay": self.replay.to_json(),
            "restart": self.restart.as_ref().map(|restart| serde_json::json!({
                "status": restart.status,
                "iterations": restart.iterations,
                "seconds": restart.seconds,
            })),
        })
    }
}

/// A verified optimal plan: one row per node, and the report.
#[derive(Clone, Debug)]
pub struct Plan {
    /// `t`, the coordinates, `dot(q)`, the inputs, `energy`,
    /// `constraint_residual` (and `holonomic_residual`), as
    /// `trajectory.csv`.
    pub table: Table,
    /// What `plan.json` reports.
    pub report: Report,
}

/// The advice of [`PlanError::Departs`] beyond its own: a scheme of
/// higher order than `scheme`. A plan can use fast motions the grid does
/// not resolve. Measured on 2026-12-08: the Ackermann car of `tests/models`
/// driven from rest to rest at `(1, 0.5)`, turned by 0.5, in 3 s, swings
/// its light steering knuckles; the midpoint rule's plan departs from its
/// replay on 31 and 121 nodes and slips off the constraints by 0.25 at the
/// nodes on 61, while Hermite-Simpson's on 31 nodes meets them within 1e-3
/// and converges as the nodes double.
fn higher_order(scheme: Scheme) -> &'static str {
    match scheme {
        Scheme::HermiteSimpson => "",
        _ => ", or a scheme of higher order (--scheme hermite-simpson)",
    }
}

/// The formulation `choice` as plans transcribe it, for `model`: the
/// Lagrange-d'Alembert equations in `(q, qdot)`, which need no chart (a
/// model with several, the bicycle, is planned in all its coordinates and
/// velocities at once, regular wherever the constraint rows are
/// independent), the reduced form in `(q, alpha)`, in chart 0, or the
/// momentum equation in `(q, rdot, p)`.
///
/// # Errors
/// [`PlanError::Formulation`] for the momentum form of a model without
/// one.
pub fn formulation(
    choice: FormulationChoice,
    model: &chaplygin_codegen::interpret::InterpretedModel,
) -> Result<Form, PlanError> {
    let form = match choice {
        FormulationChoice::Lagrange => Form::Lagrange,
        FormulationChoice::Reduced => Form::Reduced,
        FormulationChoice::Momentum => Form::Momentum,
    };
    match form.unsupported(model) {
        Some(reason) => Err(PlanError::Formulation {
            asked: form.name(),
            reason,
        }),
        None => Ok(form),
    }
}

/// The plan `request` asks of `loaded`, solved by `solver`, verified and
/// replayed.
///
/// # Errors
/// Bad input (an unknown name, fewer than two nodes, a bound the
/// conditions violate, a start off the constraints), an answer that is
/// not a verified optimum, or one whose replay departs from it by more
/// than [`Replay::TOLERANCE`].
pub fn plan(loaded: Loaded, request: &Request, solver: &dyn Solver) -> Result<Plan, Failure> {
    plan_watched(loaded, request, solver, &mut |_| ControlFlow::Continue(()))
}

/// [`plan`], telling `observer` of each of the solver's iterations.
///
/// # Errors
/// As [`plan`], and [`PlanError::Interrupted`] with the last iterate where
/// `observer` stops the solve.
pub fn plan_watched(
    loaded: Loaded,
    request: &Request,
    solver: &dyn Solver,
    observer: &mut Observer<'_>,
) -> Result<Plan, Failure> {
    plan_within(loaded, request, solver, Replay::TOLERANCE, observer)
}

/// [`plan_watched`], its replay allowed to depart by `replay_tolerance`
/// of each variable's scale (`replay`'s docs).
///
/// # Errors
/// As [`plan_watched`], a tolerance that is not positive and finite, and
/// [`PlanError::Departs`] with the plan where its replay departs by more.
pub fn plan_within(
    loaded: Loaded,
    request: &Request,
    solver: &dyn Solver,
    replay_tolerance: f64,
    observer: &mut Observer<'_>,
) -> Result<Plan, Failure> {
    if !(replay_tolerance.is_finite() && replay_tolerance > 0.0) {
        return Err(resolve::RequestError::ReplayTolerance(replay_tolerance).into());
    }
    let first = resolve::transcribe(loaded, request)?;
    let Solved {
        transcription,
        watched,
        verified,
        restart,
    } = solve_verified(first, (request, solver), observer)?;
    let solution = watched.solution;
    let answer = Answer {
        request,
        solver: solver.name(&transcription),
        seconds: watched.seconds,
        replay_tolerance,
        restart,
    };
    let Some((residuals, objective)) = verified else {
        return Err(PlanError::Interrupted(Box::new(last_iterate(
            &transcription,
            &solution,
            answer,
        )?))
        .into());
    };
    let status = solution.status.clone();
    let duration = transcription.duration(&solution.z);
    let shortest = Request::SHORTEST * request.duration;
    if request.free_duration && duration <= shortest * (1.0 + Request::VERIFIED * request.tol) {
        return Err(PlanError::ShortestDuration { shortest }.into());
    }
    let table = resolve::table(&transcription, &solution.z)?;
    within_chart(&transcription, &solution.z)?;
    let report = answer.report(
        &transcription,
        &solution,
        &table,
        status,
        objective,
        residuals,
    );
    let plan = Plan { table, report };
    if !plan.report.replay.within() {
        return Err(PlanError::Departs(Box::new(plan)).into());
    }
    Ok(plan)
}

/// Checks that every node of a reduced plan at `z` lies where chart 0
/// fits.
fn within_chart(transcription: &transcription::Transcription, z: &[f64]) -> Result<(), PlanError> {
    let model = transcription.model();
    if transcription.form().chart(model).is_none() {
        return Ok(());
    }
    let width = transcription.width();
    let states = z[..transcription.nodes() * width].chunks(width);
    match form::leaves_chart(model, states) {
        Some(node) => Err(PlanError::LeavesChart {
            node,
            t: transcription.node_time(z, node),
        }),
        None => Ok(()),
    }
}

/// A solve of a plan's program: the program, the solve, its KKT
/// residuals and objective where verified (`None` where stopped), and
/// the solve from the default guess that came before.
struct Solved {
    transcription: transcription::Transcription,
    watched: Watched,
    verified: Option<(Residuals, f64)>,
    restart: Option<Restart>,
}

/// `transcription` solved, and where its guess is the default and the
/// solve ends unverified, solved again with the inputs nudged
/// ([`Restart`]).
///
/// # Errors
/// [`verified`]'s, the first solve's where the second fails too.
fn solve_verified(
    transcription: transcription::Transcription,
    (request, solver): (&Request, &dyn Solver),
    observer: &mut Observer<'_>,
) -> Result<Solved, PlanError> {
    let watched = solve_watched(solver, &transcription, request.tol, observer);
    let checked =
        (!watched.stopped).then(|| verified(&transcription, &watched.solution, request.tol));
    match checked.transpose() {
        Err(failure @ PlanError::NotVerified { .. }) if request.guess.is_none() => {
            let restart = Restart {
                status: watched.solution.status.clone(),
                iterations: watched.solution.iterations,
                seconds: watched.seconds,
            };
            let nudged = transcription.nudging_inputs(Request::NUDGE);
            solve_again(nudged, restart, (request, solver), observer).map_err(|_| failure)
        }
        checked => Ok(Solved {
            transcription,
            watched,
            verified: checked?,
            restart: None,
        }),
    }
}

/// `nudged` solved after `restart`.
///
/// # Errors
/// [`verified`]'s.
fn solve_again(
    nudged: transcription::Transcription,
    restart: Restart,
    (request, solver): (&Request, &dyn Solver),
    observer: &mut Observer<'_>,
) -> Result<Solved, PlanError> {
    let watched = solve_watched(solver, &nudged, request.tol, observer);
    let checked = (!watched.stopped).then(|| verified(&nudged, &watched.solution, request.tol));
    Ok(Solved {
        transcription: nudged,
        watched,
        verified: checked.transpose()?,
        restart: Some(restart),
    })
}

/// A watched solve's outcome.
struct Watched {
    /// The solver's answer, or its last iterate.
    solution: Solution,
    /// Whether the observer stopped the solve.
    stopped: bool,
    /// The time the solve took.
    seconds: f64,
}

/// `nlp` solved by `solver` to `tol`, `observer` told of each iteration.
fn solve_watched(
    solver: &dyn Solver,
    nlp: &dyn Nlp,
    tol: f64,
    observer: &mut Observer<'_>,
) -> Watched {
    let started = Instant::now();
    let mut stopped = false;
    let solution = solver.solve(nlp, tol, Request::MAX_ITERATIONS, &mut |iteration| {
        let flow = observer(iteration);
        stopped = flow.is_break();
        flow
    });
    Watched {
        solution,
        stopped,
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// The KKT residuals and the objective of `solution`, where it is a
/// verified optimum of `nlp`: its residuals within
/// [`Request::VERIFIED`] times `tol`.
fn verified(nlp: &dyn Nlp, solution: &Solution, tol: f64) -> Result<(Residuals, f64), PlanError> {
    let (status, iterations) = (solution.status.clone(), solution.iterations);
    let (Some(residuals), Some(objective)) =
        (kkt::residuals(nlp, solution), nlp.objective(&solution.z))
    else {
        return Err(PlanError::NotFinite { status, iterations });
    };
    let allowed = Request::VERIFIED * tol;
    if !residuals.within(allowed) {
        let violation = kkt::largest_violation(nlp, &solution.z)
            .filter(|(_, size)| *size > allowed)
            .map_or_else(String::new, |(row, size)| {
                let row = nlp.describe_row(&solution.z, row);
                format!("; the largest violation: {row}, by {size:.1e}")
            });
        return Err(PlanError::NotVerified {
            status,
            iterations,
            residuals,
            allowed,
            violation,
        });
    }
    Ok((residuals, objective))
}

/// The KKT residuals at a stopped solve's last iterate, NaN where the
/// program's functions are not finite there.
fn last_residuals(nlp: &dyn Nlp, solution: &Solution) -> Residuals {
    kkt::residuals(nlp, solution).unwrap_or(Residuals {
        primal: f64::NAN,
        dual: f64::NAN,
        complementarity: f64::NAN,
    })
}

/// What a solve its observer stopped says: after how many iterations,
/// and the KKT residuals there.
fn interrupted(iterations: usize, kkt: &Residuals) -> String {
    format!(
        "interrupted after {iterations} iterations, at an iterate that is not an optimum (KKT \
         residuals primal {:.1e}, dual {:.1e}, complementarity {:.1e})",
        kkt.primal, kkt.dual, kkt.complementarity
    )
}

/// What every report of a solve says besides its outcome.
struct Answer<'a> {
    request: &'a Request,
    solver: &'static str,
    seconds: f64,
    replay_tolerance: f64,
    restart: Option<Restart>,
}

impl Answer<'_> {
    /// The report of `solution`, whose nodes are `table`'s rows.
    fn report(
        &self,
        transcription: &transcription::Transcription,
        solution: &Solution,
        table: &Table,
        status: String,
        objective: f64,
        kkt: Residuals,
    ) -> Report {
        Report {
            objective,
            duration: transcription.duration(&solution.z),
            nodes: self.request.nodes,
            scheme: self.request.scheme,
            formulation: transcription.form(),
            chart: transcription.form().chart(transcription.model()),
            solver: self.solver,
            iterations: solution.iterations,
            seconds: self.seconds,
            status,
            kkt,
            replay: replay::replay(
                (transcription.model(), transcription.form()),
                self.request.scheme,
                table,
                self.replay_tolerance,
            ),
            restart: self.restart.clone(),
        }
    }
}

/// The last iterate of a stopped solve as a plan whose status is
/// `interrupted`; its objective and residuals NaN where the model's
/// functions are not finite there.
fn last_iterate(
    transcription: &transcription::Transcription,
    solution: &Solution,
    answer: Answer<'_>,
) -> Result<Plan, Failure> {
    let objective = transcription.objective(&solution.z).unwrap_or(f64::NAN);
    let residuals = last_residuals(transcription, solution);
    let table = resolve::table(transcription, &solution.z)?;
    let report = answer.report(
        transcription,
        solution,
        &table,
        Report::INTERRUPTED.into(),
        objective,
        residuals,
    );
    Ok(Plan { table, report })
}

#[cfg(test)]
mod catalog_tests;
#[cfg(test)]
mod tests;
