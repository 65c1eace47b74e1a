//! Ipopt against ripopt on the same programs: the point mass moved rest to
//! rest, whose optimum `12 m^2 d^2 / T^3` (6 for m = 2, d = 1, T = 2)
//! Hermite-Simpson meets exactly, and the differential drive parked; each
//! answer verified by the KKT check of `plan`.

use std::ops::ControlFlow;

use super::super::{Hessian, Ripopt};
use super::Ipopt;
use crate::driver::plan::tests::{differential_drive, parking, point_mass, rest_to_rest};
use crate::driver::plan::{Plan, PlanError, Report, Scheme, plan, plan_watched};

/// The largest difference of two plans' inputs `push`.
fn largest_input_difference(a: &Plan, b: &Plan, input: &str) -> f64 {
    let (a, b) = (a.table.column(input).expect("a"), b.table.column(input).expect("b"));
    a.iter().zip(&b).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
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
    let planned = plan_watched(point_mass(), &request, &Ipopt::default(), &mut |iteration| {
        numbers.push(iteration.number);
        ControlFlow::Continue(())
    })
    .expect("a plan");
    assert_eq!(numbers, (0..=planned.report.iterations).collect::<Vec<_>>());
    let error = plan_watched(point_mass(), &request, &Ipopt::default(), &mut |iteration| {
        if iteration.number < 2 {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    })
    .expect_err("interrupted");
    let Ok(PlanError::Interrupted(stopped)) = error.downcast::<PlanError>().map(|e| *e) else {
        panic!("not an interruption");
    };
    assert_eq!(stopped.report.status, Report::INTERRUPTED);
    assert_eq!(stopped.report.iterations, 2);
}
