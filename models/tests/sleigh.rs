//! The Chaplygin sleigh (generated from `sleigh.model`) against its hand derivation.

use chaplygin_models::sleigh::Sleigh;
use proptest::prelude::*;

/// The blade at (x, y), the centre of mass at (x + a cos theta, y + a sin theta):
/// g = [[m, 0, -m a sin], [0, m, m a cos], [-m a sin, m a cos, I + m a^2]].
fn hand_metric(s: &Sleigh, theta: f64) -> [[f64; 3]; 3] {
    let (sin, cos) = theta.sin_cos();
    let ma = s.m * s.a;
    [
        [s.m, 0.0, -ma * sin],
        [0.0, s.m, ma * cos],
        [-ma * sin, ma * cos, s.inertia + ma * s.a],
    ]
}

fn sleigh() -> impl Strategy<Value = Sleigh> {
    (0.5f64..3.0, 0.01f64..0.5, -1.0f64..1.0).prop_map(|(m, inertia, a)| Sleigh { m, inertia, a })
}

#[test]
fn names_and_sizes_follow_the_model_file() {
    assert_eq!(Sleigh::COORDINATES, ["x", "y", "theta"]);
    assert_eq!(Sleigh::CONSTRAINTS, ["blade"]);
    assert_eq!((Sleigh::N, Sleigh::C, Sleigh::K, Sleigh::P), (3, 1, 2, 0));
    assert_eq!(
        Sleigh::default(),
        Sleigh {
            m: 1.0,
            inertia: 0.1,
            a: 0.5
        }
    );
}

proptest! {
    #[test]
    fn mass_matrix_is_the_hand_derived_metric(s in sleigh(), q in prop::array::uniform3(-4.0f64..4.0)) {
        let g = s.mass_matrix(&q);
        let expected = hand_metric(&s, q[2]);
        for i in 0..3 {
            for j in 0..3 {
                prop_assert!((g[i][j] - expected[i][j]).abs() <= 1e-14);
            }
        }
    }

    /// Motion along the blade (v cos theta, v sin theta) with any turning rate is allowed;
    /// sideways motion is not.
    #[test]
    fn residual_vanishes_along_the_blade(s in sleigh(), q in prop::array::uniform3(-4.0f64..4.0), v in -3.0f64..3.0, w in -3.0f64..3.0) {
        let theta = q[2];
        let along = [v * theta.cos(), v * theta.sin(), w];
        prop_assert!(s.constraint_residual(&q, &along)[0].abs() <= 1e-14);
        let sideways = [-theta.sin(), theta.cos(), 0.0];
        prop_assert!((s.constraint_residual(&q, &sideways)[0] - 1.0).abs() <= 1e-14);
    }
}

/// The classical reduced equations with v the speed along the blade and
/// omega the turning rate. In the body frame the centre of mass moves with
/// (v, a omega); with no force along the blade, m (vdot - a omega^2) = 0; the
/// lateral blade force F gives m (a omegadot + v omega) = F and, acting a
/// behind the centre of mass, I omegadot = -a F. Hence
/// vdot = a omega^2 and omegadot = -m a v omega / (I + m a^2).
fn reduced_rates(s: &Sleigh, v: f64, omega: f64) -> (f64, f64) {
    (
        s.a * omega * omega,
        -s.m * s.a * v * omega / (s.inertia + s.m * s.a * s.a),
    )
}

proptest! {
    #[test]
    fn acceleration_reproduces_the_reduced_equations(
        s in sleigh(),
        q in prop::array::uniform3(-4.0f64..4.0),
        v in -3.0f64..3.0,
        omega in -3.0f64..3.0,
    ) {
        let (sin, cos) = q[2].sin_cos();
        let qdot = [v * cos, v * sin, omega];
        let ([xddot, yddot, thetaddot], _) = s.acceleration(&q, &qdot, &[]);
        // v = cos(theta) xdot + sin(theta) ydot, so
        // vdot = cos xddot + sin yddot + omega (-sin xdot + cos ydot)
        let vdot = cos * xddot + sin * yddot + omega * (-sin * qdot[0] + cos * qdot[1]);
        let (expected_vdot, expected_omegadot) = reduced_rates(&s, v, omega);
        prop_assert!((vdot - expected_vdot).abs() <= 1e-12 * (1.0 + expected_vdot.abs()), "{vdot} vs {expected_vdot}");
        prop_assert!((thetaddot - expected_omegadot).abs() <= 1e-12 * (1.0 + expected_omegadot.abs()), "{thetaddot} vs {expected_omegadot}");
    }
}
