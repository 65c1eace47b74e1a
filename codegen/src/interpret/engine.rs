//! What runs a model's programs: the IR interpreter ([`Interpreter`], the
//! reference) or another engine made from the same programs, such as native
//! code compiled from them at run time.

use crate::ir::{IrError, Program};

/// Runs the programs of one model, numbered as
/// [`super::InterpretedModel::programs`] lists them.
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
