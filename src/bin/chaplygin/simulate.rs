//! `chaplygin simulate`: a model (built-in and compiled, or a `.model` file
//! interpreted), its parameters and initial state from the command line, a
//! formulation closed by a controller (the `--input` laws of the time and
//! the state, read in every formulation at its configuration and velocity:
//! `(q, qdot)`, `(q, velocities(q, alpha))` in the active chart, or
//! `(q, reconstructed_velocity(q, rdot, p))`), an integrator and a
//! `--stop-when` condition; the run writes `trajectory.csv` (INTERFACE.md
//! section 3) and the plots, and prints the energy drift and the largest
//! constraint residual, and where and why it stopped. A model with
//! configuration constraints is kept on `f(q) = 0` after every step, in
//! every formulation (`projection::Surface` for a compiled model, the
//! interpreted adapters' own projection for a `.model` file).

mod arguments;
mod inputs;
mod output;
mod start;
mod stop;

pub use arguments::SimulateArgs;
pub(crate) use arguments::assignment;
use inputs::{InputSchedule, Scope};
pub(crate) use start::{set_model_parameters, set_parameters};

use crate::catalog::{self, BuiltIn, Compiled, Motion, Source};
use crate::compiled::energy_control::{ClosedLoop, EnergyController};
use crate::compiled::{
    differential_drive::DifferentialDrive, rolling_disk::RollingDisk,
    rolling_disk_3d::RollingDisk3d, sleigh::Sleigh, sleigh_bodies::SleighBodies,
    snakeboard::Snakeboard, snakeboard_bodies::SnakeboardBodies,
};
use crate::engine;
use crate::formulation::Typed;
use crate::interpreted::dynamics::InterpretedDynamics;
use crate::interpreted::{InputLaw, InterpretedDalembert, InterpretedMomentum, InterpretedReduced};
use arguments::{Controller, Formulation as Kind};
use chaplygin::plot;
use chaplygin::runtime::law::{ChartFeedback, Feedback};
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::linearize::Linearization;
use chaplygin::runtime::nalgebra::{Const, DMatrix};
use chaplygin::runtime::projection::Surface;
use chaplygin::runtime::system::{
    Dalembert, Domain, Holonomic, LagrangeDalembert, ModelNames, Momenta, Momentum,
    MomentumEquations, Parameters, Reduced, ReducedPortHamiltonian,
};
use chaplygin_codegen::derive::MOMENTUM_WITH_HOLONOMIC;
use chaplygin_codegen::interpret::InterpretedModel;
use output::{Points, execute};
use start::{
    InputError, Kinematics, Start, compiled_start, initial_state, initial_values,
    with_default_motion,
};
use std::error::Error;

