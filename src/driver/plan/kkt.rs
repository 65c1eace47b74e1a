//! The first-order (KKT) conditions of an [`Nlp`] at a solver's answer,
//! computed from the program's own exact derivatives, not from the
//! solver's report (Nocedal and Wright, "Numerical Optimization", 2nd ed.,
//! Theorem 12.1):
//!
//! ```text
//! primal           max(|c(z)|, lo - z, z - hi)                      (0 where met)
//! dual             |grad J + Jc^T lambda - z_lo + z_hi| / s_d,       z_lo, z_hi >= 0
//! complementarity  max(z_lo (z - lo), z_hi (hi - z))
//! ```
//!
//! each the largest over its entries. The dual residual is scaled as
//! Ipopt scales it (Wächter and Biegler 2006, eq. 5): `s_d = max(1, m /
//! 100)` with `m` the mean magnitude of the multipliers. A fixed variable
//! (`lo = hi`) has a free bound multiplier, so its entry of the dual
//! residual is no condition; a multiplier of an infinite bound must vanish,
//! and a negative one counts against the dual residual.

use super::nlp::{Nlp, Solution};

/// The residuals of the KKT conditions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Residuals {
    /// The largest constraint or bound violation.
    pub primal: f64,
    /// The largest entry of the Lagrangian's gradient (scaled), or of a
    /// bound multiplier of the wrong sign.
    pub dual: f64,
    /// The largest product of a bound multiplier and its bound's slack.
    pub complementarity: f64,
}

impl Residuals {
    /// Whether each residual is within `tol` (a NaN is not).
    pub fn within(&self, tol: f64) -> bool {
        [self.primal, self.dual, self.complementarity]
            .iter()
            .all(|r| *r <= tol)
    }
}

/// The KKT residuals of `nlp` at `solution`; `None` where the program's
/// functions are not finite there.
pub fn residuals(nlp: &dyn Nlp, solution: &Solution) -> Option<Residuals> {
    let z = &solution.z;
    let (lo, hi) = nlp.bounds();
    let mut c = vec![0.0; nlp.constraints()];
    if !nlp.residuals(z, &mut c) {
        return None;
    }
    let mut gradient = lagrangian_gradient(nlp, z, 1.0, &solution.multipliers)?;
    let bounds = |j: usize| (lo[j], hi[j], solution.lower[j], solution.upper[j]);
    let mut primal = largest(c.iter().map(|r| r.abs()));
    let (mut dual, mut complementarity) = (0.0_f64, 0.0_f64);
    for (j, &zj) in z.iter().enumerate() {
        let (l, h, zl, zh) = bounds(j);
        primal = primal.max(l - zj).max(zj - h);
        complementarity = complementarity
            .max(slack_product(zl, zj - l))
            .max(slack_product(zh, h - zj));
        dual = dual.max(-zl).max(-zh);
        if l != h {
            gradient[j] += -zl + zh;
        } else {
            gradient[j] = 0.0;
        }
    }
    let scale = dual_scale(solution);
    dual = dual.max(largest(gradient.iter().map(|g| g.abs())) / scale);
    Some(Residuals {
        primal,
        dual,
        complementarity,
    })
}

/// The constraint of `nlp` furthest from holding at `z`, and `|c_i(z)|`;
/// `None` without constraints or where they are not finite.
pub fn largest_violation(nlp: &dyn Nlp, z: &[f64]) -> Option<(usize, f64)> {
    let mut c = vec![0.0; nlp.constraints()];
    if !nlp.residuals(z, &mut c) {
        return None;
    }
    (c.iter().map(|r| r.abs()).enumerate()).max_by(|a, b| a.1.total_cmp(&b.1))
}

/// `sigma grad J(z) + Jc(z)^T lambda`, from the exact gradient and
/// Jacobian; `None` where they are not finite.
pub(super) fn lagrangian_gradient(
    nlp: &dyn Nlp,
    z: &[f64],
    sigma: f64,
    lambda: &[f64],
) -> Option<Vec<f64>> {
    let mut gradient = vec![0.0; nlp.variables()];
    let mut jacobian = vec![0.0; nlp.jacobian_structure().len()];
    if !(nlp.gradient(z, &mut gradient) && nlp.jacobian_values(z, &mut jacobian)) {
        return None;
    }
    for g in &mut gradient {
        *g *= sigma;
    }
    for (&(row, column), value) in nlp.jacobian_structure().iter().zip(&jacobian) {
        gradient[column] += lambda[row] * value;
    }
    Some(gradient)
}

