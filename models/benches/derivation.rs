//! Derivation time of every built-in model: `chaplygin_codegen::generate`
//! on the model's text (`MODEL_TEXT`), from parsing to the emitted Rust
//! source. Besides criterion's estimates, prints `DERIVATION name: best of
//! several` from its own loop.
//!
//! Run with `cargo bench -p chaplygin-models --bench derivation`.

use chaplygin_codegen::generate;
use chaplygin_models::{differential_drive, rolling_disk, sleigh, snake, snakeboard};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Instant;

/// Runs of the printed best-of timing.
const RUNS: usize = 7;

fn models() -> Vec<(&'static str, String)> {
    vec![
        ("snakeboard", snakeboard::MODEL_TEXT.to_string()),
        ("sleigh", sleigh::MODEL_TEXT.to_string()),
        ("rolling_disk", rolling_disk::MODEL_TEXT.to_string()),
        (
            "differential_drive",
            differential_drive::MODEL_TEXT.to_string(),
        ),
        ("snake2", snake::n_link_snake(2)),
    ]
}

fn bench(c: &mut Criterion) {
    let models = models();
    for (name, text) in &models {
        let best = (0..RUNS)
            .map(|_| {
                let start = Instant::now();
                black_box(generate(black_box(text)).expect("the built-in model compiles"));
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min);
        println!("DERIVATION {name}: {:.3} ms", best * 1e3);
    }
    let mut group = c.benchmark_group("derivation");
    group.sample_size(10);
    for (name, text) in &models {
        group.bench_function(*name, |b| b.iter(|| generate(black_box(text))));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
