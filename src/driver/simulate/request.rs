//! What a simulation is asked for ([`Request`]: the command line's
//! `chaplygin simulate` options, docs/INTERFACE.md section 3), and the
//! choices it names: formulation, integrator, controller.

#[cfg(feature = "cli")]
use clap::ValueEnum;

/// A simulation's formulation, integrator, controller, span, stop
/// condition, parameters, initial values and input laws.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct Request {
    /// The equations integrated.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = FormulationChoice::Reduced))]
    pub formulation: FormulationChoice,
    /// The integrator [default: discrete-gradient for the reduced form, which
    /// keeps the energy of any conservative model; midpoint otherwise].
    #[cfg_attr(feature = "cli", arg(long, value_enum))]
    pub integrator: Option<Integrator>,
    /// The controller closing the inputs: `none` applies the `--input`
    /// laws (zero by default); `energy` is the energy-based controller of
    /// Duindam & Stramigioli (reduced form only), for a model with a
    /// steering angle `phi` and two inputs, the torso's and the wheels'.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = Controller::None))]
    pub controller: Controller,
    /// The final time.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = Request::T_END))]
    pub t_end: f64,
    /// The largest step and the interval between recorded states (with
    /// `--fixed-step`, the step).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = Request::DT))]
    pub dt: f64,
    /// The relative tolerance of each step's local error: every
    /// integrator's step follows it and `--atol`. It also judges the run:
    /// an energy drift of a conservative run, or a constraint residual,
    /// beyond what the tolerance allows is warned about.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = Request::RTOL))]
    pub rtol: f64,
    /// The absolute tolerance of each step's local error.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = Request::ATOL))]
    pub atol: f64,
    /// Steps of exactly `--dt`, not following the tolerance (rk4, midpoint,
    /// discrete-gradient).
    #[cfg_attr(feature = "cli", arg(long))]
    pub fixed_step: bool,
    /// End the run where a condition first holds: one comparison
    /// `EXPR < EXPR` or `EXPR > EXPR` of `t`, the coordinates, velocities
    /// `dot(q)`, inputs and parameters (`'abs(phi) > 1'`). The crossing is
    /// located within its step to 1e-9 in t; the trajectory's last row is
    /// there and the summary ends with `stopped at t = T: COND`.
    #[cfg_attr(feature = "cli", arg(long, value_name = "COND"))]
    pub stop_when: Option<String>,
    /// A model or controller parameter, `NAME=VALUE` (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "param", value_parser = assignment))]
    pub params: Vec<(String, f64)>,
    /// An initial coordinate `q=VALUE`, velocity `dot(q)=VALUE` or
    /// controller state (repeatable); VALUE is a number or an expression of
    /// the model's parameters (`dot(theta_r)=-5/rR`). When a velocity is
    /// given, those not given are solved from the constraints (an error
    /// names any left free); otherwise the model's default motion is used.
    #[cfg_attr(feature = "cli", arg(long = "initial", value_parser = expression_assignment))]
    pub initial: Vec<(String, String)>,
    /// An input `NAME=EXPRESSION` with `--controller none` (repeatable): a
    /// constant (`u1=0.1`) or an expression in the model language of the
    /// time `t`, the model's parameters (`u1=0.3*sin(2*t)`) and the state,
    /// coordinates and velocities `dot(q)`, for a feedback law
    /// (`steer_torque=-10*phi-2*dot(phi)`); functions sin cos tan sqrt exp
    /// ln abs.
    #[cfg_attr(feature = "cli", arg(long = "input", value_parser = expression_assignment))]
    pub inputs: Vec<(String, String)>,
    /// A coordinate that follows an expression of the time `t` and the
    /// model's parameters exactly, `NAME=EXPRESSION` (repeatable): a
    /// rheonomic constraint (a steering angle, a joint driven by a servo)
    /// whose force is recorded as `force(NAME)`; it starts on its law.
    #[cfg_attr(feature = "cli", arg(long = "prescribe", value_parser = expression_assignment))]
    pub prescribe: Vec<(String, String)>,
}

impl Request {
    /// The final time unless given.
    pub const T_END: f64 = 30.0;
    /// The largest step unless given.
    pub const DT: f64 = 0.01;
    /// The relative tolerance unless given.
    pub const RTOL: f64 = 1e-8;
    /// The absolute tolerance unless given.
    pub const ATOL: f64 = 1e-8;
}

impl Default for Request {
    /// The reduced form from the model's default state, with the default
    /// integrator, to [`Request::T_END`] by steps of [`Request::DT`], the
    /// inputs zero.
    fn default() -> Self {
        Self {
            formulation: FormulationChoice::Reduced,
            integrator: None,
            controller: Controller::None,
            t_end: Self::T_END,
            dt: Self::DT,
            rtol: Self::RTOL,
            atol: Self::ATOL,
            fixed_step: false,
            stop_when: None,
            params: Vec::new(),
            initial: Vec::new(),
            inputs: Vec::new(),
            prescribe: Vec::new(),
        }
    }
}

/// Which equations are integrated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(ValueEnum))]
pub enum FormulationChoice {
    /// The reduced port-Hamiltonian form in `(q, alpha)`.
    Reduced,
    /// The Lagrange-d'Alembert equations in `(q, qdot)`.
    Lagrange,
    /// The momentum equation and reconstruction in `(q, rdot, p)` (models
    /// with a symmetry).
    Momentum,
}

/// Which integrator runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(ValueEnum))]
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
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(ValueEnum))]
pub enum Controller {
    /// The `--input` laws (zero by default).
    None,
    /// The energy-based controller of the snakeboard (MATH.md 3.2), for
    /// any model with what it uses.
    Energy,
}

impl Integrator {
    /// Every integrator.
    pub const ALL: [Self; 4] = [
        Self::Rk4,
        Self::Dopri5,
        Self::Midpoint,
        Self::DiscreteGradient,
    ];

    /// The one chosen, or the default for a formulation that is or is not
    /// structured (`xdot = J dH/dx + F`): the discrete gradient, which keeps
    /// the energy of any conservative model to round-off, or the implicit
    /// midpoint rule.
    pub fn chosen_or_default(chosen: Option<Self>, structured: bool) -> Self {
        match chosen {
            Some(integrator) => integrator,
            None if structured => Self::DiscreteGradient,
            None => Self::Midpoint,
        }
    }

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Rk4 => "rk4",
            Self::Dopri5 => "dopri5",
            Self::Midpoint => "midpoint",
            Self::DiscreteGradient => "discrete-gradient",
        }
    }
}

/// `NAME=EXPRESSION`, the expression read later against the model.
pub fn expression_assignment(text: &str) -> Result<(String, String), String> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=EXPRESSION, found `{text}`"))?;
    Ok((name.trim().to_string(), value.trim().to_string()))
}

/// `NAME=VALUE` with a finite number.
pub fn assignment(text: &str) -> Result<(String, f64), String> {
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
