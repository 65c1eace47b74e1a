//! `energy.png` and `constraint_residual.png`: quantities that a correct
//! simulation keeps constant or zero, drawn against time; and a
//! [`Series`]' columns together against time, each curve in its colour
//! and named in the legend (a plan's `states.png` and `inputs.png`).
//!
//! The energy error is relative, `(E(t) - E(0)) / |E(0)|`, with `E(0)` the
//! first finite sample, unless `E(0) = 0`, where it is the absolute error
//! `E(t) - E(0)`. The residual `|r(t)|` is drawn on a logarithmic axis with
//! values below [`RESIDUAL_FLOOR`] raised to it.

use super::style::{
    Axis, Drawn, draw_axes, draw_legend, emptiest_corner, finite_bounds, finite_runs, padded_range,
    png, tick_labels, title_style,
};
use super::{PlotError, PlotSpec, RESIDUAL_FLOOR, Series};
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;

/// The energy error of each sample, and whether it is relative.
#[derive(Debug, PartialEq)]
struct EnergyError {
    /// The reference energy `E(0)`.
    initial: f64,
    /// `(E(t) - E(0)) / |E(0)|`, or `E(t) - E(0)` when `E(0) = 0`.
    error: Vec<f64>,
    /// Whether `error` is divided by `|E(0)|`.
    relative: bool,
}

impl EnergyError {
    /// The error of `energy` against its first finite sample.
    fn new(energy: &[f64]) -> Self {
        let initial = energy
            .iter()
            .copied()
            .find(|e| e.is_finite())
            .unwrap_or(f64::NAN);
        let relative = initial != 0.0;
        let scale = if relative { initial.abs() } else { 1.0 };
        let error = energy.iter().map(|e| (e - initial) / scale).collect();
        Self {
            initial,
            error,
            relative,
        }
    }

    /// The largest magnitude of the error.
    fn worst(&self) -> f64 {
        self.error
            .iter()
            .filter(|e| e.is_finite())
            .fold(0.0, |worst, e| worst.max(e.abs()))
    }
}

/// Draws `energy.png`.
pub(super) fn draw_energy(
    file: &Path,
    spec: &PlotSpec,
    time: &[f64],
    energy: &[f64],
) -> Result<(), PlotError> {
    let energy_error = EnergyError::new(energy);
    let worst = energy_error.worst();
    let EnergyError {
        initial,
        error,
        relative,
    } = energy_error;
    let y_desc = if relative {
        "(E(t) - E(0)) / |E(0)|".to_string()
    } else {
        let unit = spec.units.get(spec.energy.as_deref().unwrap_or_default());
        let unit = unit.map(|unit| format!(" [{unit}]")).unwrap_or_default();
        format!("E(t) - E(0){unit}, absolute since E(0) = 0")
    };
    let caption = format!("Energy error: E(0) = {initial:.6e}, max |error| = {worst:.2e}");
    // plotters places the ticks of a range of 1e-15 a round-off off the
    // round numbers: the error is drawn in units of its power of ten, so
    // that the ticks are round and read as plain decimals
    let exponent = if worst > 0.0 && worst.is_finite() {
        worst.log10().floor()
    } else {
        0.0
    };
    let unit = 10f64.powf(exponent);
    let scaled: Vec<f64> = error.iter().map(|e| e / unit).collect();
    let y_desc = if exponent == 0.0 {
        y_desc
    } else {
        format!("{y_desc}, in units of 1e{exponent}")
    };
    let y_range = padded_range(scaled.iter().copied(), 0.05);
    let format = tick_labels(&y_range);
    let panel = Panel {
        caption,
        y_desc,
        curves: vec![(None, &scaled)],
        y_format: &format,
    };
    draw_against_time(file, spec, time, panel, y_range)
}

/// Draws `constraint_residual.png` for the column `name`: plotters' own
/// logarithmic axis loses its ticks below machine epsilon, so the decimal
/// logarithm is drawn on a linear axis labelled in powers of ten.
pub(super) fn draw_residual(
    file: &Path,
    spec: &PlotSpec,
    name: &str,
    time: &[f64],
    residual: &[f64],
) -> Result<(), PlotError> {
    let decades: Vec<f64> = residual
        .iter()
        .map(|r| r.abs().max(RESIDUAL_FLOOR).log10())
        .collect();
    let worst = residual
        .iter()
        .filter(|r| r.is_finite())
        .fold(0.0, |worst: f64, r| worst.max(r.abs()));
    let mut y_desc = format!("|{}| (log scale", spec.label(name));
    if residual.iter().any(|r| r.abs() < RESIDUAL_FLOOR) {
        y_desc.push_str(&format!(
            "; below {RESIDUAL_FLOOR:.0e} drawn at {RESIDUAL_FLOOR:.0e}"
        ));
    }
    y_desc.push(')');
    let panel = Panel {
        caption: format!("Constraint residual: max {worst:.2e}"),
        y_desc,
        curves: vec![(None, &decades)],
        y_format: &|decade: &f64| format!("{:.0e}", 10f64.powf(*decade)),
    };
    draw_against_time(file, spec, time, panel, whole_decades(&decades))
}

