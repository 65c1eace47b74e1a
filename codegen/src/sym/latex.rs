//! LaTeX for expressions and matrices of a [`Store`].
//!
//! The printer follows the text printer ([`Store::display`]) in structure
//! and in the fewest parentheses it needs (sum < product < power < atom),
//! and writes the math as a paper would:
//!
//! ```text
//! a/b, x^-1       \frac{a}{b}, \frac{1}{x}       (a product's negative powers and
//!                                                 its coefficient's denominator)
//! x^2, x^(3/2)    x^{2}, x^{\frac{3}{2}}
//! x^(1/2)         \sqrt{x}
//! sin(phi)        \sin\phi; sin(theta + phi) -> \sin(\theta + \phi); sin(x)^2 -> \sin^{2}x
//! exp, ln, tan    \exp, \ln, \tan, as sin
//! asin, acos, atan  \arcsin, \arccos, \arctan, as sin
//! atan2(y, x)     \operatorname{atan2}(y, x)
//! dot(x)          \dot{x}
//! ```
//!
//! In a product the elementary functions come last (`u \sin\phi`, never
//! `\sin\phi u`, which reads as the sine of a product).
//!
//! Names: a name splits at its first inner underscore, or else before its
//! trailing digits, into a base and a subscript (`theta1` ->
//! `\theta_{1}`, `u_torso` -> `u_{\mathrm{torso}}`). Each part is a Greek
//! macro when it names a Greek letter (`phi` -> `\phi`, `Omega` ->
//! `\Omega`), itself when it is one character or all digits, and an upright
//! word otherwise (`jt` -> `\mathrm{jt}`, `group` -> `\mathrm{group}`), so
//! that a multi-letter name never reads as a product of letters.

use super::expr::{ExprId, Function, Node, Store, SymbolKind};
use super::number::Rational;

/// Binding strength: sum < product < power < function call < atom.
const SUM: u8 = 1;
const PRODUCT: u8 = 2;
const POWER: u8 = 3;
const CALL: u8 = 4;
const ATOM: u8 = 5;

/// The Greek letters LaTeX has macros for, spelled as the macro names.
const GREEK: [&str; 36] = [
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "varepsilon",
    "zeta",
    "eta",
    "theta",
    "vartheta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "pi",
    "rho",
    "varrho",
    "sigma",
    "varsigma",
    "tau",
    "upsilon",
    "phi",
    "varphi",
    "chi",
    "psi",
    "omega",
    "Gamma",
    "Delta",
    "Theta",
    "Lambda",
    "Xi",
    "Sigma",
    "Phi",
    "Omega",
];

impl Store {
    /// The expression as LaTeX math (no surrounding `$`).
    pub fn latex(&self, id: ExprId) -> String {
        Latex { store: self }.render(id, 0)
    }

    /// A `rows x columns` matrix of expressions (row-major `entries`) as a
    /// `bmatrix`: `\begin{bmatrix} a & b \\ c & d \end{bmatrix}`.
    pub fn latex_matrix(&self, entries: &[ExprId], columns: usize) -> String {
        let cells: Vec<String> = entries.iter().map(|&e| self.latex(e)).collect();
        bmatrix(&cells, columns)
    }
}

/// Cells already in LaTeX (row-major, `columns` per row) as a `bmatrix`.
pub fn bmatrix(cells: &[String], columns: usize) -> String {
    let rows: Vec<String> = cells
        .chunks(columns.max(1))
        .map(|row| row.join(" & "))
        .collect();
    format!(
        "\\begin{{bmatrix}} {} \\end{{bmatrix}}",
        rows.join(" \\\\ ")
    )
}

/// A symbol's name as LaTeX: base and subscript, Greek letters as macros
/// (the rule of the module documentation).
pub fn latex_name(name: &str) -> String {
    match split_name(name) {
        (base, Some(subscript)) => format!("{}_{{{}}}", latex_word(base), latex_word(subscript)),
        (base, None) => latex_word(base),
    }
}

