//! `curvature.png`: the constraint curvature functions of a principally
//! kinematic model over a plane of its shape coordinates, the height
//! functions Hatton & Choset (2011) draw: one panel for each of the body
//! displacement's components `x`, `y` and `theta`, coloured red where
//! positive and blue where negative (white at zero), with the gait's loop
//! drawn on each. A counterclockwise loop moves the body by about the
//! integral of each function over the area it encloses, and turns it by
//! exactly that integral of the `theta` panel.
//!
//! Near the singular set the functions grow without bound, so each panel's
//! colours saturate at twice the largest magnitude inside the loop (the
//! value printed in the panel's title), where its integral is decided;
//! where the connection is not defined the cell is grey.

use super::style::{Axis, Drawn, draw_axes, label_style, png, tick_labels, title_style};
use super::{PlotError, register_font};
use plotters::prelude::*;
use std::path::Path;

/// The curvature functions sampled on a grid, and the loop.
#[derive(Clone, Debug)]
pub struct CurvatureField {
    /// The two shape coordinates of the plane.
    pub axes: [String; 2],
    /// The grid's values of the first, increasing and evenly spaced.
    pub first: Vec<f64>,
    /// The grid's values of the second, likewise.
    pub second: Vec<f64>,
    /// Each panel's title and values, at `i * second.len() + j` for
    /// `(first[i], second[j])`.
    pub panels: Vec<(String, Vec<f64>)>,
    /// The loop.
    pub path: Vec<(f64, f64)>,
}

/// The image size of `curvature.png`, in pixels.
const SIZE: (u32, u32) = (1800, 680);

/// The colours saturate at this multiple of the largest magnitude inside
/// the loop.
const SATURATION_MARGIN: f64 = 2.0;

/// The most vertices of the loop the inside test walks.
const LOOP_VERTICES: usize = 400;

/// Writes `curvature.png` of `field` to `file`.
///
/// # Errors
/// [`PlotError::EmptyTable`] without grid points or panels,
/// [`PlotError::Io`] or [`PlotError::Drawing`] when the file cannot be
/// written.
pub fn write_curvature_plot(field: &CurvatureField, file: &Path) -> Result<(), PlotError> {
    if field.first.len() < 2 || field.second.len() < 2 || field.panels.is_empty() {
        return Err(PlotError::EmptyTable);
    }
    register_font()?;
    png(file, SIZE, |root| {
        let caption = format!(
            "Constraint curvature over ({}, {}), the gait's loop in black",
            field.axes[0], field.axes[1]
        );
        let area = root.titled(&caption, title_style()).drawn(file)?;
        let panels = area.split_evenly((1, field.panels.len()));
        for (panel_area, (title, values)) in panels.iter().zip(&field.panels) {
            panel(panel_area, file, field, title, values)?;
        }
        Ok(())
    })
}

/// One height function over the plane, with the loop.
fn panel(
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    file: &Path,
    field: &CurvatureField,
    title: &str,
    values: &[f64],
) -> Result<(), PlotError> {
    let (first, second) = (&field.first, &field.second);
    let x_range = first[0]..first[first.len() - 1];
    let y_range = second[0]..second[second.len() - 1];
    let scale = saturation(field, values);
    let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
    let mut chart = ChartBuilder::on(area)
        .margin(15)
        .caption(
            format!("{title} (colours saturate at {scale:.3})"),
            label_style(),
        )
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(x_range.clone(), y_range.clone())
        .drawn(file)?;
    let x = Axis {
        name: &field.axes[0],
        labels: &x_labels,
    };
    let y = Axis {
        name: &field.axes[1],
        labels: &y_labels,
    };
    draw_axes(&mut chart, x, y, false).drawn(file)?;
    let (dx, dy) = (first[1] - first[0], second[1] - second[0]);
    let cells = first.iter().enumerate().flat_map(|(i, &u)| {
        second.iter().enumerate().map(move |(j, &v)| {
            let colour = colour_of(values[i * second.len() + j], scale);
            let corners = [(u - dx / 2.0, v - dy / 2.0), (u + dx / 2.0, v + dy / 2.0)];
            Rectangle::new(corners, colour.filled())
        })
    });
    chart.draw_series(cells).drawn(file)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            field.path.clone(),
            BLACK.stroke_width(2),
        )))
        .drawn(file)?;
    Ok(())
}

