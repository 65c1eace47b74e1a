//! Ipopt against ripopt on the same programs: the point mass moved rest to
//! rest, whose optimum `12 m^2 d^2 / T^3` (6 for m = 2, d = 1, T = 2)
//! Hermite-Simpson meets exactly, and the differential drive parked; each
//! answer verified by the KKT check of `plan`. And both timed on the
//! issue's problems (BENCHMARKS.md, "Ipopt against ripopt").

use std::ops::ControlFlow;

use super::super::{Hessian, Ripopt, Solver};
use super::Ipopt;
use crate::driver::engine::Loaded;
use crate::driver::plan::catalog_tests::{
    Problem, assigned, built_in, lane_change, request, sideways,
};
use crate::driver::plan::tests::{differential_drive, parking, point_mass, rest_to_rest};
use crate::driver::plan::{Plan, PlanError, Report, Request, Scheme, plan, plan_watched};

/// The largest difference of two plans' inputs `push`.
fn largest_input_difference(a: &Plan, b: &Plan, input: &str) -> f64 {
    let (a, b) = (
        a.table.column(input).expect("a"),
        b.table.column(input).expect("b"),
    );
    a.iter()
        .zip(&b)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

#[test]
fn ipopt_and_ripopt_meet_the_point_mass_closed_form_on_the_same_grid() {
    let request = rest_to_rest(Scheme::HermiteSimpson, 51);
    let ripopt = plan(point_mass(), &request, &Ripopt::default()).expect("ripopt's plan");
    for hessian in [Hessian::Exact, Hessian::Lbfgs] {
        let ipopt = plan(point_mass(), &request, &Ipopt { hessian }).expect("ipopt's plan");
        let (objective, reference) = (ipopt.report.objective, ripopt.report.objective);
        eprintln!(
            "{hessian:?}: ipopt {objective} in {} iterations, ripopt {reference} in {}, {:?}",
            ipopt.report.iterations, ripopt.report.iterations, ipopt.report.kkt
        );
        assert!(ipopt.report.kkt.within(1e-6), "{:?}", ipopt.report.kkt);
        assert!((objective - reference).abs() <= 1e-8 * reference);
        assert!((objective - 6.0).abs() <= 1e-6 * 6.0, "{objective}");
        assert!(largest_input_difference(&ipopt, &ripopt, "push") < 1e-6);
    }
}

#[test]
fn ipopt_and_ripopt_park_the_differential_drive_at_the_same_cost() {
    let request = parking(21);
    let ripopt = plan(differential_drive(), &request, &Ripopt::default()).expect("ripopt's plan");
    let ipopt = plan(differential_drive(), &request, &Ipopt::default()).expect("ipopt's plan");
    let (objective, reference) = (ipopt.report.objective, ripopt.report.objective);
    eprintln!(
        "ipopt {objective} in {} iterations, ripopt {reference} in {}",
        ipopt.report.iterations, ripopt.report.iterations
    );
    assert_eq!(ipopt.report.solver, "ipopt (exact Hessian)");
    assert!((objective - reference).abs() <= 1e-6 * reference);
}

#[test]
fn ipopt_reports_each_iteration_and_stops_where_its_observer_says() {
    let request = rest_to_rest(Scheme::Midpoint, 21);
    let mut numbers = Vec::new();
    let planned = plan_watched(
        point_mass(),
        &request,
        &Ipopt::default(),
        &mut |iteration| {
            numbers.push(iteration.number);
            ControlFlow::Continue(())
        },
    )
    .expect("a plan");
    assert_eq!(numbers, (0..=planned.report.iterations).collect::<Vec<_>>());
    let error = plan_watched(
        point_mass(),
        &request,
        &Ipopt::default(),
        &mut |iteration| {
            if iteration.number < 2 {
                ControlFlow::Continue(())
            } else {
                ControlFlow::Break(())
            }
        },
    )
    .expect_err("interrupted");
    let Ok(PlanError::Interrupted(stopped)) = error.downcast::<PlanError>().map(|e| *e) else {
        panic!("not an interruption");
    };
    assert_eq!(stopped.report.status, Report::INTERRUPTED);
    assert_eq!(stopped.report.iterations, 2);
}

/// `problem`'s midpoint-rule request on `nodes` nodes.
fn problem_request((duration, start, goal, bounds): &Problem, nodes: usize) -> Request {
    Request {
        bounds: assigned(bounds),
        ..request(*duration, nodes, start, goal)
    }
}

/// The CPU time this thread has run (`/proc/thread-self/schedstat`, in
/// nanoseconds), in seconds.
fn thread_cpu_seconds() -> f64 {
    let schedstat = std::fs::read_to_string("/proc/thread-self/schedstat").expect("schedstat");
    let nanoseconds: f64 = (schedstat.split_whitespace().next())
        .and_then(|field| field.parse().ok())
        .expect("a CPU time");
    nanoseconds * 1e-9
}

/// One solve timed: its solver, objective (or failure), iterations and
/// CPU seconds.
struct Timed {
    label: String,
    outcome: Result<(f64, usize), String>,
    seconds: f64,
}

/// `loaded`'s plan for `request` by each solver with each Hessian.
fn timed_solves(loaded: &Loaded, request: &Request) -> Vec<Timed> {
    let mut solves = Vec::new();
    for hessian in [Hessian::Exact, Hessian::Lbfgs] {
        let solvers: [(&str, &dyn Solver); 2] = [
            ("ripopt", &Ripopt { hessian }),
            ("ipopt", &Ipopt { hessian }),
        ];
        for (name, solver) in solvers {
            let started = thread_cpu_seconds();
            let planned = plan(loaded.clone(), request, solver);
            solves.push(Timed {
                label: format!("{name}, {hessian:?} Hessian"),
                outcome: (planned.map(|p| (p.report.objective, p.report.iterations)))
                    .map_err(|error| error.to_string()),
                seconds: thread_cpu_seconds() - started,
            });
        }
    }
    solves
}

/// Each solver with each Hessian on the issue's problems: the point mass
/// (51 Hermite-Simpson nodes), the differential drive parked (41 nodes),
/// the snakeboard parked sideways (41 nodes) and the bicycle's lane change
/// (31 nodes), a table of objectives (and their excess over the least
/// found: the problems are not convex, and a verified optimum may be a
/// local one), iterations and the CPU time of each whole plan. Every solve
/// is a verified optimum.
#[test]
#[ignore = "a benchmark of about a minute: cargo test -p chaplygin --features cli,plan,ipopt --lib solvers_on_the_issue_problems -- --ignored --nocapture"]
fn solvers_on_the_issue_problems() {
    let problems = [
        (
            "point mass",
            point_mass(),
            rest_to_rest(Scheme::HermiteSimpson, 51),
        ),
        ("differential drive", differential_drive(), parking(41)),
        (
            "snakeboard sideways",
            built_in("snakeboard"),
            problem_request(&sideways(), 41),
        ),
        (
            "bicycle lane change",
            built_in("bicycle"),
            problem_request(&lane_change(), 31),
        ),
    ];
    println!("| problem | solver | objective | above the least | iterations | CPU s |");
    println!("|---|---|---|---|---|---|");
    let mut failures = Vec::new();
    for (problem, loaded, request) in problems {
        let solves = timed_solves(&loaded, &request);
        let least = (solves.iter())
            .filter_map(|solve| solve.outcome.as_ref().ok().map(|(objective, _)| *objective))
            .fold(f64::INFINITY, f64::min);
        for Timed {
            label,
            outcome,
            seconds,
        } in solves
        {
            match outcome {
                Ok((objective, iterations)) => println!(
                    "| {problem} | {label} | {objective:.10e} | {:.1e} | {iterations} | {seconds:.2} |",
                    objective / least - 1.0
                ),
                Err(error) => {
                    println!("| {problem} | {label} | fails: {error} | | | {seconds:.2} |");
                    failures.push(format!("{problem}, {label}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// `|push| <= 0.1` moves the point mass (m = 2) at most `0.05 (T/2)^2 =
/// 0.05` in T = 2, not the goal's 1: Ipopt detects the infeasibility, and
/// the plan is a one-line error with its word.
#[test]
fn ipopt_on_an_infeasible_plan_is_a_one_line_error() {
    let mut request = rest_to_rest(Scheme::Midpoint, 11);
    request.bounds.push(("push".into(), "-0.1:0.1".into()));
    let error = plan(point_mass(), &request, &Ipopt::default()).expect_err("infeasible");
    let message = error.to_string();
    assert!(message.starts_with("no verified optimum"), "{message}");
    assert!(message.contains("Infeasible_Problem_Detected"), "{message}");
    assert!(!message.contains('\n'), "{message}");
}
