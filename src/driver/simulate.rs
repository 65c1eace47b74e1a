//! A simulation of a model read from its text: its parameters and initial
//! state, a formulation closed by a controller (the input laws of the time
//! and the state, read in every formulation at its configuration and
//! velocity: `(q, qdot)`, `(q, velocities(q, alpha))` in the active chart,
//! or `(q, reconstructed_velocity(q, rdot, p))`), an integrator and a stop
//! condition ([`Request`]); the run records every row and reports the
//! energy drift, the largest constraint residual, and where and why it
//! stopped ([`Finished`]). A model with configuration constraints is kept
//! on `f(q) = 0` after every step, in every formulation. The built-in
//! snakeboard also runs under the paper's energy-based controller
//! (`crate::energy_control`), through the runtime's own interconnection of
//! the model at its fixed sizes (`chaplygin_codegen::interpret::Fixed`).

mod error;
mod inputs;
mod request;
mod run;
mod start;
mod stop;
mod trust;

pub use error::InputError;
pub use inputs::InputLawError;
pub use request::{
    Controller, FormulationChoice, Integrator, Request, assignment, expression_assignment,
};
pub use run::{Report, Tolerance};
pub use start::{set_parameters, with_parameters};
pub use stop::StopError;
pub use trust::{ALLOWANCE, Warning};

use super::catalog::{BuiltIn, Motion};
use super::engine::Loaded;
use super::expression::Scope;
use super::formulation::{Formulation, Typed};
use super::interpreted::{
    InputLaw, InterpretedDalembert, InterpretedMomentum, InterpretedReduced, evaluated,
};
use crate::driver::Failure;
use crate::energy_control::{ClosedLoop, EnergyController, closed_loop_state};
use crate::runtime::arrays::leading;
use crate::runtime::nalgebra::DMatrix;
use crate::runtime::record::{Recorder, Table};
use crate::runtime::system::Momenta;
use chaplygin_codegen::derive::MOMENTUM_WITH_HOLONOMIC;
use chaplygin_codegen::interpret::{Fixed, InterpretedModel};
use inputs::InputSchedule;
use run::Settings;
use start::{Kinematics, Start, initial_state, initial_values, with_default_motion};
use std::cell::RefCell;
use std::rc::Rc;

/// A formulation of a model closed by its inputs, and its initial state.
pub struct Prepared {
    /// The closed system.
    pub formulation: Box<dyn Formulation>,
    /// The initial state, in the formulation's chart.
    pub x0: Vec<f64>,
    /// The parameters' names and values.
    pub parameters: Vec<(String, f64)>,
    /// Inputs that replace the input laws while set ([`Prepared::with_inputs`]).
    fixed_inputs: Rc<RefCell<Option<Vec<f64>>>>,
    /// The model, for its points' positions and initial states.
    model: InterpretedModel,
    /// The built-in it is, for its default configuration and motion.
    built_in: Option<&'static BuiltIn>,
}

/// What a run recorded and how it ended.
pub struct Finished {
    /// Every recorded row: `t`, then the state.
    pub table: Table,
    /// With declared points, their positions in ground axes at every
    /// recorded row: `t`, then `P.x`, `P.y`, `P.z` for each point `P`.
    pub tracks: Option<Table>,
    /// The parameters' names and values (the controller's gains among
    /// them).
    pub parameters: Vec<(String, f64)>,
    /// The run's report, or why it failed (the rows before the failure
    /// stay recorded).
    pub outcome: Result<Report, Failure>,
}

/// Runs `request` on the `loaded` model, recording every row into the
/// returned table and into `also`, calling `progress` with the fraction of
/// the span done.
///
/// # Errors
/// Bad input (an unknown name, an expression that does not read, a
/// combination that does not run); a failed run is [`Finished::outcome`].
pub fn simulate(
    loaded: Loaded,
    request: &Request,
    also: &mut dyn Recorder,
    progress: &mut dyn FnMut(f64),
) -> Result<Finished, Failure> {
    if request.controller == Controller::Energy {
        return match loaded.built_in {
            Some(built_in) if built_in.name == "snakeboard" => {
                energy_controlled(loaded.model, built_in, request, also, progress)
            }
            _ => Err(no_controller(&loaded.label).into()),
        };
    }
    let prepared = prepare(loaded, request)?;
    let settings = Settings::new(request, &*prepared.formulation, &prepared.scope_names())?;
    let mut table = Table::new();
    let outcome = settings.run(
        &*prepared.formulation,
        &prepared.x0,
        &mut run::Both(&mut table, also),
        progress,
    );
    let tracks = prepared.tracks(&table)?;
    Ok(Finished {
        table,
        tracks,
        parameters: prepared.parameters,
        outcome,
    })
}

