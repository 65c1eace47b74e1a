//! `chaplygin simulate`: a model (built-in and compiled, or a `.model` file
//! interpreted), its parameters and initial state from the command line, a
//! formulation closed by a controller, an integrator; the run writes
//! `trajectory.csv` (INTERFACE.md section 3) and the plots, and prints the
//! energy drift and the largest constraint residual.

use crate::catalog::{self, BuiltIn, Compiled, Source};
use crate::derive::Rejected;
use crate::formulation::{Formulation, Sized, Typed, with_dimension};
use crate::interpreted::{InterpretedDalembert, InterpretedReduced};
use crate::models::energy_control::{ClosedLoop, EnergyController};
use crate::models::{
    differential_drive::DifferentialDrive, rolling_disk::RollingDisk, sleigh::Sleigh,
    snakeboard::Snakeboard,
};
use crate::options::{Controller, Formulation as Kind, Integrator, SimulateArgs};
use chaplygin::plot;
use chaplygin::runtime::control::Constant;
use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, Midpoint, Rk4};
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::nalgebra::Const;
use chaplygin::runtime::record::{CsvRecorder, Recorder, Table};
use chaplygin::runtime::simulate::{Advance, Simulation, Summary};
use chaplygin::runtime::system::{
    Dalembert, LagrangeDalembert, ModelNames, Momenta, Momentum, MomentumEquations, Parameters,
    Reduced, ReducedPortHamiltonian,
};
use chaplygin_codegen::interpret::InterpretedModel;
use std::error::Error;
use std::io;
use std::time::{Duration, Instant};

/// A problem with the command's input, stated in one line.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// `--param` names no parameter.
    #[error("unknown parameter `{name}` (parameters: {known})")]
    UnknownParameter {
        /// What was given.
        name: String,
        /// The parameters there are.
        known: String,
    },
    /// `--initial` names no coordinate, velocity or controller state.
    #[error("unknown initial value `{name}` (coordinates, `dot(q)` velocities{states}: {known})")]
    UnknownInitial {
        /// What was given.
        name: String,
        /// ", controller states" when there are some.
        states: &'static str,
        /// The names there are.
        known: String,
    },
    /// `--input` names no input.
    #[error("unknown input `{name}` (inputs: {known})")]
    UnknownInput {
        /// What was given.
        name: String,
        /// The inputs there are.
        known: String,
    },
    /// The initial velocity violates a constraint.
    #[error(
        "the initial velocity violates constraint `{constraint}`: A(q) qdot = {residual:e}, must be 0"
    )]
    ConstraintViolated {
        /// The constraint with the largest residual.
        constraint: String,
        /// Its residual.
        residual: f64,
    },
    /// A combination the command does not run.
    #[error("{0}")]
    Unsupported(String),
}

/// Runs `chaplygin simulate`.
///
/// # Errors
/// Bad input, a failed simulation, or an I/O error.
pub fn run(args: &SimulateArgs) -> Result<(), Box<dyn Error>> {
    let model = match catalog::lookup(&args.model)? {
        Source::File { path, text } => return interpreted(&path, &text, args),
        Source::BuiltIn(model) => model,
    };
    match model.compiled {
        Compiled::Snakeboard if args.controller == Controller::Energy => {
            energy_controlled(model, args)
        }
        Compiled::Snakeboard => compiled::<Snakeboard, 5, 2, 3, 2, 8, 10, 2, 1, 8>(model, args),
        Compiled::Sleigh => compiled::<Sleigh, 3, 1, 2, 0, 5, 6, 0, 2, 5>(model, args),
        Compiled::RollingDisk => compiled::<RollingDisk, 4, 2, 2, 2, 6, 8, 1, 1, 6>(model, args),
        Compiled::DifferentialDrive => {
            compiled::<DifferentialDrive, 5, 3, 2, 2, 7, 10, 2, 0, 7>(model, args)
        }
    }
}

