//! Plans against independent truths: the closed-form optimum of a point
//! mass moved between rests (over a given or a free duration, to a hard or
//! a soft goal), the schemes' orders measured against the closed-form
//! optimum of a linear-quadratic problem, the differential drive's plan
//! simulated and restarted from a coarser plan, and the one-line errors
//! of bad requests.

use super::catalog_tests::{replayed, request};
use super::form::Form;
use super::nlp::{Hessian, Ripopt};
use super::replay::{Replay, replayed_states};
use super::{Plan, Request, Scheme, plan};
use crate::driver::catalog::{Source, lookup};
use crate::driver::engine::{EngineChoice, Loaded, load};
use crate::driver::simulate::FormulationChoice;
use crate::runtime::linalg::solve;
use crate::runtime::record::{CsvRecorder, Recorder, Table};

/// `m xddot = push`.
const POINT_MASS: &str = "pub struct PointMass {
    coordinates: [x],
    parameters: [m = 2.0],
    kinetic_energy: m/2*dot(x)^2,
    inputs: [push = x],
}";

pub(super) fn point_mass() -> Loaded {
    let source = Source::File {
        path: "point_mass.model".into(),
        text: POINT_MASS.into(),
    };
    load(&source, EngineChoice::Jit).expect("the model derives")
}

/// The point mass (m = 2) from rest at 0 to rest at 1 in T = 2.
pub(super) fn rest_to_rest(scheme: Scheme, nodes: usize) -> Request {
    let at_rest = |x: f64| [("x", x), ("dot(x)", 0.0)];
    Request {
        scheme,
        ..request(2.0, nodes, &at_rest(0.0), &at_rest(1.0))
    }
}

/// The largest error of the plan's inputs against `u*(t) = m (6/T^2 -
/// 12 t/T^3)`, and of its objective against `12 m^2 / T^3` (m = 2, T = 2:
/// `u* = 3 - 3t`, `J* = 6`), from the Euler-Lagrange equations of
/// `min int u^2` under `m xddot = u`. Each node's input is compared where
/// the scheme applies it: backward Euler's and Hermite-Simpson's at the
/// node, the midpoint rule's at the midpoint of the interval it starts.
fn errors(plan: &Plan, scheme: Scheme) -> (f64, f64) {
    let t = plan.table.column("t").expect("t");
    let push = plan.table.column("push").expect("push");
    let h = t[1] - t[0];
    let shift = match scheme {
        Scheme::BackwardEuler | Scheme::HermiteSimpson => 0.0,
        Scheme::Midpoint => h / 2.0,
    };
    let input = t[..t.len() - 1]
        .iter()
        .zip(&push)
        .map(|(t, u)| (u - (3.0 - 3.0 * (t + shift))).abs())
        .fold(0.0, f64::max);
    (input, (plan.report.objective - 6.0).abs())
}

#[test]
fn the_point_mass_plan_converges_to_the_closed_form_at_the_schemes_order() {
    let schemes = [(Scheme::BackwardEuler, 1.0), (Scheme::Midpoint, 2.0)];
    let hessians = [Hessian::Exact, Hessian::Lbfgs];
    for ((scheme, order), hessian) in schemes.into_iter().flat_map(|s| hessians.map(|h| (s, h))) {
        let solver = Ripopt { hessian };
        let [coarse, fine] = [21, 41].map(|nodes| {
            let plan = plan(point_mass(), &rest_to_rest(scheme, nodes), &solver).expect("a plan");
            assert!(plan.report.kkt.within(1e-6), "{:?}", plan.report.kkt);
            errors(&plan, scheme)
        });
        for (which, (c, f)) in [
            ("inputs", (coarse.0, fine.0)),
            ("objective", (coarse.1, fine.1)),
        ] {
            let rate = (c / f).log2();
            eprintln!("{scheme:?} {hessian:?} {which}: {c:.3e} -> {f:.3e}, rate {rate:.2}");
            assert!(
                c < 0.5 && rate > order - 0.3,
                "{scheme:?} {hessian:?} {which}: {c:e} -> {f:e}"
            );
        }
    }
}