/// The magnitude where the colours saturate: [`SATURATION_MARGIN`] times
/// the largest finite one at the grid points inside the loop, 1 when none
/// is positive.
fn saturation(field: &CurvatureField, values: &[f64]) -> f64 {
    let step = field.path.len().div_ceil(LOOP_VERTICES).max(1);
    let polygon: Vec<(f64, f64)> = field.path.iter().step_by(step).copied().collect();
    let columns = field.second.len();
    let largest = (values.iter().enumerate())
        .filter(|(k, _)| {
            inside(
                &polygon,
                (field.first[k / columns], field.second[k % columns]),
            )
        })
        .map(|(_, value)| value.abs())
        .filter(|magnitude| magnitude.is_finite())
        .fold(0.0, f64::max);
    match largest > 0.0 {
        true => SATURATION_MARGIN * largest,
        false => 1.0,
    }
}

/// Whether `point` is inside the closed `polygon`, by the parity of the
/// edges a ray to its right crosses.
fn inside(polygon: &[(f64, f64)], (x, y): (f64, f64)) -> bool {
    let edges = polygon.iter().zip(polygon.iter().cycle().skip(1));
    edges
        .filter(|((_, ay), (_, by))| (*ay > y) != (*by > y))
        .filter(|((ax, ay), (bx, by))| x < ax + (y - ay) * (bx - ax) / (by - ay))
        .count()
        % 2
        == 1
}

/// Red for positive values, blue for negative, white at zero, saturated at
/// `scale`; grey where the value is not finite.
fn colour_of(value: f64, scale: f64) -> RGBColor {
    if !value.is_finite() {
        return RGBColor(160, 160, 160);
    }
    let strength = (value / scale).clamp(-1.0, 1.0);
    let fade = |full: u8| (255.0 - strength.abs() * (255.0 - f64::from(full))).round() as u8;
    match strength >= 0.0 {
        true => RGBColor(fade(178), fade(24), fade(43)),
        false => RGBColor(fade(33), fade(102), fade(172)),
    }
}

#[cfg(test)]
mod tests {
    use super::{CurvatureField, colour_of, saturation};
    use plotters::style::RGBColor;

    #[test]
    fn colours_fade_to_white_at_zero_and_saturate_at_the_scale() {
        assert_eq!(colour_of(0.0, 2.0), RGBColor(255, 255, 255));
        assert_eq!(colour_of(5.0, 2.0), RGBColor(178, 24, 43));
        assert_eq!(colour_of(-2.0, 2.0), RGBColor(33, 102, 172));
        assert_eq!(colour_of(f64::NAN, 2.0), RGBColor(160, 160, 160));
    }

    #[test]
    fn colours_saturate_at_twice_the_largest_magnitude_inside_the_loop() {
        let field = CurvatureField {
            axes: ["a".into(), "b".into()],
            first: vec![0.0, 1.0, 2.0, 3.0],
            second: vec![0.0, 1.0, 2.0],
            panels: Vec::new(),
            path: vec![(0.5, 0.5), (2.5, 0.5), (2.5, 1.5), (0.5, 1.5)],
        };
        // Grid points (a, b) row-major: only (1, 1) and (2, 1) are inside.
        let mut values = [100.0; 12];
        (values[4], values[7]) = (-3.0, 2.0);
        assert_eq!(saturation(&field, &values), 6.0);
        values[4] = f64::NAN;
        assert_eq!(saturation(&field, &values), 4.0);
        assert_eq!(saturation(&field, &[0.0; 12]), 1.0);
    }
}