/// Runs `chaplygin simulate`.
///
/// # Errors
/// Bad input, a failed simulation, or an I/O error.
pub fn run(args: &SimulateArgs) -> Result<(), Box<dyn Error>> {
    let built_in = match catalog::lookup(&args.model)? {
        Source::File { path, text } => return from_text(&path, &text, None, args),
        Source::BuiltIn(built_in) => built_in,
    };
    let Some(which) = built_in.compiled else {
        return from_text(built_in.name, built_in.source, Some(built_in), args);
    };
    let model = built_in;
    match which {
        Compiled::Snakeboard if args.controller == Controller::Energy => {
            energy_controlled(model, args)
        }
        Compiled::Snakeboard => compiled::<Snakeboard, 5, 2, 3, 2, 8, 10, 0>(
            model,
            args,
            None,
            Ok(momentum::<Snakeboard, 5, 2, 2, 1, 2, 8, 0>),
        ),
        Compiled::Sleigh => compiled::<Sleigh, 3, 1, 2, 0, 5, 6, 0>(
            model,
            args,
            None,
            Ok(momentum::<Sleigh, 3, 1, 0, 2, 0, 5, 0>),
        ),
        Compiled::RollingDisk => compiled::<RollingDisk, 4, 2, 2, 2, 6, 8, 0>(
            model,
            args,
            None,
            Ok(momentum::<RollingDisk, 4, 2, 1, 1, 2, 6, 0>),
        ),
        Compiled::DifferentialDrive => compiled::<DifferentialDrive, 5, 3, 2, 2, 7, 10, 0>(
            model,
            args,
            None,
            Ok(momentum::<DifferentialDrive, 5, 3, 2, 0, 2, 7, 0>),
        ),
        Compiled::RollingDisk3d => compiled::<RollingDisk3d, 5, 2, 3, 2, 8, 10, 0>(
            model,
            args,
            Some((&RollingDisk3d::POINTS, |disk, q| {
                disk.positions(&array(q)).as_flattened().to_vec()
            })),
            Ok(momentum::<RollingDisk3d, 5, 2, 1, 2, 2, 8, 0>),
        ),
        Compiled::SleighBodies => compiled::<SleighBodies, 3, 1, 2, 0, 5, 6, 0>(
            model,
            args,
            Some((&SleighBodies::POINTS, |sleigh, q| {
                sleigh.positions(&array(q)).as_flattened().to_vec()
            })),
            Ok(momentum::<SleighBodies, 3, 1, 0, 2, 0, 5, 0>),
        ),
        Compiled::SnakeboardBodies => compiled::<SnakeboardBodies, 5, 2, 3, 2, 8, 10, 0>(
            model,
            args,
            Some((&SnakeboardBodies::POINTS, |board, q| {
                board.positions(&array(q)).as_flattened().to_vec()
            })),
            Ok(momentum::<SnakeboardBodies, 5, 2, 2, 1, 2, 8, 0>),
        ),
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
    let constraints: Vec<&str> = names.constraints.iter().map(String::as_str).collect();
    let n = coordinates.len();
    let (alpha, given) = match built_in.map(|built_in| built_in.motion) {
        Some(Motion::Momenta(alpha)) => (alpha, args.initial.clone()),
        Some(Motion::Velocities(defaults)) => {
            (&[][..], with_default_motion(&args.initial, defaults))
        }
        None => (&[][..], args.initial.clone()),
    };
    let initial = initial_values(&given, &parameters)?;
    let dynamics = InterpretedDynamics(model);
    let start = initial_state(
        &Kinematics {
            coordinates: &coordinates,
            constraints: &constraints,
            default_q: &built_in.map_or_else(|| vec![0.0; n], |built_in| built_in.q.to_vec()),
            default_motion: &|q| {
                if alpha.is_empty() {
                    vec![0.0; n]
                } else {
                    crate::interpreted::evaluated(dynamics.0.velocities(q, alpha))
                }
            },
            constraint_matrix: &|q| {
                let a = crate::interpreted::evaluated(dynamics.0.constraint_matrix(q));
                DMatrix::from_row_slice(constraints.len(), n, &a)
            },
            holonomic: Some(&dynamics),
        },
        &initial,
        &mut [],
    )?;
    let InterpretedDynamics(model) = dynamics;
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
        Kind::Reduced => {
            let reduced = InterpretedReduced::new(model, inputs);
            let x0 = reduced.initial_state(&start.q, &start.qdot)?;
            let points = interpreted_points(&reduced.model);
            execute(&reduced, &x0, (args, &scope), (None, points))
        }
        Kind::Lagrange => {
            let x0: Vec<f64> = start.q.iter().chain(&start.qdot).copied().collect();
            let dalembert = InterpretedDalembert { model, inputs };
            let points = interpreted_points(&dalembert.model);
            execute(&dalembert, &x0, (args, &scope), (None, points))
        }
        Kind::Momentum => {
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

/// A compiled model's point names and its `positions`, flattened.
type CompiledPoints<M> = (&'static [&'static str], fn(&M, &[f64]) -> Vec<f64>);

/// [`CompiledPoints`] as the run sees them.
fn compiled_points<M, const N: usize>(
    model: &M,
    points: Option<CompiledPoints<M>>,
) -> Option<Points<'_>> {
    points.map(|(names, positions)| Points {
        names: names.iter().map(|name| name.to_string()).collect(),
        n: N,
        positions: Box::new(move |q| Ok(positions(model, q))),
    })
}

fn no_controller(model: &str) -> InputError {
    InputError::Unsupported(format!(
        "the energy controller is the built-in snakeboard's; `{model}` takes `--controller none`"
    ))
}

/// What a compiled model must offer the command line.
trait CompiledModel<const N: usize, const C: usize, const K: usize, const P: usize, const S: usize>:
    ReducedPortHamiltonian<S, P>
    + Linearization<N, C, P>
    + Momenta<N, K>
    + ModelNames
    + Domain
    + Parameters
    + Default
    + Copy
{
}

impl<M, const N: usize, const C: usize, const K: usize, const P: usize, const S: usize>
    CompiledModel<N, C, K, P, S> for M
where
    M: ReducedPortHamiltonian<S, P>
        + Linearization<N, C, P>
        + Momenta<N, K>
        + ModelNames
        + Domain
        + Parameters
        + Default
        + Copy,
{
}

/// How a compiled model with a symmetry runs in the momentum formulation
/// ([`momentum`]), or why it has none.
type MomentumRun<M> = Result<
    for<'a> fn(&'a M, &Start, &InputSchedule, Arguments<'_>, Option<Points<'a>>) -> RunResult,
    &'static str,
