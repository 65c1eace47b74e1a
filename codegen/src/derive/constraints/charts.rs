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
//! by `cos(theta)`; the benchmark bicycle's basis chosen in the body frame,
//! with the rear wheel's rate independent, degenerates where the front
//! wheel turns across the frame. How well a chart fits at `q` is its pivot
//! ratio
//!
//! ```text
//! rho_r(q) = |det A_r(q)| / prod_i |A_i(q)|   (at most 1, Hadamard)
//! ```
//!
//! and by Cauchy-Binet `sum_r det(A_r)^2 = det(A A^T)`, so wherever the rows
//! are independent some choice of dependent speeds has a ratio bounded
//! away from 0: the one Gaussian elimination with partial pivoting picks
//! there (`chaplygin_runtime::monitor::partial_pivots`) is the reference.
//!
//! Every chart's singular set is located (the `search` module: points on random
//! lines through the configuration space where its minor vanishes). A
//! point where the rows themselves are dependent (a Gram ratio
//! `det(A A^T) / prod_i |A_i|^2` below [`DEPENDENT_ROWS`]) is a singularity
//! of the mechanics, which no chart removes. At any other point found,
//! unless some chart so far fits at least [`COVERED`] times the reference,
//! the reference's columns become a new chart, whose own singular set is
//! searched in turn, up to [`MOST_CHARTS`]. The rows are the basis's own:
//! the coordinates' rows `A(q)`, or for a basis chosen in the body frame
//! (MATH.md 4) the body rows, whose charts depend on the shape
//! alone. A declared momentum basis is the user's: where it degenerates
//! the runtime hands over to a chart chosen at run time
//! (`chaplygin_runtime::partition`), as it does wherever no chart derived
//! here fits.
//!
//! [`SingularSet`] records what was found for each chart and which other
//! chart covers it; the derivation report lists them.

mod search;

use super::DistributionBasis;
use super::basis::{basis_with_dependent, speed_names};
use super::body_frame::BodyFrame;
use crate::ir::{Backend, IrError};
use crate::model::Model;
use crate::sym::Context;
use crate::sym::{ExprId, Matrix, MatrixError, RationalFunction};
use chaplygin_runtime::monitor::{gram_ratio, partial_pivots, signed_pivot_ratio};
use chaplygin_runtime::nalgebra::DMatrix;
use search::{FrameRows, RowsAt};

pub use search::{LINES, SAMPLES};

/// The most charts a model gets, its own basis included.
pub const MOST_CHARTS: usize = 4;

/// A chart covers a point where its pivot ratio is at least this fraction
/// of the partially pivoted choice's there: where none does, the runtime
/// hands over to the run-time chart (the same fraction).
pub const COVERED: f64 = chaplygin_runtime::system::RUNTIME_CHART;

/// A Gram ratio below this marks dependent rows: a genuine singularity.
pub const DEPENDENT_ROWS: f64 = 1e-9;

/// The most points a [`SingularSet`] keeps (the search may find more).
pub const KEPT_POINTS: usize = 64;

/// The charts of D beside the model's basis, and where each degenerates.
#[derive(Clone, Debug)]
pub struct Charts {
    /// The other charts, each a basis with other dependent speeds.
    pub alternatives: Vec<DistributionBasis>,
    /// The singular set found for each chart, chart 0 (the model's basis)
    /// first.
    pub singular_sets: Vec<SingularSet>,
}

/// What the search found of one chart's singular set.
#[derive(Clone, Debug, PartialEq)]
pub struct SingularSet {
    /// The chart's minor `det A_r` written out, when it is short (its
    /// numerator in normal form: the set is where it vanishes).
    pub determinant: Option<String>,
    /// Configurations found on the set with the rows independent (at most
    /// [`KEPT_POINTS`]), each of all n coordinates.
    pub points: Vec<Vec<f64>>,
    /// Configurations found on the set where the rows are dependent.
    pub dependent_rows: Vec<Vec<f64>>,
    /// The other charts that fit best at `points`, none when there are no
    /// such points.
    pub cover: Option<Cover>,
}

/// Which charts cover a singular set's points, and how well.
#[derive(Clone, Debug, PartialEq)]
pub struct Cover {
    /// The charts that fit best at some point found, in increasing order.
    pub charts: Vec<usize>,
    /// The smallest, over the points found, of the best of those charts'
    /// pivot ratio over the partially pivoted choice's there.
    pub ratio: f64,
}

