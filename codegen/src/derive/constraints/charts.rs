//! Charts of D: other choices of the dependent speeds, for where the basis
//! of section 1 degenerates although the constraint rows stay independent
//! (MATH.md 1.1; the re-selection of independent coordinates of Wehage &
//! Haug, "Generalized coordinate partitioning for dimension reduction in
//! analysis of constrained dynamic systems", J. Mech. Design 104 (1982)).
//!
//! The basis `[I; -A_r^-1 A_s]` with the dependent speeds `u_r` is regular
//! exactly where the minor `det A_r(q)` is not zero. Pivots chosen at the
//! defaults can vanish elsewhere where A keeps full rank: the sleigh's
//! blade `-sin(theta) xdot + cos(theta) ydot = 0` solved for `ydot` divides
//! by `cos(theta)`. How well a chart fits at `q` is its pivot ratio
//!
//! ```text
//! rho_r(q) = |det A_r(q)| / prod_i |A_i(q)|   (at most 1, Hadamard)
//! ```
//!
//! and by Cauchy-Binet `sum_r det(A_r)^2 = det(A A^T)`, so wherever the rows
//! are independent some choice of dependent speeds has a ratio bounded
//! away from 0. The charts are chosen at build time on a fixed set of
//! sample configurations (each coordinate alone at `+-pi/2, pi/4, 3 pi/4,
//! 1, -2`, where trigonometric minors vanish, then pseudo-random points in
//! `[-pi, pi]^n`; parameters at their defaults): where every chart so far
//! degenerates, its ratio below [`DEGENERATE`] times that of the columns
//! Gaussian elimination with partial pivoting picks there, those columns
//! become a new chart, up to [`MOST_CHARTS`]. A chart that is only worse
//! than another somewhere (the caster robot's, by a factor 2.5 at a swivel
//! of `pi/2`) needs no other.
//! Points where the rows themselves are dependent (a Gram ratio
//! `det(A A^T) / prod_i |A_i|^2` below [`DEPENDENT_ROWS`]) are genuine
//! singularities, which no chart removes, and are skipped.
//!
//! Only the basis on the coordinates' rows has charts: a declared momentum
//! basis is the user's, and a basis chosen on the body rows of a symmetric
//! model ([`super::body_frame`]) depends on the shape alone.

use super::DistributionBasis;
use super::basis::{basis_with_dependent, default_point, pivots_of};
use crate::model::Model;
use crate::sym::MatrixError;

/// The most charts a model gets, its own basis included.
pub const MOST_CHARTS: usize = 4;

/// A chart degenerates at a sample point when its pivot ratio there is
/// below this fraction of the partially pivoted choice's.
pub const DEGENERATE: f64 = 1e-3;

/// A Gram ratio below this marks dependent rows: a genuine singularity.
pub const DEPENDENT_ROWS: f64 = 1e-9;

/// The other charts of D beside `primary`, each a basis with other
/// dependent speeds; none when `primary` is regular at every sample point
/// (or is the declared or body-frame basis).
pub fn alternative_charts(
    model: &mut Model,
    primary: &DistributionBasis,
) -> Result<Vec<DistributionBasis>, MatrixError> {
    if primary.body_frame || model.momentum_basis.is_some() || model.c() == 0 {
        return Ok(Vec::new());
    }
    let (n, c) = (model.n(), model.c());
    let mut charts = vec![primary.dependent.clone()];
    for point in sample_points(n) {
        if charts.len() == MOST_CHARTS {
            break;
        }
        let values = constraint_values(model, &point);
        if gram_ratio(&values, n, c) < DEPENDENT_ROWS {
            continue;
        }
        let Some(pivots) = pivots_of(values.clone(), n, c) else {
            continue;
        };
        let best = charts
            .iter()
            .map(|dependent| pivot_ratio(&values, n, dependent))
            .fold(0.0, f64::max);
        if best < DEGENERATE * pivot_ratio(&values, n, &pivots) {
            charts.push(pivots);
        }
    }
    charts
        .into_iter()
        .skip(1)
        .map(|dependent| basis_with_dependent(model, dependent))
        .collect()
}

