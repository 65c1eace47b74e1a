//! The programs of `examples/` (`cargo run --example NAME`) run in this
//! process: each file is a module here, whose `main` writes `report` to
//! standard output, and what `report` writes is checked against values
//! from elsewhere: the sleigh's closed-form motion, the benchmark
//! bicycle's published self-stable speeds and closed-form eigenvalues, the
//! snakeboard's hand-derived momentum equation (MATH.md 4.1), the energy a
//! conservative motion keeps, a plan's goal reached by its replayed inputs. The build-script door's example is checked
//! by its own package's tests (`examples/build-script-door/tests`), where
//! its build script's output is.

#[allow(dead_code)]
#[path = "../examples/bicycle_stability.rs"]
mod bicycle_stability;
#[allow(dead_code)]
#[path = "../examples/plan_differential_drive.rs"]
mod plan_differential_drive;
#[allow(dead_code)]
#[path = "../examples/sleigh.rs"]
mod sleigh;
#[allow(dead_code)]
#[path = "../examples/snakeboard_gait.rs"]
mod snakeboard_gait;
#[allow(dead_code)]
#[path = "../examples/torsion_spring_skate.rs"]
mod torsion_spring_skate;

use crate::support::benchmark_bicycle::BenchmarkParameters;
use crate::support::markdown::root;
use crate::support::printed::numbers;
use crate::support::snakeboard_gait::hand_derived;
use std::fmt::Debug;

/// What `report` writes.
fn printed<E: Debug>(report: impl FnOnce(&mut Vec<u8>) -> Result<(), E>) -> String {
    let mut out = Vec::new();
    report(&mut out).expect("the example runs");
    String::from_utf8(out).expect("UTF-8")
}

/// The lines of `text` that are numbers alone, each as its numbers.
fn table(text: &str) -> Vec<Vec<f64>> {
    (text.lines())
        .filter_map(|line| {
            line.split_whitespace()
                .map(|word| word.parse().ok())
                .collect()
        })
        .filter(|row: &Vec<f64>| !row.is_empty())
        .collect()
}

/// The numbers of the first line of `text` that starts with `start`.
fn numbers_after(text: &str, start: &str) -> Vec<f64> {
    let line = (text
        .lines()
        .find(|line| line.trim_start().starts_with(start)))
    .unwrap_or_else(|| panic!("a line `{start}...` in\n{text}"));
    numbers(line)
}

/// Asserts that `actual` is `expected` within `tolerance`.
fn near(actual: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{what}: {actual} against {expected}"
    );
}

/// The sleigh's speed `v`, turning rate `w` and heading obey
/// `vdot = a w^2`, `J wdot = -m a v w` (`J = I + m a^2`): with
/// `U = sqrt(v0^2 + J w0^2 / m)`, `k = m a U / J` and `c = atanh(v0 / U)`,
/// `v = U tanh(k t + c)`, `w = sqrt(m / J) U sech(k t + c)` and
/// `theta = sqrt(J / m) / a (gd(k t + c) - gd(c))` (`gd` the
/// Gudermannian, `w0 > 0`). The printed values have six decimals; the run
/// is accurate to 1e-9.
#[test]
fn the_sleigh_swings_round_as_its_closed_form_says() {
    let text = printed(sleigh::report);
    let sleigh = sleigh::Sleigh::default();
    let (m, a) = (sleigh.m, sleigh.a);
    let j = sleigh.inertia + m * a * a;
    let rows = table(&text);
    assert_eq!(rows.len(), 17, "every half second from 0 to 8 s:\n{text}");
    let (v0, w0) = (rows[0][1], rows[0][2]);
    assert!(v0 < 0.0 && w0 > 0.0 && rows[0][3] == 0.0, "{text}");
    let terminal = (v0 * v0 + j * w0 * w0 / m).sqrt();
    let (k, c) = (m * a * terminal / j, (v0 / terminal).atanh());
    let gd = |x: f64| 2.0 * (x / 2.0).tanh().atan();
    for row in &rows {
        let s = k * row[0] + c;
        near(row[1], terminal * s.tanh(), 2e-6, "speed");
        near(
            row[2],
            (m / j).sqrt() * terminal / s.cosh(),
            2e-6,
            "turning rate",
        );
        near(
            row[3],
            (j / m).sqrt() / a * (gd(s) - gd(c)),
            2e-6,
            "heading",
        );
    }
    let said = numbers_after(&text, "its energy");
    near(said[said.len() - 1], terminal, 1e-12, "terminal speed");
    assert!(rows[16][1] > 0.0, "it slides on forwards");
    assert!(numbers_after(&text, "energy drift")[0] < 1e-9, "{text}");
}

