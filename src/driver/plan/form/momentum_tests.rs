//! Plans in the momentum form against independent truths: the
//! differential drive's plan against its reduced plan, the snakeboard's
//! replayed to its goal, a bound on a shape velocity held, and the
//! one-line refusals.

use super::Form;
use super::tests::in_formulation;
use crate::driver::plan::catalog_tests::{assigned, built_in, request, sideways};
use crate::driver::plan::nlp::Ripopt;
use crate::driver::plan::replay::replayed_states;
use crate::driver::plan::tests::{
    WarmStart, differential_drive, parking, point_mass, rest_to_rest,
};
use crate::driver::plan::{Request, Scheme, plan};
use crate::driver::simulate::FormulationChoice;

/// `request` in the momentum form.
fn momentum(request: Request) -> Request {
    in_formulation(request, FormulationChoice::Momentum)
}

/// The differential drive's momentum state `(q, dot(phi_r), dot(phi_l))`
/// is its reduced state `(q, alpha)`: chart 0's momenta are the wheels'
/// rates, and it has no momentum `p`. The two forms' plans are one plan,
/// reached through different derivations (the reduced equations and the
/// momentum equation's composition): they agree node by node to
/// round-off, and the momentum plan's inputs, integrated by RK4 in its
/// form, park the drive.
#[test]
fn the_momentum_differential_drive_plan_is_its_reduced_plan() {
    let [momentum, reduced] = [FormulationChoice::Momentum, FormulationChoice::Reduced]
        .map(|choice| in_formulation(parking(21), choice))
        .map(|request| plan(differential_drive(), &request, &Ripopt::default()).expect("a plan"));
    assert_eq!(momentum.report.formulation, Form::Momentum);
    assert_eq!(momentum.report.chart, None);
    let width = 1 + 7 + 2;
    for (a, b) in momentum.table.rows.iter().zip(&reduced.table.rows) {
        for (x, y) in a[..width].iter().zip(&b[..width]) {
            assert!((x - y).abs() < 1e-9 * (1.0 + y.abs()), "{a:?}\n{b:?}");
        }
    }
    let (found, expected) = (momentum.report.objective, reduced.report.objective);
    assert!(
        (found - expected).abs() < 1e-9 * expected,
        "{found} vs {expected}"
    );
    let model = differential_drive().model;
    let states = replayed_states((&model, Form::Momentum), Scheme::Midpoint, &momentum.table);
    let end = &states[states.len() - 1];
    let miss = (end[..3].iter().zip([0.3, 0.1, 0.0]))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(miss < 1e-3, "{miss:e}");
}

/// The snakeboard parked sideways in `(q, dot(psi), dot(phi), p)`, its
/// one momentum curving every row (the interpolated guess, `p = 0` while
/// `y` moves, does not solve; the Lagrange plan on the same nodes does):
/// a verified optimum whose inputs, integrated by RK4 in the momentum
/// form, park the board within the midpoint rule's error of its goal,
/// the miss shrinking about fourfold as the nodes double (measured:
/// 3.6e-2 and 1.1e-2 on 21 and 41 nodes).
#[test]
#[ignore = "11 s in a debug build: cargo test -p chaplygin --features cli,plan --lib momentum_snakeboard -- --ignored"]
fn the_momentum_snakeboard_plan_parks_it_sideways() {
    let (duration, start, goal, bounds) = sideways();
    let mut warm = WarmStart::new();
    let misses = [21, 41].map(|nodes| {
        let mut lagrange = request(duration, nodes, &start, &goal);
        lagrange.bounds = assigned(&bounds);
        let first = plan(built_in("snakeboard"), &lagrange, &Ripopt::default()).expect("a plan");
        warm.keep(&first);
        let request = warm.started(momentum(lagrange));
        let planned = plan(built_in("snakeboard"), &request, &Ripopt::default()).expect("a plan");
        let model = built_in("snakeboard").model;
        let states = replayed_states((&model, Form::Momentum), Scheme::Midpoint, &planned.table);
        let end = &states[states.len() - 1];
        let miss = (end[..3].iter().zip([0.0, 0.2, 0.0]))
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{nodes} nodes: objective {} (Lagrange {}), {} iterations, replayed miss {miss:.3e}",
            planned.report.objective, first.report.objective, planned.report.iterations
        );
        miss
    });
    assert!(
        misses[0] / misses[1] > 3.0 && misses[1] < 1.5e-2,
        "{misses:?}"
    );
}

/// A bound on a shape velocity bounds the state's own entry: the
/// differential drive parks with its right wheel's rate held under a
/// bound its free plan exceeds.
#[test]
fn a_bound_on_a_shape_velocity_holds_in_the_momentum_form() {
    let free = plan(
        differential_drive(),
        &momentum(parking(21)),
        &Ripopt::default(),
    )
    .expect("a plan");
    let fastest = |plan: &crate::driver::plan::Plan| {
        let rates = plan.table.column("dot(phi_r)").expect("a column");
        rates.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
    };
    let limit = 0.8 * fastest(&free);
    let mut request = momentum(parking(21));
    request
        .bounds
        .push(("dot(phi_r)".into(), format!("{}:{limit}", -limit)));
    let bounded = plan(differential_drive(), &request, &Ripopt::default()).expect("a plan");
    assert!(
        fastest(&bounded) <= limit * (1.0 + 1e-6),
        "{}",
        fastest(&bounded)
    );
    assert!(bounded.report.objective > free.report.objective);
}

/// The one-line error of `request` on `loaded`.
fn error_of(loaded: crate::driver::engine::Loaded, request: Request) -> String {
    let error = plan(loaded, &request, &Ripopt::default()).expect_err("refused");
    let line = error.to_string();
    assert!(!line.contains('\n'), "{line}");
    line
}

#[test]
fn what_the_momentum_form_cannot_hold_is_refused_in_one_line() {
    let line = error_of(point_mass(), momentum(rest_to_rest(Scheme::Midpoint, 5)));
    assert!(
        line.contains("--formulation momentum: the model declares no symmetry"),
        "{line}"
    );
    let mut bounded = momentum(parking(5));
    bounded.bounds.push(("dot(x)".into(), "-1:1".into()));
    let line = error_of(differential_drive(), bounded);
    assert!(
        line.contains("--bound dot(x): the momentum form's state does not hold"),
        "{line}"
    );
    let mut moving = momentum(parking(5));
    moving.goal = vec![("dot(phi_r)".into(), "1".into())];
    let line = error_of(differential_drive(), moving);
    assert!(
        line.contains("--goal: the momentum form") && line.contains("dot(phi_l) are not given"),
        "{line}"
    );
}
