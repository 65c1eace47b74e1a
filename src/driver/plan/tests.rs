//! Plans against independent truths: the closed-form optimum of a point
//! mass moved between rests, the differential drive's plan simulated, and
//! the one-line errors of bad requests.

use super::nlp::{Hessian, Ripopt};
use super::{Plan, Request, Scheme, plan};
use crate::driver::catalog::{Source, lookup};
use crate::driver::engine::{EngineChoice, Loaded, load};
use crate::driver::formulation::RunTimeSized;
use crate::driver::interpreted::{InputLaw, InterpretedDalembert};
use crate::runtime::integrate::{Rk4, integrate_fixed};
use std::cell::Cell;
use std::rc::Rc;

/// `m xddot = push`.
const POINT_MASS: &str = "pub struct PointMass {
    coordinates: [x],
    parameters: [m = 2.0],
    kinetic_energy: m/2*dot(x)^2,
    inputs: [push = x],
}";

fn point_mass() -> Loaded {
    let source = Source::File {
        path: "point_mass.model".into(),
        text: POINT_MASS.into(),
    };
    load(&source, EngineChoice::Jit).expect("the model derives")
}

fn assigned(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs
        .iter()
        .map(|(n, v)| (n.to_string(), v.to_string()))
        .collect()
}

/// The point mass (m = 2) from rest at 0 to rest at 1 in T = 2.
fn rest_to_rest(scheme: Scheme, nodes: usize) -> Request {
    Request {
        duration: 2.0,
        nodes,
        scheme,
        start: assigned(&[("x", "0"), ("dot(x)", "0")]),
        goal: assigned(&[("x", "1"), ("dot(x)", "0")]),
        minimize: None,
        bounds: Vec::new(),
        params: Vec::new(),
        tol: Request::TOL,
    }
}

/// The largest error of the plan's inputs against `u*(t) = m (6/T^2 -
/// 12 t/T^3)`, and of its objective against `12 m^2 / T^3` (m = 2, T = 2:
/// `u* = 3 - 3t`, `J* = 6`), from the Euler-Lagrange equations of
/// `min int u^2` under `m xddot = u`. Each node's input is compared where
/// the scheme applies it: backward Euler's at the node, the midpoint
/// rule's at the midpoint of the interval it starts.
fn errors(plan: &Plan, scheme: Scheme) -> (f64, f64) {
    let t = plan.table.column("t").expect("t");
    let push = plan.table.column("push").expect("push");
    let h = t[1] - t[0];
    let shift = match scheme {
        Scheme::BackwardEuler => 0.0,
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
fn parking(nodes: usize) -> Request {
    Request {
        duration: 4.0,
        nodes,
        scheme: Scheme::Midpoint,
        start: assigned(&[
            ("x", "0"),
            ("y", "0"),
            ("theta", "0"),
            ("phi_r", "0"),
            ("phi_l", "0"),
            ("dot(x)", "0"),
            ("dot(y)", "0"),
            ("dot(theta)", "0"),
            ("dot(phi_r)", "0"),
            ("dot(phi_l)", "0"),
        ]),
        goal: assigned(&[
            ("x", "0.3"),
            ("y", "0.1"),
            ("theta", "0"),
            ("dot(phi_r)", "0"),
            ("dot(phi_l)", "0"),
        ]),
        minimize: None,
        bounds: Vec::new(),
        params: Vec::new(),
        tol: Request::TOL,
    }
}

fn differential_drive() -> Loaded {
    load(
        &lookup("differential-drive").expect("built in"),
        EngineChoice::Jit,
    )
    .expect("derives")
}

/// The plan's inputs, held from the left as the midpoint rule applies
/// them, simulated by `simulate`'s Lagrange-d'Alembert formulation under
/// RK4, 20 steps per interval: the pose reached at T.
fn simulated_pose(plan: &Plan) -> [f64; 3] {
    let t = plan.table.column("t").expect("t");
    let inputs = ["u_right", "u_left"].map(|u| plan.table.column(u).expect("an input"));
    let interval = Rc::new(Cell::new(0));
    let held = Rc::clone(&interval);
    let law = move |_: f64, _: &[f64], _: &[f64], u: &mut [f64]| {
        for (u, column) in u.iter_mut().zip(&inputs) {
            *u = column[held.get()];
        }
    };
    let formulation = InterpretedDalembert {
        model: differential_drive().model,
        inputs: InputLaw {
            law: Box::new(law),
            reads_state: false,
        },
    };
    let h = t[1] - t[0];
    let mut x = vec![0.0; 10];
    for (i, start) in t[..t.len() - 1].iter().enumerate() {
        interval.set(i);
        let system = RunTimeSized(&formulation);
        x = integrate_fixed(&Rk4, &system, (*start, x), h / 20.0, 20, |_, _| {})
            .expect("the simulation runs");
    }
    [x[0], x[1], x[2]]
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
    let mut partial = parking(5);
    partial.start.pop();
    let error =
        plan(differential_drive(), &partial, &Ripopt::default()).expect_err("a partial start");
    assert!(error.to_string().contains("missing: dot(phi_l)"), "{error}");
}

/// Bounds that leave no way from the start to the goal: the solver's
/// answer fails the KKT conditions, and the plan is an error.
#[test]
fn an_infeasible_plan_is_an_error() {
    let mut request = rest_to_rest(Scheme::Midpoint, 11);
    request.bounds.push(("push".into(), "-0.1:0.1".into()));
    let error = plan(point_mass(), &request, &Ripopt::default()).expect_err("infeasible");
    assert!(
        error.to_string().starts_with("no verified optimum"),
        "{error}"
    );
}
