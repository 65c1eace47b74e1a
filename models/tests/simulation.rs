//! The simulation loop on the built-in models: the recorded columns and
//! their CSV, the closed loop's recorded energy, determinism, and the
//! structured error where a formulation degenerates (the snakeboard's wheel
//! constraints at `phi = pi/2`, the sleigh's own basis at `theta = pi/2`),
//! with the rows recorded before it kept.

use chaplygin::energy_control::{ClosedLoop, EnergyController, closed_loop_state};
use chaplygin::runtime::control::Feedback;
use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, Midpoint, Rk4};
use chaplygin::runtime::record::{CsvRecorder, Table};
use chaplygin::runtime::simulate::{Simulation, SimulationError};
use chaplygin::runtime::system::{Dalembert, Jacobian, OdeSystem, Reduced, ReducedPortHamiltonian};
use chaplygin_models::{sleigh::Sleigh, snakeboard::Snakeboard};
use std::f64::consts::FRAC_PI_2;

fn closed_loop() -> ClosedLoop<Snakeboard> {
    ClosedLoop::<Snakeboard>::new(
        Snakeboard::default(),
        EnergyController::new(1.0, 2.0, 1.0, &Snakeboard::COORDINATES).expect("phi"),
    )
}

/// At rest at `phi = 0.2`, energy in both springs.
fn at_rest() -> [f64; 10] {
    closed_loop_state(&[0.0, 0.0, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0], 1.0, 0.5)
}

fn csv_of_closed_loop(seconds: f64) -> Vec<u8> {
    let mut csv = CsvRecorder::new(Vec::new());
    Simulation::new(Midpoint::default())
        .span(0.0, seconds)
        .step(0.01)
        .run(&closed_loop(), at_rest(), &mut csv)
        .unwrap();
    csv.into_inner().unwrap()
}

/// The rows of a CSV text as numbers, after checking that each has as many
/// fields as the header.
fn parse(csv: &[u8]) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::str::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|line| line.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(rows.iter().all(|row: &Vec<f64>| row.len() == header.len()));
    (header, rows)
}

#[test]
fn the_closed_loop_csv_has_the_documented_columns_and_constant_energy() {
    let (header, rows) = parse(&csv_of_closed_loop(20.0));
    let expected =
        "t,x,y,theta,psi,phi,group,torso,wheels,xt,xw,u_torso,u_wheels,energy,constraint_residual";
    assert_eq!(header.join(","), expected);
    assert_eq!(rows.len(), 2001);
    let energy0 = rows[0][13];
    let model = closed_loop();
    for row in &rows {
        let z: [f64; 10] = core::array::from_fn(|i| row[1 + i]);
        let relative = (row[13] - energy0).abs() / energy0;
        assert!(
            relative <= 1e-12,
            "energy {} vs {energy0} at t = {}",
            row[13],
            row[0]
        );
        // the recorded energy and inputs are the closed loop's own
        assert_eq!(
            row[13],
            chaplygin::runtime::system::Energy::energy(&model, &z)
        );
        assert_eq!([row[11], row[12]], model.input(&z));
        assert!(row[14] <= 1e-12, "constraint residual {}", row[14]);
    }
}

#[test]
fn the_same_run_writes_the_same_bytes() {
    assert_eq!(csv_of_closed_loop(2.0), csv_of_closed_loop(2.0));
}

/// The snakeboard's wheels driven by `u_wheels = jw`, so `phi = 1.2 + t^2/2`
/// from rest: `phi` reaches `pi/2` at `t = sqrt(2 (pi/2 - 1.2)) = 0.861`.
fn into_the_singularity() -> (Snakeboard, [f64; 8]) {
    let board = Snakeboard::default();
    (board, [0.0, 0.0, 0.0, 0.0, 1.2, 0.0, 0.0, 0.0])
}

#[test]
fn the_wheel_constraints_degenerate_at_phi_pi_2_and_the_measure_changes_sign() {
    let board = Snakeboard::default();
    let at = |phi: f64| board.regularity(&[0.3, -0.1, 0.7, 0.2, phi, 1.0, 0.5, 0.1]);
    // the two rows of A are parallel at phi = pi/2 (MATH.md 3.1)
    let a = board.constraint_matrix(&[0.3, -0.1, 0.7, 0.2, FRAC_PI_2]);
    let cross = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    assert!(cross.abs() < 1e-15, "{a:?}");
    assert!(at(FRAC_PI_2).abs() < 1e-15, "{}", at(FRAC_PI_2));
    assert!(at(FRAC_PI_2 - 0.01) * at(FRAC_PI_2 + 0.01) < 0.0);
    assert!(at(0.0).abs() > 0.1, "regular at phi = 0: {}", at(0.0));
}

