//! A compiled model with a configuration constraint, run through the path
//! the command line takes: its initial state completed by
//! `linearize::point` (coordinates from `f(q) = 0`, velocities from
//! `A(q) qdot = 0`) and each formulation kept on `f(q) = 0` by
//! `projection::Surface`.
//!
//! The model is a spherical pendulum, a bob of mass `m` held at distance
//! `l` from the origin under gravity `-g z`, in Cartesian coordinates
//! `q = (z, x, y)`: `f(q) = x^2 + y^2 + z^2 - l^2`. The constraint force is
//! radial and gravity vertical, so the energy `m |qdot|^2 / 2 + m g z` and
//! the angular momentum about the vertical `L = m (x ydot - y xdot)` are
//! conserved, and a conical motion at polar angle `theta` turns at
//! `omega^2 = g / (l cos theta)`. (The tool's momentum basis of the reduced
//! form solves the constraint row for `dot(z)`, so the runs stay below the
//! equator `z = 0`, where it degenerates.) Without the projection the
//! constraint drifts: the tests show that too.
//!
//! The momentum form needs a symmetry whose orbits with `D` span the
//! configuration space: a configuration constraint must then move along
//! the group's orbits by constants (its differential invariant). [`Trough`]
//! is one: a bead in a parabolic trough `z = a y^2 - k x` tilted down
//! along `x`, with the translations along `x` as its symmetry.

use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, Midpoint, Rk4};
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::linearize::{Compiled, OperatingPoint, PointError};
use chaplygin::runtime::nalgebra::Const;
use chaplygin::runtime::projection::Surface;
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::{Advance, Observed, Simulation, Summary};
use chaplygin::runtime::system::{Constant, Dalembert, Holonomic, Momentum, Reduced};

chaplygin::model! {
    /// A spherical pendulum in Cartesian coordinates.
    pub struct Spherical {
        coordinates: [z, x, y],
        parameters: [m = 1.5, l = 1.2, g = 9.81],
        points: [bob = origin + x*ground.x + y*ground.y + z*ground.z],
        bodies: [ball = particle(bob, m)],
        gravity: -g*ground.z,
        holonomic: [length = inner(bob - origin, bob - origin) - l^2],
    }
}

const PENDULUM: Spherical = Spherical {
    m: 1.5,
    l: 1.2,
    g: 9.81,
};

/// `z = -0.8`, `y = 0.3` and `dot(z) = 0.5`, `dot(y) = 2` given: `x` and
/// `dot(x)` solved as the command line's `--initial` solves them (an
/// energy of `-5.7 m` keeps the bob below the equator).
fn start() -> OperatingPoint {
    OperatingPoint::solve(
        &Compiled::holonomic(&PENDULUM),
        &[Some(-0.8), None, Some(0.3)],
        &[Some(0.5), None, Some(2.0)],
    )
    .unwrap()
}

/// `(q, qdot)` as arrays.
fn arrays(point: &OperatingPoint) -> ([f64; 3], [f64; 3]) {
    (
        core::array::from_fn(|i| point.q[i]),
        core::array::from_fn(|i| point.qdot[i]),
    )
}

/// `(q, qdot)` of a Lagrange-d'Alembert state.
fn lagrange_parts(x: &[f64; 6]) -> ([f64; 3], [f64; 3]) {
    (
        core::array::from_fn(|i| x[i]),
        core::array::from_fn(|i| x[3 + i]),
    )
}

/// `(q, qdot)` of a reduced state `(q, alpha)`.
fn reduced_parts(x: &[f64; 5]) -> ([f64; 3], [f64; 3]) {
    let q: [f64; 3] = core::array::from_fn(|i| x[i]);
    (q, PENDULUM.velocities(&q, &[x[3], x[4]]))
}

/// The Lagrange-d'Alembert state `(q, qdot)`.
fn lagrange_state(q: &[f64; 3], qdot: &[f64; 3]) -> [f64; 6] {
    core::array::from_fn(|i| if i < 3 { q[i] } else { qdot[i - 3] })
}

/// `|f(q)|` of `model` exceeds 1e-9 at the end of an RK4 run of `system`
/// over `span` without the projection.
fn assert_drifts_unprojected<S, M, const D: usize>(
    system: &S,
    x0: [f64; D],
    span: (f64, f64),
    model: &M,
) where
    S: Observed<[f64; D]>,
    Rk4: Advance<S, [f64; D]>,
    Const<D>: Square,
    M: Holonomic<3, 1>,
{
    let summary = Simulation::new(Rk4)
        .span(0.0, span.0)
        .step(span.1)
        .run(system, x0, &mut Table::new())
        .unwrap();
    let q: [f64; 3] = core::array::from_fn(|i| summary.state[i]);
    let drift = model.holonomic_residual(&q)[0].abs();
    assert!(drift > 1e-9, "{drift}");
}

