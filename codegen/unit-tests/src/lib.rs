//! Empty: this package's code is the engine's (`codegen/src`), which its
//! test target `unit` compiles with the engine's unit tests, unoptimized.
//! A package needs a target of its own to be packaged (`cargo package
//! --workspace`), and the test's source lies outside this one.
