//! The canonical form `M qddot + v C1 qdot + (g K0 + v^2 K2) q = f` of
//! Meijaard et al. (2007) read off two linearizations
//! (`chaplygin::runtime::linearize::canonical`), on a stand-in for the
//! benchmark bicycle: a hand-written model whose roll and steer obey the
//! paper's closed form (`support::benchmark_bicycle`) at the forward speed
//! `v = -rR dot(theta_r)`, the rear wheel's rotation `theta_r` its
//! symmetry. The recipe must return the matrices it was built from, and
//! the linearization's eigenvalues must be the closed form's (table 2 of
//! the paper, checked in `benchmark_bicycle_reference.rs`) plus the zero of
//! the conserved speed. The mechanism bicycle will be checked the same way.

use crate::support::benchmark_bicycle::{BenchmarkParameters, CanonicalMatrices};
use chaplygin::runtime::linearize::{
    AccelerationJacobian, CanonicalForm, Compiled, GroupFactor, Linearization, OperatingPoint,
    linearize,
};
use chaplygin::runtime::nalgebra::{DMatrix, Matrix2, Vector2};
use chaplygin::runtime::system::{Domain, LagrangeDalembert, ModelNames};

/// Roll `phi`, steer `delta` and the rear wheel's rotation `theta_r`, with
/// lean and steer torques as inputs.
struct CanonicalBicycle {
    matrices: CanonicalMatrices,
    g: f64,
    r_r: f64,
}

impl CanonicalBicycle {
    /// `M^-1`.
    fn inverse_mass(&self) -> Matrix2<f64> {
        self.matrices
            .m
            .try_inverse()
            .unwrap_or(Matrix2::from_element(f64::NAN))
    }

    fn speed(&self, qdot: &[f64; 3]) -> f64 {
        -self.r_r * qdot[2]
    }
}

impl LagrangeDalembert<3, 0, 2> for CanonicalBicycle {
    fn acceleration(&self, q: &[f64; 3], qdot: &[f64; 3], u: &[f64; 2]) -> ([f64; 3], [f64; 0]) {
        let CanonicalMatrices { c1, k0, k2, .. } = self.matrices;
        let v = self.speed(qdot);
        let (angles, rates) = (Vector2::new(q[0], q[1]), Vector2::new(qdot[0], qdot[1]));
        let force = Vector2::new(u[0], u[1]) - c1 * rates * v - (k0 * self.g + k2 * v * v) * angles;
        let qddot = self.inverse_mass() * force;
        ([qddot[0], qddot[1], 0.0], [])
    }
    fn energy(&self, _q: &[f64; 3], qdot: &[f64; 3]) -> f64 {
        qdot.iter().map(|v| v * v).sum()
    }
    fn constraint_residual(&self, _q: &[f64; 3], _qdot: &[f64; 3]) -> [f64; 0] {
        []
    }
    fn constraint_regularity(&self, _q: &[f64; 3]) -> f64 {
        1.0
    }
}

impl Linearization<3, 0, 2> for CanonicalBicycle {
    fn symmetry(&self) -> &[GroupFactor] {
        &[GroupFactor::Rotation(2)]
    }
    fn mass_matrix(&self, _q: &[f64; 3]) -> [[f64; 3]; 3] {
        let m = self.matrices.m;
        [
            [m[(0, 0)], m[(0, 1)], 0.0],
            [m[(1, 0)], m[(1, 1)], 0.0],
            [0.0, 0.0, 1.0],
        ]
    }
    fn constraint_matrix(&self, _q: &[f64; 3]) -> [[f64; 3]; 0] {
        []
    }
    /// By hand: `d/dq = -M^-1 (g K0 + v^2 K2)`, `d/dqdot = -M^-1 v C1` on
    /// roll and steer and `-M^-1 (C1 qdot + 2 v K2 q) dv/dtheta_r'` on the
    /// wheel's rate (`dv/dtheta_r' = -rR`), `d/du = M^-1`.
    fn acceleration_jacobian(
        &self,
        q: &[f64; 3],
        qdot: &[f64; 3],
        _u: &[f64; 2],
    ) -> AccelerationJacobian<3, 2> {
        let CanonicalMatrices { c1, k0, k2, .. } = self.matrices;
        let inverse = self.inverse_mass();
        let v = self.speed(qdot);
        let (angles, rates) = (Vector2::new(q[0], q[1]), Vector2::new(qdot[0], qdot[1]));
        let by_angles = -inverse * (k0 * self.g + k2 * v * v);
        let by_rates = -inverse * c1 * v;
        let by_speed = -inverse * (c1 * rates + k2 * angles * (2.0 * v)) * -self.r_r;
        let row = |i: usize| {
            (
                [by_angles[(i, 0)], by_angles[(i, 1)], 0.0],
                [by_rates[(i, 0)], by_rates[(i, 1)], by_speed[i]],
                [inverse[(i, 0)], inverse[(i, 1)]],
            )
        };
        let (rows, zero) = ([row(0), row(1)], ([0.0; 3], [0.0; 3], [0.0; 2]));
        let [first, second] = rows;
        (
            [first.0, second.0, zero.0],
            [first.1, second.1, zero.1],
            [first.2, second.2, zero.2],
        )
    }
}

