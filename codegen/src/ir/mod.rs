//! Straight-line intermediate representation of derived expressions.
//!
//! A [`Program`] computes a list of outputs from a list of `f64` inputs with a
//! flat sequence of [`Instruction`]s in SSA form: each instruction defines a
//! fresh [`Value`] (printed `t<n>`) from earlier values, except
//! [`Op::SinCos`], which defines two. [`lower()`] builds a program from
//! expressions of a [`Store`](crate::sym::Store); the program can then be
//! interpreted ([`Program::evaluate`]), differentiated forward
//! ([`Program::tangents`]) or emitted as Rust statements
//! ([`Program::emit`]).
//!
//! # Common subexpressions
//!
//! The store is hash-consed, so equal sub-expressions are already one node;
//! lowering gives every node that is needed exactly one value, whatever the
//! number of parents or outputs that use it. On top of that:
//!
//! - every instruction is value-numbered: an instruction equal to an earlier one
//!   (operands of `+` and `*` taken in either order) reuses its value;
//! - n-ary sums and products become binary chains whose operands are ordered by
//!   how many sums and products share them, constants last, so that chains
//!   with a common prefix (`a*b*c` and `a*b*d`) compute the prefix (`a*b`) once;
//! - `sin u` and `cos u` both needed become one `sin_cos(u)`;
//! - a divisor `x^-e` that several sums and products read is inverted once,
//!   `r = 1 / x^e`, and multiplied (`v = p * r`, then `v * cos(phi)`, ...),
//!   rather than divided by in each of them;
//! - the same constant is one value;
//! - a term `-c*u` of a sum whose value `-c*u` is computed anyway (it is an
//!   output, say) is added rather than rebuilt as `c*u` and subtracted.
//!
//! Arithmetic is shaped as a person would write it: a term with a negative
//! coefficient is subtracted (`a - 3*b`, not `a + (-3)*b`), `-x` is a
//! negation, the factors `x^-1`, `x^-2`, `x^-3` and `x^(-1/2)` of a product
//! are gathered into one division (`a*b/(c*d^2)`) unless they are shared,
//! `x^2` and `x^3` are multiplications (`x*x`, `x^2*x`), other integer
//! powers are `powi`,
//! `x^(1/2)` is `sqrt`, `x^(-1/2)` is `1/sqrt`, and other rational powers are
//! `powf`.
//!
//! # Cost model
//!
//! One operation is one binary `+ - * /`, one negation, or one call of `sin`,
//! `cos`, `tan`, `exp`, `ln`, `sqrt`, `powi`, `powf` or `sin_cos`; inputs and
//! constants are free. [`Program::operation_count`] reports
//!
//! - `before_cse`: the cost of the outputs written out as trees, every use of
//!   a shared node paying for the node again: a sum or product of `n` operands
//!   costs `n - 1`, a call costs 1, and a power costs what it costs on its own
//!   (`x^2` 1, `x^3` 2, `x^-1` 1, `x^-2` 2, `x^-3` 3, `x^(1/2)` 1,
//!   `x^(-1/2)` 2, any other exponent 1). It is computed node by node on the
//!   DAG (never by expanding it) and saturates at `u64::MAX`;
//! - `after_cse`: the cost of the program's instructions.
//!
//! Lowering never spends more on a node than the tree pays for it, so
//! `after_cse <= before_cse` always holds.
//!
//! # Example
//!
//! `sin(x)*y - cos(x)`, `x^2 + 3*sin(x)` lowered with inputs `[x, y]`
//! prints (see [`Program`]'s `Display`):
//!
//! ```text
//! t0 = in[0] (x)
//! t1 = in[1] (y)
//! t2, t3 = sin_cos(t0)
//! t4 = t1 * t2
//! t5 = t4 - t3
//! t6 = t0 * t0
//! t7 = 3
//! t8 = t2 * t7
//! t9 = t6 + t8
//! out[0] = t5
//! out[1] = t9
//! ```

