//! What a gait does: the motion of a body with an SE(2) symmetry whose
//! shape follows a prescribed periodic trajectory (Koon & Marsden, "The
//! geometric structure of nonholonomic mechanics", section 2; MATH.md
//! section 4).
//!
//! Along a shape trajectory `r(t)` with period `T`, the momentum obeys the
//! momentum equation `pdot = f(r, rdot, p)` and the configuration the
//! reconstruction `qdot = v(q, rdot, p)` (for a principally kinematic model
//! there is no momentum and `qdot = v(q, rdot)`, the nonholonomic
//! connection). The shape entries of `q` are the prescribed `r(t)`; the
//! others (the group `(x, y, theta)` and any coordinate the shape does not
//! fix) are integrated with classical RK4 at a fixed step. The net
//! displacement of a cycle is `g(t0)^-1 g(t0 + T)`, the group motion in the
//! body frame at the cycle's start.
//!
//! The momentum equation holds where the inputs act on the shape alone
//! (`h B = 0`, as for the snakeboard): a prescribed shape then determines
//! the motion. [`Locomotion::inputs_push_momentum`] says where they do not.

use crate::system::MomentumEquations;

/// A model with an SE(2) symmetry, seen through its momentum equation and
/// reconstruction at sizes known at run time.
pub trait Locomotion {
    /// The number of coordinates `n`.
    fn coordinate_count(&self) -> usize;
    /// The indices of `(x, y, theta)` in `q`.
    fn group(&self) -> [usize; 3];
    /// The indices of the shape coordinates `r` in `q`.
    fn shape_indices(&self) -> Vec<usize>;
    /// The number of nonholonomic momenta `p` (0 for a principally
    /// kinematic model).
    fn momentum_count(&self) -> usize;
    /// `pdot = f(r, rdot, p)` with the inputs zero.
    fn momentum_rhs(&self, r: &[f64], rdot: &[f64], p: &[f64]) -> Vec<f64>;
    /// `qdot` reconstructed from `(q, rdot, p)`.
    fn reconstructed_velocity(&self, q: &[f64], rdot: &[f64], p: &[f64]) -> Vec<f64>;
    /// Whether the inputs enter the momentum equation at `q` (`h B != 0`).
    fn inputs_push_momentum(&self, q: &[f64]) -> bool;
}

/// A generated model's [`MomentumEquations`] as [`Locomotion`], its `(x, y,
/// theta)` at the indices `group` (those of its `se2` symmetry factor).
pub struct FromEquations<'m, M, const N: usize, const R: usize, const K: usize, const P: usize> {
    model: &'m M,
    group: [usize; 3],
}

impl<'m, M, const N: usize, const R: usize, const K: usize, const P: usize>
    FromEquations<'m, M, N, R, K, P>
where
    M: MomentumEquations<N, R, K, P>,
{
    /// `model` with its `(x, y, theta)` at `group`.
    pub fn new(model: &'m M, group: [usize; 3]) -> Self {
        FromEquations { model, group }
    }
}

impl<M, const N: usize, const R: usize, const K: usize, const P: usize> Locomotion
    for FromEquations<'_, M, N, R, K, P>
where
    M: MomentumEquations<N, R, K, P>,
{
    fn coordinate_count(&self) -> usize {
        N
    }
    fn group(&self) -> [usize; 3] {
        self.group
    }
    fn shape_indices(&self) -> Vec<usize> {
        self.model.shape_indices().to_vec()
    }
    fn momentum_count(&self) -> usize {
        K
    }
    fn momentum_rhs(&self, r: &[f64], rdot: &[f64], p: &[f64]) -> Vec<f64> {
        let (r, rdot, p) = (sized(r), sized(rdot), sized(p));
        self.model.momentum_rhs(&r, &rdot, &p).to_vec()
    }
    fn reconstructed_velocity(&self, q: &[f64], rdot: &[f64], p: &[f64]) -> Vec<f64> {
        let (q, rdot, p) = (sized(q), sized(rdot), sized(p));
        self.model.reconstructed_velocity(&q, &rdot, &p).to_vec()
    }
    fn inputs_push_momentum(&self, q: &[f64]) -> bool {
        let coupling = self.model.momentum_input_matrix(&sized(q));
        coupling.iter().flatten().any(|&entry| entry != 0.0)
    }
}