/// Hermite-Simpson's inputs are linear between nodes, as the optimal
/// `u* = 3 - 3t` is: replayed from rest at 0, they move the point mass as
/// the closed form `x = 3 s^2 - 2 s^3`, `dot(x) = 3 (s - s^2)` (`s = t/2`)
/// does, at every node, and the report's replay says it departs by
/// round-off only.
#[test]
fn the_point_mass_replay_follows_the_closed_form() {
    let plan = plan(
        point_mass(),
        &rest_to_rest(Scheme::HermiteSimpson, 11),
        &Ripopt::default(),
    )
    .expect("a plan");
    let states = replayed_states(
        (&point_mass().model, Form::Lagrange),
        Scheme::HermiteSimpson,
        &plan.table,
    );
    let t = plan.table.column("t").expect("t");
    for (t, state) in t.iter().zip(&states) {
        let s = t / 2.0;
        let exact = [3.0 * s * s - 2.0 * s * s * s, 3.0 * (s - s * s)];
        for (replayed, exact) in state.iter().zip(exact) {
            assert!((replayed - exact).abs() < 1e-7, "t = {t}: {state:?}");
        }
    }
    let replay = &plan.report.replay;
    assert!(
        replay.within() && replay.largest.relative < 1e-7,
        "{replay:?}"
    );
    let json = plan.report.to_json();
    let reported = &json["replay"];
    assert_eq!(reported["tolerance"], Replay::TOLERANCE);
    assert_eq!(reported["within"], true);
    assert_eq!(reported["end"]["node"], 10);
    assert!(reported["largest"]["departure"].as_f64().expect("a number") < 1e-7);
}

/// With `|push| <= 2.5` the optimal input saturates: `u = clip(k (1 - t))`
/// with `s0 = 2.5 / k`, `x(T) = 1` giving `s0^2 = 0.6` and the cost
/// `J = 12.5 (1 - 2 s0 / 3)` (the Pontryagin solution, worked by hand). The
/// active bounds' multipliers pass the KKT check, which allows a bound
/// to be exceeded by 1e-6 (the solver relaxes its bounds by 1e-8).
#[test]
fn a_saturated_point_mass_plan_meets_its_closed_form() {
    let exact = 12.5 * (1.0 - 2.0 * 0.6_f64.sqrt() / 3.0);
    let mut request = rest_to_rest(Scheme::Midpoint, 41);
    request.bounds.push(("push".into(), "-2.5:2.5".into()));
    let plan = plan(point_mass(), &request, &Ripopt::default()).expect("a plan");
    let push = plan.table.column("push").expect("push");
    let largest = push.iter().fold(0.0_f64, |m, u| m.max(u.abs()));
    let saturated = push.iter().filter(|u| u.abs() > 2.5 - 1e-6).count();
    eprintln!(
        "saturated: objective {} vs {exact}, {saturated} nodes at the bound, {} iterations, {:?}",
        plan.report.objective, plan.report.iterations, plan.report.kkt
    );
    assert!(largest <= 2.5 + 1e-6 && saturated >= 4, "{push:?}");
    assert!((plan.report.objective - exact).abs() < 1e-2);
}

/// The differential drive from rest at the origin to the pose (0.3, 0.1,
/// 0) at rest in 4 s, by the midpoint rule on `nodes` nodes.
pub(super) fn parking(nodes: usize) -> Request {
    let mut start: Vec<(&str, f64)> = ["x", "y", "theta", "phi_r", "phi_l"]
        .into_iter()
        .map(|name| (name, 0.0))
        .collect();
    start.extend(
        ["dot(x)", "dot(y)", "dot(theta)", "dot(phi_r)", "dot(phi_l)"].map(|name| (name, 0.0)),
    );
    let goal = [
        ("x", 0.3),
        ("y", 0.1),
        ("theta", 0.0),
        ("dot(phi_r)", 0.0),
        ("dot(phi_l)", 0.0),
    ];
    request(4.0, nodes, &start, &goal)
}