#[test]
fn heading_into_phi_pi_2_stops_with_a_structured_error_not_nan() {
    let (board, x0) = into_the_singularity();
    let system = Reduced::new(&board, |_t: f64| [0.0, board.jw]);
    let mut csv = CsvRecorder::new(Vec::new());
    let error = Simulation::new(Rk4)
        .span(0.0, 2.0)
        .step(0.01)
        .run(&system, x0, &mut csv)
        .unwrap_err();
    let SimulationError::Singular {
        t, quantity, state, ..
    } = &error
    else {
        panic!("{error}");
    };
    let crossing = (2.0 * (FRAC_PI_2 - 1.2)).sqrt();
    assert!(
        (t - crossing).abs() <= 0.01,
        "t = {t}, crossing at {crossing}"
    );
    assert!((state[4] - FRAC_PI_2).abs() <= 0.01, "phi = {}", state[4]);
    assert!(quantity.contains("det[A; V^T]"), "{quantity}");
    let message = error.to_string();
    println!("{message}");
    assert!(message.contains("phi = 1.57"), "{message}");
    assert!(
        message.contains("the constraint rows front, back are dependent"),
        "{message}"
    );
    // the rows before the error are kept, complete and finite: t, the
    // state, the inputs, energy, constraint_residual and chart
    let (header, rows) = parse(&csv.into_inner().unwrap());
    assert_eq!(header.len(), 1 + 8 + 2 + 2 + 1);
    assert!(rows.last().unwrap()[0] < *t);
    assert!(rows.len() >= 80);
    assert!(rows.iter().flatten().all(|v| v.is_finite()));
}

#[test]
fn the_lagrange_dalembert_form_stops_where_its_multiplier_system_degenerates() {
    let (board, _) = into_the_singularity();
    let system = Dalembert::new(&board, |_t: f64| [0.0, board.jw]);
    let mut x0 = [0.0; 10];
    x0[4] = FRAC_PI_2 - 1e-4;
    let error = Simulation::new(Rk4)
        .span(0.0, 1.0)
        .run(&system, x0, &mut Table::new())
        .unwrap_err();
    assert!(
        matches!(error, SimulationError::Singular { t: 0.0, quantity, .. } if quantity.contains("Gram")),
        "{error}"
    );
    // away from it the same system runs
    x0[4] = 0.3;
    Simulation::new(Rk4)
        .span(0.0, 0.5)
        .run(&system, x0, &mut Table::new())
        .unwrap();
}

/// The tool's basis of D for the sleigh is chosen in the body frame
/// (forward speed and turning rate), so the reduced form is regular at every
/// heading: the sleigh spinning with some forward speed turns through
/// two full turns, across `theta = +-pi/2`, in the default integrator of
/// the reduced form, the discrete gradient, which keeps its energy to
/// round-off; the Lagrange-d'Alembert form, which has no basis, agrees on
/// where it ends.
#[test]
fn the_sleigh_spins_through_every_heading_in_the_reduced_form() {
    // its centre of mass close to the blade, so the spin decays slowly
    let sleigh = Sleigh {
        a: 0.02,
        ..Sleigh::default()
    };
    let (q, qdot) = (
        [0.0, 0.0, 1.2],
        [0.1 * 1.2f64.cos(), 0.1 * 1.2f64.sin(), 3.0],
    );
    let alpha = sleigh.momenta(&q, &qdot);
    let system = Reduced::constant(&sleigh, []);
    let x0 = [q[0], q[1], q[2], alpha[0], alpha[1]];
    let mut table = Table::new();
    let summary = Simulation::new(DiscreteGradient::default())
        .span(0.0, 6.0)
        .step(0.001)
        .run(&system, x0, &mut table)
        .unwrap();
    let headings = table.column("theta").expect("recorded");
    let (lowest, highest) = headings
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &t| {
            (l.min(t), h.max(t))
        });
    assert!(
        highest - lowest >= 2.0 * std::f64::consts::TAU,
        "{lowest}..{highest}"
    );
    assert!(
        summary.energy_drift <= 1e-12,
        "energy drifted by {:e}",
        summary.energy_drift
    );
    let end = summary.state;
    let lagrange = Dalembert::constant(&sleigh, []);
    let tight = DormandPrince {
        rtol: 1e-11,
        atol: 1e-11,
        ..Default::default()
    };
    let start = [q[0], q[1], q[2], qdot[0], qdot[1], qdot[2]];
    let reference = tight.integrate(&lagrange, (0.0, start), 6.0).unwrap().x;
    for i in 0..3 {
        assert!(
            (end[i] - reference[i]).abs() <= 1e-4,
            "{end:?} vs {reference:?}"
        );
    }
}

