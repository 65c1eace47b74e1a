//! Estimates against closed forms: a spring-mass `m xddot = -k x`
//! released from rest at `x = 1` moves as `x = cos(w t)`, `w = sqrt(k /
//! m)`. Its stiffness is recovered from that motion sampled without noise,
//! and under seeded Gaussian noise the estimate lands within 4 standard
//! errors of the truth, the standard error agreeing with the Gauss-Newton
//! one of the closed form: the sensitivities `dx/dx_0 = cos(w t)`,
//! `dx/dv_0 = sin(w t) / w`, `dx/dk = -t sin(w t) / (2 m w)`. The
//! defects' exact derivatives, by the states and the parameters, agree
//! with central differences under each scheme.

use super::{Estimate, IdentifyError, Request, identify};
use crate::driver::catalog::Source;
use crate::driver::engine::{EngineChoice, Loaded, load};
use crate::driver::plan::Scheme;
use crate::driver::plan::nlp::Ripopt;
use crate::runtime::nalgebra::DMatrix;
use std::path::Path;

/// `m xddot = -k x + push`, its defaults away from the truth `k = 4`.
const SPRING_MASS: &str = "pub struct SpringMass {
    coordinates: [x],
    parameters: [m = 1.0, k = 3.0],
    kinetic_energy: m/2*dot(x)^2,
    potential_energy: k/2*x^2,
    inputs: [push = x],
}";

const STIFFNESS: f64 = 4.0;

fn spring_mass() -> Loaded {
    let source = Source::File {
        path: "spring_mass.model".into(),
        text: SPRING_MASS.into(),
    };
    load(&source, EngineChoice::Jit).expect("the model derives")
}

/// Standard normal deviates from a seeded linear congruential generator
/// (Knuth's MMIX constants) by the Box-Muller transform.
fn normal_deviates(count: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    let mut uniform = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let (a, b) = (uniform(), uniform());
            (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        })
        .collect()
}

/// `x = cos(2 t)` on `rows` rows over `[0, duration]`, plus `noise`.
fn write_data(path: &Path, rows: usize, duration: f64, noise: &[f64]) {
    let omega = STIFFNESS.sqrt();
    let mut text = String::from("t,x,push\n");
    for i in 0..rows {
        let t = duration * i as f64 / (rows - 1) as f64;
        let x = (omega * t).cos() + noise.get(i).copied().unwrap_or(0.0);
        text.push_str(&format!("{t},{x},0\n"));
    }
    std::fs::write(path, text).expect("written");
}

fn request(data: &Path, scheme: Scheme) -> Request {
    Request {
        data: data.to_path_buf(),
        estimate: vec![("k".into(), None)],
        nodes: None,
        scheme,
        params: Vec::new(),
        tol: crate::driver::plan::Request::TOL,
    }
}

fn estimated(request: &Request) -> Estimate {
    identify(spring_mass(), request, &Ripopt::default()).expect("a verified estimate")
}

#[test]
fn the_stiffness_is_recovered_from_a_noiseless_motion() {
    let dir = tempfile::tempdir().expect("a directory");
    let data = dir.path().join("data.csv");
    write_data(&data, 201, 4.0, &[]);
    for scheme in [Scheme::Midpoint, Scheme::HermiteSimpson] {
        let estimate = estimated(&request(&data, scheme));
        let k = estimate.parameters[0].1;
        assert!(
            (k - STIFFNESS).abs() < 1e-3 * STIFFNESS,
            "{scheme:?}: k = {k}"
        );
        assert_eq!(estimate.fit.column("data(x)").expect("data").len(), 201);
    }
}

/// The closed form's Gauss-Newton standard error of `k` over the times
/// `t`, per unit residual standard deviation.
fn closed_form_error(t: &[f64]) -> f64 {
    let omega = STIFFNESS.sqrt();
    let rows: Vec<f64> = t
        .iter()
        .flat_map(|t| {
            let (s, c) = (omega * t).sin_cos();
            [c, s / omega, -t * s / (2.0 * omega)]
        })
        .collect();
    let j = DMatrix::from_row_slice(t.len(), 3, &rows);
    let inverse = (j.transpose() * &j).try_inverse().expect("regular");
    inverse[(2, 2)].sqrt()
}

#[test]
fn under_noise_the_estimate_lies_within_its_standard_errors_of_the_closed_form() {
    let dir = tempfile::tempdir().expect("a directory");
    let data = dir.path().join("data.csv");
    let (rows, sigma) = (401, 0.01);
    let noise: Vec<f64> = normal_deviates(rows, 61)
        .iter()
        .map(|n| sigma * n)
        .collect();
    write_data(&data, rows, 8.0, &noise);
    let estimate = estimated(&request(&data, Scheme::HermiteSimpson));
    let (k, error) = (estimate.parameters[0].1, estimate.standard_errors[0]);
    assert!((k - STIFFNESS).abs() < 4.0 * error, "k = {k} +- {error}");
    let t = estimate.fit.column("t").expect("t");
    let spread = (estimate.residual_rms.powi(2) * rows as f64 / (rows - 3) as f64).sqrt();
    let expected = spread * closed_form_error(&t);
    assert!(
        (error - expected).abs() < 0.01 * expected,
        "{error} against the closed form's {expected}"
    );
    let stated = sigma * closed_form_error(&t);
    assert!(
        (error - stated).abs() < 0.1 * stated,
        "{error} against {stated}"
    );
}

