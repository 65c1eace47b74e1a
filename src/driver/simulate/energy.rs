//! A model under the paper's energy-based controller (MATH.md 3.2,
//! `crate::energy_control`), for any model with what the controller uses:
//! the steering angle `phi` among its coordinates, and its two inputs, the
//! torso's and the wheels', in the reduced form of the snakeboard's sizes
//! (5 coordinates, 2 constraint rows, no configuration constraints), with
//! any symmetry or none: the two inputs, in declared order, are its torso
//! and wheel ports.
//! The closed loop is the runtime's interconnection of the model at those
//! fixed sizes (`chaplygin_codegen::interpret::Fixed`). It starts at rest at
//! `q = 0` with energy in the springs (`xt = 1`, `xw = 0.5`), with the
//! gains `a = 1`, `kt = 2`, `kw = 1`, unless the request says otherwise.

use super::run::{self, Settings};
use super::{Finished, FormulationChoice, Request};
use crate::driver::Failure;
use crate::driver::formulation::Typed;
use crate::driver::setup::{Controls, InputError, Origin, Setup};
use crate::energy_control::{
    CLOSED_LOOP_STATE, ClosedLoop, EnergyController, GAINS, S, SPRINGS, STEERING, closed_loop_state,
};
use crate::runtime::arrays::leading;
use crate::runtime::record::{Recorder, Table};
use crate::runtime::system::Momenta;
use chaplygin_codegen::interpret::{Fixed, InterpretedModel};

/// The controller's gains and springs, beside the model's names.
pub(super) const CONTROLS: Controls<'static> = Controls {
    gains: &GAINS,
    states: &SPRINGS,
};

/// Where the closed loop starts unless the request says otherwise: at rest
/// at `q = 0`.
pub(super) const ORIGIN: Origin<'static> = Origin {
    q: None,
    motion: None,
};

/// The sizes the closed loop runs at: coordinates, constraint rows,
/// inputs, configuration constraints.
const SIZES: [usize; 4] = [5, 2, 2, 0];

/// Refuses a model without what the controller uses, and a request the
/// closed loop does not run, each in one line.
///
/// # Errors
/// [`InputError::Unsupported`] naming what is missing.
pub(super) fn check(
    model: &InterpretedModel,
    label: &str,
    request: &Request,
) -> Result<(), InputError> {
    if let Some(missing) = missing(model) {
        return Err(InputError::Unsupported(format!(
            "the energy controller needs a coordinate `{STEERING}`, two inputs (the torso's and \
             the wheels'), 5 coordinates, 2 constraint rows and no configuration constraints \
             (MATH.md 3.2); `{label}` has {missing}"
        )));
    }
    if request.formulation != FormulationChoice::Reduced {
        return Err(InputError::Unsupported(
            "the energy controller closes the reduced port-Hamiltonian form: use --formulation reduced".into(),
        ));
    }
    match request.inputs.first() {
        Some((name, _)) => Err(InputError::Unsupported(format!(
            "--input {name}: the energy controller sets the inputs"
        ))),
        None => Ok(()),
    }
}

/// The first thing `model` lacks of what the controller uses, said as what
/// it has instead.
fn missing(model: &InterpretedModel) -> Option<String> {
    let names = model.names();
    if !names.coordinates.iter().any(|c| c == STEERING) {
        return Some(format!("no coordinate `{STEERING}`"));
    }
    let sizes = model.sizes();
    let found = [sizes.n, sizes.c, sizes.p, names.holonomic.len()];
    let kinds = [
        "coordinates",
        "constraint rows",
        "inputs",
        "configuration constraints",
    ];
    let differ = (0..SIZES.len()).find(|&i| found[i] != SIZES[i])?;
    Some(format!("{} {}", found[differ], kinds[differ]))
}

/// Runs the closed loop of the resolved `setup` as `request` says,
/// recording every row into the returned table and into `also`.
///
/// # Errors
/// A start the formulation cannot represent, or bad run settings; a failed
/// run is [`Finished::outcome`].
pub(super) fn run(
    setup: &Setup,
    request: &Request,
    also: &mut dyn Recorder,
    progress: &mut dyn FnMut(f64),
) -> Result<Finished, Failure> {
    let momentum = setup.model.arguments("momentum_rhs").is_some();
    match (momentum, setup.model.shape().map_or(0, |shape| shape.len())) {
        (false, _) => run_at::<0, 0>(setup, request, also, progress),
        (true, 0) => run_at::<0, 3>(setup, request, also, progress),
        (true, 1) => run_at::<1, 2>(setup, request, also, progress),
        (true, 2) => run_at::<2, 1>(setup, request, also, progress),
        (true, _) => run_at::<3, 0>(setup, request, also, progress),
    }
}

/// [`run`] at `R` shape coordinates and `MP` momenta.
fn run_at<const R: usize, const MP: usize>(
    setup: &Setup,
    request: &Request,
    also: &mut dyn Recorder,
    progress: &mut dyn FnMut(f64),
) -> Result<Finished, Failure> {
    let value = |name: &str| {
        (setup.parameters.iter())
            .find(|(parameter, _)| parameter == name)
            .map_or(f64::NAN, |(_, value)| *value)
    };
    let names = setup.model.names();
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let controller = EnergyController::new(value("a"), value("kt"), value("kw"), &coordinates)
        .ok_or_else(|| InputError::Unsupported(format!("no coordinate `{STEERING}`")))?;
    let board = Fixed::<5, 2, 2, 0, R, MP>::new(&setup.model)?;
    let start = setup.start.as_ref().expect("a run asks for its start");
    let alpha: [f64; S - 5] = board.momenta(&leading(&start.q), &leading(&start.qdot));
    let x = leading(&start.q.iter().chain(&alpha).copied().collect::<Vec<f64>>());
    let [xt, xw] = [setup.controller_states[0], setup.controller_states[1]];
    let x0: [f64; CLOSED_LOOP_STATE] = closed_loop_state(&x, xt, xw);
    let closed_loop = Typed::<_, CLOSED_LOOP_STATE>::structured(
        ClosedLoop::new(board, controller),
        setup.model.engine().name(),
    );
    let settings = Settings::new(request, &closed_loop, setup.stop.as_ref())?;
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
        parameters: setup.parameters.clone(),
        outcome,
    })
}