pub(super) fn differential_drive() -> Loaded {
    load(
        &lookup("differential-drive").expect("built in"),
        EngineChoice::Jit,
    )
    .expect("derives")
}

/// The pose the plan's inputs reach, replayed from its start.
fn simulated_pose(plan: &Plan) -> [f64; 3] {
    let end = replayed("differential-drive", plan);
    [end[0], end[1], end[2]]
}

#[test]
fn the_differential_drive_plan_simulates_to_its_goal_at_the_schemes_order() {
    let [coarse, fine] = [21, 41].map(|nodes| {
        let plan = plan(differential_drive(), &parking(nodes), &Ripopt::default()).expect("a plan");
        eprintln!(
            "{nodes} nodes: {} iterations, {:.2} s, {:?}",
            plan.report.iterations, plan.report.seconds, plan.report.kkt
        );
        let last = plan.table.rows.last().expect("rows");
        assert!(
            last[1..4]
                .iter()
                .zip([0.3, 0.1, 0.0])
                .all(|(a, b)| (a - b).abs() < 1e-9)
        );
        let pose = simulated_pose(&plan);
        pose.iter()
            .zip([0.3, 0.1, 0.0])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    });
    let rate = (coarse / fine).log2();
    eprintln!("simulated pose's error {coarse:.3e} -> {fine:.3e}, rate {rate:.2}");
    assert!(coarse < 1e-3 && rate > 1.7, "{coarse:e} -> {fine:e}");
}

/// The one-line error of `request` on the point mass.
fn error_of(request: Request) -> String {
    let error = plan(point_mass(), &request, &Ripopt::default()).expect_err("a bad request");
    let line = error.to_string();
    assert!(!line.contains('\n'), "{line}");
    line
}

#[test]
fn bad_requests_are_one_line_errors() {
    let base = || rest_to_rest(Scheme::Midpoint, 5);
    let mut unknown = base();
    unknown.goal.push(("z".into(), "1".into()));
    assert!(error_of(unknown).contains("--goal: unknown name `z`"));
    let mut input_goal = base();
    input_goal.goal.push(("push".into(), "0".into()));
    assert!(error_of(input_goal).contains("is an input"));
    let mut one_node = base();
    one_node.nodes = 1;
    assert!(error_of(one_node).contains("at least 2 nodes"));
    let mut outside = base();
    outside.bounds.push(("x".into(), "-1:0.5".into()));
    assert!(error_of(outside).contains("lies outside --bound x=-1:0.5: the plan is infeasible"));
    let mut empty = base();
    empty.bounds.push(("push".into(), "1:-1".into()));
    assert!(error_of(empty).contains("infeasible"));
    let mut range = base();
    range.bounds.push(("push".into(), "1".into()));
    assert!(error_of(range).contains("expected LO:HI"));
    let mut parameter = base();
    parameter.params.push(("mass".into(), 1.0));
    assert!(error_of(parameter).contains("unknown parameter `mass`"));
    let mut cost = base();
    cost.minimize = Some("push^2 + w".into());
    assert!(error_of(cost).contains("--minimize"));
    let mut free = base();
    (free.free_duration, free.duration) = (true, 0.0);
    let line = error_of(free);
    assert!(line.contains("--duration 0: the free duration's first guess must be positive"));
    let mut final_cost = base();
    final_cost.final_cost = Some("push^2".into());
    assert!(error_of(final_cost).contains("--final-cost push^2: `push` is not"));
    let dir = tempfile::tempdir().expect("a directory");
    let path = dir.path().join("guess.csv");
    std::fs::write(&path, "t,x,z,speed\n0,0,1,2\n").expect("written");
    let mut guess = base();
    guess.guess = Some(path);
    assert!(error_of(guess).contains("guess.csv: unknown columns z, speed"));
    let mut long_guess = unit_rest_to_rest(Scheme::HermiteSimpson, 5);
    (long_guess.free_duration, long_guess.duration) = (true, 30.0);
    long_guess.final_cost = Some("t".into());
    let line = error_of(long_guess);
    assert!(
        line.contains("lower bound 3, a tenth of --duration"),
        "{line}"
    );
    let mut off = parking(5);
    off.start.retain(|(name, _)| name != "dot(x)");
    off.start.push(("dot(x)".into(), "1".into()));
    let error = plan(differential_drive(), &off, &Ripopt::default()).expect_err("off");
    assert!(
        error.to_string() == "the start is off the model's constraints: residual 1.0e0",
        "{error}"
    );
    let mut moving = parking(5);
    moving.goal.push(("dot(x)".into(), "1".into()));
    let error = plan(differential_drive(), &moving, &Ripopt::default()).expect_err("off");
    assert_eq!(
        error.to_string(),
        "--goal: the given velocities break the model's constraints at the goal's pose (least \
         residual 1.0e0, relative to them)"
    );
}