#[test]
fn bad_requests_fail_in_one_line() {
    let dir = tempfile::tempdir().expect("a directory");
    let data = dir.path().join("data.csv");
    write_data(&data, 11, 1.0, &[]);
    let mut unknown = request(&data, Scheme::Midpoint);
    unknown.estimate = vec![("c".into(), None)];
    let failure = identify(spring_mass(), &unknown, &Ripopt::default()).expect_err("unknown");
    assert!(matches!(
        failure.downcast_ref::<IdentifyError>(),
        Some(IdentifyError::UnknownEstimate { .. })
    ));
    let few = dir.path().join("few.csv");
    write_data(&few, 2, 1.0, &[]);
    let failure = identify(
        spring_mass(),
        &request(&few, Scheme::Midpoint),
        &Ripopt::default(),
    )
    .expect_err("too few rows");
    assert!(matches!(
        failure.downcast_ref::<IdentifyError>(),
        Some(IdentifyError::TooFewRows {
            measured: 2,
            unknowns: 3,
            ..
        })
    ));
    let cases = [
        ("t,x,lean\n0,1,0\n1,0,0\n", "unknown columns lean"),
        ("t,x\n0,1\n0,0\n1,0\n", "increase strictly"),
    ];
    for (text, said) in cases {
        let bad = dir.path().join("bad.csv");
        std::fs::write(&bad, text).expect("written");
        let failure = identify(
            spring_mass(),
            &request(&bad, Scheme::Midpoint),
            &Ripopt::default(),
        )
        .expect_err(said);
        let message = failure.to_string();
        assert!(
            message.contains(said) && !message.contains('\n'),
            "{message}"
        );
        assert!(message.starts_with("--data"), "{message}");
    }
}

#[test]
fn the_defects_derivatives_agree_with_central_differences() {
    use crate::driver::plan::nlp::Nlp;
    let dir = tempfile::tempdir().expect("a directory");
    let data = dir.path().join("data.csv");
    std::fs::write(
        &data,
        "t,x,push\n0,1,0.5\n0.3,0.7,-0.2\n0.6,0.2,0.9\n0.9,-0.4,0.1\n1.2,-0.8,0.3\n",
    )
    .expect("written");
    for scheme in [
        Scheme::BackwardEuler,
        Scheme::Midpoint,
        Scheme::HermiteSimpson,
    ] {
        let mut asked = request(&data, scheme);
        asked.estimate = vec![("k".into(), Some(2.5)), ("m".into(), Some(0.7))];
        let fit = super::Fit::new(spring_mass(), &asked, None).expect("a program");
        let y: Vec<f64> = fit
            .guess()
            .iter()
            .enumerate()
            .map(|(j, v)| v + 0.3 * (0.9 * j as f64).sin())
            .collect();
        let mut values = vec![0.0; fit.jacobian_structure().len()];
        assert!(fit.jacobian_values(&y, &mut values));
        let step = 1e-6;
        for (&(row, column), exact) in fit.jacobian_structure().iter().zip(&values) {
            let at = |shift: f64| {
                let mut moved = y.clone();
                moved[column] += shift;
                let mut c = vec![0.0; fit.constraints()];
                assert!(fit.residuals(&moved, &mut c));
                c[row]
            };
            let numeric = (at(step) - at(-step)) / (2.0 * step);
            assert!(
                (exact - numeric).abs() < 1e-6,
                "{scheme:?} ({row}, {column}): {exact} vs {numeric}"
            );
        }
    }
}

/// The same rows in memory give the file's estimate, bit for bit.
#[test]
fn a_table_in_memory_gives_the_file_s_estimate() {
    let dir = tempfile::tempdir().expect("a directory");
    let data = dir.path().join("data.csv");
    write_data(&data, 41, 4.0, &[]);
    let text = std::fs::read_to_string(&data).expect("read");
    let mut lines = text.lines();
    let columns = lines.next().expect("a header").split(',').map(String::from);
    let rows = lines.map(|line| line.split(',').map(|v| v.parse().expect("a number")));
    let table = crate::runtime::record::Table {
        columns: columns.collect(),
        rows: rows.map(Iterator::collect).collect(),
    };
    let request = request(&data, Scheme::Midpoint);
    let from_file = estimated(&request);
    let in_memory = super::identify_table(
        spring_mass(),
        &request,
        &table,
        &Ripopt::default(),
        &mut |_| std::ops::ControlFlow::Continue(()),
    )
    .expect("a verified estimate");
    assert_eq!(in_memory.to_json(), from_file.to_json());
    assert_eq!(in_memory.fit, from_file.fit);
}

/// An observer that stops the solve at once gets the first guess back as
/// `Interrupted`: the default `k = 3`, every node's state the data, so
/// no residual but round-off, and the defects of `x = cos(2 t)` under `k = 3` its
/// primal residual.
#[test]
fn an_observer_may_stop_the_estimate() {
    let dir = tempfile::tempdir().expect("a directory");
    let data = dir.path().join("data.csv");
    write_data(&data, 41, 4.0, &[]);
    let error = super::identify_watched(
        spring_mass(),
        &request(&data, Scheme::Midpoint),
        &Ripopt::default(),
        &mut |_| std::ops::ControlFlow::Break(()),
    )
    .expect_err("interrupted");
    let message = error.to_string();
    let Ok(stopped) = error.downcast::<super::Interrupted>() else {
        panic!("not an interruption: {message}");
    };
    assert!(
        message.starts_with("interrupted after 0 iterations, at an iterate that is not an optimum"),
        "{message}"
    );
    assert_eq!(stopped.0.parameters, [("k".to_string(), 3.0)]);
    assert_eq!(stopped.0.iterations, 0);
    assert!(stopped.0.residual_rms < 1e-12, "{}", stopped.0.residual_rms);
    assert!(stopped.0.kkt.primal > 1e-3, "{:?}", stopped.0.kkt);
}