>;

/// The arguments of a run and the names its expressions may use.
type Arguments<'a> = (&'a SimulateArgs, &'a Scope<'a>);

/// What a run returns.
type RunResult = Result<(), Box<dyn Error>>;

/// A compiled model closed by its `--input` laws, in any formulation:
/// `D = 2 N` states in `(q, qdot)`, `S = N + K` in `(q, alpha)` (the laws
/// read the velocities of the active chart), the momentum formulation by
/// `momentum`.
fn compiled<
    M,
    const N: usize,
    const C: usize,
    const K: usize,
    const P: usize,
    const S: usize,
    const D: usize,
    const H: usize,
>(
    built_in: &BuiltIn,
    args: &SimulateArgs,
    points: Option<CompiledPoints<M>>,
    momentum: MomentumRun<M>,
) -> RunResult
where
    M: CompiledModel<N, C, K, P, S> + Holonomic<N, H>,
    Const<N>: Square,
{
    if args.controller == Controller::Energy {
        return Err(no_controller(built_in.name).into());
    }
    let mut model = M::default();
    set_model_parameters(&mut model, &args.params, &mut [])?;
    let start = compiled_start::<M, N, C, K, P, S, H>(&model, built_in, args, &mut [])?;
    let parameters = parameter_values(model);
    let inputs = InputSchedule::new(M::INPUTS, &args.inputs, &parameters, M::COORDINATES)?;
    let scope = Scope {
        parameters: &parameters,
        coordinates: M::COORDINATES,
        inputs: M::INPUTS,
    };
    let points = compiled_points::<M, N>(&model, points);
    match args.formulation {
        Kind::Reduced => {
            let law = ChartFeedback(|chart, t, x: &[f64; S]| {
                let (q, alpha): ([f64; N], [f64; K]) = (array(&x[..N]), array(&x[N..]));
                inputs.array::<P>(t, &q, &model.chart_velocities(chart, &q, &alpha))
            });
            let system = Reduced::new(&model, law);
            let x0: [f64; S] = system.initial_state(&array(&start.q), &array(&start.qdot));
            execute(
                &Typed::<_, S>::structured(Surface::reduced(system)),
                &x0,
                (args, &scope),
                (None, points),
            )
        }
        Kind::Lagrange => {
            let law = Feedback(|t, x: &[f64; D]| inputs.array::<P>(t, &x[..N], &x[N..]));
            let x0: Vec<f64> = start.q.iter().chain(&start.qdot).copied().collect();
            execute(
                &Typed::<_, D>::plain(Surface::dalembert(Dalembert::new(&model, law))),
                &x0,
                (args, &scope),
                (None, points),
            )
        }
        Kind::Momentum => match momentum {
            Ok(run) => run(&model, &start, &inputs, (args, &scope), points),
            Err(reason) => Err(InputError::Unsupported(format!(
                "`{}`: the momentum formulation is {reason}: use --formulation reduced or lagrange",
                built_in.name
            ))
            .into()),
        },
    }
}