/// The differential drive's parking from the pose alone, its wheels'
/// angles free: neither the dynamics nor the cost reads them, so the
/// optimum is the whole start's, and the first node meets `A qdot = 0`.
#[test]
fn a_start_leaving_the_wheels_angles_free_costs_what_the_whole_start_does() {
    let whole = parking(11);
    let mut partial = whole.clone();
    partial
        .start
        .retain(|(name, _)| !name.starts_with("phi_") && !name.starts_with("dot("));
    partial
        .start
        .extend(["dot(phi_r)", "dot(phi_l)"].map(|name| (name.to_string(), "0".to_string())));
    let [whole, partial] = [whole, partial]
        .map(|request| plan(differential_drive(), &request, &Ripopt::default()).expect("a plan"));
    let (a, b) = (whole.report.objective, partial.report.objective);
    assert!((a - b).abs() < 1e-7 * a, "{a} vs {b}");
    let residual = partial
        .table
        .column("constraint_residual")
        .expect("a column");
    assert!(residual[0] < 1e-12, "{}", residual[0]);
}

/// The differential drive parked from the pose alone, its velocities
/// free: held to `A qdot = 0` by the first node's rows, the Lagrange
/// form's plan converges to the reduced form's, whose state meets the
/// constraints by construction, at the midpoint rule's order (their
/// objectives 0.77 % apart on 11 nodes, 0.19 % on 21); both cost less
/// than a start at rest.
#[test]
fn a_start_with_free_velocities_plans_as_the_reduced_form_does() {
    let from_pose = |nodes: usize, formulation: FormulationChoice| {
        let mut request = parking(nodes);
        request
            .start
            .retain(|(name, _)| ["x", "y", "theta"].contains(&name.as_str()));
        request.formulation = formulation;
        plan(differential_drive(), &request, &Ripopt::default()).expect("a plan")
    };
    let gaps = [11, 21].map(|nodes| {
        let lagrange = from_pose(nodes, FormulationChoice::Lagrange);
        let residual = lagrange
            .table
            .column("constraint_residual")
            .expect("a column");
        assert!(residual[0] < 1e-12, "{}", residual[0]);
        let reduced = from_pose(nodes, FormulationChoice::Reduced);
        let at_rest = plan(differential_drive(), &parking(nodes), &Ripopt::default());
        let at_rest = at_rest.expect("a plan").report.objective;
        assert!(lagrange.report.objective < at_rest);
        (lagrange.report.objective - reduced.report.objective).abs()
    });
    let rate = (gaps[0] / gaps[1]).log2();
    assert!((1.7..2.3).contains(&rate), "{gaps:?}: rate {rate}");
}

/// Bounds that leave no way from the start to the goal (a push of at
/// most 0.1 moves the mass 0.05 in the time): the solver's answer fails
/// the KKT conditions, and the plan is an error naming the constraint
/// furthest from holding. On one interval the
/// solver finds the problem locally infeasible in 40 iterations; on 11
/// nodes it ran to its iteration limit.
#[test]
fn an_infeasible_plan_is_an_error() {
    let mut request = rest_to_rest(Scheme::Midpoint, 2);
    request.bounds.push(("push".into(), "-0.1:0.1".into()));
    let error = plan(point_mass(), &request, &Ripopt::default()).expect_err("infeasible");
    let line = error.to_string();
    assert!(line.starts_with("no verified optimum"), "{line}");
    // With both ends at rest, the one interval's position defect is
    // x_1 - x_0 - h (v_0 + v_1)/2 = 1 whatever the push.
    let worst = "; the largest violation: the defect of `x` from t = 0.0000 to 2.0000, by 1.0e0";
    assert!(line.ends_with(worst), "{line}");
}

