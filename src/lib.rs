//! Chaplygin: nonholonomic mechanical models compiled into verified
//! simulators. This is the crate users depend on; the guide
//! (`docs/guide/` in the repository, an mdBook) shows what to do with it,
//! task by task.
//!
//! # The flow: parse, check, derive, emit, integrate
//!
//! A model is written once, in [`model!`] or in a `.model` file read by
//! `chaplygin_codegen::Builder` from a build script: coordinates `q`,
//! parameters, the kinetic energy `T = 1/2 qdot^T g(q) qdot` (or the mass
//! matrix `g`), a potential `V(q)`, velocity constraints `A(q) qdot = 0`,
//! inputs `B(q) u`, optionally a momentum basis `h(q)` and a symmetry group.
//! At build time it flows one way through the compiler `chaplygin_codegen`:
//!
//! 1. **parse and check**: every rule of the language, each error a compile
//!    error on the offending token, all of a model's errors at once;
//! 2. **derive**, exactly, in the compiler's own symbolic engine (a trig
//!    normal form that decides identities):
//!    - the constraint analysis: a basis `X_1..X_k` of the allowed velocities
//!      `D = ker A`, Frobenius integrability (`A [X_i, X_j] = 0`), the growth
//!      vector, the classification;
//!    - the Lagrange-d'Alembert equations with multipliers (MATH.md
//!      section 2; Moore's chapter)
//!      `g qddot + C(q, qdot) + dV/dq = A^T lambda + B u`,
//!      `A qddot + Adot qdot = 0`;
//!    - the reduced port-Hamiltonian form (MATH.md section 3; Duindam &
//!      Stramigioli 2004, Theorem 1): momenta `alpha = P g qdot`, state
//!      `x = (q, alpha)`, `xdot = Jbar(x) dHbar/dx + Bbar u` with `Jbar`
//!      skew (proved exactly) and `Hbar = 1/2 alpha^T gbar^-1 alpha + V`;
//!      no constraint or multiplier is left;
//!    - with a symmetry, the nonholonomic momentum equation (MATH.md section
//!      4; Bloch, Krishnaprasad, Marsden & Murray; Koon & Marsden (1.1)-(1.3)):
//!      `pdot = rdot^T H rdot + rdot^T K p + p^T D p`, the reconstruction and
//!      the shape equations;
//! 3. **emit**: each derived function as straight-line, allocation-free Rust
//!    on fixed-size arrays, common subexpressions shared, with a `REPORT` of
//!    what was derived;
//! 4. **integrate** with the runtime [`runtime`]: every integrator (RK4,
//!    Dormand-Prince 5(4), the implicit midpoint rule, Gonzalez's discrete
//!    gradient) on every formulation, controllers plain or port-Hamiltonian,
//!    a simulation loop that stops with a structured error at singular
//!    configurations, CSV recording.
//!
//! # Features
//!
//! Without features (the default) the crate is the library a model needs:
//! [`model!`], the runtime, its integrators, controllers and
//! linearization. Each tool beyond it is a feature:
//!
//! - `jit`: models read from their text, compiled to native code at run
//!   time (`chaplygin::jit`, Cranelift);
//! - `design`: optimal gaits (`chaplygin::gait_design`, argmin);
//! - `driver`: models read from their text run by name, simulated,
//!   linearized, mapped over their parameters and given gaits
//!   (`chaplygin::driver`, `chaplygin::animate`; with `jit` and `design`);
//! - `plot`: PNG plots (`chaplygin::plot`, plotters);
//! - `cli`: what the command line builds on (`driver` and `plot`, the
//!   requests as clap arguments).
//!
//! The `chaplygin` command line itself is the package `chaplygin-cli`.
//!
//! # Example
//!
//! ```
//! use chaplygin::runtime::integrate::Rk4;
//! use chaplygin::runtime::record::Table;
//! use chaplygin::runtime::simulate::Simulation;
//! use chaplygin::runtime::system::Dalembert;
//!
//! chaplygin::model! {
//!     /// A vertical disk rolling without slipping, driven about its axle.
//!     pub struct Disk {
//!         coordinates: [x, y, theta, phi],
//!         parameters: [m = 1.0, r = 0.5, j_axle = 0.125, j_vertical = 0.0625],
//!         kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + j_axle/2*dot(phi)^2
//!             + j_vertical/2*dot(theta)^2,
//!         constraints: [
//!             roll_x = dot(x) - r*cos(theta)*dot(phi),
//!             roll_y = dot(y) - r*sin(theta)*dot(phi),
//!         ],
//!         inputs: [drive = phi],
//!     }
//! }
//!
//! let disk = Disk::default();
//! // from rest, a constant drive torque 0.1: phi'' = 0.1 / (j_axle + m r^2)
//! let system = Dalembert::constant(&disk, [0.1]);
//! let summary = Simulation::new(Rk4)
//!     .span(0.0, 2.0)
//!     .run(&system, [0.0; 8], &mut Table::new())
//!     .unwrap();
//! let phi = summary.state[3];
//! assert!((phi - 0.1 / (0.125 + 0.25) * 2.0 * 2.0 / 2.0).abs() < 1e-12);
//! assert!((summary.state[0] - 0.5 * phi).abs() < 1e-12); // x = r phi, rolling
//! ```

