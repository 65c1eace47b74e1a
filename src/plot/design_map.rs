//! `map.png`: a design map (`chaplygin map`), the self-stable speeds over
//! one or two parameters.
//!
//! Over one parameter, the stable speed intervals of each design point as
//! a band against the parameter, its edges (the lower and upper ends of
//! the stable range) drawn as curves; over two, a heat map of the width of
//! the first stable interval (viridis; grey where there is none), the
//! stable region outlined. The model's default design is marked.

use super::style::{Axis, Drawn, draw_axes, label_style, padded_range, png, tick_labels};
use super::{PlotError, register_font};
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// A design map as drawn.
#[derive(Clone, Debug)]
pub struct DesignMapPlot {
    /// The speed variable.
    pub speed: String,
    /// The parameters varied (one or two) and their grid values.
    pub axes: Vec<(String, Vec<f64>)>,
    /// At each design point (the last axis varying fastest), the stable
    /// speed intervals; `None` where the point was not computed or failed.
    pub stable: Vec<Option<Vec<(f64, f64)>>>,
    /// The model's default value of each parameter varied.
    pub default: Vec<f64>,
}

/// The image size of `map.png`, in pixels.
const SIZE: (u32, u32) = (1200, 900);

/// Viridis (matplotlib's default colour map) at five stops.
const VIRIDIS: [(u8, u8, u8); 5] = [
    (68, 1, 84),
    (59, 82, 139),
    (33, 145, 140),
    (94, 201, 98),
    (253, 231, 37),
];

/// The colour of `value` in `0..=top` on [`VIRIDIS`], linear between stops.
fn viridis(value: f64, top: f64) -> RGBColor {
    let position = (value / top).clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f64;
    let below = (position.floor() as usize).min(VIRIDIS.len() - 2);
    let fraction = position - below as f64;
    let (a, b) = (VIRIDIS[below], VIRIDIS[below + 1]);
    let mix =
        |x: u8, y: u8| (f64::from(x) + fraction * (f64::from(y) - f64::from(x))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Light grey: a design point with no stable speed, or not computed.
const NOWHERE: RGBColor = RGBColor(225, 225, 225);

/// Writes `map.png` of `map` to `file`.
///
/// # Errors
/// [`PlotError::EmptyTable`] without design points or with other than one
/// or two axes, [`PlotError::Io`] or [`PlotError::Drawing`] when the file
/// cannot be written.
pub fn write_design_map(map: &DesignMapPlot, file: &Path) -> Result<(), PlotError> {
    let points: usize = map.axes.iter().map(|(_, values)| values.len()).product();
    if map.stable.is_empty() || map.stable.len() != points {
        return Err(PlotError::EmptyTable);
    }
    register_font()?;
    match map.axes.as_slice() {
        [axis] => png(file, SIZE, |root| over_one(root, file, map, axis)),
        [first, second] => png(file, SIZE, |root| {
            over_two(root, file, map, [first, second])
        }),
        _ => Err(PlotError::EmptyTable),
    }
}

/// The canvas.
type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// The cells of grid `values`: from midway to the previous value to midway
/// to the next (half a neighbour's spacing at either end; 1 wide alone).
fn cells(values: &[f64]) -> Vec<Range<f64>> {
    let spacing = |i: usize, j: usize| (values[j] - values[i]).abs();
    (0..values.len())
        .map(|i| {
            let below = match i {
                0 if values.len() > 1 => spacing(0, 1) / 2.0,
                0 => 0.5,
                _ => spacing(i - 1, i) / 2.0,
            };
            let above = match i + 1 < values.len() {
                true => spacing(i, i + 1) / 2.0,
                false => below,
            };
            (values[i] - below)..(values[i] + above)
        })
        .collect()
}

/// The stable speed bands against one parameter.
fn over_one(
    root: &Area<'_>,
    file: &Path,
    map: &DesignMapPlot,
    (name, values): &(String, Vec<f64>),
) -> Result<(), PlotError> {
    let caption = format!("Self-stable {} against {name}", map.speed);
    let area = root
        .titled(&caption, super::style::title_style())
        .drawn(file)?;
    let cells = cells(values);
    let x_range = cells[0].start..cells[cells.len() - 1].end;
    let ends = map
        .stable
        .iter()
        .flatten()
        .flatten()
        .flat_map(|&(a, b)| [a, b]);
    let y_range = padded_range(ends, 0.08);
    let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
    let mut chart = ChartBuilder::on(&area)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(100)
        .build_cartesian_2d(x_range.clone(), y_range.clone())
        .drawn(file)?;
    let x = Axis {
        name,
        labels: &x_labels,
    };
    let y = Axis {
        name: &format!("{} (stable intervals)", map.speed),
        labels: &y_labels,
    };
    draw_axes(&mut chart, x, y, true).drawn(file)?;
    let band = GREEN.mix(0.35).filled();
    for (cell, intervals) in cells.iter().zip(&map.stable) {
        let bars = intervals.iter().flatten();
        let bars = bars.map(|&(a, b)| Rectangle::new([(cell.start, a), (cell.end, b)], band));
        chart.draw_series(bars).drawn(file)?;
    }
    for (end, colour) in [(0, BLUE), (1, RED)] {
        let edge: Vec<(f64, f64)> = (values.iter().zip(&map.stable))
            .filter_map(|(&x, intervals)| {
                let first = intervals.as_ref()?.first()?;
                Some((x, if end == 0 { first.0 } else { first.1 }))
            })
            .collect();
        chart
            .draw_series(LineSeries::new(edge.clone(), colour.stroke_width(2)))
            .drawn(file)?
            .label(if end == 0 { "lower end" } else { "upper end" })
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(2)));
        chart
            .draw_series(edge.iter().map(|&p| Circle::new(p, 3, colour.filled())))
            .drawn(file)?;
    }
    let default = map.default[0];
    let marker = [(default, y_range.start), (default, y_range.end)];
    chart
        .draw_series(DashedLineSeries::new(marker, 8, 6, BLACK.stroke_width(1)))
        .drawn(file)?;
    let label = (default, y_range.end - 0.04 * (y_range.end - y_range.start));
    chart
        .draw_series(std::iter::once(Text::new(" default", label, label_style())))
        .drawn(file)?;
    super::style::draw_legend(&mut chart, SeriesLabelPosition::UpperRight).drawn(file)
}

