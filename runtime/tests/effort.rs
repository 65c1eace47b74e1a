//! What a run reports it took (`Summary::effort`), against what each
//! method does by construction: a fixed-step method one accepted step per
//! step of the run; an explicit method no Newton iteration; an implicit
//! one at least one per implicit step, and step doubling three implicit
//! steps per trial. And the energy drift's scale: on the thrown body
//! ([`Thrown`], `H = p^2/2 + G q`) the kinetic energy `p^2/2` at most
//! 2 (from `p = 2`) and the height's range; a constant in the energy does
//! not change it.

use crate::stop::Thrown;
use chaplygin_runtime::integrate::{
    Controlled, DiscreteGradient, DormandPrince, Effort, Midpoint, Rk4,
};
use chaplygin_runtime::record::Table;
use chaplygin_runtime::simulate::{Advance, Simulation, Summary};

/// The run of `method` on [`Thrown`] from `q = 0`, `p = 2` over `[0, 3]`
/// in steps of 0.1.
fn thrown<M: Advance<Thrown, [f64; 2]>>(method: M) -> Summary<[f64; 2]> {
    Simulation::new(method)
        .span(0.0, 3.0)
        .step(0.1)
        .run(&Thrown, [0.0, 2.0], &mut Table::new())
        .expect("the run ends")
}

#[test]
fn a_fixed_step_run_takes_one_accepted_step_per_step() {
    let explicit = Effort {
        accepted: 30,
        rejected: 0,
        newton_iterations: 0,
    };
    assert_eq!(thrown(Rk4).effort, explicit);
    for implicit in [
        thrown(Midpoint::default()).effort,
        thrown(DiscreteGradient::default()).effort,
    ] {
        assert_eq!((implicit.accepted, implicit.rejected), (30, 0));
        assert!(implicit.newton_iterations >= 30, "{implicit:?}");
    }
}

#[test]
fn an_adaptive_run_counts_every_trial() {
    let dormand_prince = thrown(DormandPrince::default()).effort;
    assert!(dormand_prince.accepted >= 30, "{dormand_prince:?}");
    assert_eq!(dormand_prince.newton_iterations, 0);
    let controlled = thrown(Controlled::new(Midpoint::default(), 1e-8, 1e-8)).effort;
    let trials = controlled.accepted + controlled.rejected;
    assert!(controlled.accepted >= 30, "{controlled:?}");
    assert!(controlled.newton_iterations >= 3 * trials, "{controlled:?}");
}

/// From `q = 0`, `p = 2` the body rises to `q = 2` at `t = 2` and falls
/// back to `q = 1.5` at `t = 3`: the largest kinetic energy is the first,
/// 2, and the height's energy ranges over `[0, 2]`.
#[test]
fn the_drift_is_relative_to_the_kinetic_energy_and_the_heights_range() {
    let summary = thrown(Rk4);
    assert!(
        (summary.energy_scale - 4.0).abs() < 1e-12,
        "{}",
        summary.energy_scale
    );
    assert!(summary.energy_drift < 1e-12, "{}", summary.energy_drift);
}