/// A `.model` file through the IR interpreter, at rest at `q = 0` unless
/// `--initial` says otherwise.
fn interpreted(path: &str, text: &str, args: &SimulateArgs) -> Result<(), Box<dyn Error>> {
    if args.controller == Controller::Energy {
        return Err(no_controller(path).into());
    }
    let mut model = InterpretedModel::from_source(text)
        .map_err(|diagnostics| Rejected(diagnostics.render(path).trim_end().to_string()))?;
    let names = model.names().clone();
    let known: Vec<&str> = names.parameters.iter().map(String::as_str).collect();
    set_parameters(&known, &args.params, &mut |name, value| {
        model.set_parameter(name, value).is_ok()
    })?;
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let constraints: Vec<&str> = names.constraints.iter().map(String::as_str).collect();
    let n = coordinates.len();
    let start = initial_state(
        &Kinematics {
            coordinates: &coordinates,
            constraints: &constraints,
            default_q: &vec![0.0; n],
            default_motion: &|_| vec![0.0; n],
            residual: &|q, qdot| model.constraint_residual(q, qdot).unwrap_or_default(),
        },
        &args.initial,
        &mut [],
    )?;
    let input_names: Vec<&str> = names.inputs.iter().map(String::as_str).collect();
    let inputs = constant_inputs(&input_names, &args.inputs)?;
    match args.formulation {
        Kind::Reduced => {
            let alpha = model.momenta(&start.q, &start.qdot)?;
            let x0: Vec<f64> = start.q.iter().chain(&alpha).copied().collect();
            execute(&InterpretedReduced { model, inputs }, &x0, args, None)
        }
        Kind::Lagrange => {
            let x0: Vec<f64> = start.q.iter().chain(&start.qdot).copied().collect();
            execute(&InterpretedDalembert { model, inputs }, &x0, args, None)
        }
        Kind::Momentum => Err(interpreted_momentum(path, &model).into()),
    }
}

/// The momentum formulation needs a symmetry, and runs on the compiled
/// models only.
fn interpreted_momentum(path: &str, model: &InterpretedModel) -> InputError {
    if model.functions().any(|name| name == "momentum_rhs") {
        InputError::Unsupported(format!(
            "the momentum formulation runs on the built-in models; `{path}` takes \
             `--formulation reduced` or `--formulation lagrange`"
        ))
    } else {
        InputError::Unsupported(format!(
            "`{path}` declares no symmetry: the momentum formulation needs one"
        ))
    }
}

fn no_controller(model: &str) -> InputError {
    InputError::Unsupported(format!(
        "the energy controller is the built-in snakeboard's; `{model}` takes `--controller none`"
    ))
}

/// What a compiled model must offer the command line.
trait CompiledModel<const N: usize, const C: usize, const K: usize, const P: usize, const S: usize>:
    ReducedPortHamiltonian<S, P>
    + LagrangeDalembert<N, C, P>
    + Momenta<N, K>
    + ModelNames
    + Parameters
    + Default
    + Copy
{
}

impl<M, const N: usize, const C: usize, const K: usize, const P: usize, const S: usize>
    CompiledModel<N, C, K, P, S> for M
where
    M: ReducedPortHamiltonian<S, P>
        + LagrangeDalembert<N, C, P>
        + Momenta<N, K>
        + ModelNames
        + Parameters
        + Default
        + Copy,
{
}

/// A compiled model with constant inputs, in any formulation: `D = 2 N`
/// states in `(q, qdot)`; `R` shape coordinates, `MP` momenta and
/// `DM = N + R + MP` states in `(q, rdot, p)`.
fn compiled<
    M,
    const N: usize,
    const C: usize,
    const K: usize,
    const P: usize,
    const S: usize,
    const D: usize,
    const R: usize,
    const MP: usize,
    const DM: usize,
