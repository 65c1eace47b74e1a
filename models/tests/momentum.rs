//! The momentum-equation items (MATH.md section 4): the snakeboard against the
//! hand derivation of MATH.md 4.1, and for every built-in model with a
//! symmetry, the momentum of trajectories of `acceleration` against
//! `momentum_rhs`; the Jacobians of `momentum_rhs` and `body_velocity`
//! against central differences.

use crate::common::{Random, rk4};
use chaplygin_models::differential_drive::DifferentialDrive;
use chaplygin_models::rolling_disk::RollingDisk;
use chaplygin_models::sleigh::Sleigh;
use chaplygin_models::snakeboard::Snakeboard;

fn close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance * (1.0 + expected.abs()),
        "{what}: {actual} vs {expected}"
    );
}

/// The tool's basis is MATH.md 4.1's `e = (cos phi, 0, sin phi / r)` (REPORT),
/// so `p` and `pdot` are 4.1's hand-derived ones.
#[test]
fn snakeboard_matches_the_hand_derivation() {
    let b = Snakeboard::default();
    let mut random = Random::new(41);
    for _ in 0..1000 {
        let r = [random.uniform(-3.0, 3.0), random.uniform(-3.0, 3.0)];
        let rdot = [random.uniform(-2.0, 2.0), random.uniform(-2.0, 2.0)];
        let p = [random.uniform(-2.0, 2.0)];
        let (sin, cos) = r[1].sin_cos();
        let (psidot, phidot, p_hand) = (rdot[0], rdot[1], p[0]);
        let delta = b.m * b.r * b.r + b.jt * sin * sin;
        let pdot_hand = b.m * b.r * b.jt * cos / delta * psidot * phidot
            + b.jt * sin * cos / delta * phidot * p_hand;
        close(b.momentum_rhs(&r, &rdot, &p)[0], pdot_hand, 1e-12, "pdot");
        let v1 = b.r * cos * (b.r * p_hand - b.jt * sin * psidot) / delta;
        let xi = b.body_velocity(&r, &rdot, &p);
        for (actual, expected) in xi.iter().zip([v1, 0.0, v1 * sin / cos / b.r]) {
            close(*actual, expected, 1e-12, "xi");
        }
    }
}

/// From MATH.md 4.1 at `p = 0`: `xi = v1 (1, 0, tan(phi) / r)` with
/// `v1 = -r cos phi Jt sin phi psidot / Delta`, so `A_nh = [[r Jt sin phi cos phi / Delta, 0],
/// [0, 0], [Jt sin^2 phi / Delta, 0]]`; the locked inertia of `e_4.1` is
/// `m cos^2 phi + J sin^2 phi / r^2 = Delta / r^2`.
#[test]
fn snakeboard_connection_and_locked_inertia() {
    let b = Snakeboard::default();
    let mut random = Random::new(44);
    for _ in 0..1000 {
        let r = [random.uniform(-3.0, 3.0), random.uniform(-3.0, 3.0)];
        let (sin, cos) = r[1].sin_cos();
        let delta = b.m * b.r * b.r + b.jt * sin * sin;
        let connection = b.nonholonomic_connection(&r);
        let expected = [
            [b.r * b.jt * sin * cos / delta, 0.0],
            [0.0, 0.0],
            [b.jt * sin * sin / delta, 0.0],
        ];
        for (row, expected_row) in connection.iter().zip(&expected) {
            for (actual, expected) in row.iter().zip(expected_row) {
                close(*actual, *expected, 1e-12, "A_nh");
            }
        }
        close(b.locked_inertia(&r)[0][0], delta / (b.r * b.r), 1e-12, "I");
    }
}

/// On D, `p_4.1 = alpha1 + (sin phi / r) alpha2` with the declared momenta
/// `alpha = (group, torso, wheels)` (MATH.md 4.1).
#[test]
fn snakeboard_momentum_on_d() {
    let b = Snakeboard::default();
    let mut random = Random::new(42);
    for _ in 0..1000 {
        let q: [f64; 5] = std::array::from_fn(|_| random.uniform(-3.0, 3.0));
        let alpha: [f64; 3] = std::array::from_fn(|_| random.uniform(-2.0, 2.0));
        let qdot = b.velocities(&q, &alpha);
        let expected = alpha[0] + q[4].sin() / b.r * alpha[1];
        close(b.momentum(&q, &qdot)[0], expected, 1e-12, "p");
    }
}

