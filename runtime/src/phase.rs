//! The group displacement of a gait on SE(2), split into its geometric and
//! dynamic parts (Koon & Marsden, "The geometric structure of nonholonomic
//! mechanics", Theorem 2.2; MATH.md section 4).
//!
//! Along a prescribed shape loop `r(t)`, `0 <= t <= T`, the momentum obeys
//! `pdot = f(r, rdot, p)` (the momentum equation) and the group element
//! `g = (x, y, theta)` the reconstruction `gdot = g xi`, `xi = xi(r, rdot, p)`:
//!
//! ```text
//! xdot = cos theta v1 - sin theta v2,   ydot = sin theta v1 + cos theta v2,   thetadot = omega
//! ```
//!
//! The geometric part `g_geo` is the reconstruction with zero momentum,
//! `xi = xi(r, rdot, 0) = -A_nh rdot` (for an abelian group, `-∮ A_nh dr`);
//! the dynamic part is the rest, `g_dyn = g_geo^-1 g`, so `g = g_geo g_dyn`.
//! All three start at the identity. Integration is classical RK4 with a fixed
//! step, on the stack.

/// The group displacement over one period, each as `(x, y, theta)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Displacement {
    /// `g(T)` with the momentum equation.
    pub total: [f64; 3],
    /// `g_geo(T)`, with zero momentum.
    pub geometric: [f64; 3],
    /// `g_geo(T)^-1 g(T)`.
    pub dynamic: [f64; 3],
}

/// The state integrated: the group element, the momentum, the geometric part.
#[derive(Clone, Copy)]
struct State<const MP: usize> {
    group: [f64; 3],
    momentum: [f64; MP],
    geometric: [f64; 3],
}

impl<const MP: usize> State<MP> {
    /// `self + h rate`.
    fn step(&self, rate: &State<MP>, h: f64) -> State<MP> {
        State {
            group: add(&self.group, &rate.group, h),
            momentum: add(&self.momentum, &rate.momentum, h),
            geometric: add(&self.geometric, &rate.geometric, h),
        }
    }
}

fn add<const N: usize>(a: &[f64; N], b: &[f64; N], h: f64) -> [f64; N] {
    core::array::from_fn(|i| a[i] + h * b[i])
}

/// `gdot = g xi` on SE(2).
fn group_rate(g: &[f64; 3], xi: &[f64; 3]) -> [f64; 3] {
    let (sin, cos) = g[2].sin_cos();
    [cos * xi[0] - sin * xi[1], sin * xi[0] + cos * xi[1], xi[2]]
}

/// `a^-1 b` on SE(2).
fn relative(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    let (sin, cos) = a[2].sin_cos();
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    [cos * dx + sin * dy, -sin * dx + cos * dy, b[2] - a[2]]
}

/// Integrates one period `T` of the shape loop `shape(t) = (r, rdot)` with
/// `steps` RK4 steps, from the identity and the momentum `p0`, with the
/// model's `momentum_rhs` and `body_velocity`; returns the displacement and
/// the final momentum.
pub fn se2_displacement<const NR: usize, const MP: usize>(
    shape: impl Fn(f64) -> ([f64; NR], [f64; NR]),
    period: f64,
    p0: [f64; MP],
    momentum_rhs: impl Fn(&[f64; NR], &[f64; NR], &[f64; MP]) -> [f64; MP],
    body_velocity: impl Fn(&[f64; NR], &[f64; NR], &[f64; MP]) -> [f64; 3],
    steps: usize,
) -> (Displacement, [f64; MP]) {
    let rate = |t: f64, s: &State<MP>| {
        let (r, rdot) = shape(t);
        State {
            group: group_rate(&s.group, &body_velocity(&r, &rdot, &s.momentum)),
            momentum: momentum_rhs(&r, &rdot, &s.momentum),
            geometric: group_rate(&s.geometric, &body_velocity(&r, &rdot, &[0.0; MP])),
        }
    };
    let h = period / steps.max(1) as f64;
    let mut s = State {
        group: [0.0; 3],
        momentum: p0,
        geometric: [0.0; 3],
    };
    for k in 0..steps {
        let t = k as f64 * h;
        let k1 = rate(t, &s);
        let k2 = rate(t + h / 2.0, &s.step(&k1, h / 2.0));
        let k3 = rate(t + h / 2.0, &s.step(&k2, h / 2.0));
        let k4 = rate(t + h, &s.step(&k3, h));
        s = s
            .step(&k1, h / 6.0)
            .step(&k2, h / 3.0)
            .step(&k3, h / 3.0)
            .step(&k4, h / 6.0);
    }
    let displacement = Displacement {
        total: s.group,
        geometric: s.geometric,
        dynamic: relative(&s.geometric, &s.group),
    };
    (displacement, s.momentum)
}

#[cfg(test)]
mod tests {
    use super::se2_displacement;

    /// With no momentum directions and a body velocity `(rdot, 0, 0)` along a
    /// loop `r = sin t`, the body comes back: zero displacement; with
    /// `xi = (1, 0, 0)` constant (a dynamic drift), `x` advances by `T`.
    #[test]
    fn straight_line_motions() {
        let loop_ = |t: f64| ([t.sin()], [t.cos()]);
        let period = 2.0 * core::f64::consts::PI;
        let (back, _) = se2_displacement(
            loop_,
            period,
            [],
            |_, _, _| [],
            |_, rdot, _| [rdot[0], 0.0, 0.0],
            1000,
        );
        assert!(back.total.iter().all(|v| v.abs() < 1e-12), "{back:?}");
        let (drift, p) = se2_displacement(
            loop_,
            period,
            [1.0],
            |_, _, _| [0.0],
            |_, _, p| [p[0], 0.0, 0.0],
            1000,
        );
        assert_eq!(p, [1.0]);
        assert!((drift.total[0] - period).abs() < 1e-12, "{drift:?}");
        assert!(drift.geometric.iter().all(|v| v.abs() < 1e-15));
        assert!((drift.dynamic[0] - period).abs() < 1e-12);
    }
}