/// Meijaard et al. (2007), section 6: weave speed 4.292382536341 m/s,
/// capsize speed 6.024262015388 m/s; the eigenvalues at each speed are
/// those of their appendix A's closed form (printed to six decimals).
#[test]
fn the_bicycle_balances_itself_between_the_published_speeds() {
    let text = printed(bicycle_stability::report);
    let closed_form = BenchmarkParameters::benchmark();
    let order = |a: &(f64, f64), b: &(f64, f64)| a.partial_cmp(b).expect("finite");
    let rows: Vec<Vec<f64>> = (text.lines())
        .filter(|line| line.starts_with("v ="))
        .map(numbers)
        .collect();
    assert_eq!(rows.len(), 21, "every half metre per second to 10:\n{text}");
    for row in &rows {
        let v = row[0];
        let mut printed: Vec<(f64, f64)> = row[1..].chunks(2).map(|e| (e[0], e[1])).collect();
        let mut expected: Vec<(f64, f64)> = (closed_form.eigenvalues(v).iter())
            .map(|e| (e.re, e.im))
            .collect();
        printed.sort_by(order);
        expected.sort_by(order);
        assert_eq!(printed.len(), 4, "{row:?}");
        for (printed, expected) in printed.iter().zip(&expected) {
            near(printed.0, expected.0, 1e-6, &format!("re at v = {v}"));
            near(printed.1, expected.1, 1e-6, &format!("im at v = {v}"));
        }
    }
    let speeds = numbers_after(&text, "self-stable");
    near(speeds[0], 4.292382536341, 1e-9, "weave speed");
    near(speeds[1], 6.024262015388, 1e-9, "capsize speed");
}

/// The differential drive's plan: its printed KKT residuals within the
/// library's check (100 times the tolerance), its torques replayed from
/// rest to within the midpoint rule's error of the goal (below 1e-3 on 21
/// nodes, shrinking as `h^2`: the library's tests), the replay's largest
/// departure within its tolerance.
#[test]
fn the_differential_drive_plan_reaches_its_goal_replayed() {
    let text = printed(plan_differential_drive::report);
    let objective = numbers_after(&text, "objective")[0];
    assert!(objective > 0.0, "{text}");
    for residual in numbers_after(&text, "KKT residuals") {
        assert!(residual.abs() <= 1e-6, "{text}");
    }
    for (name, goal) in plan_differential_drive::GOAL {
        let row = numbers_after(&text, name);
        near(row[0], goal, 1e-3, name);
        near(row[1], goal, 0.0, name);
    }
    let departure = numbers_after(&text, "replay departs most");
    let (relative, allowed) = (
        departure[departure.len() - 2],
        departure[departure.len() - 1],
    );
    assert!(relative <= allowed, "{text}");
}

/// Each loop's net and geometric displacement equal those of the
/// hand-derived equations integrated independently (printed to nine
/// decimals).
#[test]
fn the_snakeboards_gaits_move_it_as_the_hand_derived_equations_say() {
    let text = printed(snakeboard_gait::report);
    let lines: Vec<&str> = text.lines().collect();
    for shape_loop in &snakeboard_gait::LOOPS {
        let (a, f) = shape_loop.torso;
        let (b, g, c) = shape_loop.steering;
        let shape = |t: f64| {
            let steering = g * t + c;
            (
                b * steering.sin(),
                a * f * (f * t).cos(),
                b * g * steering.cos(),
            )
        };
        let at = (lines.iter())
            .position(|line| *line == format!("{}:", shape_loop.label))
            .unwrap_or_else(|| panic!("{} in\n{text}", shape_loop.label));
        for (line, momentum) in [(lines[at + 1], true), (lines[at + 2], false)] {
            let expected = hand_derived(shape, momentum, 20_000);
            for (printed, expected) in numbers(line).iter().zip(expected) {
                near(*printed, expected, 1e-8, line);
            }
        }
    }
}

/// The skate's energy is conserved: the discrete gradient keeps it to
/// round-off, the midpoint rule only to its order (its energy is not
/// quadratic).
#[test]
fn the_discrete_gradient_keeps_the_skates_energy() {
    let text = printed(torsion_spring_skate::report);
    let gradient = numbers_after(&text, "discrete gradient")[0];
    let midpoint = numbers_after(&text, "implicit midpoint")[0];
    assert!(gradient < 1e-12, "{text}");
    assert!(midpoint > 1e-6 && midpoint < 1e-2, "{text}");
}

#[test]
fn every_example_runs_here() {
    let this = std::fs::read_to_string(root().join("tests/examples.rs")).expect("this file");
    for entry in std::fs::read_dir(root().join("examples")).expect("examples/") {
        let path = entry.expect("an entry").path();
        if path.extension().is_some_and(|e| e == "rs") {
            let name = path.file_name().expect("a name").to_string_lossy();
            let module = format!("#[path = \"../examples/{name}\"]");
            assert!(
                this.contains(&module),
                "examples/{name} is not a module here"
            );
        }
    }
}
