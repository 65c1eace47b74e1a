//! The systems integrators run on, and the formulations generated models
//! implement.
//!
//! An integrator sees an [`OdeSystem`] `xdot = f(t, x)` on a
//! [`State`] (with a [`Jacobian`] when it is implicit, and in [`Structured`] form
//! `xdot = J(x) dH/dx + F(t, x)` for discrete-gradient methods). A generated
//! model implements [`ReducedPortHamiltonian`] (the reduced flow in
//! `x = (q, alpha)`, MATH.md section 3), [`LagrangeDalembert`] (the
//! equations with multipliers in `(q, qdot)`, MATH.md section 2) and
//! [`ModelNames`], and with a symmetry [`MomentumEquations`] (the momentum
//! equation and reconstruction in `x = (q, rdot, p)`, MATH.md section 4);
//! [`Reduced`], [`Dalembert`] and [`Momentum`] close them with a
//! [`Controller`] (a constant, an open-loop `u(t)`, or a feedback `u(t, x)`)
//! into an [`OdeSystem`].

mod charts;
mod reduced;

pub use crate::law::Constant;
use crate::law::Controller;
use crate::linalg::Square;
use crate::state::State;
pub use charts::{CHART_SWITCH, GENERATED_CHART, RUNTIME_CHART, next_chart};
use nalgebra::Const;
pub use reduced::Reduced;

/// A first-order system `xdot = f(t, x)` on states of type `X` (a
/// [`State`]: `[f64; D]` for a generated model, `Vec<f64>` for a size known
/// at run time).
pub trait OdeSystem<X> {
    /// The derivative `f(t, x)`.
    fn rhs(&self, t: f64, x: &X) -> X;
}

/// An [`OdeSystem`] with its Jacobian `df/dx`.
pub trait Jacobian<X: State>: OdeSystem<X> {
    /// `df/dx (t, x)`: row `i`, column `j` is `d f_i / d x_j`.
    fn jacobian(&self, t: f64, x: &X) -> X::Matrix;
}

/// An [`OdeSystem`] with an energy, conserved when no power enters.
pub trait Energy<X>: OdeSystem<X> {
    /// The energy at state `x`.
    fn energy(&self, x: &X) -> f64;
}

/// An [`OdeSystem`] in port-Hamiltonian form
/// `f(t, x) = J(x) dH/dx + F(t, x)` with `J(x)` skew-symmetric and `H` its
/// [`Energy`]: `dH/dt = dH/dx . F`, the power the forcing `F` (e.g. `B u`)
/// brings in. Discrete-gradient methods keep this balance exactly.
pub trait Structured<X: State>: Energy<X> {
    /// The skew-symmetric structure matrix `J(x)`.
    fn structure_matrix(&self, x: &X) -> X::Matrix;
    /// `dH/dx`.
    fn energy_gradient(&self, x: &X) -> X;
    /// The forcing `F(t, x) = f(t, x) - J(x) dH/dx`.
    fn forcing(&self, t: f64, x: &X) -> X;
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
    /// velocities of unit momenta (the `monitor` module). Its magnitude is at
    /// most 1; it vanishes, and changes sign when crossed transversally,
    /// where the constraint rows or the momentum basis lose rank.
    fn regularity(&self, x: &[f64; S]) -> f64;

