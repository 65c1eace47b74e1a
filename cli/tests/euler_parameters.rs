//! The Chaplygin ball turned by Euler parameters (`orient`), against
//! truths the tests compute themselves.
//!
//! The ball (radius `r`, mass `m`, principal moments `I = diag(a, b, c)`,
//! centre of mass at its centre) rolls without slipping on `z = 0`. In body
//! axes, with `omega` its angular velocity, `gamma` the upward vertical and
//! `s = -r gamma` the vector from the centre to the contact, Chaplygin's
//! angular momentum about the contact is `K = I omega + m s x (omega x s)`,
//! and the motion is `Kdot = K x omega`, `gammadot = gamma x omega`
//! (Borisov & Mamaev, "Rolling of a rigid body on a plane and sphere",
//! Regular and Chaotic Dynamics 7(2), 2002, section 2). Its first
//! integrals are the energy `1/2 omega . I omega + 1/2 m |omega x s|^2`,
//! `<K, gamma>` and `|K|^2`. The orientation's Euler parameters move with
//! `edot = 1/2 e ⊗ (0, omega)`, and the rotation matrix from body to
//! ground axes is `R(e)` of docs/MATH.md section 5.

use crate::support::chaplygin;
use crate::support::in_process::{Model, Simulated};

const BALL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../models/chaplygin_ball.model"
);
const BALL_ZXZ: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/chaplygin_ball_zxz.model"
);
const DISK: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../models/rolling_disk_euler.model"
);
const DISK_ANGLES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../models/rolling_disk_3d.model"
);
const MASS: f64 = 1.0;
const RADIUS: f64 = 0.5;
const INERTIA: [f64; 3] = [0.08, 0.1, 0.12];

type Vector = [f64; 3];

fn cross(a: Vector, b: Vector) -> Vector {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn inner(a: Vector, b: Vector) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn combined(a: Vector, s: f64, b: Vector) -> Vector {
    [0, 1, 2].map(|i| a[i] + s * b[i])
}

/// The quaternion product `p ⊗ q`.
fn product(p: [f64; 4], q: [f64; 4]) -> [f64; 4] {
    [
        p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
        p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
        p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
        p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0],
    ]
}

/// `R(e)` (body to ground axes), row-major by rows.
fn rotation([e0, e1, e2, e3]: [f64; 4]) -> [Vector; 3] {
    [
        [
            e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3,
            2.0 * (e1 * e2 - e0 * e3),
            2.0 * (e1 * e3 + e0 * e2),
        ],
        [
            2.0 * (e1 * e2 + e0 * e3),
            e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3,
            2.0 * (e2 * e3 - e0 * e1),
        ],
        [
            2.0 * (e1 * e3 - e0 * e2),
            2.0 * (e2 * e3 + e0 * e1),
            e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3,
        ],
    ]
}

/// The rotation by `angle` about axis 0, 1 or 2.
fn elementary(axis: usize, angle: f64) -> [Vector; 3] {
    let (s, c) = angle.sin_cos();
    match axis {
        0 => [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]],
        1 => [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
        _ => [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
    }
}

fn matrix_product(a: [Vector; 3], b: [Vector; 3]) -> [Vector; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The body-axes angular velocity `omega = 2 Im(conj(e) ⊗ edot)`.
fn angular_velocity(e: [f64; 4], rates: [f64; 4]) -> Vector {
    let conjugate = [e[0], -e[1], -e[2], -e[3]];
    let [_, x, y, z] = product(conjugate, rates);
    [2.0 * x, 2.0 * y, 2.0 * z]
}

/// The body-axes state of a row of a Lagrange run: `e`, `omega`, `gamma`.
fn body_state(run: &Simulated, row: usize) -> ([f64; 4], Vector, Vector) {
    let value = |name: &str| run.column(name)[row];
    let e = ["e0", "e1", "e2", "e3"].map(value);
    let rates = ["dot(e0)", "dot(e1)", "dot(e2)", "dot(e3)"].map(value);
    let upward = rotation(e)[2];
    (e, angular_velocity(e, rates), upward)
}

/// The energy, `<K, gamma>` and `|K|^2` (see the module documentation).
fn integrals(omega: Vector, gamma: Vector) -> [f64; 3] {
    let spun = [0, 1, 2].map(|i| INERTIA[i] * omega[i]);
    let arm = gamma.map(|g| -RADIUS * g);
    let moving = cross(omega, arm);
    let energy = 0.5 * inner(omega, spun) + 0.5 * MASS * inner(moving, moving);
    let momentum = combined(spun, MASS, cross(arm, moving));
    [energy, inner(momentum, gamma), inner(momentum, momentum)]
}

/// `omega` from Chaplygin's momentum: `K = (I + m r^2 (1 - gamma gamma^T)) omega`.
fn omega_of(momentum: Vector, gamma: Vector) -> Vector {
    let mr2 = MASS * RADIUS * RADIUS;
    let m: [Vector; 3] = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let diagonal = if i == j { INERTIA[i] + mr2 } else { 0.0 };
            diagonal - mr2 * gamma[i] * gamma[j]
        })
    });
    let determinant = inner(m[0], cross(m[1], m[2]));
    let columns = [cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1])];
    [0, 1, 2].map(|i| inner(columns[i], momentum) / determinant)
}

