//! The paper's energy-based controller (MATH.md 3.2) on every model with
//! what it uses, not on one model known by its name: the snakeboard read
//! from its file runs as the built-in does, and the snakeboard declared as
//! bodies and wheel contacts, a derivation of the same mechanics from
//! another declaration, runs the same motion; a model without a steering
//! angle `phi` or of other sizes is refused in one line naming what it
//! lacks.

use crate::support::in_process::{Model, Simulated};

/// Five seconds of the closed loop from its default start, energy in the
/// springs, with the implicit midpoint rule.
const RUN: [&str; 6] = [
    "--controller",
    "energy",
    "--integrator",
    "midpoint",
    "--t-end",
    "5",
];

fn controlled(model: &str) -> Simulated {
    let run = Model::load(model, "jit")
        .simulate(&RUN)
        .unwrap_or_else(|error| panic!("{model}: {error}"));
    assert!(run.outcome.is_ok(), "{model}: {:?}", run.outcome);
    run
}

#[test]
fn the_snakeboard_from_its_file_runs_as_the_built_in_does() {
    let built_in = controlled("snakeboard");
    let file = controlled(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../models/snakeboard.model"
    ));
    assert_eq!(file.header, built_in.header);
    assert_eq!(file.rows, built_in.rows);
}

/// The bodies' snakeboard derives the same equations from another
/// declaration: its rows agree with the paper's declaration's to the
/// integrator's tolerance, the closed loop's energy is kept, and energy
/// flows from the springs into the group momentum (MATH.md 3.2).
#[test]
fn the_snakeboard_declared_as_bodies_runs_the_same_motion() {
    let energy = controlled("snakeboard");
    let bodies = controlled("snakeboard-bodies");
    assert_eq!(bodies.header, energy.header);
    assert_eq!(bodies.rows.len(), energy.rows.len());
    let mut largest = 0.0f64;
    for (row, other) in bodies.rows.iter().zip(&energy.rows) {
        for (a, b) in row.iter().zip(other) {
            largest = largest.max((a - b).abs() / b.abs().max(1.0));
        }
    }
    assert!(largest < 1e-12, "largest relative difference {largest:e}");
    let total = bodies.column("energy");
    let drift = (total.iter()).fold(0.0f64, |m, e| m.max((e - total[0]).abs() / total[0]));
    assert!(drift < 1e-10, "energy drift {drift:e}");
    let group = bodies.column("group");
    assert_eq!(group[0], 0.0);
    assert!(group.iter().any(|&alpha1| alpha1 > 0.05), "{group:?}");
}

/// The leaning rolling disk has a coordinate `phi` (its lean) and two
/// inputs at the snakeboard's sizes: the controller closes its loop too,
/// and the interconnection, power-conserving whatever the plant, keeps the
/// closed loop's energy.
#[test]
fn any_model_with_what_the_controller_uses_runs_under_it() {
    let disk = controlled("rolling-disk-3d");
    let total = disk.column("energy");
    let drift = (total.iter()).fold(0.0f64, |m, e| m.max((e - total[0]).abs() / total[0]));
    assert!(drift < 1e-10, "energy drift {drift:e}");
}

#[test]
fn a_model_without_what_the_controller_uses_is_refused_in_one_line() {
    for (model, lacks) in [
        ("sleigh", "has no coordinate `phi`"),
        ("differential-drive", "has no coordinate `phi`"),
        ("bicycle", "has 8 coordinates"),
    ] {
        let error = Model::load(model, "interpret")
            .simulate(&RUN)
            .err()
            .unwrap_or_else(|| panic!("{model} ran under the energy controller"));
        assert!(!error.contains('\n'), "{error}");
        assert!(
            error.starts_with("the energy controller needs a coordinate `phi`")
                && error.ends_with(lacks),
            "{model}: {error}"
        );
    }
}
