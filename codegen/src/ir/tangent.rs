//! Forward differentiation of a [`Program`] in vector mode (Griewank and
//! Walther, "Evaluating Derivatives", 2nd ed., SIAM 2008, section 3.1).
//!
//! Every value `v` carries, beside its value, its derivatives `dv/ds_j`
//! along `d` seeded input slots `s_j`; each instruction propagates them by
//! its chain rule, `d(a op b) = (d op/da) da + (d op/db) db`, with the
//! operation's partial derivatives at the values the instruction computes
//! (`d sin a = cos a da`, `d(a/b) = (da - (a/b) db)/b`, ...). The outputs'
//! derivatives are exact to round-off: the derivatives of the very
//! operations the program runs, a numeric solve included.
//!
//! [`Program::curvatures`] carries second derivatives too (Griewank and
//! Walther, section 13.2): with `p_a` and `p_ab` an operation's first and
//! second partial derivatives by its operands,
//!
//! ```text
//! d2 v / ds_j ds_l = sum_a p_a d2a/ds_j ds_l + sum_(a, b) p_ab (da/ds_j) (db/ds_l).
//! ```
//!
//! Programs compose: [`Program::tangents_along`] and
//! [`Program::curvatures_along`] start the chain rule from the inputs' own
//! derivatives along `d` directions (an earlier program's outputs', say),
//! so that the outputs' are those of the composite; [`Program::tangents`]
//! and [`Program::curvatures`] are the case of unit slopes on the seeded
//! slots and no second derivatives. Only the directions along which some
//! input the program reads moves are carried (the others' derivatives are
//! zero: the benchmark bicycle's `acceleration_jacobian` reads neither its
//! position's coordinates `x_p`, `y_p` nor their rates, four of its 18
//! arguments), and of the second derivatives the upper triangle is
//! computed, the lower mirrored: a value costs its operation's chain rule `d` times for the first
//! derivatives and `d (d + 1) / 2` times more for the second. Along one
//! direction (a derivative by the one parameter estimated, say) the chain
//! rules are compiled for one: scalar, the same arithmetic as a row's.

use super::{Instruction, IrError, Op, Program};

/// A program's outputs and their derivatives along `d` directions.
#[derive(Clone, Debug, PartialEq)]
pub struct Tangents {
    /// The outputs, as [`Program::evaluate`] computes them.
    pub values: Vec<f64>,
    /// `d output_i / d s_j` at `i * d + j`; for [`Program::tangents`], the
    /// direction `s_j` is the input slot `seeds[j]`.
    pub derivatives: Vec<f64>,
}

/// A program's outputs with their first and second derivatives along `d`
/// directions.
#[derive(Clone, Debug, PartialEq)]
pub struct Curvatures {
    /// The outputs and their first derivatives, as [`Program::tangents`]
    /// computes them.
    pub tangents: Tangents,
    /// `d2 output_i / d s_j d s_l` at `(i d + j) d + l`.
    pub second: Vec<f64>,
}

impl Program {
    /// The outputs at `inputs` and their derivatives by the input slots
    /// `seeds` (forward differentiation, see the module documentation):
    /// [`Program::tangents_along`] with unit slopes on the seeded slots.
    ///
    /// # Errors
    /// [`IrError::InputCount`] when `inputs` does not match the input
    /// slots; [`IrError::UnboundSymbol`] when a seed is not an input slot.
    pub fn tangents(&self, inputs: &[f64], seeds: &[usize]) -> Result<Tangents, IrError> {
        let slopes = unit_slopes(inputs.len(), seeds)?;
        self.tangents_along(inputs, &slopes, seeds.len())
    }

    /// The outputs at `inputs` and their derivatives along `d` directions,
    /// the inputs' own derivatives given, `input_slopes[i * d + j] = d
    /// input_i / d s_j` (the chain rule of the module documentation, from
    /// the inputs on).
    ///
    /// # Errors
    /// [`IrError::InputCount`] when `inputs` does not match the input
    /// slots; [`IrError::DerivativeCount`] when `input_slopes` does not
    /// hold `inputs.len() * d` entries.
    pub fn tangents_along(
        &self,
        inputs: &[f64],
        input_slopes: &[f64],
        d: usize,
    ) -> Result<Tangents, IrError> {
        self.along(inputs, input_slopes, None, d)
            .map(|curvatures| curvatures.tangents)
    }

