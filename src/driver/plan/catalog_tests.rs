//! A plan on every built-in model with inputs, each verified by its KKT
//! residuals and checked by replaying its inputs (`super::replay`: the
//! plan's start integrated by `simulate`'s Lagrange-d'Alembert formulation
//! under RK4, node `i`'s inputs held over interval `i` as the midpoint rule
//! holds them), must reach the goal. The
//! miss is the scheme's error, so it shrinks by about `2^2` when the
//! midpoint rule's step halves; that rate is the independent check.

use super::form::Form;
use super::nlp::Ripopt;
use super::replay::{Replay, replayed_states};
use super::tests::WarmStart;
use super::{Plan, PlanError, Request, Scheme, plan};
use crate::driver::catalog::lookup;
use crate::driver::engine::{EngineChoice, Loaded, load};
use crate::driver::simulate::FormulationChoice;

pub(super) fn built_in(name: &str) -> Loaded {
    load(&lookup(name).expect("built in"), EngineChoice::Jit).expect("derives")
}

/// `NAME=VALUE` pairs as a request's start, goal or bounds.
pub(super) fn assigned(pairs: &[(&str, impl ToString)]) -> Vec<(String, String)> {
    (pairs.iter())
        .map(|(name, value)| (name.to_string(), value.to_string()))
        .collect()
}

