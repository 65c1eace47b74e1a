//! Expressions in the model language's syntax, evaluated on `f64`: its
//! operators `+ - * / ^`, its functions `sin cos tan sqrt exp ln asin acos
//! atan` and `atan2(y, x)`, `abs`,
//! and `pi`, of the names a `Scope` binds: the time `t`, the parameters
//! (at their values), a command's variables (a sweep variable, a speed:
//! their values given where the expression is evaluated), and where the
//! state is known the coordinates `q`, their velocities `dot(q)` and the
//! inputs. The command line's `--input`
//! laws, `--stop-when` conditions, `--initial` values and `--at`
//! operating points are read here (docs/INTERFACE.md sections 1, 3 and 5).

use chaplygin_codegen::syntax::{self, BinaryOperator, Expr, Value};

/// Why a text is not an expression of the names in scope.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExpressionError {
    /// A name the scope does not bind.
    #[error("{reason}")]
    UnknownName {
        /// The name.
        name: String,
        /// What it could have been.
        reason: String,
    },
    /// Not an expression, or one that misuses a function.
    #[error("{0}")]
    Invalid(String),
}

/// A function of the model language, or `abs`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Function {
    Sin,
    Cos,
    Tan,
    Sqrt,
    Exp,
    Ln,
    Asin,
    Acos,
    Atan,
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
            "asin" => Self::Asin,
            "acos" => Self::Acos,
            "atan" => Self::Atan,
            "abs" => Self::Abs,
            _ => return None,
        })
    }

    /// Its value, first and second derivatives at `x`.
    fn derivatives(self, x: f64) -> [f64; 3] {
        let root = (1.0 - x * x).sqrt();
        let [slope, curvature] = match self {
            Self::Sin => [x.cos(), -x.sin()],
            Self::Cos => [-x.sin(), -x.cos()],
            Self::Tan => [1.0 / x.cos().powi(2), 2.0 * x.tan() / x.cos().powi(2)],
            Self::Sqrt => [0.5 / x.sqrt(), -0.25 / (x * x.sqrt())],
            Self::Exp => [x.exp(), x.exp()],
            Self::Ln => [1.0 / x, -1.0 / (x * x)],
            Self::Asin => [1.0 / root, x / root.powi(3)],
            Self::Acos => [-1.0 / root, -x / root.powi(3)],
            Self::Atan => [1.0 / (1.0 + x * x), -2.0 * x / (1.0 + x * x).powi(2)],
            Self::Abs => [x.signum(), 0.0],
        };
        [self.at(x), slope, curvature]
    }

    /// `self(argument)` and its derivatives.
    fn jet(self, argument: Jet) -> Jet {
        argument.through(self.derivatives(argument.value))
    }

    fn at(self, x: f64) -> f64 {
        match self {
            Self::Sin => x.sin(),
            Self::Cos => x.cos(),
            Self::Tan => x.tan(),
            Self::Sqrt => x.sqrt(),
            Self::Exp => x.exp(),
            Self::Ln => x.ln(),
            Self::Asin => x.asin(),
            Self::Acos => x.acos(),
            Self::Atan => x.atan(),
            Self::Abs => x.abs(),
        }
    }
}

/// A value with its first and second derivatives in `t` or a variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Jet {
    /// The value.
    pub value: f64,
    /// Its first derivative.
    pub slope: f64,
    /// Its second derivative.
    pub curvature: f64,
}

impl Jet {
    /// A value that does not change with `t`.
    fn constant(value: f64) -> Jet {
        Jet {
            value,
            slope: 0.0,
            curvature: 0.0,
        }
    }

    /// Whether it does not change with `t`.
    fn is_constant(self) -> bool {
        self.slope == 0.0 && self.curvature == 0.0
    }

    /// `factor` times it.
    fn scaled(self, factor: f64) -> Jet {
        Jet {
            value: factor * self.value,
            slope: factor * self.slope,
            curvature: factor * self.curvature,
        }
    }

