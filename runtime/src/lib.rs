//! The Chaplygin runtime: what generated models plug into (the guide,
//! `docs/guide/` in the repository: "Simulating").
//!
//! - [`system`]: the traits a generated model implements
//!   ([`system::ReducedPortHamiltonian`], [`system::LagrangeDalembert`]) and
//!   adapters turning a model and its input into an [`system::OdeSystem`];
//! - [`law`]: plain control laws `u = f(t, x)` (constant, open-loop,
//!   feedback); [`control`]: port-Hamiltonian controllers (with their own
//!   state and energy, interconnected power-conservingly);
//! - [`state`]: the state vectors, of a size fixed at compile time
//!   (`[f64; D]`) or known at run time (`Vec<f64>`);
//! - [`integrate`]: integrators over any [`system::OdeSystem`] (RK4,
//!   Dormand-Prince 5(4), the implicit midpoint rule, Gonzalez's discrete
//!   gradient);
//! - [`monitor`]: where a formulation degenerates; [`partition`]: charts of
//!   D chosen at run time (coordinate partitioning); [`projection`]: a state
//!   moved back onto the constraint manifold after a step;
//! - [`simulate`]: the simulation loop (integrator, span, step, regularity
//!   checks, recording) and [`record`]: where its rows go (memory, CSV);
//! - [`linalg`]: linear algebra on nalgebra's matrices (LU, Cholesky,
//!   eigenvalues, central-difference Jacobians), and [`arrays`]: nalgebra
//!   values to and from the generated code's arrays;
//! - [`linearize`]: operating points, the steady-motion check and the
//!   linear system about a steady motion with its eigenvalues;
//! - [`gait`]: the motion a prescribed periodic shape trajectory makes,
//!   cycle by cycle, at sizes known at run time;
//! - [`phase`]: the group displacement over one period of a shape gait, split
//!   into its geometric and dynamic parts.

#![warn(missing_docs)]

pub mod arrays;
pub mod control;
pub mod gait;
pub mod integrate;
pub mod law;
pub mod linalg;
pub mod linearize;
pub mod monitor;
pub mod partition;
pub mod phase;
pub mod projection;
pub mod record;
pub mod simulate;
pub mod state;
pub mod system;

pub use integrate::Error;
/// The nalgebra the runtime is built on, for callers that name its types.
pub use nalgebra;
