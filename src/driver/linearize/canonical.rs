//! `--canonical Q1,Q2,... --canonical-speed VAR[=V1,V2] [--canonical-gravity G]`:
//! the canonical form of Meijaard, Papadopoulos, Ruina & Schwab (2007),
//! equation (2.2),
//!
//! ```text
//! M qddot + v C1 qdot + (g K0 + v^2 K2) q = f
//! ```
//!
//! in the coordinates `q = (Q1, Q2, ...)` named, `f` the model's inputs in
//! declared order (one per coordinate). The point `--at` describes is
//! linearized at the two values `V1`, `V2` of the speed variable VAR (1 and
//! 2 unless given) with `q` and `dot(q)` kept independent, and
//! `crate::runtime::linearize::canonical` reads off `M`, `C1` and
//! `X(v) = g K0 + v^2 K2`: `K2` from the difference of the two, `K0` from
//! the rest divided by the value of the gravity parameter G (`g` unless
//! given), all of the speed-independent stiffness taken as gravity's.

use super::{LinearizeError, linearize_at};
use crate::driver::setup::Setup;
use crate::runtime::linearize::{CanonicalError, CanonicalForm, Dynamics, point};
use crate::runtime::nalgebra::DMatrix;
use std::fmt::Write as _;

/// The speed variable of `--canonical` and its two values.
#[derive(Clone, Debug, PartialEq)]
pub struct CanonicalSpeed {
    /// The variable's name, used in `--at` expressions.
    pub variable: String,
    /// The two values the model is linearized at.
    pub values: (f64, f64),
}

/// Parses `VAR` or `VAR=V1,V2` (clap's value parser).
pub fn speed(text: &str) -> Result<CanonicalSpeed, String> {
    let malformed = || format!("expected VAR or VAR=V1,V2 with two numbers, found `{text}`");
    let (variable, values) = match text.split_once('=') {
        None => (text.trim(), (1.0, 2.0)),
        Some((variable, values)) => {
            let numbers: Vec<f64> = values
                .split(',')
                .map(|value| value.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| malformed())?;
            match numbers[..] {
                [v1, v2] if v1.is_finite() && v2.is_finite() => (variable.trim(), (v1, v2)),
                _ => return Err(malformed()),
            }
        }
    };
    let valid_name =
        !variable.is_empty() && variable.chars().all(|c| c.is_alphanumeric() || c == '_');
    if !valid_name {
        return Err(malformed());
    }
    Ok(CanonicalSpeed {
        variable: variable.to_string(),
        values,
    })
}

/// What `--canonical` asks that the model or the point cannot give.
#[derive(Debug, thiserror::Error)]
pub enum CanonicalRequestError {
    /// A name in `--canonical` is no coordinate.
    #[error("--canonical: unknown coordinate `{name}` (coordinates: {known})")]
    UnknownCoordinate {
        /// The name given.
        name: String,
        /// The coordinates there are.
        known: String,
    },
    /// The speed variable is a parameter.
    #[error(
        "--canonical-speed: `{0}` is a parameter; name a new variable and use it in --at expressions"
    )]
    SpeedIsParameter(String),
    /// No `--at` expression uses the speed variable.
    #[error(
        "--canonical-speed: no --at expression uses `{0}`, so the operating point does not move with the speed"
    )]
    SpeedUnused(String),
    /// The gravity parameter is missing or zero.
    #[error(
        "--canonical-gravity: K0 is the stiffness per unit gravity, and `{name}` is {problem} (name the gravity parameter with --canonical-gravity)"
    )]
    Gravity {
        /// The parameter's name.
        name: String,
        /// "no parameter of the model" or "0".
        problem: &'static str,
    },
    /// The linearization at one of the speeds.
    #[error(transparent)]
    Linearize(#[from] LinearizeError),
    /// The two linear systems do not give a canonical form.
    #[error("--canonical: {0}")]
    Form(#[from] CanonicalError),
}

/// What `--canonical` asks for.
pub struct Request<'a> {
    /// The coordinates `q`.
    pub coordinates: &'a [String],
    /// The speed variable and its two values.
    pub speed: &'a CanonicalSpeed,
    /// The name of the parameter `K0` multiplies.
    pub gravity: &'a str,
}

