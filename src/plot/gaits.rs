//! A comparison of gaits: each gait's loop in the plane of two shape
//! coordinates (left) and the path of the body it moves over the cycle
//! (right, equal axis scales), one colour per gait, each path's start on
//! the origin.

use super::style::{
    Axis, Drawn, draw_axes, draw_legend, padded_range, png, tick_labels, title_style,
};
use super::{PlotError, register_font};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One gait: its label, its loop in the shape plane and its path.
#[derive(Clone, Debug, PartialEq)]
pub struct GaitCurve {
    /// The legend's text.
    pub label: String,
    /// The loop, `(r_1, r_2)` at each step.
    pub shape: Vec<(f64, f64)>,
    /// The body's `(x, y)` at each step.
    pub path: Vec<(f64, f64)>,
}

/// The image size, in pixels.
const SIZE: (u32, u32) = (1800, 800);

/// The gaits' colours, in order (then repeated).
const COLOURS: [RGBColor; 4] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(0, 0, 0),
    RGBColor(44, 160, 44),
];

/// Writes the comparison of `curves` to `file` under `title`, the shape
/// plane's axes named `axes`.
///
/// # Errors
/// [`PlotError::EmptyTable`] without a curve or a point,
/// [`PlotError::Io`] or [`PlotError::Drawing`] when the file cannot be
/// written.
pub fn write_gait_comparison(
    title: &str,
    curves: &[GaitCurve],
    axes: [&str; 2],
    file: &Path,
) -> Result<(), PlotError> {
    if curves.is_empty()
        || curves
            .iter()
            .any(|c| c.shape.is_empty() || c.path.is_empty())
    {
        return Err(PlotError::EmptyTable);
    }
    register_font()?;
    png(file, SIZE, |root| {
        let area = root.titled(title, title_style()).drawn(file)?;
        let (left, right) = area.split_horizontally(SIZE.0 / 2);
        let loops: Vec<&[(f64, f64)]> = curves.iter().map(|c| c.shape.as_slice()).collect();
        panel(&left, file, &loops, axes, None)?;
        let paths: Vec<&[(f64, f64)]> = curves.iter().map(|c| c.path.as_slice()).collect();
        let labels: Vec<&str> = curves.iter().map(|c| c.label.as_str()).collect();
        panel(&right, file, &paths, ["x", "y"], Some(&labels))
    })
}

/// One panel: each curve in its colour, on equal scales, with the legend
/// when `labels` are given.
fn panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    file: &Path,
    curves: &[&[(f64, f64)]],
    [x_name, y_name]: [&str; 2],
    labels: Option<&[&str]>,
) -> Result<(), PlotError> {
    let points = || curves.iter().flat_map(|c| c.iter());
    let x_range = padded_range(points().map(|p| p.0), 0.08);
    let y_range = padded_range(points().map(|p| p.1), 0.08);
    let span = (x_range.end - x_range.start).max(y_range.end - y_range.start);
    let centre = |r: &std::ops::Range<f64>| (r.start + r.end) / 2.0;
    let (cx, cy) = (centre(&x_range), centre(&y_range));
    let (x_range, y_range) = (
        (cx - span / 2.0)..(cx + span / 2.0),
        (cy - span / 2.0)..(cy + span / 2.0),
    );
    let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(x_range, y_range)
        .drawn(file)?;
    let x = Axis {
        name: x_name,
        labels: &x_labels,
    };
    let y = Axis {
        name: y_name,
        labels: &y_labels,
    };
    draw_axes(&mut chart, x, y, true).drawn(file)?;
    for (index, (curve, colour)) in curves.iter().zip(COLOURS.iter().cycle()).enumerate() {
        let style = colour.stroke_width(3);
        let series = chart
            .draw_series(std::iter::once(PathElement::new(curve.to_vec(), style)))
            .drawn(file)?;
        if let Some(labels) = labels {
            series
                .label(labels[index])
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        }
    }
    if labels.is_some() {
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft).drawn(file)?;
    }
    Ok(())
}