    /// The outputs at `inputs` and their first and second derivatives by
    /// the input slots `seeds` (see the module documentation):
    /// [`Program::curvatures_along`] with unit slopes on the seeded slots
    /// and no second derivatives of the inputs.
    ///
    /// # Errors
    /// As [`Program::tangents`].
    pub fn curvatures(&self, inputs: &[f64], seeds: &[usize]) -> Result<Curvatures, IrError> {
        let slopes = unit_slopes(inputs.len(), seeds)?;
        let second = vec![0.0; slopes.len() * seeds.len()];
        self.curvatures_along(inputs, &slopes, &second, seeds.len())
    }

    /// The outputs at `inputs` and their first and second derivatives along
    /// `d` directions, the inputs' own given: `input_slopes` as for
    /// [`Program::tangents_along`], and `input_second[(i d + j) d + l] =
    /// d2 input_i / d s_j d s_l`, each input's `d x d` block symmetric (of
    /// which the upper triangle is read).
    ///
    /// # Errors
    /// As [`Program::tangents_along`], and [`IrError::DerivativeCount`]
    /// when `input_second` does not hold `inputs.len() * d * d` entries.
    pub fn curvatures_along(
        &self,
        inputs: &[f64],
        input_slopes: &[f64],
        input_second: &[f64],
        d: usize,
    ) -> Result<Curvatures, IrError> {
        self.along(inputs, input_slopes, Some(input_second), d)
    }

    /// [`Program::curvatures_along`], the second derivatives carried when
    /// `input_second` is given (and left empty otherwise), along the
    /// directions in which some input moves only: the others' derivatives
    /// are zero.
    fn along(
        &self,
        inputs: &[f64],
        input_slopes: &[f64],
        input_second: Option<&[f64]>,
        d: usize,
    ) -> Result<Curvatures, IrError> {
        self.check_inputs(inputs.len())?;
        check_derivatives(input_slopes.len(), inputs.len() * d)?;
        if let Some(second) = input_second {
            check_derivatives(second.len(), inputs.len() * d * d)?;
        }
        let moving = moving_directions(input_slopes, input_second, d, |slot| self.reads(slot));
        if moving.len() == d {
            return Ok(self.forward_along(inputs, input_slopes, input_second, d));
        }
        let slopes = restricted(input_slopes, d, &moving, 1);
        let second = input_second.map(|second| restricted(second, d, &moving, 2));
        let carried = self.forward_along(inputs, &slopes, second.as_deref(), moving.len());
        let rows = self.outputs.len();
        Ok(Curvatures {
            tangents: Tangents {
                values: carried.tangents.values,
                derivatives: expanded(&carried.tangents.derivatives, rows, d, &moving, 1),
            },
            second: match second {
                Some(_) => expanded(&carried.second, rows, d, &moving, 2),
                None => Vec::new(),
            },
        })
    }

    /// [`Program::forward`] along `d` directions, with scalar chain rules
    /// where `d` is one (a derivative by one parameter, say).
    fn forward_along(
        &self,
        inputs: &[f64],
        input_slopes: &[f64],
        input_second: Option<&[f64]>,
        d: usize,
    ) -> Curvatures {
        match d {
            1 => self.forward(inputs, input_slopes, input_second, One),
            _ => self.forward(inputs, input_slopes, input_second, d),
        }
    }

    /// Runs the instructions with their chain rules along `d` directions,
    /// the inputs' derivatives given (second derivatives when
    /// `input_second` is), and gathers the outputs'.
    fn forward(
        &self,
        inputs: &[f64],
        input_slopes: &[f64],
        input_second: Option<&[f64]>,
        width: impl Width,
    ) -> Curvatures {
        let d = width.get();
        let mut values = vec![0.0; self.value_count];
        let mut slopes = vec![0.0; self.value_count * d];
        let mut second = vec![0.0; input_second.map_or(0, |_| self.value_count * d * d)];
        for instruction in &self.instructions {
            propagate(
                instruction,
                inputs,
                input_slopes,
                width,
                &mut values,
                &mut slopes,
            );
            if let Some(given) = input_second {
                propagate_second(instruction, given, &values, &slopes, width, &mut second);
            }
        }
        let gathered = |per_value: &[f64], width: usize| -> Vec<f64> {
            self.outputs
                .iter()
                .flat_map(|value| &per_value[value.index() * width..(value.index() + 1) * width])
                .copied()
                .collect()
        };
        let second = if input_second.is_some() {
            gathered(&second, d * d)
        } else {
            Vec::new()
        };
        Curvatures {
            tangents: Tangents {
                values: self.outputs.iter().map(|v| values[v.index()]).collect(),
                derivatives: gathered(&slopes, d),
            },
            second,
        }
    }
}

