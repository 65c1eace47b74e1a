//! The accelerations' second derivatives differentiated at run time
//! (`chaplygin_codegen::interpret`'s `acceleration_hessian` and
//! `acceleration_parameter_jacobian`), and the reduced equations'
//! (`reduced_rhs_hessian`), on the differential drive, the snakeboard and
//! the benchmark bicycle: the operation counts of the programs they
//! differentiate (`acceleration`, `acceleration_jacobian`,
//! `reduced_rhs_jacobian`), the load time, and the time of a call of each
//! function on the IR interpreter, the mean over enough calls to last 0.2
//! s.
//!
//! Run with `cargo bench -p chaplygin-codegen --bench second`; it prints
//! one markdown row per model (BENCHMARKS.md, "Exact second derivatives").

use chaplygin_codegen::interpret::{InterpretedModel, evaluated};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// The mean time of a call of `f`, in microseconds.
fn microseconds(mut f: impl FnMut()) -> f64 {
    let mut calls = 0u32;
    let start = Instant::now();
    while start.elapsed() < Duration::from_millis(200) {
        f();
        calls += 1;
    }
    start.elapsed().as_secs_f64() * 1e6 / f64::from(calls)
}

/// The operations of the program of the function `name`, after CSE.
fn operations(model: &InterpretedModel, name: &str) -> u64 {
    model
        .programs()
        .find(|(function, _)| *function == name)
        .map_or(0, |(_, program)| program.operation_count().after_cse)
}

fn main() {
    let models = [
        (
            "differential drive",
            include_str!("../../models/differential_drive.model"),
        ),
        ("snakeboard", include_str!("../../models/snakeboard.model")),
        ("bicycle", include_str!("../../models/bicycle.model")),
    ];
    println!(
        "| model | n, p, P | ops acceleration | ops jacobian | load ms | acceleration us | \
         jacobian us | parameter jacobian us | hessian us | ops reduced jacobian | \
         reduced jacobian us | reduced hessian us |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, source) in models {
        let start = Instant::now();
        let model = InterpretedModel::from_source(source).expect("the model derives");
        let load = start.elapsed().as_secs_f64() * 1e3;
        let sizes = model.sizes();
        let (n, p) = (sizes.n, sizes.p);
        let y: Vec<f64> = (0..2 * n + p)
            .map(|j| 0.2 * (0.9 * j as f64).sin() + 0.05)
            .collect();
        let (q, rest) = y.split_at(n);
        let (qdot, u) = rest.split_at(n);
        let w: Vec<f64> = (0..n).map(|i| 0.7 - 0.3 * i as f64).collect();
        let acceleration = microseconds(|| {
            black_box(evaluated(model.acceleration(q, qdot, u)));
        });
        let jacobian = microseconds(|| {
            black_box(evaluated(model.acceleration_jacobian(q, qdot, u)));
        });
        let every_parameter: Vec<usize> = (0..model.parameter_values().len()).collect();
        let parameter_jacobian = microseconds(|| {
            black_box(evaluated(model.acceleration_parameter_jacobian(
                q,
                qdot,
                u,
                &every_parameter,
            )));
        });
        let hessian = microseconds(|| {
            black_box(evaluated(model.acceleration_hessian(q, qdot, u, &w)));
        });
        let x: Vec<f64> = (0..sizes.s)
            .map(|j| 0.2 * (0.9 * j as f64).sin() + 0.05)
            .collect();
        let v: Vec<f64> = (0..sizes.s).map(|i| 0.7 - 0.3 * i as f64).collect();
        let reduced_jacobian = microseconds(|| {
            black_box(evaluated(model.reduced_rhs_jacobian(&x, u)));
        });
        let reduced_hessian = microseconds(|| {
            black_box(evaluated(model.reduced_rhs_hessian(&x, u, &v)));
        });
        println!(
            "| {name} | {n}, {p}, {} | {} | {} | {load:.0} | {acceleration:.2} | {jacobian:.2} | \
             {parameter_jacobian:.1} | {hessian:.1} | {} | {reduced_jacobian:.2} | \
             {reduced_hessian:.1} |",
            model.parameter_values().len(),
            operations(&model, "acceleration"),
            operations(&model, "acceleration_jacobian"),
            operations(&model, "reduced_rhs_jacobian"),
        );
    }
}