/// The formulation `request` chooses of the `loaded` model, closed by its
/// `inputs` laws, from its initial state: a built-in's default
/// configuration and motion, or a file's rest at `q = 0`, unless
/// `request.initial` says otherwise.
///
/// # Errors
/// Bad input, or a formulation the model does not derive.
pub fn prepare(loaded: Loaded, request: &Request) -> Result<Prepared, Failure> {
    if request.controller == Controller::Energy {
        return Err(no_controller(&loaded.label).into());
    }
    let Loaded {
        mut model,
        label,
        built_in,
        ..
    } = loaded;
    let values = with_parameters(&mut model, &request.params)?;
    let names = model.names().clone();
    let parameters = borrowed(&values);
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let start = start_of(&model, built_in, &request.initial, &parameters, &mut [])?;
    let input_names: Vec<&str> = names.inputs.iter().map(String::as_str).collect();
    let schedule = InputSchedule::new(&input_names, &request.inputs, &parameters, &coordinates)?;
    let fixed_inputs: Rc<RefCell<Option<Vec<f64>>>> = Rc::default();
    let fixed = Rc::clone(&fixed_inputs);
    let inputs = InputLaw {
        reads_state: schedule.reads_state(),
        law: Box::new(move |t, q, qdot, u| match fixed.borrow().as_deref() {
            Some(given) => u.copy_from_slice(given),
            None => schedule.at(t, q, qdot, u),
        }),
    };
    let (formulation, x0) = closed(model.clone(), request.formulation, inputs, &start, &label)?;
    Ok(Prepared {
        formulation,
        x0,
        parameters: values,
        fixed_inputs,
        model,
        built_in,
    })
}

/// `(name, value)` pairs borrowing their names.
pub(crate) fn borrowed(pairs: &[(String, f64)]) -> Vec<(&str, f64)> {
    pairs
        .iter()
        .map(|(name, value)| (name.as_str(), *value))
        .collect()
}

/// `(name, value)` pairs owning their names.
fn owned(pairs: &[(&str, f64)]) -> Vec<(String, f64)> {
    pairs
        .iter()
        .map(|&(name, value)| (name.to_string(), value))
        .collect()
}

/// A closed formulation and its initial state.
type ClosedFrom = (Box<dyn Formulation>, Vec<f64>);

/// The formulation `choice` of `model` closed by `inputs`, and the state
/// of `start` in it.
fn closed(
    model: InterpretedModel,
    choice: FormulationChoice,
    inputs: InputLaw,
    start: &Start,
    label: &str,
) -> Result<ClosedFrom, Failure> {
    Ok(match choice {
        FormulationChoice::Reduced => {
            let reduced = InterpretedReduced::new(model, inputs);
            let x0 = reduced.initial_state(&start.q, &start.qdot)?;
            (Box::new(reduced), x0)
        }
        FormulationChoice::Lagrange => {
            let x0 = start.q.iter().chain(&start.qdot).copied().collect();
            (Box::new(InterpretedDalembert { model, inputs }), x0)
        }
        FormulationChoice::Momentum => {
            if model.shape().is_some() && model.arguments("momentum_rhs").is_none() {
                return Err(InputError::Unsupported(format!(
                    "`{label}`: the momentum formulation is {MOMENTUM_WITH_HOLONOMIC}: use --formulation reduced or lagrange"
                ))
                .into());
            }
            let momentum = InterpretedMomentum::new(model, inputs).ok_or_else(|| {
                InputError::Unsupported(format!(
                    "`{label}` declares no symmetry: the momentum formulation needs one"
                ))
            })?;
            let x0 = momentum.initial_state(&start.q, &start.qdot)?;
            (Box::new(momentum), x0)
        }
    })
}