>(
    built_in: &BuiltIn,
    args: &SimulateArgs,
) -> Result<(), Box<dyn Error>>
where
    M: CompiledModel<N, C, K, P, S> + MomentumEquations<N, R, MP, P>,
{
    if args.controller == Controller::Energy {
        return Err(no_controller(built_in.name).into());
    }
    let mut model = M::default();
    set_model_parameters(&mut model, &args.params, &mut [])?;
    let start = compiled_start::<M, N, C, K, P, S>(&model, built_in, args, &mut [])?;
    let inputs = constant_inputs(M::INPUTS, &args.inputs)?;
    let u = Constant(core::array::from_fn::<f64, P, _>(|i| inputs[i]));
    match args.formulation {
        Kind::Reduced => {
            let alpha = model.momenta(&array(&start.q), &array(&start.qdot));
            let x0: Vec<f64> = start.q.iter().chain(&alpha).copied().collect();
            execute(
                &Typed::<_, S>::structured(Reduced::new(&model, u)),
                &x0,
                args,
                None,
            )
        }
        Kind::Lagrange => {
            let x0: Vec<f64> = start.q.iter().chain(&start.qdot).copied().collect();
            execute(
                &Typed::<_, D>::plain(Dalembert::new(&model, u)),
                &x0,
                args,
                None,
            )
        }
        Kind::Momentum => {
            let system = Momentum::new(&model, u);
            let x0: [f64; DM] = system.initial_state(&array(&start.q), &array(&start.qdot));
            execute(&Typed::<_, DM>::plain(system), &x0, args, None)
        }
    }
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
        alpha: &[0.0; 3],
        ..*built_in
    };
    let start = compiled_start::<Snakeboard, 5, 2, 3, 2, 8>(
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
        args,
        Some(figure4),
    )
}

fn array<const N: usize>(values: &[f64]) -> [f64; N] {
    core::array::from_fn(|i| values[i])
}

/// Sets `--param` values with `set`, which says whether the name was a
/// parameter; `known` lists them for the error.
fn set_parameters(
    known: &[&str],
    given: &[(String, f64)],
    set: &mut dyn FnMut(&str, f64) -> bool,
) -> Result<(), InputError> {
    for (name, value) in given {
        if !set(name, *value) {
            return Err(InputError::UnknownParameter {
                name: name.clone(),
                known: known.join(", "),
            });
        }
    }
    Ok(())
}

/// Sets `--param` values on a compiled model's parameters or the `extra`
/// (controller) ones.
fn set_model_parameters<M: Parameters>(
    model: &mut M,
    given: &[(String, f64)],
    extra: &mut [(&str, &mut f64)],
) -> Result<(), InputError> {
    let known: Vec<&str> = M::PARAMETERS
        .iter()
        .copied()
        .chain(extra.iter().map(|(n, _)| *n))
        .collect();
    set_parameters(&known, given, &mut |name, value| {
        if let Some(parameter) = model.parameter_mut(name) {
            *parameter = value;
        } else if let Some((_, parameter)) = extra.iter_mut().find(|(n, _)| *n == name) {
            **parameter = value;
        } else {
            return false;
        }
        true
    })
}

/// The initial configuration and velocity.
struct Start {
    q: Vec<f64>,
    qdot: Vec<f64>,
}

/// `A(q) qdot` from `(q, qdot)`.
type Residual<'a> = dyn Fn(&[f64], &[f64]) -> Vec<f64> + 'a;

/// What the initial state is checked and completed with.
struct Kinematics<'a> {
    coordinates: &'a [&'a str],
    constraints: &'a [&'a str],
    default_q: &'a [f64],
    /// The default velocity at a configuration.
    default_motion: &'a dyn Fn(&[f64]) -> Vec<f64>,
    /// `A(q) qdot`.
    residual: &'a Residual<'a>,
}

/// The initial state from the defaults and `--initial` (coordinates,
/// `dot(q)` velocities and `controller_states`); the velocity is checked
/// against the constraints.
fn initial_state(
    kinematics: &Kinematics<'_>,
    given: &[(String, f64)],
    controller_states: &mut [(&str, &mut f64)],
) -> Result<Start, InputError> {
    let coordinates = kinematics.coordinates;
    let mut q = kinematics.default_q.to_vec();
    let mut velocities: Option<Vec<f64>> = None;
    for (name, value) in given {
        if let Some(i) = coordinates.iter().position(|c| c == name) {
            q[i] = *value;
        } else if let Some(i) = coordinates
            .iter()
            .position(|c| name == &format!("dot({c})"))
        {
            velocities.get_or_insert_with(|| vec![0.0; coordinates.len()])[i] = *value;
        } else if let Some((_, state)) = controller_states.iter_mut().find(|(n, _)| n == name) {
            **state = *value;
        } else {
            return Err(unknown_initial(name, coordinates, controller_states));
        }
    }
    let qdot = velocities.unwrap_or_else(|| (kinematics.default_motion)(&q));
    check_constraints(
        kinematics.constraints,
        &(kinematics.residual)(&q, &qdot),
        &qdot,
    )?;
    Ok(Start { q, qdot })
}