/// Why the charts could not be found.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ChartsError {
    /// A basis could not be derived.
    #[error(transparent)]
    Matrix(#[from] MatrixError),
    /// The rows could not be lowered for evaluation.
    #[error("the constraint rows: {0}")]
    Program(#[from] IrError),
}

/// Shapes where the body-frame constraint rows do not determine the group
/// velocities (the minor of the group's columns vanishes): where a
/// principally kinematic model's connection is singular. Found as the
/// charts' singular sets are (random lines through the shape coordinates,
/// the group at its identity, the parameters at their defaults); each
/// point gives all n coordinates; at most [`KEPT_POINTS`]. The rows run on
/// the engine `backend` makes.
pub fn group_singular_points(
    model: &Model,
    cx: &mut Context,
    backend: &dyn Backend,
) -> Result<Vec<Vec<f64>>, ChartsError> {
    let Some(symmetry) = &model.symmetry else {
        return Ok(Vec::new());
    };
    let group = symmetry.group_coordinates();
    let frame = Frame::of(model, cx, true)?;
    if !frame.body || model.c() != group.len() {
        return Ok(Vec::new());
    }
    let rows = FrameRows::new(model, cx, &frame.rows, frame.varying.clone(), backend)?;
    let mut points: Vec<Vec<f64>> = search::singular_points(&rows, &group)
        .into_iter()
        .map(|at| at.q)
        .collect();
    points.truncate(KEPT_POINTS);
    Ok(points)
}

/// The other charts of D beside `primary` and the singular sets of all;
/// none for a declared momentum basis or without constraints. The search
/// runs the rows on the engine `backend` makes.
pub fn alternative_charts(
    model: &Model,
    cx: &mut Context,
    primary: &DistributionBasis,
    backend: &dyn Backend,
) -> Result<Charts, ChartsError> {
    let none = Charts {
        alternatives: Vec::new(),
        singular_sets: Vec::new(),
    };
    if model.momentum_basis.is_some() || model.c() == 0 || model.k() == 0 {
        return Ok(none);
    }
    let frame = Frame::of(model, cx, primary.body_frame)?;
    let rows = FrameRows::new(model, cx, &frame.rows, frame.varying.clone(), backend)?;
    let mut charts = vec![primary.dependent.clone()];
    let mut found: Vec<Vec<RowsAt>> = Vec::new();
    while found.len() < charts.len() {
        let points = search::singular_points(&rows, &charts[found.len()]);
        cover_points(&mut charts, &points);
        found.push(points);
    }
    let singular_sets = found
        .iter()
        .enumerate()
        .map(|(i, points)| singular_set(model, cx, &frame, &charts, i, points))
        .collect();
    let alternatives = charts
        .into_iter()
        .skip(1)
        .map(|dependent| match primary.body_frame {
            true => super::basis::basis_in_body_frame(model, cx, dependent),
            false => basis_with_dependent(model, cx, dependent),
        })
        .collect::<Result<_, _>>()?;
    Ok(Charts {
        alternatives,
        singular_sets,
    })
}

/// Adds charts until each of `points` where the rows are independent is
/// covered (some chart fits at least [`COVERED`] times partial pivoting's
/// choice there) or [`MOST_CHARTS`] is reached: greedily, the partially
/// pivoted choice at an uncovered point that covers the most of them.
fn cover_points(charts: &mut Vec<Vec<usize>>, points: &[RowsAt]) {
    let references: Vec<(&RowsAt, Vec<usize>, f64)> = points
        .iter()
        .filter(|at| gram_ratio(&at.rows) >= DEPENDENT_ROWS)
        .filter_map(|at| {
            let reference = pivoted(&at.rows)?;
            let fit = signed_pivot_ratio(&at.rows, &reference).abs();
            Some((at, reference, fit))
        })
        .collect();
    let covers = |chart: &[usize], (at, _, fit): &(&RowsAt, Vec<usize>, f64)| {
        signed_pivot_ratio(&at.rows, chart).abs() >= COVERED * fit
    };
    loop {
        let uncovered: Vec<_> = references
            .iter()
            .filter(|point| !charts.iter().any(|chart| covers(chart, point)))
            .collect();
        if uncovered.is_empty() || charts.len() == MOST_CHARTS {
            return;
        }
        let Some((_, best, _)) = uncovered.iter().max_by_key(|(_, candidate, _)| {
            uncovered
                .iter()
                .filter(|point| covers(candidate, point))
                .count()
        }) else {
            return;
        };
        charts.push(best.clone());
    }
}

/// The rows a basis is eliminated on and the coordinates they depend on.
struct Frame {
    rows: Matrix<ExprId>,
    varying: Vec<usize>,
    body: bool,
}

impl Frame {
    fn of(model: &Model, cx: &mut Context, body: bool) -> Result<Frame, MatrixError> {
        let all: Vec<usize> = (0..model.n()).collect();
        let body_frame = match body {
            true => BodyFrame::of(model, cx)?,
            false => None,
        };
        Ok(match (body_frame, &model.symmetry) {
            (Some(frame), Some(symmetry)) => {
                let group = symmetry.group_coordinates();
                Frame {
                    rows: frame.constraints,
                    varying: all.into_iter().filter(|i| !group.contains(i)).collect(),
                    body: true,
                }
            }
            _ => Frame {
                rows: model.constraint_expressions.clone(),
                varying: all,
                body: false,
            },
        })
    }
}

/// The dependent speeds partial pivoting picks on `rows`, row by row (the
/// order the exact elimination of a basis pivots in); `None` where a pivot
/// vanishes.
fn pivoted(rows: &DMatrix<f64>) -> Option<Vec<usize>> {
    let mut pivots = vec![0; rows.nrows()];
    partial_pivots(rows, &mut pivots).then_some(pivots)
}

/// Chart `chart`'s singular set from the points found on it.
fn singular_set(
    model: &Model,
    cx: &mut Context,
    frame: &Frame,
    charts: &[Vec<usize>],
    chart: usize,
    points: &[RowsAt],
) -> SingularSet {
    let (regular, dependent): (Vec<&RowsAt>, Vec<&RowsAt>) = points
        .iter()
        .partition(|at| gram_ratio(&at.rows) >= DEPENDENT_ROWS);
    let relative = |at: &RowsAt, other: usize| {
        let reference = pivoted(&at.rows).map_or(0.0, |r| signed_pivot_ratio(&at.rows, &r).abs());
        signed_pivot_ratio(&at.rows, &charts[other]).abs() / reference
    };
    let best_other = |at: &RowsAt| {
        (0..charts.len())
            .filter(|&other| other != chart)
            .map(|other| (other, relative(at, other)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
    };
    let mut covering: Vec<usize> = Vec::new();
    let mut worst = f64::INFINITY;
    for at in &regular {
        let (other, ratio) = best_other(at).unwrap_or((chart, 0.0));
        if !covering.contains(&other) {
            covering.push(other);
        }
        worst = worst.min(ratio);
    }
    covering.sort_unstable();
    let cover = (!regular.is_empty()).then_some(Cover {
        charts: covering,
        ratio: worst,
    });
    let kept = |points: Vec<&RowsAt>| -> Vec<Vec<f64>> {
        points
            .into_iter()
            .take(KEPT_POINTS)
            .map(|at| at.q.clone())
            .collect()
    };
    SingularSet {
        determinant: determinant_text(model, cx, frame, &charts[chart]),
        points: kept(regular),
        dependent_rows: kept(dependent),
        cover,
    }
}

/// The longest text of a minor's determinant the report prints.
const SHORT: usize = 80;

/// The term products the determinant of a minor may take before the
/// report leaves it out: one that prints in [`SHORT`] characters has a
/// few terms, and its elimination takes far fewer products; the benchmark
/// bicycle's 5 x 5 minors spent a second of the derivation on the
/// analysis budget before they were found too long to print.
const SHORT_DETERMINANT_PRODUCTS: u64 = 20_000;

/// The numerator of `det A_r` on the frame's rows, written out, when the
/// rows are (the model's rows written out, as the exact basis needs them)
/// and it is short.
fn determinant_text(
    model: &Model,
    cx: &mut Context,
    frame: &Frame,
    dependent: &[usize],
) -> Option<String> {
    if !model.constraint_matrix.is_written_out() {
        return None;
    }
    let c = model.c();
    let rows: Vec<usize> = (0..c).collect();
    let minor = match frame.body {
        true => BodyFrame::of(model, cx)
            .ok()
            .flatten()?
            .exact_constraints(cx)
            .ok()?,
        false => model.constraint_matrix.clone(),
    };
    if !minor.is_written_out() {
        return None;
    }
    let minor = minor.submatrix(&rows, dependent);
    let determinant = cx
        .attempt(SHORT_DETERMINANT_PRODUCTS, |cx| {
            minor.determinant(cx.atoms())
        })?
        .ok()?;
    let numerator = RationalFunction::from_poly(determinant.numerator().clone());
    let expression = cx.expression_of(&numerator);
    let text = cx.display(expression).to_string();
    (text.len() <= SHORT).then_some(text)
}

/// The report's lines on the charts and their singular sets.
pub fn report_lines(model: &Model, basis: &DistributionBasis, charts: &Charts) -> Vec<String> {
    if charts.singular_sets.is_empty() {
        return Vec::new();
    }
    let frame = match basis.body_frame {
        true => "the shape coordinates (the body rows)",
        false => "the coordinates",
    };
    let mut lines = vec![format!(
        "singular sets of the charts of D ({LINES} random lines through {frame}, parameters at \
         their defaults):"
    )];
    let name = |i: usize| model.coordinates[i].declared.name.clone();
    let at = |q: &[f64], varying: &dyn Fn(usize) -> bool| {
        let values: Vec<String> = (0..q.len())
            .filter(|&i| varying(i))
            .map(|i| format!("{} = {:.4}", name(i), q[i]))
            .collect();
        values.join(", ")
    };
    let group = model
        .symmetry
        .as_ref()
        .filter(|_| basis.body_frame)
        .map(|symmetry| symmetry.group_coordinates())
        .unwrap_or_default();
    let varying = |i: usize| !group.contains(&i);
    let dependent = std::iter::once(&basis.dependent)
        .chain(charts.alternatives.iter().map(|chart| &chart.dependent));
    for (i, (set, dependent)) in charts.singular_sets.iter().zip(dependent).enumerate() {
        let speeds = speed_names(model, dependent, basis.body_frame).join(", ");
        let determinant = set
            .determinant
            .as_ref()
            .map_or_else(String::new, |text| format!(" where {text} = 0"));
        let found = match set.points.first() {
            None => "none found".to_string(),
            Some(q) => format!(
                "degenerates{determinant}: {} points found, e.g. {}",
                set.points.len(),
                at(q, &varying)
            ),
        };
        lines.push(format!("  chart {i} (dependent {speeds}): {found}"));
        if let Some(cover) = &set.cover {
            let charts: Vec<String> = cover.charts.iter().map(usize::to_string).collect();
            lines.push(format!(
                "    covered by chart {} (pivot ratio at least {:.3} times partial pivoting's there)",
                charts.join(" and "),
                cover.ratio
            ));
        }
        if let Some(q) = set.dependent_rows.first() {
            lines.push(format!(
                "    and where the rows are dependent (a singularity of the mechanics): {} points, e.g. {}",
                set.dependent_rows.len(),
                at(q, &varying)
            ));
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use crate::analysed_model;
    use crate::ir::Interpreter;

    /// The sleigh declared without its symmetry: its blade solved for
    /// `dot(y)` degenerates where `cos(theta) = 0`, solved for `dot(x)` where
    /// `sin(theta) = 0`; the lines find points of both sets to round-off,
    /// with the minors written out, and each chart covers the other's set
    /// as well as partial pivoting's choice does there.
    #[test]
    fn the_sleighs_singular_headings_are_found_and_covered() {
        let source = include_str!("../../../../tests/models/sleigh_no_symmetry.model");
        let analysed = analysed_model(source, &Interpreter).expect("analyses");
        let charts = &analysed.constraints.charts;
        assert_eq!(charts.alternatives.len(), 1);
        assert_eq!(charts.alternatives[0].dependent, [0]);
        let [by_y, by_x] = &charts.singular_sets[..] else {
            panic!("two sets: {:?}", charts.singular_sets);
        };
        assert_eq!(by_y.determinant.as_deref(), Some("cos(theta)"));
        assert!(!by_y.points.is_empty() && by_y.dependent_rows.is_empty());
        assert!(by_y.points.iter().all(|q| q[2].cos().abs() < 1e-8));
        assert!(by_x.points.iter().all(|q| q[2].sin().abs() < 1e-8));
        for (set, other) in [(by_y, 1), (by_x, 0)] {
            let cover = set.cover.as_ref().expect("covered");
            assert_eq!(cover.charts, [other]);
            assert!((cover.ratio - 1.0).abs() < 1e-12, "{cover:?}");
        }
    }
}