/// `|det A_r| / prod_i |A_i|` for the `c x n` row-major values of A and
/// the dependent columns `r` (0 when a row vanishes).
pub fn pivot_ratio(values: &[f64], n: usize, dependent: &[usize]) -> f64 {
    let c = dependent.len();
    let minor: Vec<f64> = (0..c)
        .flat_map(|i| dependent.iter().map(move |&j| values[i * n + j]))
        .collect();
    let norms: f64 = (0..c)
        .map(|i| {
            values[i * n..(i + 1) * n]
                .iter()
                .map(|v| v * v)
                .sum::<f64>()
                .sqrt()
        })
        .product();
    if norms == 0.0 {
        return 0.0;
    }
    determinant(minor, c).abs() / norms
}

/// `det(A A^T) / prod_i |A_i|^2`, in `[0, 1]`.
fn gram_ratio(values: &[f64], n: usize, c: usize) -> f64 {
    let row = |i: usize| &values[i * n..(i + 1) * n];
    let gram: Vec<f64> = (0..c * c)
        .map(|at| {
            row(at / c)
                .iter()
                .zip(row(at % c))
                .map(|(a, b)| a * b)
                .sum()
        })
        .collect();
    let scale: f64 = (0..c).map(|i| gram[i * c + i]).product();
    if scale == 0.0 {
        return 0.0;
    }
    determinant(gram, c) / scale
}

/// The determinant of a `size x size` row-major matrix, by elimination with
/// partial pivoting.
fn determinant(mut m: Vec<f64>, size: usize) -> f64 {
    let mut det = 1.0;
    for k in 0..size {
        let pivot = (k..size)
            .max_by(|&a, &b| m[a * size + k].abs().total_cmp(&m[b * size + k].abs()))
            .unwrap_or(k);
        if m[pivot * size + k] == 0.0 {
            return 0.0;
        }
        if pivot != k {
            for j in 0..size {
                m.swap(k * size + j, pivot * size + j);
            }
            det = -det;
        }
        det *= m[k * size + k];
        for i in k + 1..size {
            let factor = m[i * size + k] / m[k * size + k];
            for j in k..size {
                m[i * size + j] -= factor * m[k * size + j];
            }
        }
    }
    det
}

/// A's values at the coordinates `point`, parameters at their defaults.
fn constraint_values(model: &mut Model, point: &[f64]) -> Vec<f64> {
    let defaults = default_point(model);
    let coordinates: Vec<_> = model.coordinates.iter().map(|c| c.symbol).collect();
    let value = |s| match coordinates.iter().position(|&c| c == s) {
        Some(i) => point[i],
        None => defaults(s),
    };
    model.constraint_matrix.evaluate(&mut model.store, &value)
}

/// The sample configurations of the module documentation.
fn sample_points(n: usize) -> Vec<Vec<f64>> {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
    let single = [FRAC_PI_2, -FRAC_PI_2, FRAC_PI_4, 3.0 * FRAC_PI_4, 1.0, -2.0];
    let mut points: Vec<Vec<f64>> = (0..n)
        .flat_map(|i| {
            single.iter().map(move |&v| {
                let mut point = vec![0.0; n];
                point[i] = v;
                point
            })
        })
        .collect();
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..32 {
        points.push((0..n).map(|_| PI * (2.0 * uniform() - 1.0)).collect());
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pivot_ratios_of_the_blade_row_are_the_heading_cosine_and_sine() {
        let theta: f64 = 0.3;
        let row = [-theta.sin(), theta.cos(), 0.0];
        assert!((pivot_ratio(&row, 3, &[1]) - theta.cos()).abs() < 1e-15);
        assert!((pivot_ratio(&row, 3, &[0]) - theta.sin()).abs() < 1e-15);
        assert_eq!(pivot_ratio(&row, 3, &[2]), 0.0);
    }

    #[test]
    fn parallel_rows_have_a_vanishing_gram_ratio() {
        let rows = [1.0, 2.0, 0.0, 2.0, 4.0, 0.0];
        assert!(gram_ratio(&rows, 3, 2).abs() < 1e-15);
        let rows = [1.0, 0.0, 0.0, 0.0, 3.0, 0.0];
        assert_eq!(gram_ratio(&rows, 3, 2), 1.0);
        assert_eq!(determinant(vec![0.0, 1.0, 1.0, 0.0], 2), -1.0);
    }
}