/// `m (x ydot - y xdot)`.
fn vertical_angular_momentum(q: &[f64], qdot: &[f64]) -> f64 {
    PENDULUM.m * (q[1] * qdot[2] - q[2] * qdot[1])
}

/// The run over `t_end` with step `h`: its summary, the largest change of
/// the vertical angular momentum (from the configuration and velocity `of`
/// each recorded state), and the recorded `holonomic_residual` column.
fn run<S, I, const D: usize>(
    method: I,
    system: &S,
    x0: [f64; D],
    (t_end, h): (f64, f64),
    of: impl Fn(&[f64; D]) -> ([f64; 3], [f64; 3]),
) -> (Summary<[f64; D]>, f64, Vec<f64>)
where
    S: Observed<[f64; D]>,
    I: Advance<S, [f64; D]>,
    Const<D>: Square,
{
    let mut table = Table::new();
    let summary = Simulation::new(method)
        .span(0.0, t_end)
        .step(h)
        .run(system, x0, &mut table)
        .unwrap();
    let (q0, qdot0) = of(&x0);
    let l0 = vertical_angular_momentum(&q0, &qdot0);
    let drift = table
        .rows
        .iter()
        .map(|row| {
            let (q, qdot) = of(&core::array::from_fn(|i| row[1 + i]));
            (vertical_angular_momentum(&q, &qdot) - l0).abs()
        })
        .fold(0.0, f64::max);
    (summary, drift, table.column("holonomic_residual").unwrap())
}

/// What a run must keep: `|f(q)|` within 1e-10 at every recorded row, the
/// velocity constraint to round-off, and the energy and the vertical
/// angular momentum within the integrator's error.
fn assert_kept<const D: usize>(
    name: &str,
    (summary, momentum_drift, recorded): (Summary<[f64; D]>, f64, Vec<f64>),
    energy_bound: f64,
    momentum_bound: f64,
) {
    assert!(
        recorded.iter().all(|f| *f <= 1e-10) && summary.max_holonomic_residual <= 1e-10,
        "{name}: |f(q)| reached {}",
        summary.max_holonomic_residual
    );
    assert!(
        summary.max_constraint_residual <= 1e-13,
        "{name}: A(q) qdot reached {}",
        summary.max_constraint_residual
    );
    assert!(
        summary.energy_drift <= energy_bound,
        "{name}: energy drift {}",
        summary.energy_drift
    );
    assert!(
        momentum_drift <= momentum_bound,
        "{name}: angular momentum drift {momentum_drift}"
    );
}

/// 60 s at `h = 0.01`: about 30 swings.
const SPAN: (f64, f64) = (60.0, 0.01);

#[test]
fn the_unset_coordinate_and_velocity_are_solved_from_the_constraints() {
    let point = start();
    let (z, y, zdot, ydot) = (-0.8, 0.3, 0.5, 2.0);
    let l = PENDULUM.l;
    // on the sphere x = sqrt(l^2 - y^2 - z^2) (Newton from the generic
    // start 0.5 finds the positive root), and x xdot + y ydot + z zdot = 0
    let x = (l * l - y * y - z * z).sqrt();
    let xdot = -(y * ydot + z * zdot) / x;
    assert_eq!(point.q[0], z);
    assert_eq!(point.q[2], y);
    assert!((point.q[1] - x).abs() <= 1e-13, "{point:?} vs x = {x}");
    assert!(
        (point.qdot[1] - xdot).abs() <= 1e-12,
        "{point:?} vs dot(x) = {xdot}"
    );
    assert_eq!((point.qdot[0], point.qdot[2]), (zdot, ydot));
}

#[test]
fn an_unsatisfiable_initial_configuration_names_the_constraint_and_its_residual() {
    // y^2 + z^2 = 1.64 > l^2 = 1.44: no x meets f(q) = 0, and f >= 0.2
    let error = OperatingPoint::solve(
        &Compiled::holonomic(&PENDULUM),
        &[Some(-0.8), None, Some(1.0)],
        &[None, None, None],
    )
    .unwrap_err();
    match &error {
        PointError::HolonomicNotConverged {
            constraint,
            residual,
            ..
        } => {
            assert_eq!(constraint, "length");
            assert!(
                residual.is_finite() && *residual >= 0.2 - 1e-12,
                "{residual}"
            );
        }
        other => panic!("{other}"),
    }
    assert!(
        error.to_string().contains("`length` cannot be met"),
        "{error}"
    );
}

