//! The systems integrators run on, and the formulations generated models
//! implement.
//!
//! An integrator sees an [`OdeSystem`] `xdot = f(t, x)` of fixed dimension
//! `D` (with a [`Jacobian`] when it is implicit, and in [`Structured`] form
//! `xdot = J(x) dH/dx + F(t, x)` for discrete-gradient methods). A generated
//! model implements [`ReducedPortHamiltonian`] (the reduced flow in
//! `x = (q, alpha)`, MATH.md section 3), [`LagrangeDalembert`] (the
//! equations with multipliers in `(q, qdot)`, MATH.md section 2) and
//! [`ModelNames`]; [`Reduced`] and [`Dalembert`] close either with a
//! [`Controller`] (a constant, an open-loop `u(t)`, or a feedback `u(t, x)`)
//! into an [`OdeSystem`].

pub use crate::control::Constant;
use crate::control::Controller;

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

/// An [`OdeSystem`] in port-Hamiltonian form
/// `f(t, x) = J(x) dH/dx + F(t, x)` with `J(x)` skew-symmetric and `H` its
/// [`Energy`]: `dH/dt = dH/dx . F`, the power the forcing `F` (e.g. `B u`)
/// brings in. Discrete-gradient methods keep this balance exactly.
pub trait Structured<const D: usize>: Energy<D> {
    /// The skew-symmetric structure matrix `J(x)`.
    fn structure_matrix(&self, x: &[f64; D]) -> [[f64; D]; D];
    /// `dH/dx`.
    fn energy_gradient(&self, x: &[f64; D]) -> [f64; D];
    /// The forcing `F(t, x) = f(t, x) - J(x) dH/dx`.
    fn forcing(&self, t: f64, x: &[f64; D]) -> [f64; D];
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
    /// The skew-symmetric structure matrix `J(x)`.
    fn structure_matrix(&self, x: &[f64; S]) -> [[f64; S]; S];
    /// The input matrix `G(x)`.
    fn input_matrix(&self, x: &[f64; S]) -> [[f64; P]; S];
    /// The output `y`, power-conjugate to `u`.
    fn output(&self, x: &[f64; S]) -> [f64; P];
    /// `dy/dx`.
    fn output_jacobian(&self, x: &[f64; S]) -> [[f64; S]; P];
    /// The largest `|A(q) qdot|` with `qdot = velocities(q, alpha)`: zero
    /// up to round-off wherever the reduced form is regular.
    fn constraint_violation(&self, x: &[f64; S]) -> f64;
    /// How far the configuration is from where the reduced form degenerates:
    /// `det[A(q); V(q)^T]` over the product of its rows' norms, `V` the
    /// velocities of unit momenta (see [`crate::monitor`]). Its magnitude is at
    /// most 1; it vanishes, and changes sign when crossed transversally,
    /// where the constraint rows or the momentum basis lose rank.
    fn regularity(&self, x: &[f64; S]) -> f64;
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
    /// How far the constraint rows are from losing rank: the Hadamard ratio
    /// `det(A g^-1 A^T) / prod_i (A g^-1 A^T)_ii` of their Gram matrix in
    /// the inverse metric, in `[0, 1]`, zero exactly where they are dependent
    /// (see [`crate::monitor`]).
    fn constraint_regularity(&self, q: &[f64; N]) -> f64;
}

/// The map between velocities and the reduced momenta `alpha` (MATH.md
/// section 3): `N` coordinates, `K` momenta. Generated models implement it.
pub trait Momenta<const N: usize, const K: usize> {
    /// `alpha = P g qdot` of a velocity allowed by the constraints.
    fn momenta(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; K];
    /// `qdot = g^-1 h^T alpha`.
    fn velocities(&self, q: &[f64; N], alpha: &[f64; K]) -> [f64; N];
}

/// A generated model's parameters, by name.
pub trait Parameters {
    /// The parameters, in declared order.
    const PARAMETERS: &'static [&'static str];
    /// The parameter called `name`, if there is one.
    fn parameter_mut(&mut self, name: &str) -> Option<&mut f64>;
}

/// The names a generated model declares, in order.
pub trait ModelNames {
    /// The coordinates `q`.
    const COORDINATES: &'static [&'static str];
    /// The momenta `alpha` of the reduced state.
    const MOMENTA: &'static [&'static str];
    /// The inputs `u`.
    const INPUTS: &'static [&'static str];
    /// The constraints, as declared.
    const CONSTRAINTS: &'static [&'static str];
}

/// A model in its reduced form closed by a [`Controller`]: an
/// [`OdeSystem`] in `x = (q, alpha)` with `u = controller(t, x)`.
#[derive(Clone, Copy, Debug)]
pub struct Reduced<'a, M, F, const P: usize> {
    model: &'a M,
    controller: F,
}

