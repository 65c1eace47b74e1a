//! A run's energy drift and power balance on a scale that a constant added
//! to the potential does not change ([`super::Summary::energy_drift`]).
//!
//! With `E` the energy, `V` the energy at rest at the same configuration
//! ([`super::Observed::energy_at_rest`]) and `T = E - V` the kinetic
//! energy, over the states of the run so far:
//!
//! ```text
//! drift   = max_t |E(t) - E(0)|        / scale,
//! balance = max_t |E(t) - E(0) - W(t)| / scale,
//! scale   = max_t T(t) + max_t V(t) - min_t V(t),
//! ```
//!
//! `W` the inputs' work. Every term of the scale is a difference of
//! energies or a kinetic energy, so `E + c` gives the same drift. Without
//! inputs `T + V` is constant, so the potential's range is at most the
//! kinetic energy's and the scale lies between `max T` and `2 max T`. A run
//! at rest with a constant potential has the scale 0; its drift is then
//! absolute (the scale taken as 1).

/// The largest changes of the energy so far and their scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Drift {
    start: f64,
    change: f64,
    imbalance: f64,
    kinetic: f64,
    potential: (f64, f64),
}

impl Drift {
    /// At the first state, of energy `energy` and energy at rest `at_rest`.
    pub(super) fn start(energy: f64, at_rest: f64) -> Self {
        Self {
            start: energy,
            change: 0.0,
            imbalance: 0.0,
            kinetic: energy - at_rest,
            potential: (at_rest, at_rest),
        }
    }

    /// A state of energy `energy` and energy at rest `at_rest`, the inputs
    /// having done the work `work` since the start.
    pub(super) fn observe(&mut self, energy: f64, at_rest: f64, work: f64) {
        let gained = energy - self.start;
        self.change = self.change.max(gained.abs());
        self.imbalance = self.imbalance.max((gained - work).abs());
        self.kinetic = self.kinetic.max(energy - at_rest);
        self.potential = (self.potential.0.min(at_rest), self.potential.1.max(at_rest));
    }

    /// `max T + max V - min V`.
    pub(super) fn scale(&self) -> f64 {
        self.kinetic + self.potential.1 - self.potential.0
    }

    /// `max |E(t) - E(0)|` over the scale (over 1 where that is 0).
    pub(super) fn energy_drift(&self) -> f64 {
        self.change / self.divisor()
    }

    /// `max |E(t) - E(0) - W(t)|` over the scale (over 1 where that is 0).
    pub(super) fn power_balance(&self) -> f64 {
        self.imbalance / self.divisor()
    }

    fn divisor(&self) -> f64 {
        match self.scale() {
            0.0 => 1.0,
            scale => scale,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Drift;

    /// A pendulum's swing `E = 1/2 w^2 + (1 - cos q)` observed at its
    /// lowest point (`T = 1`, `V = 0`) and at its turning point (`T = 0`,
    /// `V = 1`, the energy off by `1e-9`): the scale is `max T + range V
    /// = 2`, the drift `0.5e-9`, whatever constant `c` is added to `V` (up
    /// to the round-off of `c`).
    #[test]
    fn a_constant_in_the_potential_leaves_the_drift_alone() {
        for c in [0.0, 1e6, -3.0] {
            let mut drift = Drift::start(1.0 + c, c);
            drift.observe(1.0 + 1e-9 + c, 1.0 + c, 0.0);
            let round_off = 4.0 * f64::EPSILON * (1.0 + c.abs());
            assert!((drift.scale() - 2.0).abs() <= round_off, "c = {c}");
            let error = (drift.energy_drift() - 0.5e-9).abs();
            assert!(error <= round_off, "c = {c}: {error:e}");
        }
    }
}
