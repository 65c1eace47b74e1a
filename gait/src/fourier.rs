//! A closed shape loop as a truncated Fourier series: with period `T`,
//! `w = 2 pi / T` and `N` harmonics, each shape coordinate is
//!
//! ```text
//! r_i(t) = c_i + sum_{k=1..N} (a_ik cos(k w t) + b_ik sin(k w t))
//! ```
//!
//! and the coefficients are stored coordinate by coordinate,
//! `[c_i, a_i1, b_i1, .., a_iN, b_iN]`, `2N + 1` per coordinate.

/// A shape loop's Fourier coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct FourierLoop {
    /// The period `T`.
    pub period: f64,
    /// The harmonics `N`.
    pub harmonics: usize,
    /// `[c_i, a_i1, b_i1, .., a_iN, b_iN]` for each shape coordinate in turn.
    pub coefficients: Vec<f64>,
}

impl FourierLoop {
    /// The coefficients per shape coordinate, `2N + 1`.
    pub fn per_coordinate(&self) -> usize {
        2 * self.harmonics + 1
    }

    /// The number of shape coordinates.
    pub fn coordinates(&self) -> usize {
        self.coefficients.len() / self.per_coordinate()
    }

    /// The basis functions at `t` and their time derivatives:
    /// `(1, cos w t, sin w t, .., cos N w t, sin N w t)` and their rates.
    pub fn basis(&self, t: f64) -> (Vec<f64>, Vec<f64>) {
        let w = 2.0 * std::f64::consts::PI / self.period;
        let mut values = vec![1.0];
        let mut rates = vec![0.0];
        for k in 1..=self.harmonics {
            let frequency = k as f64 * w;
            let (sin, cos) = (frequency * t).sin_cos();
            values.extend([cos, sin]);
            rates.extend([-frequency * sin, frequency * cos]);
        }
        (values, rates)
    }

    /// `r(t)`, without its rate: the first half of [`FourierLoop::shape`],
    /// the same sums in the same order.
    pub fn position(&self, t: f64) -> Vec<f64> {
        let w = 2.0 * std::f64::consts::PI / self.period;
        let per = self.per_coordinate();
        let mut r: Vec<f64> = self.coefficients.iter().step_by(per).copied().collect();
        for k in 1..=self.harmonics {
            let (sin, cos) = (k as f64 * w * t).sin_cos();
            for (r, c) in r.iter_mut().zip(self.coefficients.chunks(per)) {
                *r += c[2 * k - 1] * cos;
                *r += c[2 * k] * sin;
            }
        }
        r
    }

    /// `(r(t), rdot(t))`.
    pub fn shape(&self, t: f64) -> (Vec<f64>, Vec<f64>) {
        let (values, rates) = self.basis(t);
        self.coefficients
            .chunks(self.per_coordinate())
            .map(|c| {
                let at = |basis: &[f64]| basis.iter().zip(c).map(|(b, c)| b * c).sum::<f64>();
                (at(&values), at(&rates))
            })
            .unzip()
    }

    /// Each coordinate's name and law, a model-language expression of `t`
    /// (what `--cycle NAME=EXPR` takes), every coefficient at full
    /// precision.
    pub fn laws(&self, names: &[String]) -> Vec<(String, String)> {
        let w = 2.0 * std::f64::consts::PI / self.period;
        names
            .iter()
            .zip(self.coefficients.chunks(self.per_coordinate()))
            .map(|(name, c)| {
                let mut law = format!("{:?}", c[0]);
                for k in 1..=self.harmonics {
                    let frequency = k as f64 * w;
                    let (a, b) = (c[2 * k - 1], c[2 * k]);
                    law.push_str(&format!("{:+?}*cos({frequency:?}*t)", a));
                    law.push_str(&format!("{:+?}*sin({frequency:?}*t)", b));
                }
                (name.clone(), law)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::FourierLoop;
    use std::f64::consts::PI;

    #[test]
    fn the_loop_and_its_rate_follow_the_series() {
        let shape_loop = FourierLoop {
            period: PI,
            harmonics: 2,
            coefficients: vec![0.5, 1.0, 0.0, 0.0, 0.25, -1.0, 0.0, 2.0, 0.0, 0.0],
        };
        assert_eq!(shape_loop.coordinates(), 2);
        let t = 0.3;
        let (r, rdot) = shape_loop.shape(t);
        let expected = [
            0.5 + (2.0 * t).cos() + 0.25 * (4.0 * t).sin(),
            -1.0 + 2.0 * (2.0 * t).sin(),
        ];
        let rates = [
            -2.0 * (2.0 * t).sin() + (4.0 * t).cos(),
            4.0 * (2.0 * t).cos(),
        ];
        for i in 0..2 {
            assert!((r[i] - expected[i]).abs() < 1e-15 && (rdot[i] - rates[i]).abs() < 1e-14);
        }
        for t in [0.0, 0.3, 1.7, 2.9] {
            assert_eq!(shape_loop.position(t), shape_loop.shape(t).0);
        }
        let laws = shape_loop.laws(&["a".into(), "b".into()]);
        assert_eq!(
            laws[1].1,
            "-1.0+0.0*cos(2.0*t)+2.0*sin(2.0*t)+0.0*cos(4.0*t)+0.0*sin(4.0*t)"
        );
    }
}
