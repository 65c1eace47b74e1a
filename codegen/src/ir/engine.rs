//! What runs programs: the IR interpreter ([`Interpreter`], the reference)
//! or another engine made from the same programs, such as native code
//! compiled from them at run time; and the [`Backend`] that makes an engine
//! of a set of programs, which a caller chooses once for a model's
//! programs and for the numeric searches of its derivation alike.

use super::{IrError, Program};

/// Runs a set of programs, numbered as their caller lists them (a model's,
/// or a derivation's own).
pub trait Engine: Send + Sync {
    /// The engine's name, as summaries print it (`interpret`, `jit`).
    fn name(&self) -> &'static str;

    /// Runs program `index`, which is `program`, with the contract of
    /// [`Program::evaluate`]: `inputs[i]` is input slot `i`, `outputs[j]`
    /// receives output `j`.
    ///
    /// # Errors
    /// [`IrError::InputCount`] or [`IrError::OutputCount`] when a slice has
    /// the wrong length.
    fn evaluate(
        &self,
        index: usize,
        program: &Program,
        inputs: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), IrError>;
}

/// The IR interpreter, [`Program::evaluate`], its values kept in a buffer
/// of the calling thread that grows to the largest program's and is reused.
#[derive(Clone, Copy, Debug, Default)]
pub struct Interpreter;

thread_local! {
    /// The interpreter's values of the program being run.
    static VALUES: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

impl Engine for Interpreter {
    fn name(&self) -> &'static str {
        "interpret"
    }

    fn evaluate(
        &self,
        _index: usize,
        program: &Program,
        inputs: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), IrError> {
        VALUES.with_borrow_mut(|values| program.evaluate(inputs, values, outputs))
    }
}

/// What makes the engine of a set of programs: the [`Interpreter`], or
/// another backend (native code compiled at run time).
pub trait Backend {
    /// The engine that runs `programs[i]` as program `i`.
    fn engine(&self, programs: &[&Program]) -> Box<dyn Engine>;
}

impl Backend for Interpreter {
    fn engine(&self, _programs: &[&Program]) -> Box<dyn Engine> {
        Box::new(Interpreter)
    }
}
