//! Programs run one after another as one program: what an emitted function
//! that calls other emitted functions computes.
//!
//! [`Program::chained`] runs its stages in order; each input slot of a
//! stage reads an input of the whole or an output of an earlier stage. Every
//! instruction keeps its operation and its operands, so each value is
//! computed to the same bits as the stages would compute it run one by one.
//! An instruction equal to an earlier one of another stage (the same
//! operation on the same values) reuses its value, and what no output reads
//! is dropped.

use super::{Instruction, IrError, Op, Program, Value};
use rustc_hash::FxHashMap as HashMap;

/// Where a stage's input slot is read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// Input slot `i` of the chained program.
    Input(usize),
    /// Output `output` of the earlier stage `stage`.
    Output {
        /// The stage, counted from 0.
        stage: usize,
        /// Its output.
        output: usize,
    },
}

/// One stage of a chain: a program and where each of its input slots is
/// read from.
#[derive(Clone, Copy, Debug)]
pub struct Stage<'a> {
    /// The program run.
    pub program: &'a Program,
    /// One source per input slot of `program`.
    pub sources: &'a [Source],
}

impl Program {
    /// The program running `stages` in order, with input slots named
    /// `names`; its outputs are the last stage's.
    ///
    /// Fails with [`IrError::InputCount`] when a stage's sources do not
    /// match its input slots, with [`IrError::UnboundSymbol`] when a source
    /// is an input beyond `names` or an output of a stage not yet run, and
    /// with [`IrError::OutputCount`] when it is an output the stage does
    /// not have.
    pub fn chained(names: &[String], stages: &[Stage<'_>]) -> Result<Program, IrError> {
        let mut chain = Chain {
            inputs: names.len(),
            ..Chain::default()
        };
        for stage in stages {
            let outputs = chain.run(stage)?;
            chain.stage_outputs.push(outputs);
        }
        let outputs = chain.stage_outputs.pop().unwrap_or_default();
        let before_cse = stages.last().map_or(0, |stage| stage.program.before_cse);
        let whole = Program {
            input_names: names.to_vec(),
            instructions: chain.instructions,
            outputs,
            value_count: chain.values as usize,
            before_cse,
        };
        let positions: Vec<usize> = (0..whole.outputs.len()).collect();
        let slots: Vec<Option<usize>> = (0..names.len()).map(Some).collect();
        let mut pruned = whole.pruned(&positions, &slots, before_cse)?;
        pruned.input_names.resize(names.len(), String::new());
        Ok(pruned)
    }
}

/// The instructions written so far, numbered so that equal ones are one.
#[derive(Default)]
struct Chain {
    inputs: usize,
    instructions: Vec<Instruction>,
    numbered: HashMap<Op, Value>,
    sines_cosines: HashMap<Value, (Value, Value)>,
    values: u32,
    stage_outputs: Vec<Vec<Value>>,
}

impl Chain {
    /// Appends `stage`; its outputs' values.
    fn run(&mut self, stage: &Stage<'_>) -> Result<Vec<Value>, IrError> {
        let program = stage.program;
        if stage.sources.len() != program.input_count() {
            return Err(IrError::InputCount {
                expected: program.input_count(),
                found: stage.sources.len(),
            });
        }
        let mut renamed: Vec<Option<Value>> = vec![None; program.value_count];
        for instruction in &program.instructions {
            let at = |value: Value| renamed[value.index()].expect("defined before it is read");
            match &instruction.op {
                &Op::Input(slot) => {
                    let value = self.bound(stage.sources[slot])?;
                    renamed[instruction.result.index()] = Some(value);
                }
                Op::SinCos { angle, cosine } => {
                    let (sine, cosine_value) = self.sin_cos(at(*angle));
                    renamed[instruction.result.index()] = Some(sine);
                    renamed[cosine.index()] = Some(cosine_value);
                }
                op => {
                    let value = self.define(op.with_operands(at));
                    renamed[instruction.result.index()] = Some(value);
                }
            }
        }
        Ok(program
            .outputs
            .iter()
            .map(|value| renamed[value.index()].expect("outputs are defined"))
            .collect())
    }

    /// The value an input slot bound to `source` reads.
    fn bound(&mut self, source: Source) -> Result<Value, IrError> {
        match source {
            Source::Input(slot) if slot < self.inputs => Ok(self.define(Op::Input(slot))),
            Source::Output { stage, output } if stage < self.stage_outputs.len() => {
                let outputs = &self.stage_outputs[stage];
                outputs.get(output).copied().ok_or(IrError::OutputCount {
                    expected: outputs.len(),
                    found: output + 1,
                })
            }
            _ => Err(IrError::UnboundSymbol {
                name: format!("{source:?}"),
            }),
        }
    }

    /// The value of `op`: an equal earlier instruction's, or a new one.
    fn define(&mut self, op: Op) -> Value {
        if let Some(&value) = self.numbered.get(&op) {
            return value;
        }
        let result = self.fresh();
        self.instructions.push(Instruction {
            op: op.clone(),
            result,
        });
        self.numbered.insert(op, result);
        result
    }

    /// The sine and cosine of `angle`, computed once.
    fn sin_cos(&mut self, angle: Value) -> (Value, Value) {
        if let Some(&pair) = self.sines_cosines.get(&angle) {
            return pair;
        }
        let (sine, cosine) = (self.fresh(), self.fresh());
        self.instructions.push(Instruction {
            op: Op::SinCos { angle, cosine },
            result: sine,
        });
        self.sines_cosines.insert(angle, (sine, cosine));
        (sine, cosine)
    }

    fn fresh(&mut self) -> Value {
        let value = Value(self.values);
        self.values += 1;
        value
    }
}
