//! Projection onto the constraint manifold after each step of the
//! Lagrange-d'Alembert equations (`chaplygin::runtime::projection`): the
//! configuration onto `f(q) = 0` through the `Holonomic` trait (a
//! hand-written planar pendulum, a point mass on a massless rod), the
//! velocity onto `ker A(q)` in the kinetic-energy metric (the built-in
//! models), and the structured error of a constraint Newton cannot meet.

use chaplygin::runtime::integrate::{Midpoint, Rk4};
use chaplygin::runtime::projection::{self, ProjectionError, Surface};
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::{Simulation, SimulationError};
use chaplygin::runtime::system::{
    Constant, Dalembert, Domain, Holonomic, LagrangeDalembert, ModelNames,
};
use chaplygin_models::sleigh::Sleigh;
use chaplygin_models::snakeboard::Snakeboard;

/// A point mass `m` at `(x, y)` on a rod of length `l` to the origin, under
/// gravity `g` along `-y`: `f(q) = x^2 + y^2 - l^2 - offset` (`offset = 0`
/// for the pendulum; `offset = -l^2 - 1` makes `f = x^2 + y^2 + 1`, which no
/// configuration meets), velocity form `x xdot + y ydot = 0`.
///
/// Lagrange-d'Alembert by hand: `m qddot = (0, -m g) + lambda (x, y)` with
/// `A qddot + Adot qdot = 0`, i.e.
/// `lambda = m (g y - |qdot|^2) / |q|^2`.
#[derive(Clone, Copy, Debug)]
struct Pendulum {
    m: f64,
    g: f64,
    l: f64,
    offset: f64,
}

const PENDULUM: Pendulum = Pendulum {
    m: 2.0,
    g: 9.81,
    l: 1.5,
    offset: 0.0,
};

impl LagrangeDalembert<2, 1, 0> for Pendulum {
    fn acceleration(&self, q: &[f64; 2], qdot: &[f64; 2], _u: &[f64; 0]) -> ([f64; 2], [f64; 1]) {
        let speed2 = qdot[0] * qdot[0] + qdot[1] * qdot[1];
        let radius2 = q[0] * q[0] + q[1] * q[1];
        let lambda = self.m * (self.g * q[1] - speed2) / radius2;
        (
            [lambda * q[0] / self.m, lambda * q[1] / self.m - self.g],
            [lambda],
        )
    }

    fn energy(&self, q: &[f64; 2], qdot: &[f64; 2]) -> f64 {
        self.m / 2.0 * (qdot[0] * qdot[0] + qdot[1] * qdot[1]) + self.m * self.g * q[1]
    }

    fn constraint_residual(&self, q: &[f64; 2], qdot: &[f64; 2]) -> [f64; 1] {
        [q[0] * qdot[0] + q[1] * qdot[1]]
    }

    fn constraint_regularity(&self, _q: &[f64; 2]) -> f64 {
        1.0
    }
}

impl Holonomic<2, 1> for Pendulum {
    fn holonomic_names(&self) -> [&str; 1] {
        ["rod"]
    }

    fn holonomic_residual(&self, q: &[f64; 2]) -> [f64; 1] {
        [q[0] * q[0] + q[1] * q[1] - self.l * self.l - self.offset]
    }

    fn holonomic_jacobian(&self, q: &[f64; 2]) -> [[f64; 2]; 1] {
        [[2.0 * q[0], 2.0 * q[1]]]
    }
}

/// No guarded expressions: the defaults.
impl Domain for Pendulum {}

impl ModelNames for Pendulum {
    fn coordinate_names(&self) -> &[&str] {
        &["x", "y"]
    }
    fn momentum_names(&self) -> &[&str] {
        &[]
    }
    fn input_names(&self) -> &[&str] {
        &[]
    }
    fn constraint_names(&self) -> &[&str] {
        &["rod_velocity"]
    }
}

/// At angle `angle` from the downward vertical, moving with angular speed
/// `omega`.
fn swinging(angle: f64, omega: f64) -> [f64; 4] {
    let (sin, cos) = angle.sin_cos();
    let l = PENDULUM.l;
    [l * sin, -l * cos, l * omega * cos, l * omega * sin]
}

#[test]
fn the_pendulum_stays_on_its_rod_and_records_the_holonomic_residual() {
    let start = swinging(1.2, 0.5);
    let mut table = Table::new();
    let summary = Simulation::new(Rk4)
        .span(0.0, 100.0)
        .step(0.005)
        .run(
            &Surface::dalembert(Dalembert::new(&PENDULUM, Constant([]))),
            start,
            &mut table,
        )
        .unwrap();
    assert_eq!(
        table.columns,
        [
            "t",
            "x",
            "y",
            "dot(x)",
            "dot(y)",
            "energy",
            "constraint_residual",
            "holonomic_residual"
        ]
    );
    assert!(
        summary.max_holonomic_residual <= 1e-12,
        "{}",
        summary.max_holonomic_residual
    );
    assert!(
        summary.max_constraint_residual <= 1e-12,
        "{}",
        summary.max_constraint_residual
    );
    let recorded = table.column("holonomic_residual").unwrap();
    assert!(recorded.iter().all(|r| *r <= 1e-12));
    // the pendulum conserves its energy up to RK4's O(h^4) error (5e-7 at
    // h = 0.01, 16 times less at h = 0.005), not a drift off the rod
    assert!(summary.energy_drift <= 1e-7, "{}", summary.energy_drift);

    // without the projection the rod stretches: the constraint is kept only
    // through its second derivative
    let free = Simulation::new(Rk4)
        .span(0.0, 100.0)
        .step(0.005)
        .run(
            &Dalembert::new(&PENDULUM, Constant([])),
            start,
            &mut Table::new(),
        )
        .unwrap();
    let [x, y, ..] = free.state;
    let stretched = (x * x + y * y - PENDULUM.l * PENDULUM.l).abs();
    assert!(stretched > 1e-9, "{stretched}");
}