/// The trailing racer of `tests/models/trailing_racer.model`: its
/// dynamics are unchanged by the mirror image about its heading
/// (`y, theta, phi` and the input negated).
fn trailing_racer() -> Loaded {
    let source = Source::File {
        path: "trailing_racer.model".into(),
        text: include_str!("../../../tests/models/trailing_racer.model").into(),
    };
    load(&source, EngineChoice::Jit).expect("the model derives")
}

/// The racer driven from rest 0.5 m straight ahead in 4 s, `y` 0 at the
/// goal and the rest of it free.
fn straight_ahead() -> Request {
    let start = [("x", 0.0), ("y", 0.0), ("theta", 0.0), ("phi", 0.0)];
    let mut request = request(4.0, 41, &start, &[("x", 0.5), ("y", 0.0)]);
    request.start.extend([
        ("dot(x)".into(), "0".into()),
        ("dot(phi)".into(), "0".into()),
    ]);
    request.goal.push(("dot(phi)".into(), "0".into()));
    request
}

/// The default guess of [`straight_ahead`] (straight ahead, the input 0)
/// is its own mirror image, and so is every iterate of Newton's method
/// from it, while the racer can only be propelled by wiggling: the solve
/// from it ends unverified. Solved again with the inputs nudged, the plan
/// is verified and wiggles, and it costs what the plan from a wiggling
/// guess (`phi = 0.1 sin(pi t / T)`, `u1 = 0.1 sin(2 pi t / T)`) costs, to
/// 1e-7. The plan from that guess, given, is solved once.
#[test]
fn a_default_guess_stalled_by_a_symmetry_is_solved_again_nudged() {
    let nudged = plan(trailing_racer(), &straight_ahead(), &Ripopt::default()).expect("a plan");
    let restart = nudged.report.restart.as_ref().expect("solved again");
    assert!(
        restart.iterations > 0 && restart.status != nudged.report.status,
        "{restart:?}"
    );
    let phi = nudged.table.column("phi").expect("phi");
    assert!(
        phi.iter().any(|angle| angle.abs() > 0.1),
        "no wiggle: {phi:?}"
    );

    let dir = tempfile::tempdir().expect("a directory");
    let path = dir.path().join("wiggle.csv");
    let pi = std::f64::consts::PI;
    let rows: Vec<String> = (0..=40)
        .map(|k| f64::from(k) / 40.0)
        .map(|s| {
            format!(
                "{},{},{}",
                4.0 * s,
                0.1 * (pi * s).sin(),
                0.1 * (2.0 * pi * s).sin()
            )
        })
        .collect();
    std::fs::write(&path, format!("t,phi,u1\n{}\n", rows.join("\n"))).expect("written");
    let mut request = straight_ahead();
    request.guess = Some(path);
    let guessed = plan(trailing_racer(), &request, &Ripopt::default()).expect("a plan");
    assert!(guessed.report.restart.is_none());
    let (a, b) = (nudged.report.objective, guessed.report.objective);
    assert!((a - b).abs() < 1e-7 * b, "{a} vs {b}");
}

/// The point mass with `m = 1` from rest at 0 to rest at `d = 1` in `T = 1`.
fn unit_rest_to_rest(scheme: Scheme, nodes: usize) -> Request {
    let mut request = rest_to_rest(scheme, nodes);
    request.duration = 1.0;
    request.params.push(("m".into(), 1.0));
    request
}

