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
//! What the controller uses of a model is what it reads and drives: the
//! steering angle `phi`, found by its name among the coordinates
//! ([`EnergyController::new`]), and two inputs, the torso's and the
//! wheels', in the reduced state of the snakeboard's size [`S`].
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

/// Size of the closed-loop state `(q, alpha, xt, xw)`.
pub const CLOSED_LOOP_STATE: usize = S + 2;

/// The gains' names and their defaults (MATH.md 3.2).
pub const GAINS: [(&str, f64); 3] = [("a", 1.0), ("kt", 2.0), ("kw", 1.0)];

/// The springs' states and their defaults: energy stored in both springs.
pub const SPRINGS: [(&str, f64); 2] = [("xt", 1.0), ("xw", 0.5)];

/// The name of the coordinate whose sine modulates the transformer.
pub const STEERING: &str = "phi";

/// The controller's gains (MATH.md 3.2), and where the steering angle is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyController {
    /// Modulus factor of the transformer `a sin(phi)`, `a > 0`.
    pub a: f64,
    /// Stiffness of the torso spring.
    pub kt: f64,
    /// Stiffness of the wheel spring.
    pub kw: f64,
    /// The index of the steering angle `phi` among the coordinates (and so
    /// in the reduced state).
    phi: usize,
}

impl EnergyController {
    /// The controller with the gains `a`, `kt`, `kw` for a model with these
    /// `coordinates`, or `None` where none is [`STEERING`].
    pub fn new(a: f64, kt: f64, kw: f64, coordinates: &[&str]) -> Option<Self> {
        let phi = coordinates.iter().position(|&c| c == STEERING)?;
        Some(Self { a, kt, kw, phi })
    }
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
        [[self.a * x[self.phi].sin(), 0.0], [0.0, 1.0]]
    }

    fn input_matrix_derivative(&self, x: &[f64; S], _xc: &[f64; 2], j: usize) -> [[f64; 2]; 2] {
        let slope = if j == self.phi {
            self.a * x[self.phi].cos()
        } else {
            0.0
        };
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
