//! `chaplygin plan` (docs/INTERFACE.md section 13) run as a command: a
//! point mass moved between rests, whose optimal cost `12 m^2 / T^3` is
//! known in closed form, over a given or a free duration, to a hard or a
//! soft goal, and restarted from its own `plan.csv`; `plan.csv` with
//! `trajectory.csv`'s columns, in the Lagrange and the reduced form; and
//! bad requests refused in one line.

use crate::support::browser::screenshot;
use crate::support::{chaplygin, column, interrupted, read_csv, scratch};
use std::path::Path;
use std::process::Output;

/// `m xddot = push`.
const POINT_MASS: &str = "pub struct PointMass {
    coordinates: [x],
    parameters: [m = 2.0],
    kinetic_energy: m/2*dot(x)^2,
    inputs: [push = x],
}";

/// `chaplygin` with `arguments` on the point mass, written into `dir`.
fn run(dir: &Path, command: &str, arguments: &[&str]) -> Output {
    let model = dir.join("point_mass.model");
    std::fs::write(&model, POINT_MASS).expect("the model is written");
    let out = dir.join(command);
    let mut all = vec![
        command,
        model.to_str().expect("UTF-8"),
        "--out",
        out.to_str().expect("UTF-8"),
    ];
    all.extend(arguments);
    chaplygin(&all)
}

const REST_TO_REST: [&str; 10] = [
    "--duration",
    "2",
    "--start",
    "x=0",
    "--start",
    "dot(x)=0",
    "--goal",
    "x=1",
    "--goal",
    "dot(x)=0",
];

#[test]
fn a_point_mass_plan_meets_its_closed_form_cost() {
    let dir = scratch("plan-point-mass");
    let mut arguments = REST_TO_REST.to_vec();
    arguments.extend(["--nodes", "41"]);
    let output = run(dir.path(), "plan", &arguments);
    let stdout = String::from_utf8_lossy(&output.stdout);
    let report = report(dir.path(), &output);
    assert!(stdout.contains("a verified optimum"), "{stdout}");
    // 12 m^2 / T^3 with m = 2, T = 2; the midpoint rule's error on 41 nodes
    // is 3.8e-3 (h^2 / 4 of it, from the library's convergence test).
    let objective = report["objective"].as_f64().expect("a number");
    assert!((objective - 6.0).abs() < 5e-3, "{objective}");
    assert_eq!(report["nodes"], 41);
    assert_eq!(report["scheme"], "midpoint");
    for residual in ["primal", "dual", "complementarity"] {
        let value = report["kkt"][residual].as_f64().expect("a number");
        assert!(value <= 1e-6, "{residual} {value}");
    }
    // The midpoint rule's step is exact for a constant force: the replay
    // meets the nodes to round-off.
    let replay = &report["replay"];
    assert_eq!(replay["within"], true, "{replay}");
    assert_eq!(replay["tolerance"], 0.25, "{replay}");
    assert_eq!(replay["end"]["node"], 40, "{replay}");
    let departure = replay["largest"]["relative"].as_f64().expect("a number");
    assert!(departure < 1e-9, "{replay}");
    let (header, rows) = read_csv(&dir.path().join("plan/plan.csv"));
    assert_eq!(rows.len(), 41);
    let x = column(&header, &rows, "x");
    assert_eq!((x[0], x[40]), (0.0, 1.0));
    let simulated = run(
        dir.path(),
        "simulate",
        &["--formulation", "lagrange", "--t-end", "0.01"],
    );
    assert!(simulated.status.success());
    let (trajectory_header, _) = read_csv(&dir.path().join("simulate/trajectory.csv"));
    assert_eq!(header, trajectory_header);
}

