//! Emission of a [`Program`] as Rust statements.
//!
//! A value read once is written into the expression that reads it, so one
//! statement computes a small tree of operations:
//! `let t3 = (t1 - q[2]) * t0.sin() + 0.5;` rather than one `let` per
//! operation. A value gets a `let` of its own when it is read more than once
//! (its common subexpression computed once), when it is one of a `sin_cos`
//! pair (`let (t4, t5) = t3.sin_cos();`), or when writing it into its
//! reader would make that expression wider than [`WIDTH`] characters, so
//! that formatted lines stay short. Constants are float literals where they
//! are read (`2.0`, `-0.5`, `0.000000000000000000000000000001`, non-finite
//! ones as `::core::primitive::f64::INFINITY` and friends); an output that
//! nothing else reads is written into the returned expressions.
//!
//! Every operation keeps its operands: the emitted tree is the program's,
//! parenthesized where Rust's precedence would regroup it (`a - (b + c)`,
//! `(a + b).sqrt()`, `-(a * b)`), so the compiled code rounds exactly as the
//! interpreter does. Types are inferred from the inputs (`q[2]`, `self.m`,
//! all `f64`); a `let` made of literals alone is typed
//! `::core::primitive::f64`, and a literal whose method is called is
//! suffixed (`2f64.sqrt()`). The code is spliced into user crates, so it
//! names types by absolute path only (a user item called `f64` or a module
//! called `core` cannot capture it), calls only `f64` methods, allocates
//! nothing, cannot panic, and compiles warning-free: every `let` is read.
//!
//! # Blocks
//!
//! rustc's backend spends time more than linear in the length of one
//! straight-line basic block (LLVM's SLP vectorizer, register allocator and
//! scheduler): a program longer than [`BLOCK_OPERATIONS`] operations is
//! cut into blocks of that many by a branch the optimizer cannot see
//! through and that is never taken
//! (`if ::core::hint::black_box(false) { ::core::hint::black_box(()); }`).
//! Values flow across it in registers; it costs a test and a branch, and
//! the optimizer neither moves code across it nor keeps what it read from
//! memory (inputs, parameters). Measured on the benchmark bicycle
//! (BENCHMARKS.md): without blocks `rustc -O` takes 33-37 s on its code,
//! with blocks of 2,000 operations 20-21 s, as with 500; blocks of 500
//! made the right-hand side's Jacobian 1.4x slower, with blocks of 2,000 it
//! runs within 3% of none.
//!
//! # Variants
//!
//! [`Program::emit_variants`] writes a program whose outputs fall into
//! variants (the same items in several charts): the instructions every
//! variant needs first, once, then those each variant needs besides, for a
//! `match` to run one of. Instructions keep the program's order (rustc
//! compiled it faster than an order output by output, and the code ran as
//! fast).
//!
//! Values are named `t0, t1, ...` in the order of their `let`s, with
//! [`Span::mixed_site`]: inside a procedural macro they cannot clash with
//! the caller's identifiers, and they resolve among themselves and in the
//! returned output expressions. Code written out as text (e.g. from a build
//! script) has no hygiene: there, the input expressions must not mention
//! identifiers of the form `t<n>`.

mod expression;
mod writer;

use super::{IrError, Program, Value};
use proc_macro2::TokenStream;
use writer::Writer;

/// The widest expression, in characters as formatted, into which a value read
/// once is still written; a wider one gets a `let`.
pub const WIDTH: usize = 64;

/// The most operations of one basic block of a long program.
pub const BLOCK_OPERATIONS: u64 = 2000;

/// The width a name is counted with when deciding what fits.
const NAME_WIDTH: usize = 5;

/// A program written out as Rust: its statements and its outputs.
#[derive(Clone, Debug)]
pub struct RustProgram {
    /// The `let` statements computing every value, in order.
    pub statements: TokenStream,
    /// One expression per output, valid after `statements`.
    pub outputs: Vec<TokenStream>,
}

/// A program whose outputs fall into variants (the same items in several
/// charts, say) written out as Rust: what every variant needs, once, then
/// what each needs besides.
#[derive(Clone, Debug)]
pub struct RustVariants {
    /// The statements of the values every variant reads.
    pub common: TokenStream,
    /// Each variant's statements and outputs, valid after `common`.
    pub variants: Vec<RustProgram>,
}

impl Program {
    /// Emits the program as Rust statements; `inputs[i]` is an expression of
    /// type `f64` for input slot `i` (e.g. `q[2]`, `self.m`).
    ///
    /// Fails with [`IrError::InputCount`] unless there is one expression per
    /// input slot.
    pub fn emit(&self, inputs: &[TokenStream]) -> Result<RustProgram, IrError> {
        let every_output = (0..self.outputs.len()).collect();
        let emitted = self.emit_variants(inputs, &[every_output])?;
        let mut statements = emitted.common;
        let only = emitted.variants.into_iter().next().unwrap_or(RustProgram {
            statements: TokenStream::new(),
            outputs: Vec::new(),
        });
        statements.extend(only.statements);
        Ok(RustProgram {
            statements,
            outputs: only.outputs,
        })
    }

    /// Emits the program for `variants`, each a list of output positions:
    /// the instructions that every variant needs are written once, in
    /// `common` (none with one variant); those that only some need are
    /// written in each of theirs, so a variant computes no value it does
    /// not read.
    ///
    /// Fails with [`IrError::InputCount`] unless there is one expression per
    /// input slot, and with [`IrError::OutputCount`] when a position is not
    /// an output.
    pub fn emit_variants(
        &self,
        inputs: &[TokenStream],
        variants: &[Vec<usize>],
    ) -> Result<RustVariants, IrError> {
        self.check_inputs(inputs.len())?;
        if let Some(&position) = variants
            .iter()
            .flatten()
            .find(|&&i| i >= self.outputs.len())
        {
            return Err(IrError::OutputCount {
                expected: self.outputs.len(),
                found: position + 1,
            });
        }
        let needs: Vec<Vec<bool>> = variants.iter().map(|v| self.needed_by(v)).collect();
        let shared = variants.len() > 1;
        let by_all = |value: Value| shared && needs.iter().all(|need| need[value.index()]);
        let long = self.operation_count().after_cse > BLOCK_OPERATIONS;
        let mut writer = Writer::new(self, inputs, long.then_some(BLOCK_OPERATIONS));
        for instruction in self.instructions.iter().filter(|i| by_all(i.result)) {
            writer.instruction(instruction);
        }
        let common = std::mem::take(&mut writer.statements);
        let mut emitted = Vec::with_capacity(variants.len());
        for (variant, need) in variants.iter().zip(&needs) {
            let mut own = writer.clone();
            let instructions = self.instructions.iter();
            for instruction in instructions.filter(|i| need[i.result.index()] && !by_all(i.result))
            {
                own.instruction(instruction);
            }
            let outputs = variant
                .iter()
                .map(|&i| own.output(self.outputs[i]))
                .collect();
            writer.next_name = own.next_name;
            emitted.push(RustProgram {
                statements: own.statements,
                outputs,
            });
        }
        Ok(RustVariants {
            common,
            variants: emitted,
        })
    }
}
