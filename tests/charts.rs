//! Chart switching in the reduced form (docs/guide/simulating.md, "Chart switching"): the
//! sleigh declared without its symmetry has a basis of D solved for
//! `dot(y)`, singular at `theta = +-pi/2` where the blade's row is regular.
//! Its reduced form runs through those headings by switching to the chart
//! solved for `dot(x)` and back, keeping the energy to the discrete
//! gradient's round-off and the constraint, and its trajectory is the
//! Lagrange-d'Alembert equations' (an independent formulation, with
//! multipliers and no basis of D) to the integrator's second order.

use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince};
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::{Simulation, Summary};
use chaplygin::runtime::system::{Dalembert, Reduced, ReducedPortHamiltonian};
use std::f64::consts::FRAC_PI_2;

chaplygin::model! {
    /// The sleigh of `tests/models/sleigh_no_symmetry.model`: no symmetry
    /// declared, the centre of mass close to the blade.
    pub struct SleighNoSymmetry {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.05],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

/// Backwards at 0.2 along the heading 0, turning at 3 rad/s: the sleigh
/// turns through 11 rad (the crossings of `pi/2 + j pi` up to `j = 3`)
/// before its forward speed takes over.
const Q0: [f64; 3] = [0.0, 0.0, 0.0];
const QDOT0: [f64; 3] = [-0.2, 0.0, 3.0];
const T_END: f64 = 20.0;

/// The reduced form's run with the discrete gradient at step `h`.
fn reduced_run(h: f64) -> (Summary<[f64; 5]>, Table) {
    let sleigh = SleighNoSymmetry::default();
    let alpha = sleigh.momenta(&Q0, &QDOT0);
    let x0 = [Q0[0], Q0[1], Q0[2], alpha[0], alpha[1]];
    let mut table = Table::new();
    let summary = Simulation::new(DiscreteGradient::default())
        .span(0.0, T_END)
        .step(h)
        .record_every((0.01 / h).round() as usize)
        .run(&Reduced::constant(&sleigh, []), x0, &mut table)
        .expect("the reduced form runs through theta = pi/2 by changing charts");
    (summary, table)
}

/// The configurations `(x, y, theta)` of a table's rows.
fn configurations(table: &Table) -> Vec<[f64; 3]> {
    let columns = ["x", "y", "theta"].map(|name| table.column(name).expect("recorded"));
    (0..table.rows.len())
        .map(|i| columns.each_ref().map(|column| column[i]))
        .collect()
}

/// The Lagrange-d'Alembert equations with Dormand-Prince at tolerances
/// 1e-12, recorded every 0.01.
fn reference() -> Vec<[f64; 3]> {
    let sleigh = SleighNoSymmetry::default();
    let x0 = [Q0[0], Q0[1], Q0[2], QDOT0[0], QDOT0[1], QDOT0[2]];
    let method = DormandPrince {
        rtol: 1e-12,
        atol: 1e-12,
        ..DormandPrince::default()
    };
    let mut table = Table::new();
    Simulation::new(method)
        .span(0.0, T_END)
        .step(0.01)
        .run(&Dalembert::constant(&sleigh, []), x0, &mut table)
        .expect("the Lagrange-d'Alembert equations are regular everywhere");
    configurations(&table)
}

/// The largest distance between two runs' configurations at equal times.
fn largest_difference(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, r)| p.iter().zip(r).map(|(p, r)| (p - r).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn the_sleigh_without_symmetry_has_a_second_chart_solved_for_xdot() {
    assert_eq!(SleighNoSymmetry::CHARTS, [[1], [0]]);
    let sleigh = SleighNoSymmetry::default();
    assert_eq!(sleigh.charts(), 2);
    let x = [0.0, 0.0, 1.2, 0.5, 0.3];
    assert!((sleigh.chart_fit(0, &x) - 1.2f64.cos()).abs() < 1e-15);
    assert!((sleigh.chart_fit(1, &x) - 1.2f64.sin()).abs() < 1e-15);
    // the map between the charts keeps the velocity: alpha are the
    // independent speeds, (xdot, thetadot) in chart 0, (ydot, thetadot) in 1
    let moved = sleigh.change_chart(0, 1, &x);
    assert!((moved[3] - 0.5 * 1.2f64.tan()).abs() < 1e-15);
    assert_eq!(moved[4], 0.3);
    let back = sleigh.change_chart(1, 0, &moved);
    assert!((back[3] - 0.5).abs() < 1e-15);
    // both charts' energies agree on the same motion
    assert!((sleigh.chart_hamiltonian(0, &x) - sleigh.chart_hamiltonian(1, &moved)).abs() < 1e-15);
}

#[test]
fn the_reduced_form_switches_charts_through_the_singular_headings() {
    let (summary, table) = reduced_run(0.01);
    let theta = table.column("theta").expect("recorded");
    let crossings = (0..4)
        .filter(|j| {
            theta
                .iter()
                .any(|&t| t > FRAC_PI_2 + *j as f64 * std::f64::consts::PI)
        })
        .count();
    assert_eq!(crossings, 4, "theta reaches {:?}", theta.last());
    // one switch into the dot(x) chart near each crossing, one back after
    assert!(summary.chart_switches >= 2 * crossings - 1, "{summary:?}");
    let charts = table.column("chart").expect("a chart column");
    let recorded_switches = charts.windows(2).filter(|w| w[0] != w[1]).count();
    assert_eq!(recorded_switches, summary.chart_switches);
    assert!(summary.energy_drift < 1e-12, "{summary:?}");
    assert!(summary.max_constraint_residual < 1e-9, "{summary:?}");
}

/// The discrete gradient is of order 2: halving the step divides the
/// distance to the reference by about 4 (by at least 3.5 here), and the
/// Richardson extrapolation `(4 fine - coarse) / 3` of the two runs is
/// closer still, so the difference is the integrator's truncation error
/// and the chart changes add none of their own. At `h = 0.01` the
/// distance is 2.8e-2 after 20 s and 13 m of travel.
#[test]
fn the_reduced_trajectory_is_the_lagrange_dalembert_one() {
    let reference = reference();
    let coarse = configurations(&reduced_run(0.01).1);
    let fine = configurations(&reduced_run(0.005).1);
    let extrapolated: Vec<[f64; 3]> = coarse
        .iter()
        .zip(&fine)
        .map(|(c, f)| core::array::from_fn(|i| (4.0 * f[i] - c[i]) / 3.0))
        .collect();
    let coarse = largest_difference(&coarse, &reference);
    let fine = largest_difference(&fine, &reference);
    let extrapolated = largest_difference(&extrapolated, &reference);
    assert!(coarse < 5e-2, "{coarse:e}");
    assert!(fine < coarse / 3.5, "{fine:e} vs {coarse:e}");
    assert!(extrapolated < fine / 10.0, "{extrapolated:e} vs {fine:e}");
}

#[test]
fn a_run_that_needs_no_switch_reports_none() {
    let sleigh = SleighNoSymmetry::default();
    let alpha = sleigh.momenta(&Q0, &[1.0, 0.0, 0.2]);
    let summary = Simulation::new(DiscreteGradient::default())
        .span(0.0, 2.0)
        .run(
            &Reduced::constant(&sleigh, []),
            [0.0, 0.0, 0.0, alpha[0], alpha[1]],
            &mut Table::new(),
        )
        .expect("runs");
    assert_eq!(summary.chart_switches, 0);
}

/// Started on a singular heading of chart 0, the run starts in chart 1.
#[test]
fn a_run_starts_in_the_chart_that_fits_best() {
    let sleigh = SleighNoSymmetry::default();
    let system = Reduced::constant(&sleigh, []);
    let x0: [f64; 5] = system.initial_state(&[0.0, 0.0, FRAC_PI_2], &[0.0, 1.0, 1.0]);
    assert_eq!(system.chart(), 1);
    assert_eq!(x0[3..], [1.0, 1.0]);
    let summary = Simulation::new(DiscreteGradient::default())
        .span(0.0, 1.0)
        .run(&system, x0, &mut Table::new())
        .expect("runs from the singular heading of chart 0");
    assert!(summary.energy_drift < 1e-12, "{summary:?}");
}

/// The run-time chart solved for `dot(y)` ([`chaplygin::runtime::partition`],
/// numbered after the derived charts by its dependent speeds) is chart 0
/// computed numerically from `A(q)`, `g(q)`, the accelerations and the
/// energy: at random states its flow and energy equal the reduced form's
/// exact items (derived in normal form) to round-off, its energy gradient
/// to the central differences' 1e-8, and its structure matrix is
/// skew-symmetric with `Jbar dH/dx` the flow.
#[test]
fn a_run_time_chart_is_a_derived_chart_computed_numerically() {
    use chaplygin::runtime::partition::index_of;
    let sleigh = SleighNoSymmetry::default();
    let runtime = sleigh.charts() + index_of(3, &[1]);
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for _ in 0..50 {
        let x: [f64; 5] = core::array::from_fn(|_| 1.4 * uniform());
        let close = |a: f64, b: f64, tolerance: f64| (a - b).abs() <= tolerance * b.abs().max(1.0);
        let (flow, exact) = (
            sleigh.chart_rhs(runtime, &x, &[]),
            sleigh.reduced_rhs(&x, &[]),
        );
        assert!(
            (0..5).all(|i| close(flow[i], exact[i], 1e-12)),
            "{flow:?} vs {exact:?}"
        );
        assert!(close(
            sleigh.chart_hamiltonian(runtime, &x),
            sleigh.hamiltonian(&x),
            1e-14
        ));
        let gradient = sleigh.chart_hamiltonian_gradient(runtime, &x);
        let exact = sleigh.hamiltonian_gradient(&x);
        assert!(
            (0..5).all(|i| close(gradient[i], exact[i], 1e-8)),
            "{gradient:?} vs {exact:?}"
        );
        let j = sleigh.chart_structure_matrix(runtime, &x);
        assert!((0..5).all(|a| (0..5).all(|b| j[a][b] == -j[b][a])));
        for (i, row) in j.iter().enumerate() {
            let applied: f64 = row.iter().zip(&gradient).map(|(a, b)| a * b).sum();
            assert!(
                close(applied, flow[i], 1e-8),
                "row {i}: {applied} vs {}",
                flow[i]
            );
        }
        assert!(sleigh.chart_fit(runtime, &x) > 0.0);
    }
}

/// The discrete gradient in a run-time chart keeps the energy to
/// round-off, and follows the Lagrange-d'Alembert reference to its second
/// order (the distance falls about 4 times when the step halves), for the
/// 0.4 s the sleigh turns before this chart's singular heading `pi/2`.
#[test]
fn the_discrete_gradient_keeps_the_energy_in_a_run_time_chart() {
    use chaplygin::runtime::integrate::FixedStep;
    use chaplygin::runtime::partition::index_of;
    use chaplygin::runtime::system::Energy;
    let sleigh = SleighNoSymmetry::default();
    let runtime = sleigh.charts() + index_of(3, &[1]);
    let reference = reference();
    let distance = |h: f64| {
        let system = Reduced::constant(&sleigh, []);
        let x0: [f64; 5] = system.initial_state(&Q0, &QDOT0);
        let mut x = sleigh.change_chart(system.chart(), runtime, &x0);
        system.set_chart(runtime);
        let energy = system.energy(&x);
        let steps = (0.4 / h).round() as usize;
        for i in 0..steps {
            x = DiscreteGradient::default()
                .step(&system, i as f64 * h, &x, h)
                .expect("a step");
            assert!((system.energy(&x) - energy).abs() < 1e-13 * energy);
        }
        // the reference is recorded every 0.01 s: its row at t = 0.4
        (0..3)
            .map(|i| (x[i] - reference[40][i]).abs())
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (distance(0.01), distance(0.005));
    assert!(coarse < 1e-3 && fine < coarse / 3.5, "{coarse:e}, {fine:e}");
}