/// `inputs x seeds` slopes, `1` where the input is the seed's slot.
fn unit_slopes(inputs: usize, seeds: &[usize]) -> Result<Vec<f64>, IrError> {
    if let Some(&slot) = seeds.iter().find(|&&slot| slot >= inputs) {
        return Err(IrError::UnboundSymbol {
            name: format!("in[{slot}]"),
        });
    }
    Ok((0..inputs)
        .flat_map(|input| {
            seeds
                .iter()
                .map(move |&seed| f64::from(u8::from(seed == input)))
        })
        .collect())
}

/// `Err` unless `found`, the number of the inputs' derivatives given, is
/// `expected`.
fn check_derivatives(found: usize, expected: usize) -> Result<(), IrError> {
    if found == expected {
        Ok(())
    } else {
        Err(IrError::DerivativeCount { expected, found })
    }
}

/// The directions, among `d`, along which some input the program `reads`
/// has a nonzero slope or second derivative, in order: along the others
/// every value's derivatives are zero.
fn moving_directions(
    slopes: &[f64],
    second: Option<&[f64]>,
    d: usize,
    reads: impl Fn(usize) -> bool,
) -> Vec<usize> {
    let mut moving = vec![false; d];
    for (k, _) in slopes
        .iter()
        .enumerate()
        .filter(|(k, slope)| **slope != 0.0 && reads(k / d))
    {
        moving[k % d] = true;
    }
    for (k, _) in second
        .unwrap_or_default()
        .iter()
        .enumerate()
        .filter(|(k, entry)| **entry != 0.0 && reads(k / (d * d)))
    {
        moving[k % d] = true;
        moving[k / d % d] = true;
    }
    (0..d).filter(|&j| moving[j]).collect()
}

/// Each row of `per_value` (`d^order` entries: slopes, `order` 1, or
/// second derivatives, `order` 2) at the directions `moving` only.
fn restricted(per_value: &[f64], d: usize, moving: &[usize], order: u32) -> Vec<f64> {
    let width = d.pow(order);
    per_value
        .chunks_exact(width)
        .flat_map(|row| entries(moving, order).map(move |(j, l)| row[j * d.pow(order - 1) + l]))
        .collect()
}

/// The inverse of [`restricted`]: `rows` rows along the directions
/// `moving` spread to all `d`, zero along the others.
fn expanded(carried: &[f64], rows: usize, d: usize, moving: &[usize], order: u32) -> Vec<f64> {
    let mut spread = vec![0.0; rows * d.pow(order)];
    if moving.is_empty() {
        return spread;
    }
    let width = moving.len().pow(order);
    for (row, target) in carried
        .chunks_exact(width)
        .zip(spread.chunks_exact_mut(d.pow(order)))
    {
        for (&entry, (j, l)) in row.iter().zip(entries(moving, order)) {
            target[j * d.pow(order - 1) + l] = entry;
        }
    }
    spread
}

/// The positions `(j, l)` of a row's entries along `moving`: `(0, j)` for
/// slopes (`order` 1), every pair for second derivatives (`order` 2).
fn entries(moving: &[usize], order: u32) -> impl Iterator<Item = (usize, usize)> + '_ {
    let rows: &[usize] = if order == 2 { moving } else { &[0] };
    rows.iter()
        .flat_map(move |&j| moving.iter().map(move |&l| (j, l)))
}

