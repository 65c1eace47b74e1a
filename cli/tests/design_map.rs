//! Design maps (`chaplygin map`, `chaplygin::driver::design_map`): the
//! self-stable speeds over a grid of parameters against closed forms
//! written out independently of the derivation, the same map for any
//! number of threads, the files the command writes, its refusals, and
//! Ctrl-C keeping the points done.
//!
//! - The Chaplygin sleigh moving straight along its blade at speed `v`:
//!   the turning rate's eigenvalue is `-m a v / (inertia + m a^2)`, so the
//!   motion is asymptotically stable (modulo the conserved speed) exactly
//!   where `a v > 0`, and one mode changes stability at `v = 0`.
//! - The benchmark bicycle of Meijaard et al. (2007) at designs other than
//!   the paper's: the weave and capsize speeds of the closed form of its
//!   appendix A (`models/tests/support/benchmark_bicycle.rs`) with the
//!   same trail `c` and wheelbase `w`.

use crate::support::benchmark_bicycle::BenchmarkParameters;
use crate::support::{chaplygin, interrupted};
use ::chaplygin::driver::catalog::lookup;
use ::chaplygin::driver::design_map::{self, Axis, Motion, Run};
use ::chaplygin::driver::engine::{EngineChoice, load};
use ::chaplygin::driver::linearize::{LinearizeError, Stability};
use chaplygin_codegen::interpret::InterpretedModel;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

/// The sleigh moving straight along its blade at `v`, heading 0.
fn straight() -> Vec<(String, String)> {
    [
        ("dot(x)", "v"),
        ("dot(y)", "0"),
        ("dot(theta)", "0"),
        ("theta", "0"),
    ]
    .map(|(name, value)| (name.to_string(), value.to_string()))
    .to_vec()
}

/// The bicycle running upright at `v`.
fn upright() -> Vec<(String, String)> {
    [
        ("dot(theta_r)", "-v/rR"),
        ("dot(phi)", "0"),
        ("dot(delta)", "0"),
    ]
    .map(|(name, value)| (name.to_string(), value.to_string()))
    .to_vec()
}

/// The built-in `name` on the JIT.
fn model(name: &str) -> InterpretedModel {
    let source = lookup(name).expect("a built-in");
    load(&source, EngineChoice::Jit).expect("loads").model
}

/// The map of `model` over `axes` on `jobs` threads.
fn map(
    model: &InterpretedModel,
    axes: &[Axis],
    at: &[(String, String)],
    speeds: &[f64],
    jobs: usize,
) -> Vec<Option<Result<Stability, LinearizeError>>> {
    let names: Vec<String> = axes.iter().map(|axis| axis.name.clone()).collect();
    let motion = Motion {
        at,
        speed: ("v", speeds),
    };
    let stop = AtomicBool::new(false);
    let run = Run {
        jobs: Some(jobs),
        done: &|| {},
        stop: &stop,
    };
    design_map::stability_at(model, &names, &design_map::grid(axes), motion, &run)
        .expect("a valid request")
}

/// The grid `start + i step` for `i` in `0..count`.
fn grid(start: f64, step: f64, count: i32) -> Vec<f64> {
    (0..count).map(|i| start + f64::from(i) * step).collect()
}

