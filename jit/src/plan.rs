//! Where each value of a program lives between its definition and its uses.
//!
//! Cranelift's register allocator slows down sharply on the long live
//! ranges of large straight-line programs: translated value for value, the
//! benchmark bicycle's programs took 30 to 80 s to compile, nearly all of it
//! in register allocation. So the translation keeps only short live ranges
//! in registers. A value read more than [`NEAR`] instructions after it was
//! defined or last reloaded, or after a call (no floating-point register
//! survives a call in the C convention), is reloaded: an input from the
//! input array, a constant by materializing it again, anything else from a
//! spill slot it was stored into when defined. The allocator then has little
//! to search, and the code is as fast as rustc's (see [`crate`]).
//!
//! Spill slots are reused: a value's slot is free again after its last use.

use chaplygin_codegen::ir::{Op, Program, Value};

/// The most instructions between a definition (or reload) and a use that
/// reads it from a register.
pub(crate) const NEAR: usize = 32;

/// The stack slots of a program's values.
#[derive(Debug)]
pub(crate) struct Plan {
    /// The slot of each value that is stored when defined, by value index.
    slots: Vec<Option<usize>>,
    /// The number of slots.
    slot_count: usize,
}

impl Plan {
    /// Assigns a slot to every value that has a far use and cannot be
    /// reloaded from where it came from.
    pub(crate) fn new(program: &Program) -> Plan {
        let far = far_values(program);
        let last_use = last_uses(program);
        let mut slots = vec![None; program.value_count()];
        // The slots in use, by the index of the value they hold.
        let mut holding = vec![None; program.value_count()];
        let mut free = Vec::new();
        let mut slot_count = 0;
        for (position, instruction) in program.instructions().iter().enumerate() {
            for value in defined(&instruction.op, instruction.result) {
                if far[value.index()] && !rematerializable(&instruction.op) {
                    let slot = free.pop().unwrap_or_else(|| {
                        slot_count += 1;
                        slot_count - 1
                    });
                    slots[value.index()] = Some(slot);
                    holding[value.index()] = Some(slot);
                }
            }
            for operand in instruction.op.operands() {
                if last_use[operand.index()] == position {
                    free.extend(holding[operand.index()].take());
                }
            }
        }
        Plan { slots, slot_count }
    }

    /// The slot `value` is stored into, if it has one.
    pub(crate) fn slot(&self, value: Value) -> Option<usize> {
        self.slots[value.index()]
    }

    /// The number of slots.
    pub(crate) fn slot_count(&self) -> usize {
        self.slot_count
    }
}

/// Whether the value an instruction defines is reloaded by repeating it.
pub(crate) fn rematerializable(op: &Op) -> bool {
    matches!(op, Op::Input(_) | Op::Constant(_))
}

/// Whether the operation is one or more calls.
pub(crate) fn calls(op: &Op) -> bool {
    !matches!(
        op,
        Op::Input(_)
            | Op::Constant(_)
            | Op::Add(..)
            | Op::Sub(..)
            | Op::Mul(..)
            | Op::Div(..)
            | Op::Neg(_)
            | Op::Sqrt(_)
    )
}

/// The values an instruction defines.
fn defined(op: &Op, result: Value) -> impl Iterator<Item = Value> {
    let cosine = match op {
        Op::SinCos { cosine, .. } => Some(*cosine),
        _ => None,
    };
    std::iter::once(result).chain(cosine)
}

/// Whether each value (by index) is read more than [`NEAR`] instructions
/// after its definition or after a call that follows its definition.
fn far_values(program: &Program) -> Vec<bool> {
    let mut defined_at = vec![(0, 0); program.value_count()];
    let mut far = vec![false; program.value_count()];
    let mut calls_so_far = 0;
    for (position, instruction) in program.instructions().iter().enumerate() {
        for operand in instruction.op.operands() {
            let (at, calls_then) = defined_at[operand.index()];
            far[operand.index()] |= position - at > NEAR || calls_so_far != calls_then;
        }
        calls_so_far += usize::from(calls(&instruction.op));
        for value in defined(&instruction.op, instruction.result) {
            defined_at[value.index()] = (position, calls_so_far);
        }
    }
    far
}

/// The position of the last instruction that reads each value (by index).
fn last_uses(program: &Program) -> Vec<usize> {
    let mut last = vec![0; program.value_count()];
    for (position, instruction) in program.instructions().iter().enumerate() {
        for operand in instruction.op.operands() {
            last[operand.index()] = position;
        }
    }
    last
}