/// `H = [[0, h], [h, 0]]`, `h = m r Jt cos phi / (2 Delta)`, `K = (0, Jt sin phi cos phi / Delta)`,
/// `D = 0` (MATH.md 4.1), as printed: `jt + m r^2 - jt cos(phi)^2 = Delta`.
#[test]
fn snakeboard_report_states_h_k_d() {
    let report = Snakeboard::REPORT;
    for line in [
        "shape r = (psi, phi); momenta p1..p1",
        "e row 1: [cos(phi), 0, sin(phi)/r]",
        "H1 row 1: [0, (1/2)*m*r*jt*cos(phi)/(jt + m*r^2 - jt*cos(phi)^2)]",
        "H1 row 2: [(1/2)*m*r*jt*cos(phi)/(jt + m*r^2 - jt*cos(phi)^2), 0]",
        "K1 row 1: [0]",
        "K1 row 2: [jt*cos(phi)*sin(phi)/(jt + m*r^2 - jt*cos(phi)^2)]",
        "D1 row 1: [0]",
        "inputs enter the momentum equation: no (h B = 0)",
    ] {
        assert!(report.contains(line), "{line} in {report}");
    }
}

/// A function of `(q, qdot)`.
type OfState<'a> = dyn Fn(&[f64], &[f64]) -> Vec<f64> + 'a;
/// A function of `(r, rdot, p)`.
type OfReduced<'a> = dyn Fn(&[f64], &[f64], &[f64]) -> Vec<f64> + 'a;

/// Along a trajectory of `acceleration` (u = 0) from `velocities(q, alpha)`,
/// `p(t) = momentum(q, qdot)` satisfies `momentum_rhs` by central differences.
/// The step is small because the snakeboard's wheels spin fast (`phidot`
/// about 18 rad/s here): the differences' error is `dt^2 p''' / 6`.
fn momentum_follows_trajectory(
    n: usize,
    shape: &[usize],
    acceleration: &OfState<'_>,
    momentum: &OfState<'_>,
    rhs: &OfReduced<'_>,
    start: &[f64],
) {
    let field = |_: f64, x: &[f64]| -> Vec<f64> {
        let (q, qdot) = x.split_at(n);
        let mut derivative = qdot.to_vec();
        derivative.extend(acceleration(q, qdot));
        derivative
    };
    let (dt, steps) = (2.5e-5, 80_000);
    let states = rk4(&field, start, dt, steps);
    let momenta: Vec<Vec<f64>> = states.iter().map(|x| momentum(&x[..n], &x[n..])).collect();
    for at in (1..steps).step_by(997) {
        let (q, qdot) = states[at].split_at(n);
        let r: Vec<f64> = shape.iter().map(|&i| q[i]).collect();
        let rdot: Vec<f64> = shape.iter().map(|&i| qdot[i]).collect();
        let expected = rhs(&r, &rdot, &momenta[at]);
        for (i, expected) in expected.iter().enumerate() {
            let difference = (momenta[at + 1][i] - momenta[at - 1][i]) / (2.0 * dt);
            close(difference, *expected, 1e-7, "pdot");
        }
    }
}

fn start(q: &[f64], qdot: &[f64]) -> Vec<f64> {
    q.iter().chain(qdot).copied().collect()
}

#[test]
fn snakeboard_momentum_along_trajectories() {
    let b = Snakeboard::default();
    let q = [0.1, -0.2, 0.3, 0.4, 0.5];
    momentum_follows_trajectory(
        5,
        &[3, 4],
        &|q, qdot| {
            b.acceleration(q.try_into().unwrap(), qdot.try_into().unwrap(), &[0.0; 2])
                .0
                .to_vec()
        },
        &|q, qdot| {
            b.momentum(q.try_into().unwrap(), qdot.try_into().unwrap())
                .to_vec()
        },
        &|r, rdot, p| {
            b.momentum_rhs(
                r.try_into().unwrap(),
                rdot.try_into().unwrap(),
                p.try_into().unwrap(),
            )
            .to_vec()
        },
        &start(&q, &b.velocities(&q, &[0.7, -0.4, 0.9])),
    );
}

#[test]
fn sleigh_momentum_along_trajectories() {
    let s = Sleigh::default();
    let q = [0.1, -0.2, 0.3];
    momentum_follows_trajectory(
        3,
        &[],
        &|q, qdot| {
            s.acceleration(q.try_into().unwrap(), qdot.try_into().unwrap(), &[])
                .0
                .to_vec()
        },
        &|q, qdot| {
            s.momentum(q.try_into().unwrap(), qdot.try_into().unwrap())
                .to_vec()
        },
        &|r, rdot, p| {
            s.momentum_rhs(
                r.try_into().unwrap(),
                rdot.try_into().unwrap(),
                p.try_into().unwrap(),
            )
            .to_vec()
        },
        &start(&q, &s.velocities(&q, &[0.7, -0.4])),
    );
}