#[test]
fn bad_settings_are_errors() {
    let model = closed_loop();
    let run = |simulation: Simulation<Rk4>, x0: [f64; 10]| {
        simulation.run(&model, x0, &mut Table::new()).unwrap_err()
    };
    let settings = |e: SimulationError| matches!(e, SimulationError::Settings { .. });
    assert!(settings(run(
        Simulation::new(Rk4).span(1.0, 1.0),
        at_rest()
    )));
    assert!(settings(run(Simulation::new(Rk4).step(0.0), at_rest())));
    assert!(settings(run(
        Simulation::new(Rk4).step(f64::NAN),
        at_rest()
    )));
    assert!(settings(run(
        Simulation::new(Rk4).record_every(0),
        at_rest()
    )));
    let mut bad = at_rest();
    bad[3] = f64::INFINITY;
    assert!(matches!(
        run(Simulation::new(Rk4), bad),
        SimulationError::Integration(chaplygin::runtime::Error::NonFinite { t: 0.0, .. })
    ));
}

#[test]
fn the_summary_reports_drift_and_residual_and_the_last_step_ends_at_t_end() {
    let mut table = Table::new();
    let summary = Simulation::new(Midpoint::default())
        .span(0.0, 1.005)
        .step(0.01)
        .record_every(10)
        .run(&closed_loop(), at_rest(), &mut table)
        .unwrap();
    assert_eq!(summary.steps, 101);
    assert_eq!(summary.t, 1.005);
    assert_eq!(table.rows.last().unwrap()[0], 1.005);
    assert_eq!(table.rows.len(), 1 + 10 + 1);
    assert!(summary.energy_drift <= 1e-13, "{}", summary.energy_drift);
    assert!(summary.max_constraint_residual <= 1e-14);
    assert!(summary.min_regularity > 0.1);
    // the discrete gradient runs the same closed loop and keeps its energy too
    let gradient = Simulation::new(DiscreteGradient::default())
        .span(0.0, 1.0)
        .run(&closed_loop(), at_rest(), &mut Table::new())
        .unwrap();
    assert!(gradient.energy_drift <= 1e-13, "{}", gradient.energy_drift);
}

#[test]
fn a_feedback_enters_the_reduced_jacobian() {
    let board = Snakeboard::default();
    // a torso damper and a wheel spring: u = (-psidot-like alpha2, -phi)
    let feedback = Feedback(|_t: f64, x: &[f64; 8]| [-0.5 * x[6], -2.0 * x[4]]);
    let system = Reduced::new(&board, feedback);
    let x = [0.1, -0.2, 0.3, 0.4, 0.5, 0.7, -0.3, 0.1];
    let jacobian = system.jacobian(0.0, &x);
    for j in 0..8 {
        let step = 1e-6;
        let (mut plus, mut minus) = (x, x);
        plus[j] += step;
        minus[j] -= step;
        let (up, down) = (system.rhs(0.0, &plus), system.rhs(0.0, &minus));
        for i in 0..8 {
            let numeric = (up[i] - down[i]) / (2.0 * step);
            assert!(
                (jacobian[i][j] - numeric).abs() <= 1e-7,
                "({i}, {j}): {} vs {numeric}",
                jacobian[i][j]
            );
        }
    }
    // and the torso feedback reaches alpha2's row: d alpha2dot / d alpha2 = -0.5
    assert!((jacobian[6][6] + 0.5).abs() <= 1e-7, "{}", jacobian[6][6]);
}
