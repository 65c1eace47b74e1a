//! Gaits of the snakeboard of Duindam & Stramigioli (2004): the rider's
//! torso `psi` and the wheels' steering `phi` follow a periodic loop, and
//! the board moves. Declared with `chaplygin::model!` with its symmetry,
//! the board gets its nonholonomic momentum equation and reconstruction
//! (Bloch, Krishnaprasad, Marsden & Murray 1996; MATH.md section 4), and
//! `chaplygin::runtime::phase::se2_displacement` integrates one period of
//! each loop from rest.
//!
//! ```text
//! cargo run --example snakeboard_gait
//! ```
//!
//! For each loop the program prints the net displacement `(x, y, theta)`
//! in the board's frame at the start, and its geometric part, the motion
//! the loop makes with the momentum held at zero: a loop that encloses no
//! area in the shape plane (the drive gait, `psi` and `phi` in phase)
//! makes no geometric motion, and moves the board by the momentum it
//! builds up.

use chaplygin::runtime::phase::se2_displacement;
use std::f64::consts::PI;
use std::io::Write;

chaplygin::model! {
    /// The snakeboard with J = Jt + m r^2 (Duindam & Stramigioli 2004).
    pub struct Snakeboard {
        coordinates: [x, y, theta, psi, phi],
        parameters: [m = 1.0, r = 0.5, jt = 0.3, jw = 0.05],
        define: [j = jt + m*r^2],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + j/2*dot(theta)^2
            + jt*dot(theta)*dot(psi) + jt/2*dot(psi)^2 + jw/2*dot(phi)^2,
        constraints: [
            front = -sin(theta + phi)*dot(x) + cos(theta + phi)*dot(y) + r*cos(phi)*dot(theta),
            back  = -sin(theta - phi)*dot(x) + cos(theta - phi)*dot(y) - r*cos(phi)*dot(theta),
        ],
        inputs: [u_torso = psi, u_wheels = phi],
        momentum_basis: [
            group  = [cos(phi)*cos(theta), cos(phi)*sin(theta), r*sin(phi), 0, 0],
            torso  = [0, 0, 1, 1, 0],
            wheels = [0, 0, 0, 0, 1],
        ],
        symmetry: se2(x, y, theta),
    }
}

/// A shape loop `psi = a sin(f t)`, `phi = b sin(g t + c)`: its amplitudes,
/// frequencies and the steering's phase.
pub struct ShapeLoop {
    /// What the program prints for it.
    pub label: &'static str,
    /// `(a, f)` of the torso.
    pub torso: (f64, f64),
    /// `(b, g, c)` of the steering.
    pub steering: (f64, f64, f64),
}

/// The loops run, each over the period `2 pi`: the loop of `chaplygin
/// gait snakeboard` in the guide, and the classic drive and rotation
/// gaits of Ostrowski & Burdick at the amplitudes that do most per unit
/// length of the loop (the guide's "Gaits").
pub const LOOPS: [ShapeLoop; 3] = [
    ShapeLoop {
        label: "psi = 0.8 sin t, phi = 0.5 cos t",
        torso: (0.8, 1.0),
        steering: (0.5, 1.0, PI / 2.0),
    },
    ShapeLoop {
        label: "drive: psi = 1.011 sin t, phi = 0.513 sin t",
        torso: (1.011, 1.0),
        steering: (0.513, 1.0, 0.0),
    },
    ShapeLoop {
        label: "rotate: psi = pi sin 2t, phi = 1.44 sin t",
        torso: (PI, 2.0),
        steering: (1.44, 1.0, 0.0),
    },
];

/// RK4 steps per period.
const STEPS: usize = 4000;

fn main() -> std::io::Result<()> {
    report(&mut std::io::stdout().lock())
}

/// Runs one period of each of [`LOOPS`] from rest and writes the net and
/// geometric displacements to `out`.
///
/// # Errors
/// A failed write.
pub fn report(out: &mut impl Write) -> std::io::Result<()> {
    let board = Snakeboard::default();
    writeln!(
        out,
        "The snakeboard from rest, one period (2 pi) of each shape loop: the net displacement"
    )?;
    writeln!(
        out,
        "x, y, theta in the board's frame at the start, and its geometric part (zero momentum)"
    )?;
    for shape_loop in &LOOPS {
        let (a, f) = shape_loop.torso;
        let (b, g, c) = shape_loop.steering;
        let shape = |t: f64| {
            (
                [a * (f * t).sin(), b * (g * t + c).sin()],
                [a * f * (f * t).cos(), b * g * (g * t + c).cos()],
            )
        };
        let (displacement, _) = se2_displacement(
            shape,
            2.0 * PI,
            [0.0],
            |r, rdot, p| board.momentum_rhs(r, rdot, p),
            |r, rdot, p| board.body_velocity(r, rdot, p),
            STEPS,
        );
        let [x, y, theta] = displacement.total;
        let [gx, gy, gtheta] = displacement.geometric;
        writeln!(out, "{}:", shape_loop.label)?;
        writeln!(
            out,
            "  net       x = {x:+.9}, y = {y:+.9}, theta = {theta:+.9}"
        )?;
        writeln!(
            out,
            "  geometric x = {gx:+.9}, y = {gy:+.9}, theta = {gtheta:+.9}"
        )?;
    }
    Ok(())
}