#[test]
fn rolling_disk_momentum_along_trajectories() {
    let d = RollingDisk::default();
    let q = [0.1, -0.2, 0.3, 0.4];
    momentum_follows_trajectory(
        4,
        &[3],
        &|q, qdot| {
            d.acceleration(q.try_into().unwrap(), qdot.try_into().unwrap(), &[0.0; 2])
                .0
                .to_vec()
        },
        &|q, qdot| {
            d.momentum(q.try_into().unwrap(), qdot.try_into().unwrap())
                .to_vec()
        },
        &|r, rdot, p| {
            d.momentum_rhs(
                r.try_into().unwrap(),
                rdot.try_into().unwrap(),
                p.try_into().unwrap(),
            )
            .to_vec()
        },
        &start(&q, &d.velocities(&q, &[0.7, -0.4])),
    );
}

/// The differential drive's constraints fix every group velocity: S = 0, no momenta.
#[test]
fn differential_drive_has_no_momentum() {
    let d = DifferentialDrive::default();
    let q = [0.1, -0.2, 0.3, 0.4, 0.5];
    let qdot = d.velocities(&q, &[0.7, -0.4]);
    let none: [f64; 0] = d.momentum(&q, &qdot);
    assert!(none.is_empty());
    let line =
        "shape r = (phi_r, phi_l); momenta none (S = 0: the constraints fix every group velocity)";
    assert!(
        DifferentialDrive::REPORT.contains(line),
        "{}",
        DifferentialDrive::REPORT
    );
}

/// A function of `(r, rdot, p, u)`.
type OfReducedWithInputs<'a> = dyn Fn(&[f64], &[f64], &[f64], &[f64]) -> Vec<f64> + 'a;

/// The [`Items`] of a generated model `$model` with `$n` coordinates whose
/// shape coordinates are `$shape`.
macro_rules! items {
    ($model:expr, $n:expr, $shape:expr) => {{
        let d = &$model;
        Items {
            n: $n,
            shape: $shape,
            velocities: &|q, a| {
                d.velocities(q.try_into().unwrap(), a.try_into().unwrap())
                    .to_vec()
            },
            momentum: &|q, v| {
                d.momentum(q.try_into().unwrap(), v.try_into().unwrap())
                    .to_vec()
            },
            body_velocity: &|r, v, p| {
                let (r, v, p) = (
                    r.try_into().unwrap(),
                    v.try_into().unwrap(),
                    p.try_into().unwrap(),
                );
                d.body_velocity(r, v, p).to_vec()
            },
            momentum_rhs: &|r, v, p| {
                let (r, v, p) = (
                    r.try_into().unwrap(),
                    v.try_into().unwrap(),
                    p.try_into().unwrap(),
                );
                d.momentum_rhs(r, v, p).to_vec()
            },
            input_term: &|q, u| {
                let matrix = d.momentum_input_matrix(q.try_into().unwrap());
                matrix
                    .iter()
                    .map(|row| row.iter().zip(u).map(|(a, b)| a * b).sum())
                    .collect()
            },
            acceleration: &|q, v, u| {
                let (q, v, u) = (
                    q.try_into().unwrap(),
                    v.try_into().unwrap(),
                    u.try_into().unwrap(),
                );
                d.acceleration(q, v, u).0.to_vec()
            },
            shape_acceleration: &|r, v, p, u| {
                let (r, v) = (r.try_into().unwrap(), v.try_into().unwrap());
                let (p, u) = (p.try_into().unwrap(), u.try_into().unwrap());
                d.shape_acceleration(r, v, p, u).to_vec()
            },
        }
    }};
}

/// A model's items on slices, for the checks shared by every model.
struct Items<'a> {
    n: usize,
    shape: &'a [usize],
    velocities: &'a OfState<'a>,
    momentum: &'a OfState<'a>,
    body_velocity: &'a OfReduced<'a>,
    momentum_rhs: &'a OfReduced<'a>,
    /// `momentum_input_matrix(q) u` from `(q, u)`.
    input_term: &'a OfState<'a>,
    acceleration: &'a OfReduced<'a>,
    shape_acceleration: &'a OfReducedWithInputs<'a>,
}

