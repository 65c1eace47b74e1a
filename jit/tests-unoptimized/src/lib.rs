//! Empty: this package's code is the JIT's integration tests
//! (`jit/tests`), which its test target `integration` compiles
//! unoptimized. A package needs a target of its own to be packaged
//! (`cargo package --workspace`), and the tests' source lies outside this
//! one.
