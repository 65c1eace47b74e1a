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
}

use shadowed::Rail;

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