/// One instruction's second-order chain rule (see the module
/// documentation), its operands' and its own values and slopes computed;
/// an input's second derivatives are `given`'s.
fn propagate_second(
    instruction: &Instruction,
    given: &[f64],
    values: &[f64],
    slopes: &[f64],
    d: impl Width,
    second: &mut [f64],
) {
    let at = |value: super::Value| values[value.index()];
    let result = instruction.result.index();
    let block = d.get() * d.get();
    match instruction.op {
        Op::Input(slot) => second[result * block..(result + 1) * block]
            .copy_from_slice(&given[slot * block..(slot + 1) * block]),
        Op::Constant(_) => {}
        Op::SinCos { angle, cosine } => {
            let (sine, cos) = at(angle).sin_cos();
            let a = angle.index();
            chain_second(second, slopes, d, result, &[(a, cos)], &[(a, a, -sine)]);
            chain_second(
                second,
                slopes,
                d,
                cosine.index(),
                &[(a, -sine)],
                &[(a, a, -cos)],
            );
        }
        ref op => {
            let (_, partials, count) = partials(op, at);
            let (curvature, pairs) = second_partials(op, at);
            chain_second(
                second,
                slopes,
                d,
                result,
                &partials[..count],
                &curvature[..pairs],
            );
        }
    }
}

/// `second[result] = sum_a p_a second[a] + sum_(a, b, p_ab) p_ab
/// slope_a slope_b^T` over ordered pairs of operands: the upper triangle
/// computed, the lower its mirror.
pub(super) fn chain_second(
    second: &mut [f64],
    slopes: &[f64],
    d: impl Width,
    result: usize,
    partials: &[(usize, f64)],
    curvature: &[(usize, usize, f64)],
) {
    let d = d.get();
    let block = d * d;
    for j in 0..d {
        for l in j..d {
            let linear: f64 = partials
                .iter()
                .map(|&(a, p)| p * second[a * block + j * d + l])
                .sum();
            let quadratic: f64 = curvature
                .iter()
                .map(|&(a, b, p)| p * slopes[a * d + j] * slopes[b * d + l])
                .sum();
            second[result * block + j * d + l] = linear + quadratic;
            second[result * block + l * d + j] = linear + quadratic;
        }
    }
}

/// The number of directions derivatives are carried along: a `usize`, or
/// [`One`], known when compiled, so that the chain rules of one direction
/// are scalar, without the loops and bounds checks of a row.
pub(super) trait Width: Copy {
    /// The number.
    fn get(self) -> usize;
}

impl Width for usize {
    fn get(self) -> usize {
        self
    }
}

/// One direction.
#[derive(Clone, Copy)]
pub(super) struct One;

impl Width for One {
    fn get(self) -> usize {
        1
    }
}

/// An operation's nonzero second partial derivatives by its operands,
/// `(a, b, d2 op / da db)` over ordered pairs of operand positions (so
/// `a * a` counts its mixed term twice), the first `count` of
/// [`SecondPartials`]'s; inputs, constants and [`Op::SinCos`] have none
/// here.
fn second_partials(op: &Op, at: impl Fn(super::Value) -> f64) -> (SecondPartials, usize) {
    let none = (0, 0, 0.0);
    let unary = |a: super::Value, curvature: f64| {
        ([(a.index(), a.index(), curvature), none, none, none], 1)
    };
    match *op {
        Op::Input(_)
        | Op::Constant(_)
        | Op::SinCos { .. }
        | Op::Add(..)
        | Op::Sub(..)
        | Op::Neg(_) => ([none; 4], 0),
        Op::Mul(a, b) => (
            [
                (a.index(), b.index(), 1.0),
                (b.index(), a.index(), 1.0),
                none,
                none,
            ],
            2,
        ),
        Op::Div(a, b) => {
            let reciprocal = 1.0 / at(b);
            let quotient = at(a) * reciprocal;
            let mixed = -reciprocal * reciprocal;
            (
                [
                    (a.index(), b.index(), mixed),
                    (b.index(), a.index(), mixed),
                    (
                        b.index(),
                        b.index(),
                        2.0 * quotient * reciprocal * reciprocal,
                    ),
                    none,
                ],
                3,
            )
        }
        Op::Powi(a, n) => {
            let curvature = if n == 0 || n == 1 {
                0.0
            } else {
                f64::from(n) * f64::from(n - 1) * at(a).powi(n - 2)
            };
            unary(a, curvature)
        }
        Op::Sqrt(a) => unary(a, -0.25 / (at(a) * at(a).sqrt())),
        Op::Powf(a, ref e) => {
            let exponent = e.value();
            unary(a, exponent * (exponent - 1.0) * at(a).powf(exponent - 2.0))
        }
        Op::Sin(a) => unary(a, -at(a).sin()),
        Op::Cos(a) => unary(a, -at(a).cos()),
        Op::Tan(a) => {
            let tangent = at(a).tan();
            unary(a, 2.0 * tangent * (1.0 + tangent * tangent))
        }
        Op::Exp(a) => unary(a, at(a).exp()),
        Op::Ln(a) => unary(a, -1.0 / (at(a) * at(a))),
        Op::Asin(a) => unary(a, at(a) / (1.0 - at(a) * at(a)).powf(1.5)),
        Op::Acos(a) => unary(a, -at(a) / (1.0 - at(a) * at(a)).powf(1.5)),
        Op::Atan(a) => unary(a, -2.0 * at(a) / (1.0 + at(a) * at(a)).powi(2)),
        Op::Atan2(y, x) => {
            let (yv, xv) = (at(y), at(x));
            let squared = (xv * xv + yv * yv).powi(2);
            let mixed = (yv * yv - xv * xv) / squared;
            (
                [
                    (y.index(), y.index(), -2.0 * xv * yv / squared),
                    (y.index(), x.index(), mixed),
                    (x.index(), y.index(), mixed),
                    (x.index(), x.index(), 2.0 * xv * yv / squared),
                ],
                4,
            )
        }
    }
}

