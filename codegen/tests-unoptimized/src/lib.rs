//! Empty: this package's code is the engine's (`codegen/src` and
//! `codegen/tests`), which its test targets `unit` and `integration`
//! compile unoptimized. A package needs a target of its own to be packaged
//! (`cargo package --workspace`), and the tests' sources lie outside this
//! one.
