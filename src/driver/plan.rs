//! Optimal control by direct collocation (docs/INTERFACE.md section 13):
//! inputs and a trajectory over `[0, T]` that meet the start and goal
//! conditions and the bounds, and minimize a running cost
//!
//! ```text
//! minimize  integral_0^T L(t, q, qdot, u) dt   (default L = sum u^2)
//! subject to  d(q, qdot)/dt = (qdot, qddot(q, qdot, u)),  given q, qdot at 0 and T,
//!             lo <= q, qdot, u <= hi at every node.
//! ```
//!
//! - [`transcription`]: the plan as a nonlinear program on the nodes'
//!   states and inputs, its derivatives exact;
//! - `hessian`: the exact Hessian of that program's Lagrangian, from the
//!   cost's and the model's second derivatives;
//! - [`nlp`]: that program, and the solvers behind one trait;
//! - [`kkt`]: the solver's answer verified by the KKT conditions from the
//!   exact derivatives: an answer that fails them is an error.
//!
//! The dynamics are the Lagrange-d'Alembert equations in `x = (q, qdot)`
//! (`simulate --formulation lagrange`), whose variables are the columns of
//! `trajectory.csv`. The velocity constraints `A(q) qdot = 0` and the
//! configuration constraints `f(q) = 0` are invariants of that flow: a
//! model with either starts from a state that meets them (every
//! coordinate and velocity given), and the scheme keeps them to its order
//! (`plan.csv`'s `constraint_residual` and `holonomic_residual`).

mod hessian;
pub mod kkt;
pub mod nlp;
mod resolve;
pub mod transcription;

use super::Failure;
use super::engine::Loaded;
use crate::runtime::record::Table;
use kkt::Residuals;
use nlp::{Nlp, Solver};
use std::time::Instant;
pub use transcription::Scheme;

/// A plan's duration, grid, scheme, conditions, cost, bounds and
/// parameters.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct Request {
    /// The duration `T`.
    #[cfg_attr(feature = "cli", arg(long))]
    pub duration: f64,
    /// The number of nodes `N` (at least 2), `T / (N - 1)` apart.
    #[cfg_attr(feature = "cli", arg(long))]
    pub nodes: usize,
    /// The collocation scheme.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = Scheme::Midpoint))]
    pub scheme: Scheme,
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
    /// `NAME=LO:HI` bounds an input, coordinate or velocity at every node;
    /// either end may be empty (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "bound", value_parser = super::simulate::expression_assignment))]
    pub bounds: Vec<(String, String)>,
    /// A model parameter, `NAME=VALUE` (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "param", value_parser = super::simulate::assignment))]
    pub params: Vec<(String, f64)>,
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
    /// The solver's iterations at most.
    pub const MAX_ITERATIONS: usize = 3000;
}

/// Why a plan was not made.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// The solver's answer fails the KKT conditions.
    #[error(
        "no verified optimum: the solver says {status} after {iterations} iterations, but the KKT \
         residuals are primal {primal:.1e}, dual {dual:.1e}, complementarity {complementarity:.1e} \
         (allowed {allowed:.1e})",
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
    },
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
}

impl Report {
    /// As `plan.json` holds it.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "objective": self.objective,
            "duration": self.duration,
            "nodes": self.nodes,
            "scheme": self.scheme.name(),
            "solver": self.solver,
            "iterations": self.iterations,
            "seconds": self.seconds,
            "status": self.status,
            "kkt": {
                "primal": self.kkt.primal,
                "dual": self.kkt.dual,
                "complementarity": self.kkt.complementarity,
            },
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

/// The plan `request` asks of `loaded`, solved by `solver` and verified.
///
/// # Errors
/// Bad input (an unknown name, fewer than two nodes, a bound the
/// conditions violate, a start off the constraints), or an answer that is
/// not a verified optimum.
pub fn plan(loaded: Loaded, request: &Request, solver: &dyn Solver) -> Result<Plan, Failure> {
    let transcription = resolve::transcribe(loaded, request)?;
    let started = Instant::now();
    let solution = solver.solve(&transcription, request.tol, Request::MAX_ITERATIONS);
    let seconds = started.elapsed().as_secs_f64();
    let (status, iterations) = (solution.status.clone(), solution.iterations);
    let objective = transcription.objective(&solution.z);
    let (Some(residuals), Some(objective)) = (kkt::residuals(&transcription, &solution), objective)
    else {
        return Err(PlanError::NotFinite { status, iterations }.into());
    };
    let allowed = Request::VERIFIED * request.tol;
    if !residuals.within(allowed) {
        return Err(PlanError::NotVerified {
            status,
            iterations,
            residuals,
            allowed,
        }
        .into());
    }
    let report = Report {
        objective,
        duration: request.duration,
        nodes: request.nodes,
        scheme: request.scheme,
        solver: solver.name(),
        iterations,
        seconds,
        status,
        kkt: residuals,
    };
    Ok(Plan {
        table: resolve::table(&transcription, &solution.z)?,
        report,
    })
}

#[cfg(test)]
mod tests;