/// Over `a` from -0.5 to 0.5 (0 left out: there both rates are conserved),
/// stable exactly where `a v > 0`, the change at `v = 0` to 1e-10; on one
/// thread and on two, the same map bit for bit.
#[test]
fn the_sleigh_is_stable_where_its_centre_of_mass_leads() {
    let sleigh = model("sleigh");
    let a: Vec<f64> = grid(-0.5, 0.05, 21)
        .into_iter()
        .filter(|a| a.abs() > 1e-9)
        .collect();
    let axes = [Axis {
        name: "a".into(),
        values: a.clone(),
    }];
    let speeds = grid(-1.0, 0.25, 9);
    let alone = map(&sleigh, &axes, &straight(), &speeds, 1);
    let shared = map(&sleigh, &axes, &straight(), &speeds, 2);
    let points = design_map::grid(&axes);
    let names = ["a".to_string()];
    assert_eq!(
        design_map::csv(&names, &points, &alone),
        design_map::csv(&names, &points, &shared)
    );
    for (a, found) in a.iter().zip(&alone) {
        let stability = found
            .as_ref()
            .expect("computed")
            .as_ref()
            .expect("linearized");
        let (from, to, counts) = match *a > 0.0 {
            true => (0.0, 1.0, (1, 0)),
            false => (-1.0, 0.0, (0, 1)),
        };
        assert_eq!(stability.stable.len(), 1, "a = {a}: {stability:?}");
        let (found_from, found_to) = stability.stable[0].refined;
        assert!((found_from - from).abs() < 1e-10, "a = {a}: {stability:?}");
        assert!((found_to - to).abs() < 1e-10, "a = {a}: {stability:?}");
        assert_eq!(stability.changes.len(), 1, "a = {a}: {stability:?}");
        assert!(stability.changes[0].value.abs() < 1e-10, "a = {a}");
        assert_eq!(stability.changes[0].counts, counts, "a = {a}");
    }
}

/// Over trail `c` and wheelbase `w` (the paper's design among them), each
/// design's stable range is from its weave speed to its capsize speed by
/// the closed form to 1e-8 m/s, where two modes (the weave pair) become
/// stable and one (capsize) unstable.
#[test]
fn the_bicycles_map_is_the_closed_forms_weave_to_capsize_at_every_design() {
    let bicycle = model("bicycle");
    let axes = [
        Axis {
            name: "c".into(),
            values: vec![0.04, 0.08],
        },
        Axis {
            name: "w".into(),
            values: vec![0.9, 1.02],
        },
    ];
    let speeds = grid(0.0, 0.5, 21);
    let found = map(&bicycle, &axes, &upright(), &speeds, 2);
    for (point, found) in design_map::grid(&axes).iter().zip(&found) {
        let stability = found
            .as_ref()
            .expect("computed")
            .as_ref()
            .expect("linearized");
        let closed = BenchmarkParameters {
            c: point[0],
            w: point[1],
            ..BenchmarkParameters::benchmark()
        };
        let (weave, capsize) = (closed.weave_speeds(), closed.capsize_speeds());
        assert_eq!((weave.len(), capsize.len()), (1, 1), "{point:?}");
        let (from, to) = stability.stable[0].refined;
        assert_eq!(stability.stable.len(), 1, "{point:?}: {stability:?}");
        assert!(
            (from - weave[0]).abs() < 1e-8,
            "{point:?}: {from} vs {weave:?}"
        );
        assert!(
            (to - capsize[0]).abs() < 1e-8,
            "{point:?}: {to} vs {capsize:?}"
        );
        let changes: Vec<(usize, usize)> = stability.changes.iter().map(|c| c.counts).collect();
        assert_eq!(changes, [(2, 0), (0, 1)], "{point:?}");
        assert_eq!(stability.changes[0].value, from, "{point:?}");
    }
}

/// `chaplygin map` with `arguments` after the model, writing to `dir`
/// under the tests' temporary directory.
fn map_command(dir: &str, arguments: &[&str]) -> (std::process::Output, PathBuf) {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(dir);
    let _ = std::fs::remove_dir_all(&out);
    let mut all = vec!["map"];
    all.extend(arguments);
    all.extend(["--out", out.to_str().expect("UTF-8")]);
    (chaplygin(&all), out)
}