/// The differential drive parked in the reduced and the momentum form:
/// `plan.csv` has the columns of `simulate`'s `trajectory.csv` in that form
/// (the reduced momenta and `chart`, or the shape velocities), `plan.json`
/// names the formulation, its chart (0, or none) and the exact Hessian,
/// and the goal's pose is met.
#[test]
fn a_plan_in_another_form_has_that_forms_trajectory_columns() {
    for (formulation, chart) in [("reduced", Some(0)), ("momentum", None)] {
        let dir = scratch(&format!("plan-{formulation}"));
        let out = |name: &str| dir.path().join(name).to_str().expect("UTF-8").to_string();
        let (plan_out, simulate_out) = (out("plan"), out("simulate"));
        let mut arguments: Vec<String> = ["plan", "differential-drive", "--formulation"]
            .into_iter()
            .chain([formulation, "--duration", "4", "--nodes", "21"])
            .chain(["--out", &plan_out])
            .map(String::from)
            .collect();
        for q in ["x", "y", "theta", "phi_r", "phi_l"] {
            arguments.extend(["--start".into(), format!("{q}=0")]);
            arguments.extend(["--start".into(), format!("dot({q})=0")]);
        }
        for goal in ["x=0.3", "y=0.1", "theta=0", "dot(phi_r)=0", "dot(phi_l)=0"] {
            arguments.extend(["--goal".into(), goal.into()]);
        }
        let output = chaplygin(&arguments.iter().map(String::as_str).collect::<Vec<_>>());
        let report = report(dir.path(), &output);
        assert_eq!(report["formulation"], formulation);
        assert_eq!(report["chart"], serde_json::json!(chart));
        let reason = report["chart_reason"].as_str();
        assert_eq!(reason.is_some(), chart.is_some(), "{reason:?}");
        assert!(
            reason.is_none_or(|reason| reason.starts_with("chart 0, the one simulate starts in")),
            "{reason:?}"
        );
        assert_eq!(report["solver"], "ripopt (exact Hessian)");
        let (header, rows) = read_csv(&dir.path().join("plan/plan.csv"));
        let last = rows.len() - 1;
        for (name, goal) in [("x", 0.3), ("y", 0.1), ("theta", 0.0)] {
            let value = column(&header, &rows, name)[last];
            assert!((value - goal).abs() < 1e-9, "{name} {value}");
        }
        let simulated = chaplygin(&[
            "simulate",
            "differential-drive",
            "--formulation",
            formulation,
            "--t-end",
            "0.01",
            "--out",
            &simulate_out,
        ]);
        assert!(simulated.status.success());
        let (trajectory_header, _) = read_csv(&dir.path().join("simulate/trajectory.csv"));
        assert_eq!(header, trajectory_header);
    }
}

/// Both Hessians reach the closed-form cost, and `plan.json` names the one
/// used: the exact one by default.
#[test]
fn each_hessian_reaches_the_closed_form_cost_and_is_named() {
    let dir = scratch("plan-hessians");
    for (choice, solver) in [
        (None, "ripopt (exact Hessian)"),
        (Some("lbfgs"), "ripopt (L-BFGS Hessian)"),
    ] {
        let mut arguments = REST_TO_REST.to_vec();
        arguments.extend(["--nodes", "21"]);
        arguments.extend(choice.map(|h| ["--hessian", h]).into_iter().flatten());
        let output = run(dir.path(), "plan", &arguments);
        let report = report(dir.path(), &output);
        // 12 m^2 / T^3 = 6; the midpoint rule's error on 21 nodes is
        // 0.015 (h^2 / 4 of it, h = 0.1).
        let objective = report["objective"].as_f64().expect("a number");
        assert!((objective - 6.0).abs() < 2e-2, "{objective}");
        assert_eq!(report["solver"], solver);
    }
}

/// The standard error of a refused plan: one line, `error: ` and `says`.
fn refused(arguments: &[&str], says: &str) {
    let dir = scratch("plan-refused");
    let output = run(dir.path(), "plan", arguments);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: ") && stderr.contains(says),
        "{stderr}"
    );
    assert!(!dir.path().join("plan/plan.json").exists());
}