impl<'a, M, F, const P: usize> Reduced<'a, M, F, P> {
    /// `model` driven by `controller`: a [`Constant`], a closure `u(t)`,
    /// or a [`crate::control::Feedback`] `u(t, x)`.
    pub fn new(model: &'a M, controller: F) -> Self {
        Self { model, controller }
    }

    /// The model.
    pub fn model(&self) -> &'a M {
        self.model
    }

    /// The controller.
    pub fn controller(&self) -> &F {
        &self.controller
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
    F: Controller<S, P>,
{
    fn rhs(&self, t: f64, x: &[f64; S]) -> [f64; S] {
        self.model.reduced_rhs(x, &self.controller.input(t, x))
    }
}

impl<M, F, const S: usize, const P: usize> Jacobian<S> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Controller<S, P>,
{
    /// `df/dx + G(x) du/dx`: the model's exact Jacobian at fixed `u`, and
    /// the feedback's through the input matrix.
    fn jacobian(&self, t: f64, x: &[f64; S]) -> [[f64; S]; S] {
        let u = self.controller.input(t, x);
        let mut jacobian = self.model.reduced_rhs_jacobian(x, &u);
        let (g, du) = (
            self.model.input_matrix(x),
            self.controller.input_jacobian(t, x),
        );
        for (row, g_row) in jacobian.iter_mut().zip(&g) {
            for (j, entry) in row.iter_mut().enumerate() {
                *entry += (0..P).map(|l| g_row[l] * du[l][j]).sum::<f64>();
            }
        }
        jacobian
    }
}

impl<M, F, const S: usize, const P: usize> Energy<S> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Controller<S, P>,
{
    fn energy(&self, x: &[f64; S]) -> f64 {
        self.model.hamiltonian(x)
    }
}

impl<M, F, const S: usize, const P: usize> Structured<S> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Controller<S, P>,
{
    fn structure_matrix(&self, x: &[f64; S]) -> [[f64; S]; S] {
        self.model.structure_matrix(x)
    }

    fn energy_gradient(&self, x: &[f64; S]) -> [f64; S] {
        self.model.hamiltonian_gradient(x)
    }

    /// `G(x) u(t, x)`.
    fn forcing(&self, t: f64, x: &[f64; S]) -> [f64; S] {
        let (g, u) = (self.model.input_matrix(x), self.controller.input(t, x));
        core::array::from_fn(|i| (0..P).map(|l| g[i][l] * u[l]).sum())
    }
}

/// A model's Lagrange-d'Alembert equations closed by a [`Controller`]: an
/// [`OdeSystem`] in `x = (q, qdot)` of size `D = 2 N` (`D` is its own
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
///     fn constraint_regularity(&self, _q: &[f64; 1]) -> f64 {
///         1.0
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
/// #     fn constraint_regularity(&self, _q: &[f64; 1]) -> f64 { 1.0 }
/// # }
/// let system = Dalembert::constant(&Pushed, [1.0]);
/// system.rhs(0.0, &[0.0, 1.0, 2.0]);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Dalembert<'a, M, F, const N: usize, const C: usize, const P: usize> {
    model: &'a M,
    controller: F,
}

impl<'a, M, F, const N: usize, const C: usize, const P: usize> Dalembert<'a, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
{
    /// `model` driven by `controller`: a [`Constant`], a closure `u(t)`,
    /// or a [`crate::control::Feedback`] `u(t, x)` of `x = (q, qdot)`.
    pub fn new(model: &'a M, controller: F) -> Self {
        Self { model, controller }
    }

    /// The model.
    pub fn model(&self) -> &'a M {
        self.model
    }

    /// The controller.
    pub fn controller(&self) -> &F {
        &self.controller
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
pub(crate) fn split<const N: usize, const D: usize>(x: &[f64; D]) -> ([f64; N], [f64; N]) {
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
    F: Controller<D, P>,
{
    fn rhs(&self, t: f64, x: &[f64; D]) -> [f64; D] {
        let (q, qdot) = split::<N, D>(x);
        let (qddot, _) = self
            .model
            .acceleration(&q, &qdot, &self.controller.input(t, x));
        core::array::from_fn(|i| if i < N { qdot[i] } else { qddot[i - N] })
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> Jacobian<D>
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
{
    /// Central differences of [`OdeSystem::rhs`] (the generated code has no
    /// symbolic Jacobian of `acceleration`). An implicit method's Newton
    /// iteration uses it only to find its step: the step it converges to is
    /// the same, only the convergence rate depends on the Jacobian's accuracy.
    fn jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; D] {
        crate::linalg::central_difference_jacobian(|x| self.rhs(t, x), x)
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> Energy<D>
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
{
    fn energy(&self, x: &[f64; D]) -> f64 {
        let (q, qdot) = split::<N, D>(x);
        self.model.energy(&q, &qdot)
    }
}
