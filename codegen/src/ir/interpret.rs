//! The reference interpreter of a [`Program`].
//!
//! Executes the instructions in order over a table of `f64` values, one slot
//! per SSA value. The table is borrowed from the caller, so repeated
//! evaluations allocate nothing once it has grown to
//! [`Program::value_count`]. Each operation is the same `f64` method the
//! emitted Rust calls, so interpreter and emitted code agree bit for bit.

use super::{Instruction, IrError, Op, Program};

impl Program {
    /// Evaluates the program: `inputs[i]` is input slot `i`, `outputs[j]`
    /// receives output `j`, and `scratch` is the reusable value table.
    ///
    /// Fails with [`IrError::InputCount`] or [`IrError::OutputCount`] when a
    /// slice has the wrong length.
    pub fn evaluate(
        &self,
        inputs: &[f64],
        scratch: &mut Vec<f64>,
        outputs: &mut [f64],
    ) -> Result<(), IrError> {
        self.check_inputs(inputs.len())?;
        if outputs.len() != self.outputs.len() {
            return Err(IrError::OutputCount {
                expected: self.outputs.len(),
                found: outputs.len(),
            });
        }
        scratch.clear();
        scratch.resize(self.value_count, 0.0);
        for instruction in &self.instructions {
            execute(instruction, inputs, scratch);
        }
        for (output, value) in outputs.iter_mut().zip(&self.outputs) {
            *output = scratch[value.index()];
        }
        Ok(())
    }

    /// Evaluates the program into a new vector (allocates; see [`Program::evaluate`]).
    pub fn evaluate_vec(&self, inputs: &[f64]) -> Result<Vec<f64>, IrError> {
        let mut outputs = vec![0.0; self.outputs.len()];
        self.evaluate(inputs, &mut Vec::new(), &mut outputs)?;
        Ok(outputs)
    }

    /// Fails unless `found` input values or expressions match the input slots.
    pub(super) fn check_inputs(&self, found: usize) -> Result<(), IrError> {
        if found == self.input_count() {
            Ok(())
        } else {
            Err(IrError::InputCount {
                expected: self.input_count(),
                found,
            })
        }
    }
}

/// Runs one instruction; its operands are already in `values`.
fn execute(instruction: &Instruction, inputs: &[f64], values: &mut [f64]) {
    let at = |value: super::Value| values[value.index()];
    let result = match &instruction.op {
        Op::Input(slot) => inputs[*slot],
        Op::Constant(c) => c.value(),
        Op::Add(a, b) => at(*a) + at(*b),
        Op::Sub(a, b) => at(*a) - at(*b),
        Op::Mul(a, b) => at(*a) * at(*b),
        Op::Div(a, b) => at(*a) / at(*b),
        Op::Neg(a) => -at(*a),
        Op::Powi(a, n) => at(*a).powi(*n),
        Op::Sqrt(a) => at(*a).sqrt(),
        Op::Powf(a, e) => at(*a).powf(e.value()),
        Op::Sin(a) => at(*a).sin(),
        Op::Cos(a) => at(*a).cos(),
        Op::Tan(a) => at(*a).tan(),
        Op::Exp(a) => at(*a).exp(),
        Op::Ln(a) => at(*a).ln(),
        Op::Asin(a) => at(*a).asin(),
        Op::Acos(a) => at(*a).acos(),
        Op::Atan(a) => at(*a).atan(),
        Op::Atan2(y, x) => at(*y).atan2(at(*x)),
        Op::SinCos { angle, cosine } => {
            let (sine, cos) = at(*angle).sin_cos();
            values[cosine.index()] = cos;
            sine
        }
    };
    values[instruction.result.index()] = result;
}
