//! `path.png`: the planar path `(x(t), y(t))` with equal axis scales, so
//! that turns and distances look as they are, heading arrows
//! `(cos theta, sin theta)` at regular time intervals, the start and end
//! marked, and the ground tracks of declared points (a mechanism's contact
//! points) as thinner curves of their own colours.

use super::style::{
    Axis, DrawResult, Drawn, centred, draw_axes, draw_ends, draw_legend, emptiest_corner,
    finite_runs, padded_range, png, tick_labels, title_style,
};
use super::{PlanarPath, PlotError, PlotSpec};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;

/// About how many heading arrows are drawn along the path.
const HEADING_ARROWS: usize = 24;

/// Arrow length as a fraction of the longer axis span.
const ARROW_LENGTH: f64 = 0.035;

/// Half-angle of an arrowhead, in radians.
const ARROWHEAD_ANGLE: f64 = 0.45;

/// The colours of the tracks, in turn.
const TRACK_COLOURS: [RGBColor; 6] = [
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
];

/// Draws `path.png` from the spec's columns.
pub(super) fn draw(
    file: &Path,
    spec: &PlotSpec,
    planar: &PlanarPath,
    columns: &BTreeMap<String, Vec<f64>>,
) -> Result<(), PlotError> {
    let (x, y) = (&columns[&planar.x], &columns[&planar.y]);
    let points: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
    let tracks: Vec<(&str, Vec<(f64, f64)>)> = planar
        .tracks
        .iter()
        .map(|track| {
            let (x, y) = (&columns[&track.x], &columns[&track.y]);
            let points = x.iter().copied().zip(y.iter().copied()).collect();
            (track.point.as_str(), points)
        })
        .collect();
    let everything: Vec<(f64, f64)> = points
        .iter()
        .chain(tracks.iter().flat_map(|(_, track)| track))
        .copied()
        .collect();
    png(file, spec.size, |root| {
        let area = root
            .titled("Path in the plane", title_style())
            .drawn(file)?;
        let pixels = chart_builder(&area)
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)
            .drawn(file)?
            .plotting_area()
            .dim_in_pixel();
        let (x_range, y_range) = equal_scale(
            padded_range(everything.iter().map(|p| p.0), 0.08),
            padded_range(everything.iter().map(|p| p.1), 0.08),
            pixels,
        );
        let arrow = ARROW_LENGTH * (x_range.end - x_range.start).max(y_range.end - y_range.start);
        let legend_corner = emptiest_corner(&everything, &x_range, &y_range);
        let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
        let mut chart = chart_builder(&area)
            .build_cartesian_2d(x_range, y_range)
            .drawn(file)?;
        let (x_name, y_name) = (spec.label(&planar.x), spec.label(&planar.y));
        let x = Axis {
            name: &x_name,
            labels: &x_labels,
        };
        let y = Axis {
            name: &y_name,
            labels: &y_labels,
        };
        draw_axes(&mut chart, x, y, true).drawn(file)?;
        let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        draw_tracks(&mut chart, &tracks).drawn(file)?;
        let path_style = BLUE.stroke_width(2);
        chart
            .draw_series(finite_runs(&points, finite).map(|run| PathElement::new(run, path_style)))
            .drawn(file)?
            .label("path")
            .legend(move |(px, py)| PathElement::new(vec![(px, py), (px + 20, py)], path_style));
        if let Some(heading) = &planar.heading {
            let unit = spec.units.get(&spec.time).map(|unit| format!(" {unit}"));
            let interval = mark_interval(&columns[&spec.time]);
            let label = format!(
                "heading, every {}{}",
                format_interval(interval),
                unit.unwrap_or_default()
            );
            let marks = heading_marks(&points, &columns[heading]);
            draw_heading_arrows(&mut chart, &marks, arrow, label).drawn(file)?;
        }
        let ends = [
            points.iter().copied().find(finite),
            points.iter().copied().rev().find(finite),
        ];
        draw_ends(&mut chart, ends).drawn(file)?;
        draw_legend(&mut chart, legend_corner).drawn(file)?;
        Ok(())
    })
}