mod chain;
mod cost;
mod emit;
mod engine;
mod interpret;
mod lower;
#[cfg(test)]
mod properties;
mod tangent;
mod tape;
#[cfg(test)]
mod tests;

pub use chain::{Source, Stage};
pub use cost::{before_cse, estimated_weight};
pub use emit::{BLOCK_OPERATIONS, RustProgram, RustVariants, WIDTH};
pub use engine::{Backend, Engine, Interpreter};
pub use lower::lower;
pub use tangent::{Curvatures, Tangents};
pub(crate) use tape::Tape;

use crate::sym::Rational;
use std::fmt;
use std::hash::{Hash, Hasher};

/// An SSA value: the result of one instruction, printed `t<n>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Value(u32);

impl Value {
    /// Position of the value in the program's value table.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "t{}", self.0)
    }
}

/// An exact constant together with its nearest `f64`.
///
/// Equality and hashing look at the exact value only.
#[derive(Clone, Debug)]
pub struct Constant {
    exact: Rational,
    value: f64,
}

impl Constant {
    /// The constant `exact`, rounded once to `f64`.
    pub fn new(exact: Rational) -> Constant {
        let value = exact.to_f64();
        Constant { exact, value }
    }

    /// The exact value.
    pub fn exact(&self) -> &Rational {
        &self.exact
    }

    /// The value used in arithmetic.
    pub fn value(&self) -> f64 {
        self.value
    }
}

impl PartialEq for Constant {
    fn eq(&self, other: &Self) -> bool {
        self.exact == other.exact
    }
}

impl Eq for Constant {}

impl Hash for Constant {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.exact.hash(state);
    }
}

/// What an instruction computes, from earlier values.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// Input slot `i`.
    Input(usize),
    /// A constant.
    Constant(Constant),
    /// `a + b`.
    Add(Value, Value),
    /// `a - b`.
    Sub(Value, Value),
    /// `a * b`.
    Mul(Value, Value),
    /// `a / b`.
    Div(Value, Value),
    /// `-a`.
    Neg(Value),
    /// `a.powi(n)`.
    Powi(Value, i32),
    /// `a.sqrt()`.
    Sqrt(Value),
    /// `a.powf(exponent)`.
    Powf(Value, Constant),
    /// `a.sin()`.
    Sin(Value),
    /// `a.cos()`.
    Cos(Value),
    /// `a.tan()`.
    Tan(Value),
    /// `a.exp()`.
    Exp(Value),
    /// `a.ln()`.
    Ln(Value),
    /// `a.asin()`.
    Asin(Value),
    /// `a.acos()`.
    Acos(Value),
    /// `a.atan()`.
    Atan(Value),
    /// `y.atan2(x)`, the angle of the point `(x, y)`.
    Atan2(Value, Value),
    /// `angle.sin_cos()`: the instruction's result is the sine, and it also
    /// defines `cosine`.
    SinCos {
        /// The argument.
        angle: Value,
        /// The second value defined, the cosine.
        cosine: Value,
    },
}

impl Op {
    /// The operation's cost in the module's cost model: 0 for inputs and
    /// constants, 1 for everything else.
    pub fn cost(&self) -> u64 {
        match self {
            Op::Input(_) | Op::Constant(_) => 0,
            _ => 1,
        }
    }

    /// The operation's weight when choosing between forms of one function:
    /// its throughput cost relative to an addition on a current x86-64 core,
    /// roughly. Additions, subtractions, negations and products weigh 1;
    /// divisions, square roots and `powi` (a chain of products) 4; calls of
    /// the elementary functions (`sin_cos` included) 20.
    pub fn weight(&self) -> u64 {
        match self {
            Op::Input(_) | Op::Constant(_) => 0,
            Op::Add(..) | Op::Sub(..) | Op::Mul(..) | Op::Neg(_) => 1,
            Op::Div(..) | Op::Sqrt(_) | Op::Powi(..) => 4,
            Op::Powf(..)
            | Op::Sin(_)
            | Op::Cos(_)
            | Op::Tan(_)
            | Op::Exp(_)
            | Op::Ln(_)
            | Op::Asin(_)
            | Op::Acos(_)
            | Op::Atan(_)
            | Op::Atan2(..)
            | Op::SinCos { .. } => 20,
        }
    }