/// The momentum formulation of a compiled model with a symmetry: `R` shape
/// coordinates, `MP` momenta and `DM = N + R + MP` states in `(q, rdot, p)`,
/// the `--input` laws read at the reconstructed velocity.
fn momentum<
    M,
    const N: usize,
    const C: usize,
    const R: usize,
    const MP: usize,
    const P: usize,
    const DM: usize,
    const H: usize,
>(
    model: &M,
    start: &Start,
    inputs: &InputSchedule,
    arguments: Arguments<'_>,
    points: Option<Points<'_>>,
) -> RunResult
where
    M: MomentumEquations<N, R, MP, P>
        + LagrangeDalembert<N, C, P>
        + Holonomic<N, H>
        + ModelNames
        + Domain,
    Const<N>: Square,
{
    let law = Feedback(|t, x: &[f64; DM]| {
        let q: [f64; N] = array(&x[..N]);
        let (rdot, p): ([f64; R], [f64; MP]) = (array(&x[N..N + R]), array(&x[N + R..]));
        inputs.array::<P>(t, &q, &model.reconstructed_velocity(&q, &rdot, &p))
    });
    let system = Momentum::new(model, law);
    let x0: [f64; DM] = system.initial_state(&array(&start.q), &array(&start.qdot));
    let kept = Surface::momentum(system);
    execute(&Typed::<_, DM>::plain(kept), &x0, arguments, (None, points))
}

/// The snakeboard under the energy-based controller (MATH.md 3.2), from
/// rest at `q = 0` with energy in the springs (`xt = 1`, `xw = 0.5`) unless
/// `--initial` says otherwise; gains `a = 1`, `kt = 2`, `kw = 1` unless
/// `--param` says otherwise.
fn energy_controlled(built_in: &BuiltIn, args: &SimulateArgs) -> Result<(), Box<dyn Error>> {
    if args.formulation != Kind::Reduced {
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
    let mut board = Snakeboard::default();
    let mut controller = EnergyController {
        a: 1.0,
        kt: 2.0,
        kw: 1.0,
    };
    set_model_parameters(
        &mut board,
        &args.params,
        &mut [
            ("a", &mut controller.a),
            ("kt", &mut controller.kt),
            ("kw", &mut controller.kw),
        ],
    )?;
    let (mut xt, mut xw) = (1.0, 0.5);
    let at_rest = BuiltIn {
        q: &[0.0; 5],
        motion: Motion::Momenta(&[0.0; 3]),
        ..*built_in
    };
    let start = compiled_start::<Snakeboard, 5, 2, 3, 2, 8, 0>(
        &board,
        &at_rest,
        args,
        &mut [("xt", &mut xt), ("xw", &mut xw)],
    )?;
    let alpha = board.momenta(&array(&start.q), &array(&start.qdot));
    let x0: Vec<f64> = start
        .q
        .iter()
        .chain(&alpha)
        .chain(&[xt, xw])
        .copied()
        .collect();
    let mut parameters = parameter_values(board);
    parameters.extend([
        ("a", controller.a),
        ("kt", controller.kt),
        ("kw", controller.kw),
    ]);
    let scope = Scope {
        parameters: &parameters,
        coordinates: &Snakeboard::COORDINATES,
        inputs: &Snakeboard::INPUTS,
    };
    let closed_loop = ClosedLoop::new(board, controller);
    let figure4 = plot::Figure4 {
        alpha1: "group".into(),
        alpha2: "torso".into(),
        xt: "xt".into(),
        m: board.m,
        jt: board.jt,
        kt: controller.kt,
    };
    execute(
        &Typed::<_, 10>::structured(closed_loop),
        &x0,
        (args, &scope),
        (Some(figure4), None),
    )
}

/// A compiled model's parameters, by name, at their values.
fn parameter_values<M: Parameters>(mut model: M) -> Vec<(&'static str, f64)> {
    M::PARAMETERS
        .iter()
        .filter_map(|&name| model.parameter_mut(name).map(|value| (name, *value)))
        .collect()
}

fn array<const N: usize>(values: &[f64]) -> [f64; N] {
    core::array::from_fn(|i| values[i])
}
