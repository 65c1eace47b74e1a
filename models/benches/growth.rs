//! Growth with model size: the N-link wheeled snake (`snake::n_link_snake`)
//! for N = 1, 2, ... up to 12 or until a derivation exceeds its time budget
//! (`CHAPLYGIN_GROWTH_BUDGET` seconds, default 60).
//!
//! For each N it measures the derivation time of `chaplygin_codegen::generate`,
//! the operation counts of `acceleration` and `reduced_rhs` before and after
//! CSE (from the generated `REPORT`), the `rustc -O` compile time of the
//! generated code with a timing `main`, and the per-call time of the two
//! functions in that program (best of several batches); and for the same
//! model read from its text (`chaplygin::jit`), the time to compile all its
//! programs to native code with the JIT and the per-call time of the same
//! two programs at the same state, and their ratio to rustc's. It then
//! prints the least-squares slope of `ln(quantity)` against `ln(N)` for
//! each quantity: growth like `N^slope`.
//!
//! Run with `cargo bench -p chaplygin-models --bench growth`.

mod rustc;

use chaplygin::jit::NativePrograms;
use chaplygin_codegen::interpret::InterpretedModel;
use chaplygin_models::snake::n_link_snake;
use rustc::{compile, operations};
use std::hint::black_box;
use std::path::Path;
use std::process::Command;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The largest number of links studied.
const LARGEST: usize = 12;

/// One row of the study.
struct Row {
    links: usize,
    derivation_seconds: f64,
    /// `(before, after)` CSE for `acceleration` and `reduced_rhs`.
    acceleration_operations: (f64, f64),
    reduced_rhs_operations: (f64, f64),
    jacobian_operations: (f64, f64),
    compile_seconds: f64,
    acceleration_nanoseconds: f64,
    reduced_rhs_nanoseconds: f64,
    jit: Jit,
}

/// The JIT's part of a row.
struct Jit {
    compile_seconds: f64,
    acceleration_nanoseconds: f64,
    reduced_rhs_nanoseconds: f64,
}

fn main() {
    let budget = std::env::var("CHAPLYGIN_GROWTH_BUDGET")
        .ok()
        .and_then(|text| text.parse().ok())
        .unwrap_or(60.0);
    let workspace = std::env::temp_dir().join("chaplygin-growth");
    if let Err(error) = std::fs::create_dir_all(&workspace) {
        println!("cannot create {}: {error}", workspace.display());
        return;
    }
    let mut rows = Vec::new();
    for links in 1..=LARGEST {
        match study(links, budget, &workspace) {
            Ok(row) => {
                print_row(&row);
                rows.push(row);
            }
            Err(reason) => {
                println!("N = {links}: {reason}; the study stops here");
                break;
            }
        }
    }
    print_slopes(&rows);
}

fn study(links: usize, budget: f64, workspace: &Path) -> Result<Row, String> {
    let (derivation_seconds, code) = derive_within(links, budget)?;
    let source = workspace.join(format!("snake{links}.rs"));
    std::fs::write(&source, timing_program(links, &code)).map_err(|e| e.to_string())?;
    let (compile_seconds, binary) = compile(&source, "bin")?;
    let output = Command::new(&binary)
        .output()
        .map_err(|e| format!("running {}: {e}", binary.display()))?;
    let timings: Vec<f64> = String::from_utf8_lossy(&output.stdout)
        .split_whitespace()
        .filter_map(|word| word.parse().ok())
        .collect();
    let [acceleration_nanoseconds, reduced_rhs_nanoseconds] = timings[..] else {
        return Err(format!("unexpected timing output {timings:?}"));
    };
    Ok(Row {
        links,
        derivation_seconds,
        acceleration_operations: operations(&code, "acceleration")?,
        reduced_rhs_operations: operations(&code, "reduced_rhs")?,
        jacobian_operations: operations(&code, "reduced_rhs_jacobian")?,
        compile_seconds,
        acceleration_nanoseconds,
        reduced_rhs_nanoseconds,
        jit: jit_study(links)?,
    })
}

