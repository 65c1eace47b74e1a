//! The snakeboard's optimal gaits from rest against the classic gaits of
//! Ostrowski and Burdick (BENCHMARKS.md, "Snakeboard gaits"): `cargo bench
//! --bench gaits`.
//!
//! For forward motion and for rotation, the optimizer (`gait_design`, the
//! default design: per unit of the loop's length in `(psi, phi)`, limits
//! `|r_i| < pi`, margin 0.25) with one and two harmonics, each timed; and
//! the best of each classic family within the same walls (clearance above
//! 1), found by a grid over its amplitudes refined by a shrinking pattern
//! search: the drive gait `psi = a sin t`, `phi = b sin t` (rotor and axles
//! in phase) and the rotate gait `psi = a sin 2t`, `phi = b sin t` (the
//! rotor at twice the axles' frequency). Prints a Markdown table and
//! writes `target/gaits/snakeboard-forward-gaits.png` and
//! `snakeboard-rotate-gaits.png`, each gait's loop in the shape plane and
//! its path in the plane over one cycle from rest.

use chaplygin::driver::catalog::{Source, built_in};
use chaplygin::driver::engine::{EngineChoice, load};
use chaplygin::driver::gait::{FromText, locomotion};
use chaplygin::gait_design::{
    Design, Direction, FourierLoop, GaitModel, Scoring, clearances, evaluate, optimize,
};
use chaplygin::plot::{GaitCurve, write_gait_comparison};
use chaplygin::runtime::gait::{self, ShapeLoop};
use std::f64::consts::PI;
use std::time::Instant;

/// A gait found and how.
struct Found {
    name: String,
    shape_loop: FourierLoop,
    efficiency: f64,
    displacement: [f64; 3],
    length: f64,
    seconds: f64,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let source = Source::BuiltIn(built_in("snakeboard").ok_or("no snakeboard")?);
    let loaded = load(&source, EngineChoice::Jit)?;
    let body = locomotion(&loaded.model, &loaded.label)?;
    println!("| gait | efficiency | x | y | theta | loop length | time |");
    println!("|---|---|---|---|---|---|---|");
    let directory = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/gaits");
    std::fs::create_dir_all(&directory)?;
    for (direction, name) in [
        (Direction::Forward, "forward"),
        (Direction::Rotate, "rotate"),
    ] {
        let design = Design {
            direction,
            ..Design::default()
        };
        let rows = [
            optimal(&body, &design, 1)?,
            optimal(&body, &design, 2)?,
            classic(&body, direction, &design.scoring(&body)),
        ];
        for row in &rows {
            let [x, y, theta] = row.displacement;
            println!(
                "| {} | {:.4} | {x:.3} | {y:.3} | {theta:.3} | {:.3} | {:.2} s |",
                row.name, row.efficiency, row.length, row.seconds
            );
        }
        let curves: Vec<GaitCurve> = rows.iter().map(|row| curve(&body, row)).collect();
        let file = directory.join(format!("snakeboard-{name}-gaits.png"));
        let title = format!("The snakeboard's {name} gaits over one cycle from rest");
        write_gait_comparison(&title, &curves, ["psi", "phi"], &file)?;
        eprintln!("wrote {}", file.display());
    }
    Ok(())
}

/// The optimizer's loop for `design` with `harmonics`, timed.
fn optimal(
    body: &FromText<'_>,
    design: &Design,
    harmonics: usize,
) -> Result<Found, Box<dyn std::error::Error>> {
    let design = Design {
        harmonics,
        ..design.clone()
    };
    let start = Instant::now();
    let optimum = optimize(body, &design)?;
    let plural = if harmonics == 1 { "" } else { "s" };
    Ok(Found {
        name: format!("optimal, {harmonics} harmonic{plural}"),
        efficiency: optimum.efficiency(),
        displacement: optimum.evaluation.displacement,
        length: optimum.evaluation.length,
        shape_loop: optimum.shape_loop,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The classic loop of the family for `direction` with amplitudes `(a,
/// b)`: `psi = a sin t` (drive) or `a sin 2t` (rotate), `phi = b sin t`.
fn classic_loop(direction: Direction, (a, b): (f64, f64)) -> FourierLoop {
    let mut coefficients = vec![0.0; 10];
    match direction {
        Direction::Rotate => coefficients[4] = a,
        _ => coefficients[2] = a,
    }
    coefficients[7] = b;
    FourierLoop {
        period: 2.0 * PI,
        harmonics: 2,
        coefficients,
    }
}

/// The best classic gait for `direction` within `scoring`'s walls: a grid
/// over `a` in `(0, pi)` and `b` in `(-pi/2, pi/2)`, then a pattern search
/// halving its step.
fn classic(body: &dyn GaitModel, direction: Direction, scoring: &Scoring) -> Found {
    let start = Instant::now();
    let score = |ab: (f64, f64)| -> f64 {
        let shape_loop = classic_loop(direction, ab);
        match !clearances(body, &shape_loop, scoring, 400).any(|s| s <= 1.0) {
            true => evaluate(body, &shape_loop, scoring).efficiency(scoring),
            false => f64::NEG_INFINITY,
        }
    };
    let grid = (1..32).flat_map(|i| (-19..=19).map(move |j| (0.1 * i as f64, 0.08 * j as f64)));
    let mut best = grid
        .map(|ab| (score(ab), ab))
        .fold((f64::NEG_INFINITY, (0.0, 0.0)), |m, c| {
            if c.0 > m.0 { c } else { m }
        });
    let mut step = (0.05, 0.04);
    while step.0 > 1e-4 {
        let around = [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)];
        let moved = around
            .iter()
            .map(|(i, j)| (best.1.0 + i * step.0, best.1.1 + j * step.1))
            .map(|ab| (score(ab), ab))
            .fold(best, |m, c| if c.0 > m.0 { c } else { m });
        match moved.0 > best.0 {
            true => best = moved,
            false => step = (step.0 / 2.0, step.1 / 2.0),
        }
    }
    let shape_loop = classic_loop(direction, best.1);
    let at = evaluate(body, &shape_loop, scoring);
    let (a, b) = best.1;
    let name = match direction {
        Direction::Rotate => format!("classic 2:1, psi = {a:.3} sin 2t, phi = {b:.3} sin t"),
        _ => format!("classic in phase, psi = {a:.3} sin t, phi = {b:.3} sin t"),
    };
    Found {
        name,
        efficiency: at.efficiency(scoring),
        displacement: at.displacement,
        length: at.length,
        shape_loop,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// `row`'s loop and its path over one cycle from rest.
fn curve(body: &dyn GaitModel, row: &Found) -> GaitCurve {
    let law = |t: f64| row.shape_loop.shape(t);
    let shape_loop = ShapeLoop {
        shape: &law,
        period: row.shape_loop.period,
    };
    let (q0, p0) = (
        vec![0.0; body.coordinate_count()],
        vec![0.0; body.momentum_count()],
    );
    let (group, shape) = (body.group(), body.shape_indices());
    let mut curve = GaitCurve {
        label: row.name.clone(),
        shape: Vec::new(),
        path: Vec::new(),
    };
    gait::run(body, &shape_loop, (&q0, &p0), (1, 400), &mut |_, state| {
        curve.shape.push((state.q[shape[0]], state.q[shape[1]]));
        curve.path.push((state.q[group[0]], state.q[group[1]]));
    });
    curve
}
