//! Controllers: what closes a model's input port.
//!
//! - A plain [`Controller`] computes `u = f(t, x)` from the time and the
//!   state: a [`Constant`], an open-loop closure `u(t)`, or a state
//!   [`Feedback`] `u(t, x)` (defined in [`crate::law`], re-exported here).
//! - A [`PortHamiltonianController`] is a system of its own, with state
//!   `xc`, energy `Hc(xc)`, a constant skew structure `Jc` and an input
//!   matrix `Bc(x, xc)`, joined to a reduced port-Hamiltonian plant
//!   `xdot = J dH/dx + G u`, `y = G^T dH/dx` by the power-conserving
//!   interconnection (van der Schaft, *L2-Gain and Passivity Techniques in
//!   Nonlinear Control*, 3rd ed., 2017, section 6.3; Duindam & Stramigioli
//!   2004, section 4)
//!
//!   ```text
//!   u = -Bc(x, xc)^T dHc/dxc,        xcdot = Jc dHc/dxc + Bc(x, xc) y.
//!   ```
//!
//!   The closed loop [`Interconnection`] is port-Hamiltonian in
//!   `z = (x, xc)` with the energy `H + Hc` and the skew structure
//!   `[[J, -G Bc^T], [Bc G^T, Jc]]`: the energy the controller takes from the
//!   plant, `y . u`, is what it stores, so `H + Hc` is conserved.

pub use crate::law::{Constant, Controller, Feedback};
use crate::linalg::Square;
use crate::system::{Energy, Jacobian, OdeSystem, ReducedPortHamiltonian, Structured};
use nalgebra::Const;

/// A port-Hamiltonian controller with `NC` states for a plant with reduced
/// state size `S` and `P` inputs (see the module documentation).
pub trait PortHamiltonianController<const S: usize, const NC: usize, const P: usize> {
    /// The names of the controller's states, as recorded.
    const STATES: [&'static str; NC];

    /// The stored energy `Hc(xc)`.
    fn energy(&self, xc: &[f64; NC]) -> f64;

    /// `dHc/dxc`.
    fn energy_gradient(&self, xc: &[f64; NC]) -> [f64; NC];

    /// `d^2 Hc / dxc^2`.
    fn energy_hessian(&self, xc: &[f64; NC]) -> [[f64; NC]; NC];

    /// The controller's own constant skew structure `Jc` (zero by default).
    fn structure_matrix(&self) -> [[f64; NC]; NC] {
        [[0.0; NC]; NC]
    }

    /// The coupling `Bc(x, xc)`: row `a` holds how `xc_a` moves with the
    /// plant's outputs.
    fn input_matrix(&self, x: &[f64; S], xc: &[f64; NC]) -> [[f64; P]; NC];

    /// `dBc/dz_j` for `z = (x, xc)`: by default central differences of
    /// [`PortHamiltonianController::input_matrix`].
    fn input_matrix_derivative(&self, x: &[f64; S], xc: &[f64; NC], j: usize) -> [[f64; P]; NC] {
        let step = f64::EPSILON.cbrt() * if j < S { x[j] } else { xc[j - S] }.abs().max(1.0);
        let shifted = |delta: f64| {
            let (mut x, mut xc) = (*x, *xc);
            if j < S {
                x[j] += delta;
            } else {
                xc[j - S] += delta;
            }
            self.input_matrix(&x, &xc)
        };
        let (plus, minus) = (shifted(step), shifted(-step));
        core::array::from_fn(|a| {
            core::array::from_fn(|l| (plus[a][l] - minus[a][l]) / (2.0 * step))
        })
    }
}

/// A reduced port-Hamiltonian plant `M` and a [`PortHamiltonianController`]
/// `K`, interconnected power-conservingly: an [`OdeSystem`] in
/// `z = (x, xc)` of size `D = S + NC` (`D` is its own parameter because
/// `S + NC` cannot be written in a type on stable Rust; any other `D` fails
/// to compile).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interconnection<M, K, const S: usize, const NC: usize, const P: usize> {
    /// The plant.
    pub plant: M,
    /// The controller.
    pub controller: K,
}

