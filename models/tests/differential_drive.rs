//! The differential-drive robot against its hand derivation from the wheel
//! geometry: the right wheel's contact point is `(x, y) + b (sin, -cos)`,
//! the left one's `(x, y) - b (sin, -cos)`.

use chaplygin_models::differential_drive::DifferentialDrive;
use proptest::prelude::*;

/// g = diag(m, m, J, J_w, J_w).
fn hand_metric(d: &DifferentialDrive) -> [[f64; 5]; 5] {
    [
        [d.m, 0.0, 0.0, 0.0, 0.0],
        [0.0, d.m, 0.0, 0.0, 0.0],
        [0.0, 0.0, d.j, 0.0, 0.0],
        [0.0, 0.0, 0.0, d.jw, 0.0],
        [0.0, 0.0, 0.0, 0.0, d.jw],
    ]
}

/// The velocity of the point `(x, y) + side b (sin, -cos)` (side = 1 right, -1 left).
fn wheel_velocity(d: &DifferentialDrive, q: &[f64; 5], qdot: &[f64; 5], side: f64) -> [f64; 2] {
    let (sin, cos) = q[2].sin_cos();
    [
        qdot[0] + side * d.b * cos * qdot[2],
        qdot[1] + side * d.b * sin * qdot[2],
    ]
}

/// Sideways slip of the midpoint, then each wheel's forward slip against its rim.
fn hand_residual(d: &DifferentialDrive, q: &[f64; 5], qdot: &[f64; 5]) -> [f64; 3] {
    let (sin, cos) = q[2].sin_cos();
    let forward = |v: [f64; 2]| cos * v[0] + sin * v[1];
    [
        -sin * qdot[0] + cos * qdot[1],
        forward(wheel_velocity(d, q, qdot, 1.0)) - d.r * qdot[3],
        forward(wheel_velocity(d, q, qdot, -1.0)) - d.r * qdot[4],
    ]
}

/// The hand basis of D, driven by the wheel speeds: forward speed
/// `R (w_r + w_l) / 2`, turning rate `R (w_r - w_l) / (2 b)`.
fn allowed_velocity(d: &DifferentialDrive, q: &[f64; 5], w_r: f64, w_l: f64) -> [f64; 5] {
    let (sin, cos) = q[2].sin_cos();
    let speed = d.r * (w_r + w_l) / 2.0;
    [
        speed * cos,
        speed * sin,
        d.r * (w_r - w_l) / (2.0 * d.b),
        w_r,
        w_l,
    ]
}

fn robot() -> impl Strategy<Value = DifferentialDrive> {
    (
        0.5f64..10.0,
        0.01f64..1.0,
        0.01f64..0.5,
        0.05f64..0.5,
        0.0001f64..0.01,
    )
        .prop_map(|(m, j, r, b, jw)| DifferentialDrive { m, j, r, b, jw })
}

fn configuration() -> impl Strategy<Value = [f64; 5]> {
    prop::array::uniform5(-4.0f64..4.0)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-13 * (1.0 + b.abs())
}

#[test]
fn names_and_sizes_follow_the_declaration() {
    assert_eq!(
        DifferentialDrive::COORDINATES,
        ["x", "y", "theta", "phi_r", "phi_l"]
    );
    assert_eq!(DifferentialDrive::CONSTRAINTS, ["lateral", "right", "left"]);
    assert_eq!(DifferentialDrive::INPUTS, ["u_right", "u_left"]);
    assert_eq!(
        (
            DifferentialDrive::N,
            DifferentialDrive::C,
            DifferentialDrive::K,
            DifferentialDrive::P
        ),
        (5, 3, 2, 2)
    );
}

/// A left turn in place: the right wheel rolls forward, the left one back.
#[test]
fn a_left_turn_in_place_spins_the_right_wheel_forward() {
    let d = DifferentialDrive::default();
    let q = [0.3, -0.2, 0.7, 0.0, 0.0];
    let turn = [0.0, 0.0, 1.0, d.b / d.r, -d.b / d.r];
    for value in d.constraint_residual(&q, &turn) {
        assert!(value.abs() <= 1e-12, "{value}");
    }
}

/// By hand: `[X_r, X_l] = (R^2 / 2b) (-sin d_x + cos d_y)` (3); bracketing
/// that with `X_r` gives the forward direction `cos d_x + sin d_y`, outside
/// the span since it has no wheel part (4); the next brackets give the
/// sideways direction back. `right - left` is exact, so the growth stops at 4.
#[test]
fn the_report_states_the_growth_vector_and_the_classification() {
    let report = DifferentialDrive::REPORT;
    assert!(report.contains("growth vector (2, 3, 4)"), "{report}");
    assert!(report.contains("classification: nonholonomic"), "{report}");
    assert!(
        report.contains("reachable dimension (last rank of the growth): 4 of n = 5"),
        "{report}"
    );
    assert!(
        report.contains("sizes: n = 5, c = 3, k = 2, p = 2"),
        "{report}"
    );
}

proptest! {
    #[test]
    fn mass_matrix_is_the_hand_derived_metric(d in robot(), q in configuration()) {
        let g = d.mass_matrix(&q);
        let expected = hand_metric(&d);
        for i in 0..5 {
            for j in 0..5 {
                prop_assert!(close(g[i][j], expected[i][j]));
            }
        }
    }

    #[test]
    fn energy_is_the_hand_kinetic_energy(d in robot(), q in configuration(), v in prop::array::uniform5(-3.0f64..3.0)) {
        let hand = d.m / 2.0 * (v[0] * v[0] + v[1] * v[1])
            + d.j / 2.0 * v[2] * v[2]
            + d.jw / 2.0 * (v[3] * v[3] + v[4] * v[4]);
        prop_assert!(close(d.energy(&q, &v), hand));
    }

    #[test]
    fn residual_is_the_slip_of_the_wheels(d in robot(), q in configuration(), v in prop::array::uniform5(-3.0f64..3.0)) {
        let residual = d.constraint_residual(&q, &v);
        let expected = hand_residual(&d, &q, &v);
        for i in 0..3 {
            prop_assert!(close(residual[i], expected[i]), "row {}: {} vs {}", i, residual[i], expected[i]);
        }
    }

    /// Any pair of wheel speeds gives an allowed velocity; sliding sideways,
    /// or spinning one wheel alone, does not.
    #[test]
    fn residual_vanishes_on_d_and_not_off_it(d in robot(), q in configuration(), w_r in -3.0f64..3.0, w_l in -3.0f64..3.0) {
        let allowed = allowed_velocity(&d, &q, w_r, w_l);
        for value in d.constraint_residual(&q, &allowed) {
            prop_assert!(value.abs() <= 1e-12);
        }
        let (sin, cos) = q[2].sin_cos();
        let sideways = d.constraint_residual(&q, &[-sin, cos, 0.0, 0.0, 0.0]);
        prop_assert!(close(sideways[0], 1.0));
        let spin = d.constraint_residual(&q, &[0.0, 0.0, 0.0, 1.0, 0.0]);
        prop_assert!(close(spin[1], -d.r) && close(spin[2], 0.0));
    }
}
