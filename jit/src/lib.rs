//! Native code of the IR's straight-line programs, compiled at run time with
//! Cranelift: how the `chaplygin` command line and Python package run a
//! model from its text (the guide, `docs/guide/` in the repository:
//! "Simulating").
//!
//! [`JitModel::from_source`] and [`JitModel::from_file`] load a model from
//! its text with its derived functions run as native code: an
//! [`InterpretedModel`](chaplygin_codegen::interpret::InterpretedModel)
//! whose engine ([`chaplygin_codegen::interpret::Engine`]) is [`OnDemand`],
//! which compiles each function's program ([`NativePrograms`]) the first
//! time it runs; [`compile`] does the same to a model already loaded.
//!
//! [`NativePrograms::compile`] turns a list of
//! [`Program`]s (the programs of an
//! [`InterpretedModel`](chaplygin_codegen::interpret::InterpretedModel), say)
//! into machine code for the host, one function per program in one JIT
//! module, and [`NativePrograms::evaluate`] runs one of them: the same
//! computation as the reference interpreter,
//! [`Program::evaluate`](chaplygin_codegen::ir::Program::evaluate), without
//! its table of values or its dispatch per instruction.
//!
//! The results are bit-identical to the interpreter's. Every operation is
//! either the same IEEE operation (`+ - * /`, negation and square root are
//! correctly rounded in both) or a call of the same Rust `f64` method (`sin`,
//! `cos`, `tan`, `exp`, `ln`, `powi`, `powf`; `sin_cos` is `sin` and `cos`),
//! on the same operands, in the same order; the code neither fuses,
//! reassociates nor folds floating-point operations. Only the bits of a NaN
//! (its sign and payload) may differ, as IEEE leaves them open.
//!
//! # Compile time and speed
//!
//! The programs are compiled without Cranelift's optimizations (the IR has
//! shared its common subexpressions already) with its backtracking register
//! allocator, on every core of the machine. Long live ranges make that
//! allocator slow, so a value read far from its definition is reloaded
//! rather than kept in a register (`plan`). Measured on the benchmark
//! bicycle (`models/bicycle.model`: 29 programs, 196,000 instructions, the
//! largest 44,000), release build, on a 2-core machine shared with other
//! work:
//!
//! | Cranelift | compile all | `acceleration` | `reduced_rhs_jacobian` |
//! |---|---|---|---|
//! | `opt_level` none (chosen) | 0.6-0.7 s on 2 threads (1.0 s on one) | 1.6 us | 14.5 us |
//! | `opt_level` speed | 3.6-4.6 s on one thread | 2.3 us | 22 us |
//! | none, the single-pass allocator | 0.5-0.6 s on one thread | 3.1 us | 23 us |
//! | rustc (the generated Rust, release) | | 1.7 us | 16.3 us |
//! | the interpreter | | 42 us | 290 us |
//!
//! Cranelift's optimizations cost more than they give here (its value
//! numbering and redundant-load elimination can merge reloads back into
//! long live ranges). Translated value for value, without reloads, the
//! programs took 30-77 s to compile at either level.
//!
//! ```
//! use chaplygin_codegen::interpret::InterpretedModel;
//! use chaplygin_jit::NativePrograms;
//!
//! let source = std::fs::read_to_string(concat!(
//!     env!("CARGO_MANIFEST_DIR"),
//!     "/../models/sleigh.model"
//! ))
//! .unwrap();
//! let model = InterpretedModel::from_source(&source).unwrap();
//! let programs: Vec<_> = model.programs().map(|(_, program)| program).collect();
//! let native = NativePrograms::compile(&programs).unwrap();
//! let program = programs[0];
//! let inputs = vec![0.25; program.input_count()];
//! let mut outputs = vec![0.0; program.outputs().len()];
//! native.evaluate(0, &inputs, &mut outputs).unwrap();
//! assert_eq!(outputs, program.evaluate_vec(&inputs).unwrap());
//! ```

mod host;
mod model;
mod native;
mod plan;
mod routines;
mod translate;

use chaplygin_codegen::ir::{IrError, Program};
use cranelift_module::ModuleError;
use host::Verify;
pub use model::{JitModel, LoadError, Native, OnDemand, compile};
use native::Code;
use std::fmt;

/// A failure to compile programs.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum JitError {
    /// Cranelift cannot generate code for this machine.
    #[error("Cranelift does not support this host: {0}")]
    UnsupportedHost(String),
    /// Cranelift refused a setting or a function.
    #[error("Cranelift failed: {0}")]
    Compile(String),
}

impl From<ModuleError> for JitError {
    fn from(error: ModuleError) -> JitError {
        JitError::Compile(error.to_string())
    }
}

/// Native code of a list of programs, compiled into one Cranelift JIT module.
///
/// The code is freed when the value is dropped. It is immutable once
/// compiled, so the value can be shared between threads and each thread can
/// run any program at the same time.
pub struct NativePrograms {
    code: Code,
}

impl NativePrograms {
    /// Compiles every program, program `i` becoming the native program of
    /// index `i`, on as many threads as the machine runs at once.
    ///
    /// Fails with [`JitError::UnsupportedHost`] when Cranelift has no backend
    /// for the host, or [`JitError::Compile`] on a Cranelift error.
    ///
    /// # Panics
    ///
    /// If a program breaks [`Program`]'s invariants (an input slot at or past
    /// its input count, a value read before it is defined), which the
    /// programs [`lower`](chaplygin_codegen::ir::lower) builds never do.
    pub fn compile(programs: &[&Program]) -> Result<NativePrograms, JitError> {
        Ok(NativePrograms {
            code: host::compile(programs, Verify::No)?,
        })
    }

    /// [`NativePrograms::compile`], with Cranelift's IR verifier checking
    /// each translated function before its code is generated: slower, a
    /// check of the translation itself (a failure is a
    /// [`JitError::Compile`] naming what the verifier found).
    ///
    /// # Errors
    /// As [`NativePrograms::compile`].
    ///
    /// # Panics
    /// As [`NativePrograms::compile`].
    pub fn compile_verified(programs: &[&Program]) -> Result<NativePrograms, JitError> {
        Ok(NativePrograms {
            code: host::compile(programs, Verify::Yes)?,
        })
    }

    /// The number of programs.
    pub fn len(&self) -> usize {
        self.code.len()
    }

    /// Whether there are no programs.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Runs program `index`: `inputs[i]` is its input slot `i`, `outputs[j]`
    /// receives its output `j`, as in [`Program::evaluate`], which needs a
    /// table of values besides; this needs none and allocates nothing.
    ///
    /// Fails with [`IrError::InputCount`] or [`IrError::OutputCount`] when a
    /// slice has the wrong length (the input count is checked first).
    ///
    /// # Panics
    ///
    /// If `index` is not below [`NativePrograms::len`].
    pub fn evaluate(
        &self,
        index: usize,
        inputs: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), IrError> {
        self.code.run(index, inputs, outputs)
    }
}

impl fmt::Debug for NativePrograms {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NativePrograms")
            .field("programs", &self.len())
            .finish_non_exhaustive()
    }
}
