//! The systems integrators run on, and the formulations generated models
//! implement.
//!
//! An integrator sees an [`OdeSystem`] `xdot = f(t, x)` of fixed dimension
//! `D` (with a [`Jacobian`] when it is implicit). A generated model
//! implements [`ReducedPortHamiltonian`] (the reduced flow in `x = (q, alpha)`,
//! MATH.md section 3) and [`LagrangeDalembert`] (the equations with
//! multipliers in `(q, qdot)`, MATH.md section 2); [`Reduced`] and
//! [`Dalembert`] close either with an [`Input`] `u(t)` into an [`OdeSystem`].

/// A first-order system `xdot = f(t, x)` in `D` states.
pub trait OdeSystem<const D: usize> {
    /// The derivative `f(t, x)`.
    fn rhs(&self, t: f64, x: &[f64; D]) -> [f64; D];
}

/// An [`OdeSystem`] with its Jacobian `df/dx`.
pub trait Jacobian<const D: usize>: OdeSystem<D> {
    /// `df/dx (t, x)`: row `i`, column `j` is `d f_i / d x_j`.
    fn jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; D];
}

/// An [`OdeSystem`] with an energy, conserved when no power enters.
pub trait Energy<const D: usize>: OdeSystem<D> {
    /// The energy at state `x`.
    fn energy(&self, x: &[f64; D]) -> f64;
}

/// The reduced port-Hamiltonian form `xdot = J(x) dH/dx + G(x) u`,
/// `y = G(x)^T dH/dx`, with `x = (q, alpha)` of size `S = n + k` and `P`
/// inputs (MATH.md section 3). Generated models implement it.
pub trait ReducedPortHamiltonian<const S: usize, const P: usize> {
    /// `xdot` at state `x` and input `u`.
    fn reduced_rhs(&self, x: &[f64; S], u: &[f64; P]) -> [f64; S];
    /// `d xdot / dx` at state `x` and input `u`.
    fn reduced_rhs_jacobian(&self, x: &[f64; S], u: &[f64; P]) -> [[f64; S]; S];
    /// The Hamiltonian `H(x)`.
    fn hamiltonian(&self, x: &[f64; S]) -> f64;
    /// `dH/dx`.
    fn hamiltonian_gradient(&self, x: &[f64; S]) -> [f64; S];
    /// The output `y`, power-conjugate to `u`.
    fn output(&self, x: &[f64; S]) -> [f64; P];
}

/// The Lagrange-d'Alembert equations in `(q, qdot)`: `N` coordinates, `C`
/// constraints, `P` inputs (MATH.md section 2). Generated models implement it.
pub trait LagrangeDalembert<const N: usize, const C: usize, const P: usize> {
    /// The accelerations `qddot` and the multipliers `lambda`.
    fn acceleration(&self, q: &[f64; N], qdot: &[f64; N], u: &[f64; P]) -> ([f64; N], [f64; C]);
    /// The energy `T + V`.
    fn energy(&self, q: &[f64; N], qdot: &[f64; N]) -> f64;
    /// The constraint residual `A(q) qdot`.
    fn constraint_residual(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; C];
}

/// A model in its reduced form driven by the input `input(t)`: an
/// [`OdeSystem`] in `x = (q, alpha)`.
#[derive(Clone, Copy, Debug)]
pub struct Reduced<'a, M, F, const P: usize> {
    model: &'a M,
    input: F,
}

impl<'a, M, F: Input<P>, const P: usize> Reduced<'a, M, F, P> {
    /// `model` driven by the time-dependent input `input(t)`.
    pub fn new(model: &'a M, input: F) -> Self {
        Self { model, input }
    }
}

impl<'a, M, const P: usize> Reduced<'a, M, Constant<P>, P> {
    /// `model` driven by the constant input `u`.
    pub fn constant(model: &'a M, u: [f64; P]) -> Self {
        Self::new(model, Constant(u))
    }
}

impl<M, F, const S: usize, const P: usize> OdeSystem<S> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Input<P>,
{
    fn rhs(&self, t: f64, x: &[f64; S]) -> [f64; S] {
        self.model.reduced_rhs(x, &self.input.at(t))
    }
}

impl<M, F, const S: usize, const P: usize> Jacobian<S> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Input<P>,
{
    fn jacobian(&self, t: f64, x: &[f64; S]) -> [[f64; S]; S] {
        self.model.reduced_rhs_jacobian(x, &self.input.at(t))
    }
}

impl<M, F, const S: usize, const P: usize> Energy<S> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Input<P>,
{
    fn energy(&self, x: &[f64; S]) -> f64 {
        self.model.hamiltonian(x)
    }
}

