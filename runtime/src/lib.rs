//! The Chaplygin runtime: what generated models plug into.
//!
//! - [`system`]: the traits a generated model implements
//!   ([`system::ReducedPortHamiltonian`], [`system::LagrangeDalembert`]) and
//!   adapters turning a model and its input into an [`system::OdeSystem`];
//! - [`integrate`]: integrators over any [`system::OdeSystem`] (RK4,
//!   Dormand-Prince 5(4), the implicit midpoint rule);
//! - [`linalg`]: dense linear algebra on the stack;
//! - [`phase`]: the group displacement over one period of a shape gait, split
//!   into its geometric and dynamic parts.

pub mod integrate;
pub mod linalg;
pub mod phase;
pub mod system;

pub use integrate::Error;