impl<M, K, const S: usize, const NC: usize, const P: usize> Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P>,
    K: PortHamiltonianController<S, NC, P>,
{
    /// `plant` closed by `controller`.
    pub fn new(plant: M, controller: K) -> Self {
        Self { plant, controller }
    }

    /// The closed-loop state `z = (x, xc)`.
    pub fn state<const D: usize>(x: &[f64; S], xc: &[f64; NC]) -> [f64; D] {
        const {
            assert!(
                D == S + NC,
                "the closed-loop state (x, xc) has D = S + NC entries"
            )
        };
        core::array::from_fn(|i| if i < S { x[i] } else { xc[i - S] })
    }

    /// The plant's and the controller's parts of `z`.
    pub fn split<const D: usize>(z: &[f64; D]) -> ([f64; S], [f64; NC]) {
        const {
            assert!(
                D == S + NC,
                "the closed-loop state (x, xc) has D = S + NC entries"
            )
        };
        (
            core::array::from_fn(|i| z[i]),
            core::array::from_fn(|i| z[S + i]),
        )
    }

    /// The controller's action `u = -Bc(x, xc)^T dHc/dxc`.
    pub fn input<const D: usize>(&self, z: &[f64; D]) -> [f64; P] {
        let (x, xc) = Self::split(z);
        let (bc, gradient) = (
            self.controller.input_matrix(&x, &xc),
            self.controller.energy_gradient(&xc),
        );
        core::array::from_fn(|l| -(0..NC).map(|a| bc[a][l] * gradient[a]).sum::<f64>())
    }

    /// `du/dz`: row `l` holds the derivatives of `u_l`.
    fn input_jacobian<const D: usize>(&self, z: &[f64; D]) -> [[f64; D]; P] {
        let (x, xc) = Self::split(z);
        let (bc, gradient, hessian) = (
            self.controller.input_matrix(&x, &xc),
            self.controller.energy_gradient(&xc),
            self.controller.energy_hessian(&xc),
        );
        let mut du = [[0.0; D]; P];
        for j in 0..D {
            let dbc = self.controller.input_matrix_derivative(&x, &xc, j);
            for (l, row) in du.iter_mut().enumerate() {
                let through_coupling: f64 = (0..NC).map(|a| dbc[a][l] * gradient[a]).sum();
                let through_energy = if j < S {
                    0.0
                } else {
                    (0..NC).map(|a| bc[a][l] * hessian[a][j - S]).sum()
                };
                row[j] = -through_coupling - through_energy;
            }
        }
        du
    }
}

impl<M, K, const S: usize, const NC: usize, const P: usize, const D: usize> OdeSystem<[f64; D]>
    for Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P>,
    K: PortHamiltonianController<S, NC, P>,
{
    fn rhs(&self, _t: f64, z: &[f64; D]) -> [f64; D] {
        let (x, xc) = Self::split(z);
        let xdot = self.plant.reduced_rhs(&x, &self.input(z));
        let (jc, gradient) = (
            self.controller.structure_matrix(),
            self.controller.energy_gradient(&xc),
        );
        let (bc, y) = (self.controller.input_matrix(&x, &xc), self.plant.output(&x));
        core::array::from_fn(|i| {
            if i < S {
                return xdot[i];
            }
            let a = i - S;
            let internal: f64 = (0..NC).map(|b| jc[a][b] * gradient[b]).sum();
            internal + (0..P).map(|l| bc[a][l] * y[l]).sum::<f64>()
        })
    }
}

