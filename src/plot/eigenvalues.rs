//! `eigenvalues.png`: the eigenvalues of a linearization swept over a
//! variable (`chaplygin linearize --sweep`), their real parts in the upper
//! panel and their imaginary parts in the lower one, as Meijaard et al.
//! (2007) draw the benchmark bicycle's in their Figure 3. Each mode is
//! followed from one value to the next (the eigenvalue nearest to where the
//! mode was heading, [`modes`]) and drawn as a line of its own colour, so
//! that branches that cross or merge stay apart; the intervals where the
//! motion is asymptotically stable are shaded in both panels and their ends
//! marked and labelled. The zero line of the real parts is drawn: stability
//! is every real part below it.

use super::style::{
    Axis, Drawn, draw_axes, label_style, padded_range, png, tick_labels, title_style,
};
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
    /// The intervals of the variable where the motion is asymptotically
    /// stable, shaded.
    pub stable: Vec<(f64, f64)>,
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
        let modes = modes(sweep);
        panel(&upper, file, sweep, &modes, Part::Real)?;
        panel(&lower, file, sweep, &modes, Part::Imaginary)
    })
}

/// Which part of the eigenvalues a panel draws.
#[derive(Clone, Copy)]
enum Part {
    Real,
    Imaginary,
}

impl Part {
    fn of(self, (re, im): (f64, f64)) -> f64 {
        match self {
            Part::Real => re,
            Part::Imaginary => im,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Part::Real => "real part",
            Part::Imaginary => "imaginary part",
        }
    }
}

/// One mode followed across the sweep: `(value, eigenvalue)` at each value
/// where it was found.
type Mode = Vec<(f64, (f64, f64))>;

/// The eigenvalues grouped into modes: at each value, each mode takes the
/// eigenvalue nearest (in the complex plane) to where it was heading (its
/// last eigenvalue moved on by its last change), nearest pairs first; an
/// eigenvalue left over starts a new mode.
fn modes(sweep: &EigenvalueSweep) -> Vec<Mode> {
    let mut modes: Vec<Mode> = Vec::new();
    for (&value, eigenvalues) in sweep.values.iter().zip(&sweep.eigenvalues) {
        let heading: Vec<(f64, f64)> = modes.iter().map(heading_of).collect();
        let mut pairs: Vec<(f64, usize, usize)> = heading
            .iter()
            .enumerate()
            .flat_map(|(m, &(re, im))| {
                eigenvalues
                    .iter()
                    .enumerate()
                    .map(move |(e, &(er, ei))| ((er - re).hypot(ei - im), m, e))
            })
            .collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (mut mode_taken, mut taken) =
            (vec![false; modes.len()], vec![false; eigenvalues.len()]);
        for (_, m, e) in pairs {
            if !mode_taken[m] && !taken[e] {
                (mode_taken[m], taken[e]) = (true, true);
                modes[m].push((value, eigenvalues[e]));
            }
        }
        let left: Vec<(f64, f64)> = eigenvalues
            .iter()
            .zip(&taken)
            .filter(|(_, taken)| !**taken)
            .map(|(&eigenvalue, _)| eigenvalue)
            .collect();
        modes.extend(left.into_iter().map(|eigenvalue| vec![(value, eigenvalue)]));
    }
    modes
}

/// Where `mode` heads next: its last eigenvalue plus its last change.
fn heading_of(mode: &Mode) -> (f64, f64) {
    match mode.as_slice() {
        [.., (_, (r0, i0)), (_, (r1, i1))] => (2.0 * r1 - r0, 2.0 * i1 - i0),
        [.., (_, last)] => *last,
        [] => (f64::NAN, f64::NAN),
    }
}

