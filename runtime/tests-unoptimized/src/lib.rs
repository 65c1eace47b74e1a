//! Empty: this package's code is the runtime's (`runtime/src` and
//! `runtime/tests`), which its test targets `unit` and `integration`
//! compile unoptimized. A package needs a target of its own to be packaged
//! (`cargo package --workspace`), and the tests' sources lie outside this
//! one.
