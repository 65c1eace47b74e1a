//! Which chart of D a reduced form runs in: the charts derived at build
//! time and, where none of them fits, the run-time chart of partial
//! pivoting (the `partition` module); [`next_chart`] decides, for the
//! simulation loop and for a run's first state.

/// A chart is changed where it fits worse than this fraction of the best
/// chart (pivot ratios, `monitor::pivot_ratio`); the margin keeps
/// a run from switching back and forth.
pub const CHART_SWITCH: f64 = 0.5;

/// The run-time chart partial pivoting picks (the `partition` module) takes
/// over where the best generated chart fits worse than this fraction of it.
pub const RUNTIME_CHART: f64 = 0.01;

/// A run in a run-time chart goes back to the best generated chart where
/// that fits at least this fraction of the pivoted chart (above
/// [`RUNTIME_CHART`], so that a run does not switch back and forth).
pub const GENERATED_CHART: f64 = 0.1;

/// The chart to change to from `active` at a configuration where `fit`
/// measures each chart, the model has `generated` charts derived at build
/// time and partial pivoting picks the run-time chart `pivoted`, if any:
///
/// - in a generated chart, the pivoted chart where no generated chart fits
///   ([`RUNTIME_CHART`]), else the best generated one where the active
///   one fits worse than [`CHART_SWITCH`] times it;
/// - in a run-time chart, the best generated one where it fits again
///   ([`GENERATED_CHART`]), else the pivoted chart where the active one
///   fits worse than [`CHART_SWITCH`] times it.
///
/// ```
/// use chaplygin_runtime::system::next_chart;
/// let fits = [0.001, 0.3, 0.0, 0.9];
/// let fit = |chart: usize| fits[chart];
/// // Chart 0 degenerates and chart 1 fits: the generated chart 1.
/// assert_eq!(next_chart(2, 0, fit, Some(3)), Some(1));
/// // No generated chart fits: the run-time chart 3.
/// assert_eq!(next_chart(3, 2, |c| [0.0, 0.005, 0.0, 0.9][c], Some(3)), Some(3));
/// // In the run-time chart, back to chart 1 once it fits again.
/// assert_eq!(next_chart(2, 3, fit, Some(3)), Some(1));
/// ```
pub fn next_chart(
    generated: usize,
    active: usize,
    fit: impl Fn(usize) -> f64,
    pivoted: Option<usize>,
) -> Option<usize> {
    let (best, best_fit) = (0..generated)
        .map(|chart| (chart, fit(chart)))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let pivoted = pivoted.map(|chart| (chart, fit(chart)));
    let target = match pivoted {
        Some((runtime, runtime_fit)) if active >= generated => {
            if best_fit >= GENERATED_CHART * runtime_fit {
                best
            } else if fit(active) < CHART_SWITCH * runtime_fit {
                runtime
            } else {
                active
            }
        }
        None if active >= generated => active,
        Some((runtime, runtime_fit)) if best_fit < RUNTIME_CHART * runtime_fit => runtime,
        _ if fit(active) < CHART_SWITCH * best_fit => best,
        _ => active,
    };
    (target != active).then_some(target)
}