/// The width of the first stable interval over two parameters, the stable
/// region outlined, with a colour bar.
fn over_two(
    root: &Area<'_>,
    file: &Path,
    map: &DesignMapPlot,
    [(x_name, xs), (y_name, ys)]: [&(String, Vec<f64>); 2],
) -> Result<(), PlotError> {
    let caption = format!(
        "Width of the self-stable {} range over {x_name} and {y_name}",
        map.speed
    );
    let area = root
        .titled(&caption, super::style::title_style())
        .drawn(file)?;
    let (plot_area, bar_area) = area.split_horizontally(SIZE.0 - 170);
    let (x_cells, y_cells) = (cells(xs), cells(ys));
    let x_range = x_cells[0].start..x_cells[x_cells.len() - 1].end;
    let y_range = y_cells[0].start..y_cells[y_cells.len() - 1].end;
    let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
    let mut chart = ChartBuilder::on(&plot_area)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(100)
        .build_cartesian_2d(x_range, y_range)
        .drawn(file)?;
    let (x, y) = (
        Axis {
            name: x_name,
            labels: &x_labels,
        },
        Axis {
            name: y_name,
            labels: &y_labels,
        },
    );
    draw_axes(&mut chart, x, y, false).drawn(file)?;
    let width = |index: usize| -> Option<f64> {
        let first = map.stable[index].as_ref()?.first()?;
        Some(first.1 - first.0)
    };
    let widest = (0..map.stable.len()).filter_map(width).fold(0.0, f64::max);
    let colour = |w: f64| viridis(w, widest.max(f64::MIN_POSITIVE));
    let index = |i: usize, j: usize| i * ys.len() + j;
    let mut squares = Vec::new();
    for (i, x_cell) in x_cells.iter().enumerate() {
        for (j, y_cell) in y_cells.iter().enumerate() {
            let fill = width(index(i, j)).map_or(NOWHERE, colour);
            let corners = [(x_cell.start, y_cell.start), (x_cell.end, y_cell.end)];
            squares.push(Rectangle::new(corners, fill.filled()));
        }
    }
    chart.draw_series(squares).drawn(file)?;
    let stable = |i: usize, j: usize| width(index(i, j)).is_some();
    let mut outline = Vec::new();
    for (i, x_cell) in x_cells.iter().enumerate() {
        for (j, y_cell) in y_cells.iter().enumerate() {
            if i + 1 < xs.len() && stable(i, j) != stable(i + 1, j) {
                outline.push([(x_cell.end, y_cell.start), (x_cell.end, y_cell.end)]);
            }
            if j + 1 < ys.len() && stable(i, j) != stable(i, j + 1) {
                outline.push([(x_cell.start, y_cell.end), (x_cell.end, y_cell.end)]);
            }
        }
    }
    let edges = outline.into_iter();
    chart
        .draw_series(edges.map(|edge| PathElement::new(edge, BLACK.stroke_width(3))))
        .drawn(file)?;
    let default = (map.default[0], map.default[1]);
    chart
        .draw_series(std::iter::once(Cross::new(default, 9, RED.stroke_width(3))))
        .drawn(file)?;
    chart
        .draw_series(std::iter::once(Text::new(
            " default",
            default,
            label_style(),
        )))
        .drawn(file)?;
    colour_bar(&bar_area, file, &map.speed, widest)
}

