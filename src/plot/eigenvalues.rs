//! `eigenvalues.png`: the eigenvalues of a linearization swept over a
//! variable (`chaplygin linearize --sweep`), their real parts in the upper
//! panel and their imaginary parts in the lower one, each eigenvalue a
//! dot at each value of the variable (sorting by real part reorders the
//! eigenvalues where branches cross, so dots, not lines). The zero line of
//! the real parts is drawn: stability is every real part below it.

use super::style::{Drawn, label_style, padded_range, png, tick_labels, title_style};
use super::{PlotError, register_font};
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// The swept variable's values and, at each, the eigenvalues `(re, im)`.
#[derive(Clone, Debug)]
pub struct EigenvalueSweep {
    /// The variable's name.
    pub variable: String,
    /// Its values.
    pub values: Vec<f64>,
    /// The eigenvalues at each value.
    pub eigenvalues: Vec<Vec<(f64, f64)>>,
}

/// The image size of `eigenvalues.png`, in pixels.
const SIZE: (u32, u32) = (1200, 1000);

/// Writes `eigenvalues.png` of `sweep` to `file`.
///
/// # Errors
/// [`PlotError::EmptyTable`] without values, [`PlotError::Io`] or
/// [`PlotError::Drawing`] when the file cannot be written.
pub fn write_eigenvalue_plot(sweep: &EigenvalueSweep, file: &Path) -> Result<(), PlotError> {
    if sweep.values.is_empty() {
        return Err(PlotError::EmptyTable);
    }
    register_font()?;
    png(file, SIZE, |root| {
        let caption = format!("Eigenvalues against {}", sweep.variable);
        let area = root.titled(&caption, title_style()).drawn(file)?;
        let (upper, lower) = area.split_vertically(SIZE.1 / 2 - 30);
        let real = points(sweep, |(re, _)| re);
        let imaginary = points(sweep, |(_, im)| im);
        panel(&upper, file, sweep, &real, "real part")?;
        panel(&lower, file, sweep, &imaginary, "imaginary part")?;
        Ok(())
    })
}

/// `(value, part)` of every finite eigenvalue.
fn points(sweep: &EigenvalueSweep, part: impl Fn((f64, f64)) -> f64) -> Vec<(f64, f64)> {
    let part = &part;
    sweep
        .values
        .iter()
        .zip(&sweep.eigenvalues)
        .flat_map(|(&value, eigenvalues)| eigenvalues.iter().map(move |&e| (value, part(e))))
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect()
}

/// One panel: `points` against the variable, with the zero line.
fn panel(
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    file: &Path,
    sweep: &EigenvalueSweep,
    points: &[(f64, f64)],
    y_desc: &str,
) -> Result<(), PlotError> {
    let x_range = padded_range(sweep.values.iter().copied(), 0.02);
    let y_range: Range<f64> = padded_range(points.iter().map(|p| p.1).chain([0.0]), 0.05);
    let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(100)
        .build_cartesian_2d(x_range.clone(), y_range)
        .drawn(file)?;
    chart
        .configure_mesh()
        .x_desc(sweep.variable.as_str())
        .x_label_formatter(&x_labels)
        .y_desc(y_desc)
        .y_label_formatter(&y_labels)
        .axis_desc_style(label_style())
        .label_style(label_style())
        .draw()
        .drawn(file)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(x_range.start, 0.0), (x_range.end, 0.0)],
            BLACK.stroke_width(1),
        )))
        .drawn(file)?;
    chart
        .draw_series(points.iter().map(|&p| Circle::new(p, 2, BLUE.filled())))
        .drawn(file)?;
    Ok(())
}
