//! What the JIT's integration tests share (and the `jit` fuzz target).

pub mod random_programs;
