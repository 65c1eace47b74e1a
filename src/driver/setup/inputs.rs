//! The expressions of `chaplygin simulate`, in the model language's syntax
//! with its operators `+ - * / ^`, its functions `sin cos tan sqrt exp ln
//! asin acos atan atan2` and `abs`: each `--input NAME=EXPRESSION` is a law of the time `t`, the
//! model's parameters and the state, its coordinates `q` and velocities
//! `dot(q)` (`0.3*sin(2*t)`, `u0*exp(-t/tau)`, the feedback
//! `-10*phi-2*dot(phi)`), so that open-loop gaits and feedback laws run
//! without writing Rust; inputs not given are zero. The sides of
//! `--stop-when` may name the inputs too ([`super::stop`]); the values of
//! `--initial NAME=EXPRESSION` are constants of the parameters
//! (`dot(theta_r)=-5/rR`).

use super::error::InputError;
use crate::driver::expression::{Expression, Point, Scope};

/// The inputs `u(t, q, qdot)` of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct InputSchedule {
    laws: Vec<Expression>,
}

impl InputSchedule {
    /// The inputs called `names` from the `--input` assignments `given`,
    /// expressions of `t`, the `parameters` (name and value), the
    /// command's `variables` and the state (the `coordinates` and their
    /// velocities).
    ///
    /// # Errors
    /// An unknown input, or an expression that is not one of `t`, the
    /// parameters and the state.
    pub fn new(
        names: &[&str],
        given: &[(String, String)],
        parameters: &[(&str, f64)],
        (variables, coordinates): (&[&str], &[&str]),
    ) -> Result<Self, InputError> {
        let scope = Scope {
            parameters,
            variables,
            coordinates,
            ..Scope::default()
        };
        let mut laws = vec![Expression::Number(0.0); names.len()];
        for (name, text) in given {
            let i =
                names
                    .iter()
                    .position(|n| n == name)
                    .ok_or_else(|| InputError::UnknownInput {
                        name: name.clone(),
                        known: if names.is_empty() {
                            "none".into()
                        } else {
                            names.join(", ")
                        },
                    })?;
            laws[i] = Expression::parse(text, &scope).map_err(|error| InputError::InputLaw {
                name: name.clone(),
                text: text.clone(),
                reason: error.to_string(),
            })?;
        }
        Ok(Self { laws })
    }

    /// Whether an input reads the state (a feedback law): else `q` and
    /// `qdot` may be given empty.
    pub fn reads_state(&self) -> bool {
        self.laws.iter().any(Expression::reads_state)
    }

    /// Whether no input reads the time or the state: each a constant of
    /// the parameters and the variables.
    pub fn is_constant(&self) -> bool {
        !(self.laws.iter()).any(|law| law.reads_state() || law.reads_time())
    }

    /// Each input's value at `variables` and its derivative in the
    /// variable of index `variable`, for inputs that are constants
    /// ([`Self::is_constant`]).
    pub fn slopes(&self, variables: &[f64], variable: usize) -> Vec<(f64, f64)> {
        let point = Point {
            variables,
            ..Point::default()
        };
        (self.laws.iter())
            .map(|law| law.slope(&point, variable))
            .collect()
    }

    /// The inputs at time `t`, the configuration `q` and its velocity
    /// `qdot`.
    pub fn at(&self, t: f64, q: &[f64], qdot: &[f64], inputs: &mut [f64]) {
        let point = Point {
            t,
            q,
            qdot,
            ..Point::default()
        };
        for (input, law) in inputs.iter_mut().zip(&self.laws) {
            *input = law.at(&point);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{InputError, InputSchedule};
    use crate::driver::expression::constant;

    fn given(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|(name, text)| (name.to_string(), text.to_string()))
            .collect()
    }

    #[test]
    fn constants_and_functions_of_time_and_parameters() {
        let schedule = InputSchedule::new(
            &["u1", "u2", "u3"],
            &given(&[("u1", "0.3*sin(2*t)"), ("u3", "-a^2/t + 1.5e-1")]),
            &[("a", 3.0)],
            (&[], &["x"]),
        )
        .unwrap();
        assert!(!schedule.reads_state());
        let t = 0.7f64;
        let mut u = [0.0; 3];
        schedule.at(t, &[], &[], &mut u);
        assert_eq!(u, [0.3 * (2.0 * t).sin(), 0.0, -9.0 / t + 0.15]);
    }

    #[test]
    fn feedback_laws_read_the_coordinates_and_velocities() {
        let schedule = InputSchedule::new(
            &["u1", "u2"],
            &given(&[("u2", "-k*phi - 2*dot(phi) + abs(dot(x))*t")]),
            &[("k", 10.0)],
            (&[], &["x", "phi"]),
        )
        .unwrap();
        assert!(schedule.reads_state());
        let (q, qdot, t) = ([1.0, 0.3], [-0.5, 0.25], 2.0);
        let mut u = [0.0; 2];
        schedule.at(t, &q, &qdot, &mut u);
        assert_eq!(u, [0.0, -10.0 * 0.3 - 2.0 * 0.25 + 0.5 * 2.0]);
    }

    #[test]
    fn initial_values_are_constants_of_the_parameters() {
        assert_eq!(constant("-5/rR", &[("rR", 0.3)]), Ok(-5.0 / 0.3));
        assert_eq!(constant("abs(-rR)", &[("rR", 0.3)]), Ok(0.3));
        assert!(
            constant("2*t", &[])
                .unwrap_err()
                .to_string()
                .contains("`t` is not known")
        );
        assert!(
            constant("1/rR", &[("rR", 0.0)])
                .unwrap_err()
                .to_string()
                .contains("not finite")
        );
        assert!(
            constant("v", &[])
                .unwrap_err()
                .to_string()
                .contains("`v` is neither `t` nor a parameter")
        );
    }

    #[test]
    fn unknown_names_and_bad_syntax_are_errors() {
        let error =
            InputSchedule::new(&["u1"], &given(&[("v", "1")]), &[], (&[], &["x"])).unwrap_err();
        assert!(matches!(error, InputError::UnknownInput { .. }), "{error}");
        for (text, says) in [
            ("b*t", "`b` is not `t`, a parameter or a coordinate"),
            ("dot(y)", "`dot(y)`: `y` is not a coordinate"),
            ("dot(2*x)", "`dot` takes one coordinate"),
            ("sinh(t)", "`sinh` is not one of"),
            ("sin(t, t)", "takes one scalar argument"),
            ("atan2(t)", "`atan2` takes two scalar arguments"),
            ("[t]", "a list"),
        ] {
            let error = InputSchedule::new(&["u1"], &given(&[("u1", text)]), &[], (&[], &["x"]))
                .unwrap_err();
            assert!(error.to_string().contains(says), "{text}: {error}");
        }
        let error =
            InputSchedule::new(&["u1"], &given(&[("u1", "2*")]), &[], (&[], &["x"])).unwrap_err();
        assert!(error.to_string().starts_with("--input u1=2*: "), "{error}");
    }
}