#[test]
fn bad_plans_are_refused_in_one_line() {
    let with = |extra: &[&'static str]| {
        let mut all = REST_TO_REST.to_vec();
        all.extend(extra);
        if !extra.contains(&"--nodes") {
            all.extend(["--nodes", "11"]);
        }
        all
    };
    refused(&with(&["--goal", "y=1"]), "--goal: unknown name `y`");
    refused(&with(&["--nodes", "1"]), "at least 2 nodes");
    refused(
        &with(&["--bound", "x=:0.5"]),
        "lies outside --bound x=-inf:0.5",
    );
    // infeasible (a push of at most 0.1 moves the mass 0.05 in the time):
    // on one interval the solver says so in 40 iterations
    refused(
        &with(&["--bound", "push=-0.1:0.1", "--nodes", "2"]),
        "no verified optimum",
    );
    refused(
        &with(&["--replay-tol", "0"]),
        "--replay-tol 0: the replay's tolerance must be positive and finite",
    );
    refused(
        &with(&["--formulation", "momentum"]),
        "--formulation momentum: the model declares no symmetry",
    );
    refused(
        &with(&["--formulation", "reduced", "--bound", "dot(x)=-1:1"]),
        "--bound dot(x): the reduced form's state does not hold this velocity",
    );
}

/// The snakeboard parked sideways without `--bound phi=-1.2:1.2`
/// (docs/guide/planning.md) on 21 nodes: a verified optimum that steers
/// its wheels across `phi = pi/2` and jumps there, its replay departing
/// by more than its tolerance. The command fails in one line naming the
/// variable, and writes the plan marked.
#[test]
fn a_plan_its_replay_departs_from_fails_and_is_written_marked() {
    let dir = scratch("plan-departs");
    let out = dir.path().join("plan");
    let mut arguments = vec!["plan", "snakeboard", "--duration", "6", "--nodes", "21"];
    for (name, value) in [
        ("x", 0.0),
        ("y", 0.0),
        ("theta", 0.0),
        ("psi", 0.0),
        ("phi", 0.3),
    ] {
        arguments.extend(["--start", leak(format!("{name}={value}"))]);
        arguments.extend(["--start", leak(format!("dot({name})=0"))]);
        arguments.extend(["--goal", leak(format!("dot({name})=0"))]);
    }
    for goal in ["x=0", "y=0.2", "theta=0", "phi=0.3"] {
        arguments.extend(["--goal", goal]);
    }
    arguments.extend(["--out", out.to_str().expect("UTF-8")]);
    let output = chaplygin(&arguments);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let report = plan_json(&out);
    let replay = &report["replay"];
    let variable = replay["largest"]["variable"].as_str().expect("a name");
    assert!(
        stderr.contains("the plan is not a motion of the model")
            && stderr.contains(&format!("`{variable}`"))
            && stderr.contains("the plan, marked, is in"),
        "{stderr}"
    );
    assert_eq!(replay["within"], false, "{replay}");
    let relative = replay["largest"]["relative"]
        .as_f64()
        .unwrap_or(f64::INFINITY);
    assert!(relative > 0.25, "{replay}");
    let csv = std::fs::read_to_string(out.join("plan.csv")).expect("plan.csv");
    assert!(
        csv.starts_with("# not a motion of the model: its replay departs from it"),
        "{csv}"
    );
}

/// `plan.json` of a successful run in `dir`'s `plan`.
fn report(dir: &Path, output: &Output) -> serde_json::Value {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    plan_json(&dir.join("plan"))
}

/// `plan.json` in `out`.
fn plan_json(out: &Path) -> serde_json::Value {
    let json = std::fs::read_to_string(out.join("plan.json")).expect("plan.json");
    serde_json::from_str(&json).expect("JSON")
}