/// The canonical form of the model of `setup` at the point its state
/// assignments describe, their one variable the speed, printed.
///
/// # Errors
/// [`CanonicalRequestError`]: names that are no coordinate or parameter, a
/// speed variable the point does not use, a point that is not steady at
/// one of the speeds, inputs that are not one force per coordinate.
pub fn canonical_form(setup: &Setup, request: &Request) -> Result<String, CanonicalRequestError> {
    let known = setup.model.coordinates();
    if let Some(name) = request.coordinates.iter().find(|c| !known.contains(c)) {
        return Err(CanonicalRequestError::UnknownCoordinate {
            name: name.clone(),
            known: known.join(", "),
        });
    }
    let g = gravity(&setup.parameters, request.gravity)?;
    let variable = &request.speed.variable;
    if setup.parameters.iter().any(|(name, _)| name == variable) {
        return Err(CanonicalRequestError::SpeedIsParameter(variable.clone()));
    }
    if !setup.state.reads(variable) {
        return Err(CanonicalRequestError::SpeedUnused(variable.clone()));
    }
    let coordinates: Vec<&str> = request.coordinates.iter().map(String::as_str).collect();
    let velocities = point::velocity_names(request.coordinates);
    let speeds: Vec<&str> = velocities.iter().map(String::as_str).collect();
    let independent: Vec<&str> = coordinates.iter().chain(&speeds).copied().collect();
    let (v1, v2) = request.speed.values;
    let linear_at = |value: f64| {
        linearize_at(setup, &[value], &independent).map_err(|source| LinearizeError::AtSweepValue {
            variable: variable.clone(),
            value,
            source: Box::new(source),
        })
    };
    let (slow, fast) = (linear_at(v1)?, linear_at(v2)?);
    let form =
        CanonicalForm::from_linearizations((&slow, v1), (&fast, v2), &coordinates, &speeds, g)?;
    Ok(describe(&form, request, g))
}

/// The value of the gravity parameter `name`, which must be nonzero.
fn gravity(parameters: &[(String, f64)], name: &str) -> Result<f64, CanonicalRequestError> {
    let problem = match parameters.iter().find(|(parameter, _)| parameter == name) {
        None => "no parameter of the model",
        Some(&(_, value)) if value != 0.0 => return Ok(value),
        Some(_) => "0",
    };
    Err(CanonicalRequestError::Gravity {
        name: name.to_string(),
        problem,
    })
}

/// The header and the four matrices, rows and columns named by `q`.
fn describe(form: &CanonicalForm, request: &Request, g: f64) -> String {
    let q = request.coordinates;
    let CanonicalSpeed { variable, values } = request.speed;
    let mut text = format!(
        "canonical form M qddot + {variable} C1 qdot + ({gravity} K0 + {variable}^2 K2) q = f \
         in q = ({}), f the inputs in declared order\n\
         from the linearizations at {variable} = {} and {variable} = {}; \
         K0 is the speed-independent stiffness divided by {gravity} = {g}\n",
        q.join(", "),
        values.0,
        values.1,
        gravity = request.gravity,
    );
    for (name, matrix) in [
        ("M", &form.m),
        ("C1", &form.c1),
        ("K0", &form.k0),
        ("K2", &form.k2),
    ] {
        text.push_str(&named_matrix(name, matrix, q));
    }
    text
}

/// `name`, then a header row of `q` and one row per coordinate, every entry
/// to 16 significant digits (a zero printed without its sign).
fn named_matrix(name: &str, matrix: &DMatrix<f64>, q: &[String]) -> String {
    let width = q.iter().map(String::len).max().unwrap_or(0);
    let mut text = format!("{name}:\n{:width$}", "");
    for column in q {
        let _ = write!(text, " {column:>23}");
    }
    text.push('\n');
    for (i, row) in q.iter().enumerate() {
        let _ = write!(text, "{row:width$}");
        for j in 0..q.len() {
            let _ = write!(text, " {:>23.15e}", matrix[(i, j)] + 0.0);
        }
        text.push('\n');
    }
    text
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_speeds_default_to_1_and_2() {
        let speed = |text| super::speed(text).map(|s| (s.variable, s.values));
        assert_eq!(speed("v"), Ok(("v".to_string(), (1.0, 2.0))));
        assert_eq!(speed("v=3, 7"), Ok(("v".to_string(), (3.0, 7.0))));
        for bad in ["", "v=3", "v=3,7,9", "v=a,b", "dot(v)", "v=1,inf"] {
            assert!(speed(bad).is_err(), "{bad}");
        }
    }
}