/// The time derivative of the quantity `name`, the dot on its base
/// (`theta1` -> `\dot{\theta}_{1}`, `x` -> `\dot{x}`).
pub fn latex_rate(name: &str) -> String {
    match split_name(name) {
        (base, Some(subscript)) => {
            format!(
                "\\dot{{{}}}_{{{}}}",
                latex_word(base),
                latex_word(subscript)
            )
        }
        (base, None) => format!("\\dot{{{}}}", latex_word(base)),
    }
}

/// `(base, subscript)`: at the first inner underscore, else before trailing digits.
fn split_name(name: &str) -> (&str, Option<&str>) {
    if let Some(at) = name.find('_')
        && at > 0
        && at + 1 < name.len()
    {
        return (&name[..at], Some(&name[at + 1..]));
    }
    let stem = name.trim_end_matches(|c: char| c.is_ascii_digit());
    if !stem.is_empty() && stem.len() < name.len() {
        (stem, Some(&name[stem.len()..]))
    } else {
        (name, None)
    }
}

fn latex_word(word: &str) -> String {
    if GREEK.contains(&word) {
        format!("\\{word}")
    } else if word.chars().count() == 1 || word.chars().all(|c| c.is_ascii_digit()) {
        word.to_string()
    } else {
        format!("\\mathrm{{{}}}", word.replace('_', "\\_"))
    }
}

fn rational(value: &Rational) -> String {
    if value.is_integer() {
        return value.to_string();
    }
    let sign = if value.is_negative() { "-" } else { "" };
    let magnitude = value.abs();
    format!(
        "{sign}\\frac{{{}}}{{{}}}",
        magnitude.numerator(),
        magnitude.denominator()
    )
}

/// The LaTeX command of a function: its name, but `\arcsin`, `\arccos`
/// and `\arctan` for the inverse functions.
fn command(function: Function) -> String {
    match function {
        Function::Asin => "\\arcsin".to_string(),
        Function::Acos => "\\arccos".to_string(),
        Function::Atan => "\\arctan".to_string(),
        _ => format!("\\{}", function.name()),
    }
}

struct Latex<'a> {
    store: &'a Store,
}

