//! The energy-based snakeboard controller of Duindam & Stramigioli (2004),
//! as reconstructed in MATH.md 3.2, interconnected with the reduced
//! port-Hamiltonian snakeboard.
//!
//! The controller has two springs with states `(xt, xw)` and energy
//! `Hc = kt xt^2/2 + kw xw^2/2`: a spring `kw` between the wheels and the
//! frame, `u2 = -kw xw`, `xwdot = phidot`; and a spring `kt` on the torso port
//! through a modulated transformer of modulus `a sin(phi)`,
//! `u1 = -a sin(phi) kt xt`, `xtdot = a sin(phi) psidot`. The interconnection
//! is power-conserving, so the closed loop is port-Hamiltonian with the
//! energy `Hbar + Hc`, which is conserved exactly: with the snakeboard's
//! `alpha1dot = -(sin(phi)/r) u1 = (a kt/r) sin(phi)^2 xt >= 0` while
//! `xt > 0`, energy stored in the springs flows into the group momentum
//! `alpha1` while `phi` oscillates. The wheel pair `(alpha3, xw)` is a
//! separate oscillator with its own constant energy
//! `alpha3^2/(2 Jw) + kw xw^2/2`.
//!
//! [`EnergyController`] implements the runtime's
//! [`PortHamiltonianController`] with `Bc = [[a sin(phi), 0], [0, 1]]`
//! (exact derivatives) and `Jc = 0`; [`ClosedLoop`] is the runtime's
//! [`Interconnection`] of a snakeboard with it, an [`OdeSystem`] with an
//! exact [`Jacobian`] (for the implicit midpoint rule) and its [`Energy`] in
//! the state `z = (q, alpha, xt, xw)` of size [`CLOSED_LOOP_STATE`]. The
//! snakeboard is any model of the paper's snakeboard (`snakeboard.model`,
//! with its momentum basis): compiled by rustc, or read from its text
//! (`chaplygin_codegen::interpret::Fixed`).
//!
//! [`OdeSystem`]: crate::runtime::system::OdeSystem
//! [`Jacobian`]: crate::runtime::system::Jacobian
//! [`Energy`]: crate::runtime::system::Energy

use crate::runtime::control::{Interconnection, PortHamiltonianController};

/// The reduced snakeboard's state size `s = n + k`: five coordinates
/// `(x, y, theta, psi, phi)` and three momenta.
pub const S: usize = 8;

/// Index of `phi` in the snakeboard's state.
const PHI: usize = 4;

/// Size of the closed-loop state `(q, alpha, xt, xw)`.
pub const CLOSED_LOOP_STATE: usize = S + 2;

/// The controller's gains (MATH.md 3.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyController {
    /// Modulus factor of the transformer `a sin(phi)`, `a > 0`.
    pub a: f64,
    /// Stiffness of the torso spring.
    pub kt: f64,
    /// Stiffness of the wheel spring.
    pub kw: f64,
}

impl PortHamiltonianController<S, 2, 2> for EnergyController {
    const STATES: [&'static str; 2] = ["xt", "xw"];

    /// `Hc = kt xt^2/2 + kw xw^2/2`.
    fn energy(&self, xc: &[f64; 2]) -> f64 {
        (self.kt * xc[0] * xc[0] + self.kw * xc[1] * xc[1]) / 2.0
    }

    fn energy_gradient(&self, xc: &[f64; 2]) -> [f64; 2] {
        [self.kt * xc[0], self.kw * xc[1]]
    }

    fn energy_hessian(&self, _xc: &[f64; 2]) -> [[f64; 2]; 2] {
        [[self.kt, 0.0], [0.0, self.kw]]
    }

    /// The modulated transformer `a sin(phi)` on the torso port, the wheel
    /// spring directly on the wheel port.
    fn input_matrix(&self, x: &[f64; S], _xc: &[f64; 2]) -> [[f64; 2]; 2] {
        [[self.a * x[PHI].sin(), 0.0], [0.0, 1.0]]
    }

    fn input_matrix_derivative(&self, x: &[f64; S], _xc: &[f64; 2], j: usize) -> [[f64; 2]; 2] {
        let slope = if j == PHI { self.a * x[PHI].cos() } else { 0.0 };
        [[slope, 0.0], [0.0, 0.0]]
    }
}

/// The snakeboard `M` under the energy-based controller.
pub type ClosedLoop<M> = Interconnection<M, EnergyController, S, 2, 2>;

/// The closed-loop state from the board's reduced state and the springs'.
pub fn closed_loop_state(board: &[f64; S], xt: f64, xw: f64) -> [f64; CLOSED_LOOP_STATE] {
    core::array::from_fn(|i| match i {
        i if i < S => board[i],
        i if i == S => xt,
        _ => xw,
    })
}

/// The wheel pair's own energy `alpha3^2/(2 Jw) + kw xw^2/2`, for the
/// wheels' inertia `jw` and the wheel spring `kw`.
pub fn wheel_energy(jw: f64, kw: f64, z: &[f64; CLOSED_LOOP_STATE]) -> f64 {
    z[S - 1] * z[S - 1] / (2.0 * jw) + kw * z[S + 1] * z[S + 1] / 2.0
}