/// `|multiplier * slack|`, the multiplier itself where the bound is
/// infinite (it must vanish).
fn slack_product(multiplier: f64, slack: f64) -> f64 {
    if slack.is_finite() {
        (multiplier * slack).abs()
    } else {
        multiplier.abs()
    }
}

/// Ipopt's `s_d`: 1, or the multipliers' mean magnitude over 100 if larger.
fn dual_scale(solution: &Solution) -> f64 {
    let all = || {
        solution
            .multipliers
            .iter()
            .chain(&solution.lower)
            .chain(&solution.upper)
    };
    let count = all().count().max(1) as f64;
    let mean = all().map(|m| m.abs()).sum::<f64>() / count;
    (mean / 100.0).max(1.0)
}

/// The largest of `values`, 0 for none; NaN if any is NaN.
fn largest(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |worst, v| if v.is_nan() { v } else { worst.max(v) })
}

#[cfg(test)]
mod tests {
    use super::{Nlp, Residuals, Solution, residuals};

    /// `min (z0 - 2)^2 + z1^2  s.t.  z0 + z1 = 1,  z0 <= 1`: the optimum
    /// is `z = (1, 0)` with `lambda = 0` and the upper bound's multiplier
    /// `2` (by hand: `grad J = (-2, 0)`, `Jc = (1, 1)`).
    struct Bounded;

    const LO: [f64; 2] = [f64::NEG_INFINITY, f64::NEG_INFINITY];
    const HI: [f64; 2] = [1.0, f64::INFINITY];
    const STRUCTURE: [(usize, usize); 2] = [(0, 0), (0, 1)];

    impl Nlp for Bounded {
        fn variables(&self) -> usize {
            2
        }
        fn constraints(&self) -> usize {
            1
        }
        fn bounds(&self) -> (&[f64], &[f64]) {
            (&LO, &HI)
        }
        fn guess(&self) -> Vec<f64> {
            vec![0.0, 0.0]
        }
        fn objective(&self, z: &[f64]) -> Option<f64> {
            Some((z[0] - 2.0).powi(2) + z[1] * z[1])
        }
        fn gradient(&self, z: &[f64], gradient: &mut [f64]) -> bool {
            gradient.copy_from_slice(&[2.0 * (z[0] - 2.0), 2.0 * z[1]]);
            true
        }
        fn residuals(&self, z: &[f64], residuals: &mut [f64]) -> bool {
            residuals[0] = z[0] + z[1] - 1.0;
            true
        }
        fn jacobian_structure(&self) -> &[(usize, usize)] {
            &STRUCTURE
        }
        fn jacobian_values(&self, _z: &[f64], values: &mut [f64]) -> bool {
            values.copy_from_slice(&[1.0, 1.0]);
            true
        }
    }

    fn at(z: [f64; 2], multiplier: f64, upper: f64) -> Residuals {
        let solution = Solution {
            z: z.to_vec(),
            multipliers: vec![multiplier],
            lower: vec![0.0, 0.0],
            upper: vec![upper, 0.0],
            iterations: 0,
            status: "test".into(),
        };
        residuals(&Bounded, &solution).expect("finite")
    }

    #[test]
    fn the_optimum_passes() {
        let optimum = at([1.0, 0.0], 0.0, 2.0);
        assert_eq!(optimum.primal, 0.0);
        assert_eq!(optimum.dual, 0.0);
        assert_eq!(optimum.complementarity, 0.0);
        assert!(optimum.within(1e-12));
    }

    #[test]
    fn perturbed_points_fail() {
        let infeasible = at([1.0, 1e-3], 0.0, 2.0);
        assert!((infeasible.primal - 1e-3).abs() < 1e-15);
        assert!(!infeasible.within(1e-6));
        let beyond_bound = at([1.0 + 1e-3, -1e-3], 0.0, 2.0);
        assert!((beyond_bound.primal - 1e-3).abs() < 1e-15);
        let wrong_multiplier = at([1.0, 0.0], 0.0, 1.0);
        assert_eq!(wrong_multiplier.dual, 1.0);
        let wrong_sign = at([1.0, 0.0], 0.0, -2.0);
        assert!(wrong_sign.dual >= 2.0);
        let slack_with_multiplier = at([0.5, 0.5], 0.0, 1.0);
        assert_eq!(slack_with_multiplier.complementarity, 0.5);
    }
}