/// One panel: each mode's `part` against the variable, in its colour, over
/// the shaded stable intervals, with the zero line.
fn panel(
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    file: &Path,
    sweep: &EigenvalueSweep,
    modes: &[Mode],
    part: Part,
) -> Result<(), PlotError> {
    let values = modes.iter().flatten().map(|&(_, e)| part.of(e));
    let finite: Vec<f64> = values.filter(|v| v.is_finite()).collect();
    let x_range = padded_range(sweep.values.iter().copied(), 0.02);
    let y_range: Range<f64> = padded_range(finite.iter().copied().chain([0.0]), 0.05);
    let (x_labels, y_labels) = (tick_labels(&x_range), tick_labels(&y_range));
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(100)
        .build_cartesian_2d(x_range.clone(), y_range.clone())
        .drawn(file)?;
    let x = Axis {
        name: &sweep.variable,
        labels: &x_labels,
    };
    let y = Axis {
        name: part.name(),
        labels: &y_labels,
    };
    draw_axes(&mut chart, x, y, true).drawn(file)?;
    let band = GREEN.mix(0.12).filled();
    for &(from, to) in &sweep.stable {
        let corners = [(from, y_range.start), (to, y_range.end)];
        chart
            .draw_series(std::iter::once(Rectangle::new(corners, band)))
            .drawn(file)?;
        for end in [from, to] {
            let mark = vec![(end, y_range.start), (end, y_range.end)];
            chart
                .draw_series(std::iter::once(PathElement::new(
                    mark,
                    GREEN.stroke_width(1),
                )))
                .drawn(file)?;
            if let Part::Real = part {
                let top = y_range.end - 0.06 * (y_range.end - y_range.start);
                let label = Text::new(format!(" {end:.4}"), (end, top), label_style());
                chart.draw_series(std::iter::once(label)).drawn(file)?;
            }
        }
    }
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(x_range.start, 0.0), (x_range.end, 0.0)],
            BLACK.stroke_width(1),
        )))
        .drawn(file)?;
    for (index, mode) in modes.iter().enumerate() {
        let colour = Palette99::pick(index).to_rgba();
        let points: Vec<(f64, f64)> = mode.iter().map(|&(v, e)| (v, part.of(e))).collect();
        let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        for run in super::style::finite_runs(&points, finite) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    run,
                    colour.stroke_width(2),
                )))
                .drawn(file)?;
        }
        let dots = points.iter().filter(|p| finite(p));
        chart
            .draw_series(dots.map(|&p| Circle::new(p, 2, colour.filled())))
            .drawn(file)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{EigenvalueSweep, modes};

    /// Two real eigenvalues `v` and `-v`, listed by descending real part,
    /// swap places at `v = 0`; a conjugate pair `-1 +- v i` merges there.
    /// Each mode keeps its own branch through the crossing.
    #[test]
    fn modes_follow_their_branches_through_crossings() {
        let values: Vec<f64> = (-4..=4).map(|i| f64::from(i) / 2.0).collect();
        let eigenvalues = values
            .iter()
            .map(|&v| {
                let mut listed = vec![(v, 0.0), (-v, 0.0), (-1.0, v), (-1.0, -v)];
                listed.sort_by(|a, b| b.0.total_cmp(&a.0).then(b.1.total_cmp(&a.1)));
                listed
            })
            .collect();
        let sweep = EigenvalueSweep {
            variable: "v".into(),
            values: values.clone(),
            eigenvalues,
            stable: Vec::new(),
        };
        let found = modes(&sweep);
        assert_eq!(found.len(), 4);
        for mode in &found {
            assert_eq!(mode.len(), values.len());
            let (first, second) = (mode[0].1, mode[1].1);
            let slope = (second.0 - first.0, second.1 - first.1);
            for (v, e) in mode {
                let t = v - values[0];
                let expected = (first.0 + 2.0 * t * slope.0, first.1 + 2.0 * t * slope.1);
                assert!(
                    (e.0 - expected.0).abs() < 1e-12 && (e.1 - expected.1).abs() < 1e-12,
                    "{mode:?}"
                );
            }
        }
    }
}
