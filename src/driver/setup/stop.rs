//! `--stop-when COND` (docs/INTERFACE.md section 3): a run ends cleanly where
//! COND first holds. COND is one comparison `EXPR < EXPR`, `EXPR <= EXPR`,
//! `EXPR > EXPR` or `EXPR >= EXPR` of `t`, the coordinates, their velocities
//! `dot(q)`, the inputs and the parameters ([`super::inputs`]:
//! `'abs(phi) > 1'`). It holds where its larger side minus its smaller side
//! is positive, or zero for `<=` and `>=`: the event function whose
//! crossing the simulation loop locates within its step
//! (`crate::runtime::simulate::stop`), read at a state through the
//! formulation's configuration, velocity and inputs.

use crate::driver::expression::{Expression, Point, Scope};
use crate::driver::formulation::Formulation;
use crate::runtime::simulate::Stop;
use std::cell::RefCell;

/// Why a `--stop-when` condition cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum StopError {
    /// None of `<`, `<=`, `>`, `>=`.
    #[error("--stop-when {text}: no comparison `<`, `<=`, `>` or `>=`")]
    NoComparison {
        /// The condition as given.
        text: String,
    },
    /// More than one comparison.
    #[error("--stop-when {text}: {count} comparisons; a condition is one")]
    Comparisons {
        /// The condition as given.
        text: String,
        /// How many.
        count: usize,
    },
    /// A side is not an expression of the names in scope.
    #[error("--stop-when {text}: {reason}")]
    Side {
        /// The condition as given.
        text: String,
        /// What is wrong with the side.
        reason: String,
    },
}

/// A `--stop-when` condition: `larger > smaller`, or `larger >= smaller`
/// when `inclusive`.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    text: String,
    larger: Expression,
    smaller: Expression,
    inclusive: bool,
    coordinates: usize,
}

impl Comparison {
    /// `text` split at its one `<`, `<=`, `>` or `>=`, each side resolved
    /// against `scope`.
    ///
    /// # Errors
    /// No comparison, several, or a side that is not an expression of the
    /// names in `scope`.
    pub(crate) fn parse(text: &str, scope: &Scope<'_>) -> Result<Self, StopError> {
        let at: Vec<usize> = text.match_indices(['<', '>']).map(|(i, _)| i).collect();
        let i = match at.as_slice() {
            [i] => *i,
            [] => {
                return Err(StopError::NoComparison { text: text.into() });
            }
            several => {
                return Err(StopError::Comparisons {
                    text: text.into(),
                    count: several.len(),
                });
            }
        };
        let side = |side: &str| {
            Expression::parse(side.trim(), scope).map_err(|error| StopError::Side {
                text: text.into(),
                reason: error.to_string(),
            })
        };
        let inclusive = text[i + 1..].starts_with('=');
        let right_start = if inclusive { i + 2 } else { i + 1 };
        let (left, right) = (side(&text[..i])?, side(&text[right_start..])?);
        let (larger, smaller) = if text[i..].starts_with('>') {
            (left, right)
        } else {
            (right, left)
        };
        Ok(Self {
            text: text.into(),
            larger,
            smaller,
            inclusive,
            coordinates: scope.coordinates.len(),
        })
    }

    /// The condition as given.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The event function at `point`: positive where the condition holds
    /// (an inclusive comparison's equality is the smallest positive value).
    fn value(&self, point: &Point<'_>) -> f64 {
        let difference = self.larger.at(point) - self.smaller.at(point);
        if self.inclusive && difference == 0.0 {
            f64::MIN_POSITIVE
        } else {
            difference
        }
    }
}

/// The simulation loop's stop condition of `comparison` on the states of
/// `formulation`: its event function at the time, the configuration and
/// velocity ([`SliceSystem::configuration_velocity`](crate::runtime::simulate::SliceSystem::configuration_velocity)) and the inputs of a
/// state.
pub fn stop_condition<'a>(
    formulation: &'a dyn Formulation,
    comparison: &'a Comparison,
) -> Stop<&'a str, impl Fn(f64, &Vec<f64>) -> f64 + 'a> {
    let n = comparison.coordinates;
    let buffers = RefCell::new((
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; formulation.input_names().len()],
    ));
    Stop::new(comparison.text(), move |t, x: &Vec<f64>| {
        let (q, qdot, u) = &mut *buffers.borrow_mut();
        formulation.configuration_velocity(x, q, qdot);
        formulation.inputs(t, x, u);
        comparison.value(&Point {
            t,
            q,
            qdot,
            u,
            ..Point::default()
        })
    })
}

#[cfg(test)]
mod tests {
    use super::{Comparison, Point, Scope, StopError};

    const SCOPE: Scope<'static> = Scope {
        parameters: &[("k", 2.0)],
        variables: &[],
        coordinates: &["x", "phi"],
        inputs: &["u1"],
    };

    fn value(text: &str, point: &Point<'_>) -> f64 {
        Comparison::parse(text, &SCOPE).unwrap().value(point)
    }

    #[test]
    fn a_comparison_is_the_difference_of_its_sides() {
        let point = Point {
            t: 0.5,
            q: &[3.0, -1.5],
            qdot: &[0.25, 4.0],
            u: &[7.0],
            ..Point::default()
        };
        assert_eq!(value("abs(phi) > 1", &point), 0.5);
        assert_eq!(value("abs(phi) < 1", &point), -0.5);
        assert_eq!(value("k*t + dot(phi) < u1 - x", &point), 7.0 - 3.0 - 5.0);
        assert_eq!(value("abs(phi) >= 1", &point), 0.5);
        assert_eq!(value("abs(phi) <= 1", &point), -0.5);
        assert_eq!(value("x<=2", &point), -1.0);
    }

    /// At equality a strict comparison does not hold and an inclusive one
    /// does.
    #[test]
    fn an_inclusive_comparison_holds_at_equality() {
        let point = Point {
            t: 0.0,
            q: &[1.0, 0.5],
            qdot: &[0.0, 0.0],
            u: &[0.0],
            ..Point::default()
        };
        assert_eq!(value("x > 1", &point), 0.0);
        assert_eq!(value("x < 1", &point), 0.0);
        assert!(value("x >= 1", &point) > 0.0);
        assert!(value("x <= 1", &point) > 0.0);
        assert!(value("2*phi >= x", &point) > 0.0);
    }

    #[test]
    fn one_comparison_of_known_names() {
        let error = |text: &str| Comparison::parse(text, &SCOPE).unwrap_err();
        assert!(matches!(error("phi"), StopError::NoComparison { .. }));
        assert!(matches!(error("phi == 1"), StopError::NoComparison { .. }));
        assert!(matches!(
            error("0 < phi < 1"),
            StopError::Comparisons { count: 2, .. }
        ));
        assert!(matches!(
            error("0 <= phi <= 1"),
            StopError::Comparisons { count: 2, .. }
        ));
        assert_eq!(
            error("psi > 1").to_string(),
            "--stop-when psi > 1: `psi` is not `t`, a parameter, a coordinate or an input"
        );
    }
}