    /// The operation on the operands `at` maps this one's to (of
    /// [`Op::SinCos`], the angle; its cosine stays).
    pub fn with_operands(&self, at: impl Fn(Value) -> Value) -> Op {
        match *self {
            Op::Input(slot) => Op::Input(slot),
            Op::Constant(ref c) => Op::Constant(c.clone()),
            Op::Add(a, b) => Op::Add(at(a), at(b)),
            Op::Sub(a, b) => Op::Sub(at(a), at(b)),
            Op::Mul(a, b) => Op::Mul(at(a), at(b)),
            Op::Div(a, b) => Op::Div(at(a), at(b)),
            Op::Neg(a) => Op::Neg(at(a)),
            Op::Powi(a, n) => Op::Powi(at(a), n),
            Op::Sqrt(a) => Op::Sqrt(at(a)),
            Op::Powf(a, ref e) => Op::Powf(at(a), e.clone()),
            Op::Sin(a) => Op::Sin(at(a)),
            Op::Cos(a) => Op::Cos(at(a)),
            Op::Tan(a) => Op::Tan(at(a)),
            Op::Exp(a) => Op::Exp(at(a)),
            Op::Ln(a) => Op::Ln(at(a)),
            Op::Asin(a) => Op::Asin(at(a)),
            Op::Acos(a) => Op::Acos(at(a)),
            Op::Atan(a) => Op::Atan(at(a)),
            Op::Atan2(y, x) => Op::Atan2(at(y), at(x)),
            Op::SinCos { angle, cosine } => Op::SinCos {
                angle: at(angle),
                cosine,
            },
        }
    }

    /// The values the operation reads, in order.
    pub fn operands(&self) -> impl Iterator<Item = Value> {
        let (first, second) = match *self {
            Op::Input(_) | Op::Constant(_) => (None, None),
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) | Op::Atan2(a, b) => {
                (Some(a), Some(b))
            }
            Op::Neg(a)
            | Op::Powi(a, _)
            | Op::Sqrt(a)
            | Op::Powf(a, _)
            | Op::Sin(a)
            | Op::Cos(a)
            | Op::Tan(a)
            | Op::Exp(a)
            | Op::Ln(a)
            | Op::Asin(a)
            | Op::Acos(a)
            | Op::Atan(a)
            | Op::SinCos { angle: a, .. } => (Some(a), None),
        };
        first.into_iter().chain(second)
    }
}

/// One SSA instruction.
#[derive(Clone, Debug, PartialEq)]
pub struct Instruction {
    /// What is computed.
    pub op: Op,
    /// The value defined (the sine for [`Op::SinCos`]).
    pub result: Value,
}

/// Operation counts of a program under the module's cost model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OperationCount {
    /// The outputs' expression trees fully expanded (saturating).
    pub before_cse: u64,
    /// The program's instructions.
    pub after_cse: u64,
}

/// Errors of lowering, interpretation and emission.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum IrError {
    /// An output mentions a symbol that is not one of the inputs.
    #[error("symbol `{name}` is used by an output but is not an input")]
    UnboundSymbol {
        /// The symbol's name.
        name: String,
    },
    /// An output id that does not belong to the store.
    #[error("output {output} is not an expression of this store")]
    UnknownExpression {
        /// Position of the output.
        output: usize,
    },
    /// Wrong number of input values or input expressions.
    #[error("the program has {expected} inputs, {found} were given")]
    InputCount {
        /// The program's number of inputs.
        expected: usize,
        /// The number given.
        found: usize,
    },
    /// Wrong number of the inputs' derivatives given to
    /// [`Program::tangents_along`] or [`Program::curvatures_along`].
    #[error("the inputs' derivatives have {expected} entries, {found} were given")]
    DerivativeCount {
        /// The inputs times the directions (times the directions again
        /// for second derivatives).
        expected: usize,
        /// The number given.
        found: usize,
    },
    /// Wrong length of the output buffer.
    #[error("the program has {expected} outputs, the buffer holds {found}")]
    OutputCount {
        /// The program's number of outputs.
        expected: usize,
        /// The buffer's length.
        found: usize,
    },
}

