//! Every built-in model's reduced port-Hamiltonian items (MATH.md section 3)
//! against model-independent facts: the velocities of any momenta satisfy the
//! constraints and map back to them, `dHbar/dt = y . u`, and the symbolic
//! derivatives agree with central differences. A new built-in model joins by
//! one `reduced_model!` line and one test calling `check_reduced_model`.

use crate::common::{Random, check_reduced_model, rk4};
use chaplygin_models::{
    differential_drive::DifferentialDrive, rolling_disk::RollingDisk, sleigh::Sleigh,
    snakeboard::Snakeboard,
};

reduced_model!(Snakeboard);
reduced_model!(Sleigh);
reduced_model!(RollingDisk);
reduced_model!(DifferentialDrive);

/// phi away from +-pi/2, where the paper's basis of D degenerates.
fn snakeboard_configuration(random: &mut Random) -> Vec<f64> {
    let mut q = random.vector(5, -3.0, 3.0);
    q[4] = random.uniform(-1.4, 1.4);
    q
}

/// theta away from +-pi/2, where the tool's basis `(1, tan theta, 0)` degenerates.
fn sleigh_configuration(random: &mut Random) -> Vec<f64> {
    let mut q = random.vector(3, -3.0, 3.0);
    q[2] = random.uniform(-1.4, 1.4);
    q
}

#[test]
fn the_snakeboards_reduced_items_are_consistent() {
    let board = Snakeboard {
        m: 1.7,
        r: 0.4,
        jt: 0.2,
        jw: 0.07,
    };
    check_reduced_model(&board, 1, &snakeboard_configuration);
    check_reduced_model(&Snakeboard::default(), 2, &snakeboard_configuration);
}

#[test]
fn the_sleighs_reduced_items_are_consistent() {
    let sleigh = Sleigh {
        m: 2.3,
        inertia: 0.4,
        a: -0.3,
    };
    check_reduced_model(&sleigh, 3, &sleigh_configuration);
    check_reduced_model(&Sleigh::default(), 4, &sleigh_configuration);
}

/// The heading (coordinate 2) away from +-pi/2, where the tool's bases for
/// the disk and the robot, with `dot(x)` independent, may divide by `cos theta`.
fn heading_configuration(n: usize) -> impl Fn(&mut Random) -> Vec<f64> {
    move |random| {
        let mut q = random.vector(n, -3.0, 3.0);
        q[2] = random.uniform(-1.4, 1.4);
        q
    }
}

#[test]
fn the_rolling_disks_reduced_items_are_consistent() {
    check_reduced_model(&RollingDisk::default(), 5, &heading_configuration(4));
}

#[test]
fn the_differential_drives_reduced_items_are_consistent() {
    check_reduced_model(&DifferentialDrive::default(), 6, &heading_configuration(5));
}

/// The classical sleigh (blade speed v, turning rate w; Bloch, "Nonholonomic
/// Mechanics and Control", 1.7): `vdot = a w^2`, `(I + m a^2) wdot = -m a v w`,
/// `(xdot, ydot, thetadot) = (v cos theta, v sin theta, w)`.
fn classical_sleigh(sleigh: &Sleigh, state: &[f64]) -> Vec<f64> {
    let (theta, v, w) = (state[2], state[3], state[4]);
    let total = sleigh.inertia + sleigh.m * sleigh.a * sleigh.a;
    vec![
        v * theta.cos(),
        v * theta.sin(),
        w,
        sleigh.a * w * w,
        -sleigh.m * sleigh.a * v * w / total,
    ]
}

/// The reduced flow, with the tool's own basis and its gyroscopic Gamma,
/// reproduces the classical sleigh over one second.
#[test]
fn the_reduced_sleigh_moves_as_the_classical_sleigh() {
    let sleigh = Sleigh::default();
    let (q0, v0, w0): ([f64; 3], f64, f64) = ([0.1, -0.3, 0.2], 0.7, 0.9);
    let qdot0 = [v0 * q0[2].cos(), v0 * q0[2].sin(), w0];
    let alpha0 = sleigh.momenta(&q0, &qdot0);
    let x0: Vec<f64> = q0.iter().chain(&alpha0).copied().collect();
    let (dt, steps) = (1e-3, 1000);
    let reduced = rk4(
        &|_, x| sleigh.reduced_rhs(x.try_into().unwrap(), &[]).to_vec(),
        &x0,
        dt,
        steps,
    );
    let classical = rk4(
        &|_, s| classical_sleigh(&sleigh, s),
        &[q0[0], q0[1], q0[2], v0, w0],
        dt,
        steps,
    );
    let mut turned = 0.0f64;
    for (x, c) in reduced.iter().zip(&classical) {
        let q: [f64; 3] = x[..3].try_into().unwrap();
        let qdot = sleigh.velocities(&q, x[3..].try_into().unwrap());
        let expected_qdot = [c[3] * c[2].cos(), c[3] * c[2].sin(), c[4]];
        for i in 0..3 {
            assert!((q[i] - c[i]).abs() <= 1e-9, "q {q:?} vs {c:?}");
            assert!(
                (qdot[i] - expected_qdot[i]).abs() <= 1e-9,
                "qdot {qdot:?} vs {expected_qdot:?}"
            );
        }
        turned = turned.max((c[4] - w0).abs());
    }
    // the test has teeth: the turning rate changes along the way
    assert!(turned > 0.1, "turning rate changed by only {turned}");
}