/// An operation's second partial derivatives by ordered pairs of its
/// operands, `(a, b, d2 op / da db)`; see [`second_partials`].
type SecondPartials = [(usize, usize, f64); 4];

/// Runs one instruction and its chain rule: `values` and `slopes` (`d` per
/// value) hold its operands'; an input's slopes are `input_slopes`'.
fn propagate(
    instruction: &Instruction,
    inputs: &[f64],
    input_slopes: &[f64],
    width: impl Width,
    values: &mut [f64],
    slopes: &mut [f64],
) {
    let d = width.get();
    let result = instruction.result.index();
    let at = |value: super::Value| values[value.index()];
    if let Op::Input(slot) = instruction.op {
        values[result] = inputs[slot];
        slopes[result * d..(result + 1) * d]
            .copy_from_slice(&input_slopes[slot * d..(slot + 1) * d]);
        return;
    }
    if let Op::SinCos { angle, cosine } = instruction.op {
        let (sine, cos) = at(angle).sin_cos();
        values[result] = sine;
        values[cosine.index()] = cos;
        chain_slopes(slopes, width, result, &[(angle.index(), cos)]);
        chain_slopes(slopes, width, cosine.index(), &[(angle.index(), -sine)]);
        return;
    }
    let (value, partials, count) = partials(&instruction.op, at);
    values[result] = value;
    chain_slopes(slopes, width, result, &partials[..count]);
}

/// `slopes[result] = sum_k partial_k slopes[operand_k]`, the sum taken in
/// the operands' order from `-0.0`, as `Iterator::sum` takes it. The one
/// and two operands of an operation are written out, so that the loop
/// over the `d` directions runs on slices, without bounds checks.
pub(super) fn chain_slopes(
    slopes: &mut [f64],
    d: impl Width,
    result: usize,
    partials: &[(usize, f64)],
) {
    let d = d.get();
    let (before, rest) = slopes.split_at_mut(result * d);
    let (out, after) = rest.split_at_mut(d);
    // an operand's row: an operand is a value other than the result
    let row = |operand: usize| match operand < result {
        true => &before[operand * d..(operand + 1) * d],
        false => &after[(operand - result - 1) * d..(operand - result) * d],
    };
    match *partials {
        [] => out.fill(-0.0),
        [(a, pa)] => {
            for (slope, sa) in out.iter_mut().zip(row(a)) {
                *slope = pa * sa;
            }
        }
        [(a, pa), (b, pb)] => {
            for ((slope, sa), sb) in out.iter_mut().zip(row(a)).zip(row(b)) {
                *slope = pa * sa + pb * sb;
            }
        }
        _ => {
            for (j, slope) in out.iter_mut().enumerate() {
                *slope = (partials.iter())
                    .map(|&(operand, partial)| partial * row(operand)[j])
                    .sum();
            }
        }
    }
}

/// An operation's partial derivatives by its operands: (operand index,
/// derivative), the first `count` of [`Partials`]'s pairs.
type Partials = [(usize, f64); 2];

