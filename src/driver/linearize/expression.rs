//! The expressions of `--at NAME=EXPR`: numbers, names (the model's
//! parameters, the sweep variable, `pi`), `+ - * /`, `^` (binding tighter
//! than `*` and unary minus, right-associative), parentheses and the
//! functions `sin cos tan sqrt exp ln` of the model language (docs/INTERFACE.md
//! section 1), evaluated on `f64`.

use std::collections::BTreeMap;

/// Why an expression could not be evaluated.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum ExpressionError {
    /// A character or token out of place.
    #[error("`{text}`: {problem} at column {column}")]
    Syntax {
        /// The expression.
        text: String,
        /// What is wrong.
        problem: String,
        /// Where, from 1.
        column: usize,
    },
    /// A name that is neither a parameter, the sweep variable nor `pi`.
    #[error("`{text}`: unknown name `{name}` (known: {known})")]
    UnknownName {
        /// The expression.
        text: String,
        /// The name.
        name: String,
        /// The names there are.
        known: String,
    },
    /// The value is NaN or infinite.
    #[error("`{text}` is not finite ({value})")]
    NotFinite {
        /// The expression.
        text: String,
        /// Its value.
        value: f64,
    },
}

/// The value of `text` with `names` bound.
///
/// # Errors
/// [`ExpressionError`]: a syntax error, an unknown name, a non-finite value.
pub fn evaluate(text: &str, names: &BTreeMap<String, f64>) -> Result<f64, ExpressionError> {
    let mut parser = Parser {
        text,
        chars: text.char_indices().collect(),
        at: 0,
        names,
    };
    let value = parser.sum()?;
    parser.skip_spaces();
    if parser.at < parser.chars.len() {
        return Err(parser.syntax("unexpected character"));
    }
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ExpressionError::NotFinite {
            text: text.to_string(),
            value,
        })
    }
}

struct Parser<'a> {
    text: &'a str,
    chars: Vec<(usize, char)>,
    at: usize,
    names: &'a BTreeMap<String, f64>,
}

impl Parser<'_> {
    fn syntax(&self, problem: &str) -> ExpressionError {
        ExpressionError::Syntax {
            text: self.text.to_string(),
            problem: problem.to_string(),
            column: self.at + 1,
        }
    }

    fn skip_spaces(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.at += 1;
        }
    }

    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).map(|&(_, c)| c)
    }

    /// The next non-space character, taken if it is `expected`.
    fn take(&mut self, expected: char) -> bool {
        self.skip_spaces();
        let found = self.peek() == Some(expected);
        if found {
            self.at += 1;
        }
        found
    }

    /// `product (('+' | '-') product)*`
    fn sum(&mut self) -> Result<f64, ExpressionError> {
        let mut value = self.product()?;
        loop {
            if self.take('+') {
                value += self.product()?;
            } else if self.take('-') {
                value -= self.product()?;
            } else {
                return Ok(value);
            }
        }
    }

    /// `unary (('*' | '/') unary)*`
    fn product(&mut self) -> Result<f64, ExpressionError> {
        let mut value = self.unary()?;
        loop {
            if self.take('*') {
                value *= self.unary()?;
            } else if self.take('/') {
                value /= self.unary()?;
            } else {
                return Ok(value);
            }
        }
    }

    /// `'-' unary | power`
    fn unary(&mut self) -> Result<f64, ExpressionError> {
        if self.take('-') {
            Ok(-self.unary()?)
        } else {
            self.power()
        }
    }

    /// `atom ('^' unary)?`, right-associative.
    fn power(&mut self) -> Result<f64, ExpressionError> {
        let base = self.atom()?;
        if self.take('^') {
            Ok(base.powf(self.unary()?))
        } else {
            Ok(base)
        }
    }

    /// A number, a name, a call or a parenthesized sum.
    fn atom(&mut self) -> Result<f64, ExpressionError> {
        self.skip_spaces();
        match self.peek() {
            Some('(') => {
                self.at += 1;
                let value = self.sum()?;
                if self.take(')') {
                    Ok(value)
                } else {
                    Err(self.syntax("expected `)`"))
                }
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_alphabetic() || c == '_' => {
                let name = self.word();
                if self.take('(') {
                    let argument = self.sum()?;
                    if !self.take(')') {
                        return Err(self.syntax("expected `)`"));
                    }
                    self.call(&name, argument)
                } else {
                    self.name(&name)
                }
            }
            _ => Err(self.syntax("expected a number, a name or `(`")),
        }
    }

    fn word(&mut self) -> String {
        let start = self.at;
        while self.peek().is_some_and(|c| c.is_alphanumeric() || c == '_') {
            self.at += 1;
        }
        self.chars[start..self.at].iter().map(|&(_, c)| c).collect()
    }

    fn number(&mut self) -> Result<f64, ExpressionError> {
        let start = self.at;
        while self.peek().is_some_and(|c| c.is_ascii_digit() || c == '.') {
            self.at += 1;
        }
        if matches!(self.peek(), Some('e' | 'E')) {
            self.at += 1;
            if matches!(self.peek(), Some('+' | '-')) {
                self.at += 1;
            }
            while self.peek().is_some_and(|c| c.is_ascii_digit()) {
                self.at += 1;
            }
        }
        let literal: String = self.chars[start..self.at].iter().map(|&(_, c)| c).collect();
        literal.parse().map_err(|_| {
            self.at = start;
            self.syntax("malformed number")
        })
    }

    fn name(&self, name: &str) -> Result<f64, ExpressionError> {
        if name == "pi" {
            return Ok(std::f64::consts::PI);
        }
        self.names
            .get(name)
            .copied()
            .ok_or_else(|| ExpressionError::UnknownName {
                text: self.text.to_string(),
                name: name.to_string(),
                known: self
                    .names
                    .keys()
                    .map(String::as_str)
                    .chain(["pi"])
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    fn call(&self, function: &str, argument: f64) -> Result<f64, ExpressionError> {
        Ok(match function {
            "sin" => argument.sin(),
            "cos" => argument.cos(),
            "tan" => argument.tan(),
            "sqrt" => argument.sqrt(),
            "exp" => argument.exp(),
            "ln" => argument.ln(),
            _ => return Err(self.syntax(&format!("unknown function `{function}`"))),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> BTreeMap<String, f64> {
        BTreeMap::from([("v".to_string(), 2.0), ("rR".to_string(), 0.5)])
    }

    #[test]
    fn precedence_follows_the_model_language() {
        let value = |text| evaluate(text, &names()).expect("evaluates");
        assert_eq!(value("-v/rR"), -4.0);
        assert_eq!(value("2^3^2"), 512.0);
        assert_eq!(value("-2^2"), -4.0);
        assert_eq!(value("1 + 2*3 - (4 - 1)/3"), 6.0);
        assert_eq!(value("1.5e1 + 2E-1"), 15.2);
        assert_eq!(value("cos(pi) + sqrt(v*v)"), 1.0);
    }

    #[test]
    fn mistakes_are_named() {
        assert!(matches!(
            evaluate("w + 1", &names()),
            Err(ExpressionError::UnknownName { name, .. }) if name == "w"
        ));
        assert!(matches!(
            evaluate("(1 + 2", &names()),
            Err(ExpressionError::Syntax { column: 7, .. })
        ));
        assert!(matches!(
            evaluate("1/0", &names()),
            Err(ExpressionError::NotFinite { .. })
        ));
        assert!(matches!(
            evaluate("sinh(1)", &names()),
            Err(ExpressionError::Syntax { .. })
        ));
    }
}
