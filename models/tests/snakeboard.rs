//! The snakeboard's generated items against the hand-derived MATH.md 3.1.

use chaplygin_models::snakeboard::Snakeboard;
use proptest::prelude::*;

/// MATH.md 3.1: g = [[m,0,0,0,0],[0,m,0,0,0],[0,0,J,Jt,0],[0,0,Jt,Jt,0],[0,0,0,0,Jw]], J = Jt + m r^2.
fn hand_metric(b: &Snakeboard) -> [[f64; 5]; 5] {
    let j = b.jt + b.m * b.r * b.r;
    [
        [b.m, 0.0, 0.0, 0.0, 0.0],
        [0.0, b.m, 0.0, 0.0, 0.0],
        [0.0, 0.0, j, b.jt, 0.0],
        [0.0, 0.0, b.jt, b.jt, 0.0],
        [0.0, 0.0, 0.0, 0.0, b.jw],
    ]
}

fn board() -> impl Strategy<Value = Snakeboard> {
    (0.5f64..3.0, 0.1f64..1.0, 0.05f64..0.5, 0.01f64..0.2).prop_map(|(m, r, jt, jw)| Snakeboard {
        m,
        r,
        jt,
        jw,
    })
}

fn configuration() -> impl Strategy<Value = [f64; 5]> {
    // phi stays away from +-pi/2, where tan(phi) and the paper's basis of D degenerate.
    (
        -5.0f64..5.0,
        -5.0f64..5.0,
        -3.2f64..3.2,
        -3.2f64..3.2,
        -1.4f64..1.4,
    )
        .prop_map(|(x, y, theta, psi, phi)| [x, y, theta, psi, phi])
}

#[test]
fn names_and_sizes_follow_the_declaration() {
    assert_eq!(Snakeboard::COORDINATES, ["x", "y", "theta", "psi", "phi"]);
    assert_eq!(Snakeboard::PARAMETERS, ["m", "r", "jt", "jw"]);
    assert_eq!(Snakeboard::INPUTS, ["u_torso", "u_wheels"]);
    assert_eq!(Snakeboard::CONSTRAINTS, ["front", "back"]);
    assert_eq!(
        (
            Snakeboard::N,
            Snakeboard::C,
            Snakeboard::K,
            Snakeboard::P,
            Snakeboard::S
        ),
        (5, 2, 3, 2, 8)
    );
    let defaults = Snakeboard::default();
    assert_eq!(
        defaults,
        Snakeboard {
            m: 1.0,
            r: 0.5,
            jt: 0.3,
            jw: 0.05
        }
    );
}

