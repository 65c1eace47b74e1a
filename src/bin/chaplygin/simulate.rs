//! `chaplygin simulate`: a model (a built-in or a `.model` file, read from
//! its text and run on the engine `--engine` chooses), its parameters and initial state from the command line, a
//! formulation closed by a controller (the `--input` laws of the time and
//! the state, read in every formulation at its configuration and velocity:
//! `(q, qdot)`, `(q, velocities(q, alpha))` in the active chart, or
//! `(q, reconstructed_velocity(q, rdot, p))`), an integrator and a
//! `--stop-when` condition; the run writes `trajectory.csv` (INTERFACE.md
//! section 3) and the plots, and prints the energy drift and the largest
//! constraint residual, and where and why it stopped. A model with
//! configuration constraints is kept on `f(q) = 0` after every step, in
//! every formulation. The built-in snakeboard also runs under the paper's
//! energy-based controller (`chaplygin::energy_control`), through the
//! runtime's own interconnection of the model at its fixed sizes
//! (`chaplygin_codegen::interpret::Fixed`).

mod arguments;
mod inputs;
mod output;
mod start;
mod stop;

pub use arguments::SimulateArgs;
pub(crate) use arguments::assignment;
use chaplygin::runtime::arrays::leading;
use inputs::{InputSchedule, Scope};
pub(crate) use start::set_parameters;

use crate::catalog::{self, BuiltIn, Motion, Source};
use crate::engine;
use crate::formulation::Typed;
use crate::interpreted::dynamics::InterpretedDynamics;
use crate::interpreted::{
    InputLaw, InterpretedDalembert, InterpretedMomentum, InterpretedReduced, evaluated,
};
use arguments::{Controller, FormulationChoice};
use chaplygin::energy_control::{ClosedLoop, EnergyController, closed_loop_state};
use chaplygin::plot;
use chaplygin::runtime::nalgebra::DMatrix;
use chaplygin::runtime::system::Momenta;
use chaplygin_codegen::derive::MOMENTUM_WITH_HOLONOMIC;
use chaplygin_codegen::interpret::{Fixed, InterpretedModel};
use output::{Points, execute};
use start::{InputError, Kinematics, Start, initial_state, initial_values, with_default_motion};
use std::error::Error;

/// Runs `chaplygin simulate`.
///
/// # Errors
/// Bad input, a failed simulation, or an I/O error.
pub fn run(args: &SimulateArgs) -> Result<(), Box<dyn Error>> {
    match catalog::lookup(&args.model)? {
        Source::File { path, text } => from_text(&path, &text, None, args),
        Source::BuiltIn(built_in) if args.controller == Controller::Energy => {
            match built_in.name == "snakeboard" {
                true => energy_controlled(built_in, args),
                false => Err(no_controller(built_in.name).into()),
            }
        }
        Source::BuiltIn(built_in) => {
            from_text(built_in.name, built_in.source, Some(built_in), args)
        }
    }
}

/// A model from its text (a `.model` file, or a built-in run from its
/// text) on the engine of `--engine`, from a built-in's default
/// configuration and motion, or a file's rest at `q = 0`, unless `--initial`
/// says otherwise.
fn from_text(
    path: &str,
    text: &str,
    built_in: Option<&BuiltIn>,
    args: &SimulateArgs,
) -> Result<(), Box<dyn Error>> {
    if args.controller == Controller::Energy {
        return Err(no_controller(path).into());
    }
    let mut model = engine::load(path, text, args.engine)?;
    let names = model.names().clone();
    let known: Vec<&str> = names.parameters.iter().map(String::as_str).collect();
    set_parameters(&known, &args.params, &mut |name, value| {
        model.set_parameter(name, value).is_ok()
    })?;
    let parameters: Vec<(&str, f64)> = known
        .iter()
        .copied()
        .zip(model.parameter_values().iter().copied())
        .collect();
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let (model, start) = start_of(model, built_in, &args.initial, &parameters, &mut [])?;
    let input_names: Vec<&str> = names.inputs.iter().map(String::as_str).collect();
    let scope = Scope {
        parameters: &parameters,
        coordinates: &coordinates,
        inputs: &input_names,
    };
    let schedule = InputSchedule::new(&input_names, &args.inputs, &parameters, &coordinates)?;
    let inputs = InputLaw {
        reads_state: schedule.reads_state(),
        law: Box::new(move |t, q, qdot, u| schedule.at(t, q, qdot, u)),
    };
    match args.formulation {
        FormulationChoice::Reduced => {
            let reduced = InterpretedReduced::new(model, inputs);
            let x0 = reduced.initial_state(&start.q, &start.qdot)?;
            let points = interpreted_points(&reduced.model);
            execute(&reduced, &x0, (args, &scope), (None, points))
        }
        FormulationChoice::Lagrange => {
            let x0: Vec<f64> = start.q.iter().chain(&start.qdot).copied().collect();
            let dalembert = InterpretedDalembert { model, inputs };
            let points = interpreted_points(&dalembert.model);
            execute(&dalembert, &x0, (args, &scope), (None, points))
        }
        FormulationChoice::Momentum => {
            if model.shape().is_some() && model.arguments("momentum_rhs").is_none() {
                return Err(InputError::Unsupported(format!(
                    "`{path}`: the momentum formulation is {MOMENTUM_WITH_HOLONOMIC}: use --formulation reduced or lagrange"
                ))
                .into());
            }
            let momentum = InterpretedMomentum::new(model, inputs).ok_or_else(|| {
                InputError::Unsupported(format!(
                    "`{path}` declares no symmetry: the momentum formulation needs one"
                ))
            })?;
            let x0 = momentum.initial_state(&start.q, &start.qdot)?;
            let points = interpreted_points(&momentum.model);
            execute(&momentum, &x0, (args, &scope), (None, points))
        }
    }
}