/// Coordinates and velocities `NAME=VALUE`, a start or a goal.
type Conditions = Vec<(&'static str, f64)>;

/// A plan's problem: its duration, start, goal and bounds.
pub(super) type Problem = (
    f64,
    Conditions,
    Conditions,
    Vec<(&'static str, &'static str)>,
);

/// A midpoint-rule plan of `duration` on `nodes` nodes.
pub(super) fn request(
    duration: f64,
    nodes: usize,
    start: &[(&str, f64)],
    goal: &[(&str, f64)],
) -> Request {
    Request {
        duration,
        nodes,
        scheme: Scheme::Midpoint,
        formulation: FormulationChoice::Lagrange,
        start: assigned(start),
        goal: assigned(goal),
        free_duration: false,
        minimize: None,
        final_cost: None,
        bounds: Vec::new(),
        params: Vec::new(),
        guess: None,
        tol: Request::TOL,
    }
}

/// The plan's first row replayed under its inputs as the midpoint rule
/// applies them: the state `(q, dot(q))` reached at its last node.
pub(super) fn replayed(name: &str, plan: &Plan) -> Vec<f64> {
    let model = built_in(name).model;
    let states = replayed_states((&model, Form::Lagrange), Scheme::Midpoint, &plan.table);
    states[states.len() - 1].clone()
}

/// The largest distance of the replayed end from `goal`.
fn miss(name: &str, plan: &Plan, goal: &[(&str, f64)]) -> f64 {
    let end = replayed(name, plan);
    let columns = &plan.table.columns[1..];
    (goal.iter())
        .map(|(goal, value)| {
            let index = columns.iter().position(|c| c == goal).expect("a state");
            (end[index] - value).abs()
        })
        .fold(0.0, f64::max)
}

/// `name`'s plan on `nodes` and `2 nodes - 1` nodes, the finer started
/// from the coarser (so both are the same optimum, the finer found in
/// fewer iterations): each verified, each replayed to within
/// `coarse_miss` of the goal, the miss shrinking at the midpoint rule's
/// second order.
fn plans_reach_their_goal(
    name: &str,
    duration: f64,
    nodes: usize,
    start: &[(&str, f64)],
    goal: &[(&str, f64)],
    bounds: &[(&str, &str)],
    coarse_miss: f64,
) -> [f64; 2] {
    let mut warm = WarmStart::new();
    let misses = [nodes, 2 * nodes - 1].map(|nodes| {
        let mut request = warm.started(request(duration, nodes, start, goal));
        request.bounds = assigned(bounds);
        let plan = plan(built_in(name), &request, &Ripopt::default()).expect("a plan");
        assert!(plan.report.kkt.within(1e-6), "{:?}", plan.report.kkt);
        eprintln!(
            "{name}, {nodes} nodes, {} iterations: {:?}",
            plan.report.iterations, plan.report.replay
        );
        warm.keep(&plan);
        miss(name, &plan, goal)
    });
    let rate = (misses[0] / misses[1]).log2();
    eprintln!(
        "{name}: replayed miss {:.3e} -> {:.3e}, rate {rate:.2}",
        misses[0], misses[1]
    );
    assert!(misses[0] < coarse_miss, "{name}: {misses:?}");
    assert!(rate > 1.7, "{name}: {misses:?}");
    misses
}

/// Every coordinate and velocity at rest at 0 but those in `except`.
fn at_rest(
    coordinates: &[&'static str],
    except: &[(&'static str, f64)],
) -> Vec<(&'static str, f64)> {
    let mut state: Vec<(&str, f64)> = Vec::new();
    for q in coordinates {
        let value = except
            .iter()
            .find(|(name, _)| name == q)
            .map_or(0.0, |e| e.1);
        state.push((q, value));
    }
    for q in coordinates {
        state.push((Box::leak(format!("dot({q})").into_boxed_str()), 0.0));
    }
    state
}

#[test]
fn the_caster_robot_plan_replays_to_its_goal() {
    let coordinates = ["x", "y", "theta", "phi_l", "phi_r", "beta", "phi_c"];
    let goal = [
        ("x", 0.2),
        ("y", 0.05),
        ("theta", 0.0),
        ("dot(phi_l)", 0.0),
        ("dot(phi_r)", 0.0),
    ];
    plans_reach_their_goal(
        "caster-robot",
        4.0,
        21,
        &at_rest(&coordinates, &[]),
        &goal,
        &[],
        1e-2,
    );
}

#[test]
fn the_rolling_disk_plan_replays_to_its_goal() {
    let coordinates = ["x", "y", "theta", "phi"];
    let goal = [
        ("x", 0.3),
        ("y", 0.1),
        ("theta", 0.0),
        ("dot(theta)", 0.0),
        ("dot(phi)", 0.0),
    ];
    plans_reach_their_goal(
        "rolling-disk",
        4.0,
        21,
        &at_rest(&coordinates, &[]),
        &goal,
        &[],
        1e-2,
    );
}

/// Rolled 0.1 ahead and 0.02 to the side, upright at both ends: its
/// lean, unstable at rest, is balanced by steering alone.
#[test]
fn the_upright_rolling_disk_plan_replays_to_its_goal() {
    let coordinates = ["x", "y", "psi", "phi", "theta"];
    let goal = [
        ("x", 0.1),
        ("y", 0.02),
        ("psi", 0.0),
        ("phi", 0.0),
        ("dot(phi)", 0.0),
        ("dot(theta)", 0.0),
    ];
    plans_reach_their_goal(
        "rolling-disk-3d",
        2.0,
        41,
        &at_rest(&coordinates, &[]),
        &goal,
        &[],
        2e-2,
    );
}

/// The joints from `(0.6, -0.6)` to `(0.3, -0.3)`, rest to rest.
#[test]
fn the_three_link_snake_plan_replays_to_its_goal() {
    let coordinates = ["x", "y", "theta", "a1", "a2"];
    let start = at_rest(&coordinates, &[("a1", 0.6), ("a2", -0.6)]);
    let goal = [
        ("a1", 0.3),
        ("a2", -0.3),
        ("dot(a1)", 0.0),
        ("dot(a2)", 0.0),
    ];
    plans_reach_their_goal("three-link-snake", 2.0, 21, &start, &goal, &[], 1e-2);
}

/// Parked sideways: `y` from 0 to 0.2 at rest, the heading and the
/// wheels' angle as they were. The wheels stay within 1.2 rad of straight:
/// at `phi = pi/2` their axles lie along the board, the constraints'
/// rank drops, and a plan crossing there slides the board sideways
/// within one interval, a jump no simulation reproduces.
pub(super) fn sideways() -> Problem {
    let (start, goal) = parked_sideways();
    (6.0, start, goal, vec![("phi", "-1.2:1.2")])
}

fn parks_sideways(name: &str) {
    let (duration, start, goal, bounds) = sideways();
    plans_reach_their_goal(name, duration, 41, &start, &goal, &bounds, 3e-2);
}

/// The nodes of the unbounded sideways plan: few, the jump across `phi =
/// pi/2` as it is on 41.
const NODES: usize = 21;

/// The snakeboard's start at rest with its wheels at 0.3, and its goal
/// 0.2 to the side, at rest, heading and wheels as before.
fn parked_sideways() -> (Conditions, Conditions) {
    let coordinates = ["x", "y", "theta", "psi", "phi"];
    let start = at_rest(&coordinates, &[("phi", 0.3)]);
    let mut goal = at_rest(&coordinates, &[("y", 0.2), ("phi", 0.3)]);
    goal.retain(|(name, _)| *name != "psi");
    (start, goal)
}

/// Without the bound on `phi` the sideways plan is an optimum of the
/// discrete problem (its KKT residuals pass) whose wheels cross `phi =
/// pi/2`, where the constraints lose rank; replayed, its inputs leave the
/// board short of its goal, and the plan fails in one line naming the
/// variable that departs most.
#[test]
fn the_unbounded_sideways_snakeboard_plan_fails_its_replay() {
    let (start, goal) = parked_sideways();
    let request = request(6.0, NODES, &start, &goal);
    let failure =
        plan(built_in("snakeboard"), &request, &Ripopt::default()).expect_err("not a motion");
    let message = failure.to_string();
    let Ok(error) = failure.downcast::<PlanError>() else {
        panic!("{message}")
    };
    let PlanError::Departs(departed) = *error else {
        panic!("{message}")
    };
    eprintln!("{message}\n{:?}", departed.report.replay);
    let phi = departed.table.column("phi").expect("phi");
    let crossed = phi
        .iter()
        .any(|phi| phi.abs() > std::f64::consts::FRAC_PI_2);
    assert!(crossed, "{phi:?}");
    assert!(
        departed.report.kkt.within(1e-6),
        "{:?}",
        departed.report.kkt
    );
    let end = replayed("snakeboard", &departed);
    let y = departed.table.columns[1..]
        .iter()
        .position(|c| c == "y")
        .expect("y");
    assert!(
        (end[y] - 0.2).abs() > 0.1,
        "the replay reaches y = {}",
        end[y]
    );
    let largest = &departed.report.replay.largest;
    assert!(!message.contains('\n'), "{message}");
    assert!(
        message.contains(&format!("`{}`", largest.variable)),
        "{message}"
    );
    assert!(largest.relative > Replay::TOLERANCE, "{largest:?}");
    let advice = "take more nodes, or a scheme of higher order (--scheme hermite-simpson)";
    assert!(message.ends_with(advice), "{message}");
}

#[test]
fn the_snakeboard_parks_sideways() {
    parks_sideways("snakeboard");
}

#[test]
fn the_snakeboard_of_bodies_parks_sideways() {
    parks_sideways("snakeboard-bodies");
}

/// The benchmark bicycle's lane change at 5 m/s: from the upright straight
/// run (`dot(theta_r) = -v/rR`, `dot(theta_f) = -v/rF`, on the front
/// contact's height at zero pitch) to `y_p = 1` in 3 s, upright with the
/// steer straight and the heading back to 0, by the steer torque alone.
pub(super) fn lane_change() -> Problem {
    let coordinates = [
        "x_p", "y_p", "psi", "phi", "theta_b", "delta", "theta_r", "theta_f",
    ];
    let (v, r_rear, r_front) = (5.0, 0.3, 0.35);
    let start = at_rest(&coordinates, &[])
        .into_iter()
        .map(|(name, value)| match name {
            "dot(x_p)" => (name, v),
            "dot(theta_r)" => (name, -v / r_rear),
            "dot(theta_f)" => (name, -v / r_front),
            _ => (name, value),
        })
        .collect::<Vec<_>>();
    let goal = [
        ("y_p", 1.0),
        ("psi", 0.0),
        ("phi", 0.0),
        ("delta", 0.0),
        ("dot(phi)", 0.0),
        ("dot(delta)", 0.0),
    ];
    let bounds = vec![("lean_torque", "0:0")];
    (3.0, start, goal.to_vec(), bounds)
}

#[test]
fn the_bicycle_changes_lane_by_its_steer_torque() {
    let (duration, start, goal, bounds) = lane_change();
    plans_reach_their_goal("bicycle", duration, 31, &start, &goal, &bounds, 0.02);
}
