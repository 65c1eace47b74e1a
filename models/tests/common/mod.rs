//! Shared test support: checks of the reduced port-Hamiltonian items for
//! every model, and a test model with a dense metric ([`Towed`]).
//!
//! [`Reduced`] views a generated model's items through slices so that one
//! generic check serves every model; [`reduced_model!`] implements it for a
//! generated struct.

#![allow(dead_code)]

pub mod random;
pub mod towed;

/// The reduced port-Hamiltonian items of a generated model, on slices.
pub trait Reduced {
    /// Number of coordinates n.
    const N: usize;
    /// Number of reduced momenta k.
    const K: usize;
    /// Number of inputs p.
    const P: usize;
    fn constraint_residual(&self, q: &[f64], qdot: &[f64]) -> Vec<f64>;
    fn momenta(&self, q: &[f64], qdot: &[f64]) -> Vec<f64>;
    fn velocities(&self, q: &[f64], alpha: &[f64]) -> Vec<f64>;
    fn hamiltonian(&self, x: &[f64]) -> f64;
    fn hamiltonian_gradient(&self, x: &[f64]) -> Vec<f64>;
    fn structure_matrix(&self, x: &[f64]) -> Vec<Vec<f64>>;
    fn input_matrix(&self, x: &[f64]) -> Vec<Vec<f64>>;
    fn reduced_rhs(&self, x: &[f64], u: &[f64]) -> Vec<f64>;
    fn reduced_rhs_jacobian(&self, x: &[f64], u: &[f64]) -> Vec<Vec<f64>>;
    fn output(&self, x: &[f64]) -> Vec<f64>;
    fn output_jacobian(&self, x: &[f64]) -> Vec<Vec<f64>>;
}

/// Implements [`Reduced`] for a generated model by forwarding to its items.
#[macro_export]
macro_rules! reduced_model {
    ($model:ty) => {
        impl $crate::common::Reduced for $model {
            const N: usize = <$model>::N;
            const K: usize = <$model>::K;
            const P: usize = <$model>::P;
            fn constraint_residual(&self, q: &[f64], qdot: &[f64]) -> Vec<f64> {
                <$model>::constraint_residual(self, q.try_into().unwrap(), qdot.try_into().unwrap())
                    .to_vec()
            }
            fn momenta(&self, q: &[f64], qdot: &[f64]) -> Vec<f64> {
                <$model>::momenta(self, q.try_into().unwrap(), qdot.try_into().unwrap()).to_vec()
            }
            fn velocities(&self, q: &[f64], alpha: &[f64]) -> Vec<f64> {
                <$model>::velocities(self, q.try_into().unwrap(), alpha.try_into().unwrap())
                    .to_vec()
            }
            fn hamiltonian(&self, x: &[f64]) -> f64 {
                <$model>::hamiltonian(self, x.try_into().unwrap())
            }
            fn hamiltonian_gradient(&self, x: &[f64]) -> Vec<f64> {
                <$model>::hamiltonian_gradient(self, x.try_into().unwrap()).to_vec()
            }
            fn structure_matrix(&self, x: &[f64]) -> Vec<Vec<f64>> {
                <$model>::structure_matrix(self, x.try_into().unwrap())
                    .iter()
                    .map(|r| r.to_vec())
                    .collect()
            }
            fn input_matrix(&self, x: &[f64]) -> Vec<Vec<f64>> {
                <$model>::input_matrix(self, x.try_into().unwrap())
                    .iter()
                    .map(|r| r.to_vec())
                    .collect()
            }
            fn reduced_rhs(&self, x: &[f64], u: &[f64]) -> Vec<f64> {
                <$model>::reduced_rhs(self, x.try_into().unwrap(), u.try_into().unwrap()).to_vec()
            }
            fn reduced_rhs_jacobian(&self, x: &[f64], u: &[f64]) -> Vec<Vec<f64>> {
                <$model>::reduced_rhs_jacobian(self, x.try_into().unwrap(), u.try_into().unwrap())
                    .iter()
                    .map(|r| r.to_vec())
                    .collect()
            }
            fn output(&self, x: &[f64]) -> Vec<f64> {
                <$model>::output(self, x.try_into().unwrap()).to_vec()
            }
            fn output_jacobian(&self, x: &[f64]) -> Vec<Vec<f64>> {
                <$model>::output_jacobian(self, x.try_into().unwrap())
                    .iter()
                    .map(|r| r.to_vec())
                    .collect()
            }
        }
    };
}

/// A small deterministic generator (SplitMix64).
pub struct Random(u64);