    /// The number of charts of D derived at build time: 1, unless the
    /// basis of D degenerates where the constraint rows stay independent;
    /// then chart 0 is that basis and the others choose other dependent
    /// speeds (docs/guide/simulating.md, "Chart switching"). Indices from `charts()` on are
    /// run-time charts (the `partition` module): chart `charts() + i`
    /// solves for the `i`-th set of dependent speeds in lexicographic order.
    /// Every chart has the state layout `(q, alpha)`, `alpha` the momenta
    /// of its own basis; the `chart_*` methods are the items above in a
    /// chart, and chart 0's are the items above.
    fn charts(&self) -> usize {
        1
    }
    /// How well `chart` fits at the configuration of `x`, in `[0, 1]`: its
    /// pivot ratio `|det A_r(q)| / prod_i |A_i(q)|`
    /// (`monitor::pivot_ratio`; for a basis chosen in the body frame, on
    /// the body rows at `monitor::at_group_identity`), or for a
    /// declared momentum basis `|regularity|`; 0 where its basis
    /// degenerates.
    fn chart_fit(&self, _chart: usize, _x: &[f64; S]) -> f64 {
        1.0
    }
    /// The run-time chart that partial pivoting picks at the configuration
    /// of `x` (`partition::pivoted`); `None` for a model without
    /// run-time charts or where the constraint rows are dependent.
    fn pivoted_chart(&self, _x: &[f64; S]) -> Option<usize> {
        None
    }
    /// Whether a run may change charts: several charts derived at build
    /// time, or run-time charts (a generated model with constraint rows).
    fn switches_charts(&self) -> bool {
        self.charts() > 1
    }
    /// The state `x` of chart `from` in chart `to`: the same configuration,
    /// and the momenta of `to` of the velocity `x` has in `from`.
    fn change_chart(&self, _from: usize, _to: usize, x: &[f64; S]) -> [f64; S] {
        *x
    }
    /// [`ReducedPortHamiltonian::reduced_rhs`] in `chart`.
    fn chart_rhs(&self, _chart: usize, x: &[f64; S], u: &[f64; P]) -> [f64; S] {
        self.reduced_rhs(x, u)
    }
    /// [`ReducedPortHamiltonian::reduced_rhs_jacobian`] in `chart`.
    fn chart_rhs_jacobian(&self, _chart: usize, x: &[f64; S], u: &[f64; P]) -> [[f64; S]; S] {
        self.reduced_rhs_jacobian(x, u)
    }
    /// [`ReducedPortHamiltonian::hamiltonian`] in `chart`.
    fn chart_hamiltonian(&self, _chart: usize, x: &[f64; S]) -> f64 {
        self.hamiltonian(x)
    }
    /// [`ReducedPortHamiltonian::hamiltonian_gradient`] in `chart`.
    fn chart_hamiltonian_gradient(&self, _chart: usize, x: &[f64; S]) -> [f64; S] {
        self.hamiltonian_gradient(x)
    }
    /// [`ReducedPortHamiltonian::structure_matrix`] in `chart`.
    fn chart_structure_matrix(&self, _chart: usize, x: &[f64; S]) -> [[f64; S]; S] {
        self.structure_matrix(x)
    }
    /// [`ReducedPortHamiltonian::input_matrix`] in `chart`.
    fn chart_input_matrix(&self, _chart: usize, x: &[f64; S]) -> [[f64; P]; S] {
        self.input_matrix(x)
    }
    /// [`ReducedPortHamiltonian::constraint_violation`] in `chart`.
    fn chart_constraint_violation(&self, _chart: usize, x: &[f64; S]) -> f64 {
        self.constraint_violation(x)
    }
    /// [`ReducedPortHamiltonian::regularity`] in `chart`.
    fn chart_regularity(&self, _chart: usize, x: &[f64; S]) -> f64 {
        self.regularity(x)
    }
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
    /// (see the `monitor` module).
    fn constraint_regularity(&self, q: &[f64; N]) -> f64;
}

/// Configuration constraints `f(q) = 0` (docs/INTERFACE.md section 4, `holonomic`):
/// `N` coordinates, `H` constraints. Generated models implement it, with
/// `H = 0` when they declare none. Their velocity forms `(df/dq) qdot = 0`
/// are among the model's constraint rows already; the runtime uses `f` itself
/// to keep a trajectory on the constraint surface and to solve an initial
/// configuration for the coordinates it leaves unset.
pub trait Holonomic<const N: usize, const H: usize> {
    /// The constraints' names, as declared.
    fn holonomic_names(&self) -> [&str; H];
    /// `f(q)`.
    fn holonomic_residual(&self, q: &[f64; N]) -> [f64; H];
    /// `df/dq`, one row per constraint.
    fn holonomic_jacobian(&self, q: &[f64; N]) -> [[f64; N]; H];
}