/// The configuration projection lands on the circle and moves the point
/// along the gradient (the minimum-norm update of a circle is radial): the
/// projected point is `l q / |q|`, to Newton's tolerance on `f` (1e-12,
/// i.e. 1e-12 / (2 l) on the radius).
#[test]
fn the_configuration_projection_is_radial_on_a_circle() {
    let surface: Surface<_, 2, 4> = Surface::dalembert(Dalembert::new(&PENDULUM, Constant([])));
    let q = [0.7, -1.9];
    let projected = surface.project_configuration(&q).unwrap();
    let radius = q[0].hypot(q[1]);
    for (p, v) in projected.iter().zip(q) {
        assert!(
            (p - PENDULUM.l * v / radius).abs() <= 1e-12,
            "{projected:?}"
        );
    }
}

#[test]
fn a_constraint_newton_cannot_meet_is_a_structured_error_naming_it() {
    let impossible = Pendulum {
        offset: -PENDULUM.l * PENDULUM.l - 1.0,
        ..PENDULUM
    };
    let error = Simulation::new(Rk4)
        .span(0.0, 1.0)
        .step(0.01)
        .run(
            &Surface::dalembert(Dalembert::new(&impossible, Constant([]))),
            swinging(0.3, 0.0),
            &mut Table::new(),
        )
        .unwrap_err();
    match &error {
        SimulationError::Projection {
            t,
            source:
                ProjectionError::Unmet {
                    constraint,
                    residual,
                    ..
                },
        } => {
            assert!((t - 0.01).abs() < 1e-15);
            assert_eq!(constraint, "rod");
            assert!(residual.abs() >= 1.0, "{residual}");
        }
        other => panic!("{other}"),
    }
    assert!(error.to_string().contains("`rod` cannot be met"), "{error}");
}

/// The velocity projection removes exactly a multiplier's impulse: for an
/// allowed velocity `v` and any `mu`, `v + g^-1 A^T mu` projects back to
/// `v`. The sleigh's metric and blade row by hand (its kinetic energy, with
/// `a` the distance of the centre of mass ahead of the blade).
#[test]
fn the_velocity_projection_removes_an_impulse_along_the_constraint_forces() {
    let sleigh = Sleigh::default();
    let (m, inertia, a) = (sleigh.m, sleigh.inertia, sleigh.a);
    let q = [0.3, -0.2, 0.7f64];
    let (sin, cos) = q[2].sin_cos();
    let metric = [
        [m, 0.0, -m * a * sin],
        [0.0, m, m * a * cos],
        [-m * a * sin, m * a * cos, inertia + m * a * a],
    ];
    let row = [-sin, cos, 0.0];
    let allowed = [1.3 * cos, 1.3 * sin, -0.4];
    let mu = 0.8;
    let impulse = chaplygin::runtime::linalg::solve(&metric, &row.map(|r| mu * r)).unwrap();
    let disturbed: [f64; 3] = core::array::from_fn(|i| allowed[i] + impulse[i]);
    let projected = projection::dalembert_velocity::<_, 3, 1, 0>(&sleigh, &q, &disturbed).unwrap();
    for (p, v) in projected.iter().zip(allowed) {
        assert!((p - v).abs() <= 1e-14, "{projected:?} vs {allowed:?}");
    }
}

/// The snakeboard in the Lagrange-d'Alembert form, wheels locked at
/// `phi = 0.3` and circling: with the midpoint rule its constraint residual
/// reached 1.2e-3 and its energy error 55 % over 10^6 steps without
/// projection (BENCHMARKS.md); with it, the residual is round-off over 40 s
/// and the energy is kept to 1e-6 (the midpoint rule does not conserve the
/// energy of the index-reduced saddle-point equations exactly; measured
/// 4.0e-7).
#[test]
fn the_snakeboard_stays_on_its_constraints_with_the_midpoint_rule() {
    let board = Snakeboard::default();
    let phi = 0.3f64;
    let speed = 1.0;
    let q = [0.0, 0.0, 0.0, 0.0, phi];
    let qdot = [speed, 0.0, speed * phi.tan() / board.r, 0.0, 0.0];
    let start: [f64; 10] = core::array::from_fn(|i| if i < 5 { q[i] } else { qdot[i - 5] });
    let summary = Simulation::new(Midpoint::default())
        .span(0.0, 40.0)
        .step(0.01)
        .run(
            &Dalembert::new(&board, Constant([0.0, 0.0])),
            start,
            &mut Table::new(),
        )
        .unwrap();
    assert!(
        summary.max_constraint_residual <= 1e-12,
        "{}",
        summary.max_constraint_residual
    );
    assert!(summary.energy_drift <= 1e-6, "{}", summary.energy_drift);
}