/// The Lagrange-d'Alembert form with RK4, the midpoint rule and
/// Dormand-Prince. Measured: energy drift 1.3e-7, 5.1e-5 (the midpoint rule
/// does not keep the energy of the index-reduced equations), 8.4e-10;
/// angular momentum 2.4e-7, 1.1e-4, 1.7e-9; `|f|` below Newton's
/// tolerance 1e-12.
#[test]
fn the_lagrange_dalembert_form_stays_on_the_sphere_with_every_integrator() {
    let (q, qdot) = arrays(&start());
    let x0 = lagrange_state(&q, &qdot);
    let kept = Surface::dalembert(Dalembert::new(&PENDULUM, Constant([])));
    assert!(kept.keeps_configuration());
    let rk4 = run(Rk4, &kept, x0, SPAN, lagrange_parts);
    assert_kept("rk4", rk4, 1e-6, 1e-6);
    let midpoint = run(Midpoint::default(), &kept, x0, SPAN, lagrange_parts);
    assert_kept("midpoint", midpoint, 5e-4, 1e-3);
    let dopri5 = run(DormandPrince::default(), &kept, x0, SPAN, lagrange_parts);
    assert_kept("dopri5", dopri5, 1e-8, 1e-8);

    // without the projection the sphere's radius drifts (measured 8e-8)
    assert_drifts_unprojected(
        &Dalembert::new(&PENDULUM, Constant([])),
        x0,
        SPAN,
        &PENDULUM,
    );
}

/// The reduced form `(q, alpha)`, its momenta rebuilt from the projected
/// velocity, with RK4, the midpoint rule, Dormand-Prince and the discrete
/// gradient. Measured: energy drift 1.2e-7, 9.6e-6, 6.1e-10, 1.6e-13 (the
/// discrete gradient keeps the energy; the projection moves it by
/// round-off only); angular momentum 2.6e-7, 7.8e-14, 1.5e-9, 2.8e-5.
#[test]
fn the_reduced_form_stays_on_the_sphere_with_every_integrator() {
    let (q, qdot) = arrays(&start());
    let alpha = PENDULUM.momenta(&q, &qdot);
    let x0 = [q[0], q[1], q[2], alpha[0], alpha[1]];
    let kept = Surface::reduced(Reduced::new(&PENDULUM, Constant([])));
    let rk4 = run(Rk4, &kept, x0, SPAN, reduced_parts);
    assert_kept("rk4", rk4, 1e-6, 1e-6);
    let midpoint = run(Midpoint::default(), &kept, x0, SPAN, reduced_parts);
    assert_kept("midpoint", midpoint, 1e-4, 1e-12);
    let dopri5 = run(DormandPrince::default(), &kept, x0, SPAN, reduced_parts);
    assert_kept("dopri5", dopri5, 1e-8, 1e-8);
    let gradient = run(DiscreteGradient::default(), &kept, x0, SPAN, reduced_parts);
    assert_kept("discrete gradient", gradient, 1e-11, 3e-4);

    // without the projection the sphere's radius drifts (measured 5e-8)
    assert_drifts_unprojected(&Reduced::new(&PENDULUM, Constant([])), x0, SPAN, &PENDULUM);
}

/// A conical motion at polar angle `theta` (from the downward vertical)
/// turns at `omega = sqrt(g / (l cos theta))` at constant height
/// `-l cos theta`: after 20 s of RK4 on the kept Lagrange-d'Alembert form
/// the bob is where the closed form puts it.
#[test]
fn a_conical_motion_keeps_its_height_and_turns_at_the_closed_form_rate() {
    let (l, g) = (PENDULUM.l, PENDULUM.g);
    let theta = 0.6f64;
    let (radius, height) = (l * theta.sin(), -l * theta.cos());
    let omega = (g / (l * theta.cos())).sqrt();
    // at x = radius, y = 0 moving along +y
    let x0 = lagrange_state(&[height, radius, 0.0], &[0.0, 0.0, radius * omega]);
    let t_end = 20.0;
    let summary = Simulation::new(Rk4)
        .span(0.0, t_end)
        .step(0.005)
        .run(
            &Surface::dalembert(Dalembert::new(&PENDULUM, Constant([]))),
            x0,
            &mut Table::new(),
        )
        .unwrap();
    let [z, x, y, ..] = summary.state;
    let angle = omega * t_end;
    let expected = [height, radius * angle.cos(), radius * angle.sin()];
    for (got, want) in [z, x, y].iter().zip(expected) {
        assert!(
            (got - want).abs() <= 1e-6,
            "{:?} vs {expected:?}",
            [z, x, y]
        );
    }
}