/// `min T + int u^2` for the point mass with `m = 1` moved by 1: over a
/// given `T` the cost is `T + 12/T^3`, least at `T = sqrt 6` where it is
/// `8/sqrt 6`; Hermite-Simpson is exact on the optimum's cubic.
#[test]
fn a_free_duration_plan_by_hermite_simpson_meets_its_closed_form() {
    let dir = scratch("plan-free-duration");
    let mut arguments = REST_TO_REST.to_vec();
    arguments.extend([
        "--nodes",
        "21",
        "--param",
        "m=1",
        "--scheme",
        "hermite-simpson",
        "--free-duration",
        "--final-cost",
        "t",
    ]);
    let report = report(dir.path(), &run(dir.path(), "plan", &arguments));
    let duration = report["duration"].as_f64().expect("a number");
    let objective = report["objective"].as_f64().expect("a number");
    assert!((duration - 6.0_f64.sqrt()).abs() < 1e-6, "{duration}");
    assert!(
        (objective - 8.0 / 6.0_f64.sqrt()).abs() < 1e-8,
        "{objective}"
    );
    assert_eq!(report["scheme"], "hermite-simpson");
    let (header, rows) = read_csv(&dir.path().join("plan/plan.csv"));
    assert!((column(&header, &rows, "t")[20] - duration).abs() < 1e-12);
}

/// A soft goal `12 (x(T) - 1)^2` for the point mass with `m = 1` over `T =
/// 1`: reaching `y` costs `12 y^2`, so `y = 1/2` and the cost is 6.
#[test]
fn a_final_cost_plan_meets_its_closed_form() {
    let dir = scratch("plan-final-cost");
    let arguments = [
        "--duration",
        "1",
        "--nodes",
        "11",
        "--param",
        "m=1",
        "--scheme",
        "hermite-simpson",
        "--start",
        "x=0",
        "--start",
        "dot(x)=0",
        "--goal",
        "dot(x)=0",
        "--final-cost",
        "12*(x - 1)^2",
    ];
    let report = report(dir.path(), &run(dir.path(), "plan", &arguments));
    let objective = report["objective"].as_f64().expect("a number");
    assert!((objective - 6.0).abs() < 1e-7, "{objective}");
    let (header, rows) = read_csv(&dir.path().join("plan/plan.csv"));
    assert!((column(&header, &rows, "x")[10] - 0.5).abs() < 1e-7);
}

/// A plan restarted from its own `plan.csv` on a finer grid reaches the
/// same optimum (the midpoint rule's objective on 21 nodes, `12 m^2 / T^3`
/// to within its `h^2` error).
#[test]
fn a_plan_csv_is_a_guess() {
    let dir = scratch("plan-guess");
    let mut coarse = REST_TO_REST.to_vec();
    coarse.extend(["--nodes", "11"]);
    report(dir.path(), &run(dir.path(), "plan", &coarse));
    let guess = dir.path().join("guess.csv");
    std::fs::rename(dir.path().join("plan/plan.csv"), &guess).expect("moved");
    let mut fine = REST_TO_REST.to_vec();
    fine.extend(["--nodes", "21", "--guess", guess.to_str().expect("UTF-8")]);
    let report = report(dir.path(), &run(dir.path(), "plan", &fine));
    let objective = report["objective"].as_f64().expect("a number");
    assert!((objective - 6.0).abs() < 2e-2, "{objective}");
}

