//! The two formulations of every model agree: the accelerations of the
//! Lagrange-d'Alembert equations (`acceleration`, MATH.md section 2) equal the
//! accelerations implied by the reduced port-Hamiltonian flow (MATH.md
//! section 3), i.e. the time derivative of `velocities(q, alpha)` along
//! `reduced_rhs`, taken here by Richardson-extrapolated central differences
//! (error O(h^4)), independent of both derivations.

use crate::common::Random;
use chaplygin_models::{
    bicycle::Bicycle, differential_drive::DifferentialDrive, rolling_disk::RollingDisk,
    sleigh::Sleigh, snakeboard::Snakeboard,
};

/// Checks the agreement at random states of a model; `angle` is the index of
/// a coordinate kept within (-1.4, 1.4), away from where the model's basis
/// of D (and with it the reduced coordinates) degenerates.
macro_rules! formulations_agree {
    ($model:expr, $type:ty, $seed:expr, $angle:expr) => {
        formulations_agree!($model, $type, $seed, [$angle], 1.4)
    };
    ($model:expr, $type:ty, $seed:expr, $angles:expr, $bound:expr) => {{
        const N: usize = <$type>::N;
        const K: usize = <$type>::K;
        const S: usize = <$type>::S;
        let model = $model;
        let mut random = Random::new($seed);
        let mut worst = 0.0f64;
        for _ in 0..200 {
            let mut q = [0.0; N];
            for value in q.iter_mut() {
                *value = random.uniform(-3.0, 3.0);
            }
            for &angle in &$angles {
                q[angle] = random.uniform(-$bound, $bound);
            }
            let mut alpha = [0.0; K];
            for value in alpha.iter_mut() {
                *value = random.uniform(-1.0, 1.0);
            }
            let mut u = [0.0; <$type>::P];
            for value in u.iter_mut() {
                *value = random.uniform(-1.0, 1.0);
            }
            let mut x = [0.0; S];
            x[..N].copy_from_slice(&q);
            x[N..].copy_from_slice(&alpha);
            let xdot = model.reduced_rhs(&x, &u);
            // qdot along the reduced flow, at x + s xdot
            let velocities_at = |s: f64| {
                let mut q_s = [0.0; N];
                let mut alpha_s = [0.0; K];
                for i in 0..N {
                    q_s[i] = x[i] + s * xdot[i];
                }
                for i in 0..K {
                    alpha_s[i] = x[N + i] + s * xdot[N + i];
                }
                model.velocities(&q_s, &alpha_s)
            };
            let central = |h: f64| {
                let (ahead, behind) = (velocities_at(h), velocities_at(-h));
                let mut d = [0.0; N];
                for i in 0..N {
                    d[i] = (ahead[i] - behind[i]) / (2.0 * h);
                }
                d
            };
            // truncation ~h^4 and rounding ~1e-16/h balance near here (measured worst: 3e-11)
            let h = 2.5e-4;
            let (coarse, fine) = (central(h), central(h / 2.0));
            let qdot = model.velocities(&q, &alpha);
            let (qddot, _) = model.acceleration(&q, &qdot, &u);
            for i in 0..N {
                let reduced = (4.0 * fine[i] - coarse[i]) / 3.0;
                let error = (reduced - qddot[i]).abs() / qddot[i].abs().max(1.0);
                worst = worst.max(error);
            }
        }
        assert!(worst <= 1e-9, "largest relative difference {worst:e}");
    }};
}

#[test]
fn snakeboard_formulations_agree() {
    formulations_agree!(Snakeboard::default(), Snakeboard, 11, 4);
    let board = Snakeboard {
        m: 1.7,
        r: 0.4,
        jt: 0.2,
        jw: 0.07,
    };
    formulations_agree!(board, Snakeboard, 12, 4);
}

#[test]
fn sleigh_formulations_agree() {
    formulations_agree!(Sleigh::default(), Sleigh, 13, 2);
}

#[test]
fn rolling_disk_formulations_agree() {
    formulations_agree!(RollingDisk::default(), RollingDisk, 14, 2);
}

#[test]
fn differential_drive_formulations_agree() {
    formulations_agree!(DifferentialDrive::default(), DifferentialDrive, 15, 2);
}

/// The benchmark bicycle, its lean, pitch and steer kept within (-1, 1):
/// nearer the front wheel lying flat (`fork.y` vertical, where the contact
/// point's `unit(...)` is undefined) the contact moves over the rim fast
/// enough that the differences lose their accuracy (5e-4 within (-1.4, 1.4)).
#[test]
fn bicycle_formulations_agree() {
    formulations_agree!(Bicycle::default(), Bicycle, 16, [3, 4, 5], 1.0);
}