proptest! {
    #[test]
    fn mass_matrix_is_the_hand_derived_metric(b in board(), q in configuration()) {
        let g = b.mass_matrix(&q);
        let expected = hand_metric(&b);
        for i in 0..5 {
            for j in 0..5 {
                prop_assert!((g[i][j] - expected[i][j]).abs() <= 1e-14 * expected[i][j].abs().max(1.0));
            }
        }
    }

    /// qdot = a (r cos theta, r sin theta, tan phi, 0, 0) + b e_psi + c e_phi lies in D.
    #[test]
    fn residual_vanishes_on_the_papers_distribution(
        board in board(), q in configuration(), a in -2.0f64..2.0, b in -2.0f64..2.0, c in -2.0f64..2.0,
    ) {
        let (theta, phi) = (q[2], q[4]);
        let qdot = [a * board.r * theta.cos(), a * board.r * theta.sin(), a * phi.tan(), b, c];
        let residual = board.constraint_residual(&q, &qdot);
        let scale = qdot.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for value in residual {
            prop_assert!(value.abs() <= 1e-14 * scale, "residual {value}");
        }
        // and a velocity off D does not vanish: the sideways slip of the board
        let slip = [-theta.sin(), theta.cos(), 0.0, 0.0, 0.0];
        let off = board.constraint_residual(&q, &slip);
        prop_assert!(off.iter().any(|v| v.abs() > 1e-3));
    }

    #[test]
    fn constraint_residual_is_the_matrix_times_the_velocity(board in board(), q in configuration(), v in prop::array::uniform5(-2.0f64..2.0)) {
        let a = board.constraint_matrix(&q);
        let residual = board.constraint_residual(&q, &v);
        for i in 0..2 {
            let product: f64 = (0..5).map(|j| a[i][j] * v[j]).sum();
            prop_assert!((product - residual[i]).abs() <= 1e-13);
        }
        // the rows as written: front = -sin(theta + phi) xdot + cos(theta + phi) ydot + r cos(phi) thetadot
        let (theta, phi) = (q[2], q[4]);
        let front = [-(theta + phi).sin(), (theta + phi).cos(), board.r * phi.cos(), 0.0, 0.0];
        let back = [-(theta - phi).sin(), (theta - phi).cos(), -board.r * phi.cos(), 0.0, 0.0];
        for j in 0..5 {
            prop_assert!((a[0][j] - front[j]).abs() <= 1e-14 && (a[1][j] - back[j]).abs() <= 1e-14);
        }
    }

    #[test]
    fn energy_is_the_quadratic_form_of_the_metric(board in board(), q in configuration(), v in prop::array::uniform5(-2.0f64..2.0)) {
        let g = hand_metric(&board);
        let quadratic: f64 = (0..5).flat_map(|i| (0..5).map(move |j| (i, j))).map(|(i, j)| 0.5 * v[i] * g[i][j] * v[j]).sum();
        prop_assert!((board.energy(&q, &v) - quadratic).abs() <= 1e-13 * quadratic.abs().max(1.0));
    }
}

/// MATH.md 1.3: the snakeboard's D (rank 3 in n = 5) grows to 5; by hand,
/// `[d_phi, X] = sec^2(phi) d_theta` (4) and `[X, d_theta]` is sideways (5).
#[test]
fn the_report_states_the_growth_vector_and_the_classification() {
    let report = Snakeboard::REPORT;
    assert!(report.contains("growth vector (3, 4, 5)"), "{report}");
    assert!(
        report.contains("classification: completely nonholonomic"),
        "{report}"
    );
    assert!(
        report.contains("sizes: n = 5, c = 2, k = 3, p = 2"),
        "{report}"
    );
    assert!(
        report.contains("integrable (A [X_i, X_j] = 0 for all i, j): no"),
        "{report}"
    );
    assert!(
        report.contains("front not exact, back not exact"),
        "{report}"
    );
}

/// MATH.md 3.1: with the paper's momentum basis, `gbar = diag(m, Jt, Jw)`
/// (constant and diagonal) and `Gamma = 0`.
#[test]
fn the_report_states_the_papers_reduced_metric() {
    let report = Snakeboard::REPORT;
    for line in [
        "momentum basis: declared; momenta group, torso, wheels",
        "gbar = (h g^-1 h^T)^-1 constant: yes, diagonal: yes",
        "gbar row 1: [m, 0, 0]",
        "gbar row 2: [0, jt, 0]",
        "gbar row 3: [0, 0, jw]",
        "Gamma = 0: yes",
    ] {
        assert!(report.contains(line), "missing `{line}` in\n{report}");
    }
}

/// Every generated function has its operation counts in the report, and
/// sharing subexpressions never costs more than the expanded trees.
#[test]
fn the_report_counts_the_operations_of_every_function() {
    for function in [
        "mass_matrix",
        "energy",
        "constraint_matrix",
        "constraint_residual",
    ] {
        let prefix = format!("  {function}: ");
        let line = Snakeboard::REPORT
            .lines()
            .find(|line| line.starts_with(&prefix))
            .unwrap_or_else(|| panic!("no counts for {function}"));
        let counts: Vec<u64> = line[prefix.len()..]
            .split(" -> ")
            .map(|n| n.parse().expect("a count"))
            .collect();
        assert_eq!(counts.len(), 2, "{line}");
        assert!(counts[1] <= counts[0], "{line}");
    }
}