/// Each point's track, labelled `track of POINT`, in [`TRACK_COLOURS`] in turn.
fn draw_tracks(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    tracks: &[(&str, Vec<(f64, f64)>)],
) -> DrawResult {
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    for ((point, track), colour) in tracks.iter().zip(TRACK_COLOURS.iter().cycle()) {
        let style = colour.stroke_width(1);
        chart
            .draw_series(finite_runs(track, finite).map(|run| PathElement::new(run, style)))?
            .label(format!("track of {point}"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
    }
    Ok(())
}

/// Arrows of `length` at the marks `(position, heading)`.
fn draw_heading_arrows(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    marks: &[((f64, f64), f64)],
    length: f64,
    label: String,
) -> DrawResult {
    let style = BLACK.stroke_width(1);
    chart
        .draw_series(
            marks
                .iter()
                .flat_map(|&mark| arrow_strokes(mark, length))
                .map(|stroke| PathElement::new(stroke, style)),
        )?
        .label(label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
    Ok(())
}

/// The layout of the path chart: margins and label areas.
fn chart_builder<'a, 'b>(
    area: &'a DrawingArea<BitMapBackend<'b>, Shift>,
) -> ChartBuilder<'a, 'b, BitMapBackend<'b>> {
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80);
    builder
}

/// Widens the ranges about their centres so that one data unit spans the
/// same number of pixels on both axes of a plot `pixels = (width, height)`.
fn equal_scale(x: Range<f64>, y: Range<f64>, pixels: (u32, u32)) -> (Range<f64>, Range<f64>) {
    let (width, height) = (f64::from(pixels.0), f64::from(pixels.1));
    let per_pixel = ((x.end - x.start) / width).max((y.end - y.start) / height);
    (
        centred(x, per_pixel * width),
        centred(y, per_pixel * height),
    )
}

/// The rows between heading arrows: about [`HEADING_ARROWS`] arrows.
fn mark_stride(rows: usize) -> usize {
    (rows / HEADING_ARROWS).max(1)
}

/// Positions and headings of the arrows: every [`mark_stride`]-th row
/// whose position and heading are finite.
fn heading_marks(points: &[(f64, f64)], heading: &[f64]) -> Vec<((f64, f64), f64)> {
    points
        .iter()
        .zip(heading)
        .step_by(mark_stride(points.len()))
        .filter(|((x, y), theta)| x.is_finite() && y.is_finite() && theta.is_finite())
        .map(|(&point, &theta)| (point, theta))
        .collect()
}

/// The time between arrows (0 for a single row).
fn mark_interval(time: &[f64]) -> f64 {
    let stride = mark_stride(time.len());
    time.get(stride).map_or(0.0, |later| later - time[0])
}

/// A time interval with three significant digits and no trailing zeros.
fn format_interval(interval: f64) -> String {
    let decimals = (2.0 - interval.abs().log10().floor()).clamp(0.0, 12.0) as usize;
    let text = format!("{interval:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// The shaft and the head of an arrow of `length` from `point` along the
/// heading `theta`, as polylines in data coordinates.
fn arrow_strokes(((x, y), theta): ((f64, f64), f64), length: f64) -> [Vec<(f64, f64)>; 2] {
    let tip = (x + length * theta.cos(), y + length * theta.sin());
    let barb = |side: f64| {
        let angle = theta + std::f64::consts::PI + side * ARROWHEAD_ANGLE;
        (
            tip.0 + 0.4 * length * angle.cos(),
            tip.1 + 0.4 * length * angle.sin(),
        )
    };
    [vec![(x, y), tip], vec![barb(1.0), tip, barb(-1.0)]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_scale_gives_both_axes_the_same_units_per_pixel() {
        let (x, y) = equal_scale(0.0..10.0, -1.0..1.0, (800, 600));
        let per_pixel = [(x.end - x.start) / 800.0, (y.end - y.start) / 600.0];
        assert!((per_pixel[0] - per_pixel[1]).abs() < 1e-15, "{per_pixel:?}");
        assert_eq!(x, 0.0..10.0, "the wider range is kept");
        assert!(
            (y.start + y.end).abs() < 1e-15,
            "the narrower one stays centred"
        );
    }

    #[test]
    fn arrows_point_along_the_heading() {
        let [shaft, head] = arrow_strokes(((1.0, 2.0), std::f64::consts::FRAC_PI_2), 0.5);
        let tip = shaft[1];
        assert!(
            (tip.0 - 1.0).abs() < 1e-15 && (tip.1 - 2.5).abs() < 1e-15,
            "{tip:?}"
        );
        assert_eq!(head[1], tip);
        for barb in [head[0], head[2]] {
            assert!(barb.1 < tip.1, "barbs trail the tip: {barb:?}");
            let length = ((barb.0 - tip.0).powi(2) + (barb.1 - tip.1).powi(2)).sqrt();
            assert!((length - 0.2).abs() < 1e-15);
        }
    }

    #[test]
    fn intervals_keep_three_significant_digits() {
        assert_eq!(format_interval(1.25), "1.25");
        assert_eq!(format_interval(0.012_345), "0.0123");
        assert_eq!(format_interval(120.0), "120");
        assert_eq!(format_interval(0.5), "0.5");
        assert_eq!(format_interval(0.0), "0");
    }
}
