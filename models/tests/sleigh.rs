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
