//! Sets where the coordinates are singular and the mechanics is not: the
//! mass matrix `g(q)` loses rank there (INTERFACE.md section 4).
//!
//! Euler angles lose a degree of freedom at gimbal lock: the rates of the
//! z-x-z angles `(psi, theta, phi)` give the body's angular velocity through
//! a matrix of determinant `-sin(theta)` (Goldstein, Poole & Safko,
//! *Classical Mechanics*, 3rd ed., 2002, eq. 4.125), so `det g` carries
//! `sin(theta)^2` and the equations of motion divide by it. Euler
//! parameters (`orient` frames) have no such set.
//!
//! `det g` is taken exactly within [`DETERMINANT_PRODUCTS`] and its
//! numerator is tested, coordinate by coordinate, for vanishing on the set
//! `sin(q) = 0` (at `q = 0` and `q = pi`), else `cos(q) = 0` (at
//! `q = +-pi/2`), else `q = 0`. It vanishes there when its value at each
//! of [`SAMPLES`] random configurations (coordinates uniform in `[-3, 3]`,
//! parameters at their defaults) moved onto the set is below [`VANISHES`]
//! of its value at the configuration itself. A set of another shape (a
//! relation of two coordinates) is not named.
//!
//! A run checks each set's factor as a guard of the model's domain
//! ([`super::domain`]): it stops where the factor reaches zero, naming the
//! coordinate and suggesting `orient`.

use super::Model;
use super::domain::Guarded;
use crate::sym::zero::SplitMix;
use crate::sym::{Context, ExprId, Function, RationalFunction, SymError, SymbolId};
use chaplygin_runtime::system::Guard;
use std::f64::consts::{FRAC_PI_2, PI};

/// The term products the exact `det g` may take.
pub const DETERMINANT_PRODUCTS: u64 = 200_000;

/// The random configurations each candidate set is tested at.
pub const SAMPLES: usize = 3;

/// The relative value below which the determinant counts as vanishing.
pub const VANISHES: f64 = 1e-9;

/// The shape of a set of one coordinate `q`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Condition {
    /// `sin(q) = 0`.
    Sine,
    /// `cos(q) = 0`.
    Cosine,
    /// `q = 0`.
    Zero,
}

impl Condition {
    /// The values of `q` the set is tested at.
    fn points(self) -> &'static [f64] {
        match self {
            Condition::Sine => &[0.0, PI],
            Condition::Cosine => &[FRAC_PI_2, -FRAC_PI_2],
            Condition::Zero => &[0.0],
        }
    }
}

/// A set where `g` loses rank: `factor = 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct CoordinateSet {
    /// The coordinate, by index.
    pub coordinate: usize,
    /// Its shape.
    pub condition: Condition,
    /// The expression that vanishes on it: `sin(q)`, `cos(q)` or `q`.
    pub factor: ExprId,
}

impl CoordinateSet {
    /// `sin(theta) = 0`.
    pub fn describe(&self, cx: &Context) -> String {
        format!("{} = 0", cx.display(self.factor))
    }

    /// The report's warning.
    pub fn warning(&self, model: &Model, cx: &Context) -> String {
        format!(
            "mass matrix loses rank where {} (coordinates {}): a singularity of the \
             coordinates, not of the mechanics; orient(...) frames have none",
            self.describe(cx),
            self.coordinate_name(model)
        )
    }

    /// The guard a run checks: the factor must not vanish.
    pub fn guarded(&self, model: &Model, cx: &Context) -> Guarded {
        Guarded {
            description: format!(
                "the coordinates {}: {} must not vanish (the mass matrix loses rank there, a \
                 singularity of the coordinates); turn the frame with orient(...) instead",
                self.coordinate_name(model),
                cx.display(self.factor)
            ),
            expression: self.factor,
            guard: Guard::NonZero,
        }
    }

    /// The coordinate's declared name.
    pub fn coordinate_name<'m>(&self, model: &'m Model) -> &'m str {
        &model.coordinates[self.coordinate].declared.name
    }
}