impl<M, K, const S: usize, const NC: usize, const P: usize, const D: usize> Jacobian<[f64; D]>
    for Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P>,
    K: PortHamiltonianController<S, NC, P>,
    Const<D>: Square,
{
    /// Exact from the plant's Jacobians and the controller's derivatives
    /// (central differences of `Bc` unless the controller gives them).
    fn jacobian(&self, _t: f64, z: &[f64; D]) -> [[f64; D]; D] {
        let (x, xc) = Self::split(z);
        let u = self.input(z);
        let (fx, g) = (
            self.plant.reduced_rhs_jacobian(&x, &u),
            self.plant.input_matrix(&x),
        );
        let du = self.input_jacobian(z);
        let mut jacobian = [[0.0; D]; D];
        for i in 0..S {
            for j in 0..D {
                let direct = if j < S { fx[i][j] } else { 0.0 };
                jacobian[i][j] = direct + (0..P).map(|l| g[i][l] * du[l][j]).sum::<f64>();
            }
        }
        self.controller_rows(&x, &xc, &mut jacobian);
        jacobian
    }
}

impl<M, K, const S: usize, const NC: usize, const P: usize> Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P>,
    K: PortHamiltonianController<S, NC, P>,
{
    /// The rows of `d(Jc dHc/dxc + Bc y)/dz`.
    fn controller_rows<const D: usize>(
        &self,
        x: &[f64; S],
        xc: &[f64; NC],
        jacobian: &mut [[f64; D]; D],
    ) {
        let (jc, hessian) = (
            self.controller.structure_matrix(),
            self.controller.energy_hessian(xc),
        );
        let (bc, y, dy) = (
            self.controller.input_matrix(x, xc),
            self.plant.output(x),
            self.plant.output_jacobian(x),
        );
        for j in 0..D {
            let dbc = self.controller.input_matrix_derivative(x, xc, j);
            for a in 0..NC {
                let internal: f64 = if j < S {
                    0.0
                } else {
                    (0..NC).map(|b| jc[a][b] * hessian[b][j - S]).sum()
                };
                let coupling: f64 = (0..P).map(|l| dbc[a][l] * y[l]).sum();
                let through_output: f64 = if j < S {
                    (0..P).map(|l| bc[a][l] * dy[l][j]).sum()
                } else {
                    0.0
                };
                jacobian[S + a][j] = internal + coupling + through_output;
            }
        }
    }
}

impl<M, K, const S: usize, const NC: usize, const P: usize, const D: usize> Energy<[f64; D]>
    for Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P>,
    K: PortHamiltonianController<S, NC, P>,
{
    /// `H(x) + Hc(xc)`.
    fn energy(&self, z: &[f64; D]) -> f64 {
        let (x, xc) = Self::split(z);
        self.plant.hamiltonian(&x) + self.controller.energy(&xc)
    }
}

impl<M, K, const S: usize, const NC: usize, const P: usize, const D: usize> Structured<[f64; D]>
    for Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P>,
    K: PortHamiltonianController<S, NC, P>,
    Const<D>: Square,
{
    /// `[[J, -G Bc^T], [Bc G^T, Jc]]`.
    fn structure_matrix(&self, z: &[f64; D]) -> [[f64; D]; D] {
        let (x, xc) = Self::split(z);
        let (j, g) = (self.plant.structure_matrix(&x), self.plant.input_matrix(&x));
        let (jc, bc) = (
            self.controller.structure_matrix(),
            self.controller.input_matrix(&x, &xc),
        );
        let coupling = |i: usize, a: usize| (0..P).map(|l| g[i][l] * bc[a][l]).sum::<f64>();
        core::array::from_fn(|r| {
            core::array::from_fn(|c| match (r < S, c < S) {
                (true, true) => j[r][c],
                (true, false) => -coupling(r, c - S),
                (false, true) => coupling(c, r - S),
                (false, false) => jc[r - S][c - S],
            })
        })
    }

    fn energy_gradient(&self, z: &[f64; D]) -> [f64; D] {
        let (x, xc) = Self::split(z);
        let (plant, controller) = (
            self.plant.hamiltonian_gradient(&x),
            self.controller.energy_gradient(&xc),
        );
        core::array::from_fn(|i| if i < S { plant[i] } else { controller[i - S] })
    }

    /// Zero: the closed loop exchanges no power with its surroundings.
    fn forcing(&self, _t: f64, _z: &[f64; D]) -> [f64; D] {
        [0.0; D]
    }
}