/// The state `(K, gamma, e, x, y)` of the independent integration.
type Chaplygin = (Vector, Vector, [f64; 4], f64, f64);

fn rate((momentum, gamma, e, _, _): &Chaplygin) -> [f64; 13] {
    let omega = omega_of(*momentum, *gamma);
    let [_, e1, e2, e3] = product(*e, [0.0, omega[0], omega[1], omega[2]]);
    let e0 = -0.5 * inner([e[1], e[2], e[3]], omega);
    let ground = rotation(*e).map(|row| inner(row, omega));
    let velocity = cross(ground, [0.0, 0.0, RADIUS]);
    let k = cross(*momentum, omega);
    let g = cross(*gamma, omega);
    [
        k[0],
        k[1],
        k[2],
        g[0],
        g[1],
        g[2],
        e0,
        0.5 * e1,
        0.5 * e2,
        0.5 * e3,
        velocity[0],
        velocity[1],
        0.0,
    ]
}

fn flat((k, g, e, x, y): &Chaplygin) -> [f64; 13] {
    [
        k[0], k[1], k[2], g[0], g[1], g[2], e[0], e[1], e[2], e[3], *x, *y, 0.0,
    ]
}

fn unflat(v: [f64; 13]) -> Chaplygin {
    (
        [v[0], v[1], v[2]],
        [v[3], v[4], v[5]],
        [v[6], v[7], v[8], v[9]],
        v[10],
        v[11],
    )
}