/// [`initial_state`] for a compiled model, whose default motion is
/// `velocities(q, alpha)` with the built-in default momenta.
fn compiled_start<
    M,
    const N: usize,
    const C: usize,
    const K: usize,
    const P: usize,
    const S: usize,
>(
    model: &M,
    built_in: &BuiltIn,
    args: &SimulateArgs,
    controller_states: &mut [(&str, &mut f64)],
) -> Result<Start, InputError>
where
    M: CompiledModel<N, C, K, P, S>,
{
    let alpha: [f64; K] = array(built_in.alpha);
    initial_state(
        &Kinematics {
            coordinates: M::COORDINATES,
            constraints: M::CONSTRAINTS,
            default_q: built_in.q,
            default_motion: &|q| model.velocities(&array(q), &alpha).to_vec(),
            residual: &|q, qdot| model.constraint_residual(&array(q), &array(qdot)).to_vec(),
        },
        &args.initial,
        controller_states,
    )
}

fn unknown_initial(
    name: &str,
    coordinates: &[&str],
    controller_states: &[(&str, &mut f64)],
) -> InputError {
    let velocities = coordinates.iter().map(|c| format!("dot({c})"));
    let known: Vec<String> = coordinates
        .iter()
        .map(|c| c.to_string())
        .chain(velocities)
        .chain(controller_states.iter().map(|(n, _)| n.to_string()))
        .collect();
    InputError::UnknownInitial {
        name: name.to_string(),
        states: if controller_states.is_empty() {
            ""
        } else {
            ", controller states"
        },
        known: known.join(", "),
    }
}

/// [`InputError::ConstraintViolated`] when `|A(q) qdot|` exceeds round-off.
fn check_constraints(names: &[&str], residual: &[f64], qdot: &[f64]) -> Result<(), InputError> {
    let scale = qdot.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let worst = residual
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
    match worst {
        Some((i, r)) if r.abs() > 1e-9 * scale => Err(InputError::ConstraintViolated {
            constraint: names[i].to_string(),
            residual: *r,
        }),
        _ => Ok(()),
    }
}

/// The constant inputs from `--input`, zero where not given.
fn constant_inputs(names: &[&str], given: &[(String, f64)]) -> Result<Vec<f64>, InputError> {
    let mut u = vec![0.0; names.len()];
    for (name, value) in given {
        let i = names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| InputError::UnknownInput {
                name: name.clone(),
                known: if names.is_empty() {
                    "none".into()
                } else {
                    names.join(", ")
                },
            })?;
        u[i] = *value;
    }
    Ok(u)
}

/// Runs `formulation` from `x0` with the chosen integrator, writing
/// `trajectory.csv` and the plots into `--out`, and prints the summary.
fn execute(
    formulation: &dyn Formulation,
    x0: &[f64],
    args: &SimulateArgs,
    figure4: Option<plot::Figure4>,
) -> Result<(), Box<dyn Error>> {
    if args.integrator == Integrator::DiscreteGradient && !formulation.is_structured() {
        return Err(InputError::Unsupported(
            "the discrete-gradient integrator needs the structured (reduced) form: use --formulation reduced".into(),
        )
        .into());
    }
    std::fs::create_dir_all(&args.out)?;
    let csv_path = args.out.join("trajectory.csv");
    let mut recorder = Both(CsvRecorder::create(&csv_path)?, Table::new());
    let outcome = with_dimension!(x0.len(), D => integrate::<D>(formulation, x0, args, &mut recorder),
        _ => Err(InputError::Unsupported(format!(
            "the state has {} entries; the command line runs up to {}",
            x0.len(),
            crate::formulation::MAX_DIMENSION
        )).into()));
    let Both(_, table) = recorder;
    let plots = write_plots(&table, &args.out, figure4);
    let report = outcome?;
    println!("{report}");
    println!("wrote {}", csv_path.display());
    for plot in plots? {
        println!("wrote {}", plot.display());
    }
    Ok(())
}