//!
//! # nalgebra
//!
//! The generated API speaks in arrays (`[f64; n]`, `[[f64; n]; m]` row-major,
//! `m[i][j]` in row `i`); the runtime computes on nalgebra (re-exported as
//! `chaplygin::runtime::nalgebra`). `chaplygin::runtime::arrays` converts
//! between them without the transposition of nalgebra's own
//! `From<[[T; R]; C]>`, which reads the inner arrays as columns:
//!
//! ```
//! use chaplygin::runtime::arrays::matrix_from_rows;
//! use chaplygin::runtime::linalg::{SMatrix, SVector};
//!
//! chaplygin::model! {
//!     /// A knife edge: a body of mass m and inertia j about its contact point
//!     /// offset a behind its centre of mass, which moves along its heading only.
//!     pub struct Sleigh {
//!         coordinates: [x, y, theta],
//!         parameters: [m = 2.0, j = 0.5, a = 0.25],
//!         kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
//!             + (dot(y) + a*cos(theta)*dot(theta))^2) + j/2*dot(theta)^2,
//!         constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
//!     }
//! }
//!
//! let sleigh = Sleigh::default();
//! let q = [0.0, 0.0, 0.0];
//! let g: SMatrix<f64, 3, 3> = matrix_from_rows(&sleigh.mass_matrix(&q));
//! // At theta = 0 by hand: g = [[m, 0, 0], [0, m, m a], [0, m a, j + m a^2]].
//! assert_eq!(g[(1, 2)], 0.5);
//! let cholesky = g.cholesky().expect("a mass matrix is positive definite");
//! // det g = m * (m (j + m a^2) - (m a)^2) = m^2 j
//! assert!((cholesky.determinant() - 2.0).abs() < 1e-14);
//! // The velocity of unit momentum p = g qdot = (0, 0, 1): qdot = g^-1 p.
//! let qdot = cholesky.solve(&SVector::from([0.0, 0.0, 1.0]));
//! assert!(((g * qdot)[2] - 1.0).abs() < 1e-15);
//! let back: [f64; 3] = qdot.into();
//! assert!((back[2] - 1.0 / 0.5).abs() < 1e-14); // by hand: thetadot = 1/j
//! ```

#![warn(missing_docs)]

pub use chaplygin_macros::model;
pub use chaplygin_runtime as runtime;

#[cfg(feature = "driver")]
pub mod animate;
#[cfg(feature = "driver")]
pub mod driver;
pub mod energy_control;
/// Gait design: the shape loops of a model with an SE(2) symmetry that move
/// it furthest per cycle (the package `chaplygin-gait`, optimized in tests
/// and debug builds too).
#[cfg(feature = "design")]
pub use chaplygin_gait as gait_design;
#[cfg(feature = "plot")]
pub mod plot;

/// Models read from their text, every derived function compiled to native
/// code at run time with Cranelift: [`jit::JitModel::from_source`] and
/// [`jit::JitModel::from_file`], and [`jit::compile`] for a model already
/// loaded. The results equal the IR interpreter's bit for bit.
/// [`jit::Fixed`] sees such a model at sizes fixed at compile time, through
/// the runtime's traits.
#[cfg(feature = "jit")]
pub mod jit {
    pub use chaplygin_codegen::interpret::{Fixed, SizeMismatch};
    pub use chaplygin_jit::{JitError, JitModel, LoadError, Native, NativePrograms, compile};
}

/// The README's examples, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

/// The guide's Rust examples (`docs/guide/`), compiled and run as
/// doctests, a chapter each.
#[cfg(doctest)]
pub mod guide {
    #[doc = include_str!("../docs/guide/model-language.md")]
    pub struct ModelLanguage;
    #[doc = include_str!("../docs/guide/mechanisms.md")]
    pub struct Mechanisms;
    #[doc = include_str!("../docs/guide/simulating.md")]
    pub struct Simulating;
    #[doc = include_str!("../docs/guide/how-it-works.md")]
    pub struct HowItWorks;
}
