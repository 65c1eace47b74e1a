//! The arguments of `chaplygin simulate` (INTERFACE.md section 3), and the
//! choices they name: formulation, integrator, controller.

use clap::ValueEnum;
use std::path::PathBuf;

/// The arguments of `chaplygin simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    /// A built-in model's name, or the path of a `.model` file.
    pub model: String,
    /// The equations integrated.
    #[arg(long, value_enum, default_value_t = Formulation::Reduced)]
    pub formulation: Formulation,
    /// The integrator.
    #[arg(long, value_enum, default_value_t = Integrator::Midpoint)]
    pub integrator: Integrator,
    /// The controller closing the inputs: `none` applies the constant
    /// `--input` values (zero by default); `energy` is the energy-based
    /// snakeboard controller of Duindam & Stramigioli (reduced form only).
    #[arg(long, value_enum, default_value_t = Controller::None)]
    pub controller: Controller,
    /// The final time.
    #[arg(long, default_value_t = 30.0)]
    pub t_end: f64,
    /// The step (for dopri5, the interval between recorded states).
    #[arg(long, default_value_t = 0.01)]
    pub dt: f64,
    /// The directory for `trajectory.csv` and the plots.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// A model or controller parameter, `NAME=VALUE` (repeatable).
    #[arg(long = "param", value_parser = assignment)]
    pub params: Vec<(String, f64)>,
    /// An initial coordinate `q=VALUE`, velocity `dot(q)=VALUE` or
    /// controller state (repeatable). Velocities not given are zero when any
    /// is given; otherwise the model's default motion is used.
    #[arg(long = "initial", value_parser = assignment)]
    pub initial: Vec<(String, f64)>,
    /// A constant input `NAME=VALUE` with `--controller none` (repeatable).
    #[arg(long = "input", value_parser = assignment)]
    pub inputs: Vec<(String, f64)>,
}

/// Which equations are integrated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Formulation {
    /// The reduced port-Hamiltonian form in `(q, alpha)`.
    Reduced,
    /// The Lagrange-d'Alembert equations in `(q, qdot)`.
    Lagrange,
    /// The momentum equation and reconstruction in `(q, rdot, p)` (models
    /// with a symmetry).
    Momentum,
}

/// Which integrator runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Integrator {
    /// Classical Runge-Kutta, order 4.
    Rk4,
    /// Dormand-Prince 5(4), adaptive.
    Dopri5,
    /// The implicit midpoint rule, order 2, energy-preserving for quadratic energies.
    Midpoint,
    /// Gonzalez's discrete gradient, order 2, energy-preserving (reduced form only).
    DiscreteGradient,
}

/// Which controller closes the inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Controller {
    /// Constant inputs (`--input`, zero by default).
    None,
    /// The energy-based snakeboard controller (MATH.md 3.2).
    Energy,
}

/// `NAME=VALUE` with a finite number.
pub(crate) fn assignment(text: &str) -> Result<(String, f64), String> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=VALUE, found `{text}`"))?;
    let number: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("`{value}` is not a number"))?;
    if !number.is_finite() {
        return Err(format!("`{value}` is not finite"));
    }
    Ok((name.trim().to_string(), number))
}
