//! The expressions of `chaplygin simulate`, in the model language's syntax
//! with its operators `+ - * / ^`, its functions `sin cos tan sqrt exp ln`
//! and `abs`: each `--input NAME=EXPRESSION` is a law of the time `t`, the
//! model's parameters and the state, its coordinates `q` and velocities
//! `dot(q)` (`0.3*sin(2*t)`, `u0*exp(-t/tau)`, the feedback
//! `-10*phi-2*dot(phi)`), so that open-loop gaits and feedback laws run
//! without writing Rust; inputs not given are zero. The sides of
//! `--stop-when` may name the inputs too ([`super::stop`]); the values of
//! `--initial NAME=EXPRESSION` are constants of the parameters
//! (`dot(theta_r)=-5/rR`).

use super::error::InputError;
use chaplygin_codegen::syntax::{self, BinaryOperator, Expr, Value};

/// Why an `--input` cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum InputLawError {
    /// `--input` names no input.
    #[error(transparent)]
    UnknownInput(InputError),
    /// The right-hand side is not an expression of `t`, the parameters and
    /// the state.
    #[error("--input {name}={text}: {reason}")]
    Expression {
        /// The input.
        name: String,
        /// The expression as given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// A function of the model language, or `abs`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Function {
    Sin,
    Cos,
    Tan,
    Sqrt,
    Exp,
    Ln,
    Abs,
}

impl Function {
    fn named(name: &str) -> Option<Self> {
        Some(match name {
            "sin" => Self::Sin,
            "cos" => Self::Cos,
            "tan" => Self::Tan,
            "sqrt" => Self::Sqrt,
            "exp" => Self::Exp,
            "ln" => Self::Ln,
            "abs" => Self::Abs,
            _ => return None,
        })
    }

    fn at(self, x: f64) -> f64 {
        match self {
            Self::Sin => x.sin(),
            Self::Cos => x.cos(),
            Self::Tan => x.tan(),
            Self::Sqrt => x.sqrt(),
            Self::Exp => x.exp(),
            Self::Ln => x.ln(),
            Self::Abs => x.abs(),
        }
    }
}

/// What an expression may name besides `t`: the parameters, at their
/// values; where the state is known, the coordinates (and their velocities
/// `dot(q)`); where the inputs are known, the inputs.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Scope<'a> {
    /// The parameters' names and values.
    pub parameters: &'a [(&'a str, f64)],
    /// The coordinates, in order.
    pub coordinates: &'a [&'a str],
    /// The inputs, in order.
    pub inputs: &'a [&'a str],
}

impl Scope<'_> {
    /// `name` is none of the names of the scope: what it could have been.
    fn unknown(&self, name: &str) -> String {
        let mut kinds = vec!["`t`", "a parameter"];
        if !self.coordinates.is_empty() {
            kinds.push("a coordinate");
        }
        if !self.inputs.is_empty() {
            kinds.push("an input");
        }
        match kinds.as_slice() {
            [first, last] => format!("`{name}` is neither {first} nor {last}"),
            [rest @ .., last] => format!("`{name}` is not {} or {last}", rest.join(", ")),
            [] => unreachable!("`t` and the parameters are always in scope"),
        }
    }
}

/// Where an expression is evaluated: the time, the configuration, its
/// velocity and the inputs, each as long as its names in the [`Scope`]
/// (empty where the scope has none).
#[derive(Clone, Copy, Debug)]
pub(super) struct Point<'a> {
    /// The time.
    pub t: f64,
    /// The coordinates.
    pub q: &'a [f64],
    /// Their velocities.
    pub qdot: &'a [f64],
    /// The inputs.
    pub u: &'a [f64],
}

/// An expression resolved against a [`Scope`], the parameters' values
/// substituted.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Expression {
    /// A number.
    Number(f64),
    /// The time `t`.
    Time,
    /// The coordinate of this index.
    Coordinate(usize),
    /// The velocity of the coordinate of this index.
    Velocity(usize),
    /// The input of this index.
    Input(usize),
    /// A function of an expression.
    Call(Function, Box<Expression>),
    /// `-operand`.
    Negate(Box<Expression>),
    /// `left operator right`.
    Binary(BinaryOperator, Box<Expression>, Box<Expression>),
}

