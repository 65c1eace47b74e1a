//! `figure4.png`: Figure 4 of Duindam & Stramigioli (2004), the snakeboard
//! under the energy-based controller (MATH.md 3.2).
//!
//! The closed loop conserves `Hbar + Hc`, and the wheel pair `(alpha3, xw)`
//! keeps its own energy, so the remaining energy
//! `H(alpha1, alpha2, xt) = alpha1^2/(2m) + alpha2^2/(2Jt) + kt xt^2/2`
//! stays at its initial value `E0`: the curve `(alpha1, alpha2, xt)(t)`
//! lies on the ellipsoid `H = E0` with semi-axes
//! `(sqrt(2 m E0), sqrt(2 Jt E0), sqrt(2 E0 / kt))`. The plot projects the
//! curve and a wireframe of the ellipsoid (parallels of constant `xt`,
//! meridians through the `xt` poles) with `alpha1` across, `xt` up and
//! `alpha2` in depth, and states the largest `|H - E0| / E0` along the run.

use super::style::{
    DrawResult, Drawn, centred, draw_ends, draw_legend, finite_runs, label_style, padded_range,
    png, title_style,
};
use super::{Figure4, PlotError, PlotSpec};
use plotters::coord::ranged3d::Cartesian3d;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::ops::Range;
use std::path::Path;

/// Circles of constant `xt` in the wireframe.
const PARALLELS: usize = 7;

/// Half-ellipses through the poles in the wireframe.
const MERIDIANS: usize = 16;

/// Segments per wireframe line.
const SEGMENTS: usize = 64;

/// A point `(alpha1, alpha2, xt)`.
type Point = (f64, f64, f64);

impl Figure4 {
    /// `alpha1^2/(2m) + alpha2^2/(2Jt) + kt xt^2/2`.
    fn energy(&self, (alpha1, alpha2, xt): Point) -> f64 {
        alpha1 * alpha1 / (2.0 * self.m)
            + alpha2 * alpha2 / (2.0 * self.jt)
            + self.kt * xt * xt / 2.0
    }

    /// The semi-axes of the ellipsoid `H = energy`.
    fn semi_axes(&self, energy: f64) -> Point {
        (
            (2.0 * self.m * energy).sqrt(),
            (2.0 * self.jt * energy).sqrt(),
            (2.0 * energy / self.kt).sqrt(),
        )
    }
}

/// The wireframe of the ellipsoid with these semi-axes, as polylines.
fn wireframe((a1, a2, a3): Point) -> Vec<Vec<Point>> {
    let on_ellipsoid = |polar: f64, azimuth: f64| {
        (
            a1 * polar.sin() * azimuth.cos(),
            a2 * polar.sin() * azimuth.sin(),
            a3 * polar.cos(),
        )
    };
    let steps = |end: f64| (0..=SEGMENTS).map(move |i| end * i as f64 / SEGMENTS as f64);
    let parallels = (1..=PARALLELS).map(|k| {
        let polar = PI * k as f64 / (PARALLELS + 1) as f64;
        steps(2.0 * PI)
            .map(|azimuth| on_ellipsoid(polar, azimuth))
            .collect()
    });
    let meridians = (0..MERIDIANS).map(|j| {
        let azimuth = 2.0 * PI * j as f64 / MERIDIANS as f64;
        steps(PI)
            .map(|polar| on_ellipsoid(polar, azimuth))
            .collect()
    });
    parallels.chain(meridians).collect()
}

/// The ranges widened about their centres to the longest span, so that
/// the projection keeps the ellipsoid's proportions.
fn equal_spans(ranges: [Range<f64>; 3]) -> [Range<f64>; 3] {
    let span = ranges
        .iter()
        .fold(0.0f64, |span, range| span.max(range.end - range.start));
    ranges.map(|range| centred(range, span))
}

/// Plotting coordinates of a point: `alpha1` across, `xt` up, `alpha2` in
/// depth.
fn plotted((alpha1, alpha2, xt): Point) -> Point {
    (alpha1, xt, alpha2)
}

/// The 3-D chart of Figure 4, in plotting coordinates.
type Chart<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian3d<RangedCoordf64, RangedCoordf64, RangedCoordf64>,
>;

/// How far the drawn coordinate axes reach beyond the ellipsoid, as a
/// fraction of its semi-axes.
const AXIS_REACH: f64 = 1.25;

/// Draws `figure4.png` from the spec's columns.
pub(super) fn draw(
    file: &Path,
    spec: &PlotSpec,
    figure4: &Figure4,
    columns: &BTreeMap<String, Vec<f64>>,
) -> Result<(), PlotError> {
    let [alpha1, alpha2, xt] =
        [&figure4.alpha1, &figure4.alpha2, &figure4.xt].map(|name| &columns[name]);
    let curve: Vec<Point> = (0..alpha1.len())
        .map(|i| (alpha1[i], alpha2[i], xt[i]))
        .collect();
    let initial = curve.iter().copied().find(finite).unwrap_or_default();
    let energy = figure4.energy(initial);
    let axes = figure4.semi_axes(energy);
    png(file, spec.size, |root| {
        let area = root
            .titled(
                "Figure 4: (alpha1, alpha2, xt) on the constant-energy ellipsoid",
                title_style(),
            )
            .drawn(file)?;
        let reach = |values: &[f64], axis: f64| {
            padded_range(
                values
                    .iter()
                    .copied()
                    .chain([-AXIS_REACH * axis, AXIS_REACH * axis]),
                0.02,
            )
        };
        let [across, up, depth] = equal_spans([
            reach(alpha1, axes.0),
            reach(xt, axes.2),
            reach(alpha2, axes.1),
        ]);
        let mut chart = ChartBuilder::on(&area)
            .margin(20)
            .build_cartesian_3d(across, up, depth)
            .drawn(file)?;
        chart.with_projection(|mut projection| {
            projection.yaw = -0.7;
            projection.pitch = 0.35;
            projection.scale = 0.8;
            projection.into_matrix()
        });
        chart
            .configure_axes()
            .label_style(label_style())
            .light_grid_style(BLACK.mix(0.08))
            .max_light_lines(4)
            .draw()
            .drawn(file)?;
        draw_axis_names(&mut chart, spec, figure4, axes).drawn(file)?;
        draw_ellipsoid(&mut chart, figure4, energy).drawn(file)?;
        draw_trajectory(&mut chart, figure4, &curve, energy).drawn(file)?;
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft).drawn(file)?;
        Ok(())
    })
}