    /// `f(self)` from `f`, `f'` and `f''` at its value.
    fn through(self, [f, df, ddf]: [f64; 3]) -> Jet {
        if self.is_constant() {
            return Jet::constant(f);
        }
        Jet {
            value: f,
            slope: df * self.slope,
            curvature: ddf * self.slope * self.slope + df * self.curvature,
        }
    }
}

/// `a op b` and its derivatives from those of `a` and `b`.
fn binary_jet(operator: BinaryOperator, a: Jet, b: Jet) -> Jet {
    match operator {
        BinaryOperator::Add => Jet {
            value: a.value + b.value,
            slope: a.slope + b.slope,
            curvature: a.curvature + b.curvature,
        },
        BinaryOperator::Subtract => binary_jet(BinaryOperator::Add, a, b.scaled(-1.0)),
        BinaryOperator::Multiply => Jet {
            value: a.value * b.value,
            slope: a.slope * b.value + a.value * b.slope,
            curvature: a.curvature * b.value + 2.0 * a.slope * b.slope + a.value * b.curvature,
        },
        BinaryOperator::Divide => {
            let value = a.value / b.value;
            let slope = (a.slope - value * b.slope) / b.value;
            let curvature = (a.curvature - 2.0 * slope * b.slope - value * b.curvature) / b.value;
            Jet {
                value,
                slope,
                curvature,
            }
        }
        BinaryOperator::Power => power_jet(a, b),
    }
}

/// `a^b`: of a constant exponent `b` by `(a^b)' = b a^(b-1) a'`, else as
/// `exp(b ln a)`.
fn power_jet(a: Jet, b: Jet) -> Jet {
    let value = a.value.powf(b.value);
    if b.is_constant() {
        let n = b.value;
        return a.through([
            value,
            n * a.value.powf(n - 1.0),
            n * (n - 1.0) * a.value.powf(n - 2.0),
        ]);
    }
    let log = Jet {
        value: a.value.ln(),
        slope: a.slope / a.value,
        curvature: (a.curvature * a.value - a.slope * a.slope) / (a.value * a.value),
    };
    let exponent = binary_jet(BinaryOperator::Multiply, b, log);
    Jet {
        value,
        slope: value * exponent.slope,
        curvature: value * (exponent.curvature + exponent.slope * exponent.slope),
    }
}

/// `atan2(y, x)`: `theta' = N / D` with `N = x y' - y x'`,
/// `D = x^2 + y^2`.
fn atan2_jet(y: Jet, x: Jet) -> Jet {
    let numerator = x.value * y.slope - y.value * x.slope;
    let denominator = x.value * x.value + y.value * y.value;
    let numerator_slope = x.value * y.curvature - y.value * x.curvature;
    let denominator_slope = 2.0 * (x.value * x.slope + y.value * y.slope);
    Jet {
        value: y.value.atan2(x.value),
        slope: numerator / denominator,
        curvature: (numerator_slope * denominator - numerator * denominator_slope)
            / (denominator * denominator),
    }
}

/// What an expression may name besides `t`: the parameters, at their
/// values; variables, whose values come with the point; where the state is
/// known, the coordinates (and their velocities `dot(q)`); where the
/// inputs are known, the inputs.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Scope<'a> {
    /// The parameters' names and values.
    pub parameters: &'a [(&'a str, f64)],
    /// The variables, in order.
    pub variables: &'a [&'a str],
    /// The coordinates, in order.
    pub coordinates: &'a [&'a str],
    /// The inputs, in order.
    pub inputs: &'a [&'a str],
}

impl Scope<'_> {
    /// `name` is none of the names of the scope: what it could have been.
    fn unknown(&self, name: &str) -> String {
        let mut kinds = vec!["`t`", "a parameter"];
        if !self.variables.is_empty() {
            kinds.push("a variable");
        }
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

/// Where an expression is evaluated: the time, the variables, the
/// configuration, its velocity and the inputs, each as long as its names
/// in the [`Scope`] (empty where the scope has none).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Point<'a> {
    /// The time.
    pub t: f64,
    /// The variables.
    pub variables: &'a [f64],
    /// The coordinates.
    pub q: &'a [f64],
    /// Their velocities.
    pub qdot: &'a [f64],
    /// The inputs.
    pub u: &'a [f64],
}

