//! The snakeboard's reduced port-Hamiltonian items against the hand
//! derivation of MATH.md 3.1 (Duindam & Stramigioli 2004), and the tool's own
//! momentum basis against the declared one.

use crate::common::{Random, rk4};
use chaplygin_models::snakeboard::Snakeboard;

chaplygin::model! {
    /// The snakeboard without a declared momentum basis: the tool picks `h = (g X)^T`.
    pub struct SnakeboardOwnBasis {
        coordinates: [x, y, theta, psi, phi],
        parameters: [m = 1.0, r = 0.5, jt = 0.3, jw = 0.05],
        define: [j = jt + m*r^2],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + j/2*dot(theta)^2
            + jt*dot(theta)*dot(psi) + jt/2*dot(psi)^2 + jw/2*dot(phi)^2,
        potential_energy: 0,
        constraints: [
            front = -sin(theta + phi)*dot(x) + cos(theta + phi)*dot(y) + r*cos(phi)*dot(theta),
            back  = -sin(theta - phi)*dot(x) + cos(theta - phi)*dot(y) - r*cos(phi)*dot(theta),
        ],
        inputs: [u_torso = psi, u_wheels = phi],
    }
}

/// MATH.md 3.1, written out by hand: x = (x, y, theta, psi, phi, alpha1, alpha2, alpha3).
fn hand_rhs(b: &Snakeboard, x: &[f64; 8], u: &[f64; 2]) -> [f64; 8] {
    let (theta, phi) = (x[2], x[4]);
    let (a1, a2, a3) = (x[5], x[6], x[7]);
    [
        a1 / b.m * phi.cos() * theta.cos(),
        a1 / b.m * phi.cos() * theta.sin(),
        a1 * phi.sin() / (b.m * b.r),
        a2 / b.jt - a1 * phi.sin() / (b.m * b.r),
        a3 / b.jw,
        -(phi.sin() / b.r) * u[0],
        u[0],
        u[1],
    ]
}

/// The paper's basis h (rows), MATH.md 3.1.
fn hand_basis(b: &Snakeboard, q: &[f64; 8]) -> [[f64; 5]; 3] {
    let (theta, phi) = (q[2], q[4]);
    [
        [
            phi.cos() * theta.cos(),
            phi.cos() * theta.sin(),
            b.r * phi.sin(),
            0.0,
            0.0,
        ],
        [0.0, 0.0, 1.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 1.0],
    ]
}

fn board(random: &mut Random) -> Snakeboard {
    Snakeboard {
        m: random.uniform(0.5, 3.0),
        r: random.uniform(0.1, 1.0),
        jt: random.uniform(0.05, 0.5),
        jw: random.uniform(0.01, 0.2),
    }
}

/// A random state with phi away from +-pi/2, and a random input.
fn state(random: &mut Random) -> ([f64; 8], [f64; 2]) {
    let mut x = [0.0; 8];
    for value in x.iter_mut() {
        *value = random.uniform(-3.0, 3.0);
    }
    x[4] = random.uniform(-1.4, 1.4);
    (x, [random.uniform(-2.0, 2.0), random.uniform(-2.0, 2.0)])
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs()).max(1e-300)
}

#[test]
fn reduced_rhs_is_the_hand_derived_snakeboard() {
    let mut random = Random::new(31);
    for _ in 0..2000 {
        let b = board(&mut random);
        let (x, u) = state(&mut random);
        let generated = b.reduced_rhs(&x, &u);
        let expected = hand_rhs(&b, &x, &u);
        for i in 0..8 {
            // psidot is a difference of two terms: compare relative to their size
            let scale = if i == 3 {
                x[6].abs() / b.jt + (x[5] * x[4].sin()).abs() / (b.m * b.r)
            } else {
                expected[i].abs()
            };
            assert!(
                (generated[i] - expected[i]).abs() <= 1e-12 * scale.max(1e-300),
                "xdot[{i}] {} vs {} at {x:?}, {u:?}, {b:?}",
                generated[i],
                expected[i]
            );
        }
    }
}