/// `values` as an array of `S`, the missing entries 0 (the loop's sizes
/// are the model's).
fn sized<const S: usize>(values: &[f64]) -> [f64; S] {
    let mut array = [0.0; S];
    for (slot, value) in array.iter_mut().zip(values) {
        *slot = *value;
    }
    array
}

/// One cycle's net displacement `(x, y, theta)` in the body frame at its
/// start, and the momentum at its end.
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    /// `g(t0)^-1 g(t0 + T)`.
    pub displacement: [f64; 3],
    /// `p(t0 + T)`.
    pub momentum: Vec<f64>,
}

/// A prescribed periodic shape trajectory: `shape(t) = (r, rdot)`, period
/// `period`.
pub struct ShapeLoop<'a> {
    /// `(r(t), rdot(t))`.
    pub shape: &'a dyn Fn(f64) -> (Vec<f64>, Vec<f64>),
    /// `T`.
    pub period: f64,
}

/// The state the cycle integrates: the configuration and the momentum.
#[derive(Clone, Debug, PartialEq)]
pub struct GaitState {
    /// `q`, its shape entries at `r(t)`.
    pub q: Vec<f64>,
    /// `p`.
    pub p: Vec<f64>,
}

/// Runs `cycles` periods of `shape_loop` on `model` from `q0` (its shape
/// entries replaced by `r(0)`) and the momentum `p0`, `steps` RK4 steps per
/// period, calling `record(t, state)` at the start and after every step;
/// returns each cycle.
pub fn run(
    model: &dyn Locomotion,
    shape_loop: &ShapeLoop<'_>,
    (q0, p0): (&[f64], &[f64]),
    (cycles, steps): (usize, usize),
    record: &mut dyn FnMut(f64, &GaitState),
) -> Vec<Cycle> {
    let shape = model.shape_indices();
    let n = model.coordinate_count();
    let h = shape_loop.period / steps.max(1) as f64;
    let mut state = [q0, p0].concat();
    with_shape(&mut state[..n], &shape, &(shape_loop.shape)(0.0).0);
    let split = |state: &[f64]| GaitState {
        q: state[..n].to_vec(),
        p: state[n..].to_vec(),
    };
    record(0.0, &split(&state));
    let rate = |t: f64, state: &[f64]| rate(model, shape_loop, t, state);
    let mut done = Vec::with_capacity(cycles);
    for cycle in 0..cycles {
        let start = group_of(model, &state);
        for k in 0..steps.max(1) {
            let t = (cycle * steps.max(1) + k) as f64 * h;
            state = rk4_step(&rate, t, &state, h);
            let time = t + h;
            with_shape(&mut state[..n], &shape, &(shape_loop.shape)(time).0);
            record(time, &split(&state));
        }
        done.push(Cycle {
            displacement: relative(&start, &group_of(model, &state)),
            momentum: state[n..].to_vec(),
        });
    }
    done
}

/// `q` with its shape entries set to `r`.
fn with_shape(q: &mut [f64], shape: &[usize], r: &[f64]) {
    for (&i, &value) in shape.iter().zip(r) {
        q[i] = value;
    }
}

/// `(x, y, theta)` of `q`.
fn group_of(model: &dyn Locomotion, q: &[f64]) -> [f64; 3] {
    model.group().map(|i| q[i])
}

/// `a^-1 b` on SE(2).
pub fn relative(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    let (sin, cos) = a[2].sin_cos();
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    [cos * dx + sin * dy, -sin * dx + cos * dy, b[2] - a[2]]
}

/// `(qdot, pdot)` at `t` of the state `(q, p)`, the shape at `r(t)`.
fn rate(model: &dyn Locomotion, shape_loop: &ShapeLoop<'_>, t: f64, state: &[f64]) -> Vec<f64> {
    let (r, rdot) = (shape_loop.shape)(t);
    let n = model.coordinate_count();
    let (mut q, p) = (state[..n].to_vec(), &state[n..]);
    with_shape(&mut q, &model.shape_indices(), &r);
    let qdot = model.reconstructed_velocity(&q, &rdot, p);
    [qdot, model.momentum_rhs(&r, &rdot, p)].concat()
}

