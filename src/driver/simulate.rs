//! A simulation of a model read from its text: its request ([`Request`])
//! resolved once into a [`Setup`] (`crate::driver::setup`: the parameters,
//! the initial state, the input laws, the stop condition), a formulation
//! closed by a controller (the input laws of the time and the state, read
//! in every formulation at its configuration and velocity: `(q, qdot)`,
//! `(q, velocities(q, alpha))` in the active chart, or
//! `(q, reconstructed_velocity(q, rdot, p))`, and the forces that keep
//! the coordinates `--prescribe` names on their laws, `prescribe`), an
//! integrator and a stop condition; the run records every row and reports
//! the energy drift (or, driven, the power balance), the largest
//! constraint residual, and where and why it stopped ([`Finished`]). A
//! model with configuration constraints is kept on `f(q) = 0` after every
//! step, in every formulation. A model with what the paper's energy-based
//! controller uses also runs under it (`energy`).

mod energy;
mod prescribe;
mod request;
mod run;
mod trust;

pub use request::{
    Controller, FormulationChoice, Integrator, Request, assignment, expression_assignment,
};
pub use run::{Report, Tolerance};
pub use trust::{ALLOWANCE, Warning};

use super::catalog::BuiltIn;
use super::engine::{self, Loaded};
use super::formulation::Formulation;
use super::interpreted::{InputLaw, InterpretedDalembert, InterpretedMomentum, InterpretedReduced};
use super::setup::{self, Asked, Controls, InputError, InputSchedule, Origin, Setup, Start};
use crate::driver::Failure;
use crate::runtime::record::{Recorder, Table};
use chaplygin_codegen::interpret::InterpretedModel;
use prescribe::{Forces, Prescribed};
use run::Settings;
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
    /// The stop condition.
    stop: Option<setup::Comparison>,
    /// The built-in it is, for its default configuration and motion.
    built_in: Option<&'static BuiltIn>,
    /// Whether a coordinate is prescribed: the run then reports its power
    /// balance, its forces doing work.
    prescribed: bool,
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
        Prescribed::of(&loaded.model, request)?;
        energy::check(&loaded.model, &loaded.label, request)?;
        let setup = setup::resolve(
            loaded.model,
            &request.asked(energy::ORIGIN, energy::CONTROLS),
        )?;
        return energy::run(&setup, request, also, progress);
    }
    let prepared = prepare(loaded, request)?;
    let settings = Settings::new(request, &*prepared.formulation, prepared.stop.as_ref())?;
    let mut table = Table::new();
    let outcome = settings
        .run(
            &*prepared.formulation,
            &prepared.x0,
            &mut run::Both(&mut table, also),
            progress,
        )
        .map(|report| report.driven(prepared.prescribed));
    let tracks = prepared.tracks(&table)?;
    Ok(Finished {
        table,
        tracks,
        parameters: prepared.parameters,
        outcome,
    })
}

/// The formulation `request` chooses of the `loaded` model, closed by its
/// input laws, from its initial state: a built-in's default configuration
/// and motion, or a file's rest at `q = 0`, unless `request.initial` says
/// otherwise.
///
/// # Errors
/// Bad input, or a formulation the model does not derive.
pub fn prepare(loaded: Loaded, request: &Request) -> Result<Prepared, Failure> {
    if request.controller == Controller::Energy {
        return Err(InputError::Unsupported(format!(
            "`{}`: the energy controller's closed loop runs with `simulate` only",
            loaded.label
        ))
        .into());
    }
    let Loaded {
        model,
        label,
        built_in,
        ..
    } = loaded;
    let prescribed = Prescribed::of(&model, request)?;
    let initial = prescribed_start(&model, request, &prescribed)?;
    let asked = Asked {
        state: &initial,
        ..request.asked(origin(built_in), Controls::default())
    };
    let setup = setup::resolve(model, &asked)?;
    let start = setup
        .start
        .clone()
        .expect("a simulation asks for its start");
    let (model, forces) = forced(&setup, &prescribed, &label, &start)?;
    let Setup {
        parameters,
        inputs: schedule,
        stop,
        ..
    } = setup;
    let fixed_inputs: Rc<RefCell<Option<Vec<f64>>>> = Rc::default();
    let (formulation, x0) = closed(
        model.clone(),
        request.formulation,
        input_law(schedule, forces, Rc::clone(&fixed_inputs)),
        &start,
        &label,
    )?;
    Ok(Prepared {
        formulation,
        x0,
        parameters,
        fixed_inputs,
        stop,
        model,
        built_in,
        prescribed: !prescribed.is_empty(),
    })
}

