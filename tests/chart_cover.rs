//! Every configuration where the constraint rows are independent has a
//! chart that fits, for every fixture model of `tests/models/` read from
//! its file (the built-ins: `models/tests/chart_cover.rs`, which states
//! the bound): at random configurations, the chart the runtime chooses
//! (the best derived chart, or the run-time chart of partial pivoting
//! where none fits) has a pivot ratio of at least a hundredth of the
//! Cauchy-Binet bound `sqrt(gram / C(n, c))`, and the derived charts
//! cover every such configuration without the run-time chart.

use chaplygin::runtime::monitor::gram_ratio;
use chaplygin::runtime::nalgebra::DMatrix;
use chaplygin::runtime::system::next_chart;
use chaplygin_codegen::interpret::InterpretedModel;
use std::f64::consts::PI;

/// The fixture models.
const FIXTURES: [&str; 6] = [
    "lever_blade",
    "planar_pendulum",
    "roller_racer",
    "sleigh_no_symmetry",
    "tilted_trough",
    "trailing_racer",
];

fn model(name: &str) -> InterpretedModel {
    let path = format!("{}/tests/models/{name}.model", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("the fixture is there");
    InterpretedModel::from_source(&text).unwrap_or_else(|e| panic!("{}", e.render(&path)))
}

/// `C(n, k)`.
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |value, i| value * (n - i) as f64 / (i + 1) as f64)
}

/// At `q`: `None` where the rows are dependent, else whether the run-time
/// chart was needed, after asserting the chosen chart's ratio.
fn chosen_chart_fits(model: &InterpretedModel, q: &[f64]) -> Option<bool> {
    let sizes = model.sizes();
    let rows = model.constraint_matrix(q).expect("evaluates");
    let gram = gram_ratio(&DMatrix::from_row_slice(sizes.c, sizes.n, &rows));
    if gram < 1e-6 || gram.is_nan() {
        return None;
    }
    let fit = |chart| model.chart_fit(chart, q).expect("evaluates");
    let generated = model.charts().len();
    let best = (0..generated)
        .max_by(|&a, &b| fit(a).total_cmp(&fit(b)))
        .expect("a chart");
    let chosen = next_chart(generated, best, fit, model.pivoted_chart(q)).unwrap_or(best);
    let bound = 1e-2 * (gram / binomial(sizes.n, sizes.c)).sqrt();
    assert!(
        fit(chosen) >= bound,
        "q = {q:?}: chart {chosen} fits {:e}",
        fit(chosen)
    );
    Some(chosen >= generated)
}

/// 256 configurations of `n` coordinates, each uniform in `[-pi, pi]`,
/// the same every run.
fn configurations(n: usize) -> Vec<Vec<f64>> {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        PI * ((state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0)
    };
    (0..256)
        .map(|_| (0..n).map(|_| uniform()).collect())
        .collect()
}

#[test]
fn every_fixture_has_a_derived_chart_wherever_its_rows_are_independent() {
    for name in FIXTURES {
        let model = model(name);
        let mut independent = 0;
        for q in configurations(model.sizes().n) {
            if let Some(runtime) = chosen_chart_fits(&model, &q) {
                assert!(!runtime, "{name}: no derived chart fits at q = {q:?}");
                independent += 1;
            }
        }
        assert!(
            independent > 200,
            "{name}: {independent} configurations checked"
        );
    }
}