/// A model's Lagrange-d'Alembert equations driven by the input `input(t)`:
/// an [`OdeSystem`] in `x = (q, qdot)` of size `D = 2 N` (`D` is its own
/// parameter because `2 * N` cannot be written in a type on stable Rust; any
/// other `D` fails to compile).
///
/// ```
/// use chaplygin_runtime::system::{Dalembert, LagrangeDalembert, OdeSystem};
///
/// /// A unit mass on a line, pushed by `u`: no constraints.
/// struct Pushed;
///
/// impl LagrangeDalembert<1, 0, 1> for Pushed {
///     fn acceleration(&self, _q: &[f64; 1], _qdot: &[f64; 1], u: &[f64; 1]) -> ([f64; 1], [f64; 0]) {
///         ([u[0]], [])
///     }
///     fn energy(&self, _q: &[f64; 1], qdot: &[f64; 1]) -> f64 {
///         qdot[0] * qdot[0] / 2.0
///     }
///     fn constraint_residual(&self, _q: &[f64; 1], _qdot: &[f64; 1]) -> [f64; 0] {
///         []
///     }
/// }
///
/// let system = Dalembert::new(&Pushed, |t: f64| [2.0 * t]);
/// assert_eq!(system.rhs(1.5, &[0.0, 4.0]), [4.0, 3.0]);
/// ```
///
/// A state of another size does not compile:
///
/// ```compile_fail
/// # use chaplygin_runtime::system::{Dalembert, LagrangeDalembert, OdeSystem};
/// # struct Pushed;
/// # impl LagrangeDalembert<1, 0, 1> for Pushed {
/// #     fn acceleration(&self, _q: &[f64; 1], _qdot: &[f64; 1], u: &[f64; 1]) -> ([f64; 1], [f64; 0]) {
/// #         ([u[0]], [])
/// #     }
/// #     fn energy(&self, _q: &[f64; 1], qdot: &[f64; 1]) -> f64 { qdot[0] * qdot[0] / 2.0 }
/// #     fn constraint_residual(&self, _q: &[f64; 1], _qdot: &[f64; 1]) -> [f64; 0] { [] }
/// # }
/// let system = Dalembert::constant(&Pushed, [1.0]);
/// system.rhs(0.0, &[0.0, 1.0, 2.0]);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Dalembert<'a, M, F, const N: usize, const C: usize, const P: usize> {
    model: &'a M,
    input: F,
}

impl<'a, M, F, const N: usize, const C: usize, const P: usize> Dalembert<'a, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
    F: Input<P>,
{
    /// `model` driven by the time-dependent input `input(t)`.
    pub fn new(model: &'a M, input: F) -> Self {
        Self { model, input }
    }
}

impl<'a, M, const N: usize, const C: usize, const P: usize> Dalembert<'a, M, Constant<P>, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
{
    /// `model` driven by the constant input `u`.
    pub fn constant(model: &'a M, u: [f64; P]) -> Self {
        Self::new(model, Constant(u))
    }
}

/// Splits `x = (q, qdot)` of size `D = 2 N`.
fn split<const N: usize, const D: usize>(x: &[f64; D]) -> ([f64; N], [f64; N]) {
    const { assert!(D == 2 * N, "the state (q, qdot) has D = 2 N entries") };
    (
        core::array::from_fn(|i| x[i]),
        core::array::from_fn(|i| x[N + i]),
    )
}

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> OdeSystem<D>
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
    F: Input<P>,
{
    fn rhs(&self, t: f64, x: &[f64; D]) -> [f64; D] {
        let (q, qdot) = split::<N, D>(x);
        let (qddot, _) = self.model.acceleration(&q, &qdot, &self.input.at(t));
        core::array::from_fn(|i| if i < N { qdot[i] } else { qddot[i - N] })
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> Energy<D>
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
    F: Input<P>,
{
    fn energy(&self, x: &[f64; D]) -> f64 {
        let (q, qdot) = split::<N, D>(x);
        self.model.energy(&q, &qdot)
    }
}

/// A constant input, `u(t) = u`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constant<const P: usize>(pub [f64; P]);

/// An input signal `u(t)`: a [`Constant`], or any `Fn(f64) -> [f64; P]`.
pub trait Input<const P: usize> {
    /// The input at time `t`.
    fn at(&self, t: f64) -> [f64; P];
}

impl<const P: usize> Input<P> for Constant<P> {
    fn at(&self, _t: f64) -> [f64; P] {
        self.0
    }
}

impl<F: Fn(f64) -> [f64; P], const P: usize> Input<P> for F {
    fn at(&self, t: f64) -> [f64; P] {
        self(t)
    }
}