impl Latex<'_> {
    /// `id`, parenthesized when it binds more loosely than `context`.
    fn render(&self, id: ExprId, context: u8) -> String {
        let body = self.node(id);
        if self.strength(id) < context {
            format!("({body})")
        } else {
            body
        }
    }

    fn strength(&self, id: ExprId) -> u8 {
        match self.store.node(id) {
            Node::Add(_) => SUM,
            Node::Number(v) if v.is_negative() => SUM,
            Node::Mul(factors) if self.coefficient(factors).0.is_negative() => SUM,
            Node::Number(v) if !v.is_integer() => PRODUCT,
            Node::Mul(_) => PRODUCT,
            Node::Pow(_, exponent) if exponent.is_negative() => PRODUCT,
            Node::Pow(..) => POWER,
            Node::Call(..) => CALL,
            Node::Number(_) | Node::Symbol(_) | Node::Atan2(..) => ATOM,
        }
    }

    fn node(&self, id: ExprId) -> String {
        match self.store.node(id) {
            Node::Number(value) => rational(value),
            Node::Symbol(symbol) => self.symbol(*symbol),
            Node::Add(terms) => self.sum(terms),
            Node::Mul(factors) => {
                let (coefficient, rest) = self.coefficient(factors);
                self.product(&coefficient, rest)
            }
            Node::Pow(_, exponent) if exponent.is_negative() => self.product(&Rational::ONE, &[id]),
            Node::Pow(base, exponent) => self.power(*base, exponent),
            Node::Call(function, argument) => {
                format!("{}{}", command(*function), self.argument(*argument))
            }
            Node::Atan2(y, x) => format!(
                "\\operatorname{{atan2}}({}, {})",
                self.render(*y, 0),
                self.render(*x, 0)
            ),
        }
    }

    fn symbol(&self, symbol: super::SymbolId) -> String {
        let info = self.store.symbol_info(symbol);
        match info.kind {
            SymbolKind::Velocity(coordinate) => {
                latex_rate(&self.store.symbol_info(coordinate).name)
            }
            _ => latex_name(&info.name),
        }
    }

    /// A function's argument: `\phi` and ` x` bare, anything else in parentheses.
    fn argument(&self, argument: ExprId) -> String {
        let text = self.node(argument);
        if self.strength(argument) < ATOM {
            format!("({text})")
        } else if text.starts_with('\\') {
            text
        } else {
            format!(" {text}")
        }
    }

    /// A product's constant coefficient (1 when it has none) and its other factors.
    fn coefficient<'f>(&self, factors: &'f [ExprId]) -> (Rational, &'f [ExprId]) {
        match self.store.node(factors[0]) {
            Node::Number(value) => (value.clone(), &factors[1..]),
            _ => (Rational::ONE, factors),
        }
    }

    fn sum(&self, terms: &[ExprId]) -> String {
        let mut text = String::new();
        for (i, &term) in terms.iter().enumerate() {
            let (coefficient, factors) = match self.store.node(term) {
                Node::Number(value) => (value.clone(), &[][..]),
                Node::Mul(factors) => self.coefficient(factors),
                _ => (Rational::ONE, std::slice::from_ref(&terms[i])),
            };
            let negative = coefficient.is_negative();
            text.push_str(match (i, negative) {
                (0, true) => "-",
                (0, false) => "",
                (_, true) => " - ",
                (_, false) => " + ",
            });
            let magnitude = coefficient.abs();
            if factors.is_empty() {
                text.push_str(&rational(&magnitude));
            } else if factors.len() == 1 && magnitude.is_one() {
                text.push_str(&self.render(factors[0], SUM + 1));
            } else {
                text.push_str(&self.product(&magnitude, factors));
            }
        }
        text
    }

    /// `coefficient * factors`, a quotient when there is a denominator:
    /// the coefficient's numerator and the positive powers above, its
    /// denominator and the negative powers below.
    fn product(&self, coefficient: &Rational, factors: &[ExprId]) -> String {
        let sign = if coefficient.is_negative() { "-" } else { "" };
        let magnitude = coefficient.abs();
        let (below, above): (Vec<ExprId>, Vec<ExprId>) = self
            .calls_last(factors)
            .into_iter()
            .partition(|&f| matches!(self.store.node(f), Node::Pow(_, e) if e.is_negative()));
        let mut numerator: Vec<String> = Vec::new();
        if !magnitude.numerator().is_one() {
            numerator.push(magnitude.numerator().to_string());
        }
        let mut denominator: Vec<String> = Vec::new();
        if !magnitude.denominator().is_one() {
            denominator.push(magnitude.denominator().to_string());
        }
        let numerator_factors = above;
        let alone = |count: usize| if count == 1 { 0 } else { PRODUCT + 1 };
        let numerator_context = alone(numerator.len() + numerator_factors.len());
        let denominator_context = alone(denominator.len() + below.len());
        let standalone = denominator.is_empty() && below.is_empty();
        for &factor in &numerator_factors {
            let context = if standalone {
                PRODUCT + 1
            } else {
                numerator_context
            };
            numerator.push(self.render(factor, context));
        }
        for &factor in &below {
            denominator.push(self.reciprocal(factor, denominator_context));
        }
        let top = if numerator.is_empty() {
            "1".to_string()
        } else {
            numerator.join(" ")
        };
        if denominator.is_empty() {
            format!("{sign}{top}")
        } else {
            format!("{sign}\\frac{{{top}}}{{{}}}", denominator.join(" "))
        }
    }

    /// The factors with the calls and their powers (`\sin^{2}\phi`,
    /// `\frac{1}{\cos\phi}`) moved after the others, each group in order.
    fn calls_last(&self, factors: &[ExprId]) -> Vec<ExprId> {
        let is_call = |factor: &ExprId| match self.store.node(*factor) {
            Node::Call(..) | Node::Atan2(..) => true,
            Node::Pow(base, _) => {
                matches!(self.store.node(*base), Node::Call(..) | Node::Atan2(..))
            }
            _ => false,
        };
        let (calls, plain): (Vec<ExprId>, Vec<ExprId>) = factors.iter().partition(|f| is_call(f));
        plain.into_iter().chain(calls).collect()
    }

    /// A power with a non-negative exponent; `\sqrt` for one half.
    fn power(&self, base: ExprId, exponent: &Rational) -> String {
        if exponent == &Rational::HALF {
            return format!("\\sqrt{{{}}}", self.render(base, 0));
        }
        let exponent = if exponent.is_integer() {
            exponent.to_string()
        } else {
            rational(exponent)
        };
        if let Node::Call(function, argument) = self.store.node(base) {
            return format!(
                "{}^{{{exponent}}}{}",
                command(*function),
                self.argument(*argument)
            );
        }
        format!("{}^{{{exponent}}}", self.render(base, POWER + 1))
    }

    /// `base^(-e)` written as `base^e`, for a denominator.
    fn reciprocal(&self, factor: ExprId, context: u8) -> String {
        let Node::Pow(base, exponent) = self.store.node(factor) else {
            return self.render(factor, context);
        };
        let positive = exponent.neg();
        if positive.is_one() {
            self.render(*base, context)
        } else {
            self.power(*base, &positive)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::latex_name;
    use crate::sym::{ExprId, Function, Rational, Store, SymbolKind};

    /// A store with the symbols `x theta phi r m u_torso` and `dot(x)`, `dot(theta1)`.
    struct Fixture {
        store: Store,
    }

    impl Fixture {
        fn new() -> Fixture {
            let mut store = Store::new();
            for name in ["x", "theta", "phi", "theta1"] {
                store.declare(name, SymbolKind::Coordinate);
            }
            for name in ["r", "m", "jt"] {
                store.declare(name, SymbolKind::Parameter);
            }
            store.declare("u_torso", SymbolKind::Auxiliary);
            Fixture { store }
        }

        fn var(&mut self, name: &str) -> ExprId {
            let symbol = self.store.find_symbol(name).expect("declared");
            self.store.symbol(symbol)
        }

        fn dot(&mut self, name: &str) -> ExprId {
            let coordinate = self.store.find_symbol(name).expect("declared");
            let velocity = self.store.velocity_of(coordinate);
            self.store.symbol(velocity)
        }

        fn call(&mut self, function: Function, argument: ExprId) -> ExprId {
            self.store.apply(function, argument).expect("defined")
        }

        fn number(&mut self, numerator: i64, denominator: i64) -> ExprId {
            let value = Rational::new(numerator, denominator).expect("nonzero denominator");
            self.store.number(value)
        }

        fn latex(&self, id: ExprId) -> String {
            self.store.latex(id)
        }
    }

    #[test]
    fn names_split_into_greek_bases_and_subscripts() {
        assert_eq!(latex_name("theta1"), "\\theta_{1}");
        assert_eq!(latex_name("u_torso"), "u_{\\mathrm{torso}}");
        assert_eq!(latex_name("jt"), "\\mathrm{jt}");
        assert_eq!(latex_name("Omega"), "\\Omega");
        assert_eq!(latex_name("varphi"), "\\varphi");
        assert_eq!(latex_name("x_2"), "x_{2}");
        assert_eq!(latex_name("alpha12"), "\\alpha_{12}");
        assert_eq!(latex_name("m"), "m");
        assert_eq!(latex_name("x_"), "\\mathrm{x\\_}");
    }

    #[test]
    fn velocities_are_dotted() {
        let mut f = Fixture::new();
        let x = f.dot("x");
        let theta1 = f.dot("theta1");
        assert_eq!(f.latex(x), "\\dot{x}");
        assert_eq!(f.latex(theta1), "\\dot{\\theta}_{1}");
    }

    #[test]
    fn quotients_are_fractions() {
        let mut f = Fixture::new();
        let (m, r, x) = (f.var("m"), f.var("r"), f.var("x"));
        let ratio = f.store.div(x, m).expect("nonzero");
        assert_eq!(f.latex(ratio), "\\frac{x}{m}");
        let half = f.number(1, 2);
        let xdot = f.dot("x");
        let square = f.store.mul2(xdot, xdot);
        let kinetic = f.store.mul(&[half, m, square]);
        assert_eq!(f.latex(kinetic), "\\frac{m \\dot{x}^{2}}{2}");
        let r_squared = f.store.mul2(r, r);
        let mr2 = f.store.mul2(m, r_squared);
        let inverse = f.store.div(x, mr2).expect("nonzero");
        assert_eq!(f.latex(inverse), "\\frac{x}{m r^{2}}");
        let minus_three_halves = f.number(-3, 2);
        assert_eq!(f.latex(minus_three_halves), "-\\frac{3}{2}");
    }

    #[test]
    fn functions_take_bare_atoms_and_parenthesized_sums() {
        let mut f = Fixture::new();
        let (theta, phi, x) = (f.var("theta"), f.var("phi"), f.var("x"));
        let sine = f.call(Function::Sin, phi);
        assert_eq!(f.latex(sine), "\\sin\\phi");
        let angle = f.store.add2(theta, phi);
        let cosine = f.call(Function::Cos, angle);
        assert_eq!(f.latex(cosine), "\\cos(\\theta + \\phi)");
        let exponential = f.call(Function::Exp, x);
        assert_eq!(f.latex(exponential), "\\exp x");
        let logarithm = f.call(Function::Ln, x);
        assert_eq!(f.latex(logarithm), "\\ln x");
        let square = f.store.mul2(sine, sine);
        assert_eq!(f.latex(square), "\\sin^{2}\\phi");
        let root = f.store.sqrt(x).expect("defined");
        assert_eq!(f.latex(root), "\\sqrt{x}");
        let inverse_tangent = f.call(Function::Atan, x);
        assert_eq!(f.latex(inverse_tangent), "\\arctan x");
        let inverse_sine = f.call(Function::Asin, angle);
        assert_eq!(f.latex(inverse_sine), "\\arcsin(\\theta + \\phi)");
        let heading = f.store.atan2(phi, x).expect("defined");
        assert_eq!(f.latex(heading), "\\operatorname{atan2}(\\phi, x)");
    }

    /// The snakeboard's `alpha1` equation, `-(sin(phi)/r) u1` (MATH.md 3.1).
    #[test]
    fn products_put_functions_last_and_signs_first() {
        let mut f = Fixture::new();
        let (phi, r, u) = (f.var("phi"), f.var("r"), f.var("u_torso"));
        let sine = f.call(Function::Sin, phi);
        let numerator = f.store.mul2(sine, u);
        let ratio = f.store.div(numerator, r).expect("nonzero");
        let negated = f.store.neg(ratio);
        assert_eq!(
            f.latex(negated),
            "-\\frac{u_{\\mathrm{torso}} \\sin\\phi}{r}"
        );
    }

    #[test]
    fn sums_and_powers_parenthesize_by_precedence() {
        let mut f = Fixture::new();
        let (x, m, r) = (f.var("x"), f.var("m"), f.var("r"));
        let sum = f.store.add2(x, m);
        let minus_r = f.store.neg(r);
        let difference = f.store.add2(x, minus_r);
        let product = f.store.mul2(sum, difference);
        let text = f.latex(product);
        assert!(
            text == "(x + m) (x - r)" || text == "(x - r) (x + m)",
            "{text}"
        );
        let two = f.number(2, 1);
        let squared = f.store.pow(sum, Rational::integer(2)).expect("defined");
        let twice = f.store.mul2(two, squared);
        let shifted = f.store.add2(twice, minus_r);
        assert_eq!(f.latex(shifted), "-r + 2 (x + m)^{2}");
        let over_sum = f.store.div(r, sum).expect("nonzero");
        assert_eq!(f.latex(over_sum), "\\frac{r}{x + m}");
        let three_halves = f
            .store
            .pow(x, Rational::new(3, 2).expect("valid"))
            .expect("defined");
        assert_eq!(f.latex(three_halves), "x^{\\frac{3}{2}}");
    }

    #[test]
    fn matrices_are_bmatrices() {
        let mut f = Fixture::new();
        let (m, jt) = (f.var("m"), f.var("jt"));
        let zero = f.number(0, 1);
        let text = f.store.latex_matrix(&[m, zero, zero, jt], 2);
        assert_eq!(
            text,
            "\\begin{bmatrix} m & 0 \\\\ 0 & \\mathrm{jt} \\end{bmatrix}"
        );
    }
}
