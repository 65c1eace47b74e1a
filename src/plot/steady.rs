//! `steady.png`: a family of steady motions (`chaplygin steady --trace`),
//! one unknown against the traced variable, the points in the family's
//! order joined by a thin line, and the stable points drawn large and
//! green, the unstable ones small and red, so that the family's stable
//! parts and its folds show.

use super::style::{
    Axis, Drawn, draw_axes, draw_legend, padded_range, png, tick_labels, title_style,
};
use super::{PlotError, register_font};
use plotters::prelude::*;
use std::path::Path;

/// A family: `(VAR, unknown)` per point in order, and whether each point
/// is stable.
#[derive(Clone, Debug)]
pub struct SteadyFamily {
    /// The traced variable's name.
    pub variable: String,
    /// The unknown drawn.
    pub unknown: String,
    /// `(VAR, unknown)` at each point.
    pub points: Vec<(f64, f64)>,
    /// Whether the motion is stable there.
    pub stable: Vec<bool>,
}

/// The image size, in pixels.
const SIZE: (u32, u32) = (1200, 800);

/// Writes `steady.png` of `family` to `file`.
///
/// # Errors
/// [`PlotError::EmptyTable`] without points, [`PlotError::Io`] or
/// [`PlotError::Drawing`] when the file cannot be written.
pub fn write_steady_plot(family: &SteadyFamily, file: &Path) -> Result<(), PlotError> {
    if family.points.is_empty() {
        return Err(PlotError::EmptyTable);
    }
    register_font()?;
    png(file, SIZE, |root| {
        let caption = format!(
            "Steady motions: {} against {}",
            family.unknown, family.variable
        );
        let area = root.titled(&caption, title_style()).drawn(file)?;
        let x_range = padded_range(family.points.iter().map(|p| p.0), 0.05);
        let y_range = padded_range(family.points.iter().map(|p| p.1), 0.08);
        let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
        let mut chart = ChartBuilder::on(&area)
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(x_range, y_range)
            .drawn(file)?;
        let x = Axis {
            name: &family.variable,
            labels: &x_labels,
        };
        let y = Axis {
            name: &family.unknown,
            labels: &y_labels,
        };
        draw_axes(&mut chart, x, y, true).drawn(file)?;
        let line = PathElement::new(family.points.clone(), BLACK.stroke_width(1));
        chart.draw_series(std::iter::once(line)).drawn(file)?;
        for (stable, colour, radius) in [(true, GREEN, 6), (false, RED, 3)] {
            let label = if stable { "stable" } else { "unstable" };
            let points = (family.points.iter().zip(&family.stable))
                .filter(|(_, s)| **s == stable)
                .map(|(p, _)| Circle::new(*p, radius, colour.filled()));
            chart
                .draw_series(points)
                .drawn(file)?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 10, y), radius, colour.filled()));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight).drawn(file)
    })
}