/// A reduced plan's `plan.csv`, which holds the momenta `alpha` for the
/// velocities, is a guess for a Lagrange plan: read in the velocities its
/// momenta give, it starts the solve near the same optimum (the two forms'
/// plans differ by the scheme's error), which it meets in fewer
/// iterations than from the default guess, to the solver's tolerance.
#[test]
fn a_reduced_plan_is_a_lagrange_plans_guess() {
    let dir = scratch("plan-reduced-guess");
    let planned = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut arguments = parking("21");
        arguments.extend(extra);
        arguments.extend(["--out", leak(out.display().to_string())]);
        let output = chaplygin(&arguments);
        assert!(output.status.success(), "{output:?}");
        out
    };
    let reduced = planned("reduced", &["--formulation", "reduced"]).join("plan.csv");
    let guess = ["--guess", reduced.to_str().expect("UTF-8")];
    let [plain, guessed] =
        [planned("plain", &[]), planned("guessed", &guess)].map(|out| plan_json(&out));
    let number = |report: &serde_json::Value, key: &str| report[key].as_f64().expect(key);
    let (a, b) = (number(&plain, "objective"), number(&guessed, "objective"));
    assert!((a - b).abs() < 1e-6 * a, "{a} against {b}");
    let iterations = [&plain, &guessed].map(|report| number(report, "iterations"));
    assert!(iterations[1] < iterations[0], "{iterations:?}");
}

#[test]
fn bad_guesses_and_free_durations_are_refused_in_one_line() {
    let dir = scratch("plan-bad-guess");
    let guess = dir.path().join("guess.csv");
    std::fs::write(&guess, "t,x,y\n0,0,0\n1,1,0\n").expect("written");
    let mut arguments = REST_TO_REST.to_vec();
    arguments.extend(["--nodes", "11", "--guess", guess.to_str().expect("UTF-8")]);
    refused(&arguments, "guess.csv: unknown columns y");
    let mut free = REST_TO_REST[2..].to_vec();
    free.extend(["--nodes", "11", "--free-duration", "--duration", "0"]);
    refused(
        &free,
        "--duration 0: the free duration's first guess must be positive",
    );
}

/// The differential drive parked 0.3 m ahead and 0.1 m to the side, from
/// rest, on `nodes` nodes.
fn parking(nodes: &str) -> Vec<&str> {
    let mut arguments = vec!["plan", "differential-drive", "--duration", "4"];
    arguments.extend(["--nodes", nodes]);
    for start in ["x", "y", "theta", "phi_r", "phi_l"] {
        arguments.extend(["--start".to_string(), format!("{start}=0")].map(leak));
        arguments.extend(["--start".to_string(), format!("dot({start})=0")].map(leak));
    }
    for goal in ["x=0.3", "y=0.1", "theta=0", "dot(phi_r)=0", "dot(phi_l)=0"] {
        arguments.extend(["--goal", goal]);
    }
    arguments
}

fn leak(text: String) -> &'static str {
    Box::leak(text.into_boxed_str())
}

/// The scene `animation.html` embeds for its page.
fn scene(page: &Path) -> serde_json::Value {
    let html = std::fs::read_to_string(page).expect("animation.html");
    let start = r#"<script type="application/json" id="chaplygin-data">"#;
    let from = html.find(start).expect("the scene") + start.len();
    let to = from + html[from..].find("</script>").expect("its end");
    serde_json::from_str(&html[from..to]).expect("JSON")
}

