//! Models read from their text, run by name: what the `chaplygin` command
//! line and the Python package do with a model, at sizes known at run
//! time.
//!
//! - [`catalog`]: the built-in models, their sources and default motions;
//!   [`engine`]: a model's text derived and its programs compiled to native
//!   code ([`engine::load`]), or interpreted;
//! - [`formulation`]: one formulation of one model, closed by its inputs,
//!   seen through slices ([`formulation::Formulation`]), and
//!   [`interpreted`], the reduced, Lagrange-d'Alembert and momentum
//!   formulations of a model read from its text;
//! - [`setup`]: a command's request resolved once against its model
//!   (parameters, state assignments and the start they give, input laws,
//!   stop condition) into the plain value every command consumes;
//! - [`simulate`]: a [`simulate::Request`] (formulation, integrator,
//!   controller, span, stop condition, parameters, initial values, input
//!   laws) run to a table and a report;
//! - [`gait`]: the motion a prescribed periodic shape trajectory makes,
//!   cycle by cycle;
//! - [`linearize`]: operating points, linear systems, eigenvalue sweeps
//!   with their intervals of stability, the canonical form;
//!   [`design_map`]: the self-stable speeds over a grid of parameters, on
//!   every core;
//! - [`plan`] (feature `plan`): optimal control by direct collocation on
//!   the exact derivatives, its optimum verified by the KKT conditions;
//! - [`steady`]: steady motions found from unknowns of the point, and
//!   their stability;
//! - [`expression`]: the expressions of input laws, stop conditions,
//!   initial values and operating points, in the model language's syntax;
//! - [`document`]: the derivation document as text, LaTeX or JSON;
//! - [`animation`]: a run of a model as an animated scene, one offline
//!   HTML page (docs/INTERFACE.md section 10).

pub mod animation;
pub mod catalog;
pub mod design_map;
pub mod document;
pub mod engine;
pub mod expression;
pub mod formulation;
pub mod gait;
pub mod interpreted;
pub mod linearize;
#[cfg(feature = "plan")]
pub mod plan;
pub mod setup;
pub mod simulate;
pub mod steady;

/// What a driver call that fails returns: its error, which may travel
/// between threads (out of a call that released Python's GIL, back from a
/// worker).
pub type Failure = Box<dyn std::error::Error + Send + Sync>;
