//! The inputs of a run without a controller: each `--input NAME=EXPRESSION`
//! is an expression in the model language's syntax of the time `t` and the
//! model's parameters (`0.1`, `0.3*sin(2*t)`, `u0*exp(-t/tau)`), with the
//! language's operators `+ - * / ^` and functions `sin cos tan sqrt exp ln`;
//! open-loop gaits run without writing Rust. Inputs not given are zero.
//! The values of `--initial NAME=EXPRESSION` are read the same way, as
//! constants of the parameters (`dot(theta_r)=-5/rR`).

use super::start::InputError;
use chaplygin_codegen::syntax::{self, BinaryOperator, Expr, Value};

/// Why an `--input` cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum InputLawError {
    /// `--input` names no input.
    #[error(transparent)]
    UnknownInput(InputError),
    /// The right-hand side is not an expression of `t` and the parameters.
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

/// A function of the model language.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Function {
    Sin,
    Cos,
    Tan,
    Sqrt,
    Exp,
    Ln,
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
        }
    }
}

/// An input as a function of time, the parameters' values substituted.
#[derive(Clone, Debug, PartialEq)]
enum Law {
    Number(f64),
    Time,
    Call(Function, Box<Law>),
    Negate(Box<Law>),
    Binary(BinaryOperator, Box<Law>, Box<Law>),
}

impl Law {
    fn depends_on_time(&self) -> bool {
        match self {
            Law::Number(_) => false,
            Law::Time => true,
            Law::Call(_, operand) | Law::Negate(operand) => operand.depends_on_time(),
            Law::Binary(_, left, right) => left.depends_on_time() || right.depends_on_time(),
        }
    }

    fn at(&self, t: f64) -> f64 {
        match self {
            Law::Number(value) => *value,
            Law::Time => t,
            Law::Call(function, argument) => function.at(argument.at(t)),
            Law::Negate(operand) => -operand.at(t),
            Law::Binary(operator, left, right) => {
                let (a, b) = (left.at(t), right.at(t));
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

/// The inputs `u(t)` of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct InputSchedule {
    laws: Vec<Law>,
}

impl InputSchedule {
    /// The inputs called `names` from the `--input` assignments `given`,
    /// with `parameters` (name and value) as the expressions' constants.
    ///
    /// # Errors
    /// An unknown input, or an expression that is not one of `t` and the
    /// parameters.
    pub fn new(
        names: &[&str],
        given: &[(String, String)],
        parameters: &[(&str, f64)],
    ) -> Result<Self, InputLawError> {
        let mut laws = vec![Law::Number(0.0); names.len()];
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
            laws[i] = parse(text, parameters).map_err(|reason| InputLawError::Expression {
                name: name.clone(),
                text: text.clone(),
                reason,
            })?;
        }
        Ok(Self { laws })
    }

    /// The inputs at time `t`.
    pub fn at(&self, t: f64, inputs: &mut [f64]) {
        for (input, law) in inputs.iter_mut().zip(&self.laws) {
            *input = law.at(t);
        }
    }

    /// The inputs at time `t`, as an array of `P`.
    pub fn array<const P: usize>(&self, t: f64) -> [f64; P] {
        let mut inputs = [0.0; P];
        self.at(t, &mut inputs);
        inputs
    }
}

/// The value of `text`, an expression of the parameters (name and value)
/// in the model language; the reason it is none, else.
pub fn constant(text: &str, parameters: &[(&str, f64)]) -> Result<f64, String> {
    let law = parse(text, parameters)?;
    if law.depends_on_time() {
        return Err("`t` is not known at the start: use numbers and parameters".into());
    }
    let value = law.at(0.0);
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("the value {value} is not finite"))
    }
}

/// `text` read by the model language's parser (as the value of a section)
/// and resolved against `t` and the parameters.
fn parse(text: &str, parameters: &[(&str, f64)]) -> Result<Law, String> {
    let model =
        syntax::parse_str(&format!("struct Input {{ input: {text} }}")).map_err(|diagnostics| {
            let messages: Vec<&str> = diagnostics.iter().map(|d| d.message.as_str()).collect();
            messages.join("; ")
        })?;
    match model.sections.as_slice() {
        [section] => match &section.value {
            Value::Expr(expr) => resolve(expr, parameters),
            Value::List(_) => Err("a list where a scalar expression belongs".into()),
        },
        _ => Err("not one expression".into()),
    }
}

fn resolve(expr: &Expr, parameters: &[(&str, f64)]) -> Result<Law, String> {
    let resolved = |e: &Expr| resolve(e, parameters).map(Box::new);
    Ok(match expr {
        Expr::Number { literal, .. } => Law::Number(
            literal
                .parse()
                .map_err(|_| format!("`{literal}` is not a number"))?,
        ),
        Expr::Name(name) if name == "t" => Law::Time,
        Expr::Name(name) => {
            let value = parameters
                .iter()
                .find(|(parameter, _)| name == parameter)
                .map(|(_, value)| *value)
                .ok_or_else(|| format!("`{name}` is neither `t` nor a parameter"))?;
            Law::Number(value)
        }
        Expr::Call {
            function,
            arguments,
            ..
        } => {
            let known = Function::named(&function.to_string()).ok_or_else(|| {
                format!("`{function}` is not one of sin, cos, tan, sqrt, exp, ln")
            })?;
            match arguments.as_slice() {
                [Value::Expr(argument)] => Law::Call(known, resolved(argument)?),
                _ => return Err(format!("`{function}` takes one scalar argument")),
            }
        }
        Expr::Field { field, .. } => {
            return Err(format!("a field `.{field}` is not a scalar of t"));
        }
        Expr::Negate { operand, .. } => Law::Negate(resolved(operand)?),
        Expr::Binary {
            operator,
            left,
            right,
            ..
        } => Law::Binary(*operator, resolved(left)?, resolved(right)?),
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
        )
        .unwrap();
        let t = 0.7f64;
        let u: [f64; 3] = schedule.array(t);
        assert_eq!(u, [0.3 * (2.0 * t).sin(), 0.0, -9.0 / t + 0.15]);
    }

    #[test]
    fn initial_values_are_constants_of_the_parameters() {
        assert_eq!(constant("-5/rR", &[("rR", 0.3)]), Ok(-5.0 / 0.3));
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
        assert!(constant("v", &[]).unwrap_err().contains("`v` is neither"));
    }

    #[test]
    fn unknown_names_and_bad_syntax_are_errors() {
        let error = InputSchedule::new(&["u1"], &given(&[("v", "1")]), &[]).unwrap_err();
        assert!(matches!(error, InputLawError::UnknownInput(_)), "{error}");
        for (text, says) in [
            ("b*t", "`b` is neither `t` nor a parameter"),
            ("atan(t)", "`atan` is not one of"),
            ("sin(t, t)", "takes one scalar argument"),
            ("[t]", "a list"),
        ] {
            let error = InputSchedule::new(&["u1"], &given(&[("u1", text)]), &[]).unwrap_err();
            assert!(error.to_string().contains(says), "{text}: {error}");
        }
        let error = InputSchedule::new(&["u1"], &given(&[("u1", "2*")]), &[]).unwrap_err();
        assert!(error.to_string().starts_with("--input u1=2*: "), "{error}");
    }
}