/// An operation's value, its partial derivatives by its operands and their
/// number; inputs and [`Op::SinCos`] are handled by [`propagate`].
fn partials(op: &Op, at: impl Fn(super::Value) -> f64) -> (f64, Partials, usize) {
    let unary =
        |a: super::Value, value: f64, slope: f64| (value, [(a.index(), slope), (0, 0.0)], 1);
    let binary =
        |value: f64, first: (usize, f64), second: (usize, f64)| (value, [first, second], 2);
    match *op {
        Op::Input(_) | Op::SinCos { .. } => (f64::NAN, [(0, 0.0); 2], 0),
        Op::Constant(ref c) => (c.value(), [(0, 0.0); 2], 0),
        Op::Add(a, b) => binary(at(a) + at(b), (a.index(), 1.0), (b.index(), 1.0)),
        Op::Sub(a, b) => binary(at(a) - at(b), (a.index(), 1.0), (b.index(), -1.0)),
        Op::Mul(a, b) => binary(at(a) * at(b), (a.index(), at(b)), (b.index(), at(a))),
        Op::Div(a, b) => {
            let quotient = at(a) / at(b);
            let reciprocal = 1.0 / at(b);
            binary(
                quotient,
                (a.index(), reciprocal),
                (b.index(), -quotient * reciprocal),
            )
        }
        Op::Neg(a) => unary(a, -at(a), -1.0),
        Op::Powi(a, n) => {
            let slope = if n == 0 {
                0.0
            } else {
                f64::from(n) * at(a).powi(n - 1)
            };
            unary(a, at(a).powi(n), slope)
        }
        Op::Sqrt(a) => {
            let root = at(a).sqrt();
            unary(a, root, 0.5 / root)
        }
        Op::Powf(a, ref e) => {
            let exponent = e.value();
            unary(
                a,
                at(a).powf(exponent),
                exponent * at(a).powf(exponent - 1.0),
            )
        }
        Op::Sin(a) => unary(a, at(a).sin(), at(a).cos()),
        Op::Cos(a) => unary(a, at(a).cos(), -at(a).sin()),
        Op::Tan(a) => {
            let tangent = at(a).tan();
            unary(a, tangent, 1.0 + tangent * tangent)
        }
        Op::Exp(a) => {
            let exponential = at(a).exp();
            unary(a, exponential, exponential)
        }
        Op::Ln(a) => unary(a, at(a).ln(), 1.0 / at(a)),
        Op::Asin(a) => unary(a, at(a).asin(), 1.0 / (1.0 - at(a) * at(a)).sqrt()),
        Op::Acos(a) => unary(a, at(a).acos(), -1.0 / (1.0 - at(a) * at(a)).sqrt()),
        Op::Atan(a) => unary(a, at(a).atan(), 1.0 / (1.0 + at(a) * at(a))),
        Op::Atan2(y, x) => {
            let (yv, xv) = (at(y), at(x));
            let radius = xv * xv + yv * yv;
            binary(
                yv.atan2(xv),
                (y.index(), xv / radius),
                (x.index(), -yv / radius),
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::ir::{Program, lower};
    use crate::sym::{Function, Rational, Store, SymbolKind};

    /// A program of `x`, `y` whose outputs read them through each
    /// elementary function, powers, quotients and `atan2`.
    fn every_operation() -> Program {
        let mut s = Store::new();
        let symbols = [
            s.declare("x", SymbolKind::Coordinate),
            s.declare("y", SymbolKind::Coordinate),
        ];
        let [x, y] = symbols.map(|symbol| s.symbol(symbol));
        let product = s.mul2(x, y);
        let mut outputs: Vec<_> = [
            Function::Sin,
            Function::Cos,
            Function::Tan,
            Function::Exp,
            Function::Ln,
            Function::Asin,
            Function::Acos,
            Function::Atan,
        ]
        .into_iter()
        .map(|function| s.apply(function, product).expect("applies"))
        .collect();
        let exponents = [(5, 1), (1, 2), (-1, 2), (2, 3), (-3, 1)];
        for (numerator, denominator) in exponents {
            let exponent = Rational::new(numerator, denominator).expect("a rational");
            outputs.push(s.pow(product, exponent).expect("a power"));
        }
        outputs.push(s.div(x, y).expect("a quotient"));
        outputs.push(s.atan2(y, x).expect("an angle"));
        let sum = s.add2(x, y);
        let sine = s.apply(Function::Sin, sum).expect("applies");
        let cosine = s.apply(Function::Cos, sum).expect("applies");
        outputs.push(s.mul2(sine, cosine));
        lower(&s, &symbols, &outputs).expect("lowers")
    }

    /// A slot the outputs do not use is not read, and no value moves along
    /// a direction seeded there: its derivatives are zero, the others'
    /// those of the slots read alone, bit for bit.
    #[test]
    fn a_direction_on_a_slot_not_read_is_zero() {
        let mut s = Store::new();
        let symbols = ["x", "unused", "y"].map(|name| s.declare(name, SymbolKind::Coordinate));
        let [x, y] = [symbols[0], symbols[2]].map(|symbol| s.symbol(symbol));
        let product = s.mul2(x, y);
        let sine = s.apply(Function::Sin, product).expect("applies");
        let outputs = [sine, s.div(x, y).expect("a quotient")];
        let program = lower(&s, &symbols, &outputs).expect("lowers");
        let read: Vec<bool> = (0..3)
            .map(|slot| {
                (program.instructions().iter()).any(
                    |instruction| matches!(instruction.op, crate::ir::Op::Input(k) if k == slot),
                )
            })
            .collect();
        assert_eq!(read, [true, false, true]);
        assert_eq!(
            read,
            (0..3).map(|slot| program.reads(slot)).collect::<Vec<_>>()
        );
        let point = [0.7, 5.0, 0.4];
        let all = program.curvatures(&point, &[0, 1, 2]).expect("evaluates");
        let read_alone = program.curvatures(&point, &[0, 2]).expect("evaluates");
        for (i, row) in all.tangents.derivatives.chunks(3).enumerate() {
            assert_eq!(row[1].to_bits(), 0.0f64.to_bits());
            let alone = &read_alone.tangents.derivatives[2 * i..2 * i + 2];
            assert_eq!(
                [row[0], row[2]].map(f64::to_bits),
                [alone[0], alone[1]].map(f64::to_bits)
            );
        }
        for (i, block) in all.second.chunks(9).enumerate() {
            let alone = &read_alone.second[4 * i..4 * i + 4];
            assert!(
                block[3..6]
                    .iter()
                    .chain(block.iter().skip(1).step_by(3))
                    .all(|v| v.to_bits() == 0)
            );
            let read_entries = [block[0], block[2], block[6], block[8]];
            assert_eq!(
                read_entries.map(f64::to_bits),
                [alone[0], alone[1], alone[2], alone[3]].map(f64::to_bits)
            );
        }
    }

    /// Every operation's chain rule against central differences of the
    /// program's own values.
    #[test]
    fn the_tangents_agree_with_central_differences() {
        let program = every_operation();
        let point = [0.7, 0.4];
        let tangents = program.tangents(&point, &[0, 1]).expect("evaluates");
        assert_eq!(
            tangents.values,
            program.evaluate_vec(&point).expect("evaluates")
        );
        for seed in 0..2 {
            let step = 1e-6;
            let shifted = |by: f64| {
                let mut at = point;
                at[seed] += by;
                program.evaluate_vec(&at).expect("evaluates")
            };
            let (plus, minus) = (shifted(step), shifted(-step));
            for (i, (a, b)) in plus.iter().zip(&minus).enumerate() {
                let numeric = (a - b) / (2.0 * step);
                let exact = tangents.derivatives[2 * i + seed];
                assert!(
                    (exact - numeric).abs() <= 1e-7 * (1.0 + numeric.abs()),
                    "output {i} by {seed}: {exact} vs {numeric}"
                );
            }
        }
    }

    /// Every operation's second-order chain rule against central
    /// differences of the exact first derivatives.
    /// Along one direction the chain rules are scalar ([`super::One`]):
    /// each direction's derivatives are those the rows of two directions
    /// carry for it, bit for bit, first and second.
    #[test]
    fn one_direction_is_each_column_of_two() {
        let program = every_operation();
        let point = [0.7, 0.4];
        let both = program.curvatures(&point, &[0, 1]).expect("evaluates");
        let bits = |values: &[f64]| values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        for seed in 0..2 {
            let alone = program.curvatures(&point, &[seed]).expect("evaluates");
            let column: Vec<f64> = (both.tangents.derivatives.iter())
                .skip(seed)
                .step_by(2)
                .copied()
                .collect();
            assert_eq!(bits(&alone.tangents.derivatives), bits(&column));
            let diagonal: Vec<f64> = (both.second.iter())
                .skip(3 * seed)
                .step_by(4)
                .copied()
                .collect();
            assert_eq!(bits(&alone.second), bits(&diagonal));
            let tangents = program.tangents(&point, &[seed]).expect("evaluates");
            assert_eq!(tangents, alone.tangents);
        }
    }

    #[test]
    fn the_curvatures_agree_with_central_differences_of_the_tangents() {
        let program = every_operation();
        let point = [0.7, 0.4];
        let curvatures = program.curvatures(&point, &[0, 1]).expect("evaluates");
        assert_eq!(
            curvatures.tangents,
            program.tangents(&point, &[0, 1]).expect("evaluates")
        );
        for seed in 0..2 {
            let step = 1e-6;
            let shifted = |by: f64| {
                let mut at = point;
                at[seed] += by;
                program
                    .tangents(&at, &[0, 1])
                    .expect("evaluates")
                    .derivatives
            };
            let (plus, minus) = (shifted(step), shifted(-step));
            for (k, (a, b)) in plus.iter().zip(&minus).enumerate() {
                let numeric = (a - b) / (2.0 * step);
                let exact = curvatures.second[2 * k + seed];
                assert!(
                    (exact - numeric).abs() <= 1e-6 * (1.0 + numeric.abs()),
                    "output {} by ({}, {seed}): {exact} vs {numeric}",
                    k / 2,
                    k % 2
                );
            }
        }
    }

    /// `inner(x, y) = (x y, sin x + y)` then `outer(a, b) = (a / b,
    /// atan2(a, b), exp(a) b)`, composed through the `*_along` forms, against
    /// the composite lowered as one program; a third direction along which
    /// no input moves keeps zero derivatives.
    #[test]
    fn programs_composed_along_their_derivatives_are_the_composite() {
        let mut s = Store::new();
        let [x, y, a, b] = ["x", "y", "a", "b"].map(|name| s.declare(name, SymbolKind::Coordinate));
        let [xv, yv, av, bv] = [x, y, a, b].map(|symbol| s.symbol(symbol));
        let product = s.mul2(xv, yv);
        let sine = s.apply(Function::Sin, xv).expect("applies");
        let sum = s.add2(sine, yv);
        let inner = lower(&s, &[x, y], &[product, sum]).expect("lowers");
        let outer_of = |s: &mut Store, a, b| {
            let quotient = s.div(a, b).expect("a quotient");
            let angle = s.atan2(a, b).expect("an angle");
            let exponential = s.apply(Function::Exp, a).expect("applies");
            [quotient, angle, s.mul2(exponential, b)]
        };
        let outer = outer_of(&mut s, av, bv);
        let outer = lower(&s, &[a, b], &outer).expect("lowers");
        let composite = outer_of(&mut s, product, sum);
        let composite = lower(&s, &[x, y], &composite).expect("lowers");
        let point = [0.7, -0.4];
        let expected = composite.curvatures(&point, &[0, 1]).expect("evaluates");
        let slopes = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        let first = inner
            .curvatures_along(&point, &slopes, &[0.0; 18], 3)
            .expect("evaluates");
        let found = outer
            .curvatures_along(
                &first.tangents.values,
                &first.tangents.derivatives,
                &first.second,
                3,
            )
            .expect("evaluates");
        let close = |found: f64, expected: f64| {
            assert!(
                (found - expected).abs() <= 1e-13 * (1.0 + expected.abs()),
                "{found} vs {expected}"
            );
        };
        for i in 0..3 {
            close(found.tangents.values[i], expected.tangents.values[i]);
            for j in 0..3 {
                let slope = found.tangents.derivatives[3 * i + j];
                close(
                    slope,
                    if j < 2 {
                        expected.tangents.derivatives[2 * i + j]
                    } else {
                        0.0
                    },
                );
                for l in 0..3 {
                    let second = found.second[9 * i + 3 * j + l];
                    let exact = if j < 2 && l < 2 {
                        expected.second[4 * i + 2 * j + l]
                    } else {
                        0.0
                    };
                    close(second, exact);
                }
            }
        }
        let along = inner.tangents_along(&point, &slopes, 3).expect("evaluates");
        assert_eq!(along, first.tangents);
    }
}