impl Prepared {
    /// The state of the formulation from the model's defaults and the
    /// `given` initial values (as [`Request::initial`] takes them); a
    /// formulation with charts makes the one that fits best active.
    ///
    /// # Errors
    /// An unknown name, a value that does not read, velocities the
    /// constraints do not determine, or a velocity the formulation cannot
    /// represent.
    pub fn initial_state(&self, given: &[(String, String)]) -> Result<Vec<f64>, Failure> {
        let start = start_of(
            &self.model,
            self.built_in,
            given,
            &borrowed(&self.parameters),
            &mut [],
        )?;
        self.formulation.state_of(&start.q, &start.qdot)
    }

    /// `read` with the inputs `u` in place of the input laws (`None`: the
    /// laws).
    pub fn with_inputs<T>(&self, u: Option<&[f64]>, read: impl FnOnce(&dyn Formulation) -> T) -> T {
        *self.fixed_inputs.borrow_mut() = u.map(<[f64]>::to_vec);
        let value = read(&*self.formulation);
        *self.fixed_inputs.borrow_mut() = None;
        value
    }

    /// The model's number of inputs.
    pub fn input_count(&self) -> usize {
        self.model.sizes().p
    }

    /// The names a stop condition may read: the parameters, the
    /// coordinates and the inputs.
    fn scope_names(&self) -> ScopeNames {
        let names = self.model.names();
        ScopeNames {
            parameters: self.parameters.clone(),
            coordinates: names.coordinates.clone(),
            inputs: names.inputs.clone(),
        }
    }

    /// The declared points' positions at every row of `table`, `None`
    /// without points.
    fn tracks(&self, table: &Table) -> Result<Option<Table>, Failure> {
        let names = &self.model.names().points;
        if names.is_empty() {
            return Ok(None);
        }
        let mut tracks = Table::new();
        let mut columns = vec!["t".to_string()];
        for name in names {
            columns.extend(["x", "y", "z"].map(|axis| format!("{name}.{axis}")));
        }
        tracks.start(&columns)?;
        let n = self.model.sizes().n;
        for row in &table.rows {
            let mut tracked = vec![row[0]];
            tracked.extend(self.model.call("positions", &[&row[1..=n]])?);
            tracks.record(&tracked)?;
        }
        Ok(Some(tracks))
    }
}

/// The names of a run's scope, owned: the parameters with their values,
/// the coordinates, the inputs.
pub(crate) struct ScopeNames {
    parameters: Vec<(String, f64)>,
    coordinates: Vec<String>,
    inputs: Vec<String>,
}

