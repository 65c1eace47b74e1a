//! Derivation time of every built-in model: `chaplygin_codegen::generate`
//! on the model's text (`MODEL_TEXT`), from parsing to the emitted Rust
//! source. Besides criterion's estimates, prints `DERIVATION name: best of
//! several` from its own loop. `CHAPLYGIN_DERIVATION_MODELS=snakeboard,snake12`
//! restricts that loop to the models named (`snakeN`: the N-link snake, best
//! of [`SNAKE_RUNS`]) and skips criterion, for timing the larger snakes and
//! for counting one model's instructions (`valgrind --tool=cachegrind`).
//!
//! Run with `cargo bench -p chaplygin-models --bench derivation`.

use chaplygin_codegen::generate;
use chaplygin_models::{differential_drive, rolling_disk, sleigh, snake, snakeboard};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Instant;

/// Runs of the printed best-of timing.
const RUNS: usize = 7;
/// Runs of the printed best-of timing of the larger snakes.
const SNAKE_RUNS: usize = 3;

/// The models named in `CHAPLYGIN_DERIVATION_MODELS`, with their text and
/// runs, or `None` when it is not set.
fn chosen_models() -> Option<Vec<(String, String, usize)>> {
    let names = std::env::var("CHAPLYGIN_DERIVATION_MODELS").ok()?;
    let built_in = models();
    let chosen = names.split(',').map(str::trim).filter_map(|name| {
        let links = name.strip_prefix("snake").and_then(|n| n.parse().ok());
        match links {
            Some(links) => Some((name.to_string(), snake::n_link_snake(links), SNAKE_RUNS)),
            None => built_in
                .iter()
                .find(|(known, _)| *known == name)
                .map(|(_, text)| (name.to_string(), text.clone(), RUNS)),
        }
    });
    Some(chosen.collect())
}

/// Prints `DERIVATION name: best of runs`.
fn print_best(name: &str, text: &str, runs: usize) {
    let best = (0..runs)
        .map(|_| {
            let start = Instant::now();
            black_box(generate(black_box(text)).expect("the built-in model compiles"));
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min);
    println!("DERIVATION {name}: {:.3} ms", best * 1e3);
}

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
    if let Some(chosen) = chosen_models() {
        for (name, text, runs) in &chosen {
            print_best(name, text, *runs);
        }
        return;
    }
    let models = models();
    for (name, text) in &models {
        print_best(name, text, RUNS);
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