/// Whether every coordinate of a point is finite.
fn finite(point: &Point) -> bool {
    point.0.is_finite() && point.1.is_finite() && point.2.is_finite()
}

/// The coordinate axes through the ellipsoid's centre, each named at its
/// positive end.
fn draw_axis_names(
    chart: &mut Chart<'_, '_>,
    spec: &PlotSpec,
    figure4: &Figure4,
    (a1, a2, a3): Point,
) -> DrawResult {
    let name = |paper: &str, column: &str| match spec.label(column) {
        label if column == paper => label,
        label => format!("{paper} ({label})"),
    };
    let names = [
        ((a1, 0.0, 0.0), name("alpha1", &figure4.alpha1)),
        ((0.0, a2, 0.0), name("alpha2", &figure4.alpha2)),
        ((0.0, 0.0, a3), name("xt", &figure4.xt)),
    ];
    let style = BLACK.mix(0.6).stroke_width(1);
    chart.draw_series(names.iter().map(|((x, y, z), _)| {
        let tip = (AXIS_REACH * x, AXIS_REACH * y, AXIS_REACH * z);
        PathElement::new(vec![plotted((-x, -y, -z)), plotted(tip)], style)
    }))?;
    chart.draw_series(names.into_iter().map(|((x, y, z), name)| {
        let tip = (AXIS_REACH * x, AXIS_REACH * y, AXIS_REACH * z);
        Text::new(name, plotted(tip), label_style())
    }))?;
    Ok(())
}

/// The wireframe of the ellipsoid `H = energy`, labelled with its
/// parameters.
fn draw_ellipsoid(chart: &mut Chart<'_, '_>, figure4: &Figure4, energy: f64) -> DrawResult {
    let style = RGBColor(150, 150, 150).stroke_width(1);
    let lines = wireframe(figure4.semi_axes(energy)).into_iter();
    let Figure4 { m, jt, kt, .. } = *figure4;
    chart
        .draw_series(lines.map(|line| {
            PathElement::new(line.into_iter().map(plotted).collect::<Vec<_>>(), style)
        }))?
        .label(format!(
            "H = E0 = {energy:.4}  (m = {m}, Jt = {jt}, kt = {kt})"
        ))
        .legend(move |(px, py)| PathElement::new(vec![(px, py), (px + 20, py)], style));
    Ok(())
}

/// The curve `(alpha1, alpha2, xt)(t)`, labelled with its largest
/// deviation from the ellipsoid, and its start and end.
fn draw_trajectory(
    chart: &mut Chart<'_, '_>,
    figure4: &Figure4,
    curve: &[Point],
    energy: f64,
) -> DrawResult {
    let (scale, deviation) = if energy > 0.0 {
        (energy, "|H - E0| / E0")
    } else {
        (1.0, "|H - E0|")
    };
    let worst = curve
        .iter()
        .filter(|p| finite(p))
        .fold(0.0f64, |worst, &p| {
            worst.max((figure4.energy(p) - energy).abs() / scale)
        });
    let style = BLUE.stroke_width(2);
    chart
        .draw_series(finite_runs(curve, finite).map(|run| {
            PathElement::new(run.iter().copied().map(plotted).collect::<Vec<_>>(), style)
        }))?
        .label(format!("trajectory, max {deviation} = {worst:.1e}"))
        .legend(move |(px, py)| PathElement::new(vec![(px, py), (px + 20, py)], style));
    let ends = [
        curve.iter().copied().find(finite),
        curve.iter().copied().rev().find(finite),
    ];
    draw_ends(chart, ends.map(|end| end.map(plotted)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn board() -> Figure4 {
        Figure4 {
            alpha1: "alpha1".into(),
            alpha2: "alpha2".into(),
            xt: "xt".into(),
            m: 1.5,
            jt: 0.3,
            kt: 2.0,
        }
    }

    #[test]
    fn the_wireframe_lies_on_the_ellipsoid() {
        let figure4 = board();
        let energy = 0.7;
        let lines = wireframe(figure4.semi_axes(energy));
        assert_eq!(lines.len(), PARALLELS + MERIDIANS);
        for point in lines.iter().flatten() {
            let error = (figure4.energy(*point) - energy).abs();
            assert!(error < 1e-14, "{point:?}: {error}");
        }
    }

    #[test]
    fn the_semi_axes_put_all_energy_in_one_coordinate() {
        let figure4 = board();
        let (a1, a2, a3) = figure4.semi_axes(0.7);
        for point in [(a1, 0.0, 0.0), (0.0, a2, 0.0), (0.0, 0.0, a3)] {
            assert!((figure4.energy(point) - 0.7).abs() < 1e-15, "{point:?}");
        }
    }
}