/// Hermite-Simpson is exact on the point mass's optimum, a cubic `x` under
/// a linear input `u = 6 - 12 t`: the objective is `12 m^2 d^2 / T^3 = 12`.
#[test]
fn the_hermite_simpson_point_mass_plan_costs_12() {
    let plan = plan(
        point_mass(),
        &unit_rest_to_rest(Scheme::HermiteSimpson, 51),
        &Ripopt::default(),
    )
    .expect("a plan");
    eprintln!(
        "Hermite-Simpson, 51 nodes: objective {:.12} in {} iterations",
        plan.report.objective, plan.report.iterations
    );
    assert!((plan.report.objective - 12.0).abs() < 1e-6);
    let push = plan.table.column("push").expect("push");
    let t = plan.table.column("t").expect("t");
    for (t, u) in t.iter().zip(&push) {
        assert!((u - (6.0 - 12.0 * t)).abs() < 1e-4, "{t}: {u}");
    }
}

/// The optimum of `int_0^T (u^2 + x^2) dt` under `xddot = u` from rest at
/// 0 to rest at 1. Euler-Lagrange gives `x'''' = -x`, so `x = sum c_k
/// phi_k` over `Re, Im e^{r t}` with `r = (+-1 + i)/sqrt 2`, the `c_k` from
/// the four end conditions; by parts, `J = [x'' x' - x''' x]_0^T =
/// -x'''(T)`.
fn linear_quadratic_optimum(duration: f64) -> f64 {
    let a = std::f64::consts::FRAC_1_SQRT_2;
    let basis = |t: f64, derivative: usize| {
        let mut values = [0.0; 4];
        for (pair, sign) in [(0, 1.0), (1, -1.0)] {
            let grow = (sign * a * t).exp();
            let (mut re, mut im) = (grow * (a * t).cos(), grow * (a * t).sin());
            for _ in 0..derivative {
                (re, im) = (sign * a * re - a * im, a * re + sign * a * im);
            }
            values[2 * pair] = re;
            values[2 * pair + 1] = im;
        }
        values
    };
    let conditions = [
        basis(0.0, 0),
        basis(0.0, 1),
        basis(duration, 0),
        basis(duration, 1),
    ];
    let c = solve(&conditions, &[0.0, 0.0, 1.0, 0.0]).expect("regular");
    let third = basis(duration, 3);
    -(0..4).map(|k| c[k] * third[k]).sum::<f64>()
}

/// The least-squares slope of `ln error` against `ln h`.
fn fitted_order(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|(h, e)| (h.ln(), e.ln())).collect();
    let count = logs.len() as f64;
    let (mean_h, mean_e) = logs
        .iter()
        .fold((0.0, 0.0), |(a, b), (h, e)| (a + h / count, b + e / count));
    let covariance: f64 = logs.iter().map(|(h, e)| (h - mean_h) * (e - mean_e)).sum();
    let variance: f64 = logs.iter().map(|(h, _)| (h - mean_h).powi(2)).sum();
    covariance / variance
}

#[test]
fn the_schemes_converge_at_orders_1_2_and_4() {
    let exact = linear_quadratic_optimum(2.0);
    let grids = [
        (Scheme::BackwardEuler, 1.0, [11, 21, 41, 81]),
        (Scheme::Midpoint, 2.0, [11, 21, 41, 81]),
        (Scheme::HermiteSimpson, 4.0, [11, 21, 41, 81]),
    ];
    for (scheme, order, nodes) in grids {
        let errors: Vec<(f64, f64)> = nodes
            .iter()
            .map(|&nodes| {
                let mut request = rest_to_rest(scheme, nodes);
                request.params.push(("m".into(), 1.0));
                request.minimize = Some("push^2 + x^2".into());
                let plan = plan(point_mass(), &request, &Ripopt::default()).expect("a plan");
                let h = 2.0 / (nodes - 1) as f64;
                (h, (plan.report.objective - exact).abs())
            })
            .collect();
        let measured = fitted_order(&errors);
        eprintln!("{scheme:?}: J* = {exact:.12}, (h, error) {errors:?}, order {measured:.3}");
        assert!((measured - order).abs() < 0.3, "{scheme:?}: {measured}");
    }
}