impl Random {
    pub fn new(seed: u64) -> Random {
        Random(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[low, high)`.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn vector(&mut self, length: usize, low: f64, high: f64) -> Vec<f64> {
        (0..length).map(|_| self.uniform(low, high)).collect()
    }
}

/// A random reduced state and input: `q` from `configuration`, momenta and
/// inputs in `[-2, 2)`.
pub struct Sample {
    pub q: Vec<f64>,
    pub alpha: Vec<f64>,
    pub x: Vec<f64>,
    pub u: Vec<f64>,
}

pub fn sample<M: Reduced>(
    random: &mut Random,
    configuration: &dyn Fn(&mut Random) -> Vec<f64>,
) -> Sample {
    let q = configuration(random);
    let alpha = random.vector(M::K, -2.0, 2.0);
    let u = random.vector(M::P, -2.0, 2.0);
    let x = q.iter().chain(&alpha).copied().collect();
    Sample { q, alpha, x, u }
}

fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Samples drawn by [`check_reduced_model`].
pub const SAMPLES: usize = 1000;

/// Every generic property of the reduced items, at [`SAMPLES`] random states.
pub fn check_reduced_model<M: Reduced>(
    model: &M,
    seed: u64,
    configuration: &dyn Fn(&mut Random) -> Vec<f64>,
) {
    let mut random = Random::new(seed);
    for _ in 0..SAMPLES {
        let s = sample::<M>(&mut random, configuration);
        velocities_satisfy_the_constraints(model, &s);
        momenta_invert_velocities(model, &s);
        power_balance_holds(model, &s);
        gradient_matches_central_differences(model, &s);
        jacobian_matches_central_differences(model, &s);
        output_jacobian_matches_central_differences(model, &s);
    }
}

/// `A(q) velocities(q, alpha) = 0`.
pub fn velocities_satisfy_the_constraints<M: Reduced>(model: &M, s: &Sample) {
    let qdot = model.velocities(&s.q, &s.alpha);
    let residual = model.constraint_residual(&s.q, &qdot);
    let scale = max_abs(&qdot).max(1.0);
    assert!(
        max_abs(&residual) <= 1e-12 * scale,
        "residual {residual:?} at q {:?}",
        s.q
    );
}

/// `momenta(q, velocities(q, alpha)) = alpha`.
pub fn momenta_invert_velocities<M: Reduced>(model: &M, s: &Sample) {
    let qdot = model.velocities(&s.q, &s.alpha);
    let alpha = model.momenta(&s.q, &qdot);
    for (a, b) in alpha.iter().zip(&s.alpha) {
        assert!(
            (a - b).abs() <= 1e-12 * max_abs(&s.alpha).max(1.0),
            "{alpha:?} vs {:?}",
            s.alpha
        );
    }
}

/// `dHbar/dt = dHbar/dx . xdot = y . u` (Jbar is skew).
pub fn power_balance_holds<M: Reduced>(model: &M, s: &Sample) {
    let gradient = model.hamiltonian_gradient(&s.x);
    let xdot = model.reduced_rhs(&s.x, &s.u);
    let y = model.output(&s.x);
    let rate = dot(&gradient, &xdot);
    let supplied = dot(&y, &s.u);
    let scale: f64 = gradient
        .iter()
        .zip(&xdot)
        .map(|(g, v)| (g * v).abs())
        .sum::<f64>()
        + supplied.abs();
    assert!(
        (rate - supplied).abs() <= 1e-12 * scale.max(1e-300),
        "dH/dt {rate} vs y.u {supplied}"
    );
}

/// Central differences with a step scaled to the coordinate; error O(h^2).
fn central_difference(f: &dyn Fn(&[f64]) -> Vec<f64>, x: &[f64], j: usize) -> Vec<f64> {
    let h = 1e-6 * x[j].abs().max(1.0);
    let (mut plus, mut minus) = (x.to_vec(), x.to_vec());
    plus[j] += h;
    minus[j] -= h;
    let (up, down) = (f(&plus), f(&minus));
    up.iter()
        .zip(&down)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect()
}

pub fn gradient_matches_central_differences<M: Reduced>(model: &M, s: &Sample) {
    let gradient = model.hamiltonian_gradient(&s.x);
    let energy = |x: &[f64]| vec![model.hamiltonian(x)];
    for (j, derivative) in gradient.iter().enumerate() {
        let numeric = central_difference(&energy, &s.x, j)[0];
        let tolerance = 1e-6 * (derivative.abs() + model.hamiltonian(&s.x).abs()).max(1.0);
        assert!(
            (numeric - derivative).abs() <= tolerance,
            "dH/dx[{j}] {derivative} vs {numeric}"
        );
    }
}

pub fn jacobian_matches_central_differences<M: Reduced>(model: &M, s: &Sample) {
    let jacobian = model.reduced_rhs_jacobian(&s.x, &s.u);
    let rhs = |x: &[f64]| model.reduced_rhs(x, &s.u);
    check_jacobian("xdot", &jacobian, &rhs, &s.x);
}

pub fn output_jacobian_matches_central_differences<M: Reduced>(model: &M, s: &Sample) {
    let jacobian = model.output_jacobian(&s.x);
    check_jacobian("y", &jacobian, &|x: &[f64]| model.output(x), &s.x);
}

/// Each column of `jacobian` against central differences of `f` at `x`.
fn check_jacobian(name: &str, jacobian: &[Vec<f64>], f: &dyn Fn(&[f64]) -> Vec<f64>, x: &[f64]) {
    let scale = max_abs(&f(x)).max(1.0);
    for j in 0..x.len() {
        let numeric = central_difference(f, x, j);
        for (i, (value, row)) in numeric.iter().zip(jacobian).enumerate() {
            let tolerance = 1e-6 * (row[j].abs() + scale);
            assert!(
                (value - row[j]).abs() <= tolerance,
                "d {name}[{i}]/dx[{j}] {} vs {value}",
                row[j]
            );
        }
    }
}

/// One classical Runge-Kutta step of `xdot = f(t, x)`.
pub fn rk4_step(f: &dyn Fn(f64, &[f64]) -> Vec<f64>, t: f64, x: &[f64], dt: f64) -> Vec<f64> {
    let shifted =
        |k: &[f64], c: f64| -> Vec<f64> { x.iter().zip(k).map(|(a, b)| a + c * b).collect() };
    let k1 = f(t, x);
    let k2 = f(t + dt / 2.0, &shifted(&k1, dt / 2.0));
    let k3 = f(t + dt / 2.0, &shifted(&k2, dt / 2.0));
    let k4 = f(t + dt, &shifted(&k3, dt));
    (0..x.len())
        .map(|i| x[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
        .collect()
}

/// Integrates `xdot = f(t, x)` with `steps` RK4 steps of `dt`; every state, the initial included.
pub fn rk4(
    f: &dyn Fn(f64, &[f64]) -> Vec<f64>,
    x0: &[f64],
    dt: f64,
    steps: usize,
) -> Vec<Vec<f64>> {
    let mut states = vec![x0.to_vec()];
    for step in 0..steps {
        let next = rk4_step(f, step as f64 * dt, states.last().unwrap(), dt);
        states.push(next);
    }
    states
}

/// `|exact - differenced| <= 1e-6 max(1, |exact|)` entry by entry (central
/// differences are good to about 1e-10 relative on these smooth functions;
/// the bound leaves room for their round-off on larger entries).
pub fn assert_close<const R: usize, const K: usize>(
    exact: &[[f64; K]; R],
    differenced: &[[f64; K]; R],
    what: &str,
) {
    for i in 0..R {
        for j in 0..K {
            let (e, d) = (exact[i][j], differenced[i][j]);
            assert!(
                (e - d).abs() <= 1e-6 * e.abs().max(1.0),
                "{what}[{i}][{j}]: exact {e}, central differences {d}"
            );
        }
    }
}

/// Compares the three exact Jacobians of `model` with central differences
/// of its `acceleration` at `(q, qdot, u)`.
pub fn check_jacobians<M, const N: usize, const C: usize, const P: usize>(
    model: &M,
    q: [f64; N],
    qdot: [f64; N],
    u: [f64; P],
) where
    M: chaplygin::runtime::linearize::Linearization<N, C, P>,
{
    let (by_q, by_qdot, by_u) = model.acceleration_jacobian(&q, &qdot, &u);
    let qddot = |q: &[f64; N], qdot: &[f64; N], u: &[f64; P]| model.acceleration(q, qdot, u).0;
    assert_close(
        &by_q,
        &chaplygin::runtime::linalg::central_difference_jacobian(|q| qddot(q, &qdot, &u), &q),
        "d qddot/dq",
    );
    assert_close(
        &by_qdot,
        &chaplygin::runtime::linalg::central_difference_jacobian(|qdot| qddot(&q, qdot, &u), &qdot),
        "d qddot/dqdot",
    );
    assert_close(
        &by_u,
        &chaplygin::runtime::linalg::central_difference_jacobian(|u| qddot(&q, &qdot, u), &u),
        "d qddot/du",
    );
}