/// Beside `plan.csv`: the plots `simulate` draws, the states and inputs
/// against `t`, and with `--animate` the page of the plan's nodes, whose
/// frames are rows of `plan.csv` and whose drive sits at their `(x, y)`.
#[test]
fn a_plan_is_plotted_and_animated_from_its_nodes() {
    let dir = scratch("plan-outputs");
    let out = dir.path().join("parked");
    let mut arguments = parking("41");
    arguments.extend([
        "--animate",
        "--fps",
        "5",
        "--out",
        leak(out.display().to_string()),
    ]);
    let output = chaplygin(&arguments);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for png in ["path", "energy", "constraint_residual", "states", "inputs"] {
        let file = out.join(format!("{png}.png"));
        let bytes = std::fs::read(&file).unwrap_or_else(|_| panic!("{png}.png: {stdout}"));
        assert_eq!(bytes[..8], *b"\x89PNG\r\n\x1a\n", "{png}.png");
        assert!(
            stdout.contains(&format!("wrote {}", file.display())),
            "{stdout}"
        );
    }
    let (header, rows) = read_csv(&out.join("plan.csv"));
    let [t, x, y] = ["t", "x", "y"].map(|name| column(&header, &rows, name));
    let scene = scene(&out.join("animation.html"));
    let times: Vec<f64> = (scene["times"].as_array().expect("times").iter())
        .map(|time| time.as_f64().expect("a number"))
        .collect();
    // 5 frames a second over 4 s of nodes 0.1 s apart: every second node
    // (serde_json reads a decimal to within an ulp, not always exactly)
    let frames: Vec<usize> = (times.iter())
        .map(|time| {
            (t.iter().position(|node| (node - time).abs() < 1e-12))
                .unwrap_or_else(|| panic!("{time} is not a node's time: {t:?}"))
        })
        .collect();
    assert_eq!(frames, (0..41).step_by(2).collect::<Vec<_>>());
    let body = (scene["items"].as_array().expect("items").iter())
        .find(|item| item["shape"] == "box")
        .expect("the drive's body");
    let centres: Vec<f64> = (body["position"].as_array().expect("positions").iter())
        .map(|value| value.as_f64().expect("a number"))
        .collect();
    for (centre, &row) in centres.chunks(3).zip(&frames) {
        let off = (centre[0] - x[row]).hypot(centre[1] - y[row]);
        assert!(off < 1e-12, "frame at t = {}: {centre:?}", t[row]);
    }
}

/// On a terminal (a pseudo-terminal from `script`), standard error shows
/// one line per solver iteration, numbered from 0, the last one's
/// objective the optimum `plan.json` reports and its primal infeasibility
/// within what the KKT check allows (100 times `--tol`).
#[test]
fn a_terminal_shows_each_iteration() {
    let dir = scratch("plan-terminal");
    let out = dir.path().join("parked");
    let mut arguments = parking("21");
    arguments.extend(["--out", leak(out.display().to_string())]);
    let command = std::iter::once(env!("CARGO_BIN_EXE_chaplygin"))
        .chain(arguments)
        .map(|argument| format!("'{argument}'"))
        .collect::<Vec<_>>()
        .join(" ");
    let output = std::process::Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .output()
        .expect("script runs");
    let shown = String::from_utf8_lossy(&output.stdout).replace('\r', "");
    assert!(output.status.success(), "{shown}");
    let report = plan_json(&out);
    let header = shown.lines().position(|line| {
        line.split_whitespace()
            .eq(["iter", "objective", "primal", "dual"])
    });
    let lines: Vec<Vec<f64>> = (shown.lines().skip(header.expect("a header") + 1))
        .map_while(|line| {
            let fields: Option<Vec<f64>> =
                line.split_whitespace().map(|f| f.parse().ok()).collect();
            fields.filter(|fields| fields.len() == 4)
        })
        .collect();
    let iterations = report["iterations"].as_u64().expect("a count") as usize;
    assert_eq!(lines.len(), iterations + 1, "{shown}");
    for (number, line) in lines.iter().enumerate() {
        assert_eq!(line[0], number as f64, "{shown}");
    }
    let objective = report["objective"].as_f64().expect("a number");
    let last = lines.last().expect("a line");
    assert!(
        (last[1] - objective).abs() <= 1e-8 * objective.abs(),
        "{last:?} against {objective}"
    );
    let primal = report["kkt"]["primal"].as_f64().expect("a number");
    assert!(
        primal <= 1e-6 && last[2] <= 1e-6,
        "{last:?}, KKT primal {primal}"
    );
}