/// The colour bar of the widths, 0 to `widest`, with the grey of no
/// stable speed below it.
fn colour_bar(area: &Area<'_>, file: &Path, speed: &str, widest: f64) -> Result<(), PlotError> {
    let range = 0.0..widest.max(f64::MIN_POSITIVE);
    let labels = tick_labels(&range);
    let mut chart = ChartBuilder::on(area)
        .margin_top(40)
        .margin_bottom(110)
        .margin_right(10)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, range.clone())
        .drawn(file)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_y_mesh()
        .disable_x_axis()
        .y_label_formatter(&labels)
        .y_desc(format!("width of the stable {speed} range"))
        .label_style(label_style())
        .draw()
        .drawn(file)?;
    let steps = 100;
    let strips = (0..steps).map(|k| {
        let (low, high) = (
            range.end * f64::from(k) / f64::from(steps),
            range.end * f64::from(k + 1) / f64::from(steps),
        );
        let fill = viridis((low + high) / 2.0, range.end);
        Rectangle::new([(0.0, low), (1.0, high)], fill.filled())
    });
    chart.draw_series(strips).drawn(file)?;
    area.draw(&Text::new(
        "grey: none",
        (10, (SIZE.1 - 90) as i32),
        label_style(),
    ))
    .drawn(file)
}

#[cfg(test)]
mod tests {
    use super::{VIRIDIS, cells, viridis};
    use plotters::style::RGBColor;

    #[test]
    fn viridis_runs_through_its_stops() {
        assert_eq!(viridis(0.0, 2.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0, 2.0), RGBColor(33, 145, 140));
        assert_eq!(viridis(5.0, 2.0), RGBColor(253, 231, 37));
        let (a, b) = (VIRIDIS[0], VIRIDIS[1]);
        let halfway = viridis(0.125, 1.0);
        assert_eq!(
            halfway.0,
            ((f64::from(a.0) + f64::from(b.0)) / 2.0).round() as u8
        );
    }

    #[test]
    fn cells_reach_midway_to_their_neighbours() {
        assert_eq!(cells(&[0.0, 1.0, 3.0]), [-0.5..0.5, 0.5..2.0, 2.0..4.0]);
        assert_eq!(cells(&[2.0]), [1.5..2.5]);
    }
}