#[test]
fn the_structure_matrix_is_zero_p_transpose_minus_p_zero() {
    let mut random = Random::new(32);
    for _ in 0..1000 {
        let b = board(&mut random);
        let (x, _) = state(&mut random);
        let j = b.structure_matrix(&x);
        let h = hand_basis(&b, &x);
        for (row, column) in (0..8).flat_map(|row| (0..8).map(move |column| (row, column))) {
            let top_left = row < 5 && column < 5;
            let gamma = row >= 5 && column >= 5;
            if top_left || gamma {
                assert_eq!(j[row][column], 0.0, "Jbar[{row}][{column}]");
            }
            assert_eq!(j[row][column], -j[column][row], "skew at ({row}, {column})");
        }
        // the lower-left block is -P, and P h^T = I with the paper's h
        for a in 0..3 {
            for (c, h_c) in h.iter().enumerate() {
                let product: f64 = (0..5).map(|l| -j[5 + a][l] * h_c[l]).sum();
                let identity = if a == c { 1.0 } else { 0.0 };
                assert!(
                    (product - identity).abs() <= 1e-12,
                    "(P h^T)[{a}][{c}] = {product}"
                );
            }
        }
        let bbar = b.input_matrix(&x);
        let expected_bbar = [[-x[4].sin() / b.r, 0.0], [1.0, 0.0], [0.0, 1.0]];
        assert!(bbar[..5].iter().all(|row| *row == [0.0, 0.0]));
        for a in 0..3 {
            for input in 0..2 {
                assert!(
                    close(bbar[5 + a][input], expected_bbar[a][input], 1e-14),
                    "Bbar[{}][{input}]",
                    5 + a
                );
            }
        }
    }
}

#[test]
fn hamiltonian_and_output_are_the_papers() {
    let mut random = Random::new(33);
    for _ in 0..1000 {
        let b = board(&mut random);
        let (x, u) = state(&mut random);
        let (a1, a2, a3) = (x[5], x[6], x[7]);
        let expected = a1 * a1 / (2.0 * b.m) + a2 * a2 / (2.0 * b.jt) + a3 * a3 / (2.0 * b.jw);
        assert!(close(b.hamiltonian(&x), expected, 1e-13));
        let xdot = hand_rhs(&b, &x, &u);
        let y = b.output(&x);
        let psidot_scale = a2.abs() / b.jt + (a1 * x[4].sin()).abs() / (b.m * b.r);
        assert!(
            (y[0] - xdot[3]).abs() <= 1e-12 * psidot_scale,
            "y0 {} vs psidot {}",
            y[0],
            xdot[3]
        );
        assert!(
            close(y[1], xdot[4], 1e-13),
            "y1 {} vs phidot {}",
            y[1],
            xdot[4]
        );
    }
}

/// Same initial q and qdot; each model's momenta from its own `momenta`;
/// both reduced flows integrated for 1 s: the motions agree. The motion keeps
/// phi and theta away from +-pi/2, where the bases degenerate.
#[test]
fn the_tools_own_basis_moves_the_snakeboard_as_the_papers_basis() {
    let (declared, own) = (Snakeboard::default(), SnakeboardOwnBasis::default());
    let q0 = [0.1, -0.2, 0.3, 0.0, 0.2];
    let qdot0 = declared.velocities(&q0, &[0.5, 0.2, -0.02]);
    let start = |alpha: &[f64; 3]| -> Vec<f64> { q0.iter().chain(alpha).copied().collect() };
    let x_declared = start(&declared.momenta(&q0, &qdot0));
    let x_own = start(&own.momenta(&q0, &qdot0));
    let input = |t: f64| [0.2 * (2.0 * t).sin(), 0.02 * (3.0 * t).cos()];
    let (dt, steps) = (1e-3, 1000);
    let declared_flow = rk4(
        &|t, x| {
            declared
                .reduced_rhs(x.try_into().unwrap(), &input(t))
                .to_vec()
        },
        &x_declared,
        dt,
        steps,
    );
    let own_flow = rk4(
        &|t, x| own.reduced_rhs(x.try_into().unwrap(), &input(t)).to_vec(),
        &x_own,
        dt,
        steps,
    );
    let (mut travelled, mut steered, mut difference) = (0.0f64, 0.0f64, 0.0f64);
    for (a, b) in declared_flow.iter().zip(&own_flow) {
        let (qa, qb): ([f64; 5], [f64; 5]) =
            (a[..5].try_into().unwrap(), b[..5].try_into().unwrap());
        let va = declared.velocities(&qa, a[5..].try_into().unwrap());
        let vb = own.velocities(&qb, b[5..].try_into().unwrap());
        for i in 0..5 {
            assert!((qa[i] - qb[i]).abs() <= 1e-9, "q {qa:?} vs {qb:?}");
            assert!((va[i] - vb[i]).abs() <= 1e-9, "qdot {va:?} vs {vb:?}");
        }
        travelled = travelled.max((qa[0] - q0[0]).abs() + (qa[2] - q0[2]).abs());
        steered = steered.max(qa[4].abs().max(qa[2].abs()));
        difference = (0..5).fold(difference, |d, i| {
            d.max((qa[i] - qb[i]).abs()).max((va[i] - vb[i]).abs())
        });
    }
    println!("largest difference {difference:e}, largest |phi|, |theta| {steered}");
    assert!(
        steered < 1.2,
        "the motion came near a singular basis: {steered}"
    );
    assert!(travelled > 0.1, "the board barely moved: {travelled}");
}
