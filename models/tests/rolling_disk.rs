//! The vertical rolling disk against its hand derivation (Bloch 2003, chapter 1).

use chaplygin_models::rolling_disk::RollingDisk;
use proptest::prelude::*;

/// `T = m/2 (xdot^2 + ydot^2) + J_vertical/2 thetadot^2 + J_axle/2 phidot^2`:
/// g = diag(m, m, J_vertical, J_axle).
fn hand_metric(d: &RollingDisk) -> [[f64; 4]; 4] {
    [
        [d.m, 0.0, 0.0, 0.0],
        [0.0, d.m, 0.0, 0.0],
        [0.0, 0.0, d.j_vertical, 0.0],
        [0.0, 0.0, 0.0, d.j_axle],
    ]
}

/// The contact point's velocity minus the rim's: `(xdot, ydot) - R phidot (cos, sin)`.
fn hand_residual(d: &RollingDisk, q: &[f64; 4], qdot: &[f64; 4]) -> [f64; 2] {
    let (sin, cos) = q[2].sin_cos();
    [qdot[0] - d.r * cos * qdot[3], qdot[1] - d.r * sin * qdot[3]]
}

fn disk() -> impl Strategy<Value = RollingDisk> {
    (0.5f64..3.0, 0.1f64..1.0, 0.01f64..0.5, 0.01f64..0.5).prop_map(|(m, r, j_axle, j_vertical)| {
        RollingDisk {
            m,
            r,
            j_axle,
            j_vertical,
        }
    })
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-13 * (1.0 + b.abs())
}

#[test]
fn names_and_sizes_follow_the_declaration() {
    assert_eq!(RollingDisk::COORDINATES, ["x", "y", "theta", "phi"]);
    assert_eq!(RollingDisk::CONSTRAINTS, ["roll_x", "roll_y"]);
    assert_eq!(RollingDisk::INPUTS, ["u_steer", "u_drive"]);
    assert_eq!(
        (
            RollingDisk::N,
            RollingDisk::C,
            RollingDisk::K,
            RollingDisk::P
        ),
        (4, 2, 2, 2)
    );
}

/// By hand: X_steer = d_theta, X_roll = R cos d_x + R sin d_y + d_phi;
/// `[X_steer, X_roll] = R (-sin d_x + cos d_y)` (3), and bracketing that with
/// X_steer gives `-R (cos d_x + sin d_y)`, outside the span (no d_phi) (4).
#[test]
fn the_report_states_the_growth_vector_and_the_classification() {
    let report = RollingDisk::REPORT;
    assert!(report.contains("growth vector (2, 3, 4)"), "{report}");
    assert!(
        report.contains("classification: completely nonholonomic"),
        "{report}"
    );
    assert!(
        report.contains("sizes: n = 4, c = 2, k = 2, p = 2"),
        "{report}"
    );
}

proptest! {
    #[test]
    fn mass_matrix_is_the_hand_derived_metric(d in disk(), q in prop::array::uniform4(-4.0f64..4.0)) {
        let g = d.mass_matrix(&q);
        let expected = hand_metric(&d);
        for i in 0..4 {
            for j in 0..4 {
                prop_assert!(close(g[i][j], expected[i][j]));
            }
        }
    }

    #[test]
    fn energy_is_the_hand_kinetic_energy(d in disk(), q in prop::array::uniform4(-4.0f64..4.0), v in prop::array::uniform4(-3.0f64..3.0)) {
        let hand = d.m / 2.0 * (v[0] * v[0] + v[1] * v[1])
            + d.j_vertical / 2.0 * v[2] * v[2]
            + d.j_axle / 2.0 * v[3] * v[3];
        prop_assert!(close(d.energy(&q, &v), hand));
    }

    #[test]
    fn residual_is_the_contact_slip(d in disk(), q in prop::array::uniform4(-4.0f64..4.0), v in prop::array::uniform4(-3.0f64..3.0)) {
        let residual = d.constraint_residual(&q, &v);
        let expected = hand_residual(&d, &q, &v);
        for i in 0..2 {
            prop_assert!(close(residual[i], expected[i]));
        }
    }

    /// Steering and rolling (`a X_steer + b X_roll`) are allowed; sliding
    /// sideways `(-sin, cos, 0, 0)` slips by exactly that velocity.
    #[test]
    fn residual_vanishes_on_d_and_not_off_it(d in disk(), q in prop::array::uniform4(-4.0f64..4.0), steer in -3.0f64..3.0, roll in -3.0f64..3.0) {
        let (sin, cos) = q[2].sin_cos();
        let allowed = [roll * d.r * cos, roll * d.r * sin, steer, roll];
        for value in d.constraint_residual(&q, &allowed) {
            prop_assert!(value.abs() <= 1e-13);
        }
        let sideways = d.constraint_residual(&q, &[-sin, cos, 0.0, 0.0]);
        prop_assert!(close(sideways[0], -sin) && close(sideways[1], cos));
    }
}