impl ScopeNames {
    /// `read` with the names as a [`Scope`].
    fn with_scope<T>(&self, read: impl FnOnce(&Scope<'_>) -> T) -> T {
        let parameters: Vec<(&str, f64)> = self
            .parameters
            .iter()
            .map(|(name, value)| (name.as_str(), *value))
            .collect();
        let coordinates: Vec<&str> = self.coordinates.iter().map(String::as_str).collect();
        let inputs: Vec<&str> = self.inputs.iter().map(String::as_str).collect();
        read(&Scope {
            parameters: &parameters,
            coordinates: &coordinates,
            inputs: &inputs,
        })
    }
}

fn no_controller(model: &str) -> InputError {
    InputError::Unsupported(format!(
        "the energy controller is the built-in snakeboard's; `{model}` takes `--controller none`"
    ))
}

/// The initial state of `model` from a built-in's default configuration
/// and motion, or a file's rest at `q = 0`, and the `given` `--initial`
/// assignments, expressions of the `parameters`; the `controller_states`
/// take their `--initial` values too.
fn start_of(
    model: &InterpretedModel,
    built_in: Option<&BuiltIn>,
    given: &[(String, String)],
    parameters: &[(&str, f64)],
    controller_states: &mut [(&str, &mut f64)],
) -> Result<Start, InputError> {
    let names = model.names();
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let constraints: Vec<&str> = names.constraints.iter().map(String::as_str).collect();
    let n = coordinates.len();
    let (alpha, given) = match built_in.map(|built_in| built_in.motion) {
        Some(Motion::Momenta(alpha)) => (alpha, given.to_vec()),
        Some(Motion::Velocities(defaults)) => (&[][..], with_default_motion(given, defaults)),
        None => (&[][..], given.to_vec()),
    };
    let initial = initial_values(&given, parameters)?;
    initial_state(
        &Kinematics {
            coordinates: &coordinates,
            constraints: &constraints,
            default_q: &built_in.map_or_else(|| vec![0.0; n], |built_in| built_in.q.to_vec()),
            default_motion: &|q| match alpha.is_empty() {
                true => vec![0.0; n],
                false => evaluated(model.velocities(q, alpha)),
            },
            constraint_matrix: &|q| {
                let a = evaluated(model.constraint_matrix(q));
                DMatrix::from_row_slice(constraints.len(), n, &a)
            },
            holonomic: Some(model),
        },
        &initial,
        controller_states,
    )
}

/// The snakeboard under the energy-based controller (MATH.md 3.2), from
/// rest at `q = 0` with energy in the springs (`xt = 1`, `xw = 0.5`) unless
/// `request.initial` says otherwise; gains `a = 1`, `kt = 2`, `kw = 1`
/// unless `request.params` says otherwise. The closed loop is the
/// runtime's interconnection of the model at its sizes: 5 coordinates, 2
/// constraint rows, 2 inputs, no configuration constraints, 2 shape
/// coordinates and 1 momentum.
fn energy_controlled(
    mut model: InterpretedModel,
    built_in: &BuiltIn,
    request: &Request,
    also: &mut dyn Recorder,
    progress: &mut dyn FnMut(f64),
) -> Result<Finished, Failure> {
    if request.formulation != FormulationChoice::Reduced {
        return Err(InputError::Unsupported(
            "the energy controller closes the reduced port-Hamiltonian form: use --formulation reduced".into(),
        )
        .into());
    }
    if let Some((name, _)) = request.inputs.first() {
        return Err(InputError::Unsupported(format!(
            "--input {name}: the energy controller sets the inputs"
        ))
        .into());
    }
    let mut controller = EnergyController {
        a: 1.0,
        kt: 2.0,
        kw: 1.0,
    };
    let names = model.names().clone();
    let known: Vec<&str> = names
        .parameters
        .iter()
        .map(String::as_str)
        .chain(["a", "kt", "kw"])
        .collect();
    set_parameters(&known, &request.params, &mut |name, value| {
        let gain = match name {
            "a" => &mut controller.a,
            "kt" => &mut controller.kt,
            "kw" => &mut controller.kw,
            _ => return model.set_parameter(name, value).is_ok(),
        };
        *gain = value;
        true
    })?;
    let mut parameters: Vec<(&str, f64)> = known
        .iter()
        .copied()
        .zip(model.parameter_values().iter().copied())
        .collect();
    parameters.extend([
        ("a", controller.a),
        ("kt", controller.kt),
        ("kw", controller.kw),
    ]);
    let (mut xt, mut xw) = (1.0, 0.5);
    let at_rest = BuiltIn {
        q: &[0.0; 5],
        motion: Motion::Momenta(&[0.0; 3]),
        ..*built_in
    };
    let start = start_of(
        &model,
        Some(&at_rest),
        &request.initial,
        &parameters,
        &mut [("xt", &mut xt), ("xw", &mut xw)],
    )?;
    let board = Fixed::<5, 2, 2, 0, 2, 1>::new(&model)?;
    let alpha: [f64; 3] = board.momenta(&leading(&start.q), &leading(&start.qdot));
    let x = leading(&start.q.iter().chain(&alpha).copied().collect::<Vec<f64>>());
    let x0 = closed_loop_state(&x, xt, xw);
    let scope = ScopeNames {
        parameters: owned(&parameters),
        coordinates: names.coordinates.clone(),
        inputs: names.inputs.clone(),
    };
    let closed_loop =
        Typed::<_, 10>::structured(ClosedLoop::new(board, controller), model.engine().name());
    let settings = Settings::new(request, &closed_loop, &scope)?;
    let mut table = Table::new();
    let outcome = settings.run(
        &closed_loop,
        &x0,
        &mut run::Both(&mut table, also),
        progress,
    );
    Ok(Finished {
        table,
        tracks: None,
        parameters: scope.parameters,
        outcome,
    })
}