/// `min T + int_0^T u^2 dt` for the point mass (`m = d = 1`): over a given
/// `T` the cost is `T + 12/T^3`, least at `T^4 = 36`, `T = sqrt 6`, where
/// it is `8/sqrt 6`. The `T` comes as a final cost `t`, or as the running
/// cost's 1.
#[test]
fn a_free_duration_meets_its_closed_form_optimum() {
    let (best, least) = (6.0_f64.sqrt(), 8.0 / 6.0_f64.sqrt());
    for (minimize, final_cost) in [(None, Some("t")), (Some("1 + push^2"), None)] {
        let mut request = unit_rest_to_rest(Scheme::HermiteSimpson, 21);
        request.free_duration = true;
        request.minimize = minimize.map(String::from);
        request.final_cost = final_cost.map(String::from);
        let plan = plan(point_mass(), &request, &Ripopt::default()).expect("a plan");
        let report = &plan.report;
        eprintln!(
            "free duration: T {:.12} vs {best:.12}, J {:.12} vs {least:.12}, {} iterations",
            report.duration, report.objective, report.iterations
        );
        assert!((report.duration - best).abs() < 1e-6);
        assert!((report.objective - least).abs() < 1e-8);
        let t = plan.table.column("t").expect("t");
        assert!((t[20] - report.duration).abs() < 1e-12);
    }
}

/// A soft goal `k m (x(T) - 1)^2` instead of a hard one (`m = 1`, `T = 1`,
/// `k = 12`): reaching `y` costs `12 y^2 / T^3`, so `y = k / (k + 12) =
/// 1/2` and the cost is `3 + 3 = 6`.
#[test]
fn a_final_cost_meets_its_closed_form_optimum() {
    let mut request = unit_rest_to_rest(Scheme::HermiteSimpson, 21);
    request.goal.retain(|(name, _)| name != "x");
    request.final_cost = Some("12*m*(x - 1)^2".into());
    let plan = plan(point_mass(), &request, &Ripopt::default()).expect("a plan");
    let x = plan.table.column("x").expect("x");
    eprintln!(
        "soft goal: x(T) {:.12}, J {:.12}",
        x[20], plan.report.objective
    );
    assert!((x[20] - 0.5).abs() < 1e-7);
    assert!((plan.report.objective - 6.0).abs() < 1e-7);
}

/// `table` as CSV at `path`.
pub(super) fn write_csv(table: &Table, path: &std::path::Path) {
    let mut recorder = CsvRecorder::create(path).expect("created");
    recorder.start(&table.columns).expect("header");
    for row in &table.rows {
        recorder.record(row).expect("row");
    }
    recorder.finish().expect("flushed");
}

/// Requests started from the plan kept last, its table written as their
/// `guess`: a finer grid's from a coarser plan, another form's from the
/// Lagrange form's plan.
pub(super) struct WarmStart {
    dir: tempfile::TempDir,
    last: Option<std::path::PathBuf>,
}

impl WarmStart {
    pub(super) fn new() -> Self {
        WarmStart {
            dir: tempfile::tempdir().expect("a directory"),
            last: None,
        }
    }

    /// `request`, started from the plan kept last, if any.
    pub(super) fn started(&mut self, request: Request) -> Request {
        Request {
            guess: self.last.take(),
            ..request
        }
    }

    /// Keeps `plan` as the next request's start.
    pub(super) fn keep(&mut self, plan: &Plan) {
        let path = (self.dir.path()).join(format!("plan-{}.csv", plan.table.rows.len()));
        write_csv(&plan.table, &path);
        self.last = Some(path);
    }
}

#[test]
fn a_coarser_plan_as_the_guess_saves_iterations() {
    let coarse = plan(differential_drive(), &parking(21), &Ripopt::default()).expect("a plan");
    let dir = tempfile::tempdir().expect("a directory");
    let path = dir.path().join("plan.csv");
    write_csv(&coarse.table, &path);
    let cold = plan(differential_drive(), &parking(41), &Ripopt::default()).expect("a plan");
    let mut request = parking(41);
    request.guess = Some(path);
    let warm = plan(differential_drive(), &request, &Ripopt::default()).expect("a plan");
    eprintln!(
        "41 nodes: {} iterations from the default guess, {} from the 21-node plan",
        cold.report.iterations, warm.report.iterations
    );
    assert!(warm.report.iterations < cold.report.iterations);
    let difference = (warm.report.objective - cold.report.objective).abs();
    assert!(
        difference < 1e-6 * cold.report.objective.abs(),
        "{difference}"
    );
}