/// The derivatives of an expression by the time, the coordinates, their
/// velocities and the inputs.
#[cfg(feature = "plan")]
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Gradient {
    /// By the time.
    pub t: f64,
    /// By the coordinates.
    pub q: Vec<f64>,
    /// By their velocities.
    pub qdot: Vec<f64>,
    /// By the inputs.
    pub u: Vec<f64>,
}

/// An expression resolved against a [`Scope`], the parameters' values
/// substituted.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Expression {
    /// A number.
    Number(f64),
    /// The time `t`.
    Time,
    /// The variable of this index.
    Variable(usize),
    /// The coordinate of this index.
    Coordinate(usize),
    /// The velocity of the coordinate of this index.
    Velocity(usize),
    /// The input of this index.
    Input(usize),
    /// A function of an expression.
    Call(Function, Box<Expression>),
    /// `atan2(y, x)`.
    Atan2(Box<Expression>, Box<Expression>),
    /// `-operand`.
    Negate(Box<Expression>),
    /// `left operator right`.
    Binary(BinaryOperator, Box<Expression>, Box<Expression>),
}

impl Expression {
    /// `text` read by the model language's parser (as the value of a
    /// section) and resolved against `scope`; the reason it is none, else.
    pub(crate) fn parse(text: &str, scope: &Scope<'_>) -> Result<Self, ExpressionError> {
        let model = syntax::parse_str(&format!("struct Input {{ input: {text} }}")).map_err(
            |diagnostics| {
                let messages: Vec<&str> = diagnostics.iter().map(|d| d.message.as_str()).collect();
                invalid(messages.join("; "))
            },
        )?;
        match model.sections.as_slice() {
            [section] => match &section.value {
                Value::Expr(expr) => resolve(expr, scope),
                Value::List(_) => Err(invalid("a list where a scalar expression belongs")),
            },
            _ => Err(invalid("not one expression")),
        }
    }

    /// Whether this expression or a part of it is `leaf`.
    fn contains(&self, leaf: &impl Fn(&Expression) -> bool) -> bool {
        leaf(self)
            || match self {
                Self::Call(_, operand) | Self::Negate(operand) => operand.contains(leaf),
                Self::Binary(_, left, right) | Self::Atan2(left, right) => {
                    left.contains(leaf) || right.contains(leaf)
                }
                _ => false,
            }
    }

    pub(crate) fn reads_time(&self) -> bool {
        self.contains(&|e| matches!(e, Self::Time))
    }

    /// Whether the expression reads the variable of index `i`.
    pub(crate) fn reads_variable(&self, i: usize) -> bool {
        self.contains(&|e| *e == Self::Variable(i))
    }

    /// Whether the expression reads the configuration or the velocity.
    pub(crate) fn reads_state(&self) -> bool {
        self.contains(&|e| matches!(e, Self::Coordinate(_) | Self::Velocity(_)))
    }

    /// The value and its time derivative at `t`, for an expression of `t`
    /// and the parameters alone (forward differentiation, exact to
    /// round-off); the state and the inputs read as constants.
    pub(crate) fn rate(&self, t: f64) -> (f64, f64) {
        let Jet { value, slope, .. } = self.jet(t);
        (value, slope)
    }

    /// The value and its first and second time derivatives at `t`, for an
    /// expression of `t` and the parameters alone; the state and the
    /// inputs read as constants.
    pub(crate) fn jet(&self, t: f64) -> Jet {
        self.jet_along(&|leaf| match leaf {
            Self::Time => Jet {
                value: t,
                slope: 1.0,
                curvature: 0.0,
            },
            _ => Jet::constant(f64::NAN),
        })
    }