/// One classical Runge-Kutta step of length `h`.
fn step(state: &Chaplygin, h: f64) -> Chaplygin {
    let at =
        |base: [f64; 13], k: [f64; 13], s: f64| unflat(std::array::from_fn(|i| base[i] + s * k[i]));
    let base = flat(state);
    let k1 = rate(state);
    let k2 = rate(&at(base, k1, h / 2.0));
    let k3 = rate(&at(base, k2, h / 2.0));
    let k4 = rate(&at(base, k3, h));
    unflat(std::array::from_fn(|i| {
        base[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    }))
}

/// The ball started at the z-x-z angles (0.3, 0.5, 0.7) turning at
/// (1, 1.6, 2.2) rad/s in its own axes.
const START: [&str; 4] = [
    "--initial",
    "angles(ball, zxz)=[0.3, 0.5, 0.7]",
    "--initial",
    "omega(ball)=[1, 1.6, 2.2]",
];

/// The z-x-z ball's angles (psi, theta, phi) = (0.3, 0.5, 0.7).
const ZXZ_ANGLES: [&str; 6] = [
    "--initial",
    "psi=0.3",
    "--initial",
    "theta=0.5",
    "--initial",
    "phi=0.7",
];

fn run(model: &Model, options: &[&str]) -> Simulated {
    let run = model.simulate(options).expect("the options are taken");
    assert!(run.outcome.is_ok(), "{:?}", run.outcome);
    run
}

/// The three first integrals, computed from the trajectory's `e` and
/// `dot(e)`, hold to 1e-6 over 20 s; and the ball's centre and
/// orientation follow Chaplygin's equations integrated here by RK4 at
/// 1e-3 s to 1e-6.
#[test]
fn the_ball_keeps_its_integrals_and_follows_chaplygins_equations() {
    let ball = Model::load(BALL, "jit");
    let options = [
        &START[..],
        &[
            "--formulation",
            "lagrange",
            "--integrator",
            "dopri5",
            "--t-end",
            "20",
        ],
    ]
    .concat();
    let run = run(ball, &options);
    let (e, omega, gamma) = body_state(&run, 0);
    let first = integrals(omega, gamma);
    for row in 0..run.rows.len() {
        let (_, omega, gamma) = body_state(&run, row);
        for (found, expected) in integrals(omega, gamma).iter().zip(first) {
            assert!(
                (found - expected).abs() < 1e-6,
                "row {row}: {found} vs {expected}"
            );
        }
    }
    let spun = [0, 1, 2].map(|i| INERTIA[i] * omega[i]);
    let arm = gamma.map(|g| -RADIUS * g);
    let momentum = combined(spun, MASS, cross(arm, cross(omega, arm)));
    let mut state: Chaplygin = (momentum, gamma, e, 0.0, 0.0);
    let (times, x, y) = (run.column("t"), run.column("x"), run.column("y"));
    let mut t = 0.0;
    for (row, &time) in times.iter().enumerate() {
        while t < time - 1e-9 {
            state = step(&state, 1e-3);
            t += 1e-3;
        }
        let (_, _, e, x_here, y_here) = state;
        assert!(
            (x[row] - x_here).abs() < 1e-6,
            "t = {time}: x {} vs {x_here}",
            x[row]
        );
        assert!(
            (y[row] - y_here).abs() < 1e-6,
            "t = {time}: y {} vs {y_here}",
            y[row]
        );
        let found = ["e0", "e1", "e2", "e3"].map(|name| run.column(name)[row]);
        for (a, b) in found.iter().zip(e) {
            assert!((a - b).abs() < 1e-6, "t = {time}: e {found:?} vs {e:?}");
        }
    }
}

/// The same motion declared with z-x-z Euler angles: the centres agree to
/// 1e-6 over 3 s, where theta stays away from 0.
#[test]
fn the_quaternion_ball_moves_as_the_euler_angle_ball() {
    let options = [
        "--formulation",
        "lagrange",
        "--integrator",
        "dopri5",
        "--t-end",
        "3",
    ];
    let quaternion = run(Model::load(BALL, "jit"), &[&START[..], &options].concat());
    let turning = ["--initial", "omega(ball)=[1, 1.6, 2.2]"];
    let euler = run(
        Model::load(BALL_ZXZ, "interpret"),
        &[&ZXZ_ANGLES[..], &turning, &options].concat(),
    );
    assert_eq!(quaternion.rows.len(), euler.rows.len());
    for name in ["x", "y"] {
        for (a, b) in quaternion.column(name).iter().zip(euler.column(name)) {
            assert!((a - b).abs() < 1e-6, "{name}: {a} vs {b}");
        }
    }
}

/// Rolling about its smallest principal axis, horizontal along ground x
/// at -2 rad/s, from theta = 0.2: the ball passes through the z-x-z
/// singular orientation theta = 0 at t = 0.1, its centre moving at 1 m/s
/// along y with `e = (cos(theta/2), sin(theta/2), 0, 0)`,
/// `theta = 0.2 - 2 t`. Every integrator keeps the unit norm to 1e-10 and
/// follows that motion to 1e-6; the Lagrange runs keep the integrals.
#[test]
fn every_integrator_runs_through_the_euler_angles_singular_orientation() {
    let ball = Model::load(BALL, "jit");
    for (formulation, integrator) in [
        ("lagrange", "dopri5"),
        ("lagrange", "rk4"),
        ("lagrange", "midpoint"),
        ("reduced", "discrete-gradient"),
    ] {
        let options = [
            "--initial",
            "angles(ball, zxz)=[0, 0.2, 0]",
            "--initial",
            "omega(ball)=[-2, 0, 0]",
            "--formulation",
            formulation,
            "--integrator",
            integrator,
            "--t-end",
            "0.5",
        ];
        let run = run(ball, &options);
        let residual = run.column("holonomic_residual");
        assert!(
            residual.iter().all(|r| r.abs() < 1e-10),
            "{integrator}: {residual:?}"
        );
        for (row, &t) in run.column("t").iter().enumerate() {
            let theta: f64 = 0.2 - 2.0 * t;
            let expected = [(theta / 2.0).cos(), (theta / 2.0).sin(), 0.0, 0.0, 0.0, t];
            let names = ["e0", "e1", "e2", "e3", "x", "y"];
            for (name, value) in names.iter().zip(expected) {
                let found = run.column(name)[row];
                assert!(
                    (found - value).abs() < 1e-6,
                    "{integrator} t = {t}: {name} {found} vs {value}"
                );
            }
            if formulation == "lagrange" {
                let (_, omega, gamma) = body_state(&run, row);
                let first = integrals([-2.0, 0.0, 0.0], [0.0, (0.2f64).sin(), (0.2f64).cos()]);
                for (found, expected) in integrals(omega, gamma).iter().zip(first) {
                    assert!(
                        (found - expected).abs() < 1e-6,
                        "{integrator} t = {t}: {found} vs {expected}"
                    );
                }
            }
        }
    }
}

/// The angular velocity (0.3, -0.7, 1.9) asked, and a Lagrange run's
/// first rows.
const TURNING: [&str; 6] = [
    "--initial",
    "omega(ball)=[0.3, -0.7, 1.9]",
    "--formulation",
    "lagrange",
    "--t-end",
    "0.01",
];

/// `angles(ball, SEQ)` gives the rotation composed of the sequence's
/// elementary rotations (intrinsic: `R = R_1(a) R_2(b) R_3(c)`), and
/// `omega(ball)` the angular velocity asked, read from the first row's `e`
/// and `dot(e)`; on the z-x-z ball, `omega(ball)` sets the angles' rates
/// of the textbook map `omega = (psidot sin theta sin phi + thetadot cos phi,
/// psidot sin theta cos phi - thetadot sin phi, psidot cos theta + phidot)`.
#[test]
fn omega_and_angles_set_the_frames_state() {
    let ball = Model::load(BALL, "interpret");
    let angles = [0.4, -1.1, 2.3];
    for (sequence, axes) in [
        ("zxz", [2, 0, 2]),
        ("zyx", [2, 1, 0]),
        ("xyz", [0, 1, 2]),
        ("zyz", [2, 1, 2]),
    ] {
        let given = format!("angles(ball, {sequence})=[0.4, -1.1, 2.3]");
        let run = run(ball, &[&["--initial", &given][..], &TURNING].concat());
        let (e, omega, _) = body_state(&run, 0);
        let composed = (0..3).fold(elementary(0, 0.0), |r, k| {
            matrix_product(r, elementary(axes[k], angles[k]))
        });
        let found = rotation(e);
        for (i, j) in (0..3).flat_map(|i| (0..3).map(move |j| (i, j))) {
            assert!(
                (found[i][j] - composed[i][j]).abs() < 1e-12,
                "{sequence}: R[{i}][{j}]"
            );
        }
        for (found, asked) in omega.iter().zip([0.3, -0.7, 1.9]) {
            assert!((found - asked).abs() < 1e-12, "{sequence}: omega {omega:?}");
        }
    }
    let euler = Model::load(BALL_ZXZ, "interpret");
    let run = run(euler, &[&ZXZ_ANGLES[..], &TURNING].concat());
    let [psi, theta, phi] = ["dot(psi)", "dot(theta)", "dot(phi)"].map(|name| run.column(name)[0]);
    let (st, ct, sp, cp) = (0.5f64.sin(), 0.5f64.cos(), 0.7f64.sin(), 0.7f64.cos());
    let omega = [
        psi * st * sp + theta * cp,
        psi * st * cp - theta * sp,
        psi * ct + phi,
    ];
    for (found, asked) in omega.iter().zip([0.3, -0.7, 1.9]) {
        assert!((found - asked).abs() < 1e-8, "omega {omega:?}");
    }
}

/// Each mistake in a frame's state is one line naming the flag.
#[test]
fn a_frames_state_that_cannot_be_met_is_one_line() {
    for (model, given, expected) in [
        (
            BALL,
            "omega(bal)=[1, 2, 3]",
            "error: --initial omega(bal): unknown frame `bal` (frames: ball)",
        ),
        (
            BALL,
            "angles(ball, zzx)=[1, 2, 3]",
            "error: --initial angles(ball, zzx): `zzx` is no sequence of three axes",
        ),
        (
            BALL,
            "omega(ball)=[1, 2]",
            "error: --initial omega(ball)=[1, 2]: expected three values `[a, b, c]`",
        ),
        (
            BALL_ZXZ,
            "angles(ball, zxz)=[1, 2, 3]",
            "error: --initial angles(ball, zxz): `ball` is not an `orient` frame",
        ),
        (
            BALL_ZXZ,
            "omega(nutation)=[1, 2, 3]",
            "error: --initial omega(nutation): the rotations from `ground` to `nutation` read 2 coordinates (theta, psi)",
        ),
        (
            BALL_ZXZ,
            "omega(ball)=[1, 2, 3]",
            "error: --initial omega(ball): the rates of phi, theta, psi do not turn `ball` about every axis here",
        ),
    ] {
        let output = chaplygin(&[
            "simulate",
            model,
            "--engine",
            "interpret",
            "--initial",
            given,
            "--t-end",
            "0.01",
        ]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{given}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.starts_with(expected), "{stderr}");
    }
}

/// The rolling disk turned by Euler parameters against the same disk in
/// heading, lean and spin angles (`rolling_disk_3d.model`, contact point
/// `(x, y)`, centre `contact + r (sin(psi) sin(phi), -cos(psi) sin(phi),
/// cos(phi))`): from lean 0.3 and one angular velocity, the centres agree
/// to 1e-8 over 3 s, the energies at the start to round-off (each run
/// keeps its own to 1e-8), and the unit norm and the contact's height hold
/// to 1e-10.
#[test]
fn the_quaternion_disk_rolls_as_the_euler_angle_disk() {
    let options = [
        "--initial",
        "omega(disk)=[0.5, 4, 1]",
        "--integrator",
        "dopri5",
        "--t-end",
        "3",
    ];
    let start = [
        "--initial",
        "angles(disk, zxy)=[0, 0.3, 0]",
        "--initial",
        "x=0",
        "--initial",
        "y=0",
    ];
    let quaternion = run(Model::load(DISK, "jit"), &[&start[..], &options].concat());
    let angles = run(
        Model::load(DISK_ANGLES, "jit"),
        &[&["--initial", "phi=0.3"][..], &options].concat(),
    );
    let residual = quaternion.column("holonomic_residual");
    assert!(residual.iter().all(|r| r.abs() < 1e-10), "{residual:?}");
    let radius = 0.5;
    let (psi, phi) = (angles.column("psi"), angles.column("phi"));
    let (x, y) = (angles.column("x"), angles.column("y"));
    let centre = |i: usize| {
        let (s, c) = (psi[i].sin_cos(), phi[i].sin_cos());
        [
            x[i] + radius * s.0 * c.0,
            y[i] - radius * s.1 * c.0,
            radius * c.1,
        ]
    };
    let found = [
        quaternion.column("x"),
        quaternion.column("y"),
        quaternion.column("z"),
    ];
    assert_eq!(quaternion.rows.len(), angles.rows.len());
    // The angle disk's contact starts at the origin, the quaternion disk's
    // centre: the centres' displacements agree, and their heights.
    let (first, origin) = (centre(0), [0.0, 0.0, 0.0]);
    for i in 0..angles.rows.len() {
        let expected = centre(i);
        for axis in 0..3 {
            let moved = if axis == 2 {
                expected[2]
            } else {
                expected[axis] - first[axis]
            };
            let found = found[axis][i] - origin[axis];
            assert!(
                (found - moved).abs() < 1e-8,
                "row {i} axis {axis}: {found} vs {moved}"
            );
        }
    }
    let (a, b) = (quaternion.column("energy"), angles.column("energy"));
    let by_hand = disk_energy(0.3, [0.5, 4.0, 1.0]);
    assert!(
        (a[0] / by_hand - 1.0).abs() < 1e-12,
        "energy {} vs {by_hand}",
        a[0]
    );
    // Measured 1.3e-11: the angles' start is solved through their own rates.
    assert!(
        (b[0] / by_hand - 1.0).abs() < 1e-10,
        "energy {} vs {by_hand}",
        b[0]
    );
    for energy in [&a, &b] {
        let drift = energy
            .iter()
            .map(|e| (e - energy[0]).abs())
            .fold(0.0, f64::max);
        assert!(drift < 1e-8 * energy[0], "drift {drift}");
    }
}

/// The energy of the uniform disk (mass 1, radius 0.5, g = 9.81) at lean
/// `phi` turning at `omega` in its body axes (axle y): the contact is
/// `s = -r d / |d|` from the centre, `d` the upward vertical's part in the
/// disk's plane, the centre moves at `-omega x s`, and the centre's height
/// is `r cos(phi)`.
fn disk_energy(phi: f64, omega: Vector) -> f64 {
    let (m, r, g) = (1.0, 0.5, 9.81);
    let up = [0.0, phi.sin(), phi.cos()];
    let length = up[0].hypot(up[2]);
    let contact = [-r * up[0] / length, 0.0, -r * up[2] / length];
    let velocity = cross(contact, omega);
    let moments = [m * r * r / 4.0, m * r * r / 2.0, m * r * r / 4.0];
    let spin: f64 = (0..3).map(|i| moments[i] * omega[i] * omega[i]).sum();
    (m * inner(velocity, velocity) + spin) / 2.0 + m * g * r * phi.cos()
}
