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
//! The closed-loop state is `z = (q, alpha, xt, xw)`, of size
//! [`CLOSED_LOOP_STATE`]; [`ClosedLoop`] implements the runtime's
//! [`OdeSystem`], [`Jacobian`] (for the implicit midpoint rule) and
//! [`Energy`].

use crate::snakeboard::Snakeboard;
use chaplygin::runtime::system::{Energy, Jacobian, OdeSystem};

/// The reduced snakeboard's state size `s = n + k`.
const S: usize = Snakeboard::S;

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

/// The snakeboard under the energy-based controller.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosedLoop {
    /// The plant.
    pub board: Snakeboard,
    /// The controller.
    pub controller: EnergyController,
}

impl ClosedLoop {
    /// The closed-loop state from the board's reduced state and the springs'.
    pub fn state(board: &[f64; S], xt: f64, xw: f64) -> [f64; CLOSED_LOOP_STATE] {
        core::array::from_fn(|i| match i {
            i if i < S => board[i],
            i if i == S => xt,
            _ => xw,
        })
    }

    /// The board's part of a closed-loop state.
    pub fn board_state(z: &[f64; CLOSED_LOOP_STATE]) -> [f64; S] {
        core::array::from_fn(|i| z[i])
    }

    /// The controller's torques `(u1, u2) = (-a sin(phi) kt xt, -kw xw)`.
    pub fn input(&self, z: &[f64; CLOSED_LOOP_STATE]) -> [f64; 2] {
        let EnergyController { a, kt, kw } = self.controller;
        [-a * z[4].sin() * kt * z[S], -kw * z[S + 1]]
    }

    /// The wheel pair's own energy `alpha3^2/(2 Jw) + kw xw^2/2`.
    pub fn wheel_energy(&self, z: &[f64; CLOSED_LOOP_STATE]) -> f64 {
        z[S - 1] * z[S - 1] / (2.0 * self.board.jw) + self.controller.kw * z[S + 1] * z[S + 1] / 2.0
    }
}

impl OdeSystem<CLOSED_LOOP_STATE> for ClosedLoop {
    fn rhs(&self, _t: f64, z: &[f64; CLOSED_LOOP_STATE]) -> [f64; CLOSED_LOOP_STATE] {
        let f = self
            .board
            .reduced_rhs(&Self::board_state(z), &self.input(z));
        let springs = [self.controller.a * z[4].sin() * f[3], f[4]];
        core::array::from_fn(|i| if i < S { f[i] } else { springs[i - S] })
    }
}

impl Jacobian<CLOSED_LOOP_STATE> for ClosedLoop {
    /// `d f/dx + B du/dz` for the board's rows; the springs' rows follow
    /// from those of `psidot` and `phidot`, which do not depend on `u`.
    fn jacobian(
        &self,
        _t: f64,
        z: &[f64; CLOSED_LOOP_STATE],
    ) -> [[f64; CLOSED_LOOP_STATE]; CLOSED_LOOP_STATE] {
        let EnergyController { a, kt, kw } = self.controller;
        let x = Self::board_state(z);
        let u = self.input(z);
        let (fx, b) = (
            self.board.reduced_rhs_jacobian(&x, &u),
            self.board.input_matrix(&x),
        );
        let (sin, cos) = z[4].sin_cos();
        let mut du = [[0.0; CLOSED_LOOP_STATE]; 2];
        du[0][4] = -a * cos * kt * z[S];
        du[0][S] = -a * sin * kt;
        du[1][S + 1] = -kw;
        let mut jacobian = [[0.0; CLOSED_LOOP_STATE]; CLOSED_LOOP_STATE];
        for i in 0..S {
            for j in 0..CLOSED_LOOP_STATE {
                let through_u = b[i][0] * du[0][j] + b[i][1] * du[1][j];
                jacobian[i][j] = if j < S { fx[i][j] } else { 0.0 } + through_u;
            }
        }
        let psidot = self.board.reduced_rhs(&x, &u)[3];
        jacobian[S] = core::array::from_fn(|j| a * sin * jacobian[3][j]);
        jacobian[S][4] += a * cos * psidot;
        jacobian[S + 1] = jacobian[4];
        jacobian
    }
}

impl Energy<CLOSED_LOOP_STATE> for ClosedLoop {
    /// `Hbar + kt xt^2/2 + kw xw^2/2`.
    fn energy(&self, z: &[f64; CLOSED_LOOP_STATE]) -> f64 {
        let EnergyController { kt, kw, .. } = self.controller;
        let springs = kt * z[S] * z[S] / 2.0 + kw * z[S + 1] * z[S + 1] / 2.0;
        self.board.hamiltonian(&Self::board_state(z)) + springs
    }
}
