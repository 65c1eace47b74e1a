//! The work of a run's inputs, `W(t) = int_0^t P dt` with the input power
//! `P = u . B(q)^T qdot` ([`super::Observed::input_power`]), for the power
//! balance `E(t) - E(0) - W(t)` ([`super::Summary::power_balance`]).
//!
//! Each step adds the integral over `[t_1, t_2]` of the quadratic through
//! the powers at the last three states `t_0 < t_1 < t_2`, with
//! `h_1 = t_1 - t_0` and `h_2 = t_2 - t_1`:
//!
//! ```text
//! int_{t_1}^{t_2} P dt ~ h_2 (a_0 P_0 + a_1 P_1 + a_2 P_2),
//! a_0 = -h_2^2 / (6 h_1 (h_1 + h_2)),  a_1 = (h_2 + 3 h_1) / (6 h_1),
//! a_2 = (3 h_1 + 2 h_2) / (6 (h_1 + h_2)),
//! ```
//!
//! exact for quadratics, so the work is accurate to third order in the
//! step (`-1/12, 8/12, 5/12` for equal steps); the first step, with two
//! states only, takes the trapezoid.

/// The work done so far and the last two states' powers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Work {
    total: f64,
    earlier: Option<(f64, f64)>,
    latest: (f64, f64),
}

impl Work {
    /// No work yet, with the power `power` at `t`.
    pub(super) fn start(t: f64, power: f64) -> Work {
        Work {
            total: 0.0,
            earlier: None,
            latest: (t, power),
        }
    }

    /// The work up to `t`, where the power is `power`.
    pub(super) fn advance(&mut self, t: f64, power: f64) {
        let (t_1, p_1) = self.latest;
        let h_2 = t - t_1;
        self.total += match self.earlier {
            Some((t_0, p_0)) if t_1 > t_0 => {
                let h_1 = t_1 - t_0;
                let a_0 = -h_2 * h_2 / (6.0 * h_1 * (h_1 + h_2));
                let a_1 = (h_2 + 3.0 * h_1) / (6.0 * h_1);
                let a_2 = (3.0 * h_1 + 2.0 * h_2) / (6.0 * (h_1 + h_2));
                h_2 * (a_0 * p_0 + a_1 * p_1 + a_2 * power)
            }
            _ => 0.5 * h_2 * (p_1 + power),
        };
        self.earlier = Some(self.latest);
        self.latest = (t, power);
    }

    /// `W` at the latest state.
    pub(super) fn total(&self) -> f64 {
        self.total
    }
}

#[cfg(test)]
mod tests {
    use super::Work;

    /// Against the closed form `int_0^t cos = sin t`, on unequal steps:
    /// the error falls as the cube of the step.
    #[test]
    fn the_work_of_a_cosine_power_is_the_sine_to_third_order() {
        let error = |h: f64| {
            let mut work = Work::start(0.0, 1.0);
            let mut t = 0.0;
            for i in 0..(2.0 / h) as usize {
                t += if i % 2 == 0 { 0.7 * h } else { 1.3 * h };
                work.advance(t, t.cos());
            }
            (work.total() - t.sin()).abs()
        };
        let (coarse, fine) = (error(0.02), error(0.01));
        assert!(coarse < 1e-5, "{coarse:e}");
        assert!(coarse / fine > 6.0, "{coarse:e} / {fine:e}");
    }
}