/// The plots of what was recorded (`chaplygin::plot`), Figure 4 with
/// `figure4`.
fn write_plots(
    table: &Table,
    out: &std::path::Path,
    figure4: Option<plot::Figure4>,
) -> Result<Vec<std::path::PathBuf>, plot::PlotError> {
    if table.rows.is_empty() {
        return Ok(Vec::new());
    }
    let mut plotted = plot::Table::new(table.columns.clone())?;
    for row in &table.rows {
        plotted.push_row(row.clone())?;
    }
    let spec = plot::PlotSpec::for_table(&plotted);
    let spec = match figure4 {
        Some(figure4) => spec.with_figure4(figure4),
        None => spec,
    };
    plot::write_plots(&plotted, &spec, out)
}

/// What a finished run prints.
struct Report {
    steps: usize,
    t: f64,
    energy_drift: f64,
    max_constraint_residual: f64,
    seconds: f64,
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "t = {}: {} steps in {:.3} s; energy drift (relative) {:.3e}; max constraint residual {:.3e}",
            self.t, self.steps, self.seconds, self.energy_drift, self.max_constraint_residual
        )
    }
}

/// The run in dimension `D`.
fn integrate<const D: usize>(
    formulation: &dyn Formulation,
    x0: &[f64],
    args: &SimulateArgs,
    recorder: &mut impl Recorder,
) -> Result<Report, Box<dyn Error>>
where
    Const<D>: Square,
{
    let system = Sized::<D>(formulation);
    let x0: [f64; D] = core::array::from_fn(|i| x0[i]);
    let started = Instant::now();
    let summary = match args.integrator {
        Integrator::Rk4 => run_with(Rk4, &system, x0, args, recorder),
        Integrator::Midpoint => run_with(Midpoint::default(), &system, x0, args, recorder),
        Integrator::DiscreteGradient => {
            run_with(DiscreteGradient::default(), &system, x0, args, recorder)
        }
        Integrator::Dopri5 => run_with(DormandPrince::default(), &system, x0, args, recorder),
    }?;
    Ok(Report {
        steps: summary.steps,
        t: summary.t,
        energy_drift: summary.energy_drift,
        max_constraint_residual: summary.max_constraint_residual,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// One integrator's run, with a progress bar once it has taken a second.
fn run_with<M, const D: usize>(
    method: M,
    system: &Sized<'_, D>,
    x0: [f64; D],
    args: &SimulateArgs,
    recorder: &mut impl Recorder,
) -> Result<Summary<D>, Box<dyn Error>>
where
    M: for<'a> Advance<Sized<'a, D>, D>,
{
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(1000),
        indicatif::ProgressDrawTarget::hidden(),
    );
    let started = Instant::now();
    let progress = |fraction: f64| {
        if bar.is_hidden() && started.elapsed() > Duration::from_secs(1) {
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
        }
        bar.set_position((fraction * 1000.0) as u64);
    };
    let summary = Simulation::new(method)
        .span(0.0, args.t_end)
        .step(args.dt)
        .run_with_progress(system, x0, recorder, progress);
    bar.finish_and_clear();
    Ok(summary?)
}

/// A recorder writing into two.
struct Both<A, B>(A, B);

impl<A: Recorder, B: Recorder> Recorder for Both<A, B> {
    fn start(&mut self, columns: &[String]) -> io::Result<()> {
        self.0.start(columns)?;
        self.1.start(columns)
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        self.0.record(row)?;
        self.1.record(row)
    }

    fn finish(&mut self) -> io::Result<()> {
        self.0.finish()?;
        self.1.finish()
    }
}