impl Expression {
    /// `text` read by the model language's parser (as the value of a
    /// section) and resolved against `scope`; the reason it is none, else.
    pub(super) fn parse(text: &str, scope: &Scope<'_>) -> Result<Self, String> {
        let model = syntax::parse_str(&format!("struct Input {{ input: {text} }}")).map_err(
            |diagnostics| {
                let messages: Vec<&str> = diagnostics.iter().map(|d| d.message.as_str()).collect();
                messages.join("; ")
            },
        )?;
        match model.sections.as_slice() {
            [section] => match &section.value {
                Value::Expr(expr) => resolve(expr, scope),
                Value::List(_) => Err("a list where a scalar expression belongs".into()),
            },
            _ => Err("not one expression".into()),
        }
    }

    /// Whether this expression or a part of it is `leaf`.
    fn contains(&self, leaf: &impl Fn(&Expression) -> bool) -> bool {
        leaf(self)
            || match self {
                Self::Call(_, operand) | Self::Negate(operand) => operand.contains(leaf),
                Self::Binary(_, left, right) => left.contains(leaf) || right.contains(leaf),
                _ => false,
            }
    }

    fn reads_time(&self) -> bool {
        self.contains(&|e| matches!(e, Self::Time))
    }

    /// Whether the expression reads the configuration or the velocity.
    fn reads_state(&self) -> bool {
        self.contains(&|e| matches!(e, Self::Coordinate(_) | Self::Velocity(_)))
    }

    /// The value at `point`.
    pub(super) fn at(&self, point: &Point<'_>) -> f64 {
        match self {
            Self::Number(value) => *value,
            Self::Time => point.t,
            Self::Coordinate(i) => point.q[*i],
            Self::Velocity(i) => point.qdot[*i],
            Self::Input(i) => point.u[*i],
            Self::Call(function, argument) => function.at(argument.at(point)),
            Self::Negate(operand) => -operand.at(point),
            Self::Binary(operator, left, right) => {
                let (a, b) = (left.at(point), right.at(point));
                match operator {
                    BinaryOperator::Add => a + b,
                    BinaryOperator::Subtract => a - b,
                    BinaryOperator::Multiply => a * b,
                    BinaryOperator::Divide => a / b,
                    BinaryOperator::Power => a.powf(b),
                }
            }
        }
    }
}

/// The inputs `u(t, q, qdot)` of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct InputSchedule {
    laws: Vec<Expression>,
}

impl InputSchedule {
    /// The inputs called `names` from the `--input` assignments `given`,
    /// expressions of `t`, the `parameters` (name and value) and the state
    /// (the `coordinates` and their velocities).
    ///
    /// # Errors
    /// An unknown input, or an expression that is not one of `t`, the
    /// parameters and the state.
    pub fn new(
        names: &[&str],
        given: &[(String, String)],
        parameters: &[(&str, f64)],
        coordinates: &[&str],
    ) -> Result<Self, InputLawError> {
        let scope = Scope {
            parameters,
            coordinates,
            inputs: &[],
        };
        let mut laws = vec![Expression::Number(0.0); names.len()];
        for (name, text) in given {
            let i = names.iter().position(|n| n == name).ok_or_else(|| {
                InputLawError::UnknownInput(InputError::UnknownInput {
                    name: name.clone(),
                    known: if names.is_empty() {
                        "none".into()
                    } else {
                        names.join(", ")
                    },
                })
            })?;
            laws[i] =
                Expression::parse(text, &scope).map_err(|reason| InputLawError::Expression {
                    name: name.clone(),
                    text: text.clone(),
                    reason,
                })?;
        }
        Ok(Self { laws })
    }

    /// Whether an input reads the state (a feedback law): else `q` and
    /// `qdot` may be given empty.
    pub fn reads_state(&self) -> bool {
        self.laws.iter().any(Expression::reads_state)
    }

    /// The inputs at time `t`, the configuration `q` and its velocity
    /// `qdot`.
    pub fn at(&self, t: f64, q: &[f64], qdot: &[f64], inputs: &mut [f64]) {
        let point = Point { t, q, qdot, u: &[] };
        for (input, law) in inputs.iter_mut().zip(&self.laws) {
            *input = law.at(&point);
        }
    }
}