/// The request's `--initial` values, and the prescribed coordinates'
/// starts on their laws at `t = 0` (the laws read at the parameters
/// `--param` sets).
fn prescribed_start(
    model: &InterpretedModel,
    request: &Request,
    prescribed: &Prescribed,
) -> Result<Vec<(String, String)>, Failure> {
    let mut initial = request.initial.clone();
    if !prescribed.is_empty() {
        let asked = Asked {
            params: &request.params,
            ..Asked::default()
        };
        let setup = setup::resolve(model.clone(), &asked)?;
        initial.extend(prescribed.starts(&setup.model, &setup.bound())?);
    }
    Ok(initial)
}

/// The model the formulation runs, and the forces that keep the
/// prescribed coordinates on their laws: `setup`'s model, derived again
/// with a force along each (checked to move it at the `start`), where
/// any is prescribed.
fn forced(
    setup: &Setup,
    prescribed: &Prescribed,
    label: &str,
    start: &Start,
) -> Result<(InterpretedModel, Option<Forces>), Failure> {
    if prescribed.is_empty() {
        return Ok((setup.model.clone(), None));
    }
    let model = engine::with_coordinate_forces(&setup.model, &prescribed.indices, label)?;
    let declared = setup.model.sizes().p;
    let forces = prescribed.forces(model.clone(), declared, &setup.bound())?;
    forces.check_at(&start.q, &start.qdot)?;
    Ok((model, Some(forces)))
}

/// Where a run of a built-in starts: its default configuration and
/// motion; a model from a file's at rest at `q = 0`.
fn origin(built_in: Option<&'static BuiltIn>) -> Origin<'static> {
    built_in.map_or_else(Origin::default, |built_in| Origin {
        q: Some(built_in.q),
        motion: Some(built_in.motion),
    })
}

/// The input law of `schedule` and the prescribed coordinates' `forces`,
/// or the inputs `fixed` holds while it holds some.
fn input_law(
    schedule: InputSchedule,
    forces: Option<Forces>,
    fixed: Rc<RefCell<Option<Vec<f64>>>>,
) -> InputLaw {
    InputLaw {
        reads_state: schedule.reads_state() || forces.is_some(),
        law: Box::new(move |t, q, qdot, u| match fixed.borrow().as_deref() {
            Some(given) => u.copy_from_slice(given),
            None => {
                schedule.at(t, q, qdot, u);
                if let Some(forces) = &forces {
                    forces.apply(t, q, qdot, u);
                }
            }
        }),
    }
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
            let momentum = InterpretedMomentum::new(model, inputs).map_err(|reason| {
                InputError::Unsupported(format!(
                    "`{label}`: {reason}: use --formulation reduced or lagrange"
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
        let asked = Asked {
            state_flag: "--initial",
            state: given,
            start: Some(origin(self.built_in)),
            ..Asked::default()
        };
        let setup = setup::resolve(self.model.clone(), &asked)?;
        let start = setup.start.expect("asked for its start");
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

impl Request {
    /// The request's assignments, for [`setup::resolve`], a run from
    /// `origin` unless they say otherwise, with the `controls` of its
    /// controller.
    fn asked<'a>(&'a self, origin: Origin<'a>, controls: Controls<'a>) -> Asked<'a> {
        Asked {
            params: &self.params,
            state_flag: "--initial",
            state: &self.initial,
            inputs: &self.inputs,
            stop_when: self.stop_when.as_deref(),
            start: Some(origin),
            controls,
            ..Asked::default()
        }
    }
}