    /// The value at `point` and the gradient by the time, the coordinates,
    /// their velocities and the inputs, each as long as `point`'s (forward
    /// differentiation, one pass per name, exact to round-off).
    #[cfg(feature = "plan")]
    pub(crate) fn gradient(&self, point: &Point<'_>) -> (f64, Gradient) {
        let by = |seed: &dyn Fn(&Self) -> bool| {
            let along = |leaf: &Self| Jet {
                value: leaf.at(point),
                slope: if seed(leaf) { 1.0 } else { 0.0 },
                curvature: 0.0,
            };
            self.jet_along(&along).slope
        };
        let gradient = Gradient {
            t: by(&|l| *l == Self::Time),
            q: (0..point.q.len())
                .map(|i| by(&|l| *l == Self::Coordinate(i)))
                .collect(),
            qdot: (0..point.qdot.len())
                .map(|i| by(&|l| *l == Self::Velocity(i)))
                .collect(),
            u: (0..point.u.len())
                .map(|i| by(&|l| *l == Self::Input(i)))
                .collect(),
        };
        (self.at(point), gradient)
    }

    /// The Hessian by `y = (t, q, qdot, u)`, each as long as `point`'s,
    /// row-major: the second derivatives along each `e_j` and each
    /// `e_j + e_k`, polarized, `H_jk = (D^2_{e_j + e_k} - D^2_{e_j} -
    /// D^2_{e_k}) / 2` (forward differentiation to second order, exact to
    /// round-off).
    #[cfg(feature = "plan")]
    pub(crate) fn hessian(&self, point: &Point<'_>) -> Vec<f64> {
        let (nq, nv) = (point.q.len(), point.qdot.len());
        let m = 1 + nq + nv + point.u.len();
        let position = |leaf: &Self| match *leaf {
            Self::Time => Some(0),
            Self::Coordinate(i) => Some(1 + i),
            Self::Velocity(i) => Some(1 + nq + i),
            Self::Input(i) => Some(1 + nq + nv + i),
            _ => None,
        };
        let curvature = |along: &[usize]| {
            let leaf = |leaf: &Self| Jet {
                value: leaf.at(point),
                slope: position(leaf)
                    .map_or(0.0, |j| along.iter().filter(|&&a| a == j).count() as f64),
                curvature: 0.0,
            };
            self.jet_along(&leaf).curvature
        };
        let pure: Vec<f64> = (0..m).map(|j| curvature(&[j])).collect();
        let mut hessian = vec![0.0; m * m];
        for j in 0..m {
            hessian[j * m + j] = pure[j];
            for k in 0..j {
                let mixed = 0.5 * (curvature(&[j, k]) - pure[j] - pure[k]);
                (hessian[j * m + k], hessian[k * m + j]) = (mixed, mixed);
            }
        }
        hessian
    }

    /// The value at `point` and its derivative in the variable of index
    /// `variable` (forward differentiation, exact to round-off); a name
    /// `point` does not give reads as NaN.
    pub(crate) fn slope(&self, point: &Point<'_>, variable: usize) -> (f64, f64) {
        let along = |leaf: &Self| Jet {
            value: leaf.read(point),
            slope: f64::from(u8::from(*leaf == Self::Variable(variable))),
            curvature: 0.0,
        };
        let Jet { value, slope, .. } = self.jet_along(&along);
        (value, slope)
    }

    /// A leaf's value at `point`, NaN where `point` does not give it.
    fn read(&self, point: &Point<'_>) -> f64 {
        let read = |values: &[f64], i: usize| values.get(i).copied().unwrap_or(f64::NAN);
        match self {
            Self::Time => point.t,
            Self::Variable(i) => read(point.variables, *i),
            Self::Coordinate(i) => read(point.q, *i),
            Self::Velocity(i) => read(point.qdot, *i),
            Self::Input(i) => read(point.u, *i),
            _ => f64::NAN,
        }
    }

    /// The value and its first and second derivatives along a path on
    /// which each leaf (the time, a variable, a coordinate, a velocity, an
    /// input) has the jet `leaf` gives: forward differentiation to second
    /// order, each operation by its chain rule
    /// (`(f o a)'' = f''(a) a'^2 + f'(a) a''`), exact to round-off.
    fn jet_along(&self, leaf: &dyn Fn(&Self) -> Jet) -> Jet {
        match self {
            Self::Number(value) => Jet::constant(*value),
            Self::Time
            | Self::Variable(_)
            | Self::Coordinate(_)
            | Self::Velocity(_)
            | Self::Input(_) => leaf(self),
            Self::Call(function, argument) => function.jet(argument.jet_along(leaf)),
            Self::Atan2(ordinate, abscissa) => {
                atan2_jet(ordinate.jet_along(leaf), abscissa.jet_along(leaf))
            }
            Self::Negate(operand) => operand.jet_along(leaf).scaled(-1.0),
            Self::Binary(operator, left, right) => {
                binary_jet(*operator, left.jet_along(leaf), right.jet_along(leaf))
            }
        }
    }