/// The points an interpreted model declares, `None` without any.
fn interpreted_points(model: &InterpretedModel) -> Option<Points<'_>> {
    let names = &model.names().points;
    (!names.is_empty()).then(|| Points {
        names: names.clone(),
        n: model.sizes().n,
        positions: Box::new(|q| Ok(model.call("positions", &[q])?)),
    })
}

fn no_controller(model: &str) -> InputError {
    InputError::Unsupported(format!(
        "the energy controller is the built-in snakeboard's; `{model}` takes `--controller none`"
    ))
}

/// The initial state of `model` (moved in and out, as the initial state
/// solves its configuration constraints through it) from a built-in's
/// default configuration and motion, or a file's rest at `q = 0`, and the
/// `given` `--initial` assignments, expressions of the `parameters`; the
/// `controller_states` take their `--initial` values too.
fn start_of(
    model: InterpretedModel,
    built_in: Option<&BuiltIn>,
    given: &[(String, String)],
    parameters: &[(&str, f64)],
    controller_states: &mut [(&str, &mut f64)],
) -> Result<(InterpretedModel, Start), InputError> {
    let names = model.names().clone();
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let constraints: Vec<&str> = names.constraints.iter().map(String::as_str).collect();
    let n = coordinates.len();
    let (alpha, given) = match built_in.map(|built_in| built_in.motion) {
        Some(Motion::Momenta(alpha)) => (alpha, given.to_vec()),
        Some(Motion::Velocities(defaults)) => (&[][..], with_default_motion(given, defaults)),
        None => (&[][..], given.to_vec()),
    };
    let initial = initial_values(&given, parameters)?;
    let dynamics = InterpretedDynamics(model);
    let start = initial_state(
        &Kinematics {
            coordinates: &coordinates,
            constraints: &constraints,
            default_q: &built_in.map_or_else(|| vec![0.0; n], |built_in| built_in.q.to_vec()),
            default_motion: &|q| match alpha.is_empty() {
                true => vec![0.0; n],
                false => evaluated(dynamics.0.velocities(q, alpha)),
            },
            constraint_matrix: &|q| {
                let a = evaluated(dynamics.0.constraint_matrix(q));
                DMatrix::from_row_slice(constraints.len(), n, &a)
            },
            holonomic: Some(&dynamics),
        },
        &initial,
        controller_states,
    )?;
    Ok((dynamics.0, start))
}

/// The snakeboard under the energy-based controller (MATH.md 3.2), from
/// rest at `q = 0` with energy in the springs (`xt = 1`, `xw = 0.5`) unless
/// `--initial` says otherwise; gains `a = 1`, `kt = 2`, `kw = 1` unless
/// `--param` says otherwise. The closed loop is the runtime's
/// interconnection of the model at its sizes: 5 coordinates, 2 constraint
/// rows, 2 inputs, no configuration constraints, 2 shape coordinates and 1
/// momentum.
fn energy_controlled(built_in: &BuiltIn, args: &SimulateArgs) -> Result<(), Box<dyn Error>> {
    if args.formulation != FormulationChoice::Reduced {
        return Err(InputError::Unsupported(
            "the energy controller closes the reduced port-Hamiltonian form: use --formulation reduced".into(),
        )
        .into());
    }
    if let Some((name, _)) = args.inputs.first() {
        return Err(InputError::Unsupported(format!(
            "--input {name}: the energy controller sets the inputs"
        ))
        .into());
    }
    let mut model = engine::load(built_in.name, built_in.source, args.engine)?;
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
    set_parameters(&known, &args.params, &mut |name, value| {
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
    let (model, start) = start_of(
        model,
        Some(&at_rest),
        &args.initial,
        &parameters,
        &mut [("xt", &mut xt), ("xw", &mut xw)],
    )?;
    let board = Fixed::<5, 2, 2, 0, 2, 1>::new(&model)?;
    let alpha: [f64; 3] = board.momenta(&leading(&start.q), &leading(&start.qdot));
    let x = leading(&start.q.iter().chain(&alpha).copied().collect::<Vec<f64>>());
    let x0 = closed_loop_state(&x, xt, xw);
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let inputs: Vec<&str> = names.inputs.iter().map(String::as_str).collect();
    let scope = Scope {
        parameters: &parameters,
        coordinates: &coordinates,
        inputs: &inputs,
    };
    let value = |name: &str| {
        parameters
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(f64::NAN, |p| p.1)
    };
    let figure4 = plot::Figure4 {
        alpha1: "group".into(),
        alpha2: "torso".into(),
        xt: "xt".into(),
        m: value("m"),
        jt: value("jt"),
        kt: controller.kt,
    };
    let closed_loop = ClosedLoop::new(board, controller);
    execute(
        &Typed::<_, 10>::structured(closed_loop, model.engine().name()),
        &x0,
        (args, &scope),
        (Some(figure4), None),
    )
}