/// The map between velocities and the reduced momenta `alpha` (MATH.md
/// section 3): `N` coordinates, `K` momenta. Generated models implement it.
pub trait Momenta<const N: usize, const K: usize> {
    /// `alpha = P g qdot` of a velocity allowed by the constraints.
    fn momenta(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; K];
    /// `qdot = g^-1 h^T alpha`.
    fn velocities(&self, q: &[f64; N], alpha: &[f64; K]) -> [f64; N];
    /// [`Momenta::momenta`] in chart `chart` of the reduced form (see
    /// [`ReducedPortHamiltonian::charts`]); chart 0's are `momenta`.
    fn chart_momenta(&self, _chart: usize, q: &[f64; N], qdot: &[f64; N]) -> [f64; K] {
        self.momenta(q, qdot)
    }
    /// [`Momenta::velocities`] in chart `chart`; chart 0's are `velocities`.
    fn chart_velocities(&self, _chart: usize, q: &[f64; N], alpha: &[f64; K]) -> [f64; N] {
        self.velocities(q, alpha)
    }
}

/// The momentum equation of a model with a symmetry (MATH.md section 4):
/// `N` coordinates, of which `R` are the shape `r` (those the group does not
/// act on), `K` momenta `p`, `P` inputs. Generated models with a `symmetry`
/// implement it.
///
/// ```text
/// pdot = momentum_rhs(r, rdot, p) + momentum_input_matrix(q) u
/// rddot = shape_acceleration(r, rdot, p, u)
/// qdot = reconstructed_velocity(q, rdot, p)
/// ```
pub trait MomentumEquations<const N: usize, const R: usize, const K: usize, const P: usize> {
    /// The indices of the shape coordinates in `q`, in declared order.
    fn shape_indices(&self) -> [usize; R];
    /// The momenta `p = h(q) M(q) qdot` of a velocity.
    fn momentum(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; K];
    /// The unforced momentum equation's right-hand side.
    fn momentum_rhs(&self, r: &[f64; R], rdot: &[f64; R], p: &[f64; K]) -> [f64; K];
    /// `h(q) B(q)`: the inputs' term of the momentum equation.
    fn momentum_input_matrix(&self, q: &[f64; N]) -> [[f64; P]; K];
    /// The shape accelerations `rddot` at `(r, rdot, p)` and inputs `u`.
    fn shape_acceleration(
        &self,
        r: &[f64; R],
        rdot: &[f64; R],
        p: &[f64; K],
        u: &[f64; P],
    ) -> [f64; R];
    /// The velocity `qdot` of the whole configuration: the reconstructed
    /// body velocity moved to the coordinates' frame on the group
    /// (`R(theta) (v1, v2)` and `omega` for `se2`), `rdot` on the shape.
    fn reconstructed_velocity(&self, q: &[f64; N], rdot: &[f64; R], p: &[f64; K]) -> [f64; N];
    /// The divisors of the momentum basis `e(r)` that depend on the
    /// parameters alone, described: where one is zero the basis degenerates
    /// at every configuration. None by default.
    fn basis_divisor_names(&self) -> &[&str] {
        &[]
    }
    /// The values of [`MomentumEquations::basis_divisor_names`], in order.
    fn basis_divisors(&self, _values: &mut [f64]) {}
    /// The shape coordinates `r` of `q`.
    fn shape(&self, q: &[f64; N]) -> [f64; R] {
        self.shape_indices().map(|i| q[i])
    }
}

/// One factor of a model's symmetry group, acting on the coordinates at
/// these indices (the model language's `symmetry` section).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroupFactor {
    /// The special Euclidean group of the plane on `(x, y, theta)`.
    Se2 {
        /// Index of `x`.
        x: usize,
        /// Index of `y`.
        y: usize,
        /// Index of the heading `theta`.
        theta: usize,
    },
    /// Translations of one coordinate.
    Translation(usize),
    /// Rotations of one angle.
    Rotation(usize),
}

