//! Chaplygin: nonholonomic mechanical models compiled into verified
//! simulators.
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
//!    configurations, CSV recording; and, with the default `cli` feature,
//!    [`plot`] for PNG plots and the `chaplygin` command line.
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

#![warn(missing_docs)]

pub use chaplygin_macros::model;
pub use chaplygin_runtime as runtime;

#[cfg(feature = "cli")]
pub mod plot;

/// The README's examples, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