/// The sets of one coordinate where `det g` vanishes; none when the exact
/// determinant is beyond its budget.
pub fn coordinate_sets(model: &Model, cx: &mut Context) -> Result<Vec<CoordinateSet>, SymError> {
    let Some(numerator) = determinant_numerator(model, cx) else {
        return Ok(Vec::new());
    };
    let mut sets = Vec::new();
    for coordinate in 0..model.n() {
        let found = [Condition::Sine, Condition::Cosine, Condition::Zero]
            .into_iter()
            .find(|&condition| vanishes_on(model, cx, &numerator, coordinate, condition));
        if let Some(condition) = found {
            let factor = factor_of(model, cx, coordinate, condition)?;
            sets.push(CoordinateSet {
                coordinate,
                condition,
                factor,
            });
        }
    }
    Ok(sets)
}

/// The numerator of `det g`, when it is written out, fits
/// [`DETERMINANT_PRODUCTS`] and is not constant.
fn determinant_numerator(model: &Model, cx: &mut Context) -> Option<RationalFunction> {
    if !model.mass_matrix.is_written_out() {
        return None;
    }
    let determinant = cx
        .attempt(DETERMINANT_PRODUCTS, |cx| {
            model.mass_matrix.determinant(cx.atoms())
        })?
        .ok()?;
    let numerator = RationalFunction::from_poly(determinant.numerator().clone());
    numerator.as_constant().is_none().then_some(numerator)
}

/// Whether `numerator` vanishes on the set `condition` of `coordinate`.
fn vanishes_on(
    model: &Model,
    cx: &mut Context,
    numerator: &RationalFunction,
    coordinate: usize,
    condition: Condition,
) -> bool {
    let mut generator = SplitMix::new(0x5eed_0f9e + coordinate as u64);
    (0..SAMPLES).all(|_| {
        let mut q: Vec<f64> = (0..model.n())
            .map(|_| generator.uniform(-3.0, 3.0))
            .collect();
        let scale = value_at(model, cx, numerator, &q).abs();
        condition.points().iter().all(|&value| {
            q[coordinate] = value;
            value_at(model, cx, numerator, &q).abs() <= VANISHES * scale
        })
    })
}

/// `form` at the configuration `q`, the parameters at their defaults.
fn value_at(model: &Model, cx: &mut Context, form: &RationalFunction, q: &[f64]) -> f64 {
    let defaults = model.parameter_defaults();
    let value_of = |s: SymbolId| {
        let coordinate = model.coordinates.iter().position(|c| c.symbol == s);
        let parameter = model.parameters.iter().position(|p| p.variable.symbol == s);
        match (coordinate, parameter) {
            (Some(i), _) => q[i],
            (None, Some(j)) => defaults[j],
            (None, None) => f64::NAN,
        }
    };
    cx.evaluate_normal(form, &value_of)
}

/// `sin(q)`, `cos(q)` or `q`.
fn factor_of(
    model: &Model,
    cx: &mut Context,
    coordinate: usize,
    condition: Condition,
) -> Result<ExprId, SymError> {
    let q = cx.symbol(model.coordinates[coordinate].symbol);
    match condition {
        Condition::Sine => cx.apply(Function::Sin, q),
        Condition::Cosine => cx.apply(Function::Cos, q),
        Condition::Zero => Ok(q),
    }
}

#[cfg(test)]
mod tests {
    use super::Condition;
    use crate::analysed_model;
    use crate::ir::Interpreter;

    /// The z-x-z ball's `det g = m^2 a b c sin(theta)^2` vanishes where
    /// `sin(theta) = 0` alone; its Euler-parameter twin's nowhere.
    #[test]
    fn the_zxz_angles_are_singular_where_sin_theta_vanishes() {
        let source = include_str!("../../../tests/models/chaplygin_ball_zxz.model");
        let analysed = analysed_model(source, &Interpreter).expect("analyses");
        let [set] = &analysed.constraints.coordinate_sets[..] else {
            panic!("one set: {:?}", analysed.constraints.coordinate_sets);
        };
        assert_eq!((set.coordinate, set.condition), (3, Condition::Sine));
        assert_eq!(set.describe(&analysed.cx), "sin(theta) = 0");
        let source = include_str!("../../../models/chaplygin_ball.model");
        let analysed = analysed_model(source, &Interpreter).expect("analyses");
        assert!(analysed.constraints.coordinate_sets.is_empty());
    }
}