/// The model of `n_link_snake(links)` read from its text: the time to
/// compile all its programs with the JIT, and the nanoseconds per call of
/// its native `acceleration` and `reduced_rhs` at the state the rustc
/// timing program uses (best of 7 batches of 10^5 calls).
fn jit_study(links: usize) -> Result<Jit, String> {
    let model = InterpretedModel::from_source(&n_link_snake(links))
        .map_err(|diagnostics| diagnostics.render("n_link_snake"))?;
    let programs: Vec<_> = model.programs().map(|(_, program)| program).collect();
    let started = Instant::now();
    let native = NativePrograms::compile(&programs).map_err(|error| error.to_string())?;
    let compile_seconds = started.elapsed().as_secs_f64();
    let sizes = model.sizes();
    let q: Vec<f64> = (0..sizes.n).map(|i| 0.3 * (i as f64 + 1.0).sin()).collect();
    let (alpha, u) = (vec![0.4; sizes.k], vec![0.1; sizes.p]);
    let qdot = model
        .velocities(&q, &alpha)
        .map_err(|error| error.to_string())?;
    let per_call = |name: &str, arguments: Vec<&[f64]>| -> Result<f64, String> {
        let (index, (_, program)) = model
            .programs()
            .enumerate()
            .find(|(_, (function, _))| *function == name)
            .ok_or_else(|| format!("no program {name}"))?;
        let inputs: Vec<f64> = arguments
            .concat()
            .into_iter()
            .chain(model.parameter_values().iter().copied())
            .collect();
        let mut outputs = vec![0.0; program.outputs().len()];
        let batch = |outputs: &mut [f64]| {
            let started = Instant::now();
            for _ in 0..100_000 {
                let _ = native.evaluate(index, black_box(&inputs), outputs);
                black_box(&outputs);
            }
            started.elapsed().as_nanos() as f64 / 100_000.0
        };
        Ok((0..7)
            .map(|_| batch(&mut outputs))
            .fold(f64::INFINITY, f64::min))
    };
    Ok(Jit {
        compile_seconds,
        acceleration_nanoseconds: per_call("acceleration", vec![&q, &qdot, &u])?,
        reduced_rhs_nanoseconds: per_call("reduced_rhs", vec![&q, &alpha, &u])?,
    })
}

/// `generate` on its own thread; gives up (leaving the thread) after `budget` seconds.
fn derive_within(links: usize, budget: f64) -> Result<(f64, String), String> {
    let (sender, receiver) = mpsc::channel();
    std::thread::spawn(move || {
        let start = Instant::now();
        let code = chaplygin_codegen::generate(&n_link_snake(links))
            .map_err(|diagnostics| diagnostics.render("n_link_snake"));
        let _ = sender.send((start.elapsed().as_secs_f64(), code));
    });
    match receiver.recv_timeout(Duration::from_secs_f64(budget)) {
        Ok((seconds, Ok(code))) => Ok((seconds, code)),
        Ok((_, Err(rendered))) => Err(rendered),
        Err(_) => Err(format!("derivation exceeded the budget of {budget} s")),
    }
}

/// The generated items and a `main` printing the nanoseconds per call of
/// `acceleration` and `reduced_rhs` at a bent, moving snake.
fn timing_program(links: usize, code: &str) -> String {
    format!(
        "{code}\n\
         fn best(mut f: impl FnMut() -> f64) -> f64 {{\n\
         \x20   (0..7).map(|_| {{ let t = std::time::Instant::now(); let s = f(); std::hint::black_box(s); t.elapsed().as_nanos() as f64 / 100000.0 }}).fold(f64::INFINITY, f64::min)\n\
         }}\n\
         fn main() {{\n\
         \x20   let model = Snake{links}::default();\n\
         \x20   let q: [f64; Snake{links}::N] = std::array::from_fn(|i| 0.3 * (i as f64 + 1.0).sin());\n\
         \x20   let alpha = [0.4; Snake{links}::K];\n\
         \x20   let u = [0.1; Snake{links}::P];\n\
         \x20   let qdot = model.velocities(&q, &alpha);\n\
         \x20   let x: [f64; Snake{links}::S] = std::array::from_fn(|i| if i < q.len() {{ q[i] }} else {{ alpha[i - q.len()] }});\n\
         \x20   let acceleration = best(|| (0..100000).map(|_| std::hint::black_box(model.acceleration(std::hint::black_box(&q), std::hint::black_box(&qdot), std::hint::black_box(&u))).0[0]).sum());\n\
         \x20   let reduced_rhs = best(|| (0..100000).map(|_| std::hint::black_box(model.reduced_rhs(std::hint::black_box(&x), std::hint::black_box(&u)))[0]).sum());\n\
         \x20   println!(\"{{acceleration}} {{reduced_rhs}}\");\n\
         }}\n"
    )
}