/// `map.csv` has the documented columns and a row per design point (the
/// last parameter fastest), `map.png` is a picture, and the command says
/// what it wrote.
#[test]
fn the_command_writes_the_map_and_its_picture() {
    let mut arguments = vec!["sleigh", "--speed", "v=-1:1:0.5"];
    for (name, value) in straight() {
        arguments.extend(["--at".to_string(), format!("{name}={value}")].map(leak));
    }
    arguments.extend([
        "--param",
        "a=0.25:0.5:0.25",
        "--param",
        "inertia=0.1:0.2:0.1",
    ]);
    arguments.extend(["--param", "m=2", "--jobs", "2"]);
    let (output, out) = map_command("map-sleigh", &arguments);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("4 design points: 4 self-stable at some v"),
        "{stdout}"
    );
    let text = std::fs::read_to_string(out.join("map.csv")).expect("map.csv");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "a,inertia,intervals,stable_from,stable_to,changes,failure"
    );
    let designs: Vec<(f64, f64)> = lines[1..]
        .iter()
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            assert_eq!(fields.len(), 7, "{line}");
            assert_eq!(fields[4], "1", "{line}");
            assert!(fields[3].parse::<f64>().expect("a number").abs() < 1e-10);
            (
                fields[0].parse().expect("a"),
                fields[1].parse().expect("inertia"),
            )
        })
        .collect();
    assert_eq!(designs, [(0.25, 0.1), (0.25, 0.2), (0.5, 0.1), (0.5, 0.2)]);
    let png = std::fs::read(out.join("map.png")).expect("map.png");
    let decoder = png::Decoder::new(std::io::Cursor::new(png));
    let info = decoder.read_info().expect("a PNG").info().clone();
    assert_eq!((info.width, info.height), (1200, 900));
}

/// Leaks `text` for an argument list of `&str`.
fn leak(text: String) -> &'static str {
    Box::leak(text.into_boxed_str())
}

/// No varied parameter, three, a name that is not a parameter, a speed
/// that is one: each refused with what is wrong.
#[test]
fn bad_maps_are_refused_with_their_reason() {
    let refused = |extra: &[&str], expected: &str| {
        let mut arguments = vec!["sleigh", "--at", "dot(x)=v"];
        if !extra.contains(&"--speed") {
            arguments.extend(["--speed", "v=0:1:0.5"]);
        }
        arguments.extend(extra);
        let (output, _) = map_command("map-refused", &arguments);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{extra:?}");
        assert!(stderr.contains(expected), "{extra:?}: {stderr}");
    };
    refused(&["--param", "a=1"], "vary one or two parameters");
    let three = [
        "--param",
        "a=0:1:1",
        "--param",
        "m=1:2:1",
        "--param",
        "inertia=1:2:1",
    ];
    refused(
        &three,
        "vary one or two parameters (NAME=START:STOP:STEP), found 3",
    );
    refused(&["--param", "length=0:1:1"], "unknown parameter `length`");
    refused(
        &["--param", "a=0:1:1", "--param", "a=2:3:1"],
        "--param a: varied twice",
    );
    let speed_is_a = ["--param", "m=1:2:1", "--speed", "a=0:1:0.5"];
    refused(&speed_is_a, "`a` is a parameter");
}

/// Ctrl-C (SIGINT) while a map runs: the command writes the design points
/// done, says how many of how many, and fails.
#[test]
fn an_interrupted_map_keeps_the_points_done() {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("map-interrupted");
    let _ = std::fs::remove_dir_all(&out);
    let mut arguments = vec!["map", "bicycle", "--speed", "v=0:10:0.01", "--jobs", "1"];
    for (name, value) in upright() {
        arguments.extend(["--at".to_string(), format!("{name}={value}")].map(leak));
    }
    arguments.extend([
        "--param",
        "c=0:0.2:0.001",
        "--out",
        leak(out.display().to_string()),
    ]);
    let output = interrupted(&arguments);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let said = stderr
        .lines()
        .find_map(|line| line.strip_prefix("error: interrupted: "))
        .unwrap_or_else(|| panic!("{stderr}"));
    let done: usize = said
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .expect("a count");
    assert!(
        said.ends_with(" of 201 design points computed and written"),
        "{said}"
    );
    assert!(done < 201, "{said}");
    let text = std::fs::read_to_string(out.join("map.csv")).expect("map.csv");
    assert_eq!(text.lines().count(), 1 + done, "{text}");
}
