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

use super::{Instruction, IrError, Op, Program};

/// A program's outputs and their derivatives along seeded input slots.
#[derive(Clone, Debug, PartialEq)]
pub struct Tangents {
    /// The outputs, as [`Program::evaluate`] computes them.
    pub values: Vec<f64>,
    /// `d output_i / d input_{seeds[j]}` at `i * seeds.len() + j`.
    pub derivatives: Vec<f64>,
}

impl Program {
    /// The outputs at `inputs` and their derivatives by the input slots
    /// `seeds` (forward differentiation, see the module documentation).
    ///
    /// # Errors
    /// [`IrError::InputCount`] when `inputs` does not match the input
    /// slots; [`IrError::UnboundSymbol`] when a seed is not an input slot.
    pub fn tangents(&self, inputs: &[f64], seeds: &[usize]) -> Result<Tangents, IrError> {
        self.check_inputs(inputs.len())?;
        if let Some(&slot) = seeds.iter().find(|&&slot| slot >= inputs.len()) {
            return Err(IrError::UnboundSymbol {
                name: format!("in[{slot}]"),
            });
        }
        let d = seeds.len();
        let mut values = vec![0.0; self.value_count];
        let mut slopes = vec![0.0; self.value_count * d];
        for instruction in &self.instructions {
            propagate(instruction, inputs, seeds, &mut values, &mut slopes);
        }
        let derivatives = self
            .outputs
            .iter()
            .flat_map(|value| &slopes[value.index() * d..(value.index() + 1) * d])
            .copied()
            .collect();
        let values = self.outputs.iter().map(|v| values[v.index()]).collect();
        Ok(Tangents {
            values,
            derivatives,
        })
    }
}

/// A program's outputs with their first and second derivatives along
/// seeded input slots.
#[derive(Clone, Debug, PartialEq)]
pub struct Curvatures {
    /// The outputs and their first derivatives, as [`Program::tangents`]
    /// computes them.
    pub tangents: Tangents,
    /// `d2 output_i / d input_{seeds[j]} d input_{seeds[l]}` at `(i d + j)
    /// d + l`, `d` the number of seeds.
    pub second: Vec<f64>,
}

impl Program {
    /// The outputs at `inputs` and their first and second derivatives by
    /// the input slots `seeds` (see the module documentation).
    ///
    /// # Errors
    /// As [`Program::tangents`].
    pub fn curvatures(&self, inputs: &[f64], seeds: &[usize]) -> Result<Curvatures, IrError> {
        let tangents = self.tangents(inputs, seeds)?;
        let d = seeds.len();
        let mut values = vec![0.0; self.value_count];
        let mut slopes = vec![0.0; self.value_count * d];
        let mut second = vec![0.0; self.value_count * d * d];
        for instruction in &self.instructions {
            propagate(instruction, inputs, seeds, &mut values, &mut slopes);
            propagate_second(instruction, &values, &slopes, d, &mut second);
        }
        let second = self
            .outputs
            .iter()
            .flat_map(|value| &second[value.index() * d * d..(value.index() + 1) * d * d])
            .copied()
            .collect();
        Ok(Curvatures { tangents, second })
    }
}

/// One instruction's second-order chain rule (see the module
/// documentation), its operands' and its own values and slopes computed.
fn propagate_second(
    instruction: &Instruction,
    values: &[f64],
    slopes: &[f64],
    d: usize,
    second: &mut [f64],
) {
    let at = |value: super::Value| values[value.index()];
    let result = instruction.result.index();
    match instruction.op {
        Op::Input(_) | Op::Constant(_) => {}
        Op::SinCos { angle, cosine } => {
            let (sine, cos) = at(angle).sin_cos();
            let a = angle.index();
            compose(second, slopes, d, result, &[(a, cos)], &[(a, a, -sine)]);
            compose(
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
            let curvature = second_partials(op, at);
            compose(second, slopes, d, result, &partials[..count], &curvature);
        }
    }
}

/// `second[result] = sum_a p_a second[a] + sum_(a, b, p_ab) p_ab
/// slope_a slope_b^T` over ordered pairs of operands.
fn compose(
    second: &mut [f64],
    slopes: &[f64],
    d: usize,
    result: usize,
    partials: &[(usize, f64)],
    curvature: &[(usize, usize, f64)],
) {
    let block = d * d;
    for j in 0..d {
        for l in 0..d {
            let linear: f64 = partials
                .iter()
                .map(|&(a, p)| p * second[a * block + j * d + l])
                .sum();
            let quadratic: f64 = curvature
                .iter()
                .map(|&(a, b, p)| p * slopes[a * d + j] * slopes[b * d + l])
                .sum();
            second[result * block + j * d + l] = linear + quadratic;
        }
    }
}

/// An operation's nonzero second partial derivatives by its operands,
/// `(a, b, d2 op / da db)` over ordered pairs of operand positions (so
/// `a * a` counts its mixed term twice); inputs, constants and
/// [`Op::SinCos`] have none here.
fn second_partials(op: &Op, at: impl Fn(super::Value) -> f64) -> Vec<(usize, usize, f64)> {
    let unary = |a: super::Value, curvature: f64| vec![(a.index(), a.index(), curvature)];
    match *op {
        Op::Input(_)
        | Op::Constant(_)
        | Op::SinCos { .. }
        | Op::Add(..)
        | Op::Sub(..)
        | Op::Neg(_) => Vec::new(),
        Op::Mul(a, b) => vec![(a.index(), b.index(), 1.0), (b.index(), a.index(), 1.0)],
        Op::Div(a, b) => {
            let reciprocal = 1.0 / at(b);
            let quotient = at(a) * reciprocal;
            let mixed = -reciprocal * reciprocal;
            vec![
                (a.index(), b.index(), mixed),
                (b.index(), a.index(), mixed),
                (
                    b.index(),
                    b.index(),
                    2.0 * quotient * reciprocal * reciprocal,
                ),
            ]
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
            vec![
                (y.index(), y.index(), -2.0 * xv * yv / squared),
                (y.index(), x.index(), mixed),
                (x.index(), y.index(), mixed),
                (x.index(), x.index(), 2.0 * xv * yv / squared),
            ]
        }
    }
}

/// Runs one instruction and its chain rule: `values` and `slopes` (`d` per
/// value) hold its operands'.
fn propagate(
    instruction: &Instruction,
    inputs: &[f64],
    seeds: &[usize],
    values: &mut [f64],
    slopes: &mut [f64],
) {
    let d = seeds.len();
    let result = instruction.result.index();
    let at = |value: super::Value| values[value.index()];
    if let Op::Input(slot) = instruction.op {
        values[result] = inputs[slot];
        for (j, &seed) in seeds.iter().enumerate() {
            slopes[result * d + j] = f64::from(u8::from(seed == slot));
        }
        return;
    }
    if let Op::SinCos { angle, cosine } = instruction.op {
        let (sine, cos) = at(angle).sin_cos();
        values[result] = sine;
        values[cosine.index()] = cos;
        combine(slopes, d, result, &[(angle.index(), cos)]);
        combine(slopes, d, cosine.index(), &[(angle.index(), -sine)]);
        return;
    }
    let (value, partials, count) = partials(&instruction.op, at);
    values[result] = value;
    combine(slopes, d, result, &partials[..count]);
}

/// `slopes[result] = sum_k partial_k slopes[operand_k]`.
fn combine(slopes: &mut [f64], d: usize, result: usize, partials: &[(usize, f64)]) {
    for j in 0..d {
        slopes[result * d + j] = partials
            .iter()
            .map(|&(operand, partial)| partial * slopes[operand * d + j])
            .sum();
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
}