chaplygin::model! {
    /// A bead in a parabolic trough tilted down along `x`.
    pub struct Trough {
        coordinates: [x, y, z],
        parameters: [m = 1.0, k = 0.2, a = 2.0, g = 9.81],
        points: [bead = origin + x*ground.x + y*ground.y + z*ground.z],
        bodies: [ball = particle(bead, m)],
        gravity: -g*ground.z,
        holonomic: [trough = z - a*y^2 + k*x],
        symmetry: translation(x),
    }
}

const TROUGH: Trough = Trough {
    m: 1.0,
    k: 0.2,
    a: 2.0,
    g: 9.81,
};

/// The height is solved from `z = a y^2 - k x`, `dot(z)` from its
/// derivative; a configuration given in full off the trough is named with
/// its residual `f(q)`.
#[test]
fn the_trough_solves_the_height_and_names_a_configuration_off_it() {
    let model = Compiled::holonomic(&TROUGH);
    let (x, y, xdot, ydot) = (0.4, 0.3, -2.0, 0.5);
    let point = OperatingPoint::solve(
        &model,
        &[Some(x), Some(y), None],
        &[Some(xdot), Some(ydot), None],
    )
    .unwrap();
    let (a, k) = (TROUGH.a, TROUGH.k);
    assert!(
        (point.q[2] - (a * y * y - k * x)).abs() <= 1e-15,
        "{point:?}"
    );
    assert!(
        (point.qdot[2] - (2.0 * a * y * ydot - k * xdot)).abs() <= 1e-15,
        "{point:?}"
    );

    let z = 1.0;
    let error =
        OperatingPoint::solve(&model, &[Some(x), Some(y), Some(z)], &[None; 3]).unwrap_err();
    assert_eq!(
        error,
        PointError::HolonomicFixed {
            constraint: "trough".into(),
            residual: z - a * y * y + k * x,
        }
    );
}

/// The momentum form `(q, rdot)` (the constraint fixes the one group
/// velocity: no momenta) rebuilt from the projected configuration and
/// velocity after each step, 10 s sliding down the trough while swinging
/// across it: `|f| <= 1e-10` with RK4, the midpoint rule and
/// Dormand-Prince, the energy within each integrator's error (measured
/// 1.8e-4, 5.3e-4, 2.0e-8), and Dormand-Prince's run where the kept
/// Lagrange-d'Alembert form's is (measured 4e-8 apart).
#[test]
fn the_momentum_form_stays_in_the_trough_with_every_integrator() {
    let point = OperatingPoint::solve(
        &Compiled::holonomic(&TROUGH),
        &[Some(0.0), Some(0.3), None],
        &[Some(-2.0), Some(0.0), None],
    )
    .unwrap();
    let (q, qdot) = arrays(&point);
    let momentum = Momentum::new(&TROUGH, Constant([]));
    let x0: [f64; 5] = momentum.initial_state(&q, &qdot);
    let kept = Surface::momentum(momentum);
    let span = (10.0, 0.01);
    let of = |x: &[f64; 5]| momentum.configuration_velocity(x);
    let mut finals = Vec::new();
    for (name, (summary, _, recorded), energy_bound) in [
        ("rk4", run(Rk4, &kept, x0, span, of), 1e-3),
        (
            "midpoint",
            run(Midpoint::default(), &kept, x0, span, of),
            2e-3,
        ),
        (
            "dopri5",
            run(DormandPrince::default(), &kept, x0, span, of),
            1e-7,
        ),
    ] {
        assert!(
            recorded.iter().all(|f| *f <= 1e-10),
            "{name}: |f| reached {}",
            summary.max_holonomic_residual
        );
        assert!(
            summary.energy_drift <= energy_bound,
            "{name}: energy drift {}",
            summary.energy_drift
        );
        finals.push(summary.state);
    }
    let lagrange = Simulation::new(DormandPrince::default())
        .span(0.0, span.0)
        .step(span.1)
        .run(
            &Surface::dalembert(Dalembert::new(&TROUGH, Constant([]))),
            lagrange_state(&q, &qdot),
            &mut Table::new(),
        )
        .unwrap();
    for i in 0..3 {
        assert!(
            (finals[2][i] - lagrange.state[i]).abs() <= 1e-6,
            "{:?} vs {:?}",
            finals[2],
            lagrange.state
        );
    }

    // without the projection the trough's height drifts (measured 3.6e-8)
    assert_drifts_unprojected(&momentum, x0, span, &TROUGH);
}