/// The value of `text`, an expression of the parameters (name and value)
/// in the model language; the reason it is none, else.
pub fn constant(text: &str, parameters: &[(&str, f64)]) -> Result<f64, String> {
    let scope = Scope {
        parameters,
        ..Scope::default()
    };
    let law = Expression::parse(text, &scope)?;
    if law.reads_time() {
        return Err("`t` is not known at the start: use numbers and parameters".into());
    }
    let value = law.at(&Point {
        t: 0.0,
        q: &[],
        qdot: &[],
        u: &[],
    });
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("the value {value} is not finite"))
    }
}

/// The index of `name` in `names`.
fn index(names: &[&str], name: &str) -> Option<usize> {
    names.iter().position(|n| *n == name)
}

fn resolve(expr: &Expr, scope: &Scope<'_>) -> Result<Expression, String> {
    let resolved = |e: &Expr| resolve(e, scope).map(Box::new);
    Ok(match expr {
        Expr::Number { literal, .. } => Expression::Number(
            literal
                .parse()
                .map_err(|_| format!("`{literal}` is not a number"))?,
        ),
        Expr::Name(name) if name == "t" => Expression::Time,
        Expr::Name(name) => {
            let name = name.to_string();
            if let Some((_, value)) = scope.parameters.iter().find(|(p, _)| *p == name) {
                Expression::Number(*value)
            } else if let Some(i) = index(scope.coordinates, &name) {
                Expression::Coordinate(i)
            } else if let Some(i) = index(scope.inputs, &name) {
                Expression::Input(i)
            } else {
                return Err(scope.unknown(&name));
            }
        }
        Expr::Call {
            function,
            arguments,
            ..
        } if function == "dot" => match arguments.as_slice() {
            [Value::Expr(Expr::Name(name))] => index(scope.coordinates, &name.to_string())
                .map(Expression::Velocity)
                .ok_or_else(|| format!("`dot({name})`: `{name}` is not a coordinate"))?,
            _ => return Err("`dot` takes one coordinate".into()),
        },
        Expr::Call {
            function,
            arguments,
            ..
        } => {
            let known = Function::named(&function.to_string()).ok_or_else(|| {
                format!("`{function}` is not one of sin, cos, tan, sqrt, exp, ln, abs")
            })?;
            match arguments.as_slice() {
                [Value::Expr(argument)] => Expression::Call(known, resolved(argument)?),
                _ => return Err(format!("`{function}` takes one scalar argument")),
            }
        }
        Expr::Field { field, .. } => {
            return Err(format!("a field `.{field}` is not a scalar of t"));
        }
        Expr::Negate { operand, .. } => Expression::Negate(resolved(operand)?),
        Expr::Binary {
            operator,
            left,
            right,
            ..
        } => Expression::Binary(*operator, resolved(left)?, resolved(right)?),
    })
}

#[cfg(test)]
mod tests {
    use super::{InputLawError, InputSchedule, constant};

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
            &["x"],
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
            &["x", "phi"],
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
                .contains("`t` is not known")
        );
        assert!(
            constant("1/rR", &[("rR", 0.0)])
                .unwrap_err()
                .contains("not finite")
        );
        assert!(
            constant("v", &[])
                .unwrap_err()
                .contains("`v` is neither `t` nor a parameter")
        );
    }

    #[test]
    fn unknown_names_and_bad_syntax_are_errors() {
        let error = InputSchedule::new(&["u1"], &given(&[("v", "1")]), &[], &["x"]).unwrap_err();
        assert!(matches!(error, InputLawError::UnknownInput(_)), "{error}");
        for (text, says) in [
            ("b*t", "`b` is not `t`, a parameter or a coordinate"),
            ("dot(y)", "`dot(y)`: `y` is not a coordinate"),
            ("dot(2*x)", "`dot` takes one coordinate"),
            ("atan(t)", "`atan` is not one of"),
            ("sin(t, t)", "takes one scalar argument"),
            ("[t]", "a list"),
        ] {
            let error =
                InputSchedule::new(&["u1"], &given(&[("u1", text)]), &[], &["x"]).unwrap_err();
            assert!(error.to_string().contains(says), "{text}: {error}");
        }
        let error = InputSchedule::new(&["u1"], &given(&[("u1", "2*")]), &[], &["x"]).unwrap_err();
        assert!(error.to_string().starts_with("--input u1=2*: "), "{error}");
    }
}