/// At random states on D (`qdot = velocities(q, alpha)`) and random inputs:
/// `body_velocity` rotated by `theta` is `(xdot, ydot, thetadot)`, and
/// `shape_acceleration` is the shape rows of `acceleration` (the group
/// coordinates are the first three, `se2(x, y, theta)`).
fn reconstruction_and_shape_equations(items: &Items, k: usize, p: usize) {
    let mut random = Random::new(43);
    for _ in 0..1000 {
        let q: Vec<f64> = (0..items.n).map(|_| random.uniform(-3.0, 3.0)).collect();
        let alpha: Vec<f64> = (0..k).map(|_| random.uniform(-2.0, 2.0)).collect();
        let u: Vec<f64> = (0..p).map(|_| random.uniform(-2.0, 2.0)).collect();
        let qdot = (items.velocities)(&q, &alpha);
        let momentum = (items.momentum)(&q, &qdot);
        let r: Vec<f64> = items.shape.iter().map(|&i| q[i]).collect();
        let rdot: Vec<f64> = items.shape.iter().map(|&i| qdot[i]).collect();
        let xi = (items.body_velocity)(&r, &rdot, &momentum);
        let (sin, cos) = q[2].sin_cos();
        let world = [cos * xi[0] - sin * xi[1], sin * xi[0] + cos * xi[1], xi[2]];
        for (actual, expected) in world.iter().zip(&qdot[..3]) {
            close(*actual, *expected, 1e-12, "reconstruction");
        }
        let qddot = (items.acceleration)(&q, &qdot, &u);
        let shape = (items.shape_acceleration)(&r, &rdot, &momentum, &u);
        for (actual, &i) in shape.iter().zip(items.shape) {
            close(*actual, qddot[i], 1e-12, "shape acceleration");
        }
    }
}