    /// The value at `point`.
    pub(crate) fn at(&self, point: &Point<'_>) -> f64 {
        match self {
            Self::Number(value) => *value,
            Self::Time => point.t,
            Self::Variable(i) => point.variables[*i],
            Self::Coordinate(i) => point.q[*i],
            Self::Velocity(i) => point.qdot[*i],
            Self::Input(i) => point.u[*i],
            Self::Call(function, argument) => function.at(argument.at(point)),
            Self::Atan2(y, x) => y.at(point).atan2(x.at(point)),
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

/// The value of `text`, an expression of the parameters (name and value)
/// in the model language; the reason it is none, else.
pub(crate) fn constant(text: &str, parameters: &[(&str, f64)]) -> Result<f64, ExpressionError> {
    let scope = Scope {
        parameters,
        ..Scope::default()
    };
    let law = Expression::parse(text, &scope)?;
    if law.reads_time() {
        return Err(invalid(
            "`t` is not known at the start: use numbers and parameters",
        ));
    }
    let value = law.at(&Point::default());
    if value.is_finite() {
        Ok(value)
    } else {
        Err(invalid(format!("the value {value} is not finite")))
    }
}

/// The index of `name` in `names`.
fn index(names: &[&str], name: &str) -> Option<usize> {
    names.iter().position(|n| *n == name)
}

fn resolve(expr: &Expr, scope: &Scope<'_>) -> Result<Expression, ExpressionError> {
    let resolved = |e: &Expr| resolve(e, scope).map(Box::new);
    Ok(match expr {
        Expr::Number { literal, .. } => Expression::Number(
            literal
                .parse()
                .map_err(|_| invalid(format!("`{literal}` is not a number")))?,
        ),
        Expr::Name(name) if name == "t" => Expression::Time,
        Expr::Name(name) => {
            let name = name.to_string();
            if let Some((_, value)) = scope.parameters.iter().find(|(p, _)| *p == name) {
                Expression::Number(*value)
            } else if let Some(i) = index(scope.variables, &name) {
                Expression::Variable(i)
            } else if let Some(i) = index(scope.coordinates, &name) {
                Expression::Coordinate(i)
            } else if let Some(i) = index(scope.inputs, &name) {
                Expression::Input(i)
            } else if name == "pi" {
                Expression::Number(std::f64::consts::PI)
            } else {
                let reason = scope.unknown(&name);
                return Err(ExpressionError::UnknownName { name, reason });
            }
        }
        Expr::Call {
            function, keywords, ..
        } if !keywords.is_empty() => {
            let name = &keywords[0].name;
            return Err(invalid(format!(
                "`{function}` takes no keyword argument such as `{name} = ...`"
            )));
        }
        Expr::Call {
            function,
            arguments,
            ..
        } if function == "dot" => match arguments.as_slice() {
            [Value::Expr(Expr::Name(name))] => index(scope.coordinates, &name.to_string())
                .map(Expression::Velocity)
                .ok_or_else(|| invalid(format!("`dot({name})`: `{name}` is not a coordinate")))?,
            _ => return Err(invalid("`dot` takes one coordinate")),
        },
        Expr::Call {
            function,
            arguments,
            ..
        } if function == "atan2" => match arguments.as_slice() {
            [Value::Expr(y), Value::Expr(x)] => Expression::Atan2(resolved(y)?, resolved(x)?),
            _ => return Err(invalid("`atan2` takes two scalar arguments, `atan2(y, x)`")),
        },
        Expr::Call {
            function,
            arguments,
            ..
        } => {
            let known = Function::named(&function.to_string()).ok_or_else(|| {
                invalid(format!(
                    "`{function}` is not one of sin, cos, tan, sqrt, exp, ln, asin, acos, atan, \
                     atan2, abs"
                ))
            })?;
            match arguments.as_slice() {
                [Value::Expr(argument)] => Expression::Call(known, resolved(argument)?),
                _ => return Err(invalid(format!("`{function}` takes one scalar argument"))),
            }
        }
        Expr::Field { field, .. } => {
            return Err(invalid(format!("a field `.{field}` is not a scalar of t")));
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

/// An [`ExpressionError::Invalid`].
fn invalid(reason: impl Into<String>) -> ExpressionError {
    ExpressionError::Invalid(reason.into())
}

#[cfg(test)]
mod tests {
    use super::{Expression, ExpressionError, Jet, Scope, constant};

    const NAMES: [(&str, f64); 2] = [("v", 2.0), ("rR", 0.5)];

    #[test]
    fn precedence_follows_the_model_language() {
        let value = |text| constant(text, &NAMES).expect("evaluates");
        assert_eq!(value("-v/rR"), -4.0);
        assert_eq!(value("2^3^2"), 512.0);
        assert_eq!(value("-2^2"), -4.0);
        assert_eq!(value("1 + 2*3 - (4 - 1)/3"), 6.0);
        assert_eq!(value("1.5e1 + 2E-1"), 15.2);
        assert_eq!(value("cos(pi) + sqrt(v*v)"), 1.0);
        assert_eq!(value("abs(-rR)"), 0.5);
    }

    /// The time derivative against the closed form.
    #[test]
    fn the_rate_is_the_time_derivative() {
        let scope = Scope {
            parameters: &NAMES,
            ..Scope::default()
        };
        let rate = |text| Expression::parse(text, &scope).expect("parses").rate(0.7);
        let (value, slope) = rate("v*sin(2*t) + t^3/rR - sqrt(exp(t))");
        let t: f64 = 0.7;
        assert!(
            (value - (2.0 * (2.0 * t).sin() + t.powi(3) / 0.5 - (t / 2.0).exp())).abs() < 1e-15
        );
        let exact = 4.0 * (2.0 * t).cos() + 3.0 * t * t / 0.5 - 0.5 * (t / 2.0).exp();
        assert!((slope - exact).abs() < 1e-14, "{slope} vs {exact}");
        assert_eq!(rate("2^t").1, 2f64.powf(t) * 2f64.ln());
        assert_eq!(rate("-cos(t)/tan(v)").1, t.sin() / 2f64.tan());
    }

    /// The second time derivative against the closed form, and against
    /// second differences of the values for every function and operator.
    #[test]
    fn the_jet_is_the_second_time_derivative() {
        let scope = Scope {
            parameters: &NAMES,
            ..Scope::default()
        };
        let jet = |text, t| Expression::parse(text, &scope).expect("parses").jet(t);
        let t: f64 = 0.7;
        let curvature = jet("v*sin(2*t) + t^3/rR - sqrt(exp(t))", t).curvature;
        let exact = -8.0 * (2.0 * t).sin() + 6.0 * t / 0.5 - 0.25 * (t / 2.0).exp();
        assert!((curvature - exact).abs() < 1e-13, "{curvature} vs {exact}");
        let h = 1e-4;
        for text in [
            "tan(t)*cos(t^2)",
            "ln(1 + t)/exp(-t)",
            "asin(t/v) - acos(t/v) + atan(3*t)",
            "atan2(t - 1, rR + t^2)",
            "t^t + 2^t + abs(t - 2)",
            "sqrt(t)*(1 - t)",
        ] {
            let second = (jet(text, t + h).value - 2.0 * jet(text, t).value
                + jet(text, t - h).value)
                / (h * h);
            let Jet { curvature, .. } = jet(text, t);
            assert!(
                (curvature - second).abs() < 1e-6 * second.abs().max(1.0),
                "{text}: {curvature} vs {second}"
            );
        }
    }

    #[cfg(feature = "plan")]
    #[test]
    fn the_gradient_is_the_closed_form_derivative() {
        use super::Point;
        let scope = Scope {
            parameters: &NAMES,
            coordinates: &["x", "y"],
            inputs: &["F"],
            ..Scope::default()
        };
        let cost =
            Expression::parse("v*dot(x)^2 + sin(y)*F^2 + atan2(y, x)", &scope).expect("parses");
        let (x, y, xdot, f) = (0.3, -1.2, 0.8, 2.5);
        let point = Point {
            t: 0.1,
            q: &[x, y],
            qdot: &[xdot, 0.4],
            u: &[f],
            ..Point::default()
        };
        let (value, gradient) = cost.gradient(&point);
        let r2 = x * x + y * y;
        let close = |a: f64, b: f64| assert!((a - b).abs() < 1e-14, "{a} vs {b}");
        close(value, 2.0 * xdot * xdot + y.sin() * f * f + y.atan2(x));
        close(gradient.q[0], -y / r2);
        close(gradient.q[1], y.cos() * f * f + x / r2);
        close(gradient.qdot[0], 4.0 * xdot);
        close(gradient.qdot[1], 0.0);
        close(gradient.u[0], 2.0 * y.sin() * f);
    }

    /// The derivative in a variable against the closed form, the other
    /// variable and `t` held.
    #[test]
    fn the_slope_is_the_derivative_in_a_variable() {
        let scope = Scope {
            parameters: &NAMES,
            variables: &["a", "b"],
            ..Scope::default()
        };
        let law = Expression::parse("-a/rR + b*sin(a^2) + atan2(b, a)", &scope).expect("parses");
        let (a, b) = (0.8f64, -1.3f64);
        let point = super::Point {
            variables: &[a, b],
            ..super::Point::default()
        };
        let (value, by_a) = law.slope(&point, 0);
        let exact_value = -a / 0.5 + b * (a * a).sin() + b.atan2(a);
        assert!(
            (value - exact_value).abs() < 1e-15,
            "{value} vs {exact_value}"
        );
        let exact_a = -1.0 / 0.5 + 2.0 * a * b * (a * a).cos() - b / (a * a + b * b);
        assert!((by_a - exact_a).abs() < 1e-14, "{by_a} vs {exact_a}");
        let exact_b = (a * a).sin() + a / (a * a + b * b);
        assert!((law.slope(&point, 1).1 - exact_b).abs() < 1e-15);
    }

    /// A function of the time, computed by `f64`'s own methods.
    type Law = fn(f64) -> f64;

    /// The inverse functions' values against `f64`'s, their rates against
    /// central differences of those values.
    #[test]
    fn inverse_functions_and_their_rates() {
        let scope = Scope {
            parameters: &NAMES,
            ..Scope::default()
        };
        let t: f64 = 0.3;
        let h = 1e-6;
        let laws: [(&str, Law); 5] = [
            ("asin(t)", f64::asin),
            ("acos(t/v)", |t| (t / 2.0).acos()),
            ("atan(3*t)", |t| (3.0 * t).atan()),
            ("atan2(t - 1, rR)", |t| (t - 1.0).atan2(0.5)),
            ("atan2(v, -t)", |t| 2f64.atan2(-t)),
        ];
        for (text, exact) in laws {
            let (value, slope) = Expression::parse(text, &scope).expect("parses").rate(t);
            assert_eq!(value, exact(t), "{text}");
            let difference = (exact(t + h) - exact(t - h)) / (2.0 * h);
            assert!(
                (slope - difference).abs() < 1e-8,
                "{text}: {slope} vs {difference}"
            );
        }
    }

    #[test]
    fn mistakes_are_named() {
        assert!(matches!(
            constant("w + 1", &NAMES),
            Err(ExpressionError::UnknownName { name, .. }) if name == "w"
        ));
        let invalid = |text| matches!(constant(text, &NAMES), Err(ExpressionError::Invalid(_)));
        assert!(invalid("(1 + 2"));
        assert!(invalid("1/0"));
        assert!(invalid("sinh(1)"));
        assert!(invalid("t + 1"));
    }
}