/// Hermite-Simpson parks the differential drive on 11, 21 and 41 nodes,
/// each plan started from the coarser one: the objectives' differences
/// shrink by `2^4`, and their extrapolated limit agrees with the midpoint
/// rule's Richardson extrapolation from 21 and 41 nodes (whose own error
/// is of higher order than the midpoint rule's `h^2`).
#[test]
fn hermite_simpson_parks_the_differential_drive_at_fourth_order() {
    let mut warm = WarmStart::new();
    let objectives = [11, 21, 41].map(|nodes| {
        let mut request = warm.started(parking(nodes));
        request.scheme = Scheme::HermiteSimpson;
        let plan = plan(differential_drive(), &request, &Ripopt::default()).expect("a plan");
        warm.keep(&plan);
        plan.report.objective
    });
    let ratio = (objectives[0] - objectives[1]) / (objectives[1] - objectives[2]);
    let limit = objectives[2] - (objectives[1] - objectives[2]) / 15.0;
    let [coarse, fine] = [21, 41].map(|nodes| {
        let plan = plan(differential_drive(), &parking(nodes), &Ripopt::default()).expect("a plan");
        plan.report.objective
    });
    let richardson = fine - (coarse - fine) / 3.0;
    eprintln!(
        "Hermite-Simpson {objectives:?}: ratio {ratio:.2}, limit {limit:.9e}; \
         midpoint {coarse:.9e}, {fine:.9e}: limit {richardson:.9e}"
    );
    assert!((ratio.log2() - 4.0).abs() < 0.3, "{ratio}");
    assert!(
        (limit - richardson).abs() < 2e-5 * limit,
        "{limit} vs {richardson}"
    );
}

/// The observer is told of every iteration, numbered from 0, the last one
/// at the optimum the report gives. One that stops the solve at once gets
/// the first guess back as `PlanError::Interrupted`: the start and goal
/// interpolated, at rest, whose position defects are the step, `1/20`,
/// its primal residual.
#[test]
fn an_observer_sees_every_iteration_and_may_stop_the_solve() {
    let request = rest_to_rest(Scheme::Midpoint, 21);
    let mut seen = Vec::new();
    let planned = super::plan_watched(
        point_mass(),
        &request,
        &Ripopt::default(),
        &mut |iteration| {
            seen.push(*iteration);
            std::ops::ControlFlow::Continue(())
        },
    )
    .expect("a plan");
    let numbers: Vec<usize> = seen.iter().map(|iteration| iteration.number).collect();
    assert_eq!(numbers, (0..=planned.report.iterations).collect::<Vec<_>>());
    let last = seen.last().expect("an iteration");
    let objective = planned.report.objective;
    assert!(
        (last.objective - objective).abs() <= 1e-10 * objective,
        "{last:?}"
    );
    let error = super::plan_watched(point_mass(), &request, &Ripopt::default(), &mut |_| {
        std::ops::ControlFlow::Break(())
    })
    .expect_err("interrupted");
    let Ok(super::PlanError::Interrupted(stopped)) =
        error.downcast::<super::PlanError>().map(|e| *e)
    else {
        panic!("not an interruption");
    };
    assert_eq!(stopped.report.status, super::Report::INTERRUPTED);
    assert_eq!(stopped.report.iterations, 0);
    assert_eq!(stopped.report.objective, 0.0);
    let primal = stopped.report.kkt.primal;
    assert!((primal - 0.05).abs() < 1e-12, "{primal}");
    let x = stopped.table.column("x").expect("x");
    assert_eq!((x.len(), x[0], x[20]), (21, 0.0, 1.0));
}