/// What an expression of a model needs to stay defined
/// ([`Domain::guards`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guard {
    /// Its value must stay positive (the argument of a square root or a
    /// logarithm).
    Positive,
    /// It must not vanish: its sign stays what it was (a divisor).
    NonZero,
}

/// Where a model's equations are defined (docs/guide/simulating.md, "Where a run ends"):
/// its own expressions' square roots, logarithms, divisions and tangents,
/// each with a [`Guard`], and its constraint rows, which must stay
/// independent. A run evaluates them where a step fails, to name what the
/// step crossed. Generated models implement it; the defaults declare
/// nothing.
pub trait Domain {
    /// Each guarded expression, described (what, where, what must hold),
    /// with its guard.
    fn guards(&self) -> &[(&str, Guard)] {
        &[]
    }
    /// The guarded expressions' values at the configuration `q`, in the
    /// order of [`Domain::guards`].
    fn domain(&self, _q: &[f64], _values: &mut [f64]) {}
    /// The constraint rows `A(q)`, `c x n` row-major into `rows`; `false`
    /// when the model does not give them.
    fn constraint_rows(&self, _q: &[f64], _rows: &mut [f64]) -> bool {
        false
    }
}

/// A generated model's parameters, by name.
pub trait Parameters {
    /// The parameters, in declared order.
    fn parameter_names(&self) -> &[&str];
    /// The parameter called `name`, if there is one.
    fn parameter_mut(&mut self, name: &str) -> Option<&mut f64>;
}