/// The decades from below the smallest to above the largest finite value
/// (at least one), widened by 5% so that curves clear the frame.
fn whole_decades(decades: &[f64]) -> Range<f64> {
    let (low, high) = finite_bounds(decades.iter().copied());
    padded_range([low.floor(), high.ceil().max(low.floor() + 1.0)], 0.05)
}

/// Draws `series` from the table's `columns`, one curve per column named
/// in the legend.
pub(super) fn draw_series(
    file: &Path,
    spec: &PlotSpec,
    series: &Series,
    time: &[f64],
    columns: &BTreeMap<String, Vec<f64>>,
) -> Result<(), PlotError> {
    let curves: Vec<(Option<String>, &[f64])> = (series.columns.iter())
        .map(|name| (Some(spec.label(name)), &columns[name][..]))
        .collect();
    let y_range = padded_range(curves.iter().flat_map(|(_, v)| v.iter().copied()), 0.05);
    let format = tick_labels(&y_range);
    let panel = Panel {
        caption: series.title.clone(),
        y_desc: series.y_desc.clone(),
        curves,
        y_format: &format,
    };
    draw_against_time(file, spec, time, panel, y_range)
}

/// What one plot against time shows.
struct Panel<'a> {
    /// The title.
    caption: String,
    /// The y axis description.
    y_desc: String,
    /// The curves, each one value per time sample, with its name in the
    /// legend (no legend where none is named).
    curves: Vec<(Option<String>, &'a [f64])>,
    /// The y tick labels.
    y_format: &'a dyn Fn(&f64) -> String,
}

/// Draws the panel's values against `time` on the y axis `y_range`.
fn draw_against_time(
    file: &Path,
    spec: &PlotSpec,
    time: &[f64],
    panel: Panel<'_>,
    y_range: Range<f64>,
) -> Result<(), PlotError> {
    let curves: Vec<_> = (panel.curves.into_iter())
        .map(|(name, values)| {
            let points: Vec<(f64, f64)> =
                time.iter().copied().zip(values.iter().copied()).collect();
            (name, points)
        })
        .collect();
    png(file, spec.size, |root| {
        let area = root.titled(&panel.caption, title_style()).drawn(file)?;
        let time_range = padded_range(time.iter().copied(), 0.0);
        let corner = emptiest_corner(
            &curves
                .iter()
                .flat_map(|(_, points)| points.clone())
                .collect::<Vec<_>>(),
            &time_range,
            &y_range,
        );
        let time_labels = tick_labels(&time_range);
        let mut chart = ChartBuilder::on(&area)
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(100)
            .build_cartesian_2d(time_range, y_range)
            .drawn(file)?;
        let time_name = spec.label(&spec.time);
        let x = Axis {
            name: &time_name,
            labels: &time_labels,
        };
        let y = Axis {
            name: &panel.y_desc,
            labels: panel.y_format,
        };
        draw_axes(&mut chart, x, y, true).drawn(file)?;
        let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        let named = curves.iter().any(|(name, _)| name.is_some());
        for (index, (name, points)) in curves.iter().enumerate() {
            let colour = if named {
                Palette99::pick(index).to_rgba()
            } else {
                BLUE.to_rgba()
            };
            let drawn =
                chart
                    .draw_series(finite_runs(points, finite).map(|run| {
                        PathElement::new(run, colour.stroke_width(1 + u32::from(named)))
                    }))
                    .drawn(file)?;
            if let Some(name) = name {
                drawn.label(name.as_str()).legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            }
        }
        if named {
            draw_legend(&mut chart, corner).drawn(file)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_energy_error_is_relative_to_the_initial_energy() {
        let energy = EnergyError::new(&[-2.0, -2.2, -1.8]);
        assert_eq!(energy.initial, -2.0);
        assert!(energy.relative);
        let expected = [0.0, -0.1, 0.1];
        for (error, expected) in energy.error.iter().zip(expected) {
            assert!((error - expected).abs() < 1e-15, "{error} vs {expected}");
        }
        assert!((energy.worst() - 0.1).abs() < 1e-15);
    }

    #[test]
    fn the_residual_axis_spans_whole_decades() {
        let range = whole_decades(&[-17.3, -15.2, f64::NAN]);
        assert!((range.start - (-18.15)).abs() < 1e-12, "{range:?}");
        assert!((range.end - (-14.85)).abs() < 1e-12, "{range:?}");
        let flat = whole_decades(&[-18.0, -18.0]);
        assert!(
            (flat.start - (-18.05)).abs() < 1e-12 && (flat.end - (-16.95)).abs() < 1e-12,
            "{flat:?}"
        );
    }

    #[test]
    fn a_zero_initial_energy_gives_the_absolute_error() {
        let energy = EnergyError::new(&[f64::NAN, 0.0, 1e-3, -2e-3]);
        assert_eq!(
            energy.initial, 0.0,
            "the first finite sample is the reference"
        );
        assert!(!energy.relative);
        assert_eq!(energy.error[2..], [1e-3, -2e-3]);
        assert_eq!(energy.worst(), 2e-3);
    }
}