/// One classical RK4 step of `xdot = rate(t, x)` from `x` at `t`: the
/// integrator of every gait, so that a gait's forward sensitivities, the
/// same step applied to the variational equations, are the exact
/// derivatives of its discrete displacement.
pub fn rk4_step(rate: &dyn Fn(f64, &[f64]) -> Vec<f64>, t: f64, x: &[f64], h: f64) -> Vec<f64> {
    let moved =
        |k: &[f64], by: f64| -> Vec<f64> { x.iter().zip(k).map(|(x, k)| x + by * k).collect() };
    let k1 = rate(t, x);
    let k2 = rate(t + h / 2.0, &moved(&k1, h / 2.0));
    let k3 = rate(t + h / 2.0, &moved(&k2, h / 2.0));
    let k4 = rate(t + h, &moved(&k3, h));
    (0..x.len())
        .map(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{Locomotion, ShapeLoop, run};
    use std::f64::consts::PI;

    /// A body on `(x, y, theta)` with shape `(a, b)` whose body velocity is
    /// `(b adot, 0, (a bdot - b adot) / 2)`, and one momentum decaying as
    /// `pdot = -p` that adds `p` to the forward speed.
    struct Toy;

    impl Locomotion for Toy {
        fn coordinate_count(&self) -> usize {
            5
        }
        fn group(&self) -> [usize; 3] {
            [0, 1, 2]
        }
        fn shape_indices(&self) -> Vec<usize> {
            vec![3, 4]
        }
        fn momentum_count(&self) -> usize {
            1
        }
        fn momentum_rhs(&self, _r: &[f64], _rdot: &[f64], p: &[f64]) -> Vec<f64> {
            vec![-p[0]]
        }
        fn reconstructed_velocity(&self, q: &[f64], rdot: &[f64], p: &[f64]) -> Vec<f64> {
            let (a, b, theta) = (q[3], q[4], q[2]);
            let forward = b * rdot[0] + p[0];
            let turn = (a * rdot[1] - b * rdot[0]) / 2.0;
            vec![
                theta.cos() * forward,
                theta.sin() * forward,
                turn,
                rdot[0],
                rdot[1],
            ]
        }
        fn inputs_push_momentum(&self, _q: &[f64]) -> bool {
            false
        }
    }

    /// The unit circle `a = sin t`, `b = cos t` turns the body by the
    /// enclosed area with its orientation, `-pi`: the heading is
    /// `theta(t) = -t/2`, and `x + i y = int cos(t)^2 e^(-i t/2) dt`; the
    /// momentum decays by `e^-T`; the second cycle starts where the first
    /// ended and repeats it in its own frame.
    #[test]
    fn a_loop_moves_the_body_by_its_integral() {
        let circle = |t: f64| (vec![t.sin(), t.cos()], vec![t.cos(), -t.sin()]);
        let shape_loop = ShapeLoop {
            shape: &circle,
            period: 2.0 * PI,
        };
        let mut rows = 0;
        let cycles = run(
            &Toy,
            &shape_loop,
            (&[0.0; 5], &[0.0]),
            (2, 2000),
            &mut |_, _| rows += 1,
        );
        assert_eq!(rows, 4001);
        // The closed form, by the midpoint rule on a fine grid.
        let (mut x, mut y) = (0.0, 0.0);
        let n = 200_000;
        for k in 0..n {
            let t = (k as f64 + 0.5) * 2.0 * PI / n as f64;
            let speed = t.cos().powi(2) * 2.0 * PI / n as f64;
            x += (-t / 2.0).cos() * speed;
            y += (-t / 2.0).sin() * speed;
        }
        // RK4's global error at h = pi/1000 is of order h^4 = 1e-10.
        for cycle in &cycles {
            let [dx, dy, dtheta] = cycle.displacement;
            assert!((dtheta + PI).abs() < 1e-10, "{dtheta}");
            assert!(
                (dx - x).abs() < 1e-9 && (dy - y).abs() < 1e-9,
                "{dx} {dy} vs {x} {y}"
            );
        }
        let decayed = run(
            &Toy,
            &shape_loop,
            (&[0.0; 5], &[1.0]),
            (1, 2000),
            &mut |_, _| {},
        );
        assert!((decayed[0].momentum[0] - (-2.0 * PI).exp()).abs() < 1e-12);
    }
}