/// From `q0 = (0.1, -0.2, 0.3, ...)`, `qdot0 = velocities(q0, alpha)` and
/// constant inputs `u`, integrating `(g, r, rdot, p)` with
/// `gdot = R(theta) xi`, `rddot = shape_acceleration`,
/// `pdot = momentum_rhs + momentum_input_matrix(q) u` reproduces the
/// configuration of `acceleration`'s trajectory to 1e-8 over 5 s (RK4,
/// both with the same small step).
fn reduced_reproduces_full(items: &Items, alpha: &[f64], u: &[f64]) {
    let n = items.n;
    let nr = items.shape.len();
    let q0: Vec<f64> = (0..n)
        .map(|i| 0.1 * (i as f64 + 1.0) * if i % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let qdot0 = (items.velocities)(&q0, alpha);
    let full = |_: f64, x: &[f64]| -> Vec<f64> {
        let (q, qdot) = x.split_at(n);
        let mut derivative = qdot.to_vec();
        derivative.extend((items.acceleration)(q, qdot, u));
        derivative
    };
    let reduced = |_: f64, x: &[f64]| -> Vec<f64> {
        let (g, rest) = x.split_at(3);
        let (r, rest) = rest.split_at(nr);
        let (rdot, p) = rest.split_at(nr);
        let xi = (items.body_velocity)(r, rdot, p);
        let (sin, cos) = g[2].sin_cos();
        let mut derivative = vec![cos * xi[0] - sin * xi[1], sin * xi[0] + cos * xi[1], xi[2]];
        derivative.extend(rdot);
        derivative.extend((items.shape_acceleration)(r, rdot, p, u));
        let mut q = vec![0.0; n];
        q[..3].copy_from_slice(g);
        for (a, &i) in items.shape.iter().enumerate() {
            q[i] = r[a];
        }
        let forced = (items.input_term)(&q, u);
        let unforced = (items.momentum_rhs)(r, rdot, p);
        derivative.extend(unforced.iter().zip(&forced).map(|(a, b)| a + b));
        derivative
    };
    let mut start = q0[..3].to_vec();
    start.extend(items.shape.iter().map(|&i| q0[i]));
    start.extend(items.shape.iter().map(|&i| qdot0[i]));
    start.extend((items.momentum)(&q0, &qdot0));
    let (dt, steps) = (1e-4, 50_000);
    let full_states = rk4(&full, &start_of(&q0, &qdot0), dt, steps);
    let reduced_states = rk4(&reduced, &start, dt, steps);
    for (f, r) in full_states.iter().zip(&reduced_states).step_by(1250) {
        for (i, expected) in f[..3].iter().enumerate() {
            close(r[i], *expected, 1e-8, "group");
        }
        for (a, &i) in items.shape.iter().enumerate() {
            close(r[3 + a], f[i], 1e-8, "shape");
        }
    }
}

fn start_of(q: &[f64], qdot: &[f64]) -> Vec<f64> {
    q.iter().chain(qdot).copied().collect()
}

#[test]
fn snakeboard_reconstruction_and_shape_equations() {
    let b = Snakeboard::default();
    let items = items!(b, 5, &[3, 4]);
    reconstruction_and_shape_equations(&items, 3, 2);
    reduced_reproduces_full(&items, &[0.7, -0.4, 0.9], &[0.3, -0.2]);
}

#[test]
fn sleigh_reconstruction() {
    let s = Sleigh::default();
    let items = items!(s, 3, &[]);
    reconstruction_and_shape_equations(&items, 2, 0);
    reduced_reproduces_full(&items, &[0.7, -0.4], &[]);
}

#[test]
fn rolling_disk_reconstruction_and_shape_equations() {
    let d = RollingDisk::default();
    let items = items!(d, 4, &[3]);
    reconstruction_and_shape_equations(&items, 2, 2);
    reduced_reproduces_full(&items, &[0.7, -0.4], &[0.2, 0.3]);
}

#[test]
fn differential_drive_reconstruction_and_shape_equations() {
    let d = DifferentialDrive::default();
    let items = items!(d, 5, &[3, 4]);
    reconstruction_and_shape_equations(&items, 2, 2);
    reduced_reproduces_full(&items, &[0.7, -0.4], &[0.3, -0.2]);
}

/// The snakeboard gait `psi = A sin t`, `phi = B sin(t + delta)` from rest
/// (`p = 0`, at the identity) moves it; the displacement over one period from
/// the geometric-phase utility equals the full simulation's, where the
/// inputs (both on the shape) are solved at each evaluation so that
/// `acceleration` follows the gait.
#[test]
fn snakeboard_gait_displacement_matches_full_simulation() {
    use chaplygin::runtime::phase::se2_displacement;
    let b = Snakeboard::default();
    let (amplitude_psi, amplitude_phi, delta) = (0.8, 0.5, std::f64::consts::FRAC_PI_2);
    let gait = |t: f64| {
        (
            [amplitude_psi * t.sin(), amplitude_phi * (t + delta).sin()],
            [amplitude_psi * t.cos(), amplitude_phi * (t + delta).cos()],
        )
    };
    let gait_acceleration = |t: f64| [-amplitude_psi * t.sin(), -amplitude_phi * (t + delta).sin()];
    let period = 2.0 * std::f64::consts::PI;
    let steps = 20_000;
    let (displacement, _) = se2_displacement(
        gait,
        period,
        [0.0],
        |r, rdot, p| b.momentum_rhs(r, rdot, p),
        |r, rdot, p| b.body_velocity(r, rdot, p),
        steps,
    );
    let moved = displacement.total[0].hypot(displacement.total[1]);
    assert!(moved > 1e-2, "the gait moves the board: {displacement:?}");
    let field = |t: f64, x: &[f64]| -> Vec<f64> {
        let q: [f64; 5] = x[..5].try_into().unwrap();
        let qdot: [f64; 5] = x[5..].try_into().unwrap();
        let shape_rows = |u: [f64; 2]| {
            let qddot = b.acceleration(&q, &qdot, &u).0;
            [qddot[3], qddot[4]]
        };
        let free = shape_rows([0.0, 0.0]);
        let (torso, wheels) = (shape_rows([1.0, 0.0]), shape_rows([0.0, 1.0]));
        let gain = [
            [torso[0] - free[0], wheels[0] - free[0]],
            [torso[1] - free[1], wheels[1] - free[1]],
        ];
        let wanted = gait_acceleration(t);
        let u =
            chaplygin::runtime::linalg::solve(&gain, &[wanted[0] - free[0], wanted[1] - free[1]])
                .expect("the inputs move the shape independently");
        let mut derivative = qdot.to_vec();
        derivative.extend(b.acceleration(&q, &qdot, &u).0);
        derivative
    };
    let (r0, rdot0) = gait(0.0);
    let xi0 = b.body_velocity(&r0, &rdot0, &[0.0]);
    let start = [
        0.0, 0.0, 0.0, r0[0], r0[1], xi0[0], xi0[1], xi0[2], rdot0[0], rdot0[1],
    ];
    let states = rk4(&field, &start, period / steps as f64, steps);
    let last = states.last().unwrap();
    for (actual, expected) in displacement.total.iter().zip(&last[..3]) {
        close(*actual, *expected, 1e-8, "displacement");
    }
    close(last[3], r0[0], 1e-8, "the gait closes");
}

/// The sleigh has no shape: its momentum equation is the Euler-Poincare-Suslov
/// system `pdot = p^T D p`, which conserves the energy `1/2 p^T I^-1 p`
/// (`I = locked_inertia`), here to 1e-10 over 5 s of RK4, and equals the
/// energy of the configuration-space state it reconstructs.
#[test]
fn sleigh_reduced_energy_is_conserved() {
    let s = Sleigh::default();
    let inertia = s.locked_inertia(&[]);
    let energy = |p: &[f64]| {
        let omega = chaplygin::runtime::linalg::solve_positive_definite(&inertia, &[p[0], p[1]])
            .expect("the locked inertia is positive definite");
        0.5 * (p[0] * omega[0] + p[1] * omega[1])
    };
    let q = [0.1, -0.2, 0.3];
    let qdot = s.velocities(&q, &[0.7, -0.4]);
    let p0 = s.momentum(&q, &qdot);
    close(
        energy(&p0),
        s.energy(&q, &qdot),
        1e-12,
        "energy of the state",
    );
    let field = |_: f64, p: &[f64]| s.momentum_rhs(&[], &[], &[p[0], p[1]]).to_vec();
    let states = rk4(&field, &p0, 1e-3, 5000);
    for p in states.iter().step_by(500) {
        close(energy(p), energy(&p0), 1e-10, "energy");
    }
}

/// `momentum_rhs_jacobian` and `body_velocity_jacobian` of `$model` equal
/// central differences of `momentum_rhs` and `body_velocity` to 1e-7 of
/// each Jacobian's largest entry, at random arguments.
macro_rules! jacobians_match_differences {
    ($test:ident, $model:ty, $nr:literal, $mp:literal) => {
        #[test]
        fn $test() {
            let model = <$model>::default();
            let mut random = Random::new(47);
            for _ in 0..50 {
                let mut point = random.vector(2 * $nr + $mp, -1.0, 1.0);
                let split = |x: &[f64]| -> ([f64; $nr], [f64; $nr], [f64; $mp]) {
                    (
                        std::array::from_fn(|i| x[i]),
                        std::array::from_fn(|i| x[$nr + i]),
                        std::array::from_fn(|i| x[2 * $nr + i]),
                    )
                };
                let (r, rdot, p) = split(&point);
                let exact = [
                    model.momentum_rhs_jacobian(&r, &rdot, &p).concat(),
                    model.body_velocity_jacobian(&r, &rdot, &p).concat(),
                ];
                let columns = 2 * $nr + $mp;
                for (which, jacobian) in exact.iter().enumerate() {
                    let scale = jacobian.iter().fold(1e-3_f64, |m, v| m.max(v.abs()));
                    for j in 0..columns {
                        let value = |x: &[f64]| -> Vec<f64> {
                            let (r, rdot, p) = split(x);
                            match which {
                                0 => model.momentum_rhs(&r, &rdot, &p).to_vec(),
                                _ => model.body_velocity(&r, &rdot, &p).to_vec(),
                            }
                        };
                        let h = 1e-6;
                        point[j] += h;
                        let plus = value(&point);
                        point[j] -= 2.0 * h;
                        let minus = value(&point);
                        point[j] += h;
                        for (i, (a, b)) in plus.iter().zip(&minus).enumerate() {
                            let difference = (a - b) / (2.0 * h);
                            let entry = jacobian[i * columns + j];
                            assert!(
                                (entry - difference).abs() <= 1e-7 * scale,
                                "{} [{i}][{j}]: {entry} vs {difference}",
                                ["momentum_rhs_jacobian", "body_velocity_jacobian"][which]
                            );
                        }
                    }
                }
            }
        }
    };
}

jacobians_match_differences!(snakeboard_jacobians_match_differences, Snakeboard, 2, 1);
jacobians_match_differences!(sleigh_jacobians_match_differences, Sleigh, 0, 2);
jacobians_match_differences!(rolling_disk_jacobians_match_differences, RollingDisk, 1, 1);
jacobians_match_differences!(
    three_link_snake_jacobians_match_differences,
    chaplygin_models::three_link_snake::ThreeLinkSnake,
    2,
    0
);