/// Ctrl-C (SIGINT) during a long solve: the command writes the last
/// iterate, `plan.csv` marked as not verified and `plan.json` with the
/// status `interrupted` and its KKT residuals, and fails in one line.
#[test]
fn an_interrupted_plan_keeps_its_last_iterate() {
    let dir = scratch("plan-interrupted");
    let out = dir.path().join("parked");
    let mut arguments = parking("1001");
    arguments.extend(["--out", leak(out.display().to_string())]);
    // the solve takes a minute; its start, three seconds
    let output = interrupted(&arguments);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let said =
        (stderr.strip_prefix("error: interrupted after ")).unwrap_or_else(|| panic!("{stderr}"));
    assert!(
        said.contains("not an optimum")
            && said.contains(&format!(
                "the last iterate, not verified, is in {}",
                out.display()
            )),
        "{stderr}"
    );
    let report = plan_json(&out);
    assert_eq!(report["status"], "interrupted");
    let iterations = report["iterations"].as_u64().expect("a count");
    assert!(
        said.starts_with(&format!("{iterations} iterations")),
        "{stderr}"
    );
    for residual in ["primal", "dual", "complementarity"] {
        assert!(report["kkt"][residual].is_number(), "{report}");
    }
    let text = std::fs::read_to_string(out.join("plan.csv")).expect("plan.csv");
    let first = text.lines().next().expect("a first line");
    assert_eq!(
        first,
        format!("# not verified: interrupted after {iterations} iterations (plan.json)")
    );
    let marked = out.join("plan.csv");
    let unmarked = dir.path().join("unmarked.csv");
    std::fs::write(&unmarked, text.split_once('\n').expect("rows").1).expect("written");
    let (header, rows) = read_csv(&unmarked);
    assert_eq!(rows.len(), 1001, "{}", marked.display());
    // the start is fixed by the bounds, which every iterate meets
    assert_eq!(column(&header, &rows, "x")[0], 0.0);
}

/// The guide's lane change: the benchmark bicycle from its upright
/// straight run at 5 m/s to `y_p = 1` in 3 s, upright, steer and heading
/// straight, the lean torque bounded to 0 (the library's
/// `catalog_tests` replays its steer torque to the goal).
fn lane_change(out: &Path) -> Vec<&'static str> {
    let mut arguments = vec!["plan", "bicycle", "--duration", "3", "--nodes", "31"];
    for q in [
        "x_p", "y_p", "psi", "phi", "theta_b", "delta", "theta_r", "theta_f",
    ] {
        arguments.extend(["--start".to_string(), format!("{q}=0")].map(leak));
    }
    for velocity in ["dot(y_p)=0", "dot(psi)=0", "dot(phi)=0", "dot(theta_b)=0"] {
        arguments.extend(["--start", velocity]);
    }
    for velocity in [
        "dot(delta)=0",
        "dot(x_p)=5",
        "dot(theta_r)=-5/rR",
        "dot(theta_f)=-5/rF",
    ] {
        arguments.extend(["--start", velocity]);
    }
    for goal in [
        "y_p=1",
        "psi=0",
        "phi=0",
        "delta=0",
        "dot(phi)=0",
        "dot(delta)=0",
    ] {
        arguments.extend(["--goal", goal]);
    }
    arguments.extend(["--bound", "lean_torque=0:0", "--animate", "--fps", "20"]);
    arguments.extend(["--out", leak(out.display().to_string())]);
    arguments
}

/// The lane change is a verified optimum whose last node is the goal, with
/// no lean torque; its page is the guide's screenshot, the bicycle
/// halfway across.
#[test]
fn the_bicycle_changes_lane() {
    let dir = scratch("plan-lane-change");
    let out = dir.path().join("lane");
    let output = chaplygin(&lane_change(&out));
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let (header, rows) = read_csv(&out.join("plan.csv"));
    let [y, phi, lean] = ["y_p", "phi", "lean_torque"].map(|name| column(&header, &rows, name));
    assert_eq!((y[0], y[30], phi[30]), (0.0, 1.0, 0.0));
    assert!(lean.iter().all(|u| u.abs() <= 1e-6), "{lean:?}");
    let page = std::fs::read_to_string(out.join("animation.html")).expect("animation.html");
    screenshot(&page, 1.6, "bicycle-lane-change", dir.path());
}