/// The names a generated model declares, in order.
pub trait ModelNames {
    /// The coordinates `q`.
    fn coordinate_names(&self) -> &[&str];
    /// The momenta `alpha` of the reduced state.
    fn momentum_names(&self) -> &[&str];
    /// The inputs `u`.
    fn input_names(&self) -> &[&str];
    /// The constraints, as declared.
    fn constraint_names(&self) -> &[&str];
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
    /// or a [`crate::law::Feedback`] `u(t, x)` of `x = (q, qdot)`.
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

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> OdeSystem<[f64; D]>
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

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> Jacobian<[f64; D]>
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
    Const<D>: Square,
{
    /// Central differences of [`OdeSystem::rhs`] ([`LagrangeDalembert`]
    /// carries no Jacobian; generated models' exact one is
    /// `linearize::Linearization::acceleration_jacobian`). An implicit method's Newton
    /// iteration uses it only to find its step: the step it converges to is
    /// the same, only the convergence rate depends on the Jacobian's accuracy.
    fn jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; D] {
        crate::linalg::central_difference_jacobian(|x| self.rhs(t, x), x)
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> Energy<[f64; D]>
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

/// A model's momentum equation closed by a [`Controller`]: an
/// [`OdeSystem`] in `x = (q, rdot, p)` (all `N` coordinates in declared
/// order, the `R` shape velocities, the `K` momenta) of size
/// `D = N + R + K` (its own parameter, as for [`Dalembert`]; any other `D`
/// fails to compile):
///
/// ```text
/// qdot  = reconstructed_velocity(q, rdot, p)
/// rddot = shape_acceleration(r, rdot, p, u)
/// pdot  = momentum_rhs(r, rdot, p) + momentum_input_matrix(q) u
/// ```
///
/// Its energy, constraint residual and regularity are the
/// [`LagrangeDalembert`] ones at the reconstructed velocity (`C`
/// constraints).
#[derive(Clone, Copy, Debug)]
pub struct Momentum<
    'a,
    M,
    F,
    const N: usize,
    const R: usize,
    const K: usize,
    const C: usize,
    const P: usize,
> {
    model: &'a M,
    controller: F,
}

impl<'a, M, F, const N: usize, const R: usize, const K: usize, const C: usize, const P: usize>
    Momentum<'a, M, F, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P>,
{
    /// `model` driven by `controller`: a [`Constant`], a closure `u(t)`,
    /// or a [`crate::law::Feedback`] `u(t, x)` of `x = (q, rdot, p)`.
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

    /// The state `(q, rdot, p)` of the configuration `q` moving with
    /// `qdot` (a velocity the constraints allow).
    pub fn initial_state<const D: usize>(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; D] {
        let rdot = self.model.shape(qdot);
        let p = self.model.momentum(q, qdot);
        join(q, &rdot, &p)
    }

    /// The configuration `q` and the reconstructed velocity `qdot` at `x`.
    pub fn configuration_velocity<const D: usize>(&self, x: &[f64; D]) -> ([f64; N], [f64; N]) {
        let (q, rdot, p) = split_momentum::<N, R, K, D>(x);
        let qdot = self.model.reconstructed_velocity(&q, &rdot, &p);
        (q, qdot)
    }
}

impl<'a, M, const N: usize, const R: usize, const K: usize, const C: usize, const P: usize>
    Momentum<'a, M, Constant<P>, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P>,
{
    /// `model` driven by the constant input `u`.
    pub fn constant(model: &'a M, u: [f64; P]) -> Self {
        Self::new(model, Constant(u))
    }
}

/// Splits `x = (q, rdot, p)` of size `D = N + R + K`.
fn split_momentum<const N: usize, const R: usize, const K: usize, const D: usize>(
    x: &[f64; D],
) -> ([f64; N], [f64; R], [f64; K]) {
    const {
        assert!(
            D == N + R + K,
            "the state (q, rdot, p) has D = N + R + K entries"
        )
    };
    (
        core::array::from_fn(|i| x[i]),
        core::array::from_fn(|i| x[N + i]),
        core::array::from_fn(|i| x[N + R + i]),
    )
}

/// Joins `(q, rdot, p)` into a state of size `D = N + R + K`.
fn join<const N: usize, const R: usize, const K: usize, const D: usize>(
    q: &[f64; N],
    rdot: &[f64; R],
    p: &[f64; K],
) -> [f64; D] {
    const {
        assert!(
            D == N + R + K,
            "the state (q, rdot, p) has D = N + R + K entries"
        )
    };
    core::array::from_fn(|i| match i {
        i if i < N => q[i],
        i if i < N + R => rdot[i - N],
        i => p[i - N - R],
    })
}

impl<
    M,
    F,
    const N: usize,
    const R: usize,
    const K: usize,
    const C: usize,
    const P: usize,
    const D: usize,
> OdeSystem<[f64; D]> for Momentum<'_, M, F, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
{
    fn rhs(&self, t: f64, x: &[f64; D]) -> [f64; D] {
        let (q, rdot, p) = split_momentum::<N, R, K, D>(x);
        let u = self.controller.input(t, x);
        let r = self.model.shape(&q);
        let qdot = self.model.reconstructed_velocity(&q, &rdot, &p);
        let rddot = self.model.shape_acceleration(&r, &rdot, &p, &u);
        let unforced = self.model.momentum_rhs(&r, &rdot, &p);
        let input_matrix = self.model.momentum_input_matrix(&q);
        let pdot: [f64; K] = core::array::from_fn(|i| {
            unforced[i] + (0..P).map(|l| input_matrix[i][l] * u[l]).sum::<f64>()
        });
        join(&qdot, &rddot, &pdot)
    }
}

impl<
    M,
    F,
    const N: usize,
    const R: usize,
    const K: usize,
    const C: usize,
    const P: usize,
    const D: usize,
> Jacobian<[f64; D]> for Momentum<'_, M, F, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
    Const<D>: Square,
{
    /// Central differences of [`OdeSystem::rhs`], as for [`Dalembert`].
    fn jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; D] {
        crate::linalg::central_difference_jacobian(|x| self.rhs(t, x), x)
    }
}

impl<
    M,
    F,
    const N: usize,
    const R: usize,
    const K: usize,
    const C: usize,
    const P: usize,
    const D: usize,
> Energy<[f64; D]> for Momentum<'_, M, F, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
{
    /// The energy `T + V` at the reconstructed velocity.
    fn energy(&self, x: &[f64; D]) -> f64 {
        let (q, qdot) = self.configuration_velocity(x);
        LagrangeDalembert::energy(self.model, &q, &qdot)
    }
}
