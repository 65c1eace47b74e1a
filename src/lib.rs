//! Chaplygin: nonholonomic mechanical models compiled into verified simulators.
//!
//! Declare a model with [`model!`] (or in a `.model` file read by
//! `chaplygin_codegen::Builder` in a build script). At build time the model
//! flows one way: parse, check (every rule of the language, errors on the
//! offending token), derive (constraint analysis; the Lagrange-d'Alembert
//! equations with multipliers; the reduced port-Hamiltonian form of Duindam &
//! Stramigioli; with a symmetry, the nonholonomic momentum equation), emit. The result is a parameter struct whose allocation-free
//! methods compute the mass matrix, the energy, the constraints,
//! `acceleration`, and the reduced flow `reduced_rhs` with its Jacobian, with
//! a symmetry the momentum equation, the reconstruction and the shape
//! equations, plus a `REPORT` of what was derived. The README lists every item.

pub use chaplygin_macros::model;
pub use chaplygin_runtime as runtime;

#[cfg(feature = "cli")]
pub mod plot;

/// The README's examples, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