/// Straight-line code computing outputs from inputs; built by [`lower()`].
///
/// Every value is defined before it is read, and every value defined is read
/// by a later instruction or is an output.
#[derive(Clone, Debug)]
pub struct Program {
    /// Names of the input slots (empty for slots the outputs do not use).
    input_names: Vec<String>,
    instructions: Vec<Instruction>,
    outputs: Vec<Value>,
    value_count: usize,
    before_cse: u64,
}

impl Program {
    /// The instructions, in execution order.
    pub fn instructions(&self) -> &[Instruction] {
        &self.instructions
    }

    /// The value of each output.
    pub fn outputs(&self) -> &[Value] {
        &self.outputs
    }

    /// The number of input slots.
    pub fn input_count(&self) -> usize {
        self.input_names.len()
    }

    /// Whether the outputs use input slot `slot`: only such a slot is read
    /// by an [`Op::Input`] (a slot they do not use has no name).
    pub fn reads(&self, slot: usize) -> bool {
        self.input_names
            .get(slot)
            .is_some_and(|name| !name.is_empty())
    }

    /// The number of values the instructions define.
    pub fn value_count(&self) -> usize {
        self.value_count
    }

    /// The sum of the instructions' [`Op::weight`]s (the operation count
    /// treats a division like an addition): what [`estimated_weight`]
    /// estimates on the expression DAG, without lowering, when a derivation
    /// chooses between forms of one function.
    pub fn weighted_cost(&self) -> u64 {
        self.instructions.iter().map(|i| i.op.weight()).sum()
    }

    /// Operation counts before and after common subexpressions are shared.
    pub fn operation_count(&self) -> OperationCount {
        OperationCount {
            before_cse: self.before_cse,
            after_cse: self.instructions.iter().map(|i| i.op.cost()).sum(),
        }
    }
}

impl Program {
    /// The program computing only the outputs at `positions`, in that
    /// order: the instructions they need, in this program's order, values
    /// renumbered, input slot `i` read from slot `slots[i]` of its own
    /// inputs. Each output is computed by the same operations on the same
    /// operands as here, so to the same bits; `before_cse` is the cost of
    /// those outputs as trees ([`before_cse`]).
    ///
    /// Fails with [`IrError::UnboundSymbol`] when a needed input has no
    /// slot, and with [`IrError::OutputCount`] when a position is not an
    /// output.
    pub fn pruned(
        &self,
        positions: &[usize],
        slots: &[Option<usize>],
        before_cse: u64,
    ) -> Result<Program, IrError> {
        if let Some(&position) = positions.iter().find(|&&i| i >= self.outputs.len()) {
            return Err(IrError::OutputCount {
                expected: self.outputs.len(),
                found: position + 1,
            });
        }
        let needed = self.needed_by(positions);
        let inputs = slots.iter().flatten().max().map_or(0, |&last| last + 1);
        let mut input_names = vec![String::new(); inputs];
        let mut renumbered: Vec<Option<Value>> = vec![None; self.value_count];
        let mut fresh = 0u32;
        let mut number = |value: Value, renumbered: &mut Vec<Option<Value>>| {
            let new = Value(fresh);
            fresh += 1;
            renumbered[value.index()] = Some(new);
            new
        };
        let mut instructions = Vec::new();
        for instruction in &self.instructions {
            if !needed[instruction.result.index()] {
                continue;
            }
            let at = |value: Value| renumbered[value.index()].unwrap_or(value);
            let op = match &instruction.op {
                &Op::Input(slot) => {
                    let name = &self.input_names[slot];
                    let Some(new) = slots.get(slot).copied().flatten() else {
                        return Err(IrError::UnboundSymbol { name: name.clone() });
                    };
                    input_names[new] = name.clone();
                    Op::Input(new)
                }
                &Op::SinCos { angle, cosine } => {
                    let angle = at(angle);
                    let result = number(instruction.result, &mut renumbered);
                    let cosine = number(cosine, &mut renumbered);
                    instructions.push(Instruction {
                        op: Op::SinCos { angle, cosine },
                        result,
                    });
                    continue;
                }
                op => op.with_operands(at),
            };
            let result = number(instruction.result, &mut renumbered);
            instructions.push(Instruction { op, result });
        }
        let outputs = positions
            .iter()
            .map(|&i| renumbered[self.outputs[i].index()].unwrap_or(self.outputs[i]))
            .collect();
        Ok(Program {
            input_names,
            instructions,
            outputs,
            value_count: fresh as usize,
            before_cse,
        })
    }