fn print_row(row: &Row) {
    println!(
        "N = {:2}: derivation {:9.3} s | acceleration ops {:>8} -> {:>6} | reduced_rhs ops {:>8} -> {:>6} | reduced_rhs_jacobian ops after CSE {:>7} | rustc -O {:7.2} s | acceleration {:9.1} ns | reduced_rhs {:9.1} ns | JIT compile {:6.3} s | JIT acceleration {:9.1} ns ({:.2}x rustc) | JIT reduced_rhs {:9.1} ns ({:.2}x rustc)",
        row.links,
        row.derivation_seconds,
        row.acceleration_operations.0,
        row.acceleration_operations.1,
        row.reduced_rhs_operations.0,
        row.reduced_rhs_operations.1,
        row.jacobian_operations.1,
        row.compile_seconds,
        row.acceleration_nanoseconds,
        row.reduced_rhs_nanoseconds,
        row.jit.compile_seconds,
        row.jit.acceleration_nanoseconds,
        row.jit.acceleration_nanoseconds / row.acceleration_nanoseconds,
        row.jit.reduced_rhs_nanoseconds,
        row.jit.reduced_rhs_nanoseconds / row.reduced_rhs_nanoseconds,
    );
}

/// A measured quantity of a row, by name.
type Quantity = (&'static str, fn(&Row) -> f64);

/// The least-squares slope of `ln(value)` against `ln(N)` for each quantity.
fn print_slopes(rows: &[Row]) {
    let quantities: [Quantity; 10] = [
        ("derivation time", |r| r.derivation_seconds),
        ("acceleration ops before CSE", |r| {
            r.acceleration_operations.0
        }),
        ("acceleration ops after CSE", |r| {
            r.acceleration_operations.1
        }),
        ("reduced_rhs ops before CSE", |r| r.reduced_rhs_operations.0),
        ("reduced_rhs ops after CSE", |r| r.reduced_rhs_operations.1),
        ("reduced_rhs_jacobian ops after CSE", |r| {
            r.jacobian_operations.1
        }),
        ("rustc -O time", |r| r.compile_seconds),
        ("acceleration time per call", |r| r.acceleration_nanoseconds),
        ("reduced_rhs time per call", |r| r.reduced_rhs_nanoseconds),
        ("JIT compile time", |r| r.jit.compile_seconds),
    ];
    for (name, value) in quantities {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .map(|r| ((r.links as f64).ln(), value(r).ln()))
            .collect();
        match slope(&points) {
            Some(slope) => println!("SLOPE {name}: {slope:.2} (log-log, {} sizes)", points.len()),
            None => println!("SLOPE {name}: needs two sizes"),
        }
    }
}

fn slope(points: &[(f64, f64)]) -> Option<f64> {
    let count = points.len() as f64;
    let (mean_x, mean_y) = points
        .iter()
        .fold((0.0, 0.0), |(x, y), p| (x + p.0 / count, y + p.1 / count));
    let spread: f64 = points.iter().map(|p| (p.0 - mean_x).powi(2)).sum();
    (points.len() >= 2 && spread > 0.0).then(|| {
        points
            .iter()
            .map(|p| (p.0 - mean_x) * (p.1 - mean_y))
            .sum::<f64>()
            / spread
    })
}
