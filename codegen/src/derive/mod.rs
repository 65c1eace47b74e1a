//! Derivations: from a checked model to its equations of motion.
//!
//! One module per formulation, each stating its equation and citing its source.

pub mod constraints;
pub mod lagrange_dalembert;
pub mod momentum;
pub mod port_hamiltonian;
