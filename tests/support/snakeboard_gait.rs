//! The snakeboard's gaits from rest by the hand-derived equations of
//! MATH.md 4.1, integrated independently of the tool, and the gait `psi =
//! 0.8 sin t`, `phi = 0.5 cos t` as `chaplygin gait` takes it.

use std::f64::consts::PI;

/// The gait as `chaplygin gait` takes it: the model, its shape and laws
/// over the period 2 pi.
pub const GAIT: [&str; 9] = [
    "snakeboard",
    "--shape",
    "psi,phi",
    "--cycle",
    "psi=0.8*sin(t)",
    "--cycle",
    "phi=0.5*cos(t)",
    "--period",
    "6.283185307179586",
];

/// One period `2 pi` of the gait `shape(t) = (phi, psidot, phidot)` from rest (m = 1, r = 0.5,
/// Jt = 0.3): with `Delta = m r^2 + Jt sin^2 phi`,
/// `pdot = (m r Jt cos phi / Delta) psidot phidot + (Jt sin phi cos phi / Delta) phidot p`,
/// `v1 = r cos phi (r p - Jt sin phi psidot) / Delta`, `v2 = 0`,
/// `omega = v1 tan phi / r`, and `(x, y, theta)' = (cos theta v1, sin theta v1, omega)`;
/// RK4 with `steps` steps. Without `momentum` the momentum `p` is held at
/// 0: the gait's geometric part. Returns `(x, y, theta)`.
pub fn hand_derived(
    shape: impl Fn(f64) -> (f64, f64, f64),
    momentum: bool,
    steps: usize,
) -> [f64; 3] {
    let (m, r, jt) = (1.0, 0.5, 0.3);
    let rate = |t: f64, s: [f64; 4]| {
        let (phi, psidot, phidot) = shape(t);
        let delta = m * r * r + jt * phi.sin().powi(2);
        let p = s[3];
        let pdot = m * r * jt * phi.cos() / delta * psidot * phidot
            + jt * phi.sin() * phi.cos() / delta * phidot * p;
        let v1 = r * phi.cos() * (r * p - jt * phi.sin() * psidot) / delta;
        let omega = v1 * phi.tan() / r;
        let pdot = if momentum { pdot } else { 0.0 };
        [s[2].cos() * v1, s[2].sin() * v1, omega, pdot]
    };
    let s = rk4_from_zero(rate, steps);
    [s[0], s[1], s[2]]
}

/// [`hand_derived`] of the gait `psi = 0.8 sin t`, `phi = 0.5 cos t`.
pub fn hand_derived_cycle(steps: usize) -> [f64; 3] {
    let shape = |t: f64| (0.5 * t.cos(), 0.8 * t.cos(), -0.5 * t.sin());
    hand_derived(shape, true, steps)
}

/// Classical RK4 of `rate` from 0 over `t` in `[0, 2 pi]`, `steps` steps.
pub fn rk4_from_zero<const N: usize>(
    rate: impl Fn(f64, [f64; N]) -> [f64; N],
    steps: usize,
) -> [f64; N] {
    let h = 2.0 * PI / steps as f64;
    let mut s = [0.0; N];
    let add = |a: [f64; N], b: [f64; N], h: f64| core::array::from_fn(|i| a[i] + h * b[i]);
    for k in 0..steps {
        let t = k as f64 * h;
        let k1 = rate(t, s);
        let k2 = rate(t + h / 2.0, add(s, k1, h / 2.0));
        let k3 = rate(t + h / 2.0, add(s, k2, h / 2.0));
        let k4 = rate(t + h, add(s, k3, h));
        s = core::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    s
}