    /// Which values the outputs at `positions` read, directly or not.
    fn needed_by(&self, positions: &[usize]) -> Vec<bool> {
        let mut needed = vec![false; self.value_count];
        for &i in positions {
            needed[self.outputs[i].index()] = true;
        }
        for instruction in self.instructions.iter().rev() {
            let defined = match instruction.op {
                Op::SinCos { cosine, .. } => {
                    needed[instruction.result.index()] || needed[cosine.index()]
                }
                _ => needed[instruction.result.index()],
            };
            if defined {
                needed[instruction.result.index()] = true;
                for operand in instruction.op.operands() {
                    needed[operand.index()] = true;
                }
            }
        }
        needed
    }
}

/// One line per instruction (`t3 = t1 * t0`), then one per output (`out[0] = t3`).
impl fmt::Display for Program {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for instruction in &self.instructions {
            self.write_instruction(f, instruction)?;
        }
        for (i, value) in self.outputs.iter().enumerate() {
            writeln!(f, "out[{i}] = {value}")?;
        }
        Ok(())
    }
}

impl Program {
    fn write_instruction(
        &self,
        f: &mut fmt::Formatter<'_>,
        instruction: &Instruction,
    ) -> fmt::Result {
        let t = instruction.result;
        match &instruction.op {
            Op::Input(slot) => writeln!(f, "{t} = in[{slot}] ({})", self.input_names[*slot]),
            Op::Constant(c) => writeln!(f, "{t} = {}", c.exact),
            Op::Add(a, b) => writeln!(f, "{t} = {a} + {b}"),
            Op::Sub(a, b) => writeln!(f, "{t} = {a} - {b}"),
            Op::Mul(a, b) => writeln!(f, "{t} = {a} * {b}"),
            Op::Div(a, b) => writeln!(f, "{t} = {a} / {b}"),
            Op::Neg(a) => writeln!(f, "{t} = -{a}"),
            Op::Powi(a, n) => writeln!(f, "{t} = powi({a}, {n})"),
            Op::Sqrt(a) => writeln!(f, "{t} = sqrt({a})"),
            Op::Powf(a, e) => writeln!(f, "{t} = powf({a}, {})", e.exact),
            Op::Sin(a) => writeln!(f, "{t} = sin({a})"),
            Op::Cos(a) => writeln!(f, "{t} = cos({a})"),
            Op::Tan(a) => writeln!(f, "{t} = tan({a})"),
            Op::Exp(a) => writeln!(f, "{t} = exp({a})"),
            Op::Ln(a) => writeln!(f, "{t} = ln({a})"),
            Op::Asin(a) => writeln!(f, "{t} = asin({a})"),
            Op::Acos(a) => writeln!(f, "{t} = acos({a})"),
            Op::Atan(a) => writeln!(f, "{t} = atan({a})"),
            Op::Atan2(y, x) => writeln!(f, "{t} = atan2({y}, {x})"),
            Op::SinCos { angle, cosine } => writeln!(f, "{t}, {cosine} = sin_cos({angle})"),
        }
    }
}
