//! Generated code is hygienic: it compiles under `#![deny(warnings)]` in a
//! scope where `Result`, `Ok`, `Some`, `f64`, `Default`, `Clone` and a module
//! `core` are the caller's own items, and it still computes the right values.

#![deny(warnings)]

mod shadowed {
    #![allow(non_camel_case_types, dead_code)]

    pub struct Result;
    pub struct Ok;
    pub struct Some;
    pub struct None;
    pub struct f64;
    pub struct usize;
    pub struct str;
    pub struct Default;
    pub struct Clone;
    pub mod core {}
    pub mod std {}

    chaplygin::model! {
        /// A point mass on a rail at angle `theta` from a pivot: r and theta.
        pub struct Rail {
            coordinates: [r, theta],
            parameters: [m = 2.0, g = 9.81],
            kinetic_energy: m/2*(dot(r)^2 + r^2*dot(theta)^2),
            potential_energy: m*g*r*sin(theta),
            constraints: [fixed_angle = dot(theta)],
            inputs: [push = r],
        }
    }

    chaplygin::model! {
        /// A sleigh towing a spring-held pendulum: its coupled metric makes
        /// `acceleration` solve at run time through `::chaplygin::runtime`.
        pub struct Towed {
            coordinates: [x, y, theta, alpha],
            parameters: [m = 1.0, inertia = 0.1, a = 0.5, mp = 0.3, l = 0.7, k = 2.0],
            kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
                + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2
                + mp/2*((dot(x) - l*sin(theta + alpha)*(dot(theta) + dot(alpha)))^2
                + (dot(y) + l*cos(theta + alpha)*(dot(theta) + dot(alpha)))^2),
            potential_energy: k/2*alpha^2,
            constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
            inputs: [steer = alpha],
        }
    }
}

use shadowed::{Rail, Towed};

#[test]
fn generated_items_work_amid_shadowed_names() {
    let rail = Rail::default();
    assert_eq!(rail, Rail { m: 2.0, g: 9.81 });
    let q = [1.5, 0.3];
    let g = rail.mass_matrix(&q);
    assert_eq!(g, [[2.0, 0.0], [0.0, 2.0 * 1.5 * 1.5]]);
    let qdot = [0.4, 0.0];
    let expected = 0.5 * 2.0 * 0.4 * 0.4 + 2.0 * 9.81 * 1.5 * 0.3f64.sin();
    assert!((rail.energy(&q, &qdot) - expected).abs() < 1e-12);
    assert_eq!(rail.constraint_residual(&q, &[0.4, 0.7]), [0.7]);
    assert_eq!(Rail::CONSTRAINTS, ["fixed_angle"]);
}

/// Rail by hand: `m rddot - m r thetadot^2 + m g sin(theta) = push` and
/// `m r^2 thetaddot + 2 m r rdot thetadot + m g r cos(theta) = lambda`, with
/// `thetaddot = 0`.
#[test]
fn acceleration_works_amid_shadowed_names() {
    let rail = Rail::default();
    let (q, qdot, push) = ([1.5, 0.3], [0.4, 0.0], 3.0);
    let ([rddot, thetaddot], [lambda]) = rail.acceleration(&q, &qdot, &[push]);
    assert!((rddot - (push / 2.0 - 9.81 * 0.3f64.sin())).abs() < 1e-12);
    assert_eq!(thetaddot, 0.0);
    assert!((lambda - 2.0 * 9.81 * 1.5 * 0.3f64.cos()).abs() < 1e-12);
}

/// At rest the towed sleigh's run-time solve balances
/// `g qddot = B u - dV/dq + A^T lambda` (`dV/dq = (0, 0, 0, k alpha)`) with `A qddot = 0`.
#[test]
fn the_run_time_solve_works_amid_shadowed_names() {
    let towed = Towed::default();
    let (q, steer) = ([0.3, -0.2, 0.5, 0.4], 1.5);
    let (qddot, [lambda]) = towed.acceleration(&q, &[0.0; 4], &[steer]);
    let (g, [a]) = (towed.mass_matrix(&q), towed.constraint_matrix(&q));
    for i in 0..4 {
        let inertial: f64 = (0..4).map(|j| g[i][j] * qddot[j]).sum();
        let applied = if i == 3 { steer - towed.k * q[3] } else { 0.0 };
        assert!(
            (inertial - applied - a[i] * lambda).abs() < 1e-12,
            "row {i}"
        );
    }
    assert!(towed.constraint_residual(&q, &qddot)[0].abs() < 1e-12);
}

/// The towed sleigh has no symmetry: its blade solved for `dot(y)` divides
/// by `cos(theta)`, so it has a second chart, solved for `dot(x)`, whose
/// items compile and agree with chart 0 amid the shadowed names.
#[test]
fn chart_items_work_amid_shadowed_names() {
    use chaplygin::runtime::system::ReducedPortHamiltonian;
    assert_eq!(Towed::CHARTS, [[1], [0]]);
    let towed = Towed::default();
    let x = [0.3, -0.2, 0.5, 0.4, 0.7, -0.1, 0.2];
    let moved = towed.change_chart(0, 1, &x);
    let (h0, h1) = (
        towed.chart_hamiltonian(0, &x),
        towed.chart_hamiltonian(1, &moved),
    );
    assert!((h0 - h1).abs() < 1e-12 * h0.abs(), "{h0} vs {h1}");
    assert!(towed.chart_constraint_violation(1, &moved) < 1e-12);
    assert!((towed.chart_fit(1, &x) - 0.5f64.sin()).abs() < 1e-15);
}
