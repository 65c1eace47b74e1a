//! Integrals of the constraints: combinations of rows with constant
//! coefficients that are exact (docs/INTERFACE.md section 4).
//!
//! A combination `w = sum_r mu_r a_r(q)` of the constraint rows, the
//! `mu_r` constant, is the differential of a function `F` when its curl
//! vanishes (Moore's mixed partials, on the combination):
//!
//! ```text
//! sum_r mu_r (d a_ri / d q_j - d a_rj / d q_i) = 0   for all i < j.
//! ```
//!
//! Every motion then keeps `F` constant: an integral, which lowers the
//! reachable dimension below `n - h` (Koon & Marsden; Bloch, *Nonholonomic
//! Mechanics and Control*, 2003). A car's two rear wheels give one: their
//! rolling rows `cos(theta) xdot + sin(theta) ydot -+ b thetadot - r phidot`
//! differ by `d(2 b theta + r phi_l - r phi_r)`, the rear differential's
//! integral.
//!
//! The rows exact alone are Moore's; this finds the combinations of the
//! others. The curls are evaluated modulo a prime at random points
//! ([`crate::sym::modular`]); the `mu` are the kernel of those values,
//! each entry reconstructed as a small rational and the combination
//! checked at further points (a non-zero value proves a candidate wrong;
//! zeros at every point are probable, wrong with probability below
//! `1e-15`). Where `w`'s entries are constant too, `F = sum_i w_i q_i` is
//! written out.

use super::at_points::curl;
use crate::model::Model;
use crate::sym::modular::{self, ModularError};
use crate::sym::residues::Values;
use crate::sym::{Context, ExprId, Rational};

/// How many random points decide the kernel, and how many more check it.
const KERNEL_POINTS: usize = 3;
const CHECK_POINTS: usize = 3;

/// The largest numerator or denominator of a coefficient `mu_r`.
const COEFFICIENT_BOUND: i64 = 1 << 20;

/// An integral of the constraints: `sum_r mu_r a_r = dF`.
#[derive(Clone, Debug, PartialEq)]
pub struct Integral {
    /// The rows combined, by index into the constraints, with their
    /// coefficients `mu_r`.
    pub rows: Vec<(usize, Rational)>,
    /// `F`, when the combination's entries are constant.
    pub function: Option<ExprId>,
}

impl Integral {
    /// The combination of rows in words: `rear_right_roll_1 - rear_left_roll_1`.
    pub fn combination(&self, model: &Model) -> String {
        let mut text = String::new();
        for (index, (row, mu)) in self.rows.iter().enumerate() {
            let sign = match (index, mu.is_negative()) {
                (0, false) => "",
                (0, true) => "-",
                (_, false) => " + ",
                (_, true) => " - ",
            };
            let magnitude = mu.abs();
            let factor = match magnitude.is_one() {
                true => String::new(),
                false => format!("{magnitude}*"),
            };
            text += &format!("{sign}{factor}{}", model.constraints[*row].name);
        }
        text
    }

    /// The integral in words: `F = const (combination)`, or the combination
    /// alone when `F` is not written out.
    pub fn describe(&self, model: &Model, cx: &Context) -> String {
        let combination = self.combination(model);
        match self.function {
            Some(function) => format!(
                "{} is constant ({combination} is its differential)",
                cx.display(function)
            ),
            None => format!("{combination} is the differential of a function"),
        }
    }
}

/// The integrals found among the rows that are not exact alone
/// (`exact_rows`, Moore's test); none when the rows are outside the class
/// evaluated modulo a prime.
pub(super) fn integrals(model: &Model, cx: &mut Context, exact_rows: &[bool]) -> Vec<Integral> {
    let candidates: Vec<usize> = (0..exact_rows.len()).filter(|&r| !exact_rows[r]).collect();
    if candidates.len() < 2 {
        return Vec::new();
    }
    let curls: Vec<Vec<ExprId>> = (candidates.iter())
        .map(|&row| curl(model, cx, &model.constraint_expressions.row_entries(row)))
        .collect();
    let roots: Vec<ExprId> = curls.concat();
    let Ok(values) = modular::at_defined_points(KERNEL_POINTS + CHECK_POINTS, |point| {
        Values::at(point).of(cx, &roots)
    }) else {
        return Vec::new();
    };
    let (pairs, columns) = (curls[0].len(), candidates.len());
    let deciding = curl_matrix(&values[..KERNEL_POINTS], columns, pairs);
    let checking = curl_matrix(&values[KERNEL_POINTS..], columns, pairs);
    modular::kernel(deciding, KERNEL_POINTS * pairs, columns)
        .into_iter()
        .filter(|mu| checking.chunks(columns).all(|row| dot(row, mu) == 0))
        .filter_map(|mu| coefficients(&candidates, &mu))
        .map(|rows| {
            let function = function(model, cx, &rows);
            Integral { rows, function }
        })
        .collect()
}

