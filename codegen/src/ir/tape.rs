//! Values with their derivatives along `d` directions, for composing
//! programs with the arithmetic between them (forward differentiation in
//! vector mode, Griewank and Walther, "Evaluating Derivatives", 2nd ed.,
//! SIAM 2008, sections 3.1 and 13.2).
//!
//! A [`Tape`] holds entries, each a value, its `d` slopes and, when asked,
//! its `d x d` second derivatives. Entries are seeded (moving along one
//! direction each), constant, the outputs of a [`Program`] at earlier
//! entries ([`Program::tangents_along`], [`Program::curvatures_along`]), or
//! sums of earlier entries and of their products, by the chain rules of
//! [`super::tangent`].

use super::tangent::{chain_second, chain_slopes};
use super::{IrError, Program};
use std::ops::Range;

/// Entries with their derivatives along `d` directions (see the module
/// documentation).
#[derive(Clone, Debug)]
pub(crate) struct Tape {
    directions: usize,
    values: Vec<f64>,
    slopes: Vec<f64>,
    /// The second derivatives, `d x d` an entry, when carried.
    second: Option<Vec<f64>>,
}

impl Tape {
    /// An empty tape along `directions` directions, carrying second
    /// derivatives when `second`.
    pub(crate) fn new(directions: usize, second: bool) -> Tape {
        Tape {
            directions,
            values: Vec::new(),
            slopes: Vec::new(),
            second: second.then(Vec::new),
        }
    }

    /// The number of directions.
    pub(crate) fn directions(&self) -> usize {
        self.directions
    }

    /// The value of each entry of `entries`.
    pub(crate) fn values(&self, entries: &[usize]) -> Vec<f64> {
        entries.iter().map(|&i| self.values[i]).collect()
    }

    /// The slopes of `entry`, `d` of them.
    pub(crate) fn slopes(&self, entry: usize) -> &[f64] {
        let d = self.directions;
        &self.slopes[entry * d..(entry + 1) * d]
    }

    /// The second derivatives of `entry`, `d x d` row-major (empty unless
    /// carried).
    pub(crate) fn second(&self, entry: usize) -> &[f64] {
        let block = self.directions * self.directions;
        self.second
            .as_ref()
            .map_or(&[], |second| &second[entry * block..(entry + 1) * block])
    }

    /// Appends `values`, the `i`-th moving along the direction `first + i`
    /// with slope 1 (not at all beyond the last direction).
    pub(crate) fn seeded(&mut self, values: &[f64], first: usize) -> Range<usize> {
        let entries = self.constants(values);
        let d = self.directions;
        for (offset, entry) in entries.clone().enumerate() {
            if first + offset < d {
                self.slopes[entry * d + first + offset] = 1.0;
            }
        }
        entries
    }

    /// Appends `values`, which do not move.
    pub(crate) fn constants(&mut self, values: &[f64]) -> Range<usize> {
        let start = self.values.len();
        for &value in values {
            self.push(value);
        }
        start..self.values.len()
    }

    /// Appends `sum linear + sum_(c, a, b) c a b` of earlier entries.
    pub(crate) fn combination(
        &mut self,
        linear: &[usize],
        products: &[(f64, usize, usize)],
    ) -> usize {
        let at = |entry: usize| self.values[entry];
        let value = products
            .iter()
            .map(|&(c, a, b)| c * at(a) * at(b))
            .sum::<f64>()
            + linear.iter().map(|&a| at(a)).sum::<f64>();
        let partials: Vec<(usize, f64)> = linear
            .iter()
            .map(|&a| (a, 1.0))
            .chain(
                products
                    .iter()
                    .flat_map(|&(c, a, b)| [(a, c * at(b)), (b, c * at(a))]),
            )
            .collect();
        let curvature: Vec<(usize, usize, f64)> = products
            .iter()
            .flat_map(|&(c, a, b)| [(a, b, c), (b, a, c)])
            .collect();
        self.push_chained(value, &partials, &curvature)
    }

    /// Appends `(sin a, cos a)` of the entry `angle`.
    pub(crate) fn sin_cos(&mut self, angle: usize) -> (usize, usize) {
        let (sine, cosine) = self.values[angle].sin_cos();
        let sin = self.push_chained(sine, &[(angle, cosine)], &[(angle, angle, -sine)]);
        let cos = self.push_chained(cosine, &[(angle, -sine)], &[(angle, angle, -cosine)]);
        (sin, cos)
    }

    /// Appends the outputs of `program` at the entries `inputs`, then the
    /// constants `fixed` (a program's parameters, say).
    ///
    /// # Errors
    /// As [`Program::curvatures_along`].
    pub(crate) fn apply(
        &mut self,
        program: &Program,
        inputs: &[usize],
        fixed: &[f64],
    ) -> Result<Range<usize>, IrError> {
        let d = self.directions;
        let count = inputs.len() + fixed.len();
        let values: Vec<f64> = self
            .values(inputs)
            .into_iter()
            .chain(fixed.iter().copied())
            .collect();
        let mut slopes: Vec<f64> = inputs
            .iter()
            .flat_map(|&i| self.slopes(i))
            .copied()
            .collect();
        slopes.resize(count * d, 0.0);
        let start = self.values.len();
        let tangents = match &self.second {
            None => program.tangents_along(&values, &slopes, d)?,
            Some(_) => {
                let mut given: Vec<f64> = inputs
                    .iter()
                    .flat_map(|&i| self.second(i))
                    .copied()
                    .collect();
                given.resize(count * d * d, 0.0);
                let curvatures = program.curvatures_along(&values, &slopes, &given, d)?;
                if let Some(second) = &mut self.second {
                    second.extend(curvatures.second);
                }
                curvatures.tangents
            }
        };
        self.values.extend(tangents.values);
        self.slopes.extend(tangents.derivatives);
        Ok(start..self.values.len())
    }

    /// Appends a constant entry.
    fn push(&mut self, value: f64) -> usize {
        let d = self.directions;
        self.values.push(value);
        self.slopes.resize(self.slopes.len() + d, 0.0);
        if let Some(second) = &mut self.second {
            second.resize(second.len() + d * d, 0.0);
        }
        self.values.len() - 1
    }

    /// Appends `value`, a function of earlier entries with the partial
    /// derivatives `partials` and second partial derivatives `curvature`
    /// by them (over ordered pairs), by the chain rules.
    fn push_chained(
        &mut self,
        value: f64,
        partials: &[(usize, f64)],
        curvature: &[(usize, usize, f64)],
    ) -> usize {
        let entry = self.push(value);
        let d = self.directions;
        chain_slopes(&mut self.slopes, d, entry, partials);
        if let Some(second) = &mut self.second {
            chain_second(second, &self.slopes, d, entry, partials, curvature);
        }
        entry
    }
}