/// No guarded expressions: the defaults.
impl Domain for CanonicalBicycle {}

impl ModelNames for CanonicalBicycle {
    fn coordinate_names(&self) -> &[&str] {
        &["phi", "delta", "theta_r"]
    }
    fn momentum_names(&self) -> &[&str] {
        &["a", "b", "c"]
    }
    fn input_names(&self) -> &[&str] {
        &["t_phi", "t_delta"]
    }
    fn constraint_names(&self) -> &[&str] {
        &[]
    }
}

fn assert_matrix(found: &DMatrix<f64>, expected: &Matrix2<f64>, what: &str) {
    for i in 0..2 {
        for j in 0..2 {
            let (f, e) = (found[(i, j)], expected[(i, j)]);
            assert!(
                (f - e).abs() <= 1e-11 * e.abs().max(1.0),
                "{what}[{i}][{j}]: {f} vs {e}"
            );
        }
    }
}

#[test]
fn two_speeds_give_back_the_canonical_matrices_and_table_2() {
    let parameters = BenchmarkParameters::benchmark();
    let bicycle = CanonicalBicycle {
        matrices: parameters.canonical(),
        g: parameters.g,
        r_r: parameters.r_r,
    };
    let model = Compiled::new(&bicycle);
    let at_speed = |v: f64| {
        let point = OperatingPoint::solve(
            &model,
            &[Some(0.0); 3],
            &[Some(0.0), Some(0.0), Some(-v / parameters.r_r)],
        )
        .expect("all velocities given");
        linearize(&model, &point, &[0.0, 0.0], &[]).expect("upright running is steady")
    };
    let (slow, fast) = (at_speed(3.0), at_speed(7.0));
    assert_eq!(
        slow.state,
        ["phi", "delta", "dot(phi)", "dot(delta)", "dot(theta_r)"]
    );
    let form = CanonicalForm::from_linearizations(
        (&slow, 3.0),
        (&fast, 7.0),
        &["phi", "delta"],
        &["dot(phi)", "dot(delta)"],
        parameters.g,
    )
    .expect("the canonical form");
    let CanonicalMatrices { m, c1, k0, k2 } = parameters.canonical();
    assert_matrix(&form.m, &m, "M");
    assert_matrix(&form.c1, &c1, "C1");
    assert_matrix(&form.k0, &k0, "K0");
    assert_matrix(&form.k2, &k2, "K2");
    for v in 1..=10 {
        let v = f64::from(v);
        let linear = at_speed(v);
        let reference = parameters.eigenvalues(v);
        let found: Vec<_> = linear
            .eigenvalues
            .iter()
            .filter(|&&e| !linear.is_zero(e))
            .collect();
        assert_eq!(found.len(), 4, "v = {v}: {:?}", linear.eigenvalues);
        for (found, expected) in found.iter().zip(reference) {
            assert!(
                (*found - expected).norm() < 1e-10,
                "v = {v}: {found} vs {expected}"
            );
        }
    }
}