/// The row-major matrix whose row `(point, pair)` holds every candidate's
/// curl entry `pair` at `point`: its kernel is the combinations exact at
/// those points.
fn curl_matrix(values: &[Vec<u64>], candidates: usize, pairs: usize) -> Vec<u64> {
    let mut matrix = Vec::with_capacity(values.len() * pairs * candidates);
    for point in values {
        for pair in 0..pairs {
            matrix.extend((0..candidates).map(|r| point[r * pairs + pair]));
        }
    }
    matrix
}

fn dot(row: &[u64], vector: &[u64]) -> u64 {
    (row.iter().zip(vector)).fold(0, |sum, (&a, &v)| {
        modular::add(sum, modular::multiply(a, v, modular::PRIME))
    })
}

/// The kernel vector `mu` as small rationals on the candidate rows, its
/// zero entries left out and its first entry positive; `None` when an
/// entry is no small rational.
fn coefficients(candidates: &[usize], mu: &[u64]) -> Option<Vec<(usize, Rational)>> {
    let rows: Vec<(usize, Rational)> = (candidates.iter().zip(mu))
        .filter(|(_, residue)| **residue != 0)
        .map(|(&row, &residue)| {
            let (numerator, denominator) = modular::rational(residue, COEFFICIENT_BOUND)?;
            Some((row, Rational::new(numerator, denominator)?))
        })
        .collect::<Option<_>>()?;
    let flip = rows.first().is_some_and(|(_, mu)| mu.is_negative());
    Some(match flip {
        true => rows.into_iter().map(|(row, mu)| (row, mu.neg())).collect(),
        false => rows,
    })
}

/// `F = sum_i w_i q_i` where every entry `w_i` of the combination is free
/// of the coordinates, else `None`.
fn function(model: &Model, cx: &mut Context, rows: &[(usize, Rational)]) -> Option<ExprId> {
    let combination = combined_row(model, cx, rows);
    let coordinates = model.coordinate_symbols();
    let rates: Vec<ExprId> = (combination.iter())
        .flat_map(|&w| coordinates.iter().map(move |&q| (w, q)))
        .map(|(w, q)| cx.derivative(w, q))
        .collect();
    let constant = rates_vanish(cx, &rates).ok()?;
    constant.then(|| {
        let terms: Vec<ExprId> = (combination.iter().zip(&coordinates))
            .map(|(&w, &q)| {
                let q = cx.symbol(q);
                cx.mul2(w, q)
            })
            .collect();
        let sum = cx.add(&terms);
        match cx.normal(sum) {
            Ok(form) => cx.expression_of(&form),
            Err(_) => sum,
        }
    })
}

/// `w_i = sum_r mu_r a_ri`.
fn combined_row(model: &Model, cx: &mut Context, rows: &[(usize, Rational)]) -> Vec<ExprId> {
    (0..model.n())
        .map(|i| {
            let terms: Vec<ExprId> = (rows.iter())
                .map(|(row, mu)| {
                    let mu = cx.number(mu.clone());
                    cx.mul2(mu, *model.constraint_expressions.get(*row, i))
                })
                .collect();
            cx.add(&terms)
        })
        .collect()
}

/// Whether every one of `rates` vanishes at the random points.
fn rates_vanish(cx: &Context, rates: &[ExprId]) -> Result<bool, ModularError> {
    let values =
        modular::at_defined_points(KERNEL_POINTS, |point| Values::at(point).of(cx, rates))?;
    Ok(values.iter().flatten().all(|&v| v == 0))
}
