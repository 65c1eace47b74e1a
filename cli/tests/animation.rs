//! `chaplygin simulate MODEL ... --animate` for every built-in model, the
//! Chaplygin ball and the Ackermann car of their files, and `chaplygin
//! gait snakeboard ... --animate` (docs/INTERFACE.md section 10), the pages opened together in one headless Chromium with a probe
//! that reads `window.chaplygin.pose` of every item at every frame's time,
//! the embedded traces and the canvas's pixels. Every page makes no
//! request, logs no error and draws something; its frames are rows of the
//! run's table. Against what the tests compute from `trajectory.csv` (or
//! the gait's `cycle.csv`) themselves:
//!
//! - the benchmark bicycle pushed to lean at 3 m/s, below its weave speed,
//!   until it falls: at every frame each wheel's disc touches the ground
//!   (z = 0) at its contact point's trace, and the rear wheel's centre is
//!   the one the paper's geometry gives (the model's z axis points down:
//!   the page shows it turned by pi about x);
//! - the snakeboard's gait `psi = 0.8 sin t`, `phi = 0.5 cos t`: the board
//!   turned about z by `theta`, at `(x, y)`, and the front wheels' axle
//!   across the direction `theta + phi` they roll in, `r` ahead;
//! - the vertical rolling disk: its disc at `(x, y, r)`, turned by `theta`
//!   about z and by `phi` about its axle;
//! - the Chaplygin ball turning about all three axes: a sphere of its
//!   radius `r`, its lowest point on the ground at `(x, y)`, turned by its
//!   Euler parameters;
//! - the Ackermann car driven round: its chassis a box spanning the contact
//!   points its geometry (`l`, `b`) places about `(x, y)` heading `theta`,
//!   at the rear axle's height.
//!
//! The guide's screenshots of the bicycle's fall, the snakeboard's gait,
//! the Chaplygin ball and the Ackermann car are these pages (`support::browser::screenshot`). A model with nothing
//! to draw is refused by name.

use crate::support::browser::{chromium, distance, num, nums, pose_of, probe_pages, screenshot};
use crate::support::snakeboard_gait::GAIT;
use crate::support::{FALL, chaplygin, column, markdown, read_csv, scratch};
use chaplygin::driver::catalog::BUILT_IN;
use chaplygin::runtime::nalgebra::{UnitQuaternion, Vector3};
use serde_json::Value;
use std::f64::consts::PI;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::OnceLock;

/// The probe's `measure()` (inside `support::browser::probed`'s start and
/// end, which record the errors): the items, the frames' times, every
/// item's pose at every frame's time, the embedded traces and note, the
/// canvas's drawn pixels and the resources requested.
const PROBE: &str = r#"  async function measure() {
    const c = window.chaplygin;
    await c.ready;
    const data = JSON.parse(document.getElementById('chaplygin-data').textContent);
    const result = { errors, items: c.items, times: Array.from(c.times), note: data.note, traces: data.traces, poses: {} };
    for (const item of c.items) result.poses[item.name] = Array.from(c.times, (t) => c.pose(item.name, t));
    c.seek(c.times[Math.floor(c.times.length / 2)]);
    const canvas = document.querySelector('#view canvas');
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext('2d');
    context.drawImage(canvas, 0, 0);
    const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
    const background = [pixels[0], pixels[1], pixels[2]];
    let drawn = 0;
    const colours = new Set();
    for (let i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - background[0]) + Math.abs(pixels[i + 1] - background[1]) + Math.abs(pixels[i + 2] - background[2]) > 24) drawn++;
      colours.add((pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2]);
    }
    result.pixels = { total: pixels.length / 4, drawn, colours: colours.size };
    result.resources = performance.getEntriesByType('resource').map((entry) => entry.name);
    return result;
  }
"#;

/// Until the bicycle's lean reaches 1.2 rad, after its push (`FALL`, as
/// `bicycle_falling` starts it).
const UNTIL_IT_FALLS: [&str; 4] = ["--t-end", "3", "--stop-when", "abs(phi) > 1.2"];

/// The snakeboard's half length `r`, where its wheels are.
const SNAKEBOARD_R: f64 = 0.5;

/// The Chaplygin ball started at the z-x-z angles (0.3, 0.5, 0.7) turning
/// at (1, 1.6, 2.2) rad/s in its own axes, for 3 s (as the guide shows it).
const BALL: [&str; 8] = [
    "simulate",
    "models/chaplygin_ball.model",
    "--initial",
    "angles(ball, zxz)=[0.3, 0.5, 0.7]",
    "--initial",
    "omega(ball)=[1, 1.6, 2.2]",
    "--t-end",
    "3",
];

/// The Ackermann car driven round a circle, its left front wheel held at
/// `delta_l = 0.3`, for 3 s: the guide's command (docs/guide/mechanisms.md).
const CAR: [&str; 14] = [
    "simulate",
    "tests/models/ackermann_car.model",
    "--input",
    "drive=1",
    "--input",
    "steer_left=-50*(delta_l-0.3)-5*dot(delta_l)",
    "--initial",
    "delta_l=0.3",
    "--initial",
    "dot(delta_l)=0",
    "--initial",
    "dot(phi_rl)=2",
    "--t-end",
    "3",
];

/// The runs of models' files, from the repository's root: their names and
/// arguments.
const FILES: [(&str, &[&str]); 2] = [("chaplygin-ball", &BALL), ("ackermann-car", &CAR)];

/// A run with `--animate`: its name, directory, what it printed, its table
/// (`trajectory.csv` or the gait's `cycle.csv`) and page.
struct Run {
    name: String,
    directory: PathBuf,
    stdout: String,
    table: (Vec<String>, Vec<Vec<f64>>),
    page: String,
}

/// Every run, and what the probe found in each page (`None` without
/// Chromium).
struct Runs {
    runs: Vec<Run>,
    probes: Option<Vec<Value>>,
}

impl Runs {
    /// The run named `name` and its probe's findings.
    fn get(&self, name: &str) -> (&Run, Option<&Value>) {
        let i = (self.runs.iter())
            .position(|run| run.name == name)
            .unwrap_or_else(|| panic!("a run `{name}`"));
        (&self.runs[i], self.probes.as_ref().map(|probes| &probes[i]))
    }
}

/// The built-in model run from its default motion until it fails, its page
/// drawing the rows before the failure as `trajectory.csv` keeps them: the
/// snakeboard, whose wheels turn to `phi = pi/2`, where its two constraint
/// rows become dependent (`models/src/lib.rs`).
const FAILING: &str = "snakeboard";

/// The directory the runs write into, kept after the tests for a look at
/// the pages. The process holds an exclusive lock on `animation.lock`
/// beside it until it exits, so that test runners running each test in a
/// process of its own (`cargo nextest`) take turns with it rather than
/// remove each other's files.
fn runs_directory() -> PathBuf {
    static LOCK: OnceLock<std::fs::File> = OnceLock::new();
    let parent = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    LOCK.get_or_init(|| {
        let lock = std::fs::File::create(parent.join("animation.lock")).expect("the lock file");
        lock.lock().expect("the lock taken");
        lock
    });
    parent.join("animation")
}

/// The runs, made once for all the tests here: each built-in model's
/// `simulate` (for 1 s from its default motion, the bicycle falling,
/// [`FAILING`] until it fails), and the snakeboard's gait, as concurrent
/// processes; then their pages in one Chromium.
fn runs() -> &'static Runs {
    static RUNS: OnceLock<Runs> = OnceLock::new();
    RUNS.get_or_init(|| {
        let root = runs_directory();
        let _ = std::fs::remove_dir_all(&root);
        let mut commands: Vec<(String, Vec<String>, &str)> = (BUILT_IN.iter())
            .map(|model| {
                let mut arguments = vec!["simulate".to_string(), model.name.to_string()];
                match model.name {
                    "bicycle" => arguments
                        .extend((FALL.iter().chain(&UNTIL_IT_FALLS)).map(|a| a.to_string())),
                    FAILING => {}
                    _ => arguments.extend(["--t-end", "1"].map(String::from)),
                }
                (model.name.to_string(), arguments, "trajectory.csv")
            })
            .collect();
        let mut gait = vec!["gait".to_string()];
        gait.extend(GAIT.map(String::from));
        commands.push(("snakeboard-gait".to_string(), gait, "cycle.csv"));
        for (name, arguments) in FILES {
            let arguments = arguments.iter().map(|a| a.to_string()).collect();
            commands.push((name.to_string(), arguments, "trajectory.csv"));
        }
        let children: Vec<_> = (commands.iter())
            .map(|(name, arguments, _)| {
                let directory = root.join(name);
                Command::new(env!("CARGO_BIN_EXE_chaplygin"))
                    .current_dir(markdown::root())
                    .args(arguments)
                    .arg("--animate")
                    .arg("--out")
                    .arg(&directory)
                    .stdout(Stdio::piped())
                    .stderr(Stdio::piped())
                    .spawn()
                    .expect("the binary runs")
            })
            .collect();
        let runs: Vec<Run> = (commands.iter().zip(children))
            .map(|((name, arguments, table), child)| {
                let output = child.wait_with_output().expect("the run ends");
                let stdout = String::from_utf8_lossy(&output.stdout).to_string();
                let stderr = String::from_utf8_lossy(&output.stderr);
                assert_eq!(
                    output.status.success(),
                    name != FAILING,
                    "{arguments:?}: {stdout}{stderr}"
                );
                if name == FAILING {
                    assert!(stderr.contains("error: singular configuration"), "{stderr}");
                }
                let directory = root.join(name);
                Run {
                    name: name.clone(),
                    table: read_csv(&directory.join(table)),
                    page: std::fs::read_to_string(directory.join("animation.html")).unwrap(),
                    directory,
                    stdout,
                }
            })
            .collect();
        let probes = chromium().map(|chromium| {
            let pages: Vec<&str> = runs.iter().map(|run| run.page.as_str()).collect();
            let probe_directory = scratch("animation-probe");
            probe_pages(&chromium, &pages, PROBE, probe_directory.path())
        });
        Runs { runs, probes }
    })
}

#[test]
fn every_built_in_model_s_page_renders_with_no_error_and_no_request() {
    let runs = runs();
    assert_eq!(runs.runs.len(), BUILT_IN.len() + 1 + FILES.len());
    for run in &runs.runs {
        let path = run.directory.join("animation.html");
        let said = format!(
            "wrote {} ({} kB)",
            path.display(),
            run.page.len().div_ceil(1000)
        );
        assert!(run.stdout.contains(&said), "{said} in {}", run.stdout);
    }
    let Some(probes) = &runs.probes else {
        return;
    };
    for (run, result) in runs.runs.iter().zip(probes) {
        let name = &run.name;
        assert_eq!(result["errors"], Value::Array(vec![]), "{name}: errors");
        assert_eq!(
            result["resources"],
            Value::Array(vec![]),
            "{name}: requests"
        );
        assert!(!result["items"].as_array().unwrap().is_empty(), "{name}");
        // every frame is a row of the table, the first and the last among them
        let (header, rows) = &run.table;
        let t = column(header, rows, "t");
        let times = nums(&result["times"]);
        assert!(times.len() > 10, "{name}: {} frames", times.len());
        assert_eq!(
            (times.first(), times.last()),
            (t.first(), t.last()),
            "{name}"
        );
        for time in &times {
            assert!(
                t.iter().any(|row| row.to_bits() == time.to_bits()),
                "{name}: no row at the frame's time {time}"
            );
        }
        let pixels = &result["pixels"];
        let total = num(&pixels["total"]);
        assert!(total >= 100_000.0, "{name}: {pixels}");
        assert!(
            num(&pixels["drawn"]) > 0.02 * total,
            "{name} blank: {pixels}"
        );
        assert!(num(&pixels["colours"]) > 50.0, "{name} blank: {pixels}");
    }
}

/// The columns `names` of `table`.
fn columns<const N: usize>(
    table: &(Vec<String>, Vec<Vec<f64>>),
    names: [&str; N],
) -> [Vec<f64>; N] {
    names.map(|name| column(&table.0, &table.1, name))
}

/// The rows of `t` at the frames' `times`.
fn frame_rows(t: &[f64], times: &[f64]) -> Vec<usize> {
    (times.iter())
        .map(|time| {
            (t.iter().position(|row| row.to_bits() == time.to_bits()))
                .unwrap_or_else(|| panic!("a row at the frame's time {time}"))
        })
        .collect()
}

/// The paper's wheel radii, rear and front.
const RADII: [(&str, &str, f64); 2] = [
    ("rear_wheel_body", "rear_rolling", 0.3),
    ("front_wheel_body", "front_rolling", 0.35),
];

/// The rear wheel's centre in the page's world from the paper's
/// coordinates: the rear contact `(x_p, y_p, 0)` plus `rR` along the lean
/// frame's upward axis `-(sin psi sin phi, -cos psi sin phi, cos phi)`
/// (z down), then turned by pi about x.
fn rear_centre(x_p: f64, y_p: f64, psi: f64, phi: f64) -> [f64; 3] {
    let r = 0.3;
    let centre = [
        x_p - r * psi.sin() * phi.sin(),
        y_p + r * psi.cos() * phi.sin(),
        -r * phi.cos(),
    ];
    [centre[0], -centre[1], -centre[2]]
}

/// The unit quaternion `[x, y, z, w]` as nalgebra's.
fn rotation(quaternion: [f64; 4]) -> UnitQuaternion<f64> {
    let [i, j, k, w] = quaternion;
    UnitQuaternion::from_quaternion([i, j, k, w].into())
}

/// The lowest point of a disc of `radius` at `centre` whose axle is the
/// local y axis turned by `quaternion`: the centre plus the radius along
/// world down (`-z`) made perpendicular to the axle.
fn lowest_point(centre: [f64; 3], quaternion: [f64; 4], radius: f64) -> [f64; 3] {
    let axle = rotation(quaternion) * Vector3::y();
    let down = -Vector3::z();
    let below = (down - axle * axle.dot(&down)).normalize();
    (Vector3::from(centre) + radius * below).into()
}

#[test]
fn the_falling_bicycle_s_wheels_roll_on_the_ground_in_the_page() {
    let (run, result) = runs().get("bicycle");
    let Some(result) = result else {
        return;
    };
    assert!(result["note"].as_str().unwrap().contains("(x, -y, -z)"));
    let (header, rows) = &run.table;
    let t = column(header, rows, "t");
    let times = nums(&result["times"]);
    let frames = frame_rows(&t, &times);
    // rows 1 ms apart: every 17th for 60 frames per second, and the last
    assert_eq!(&frames[..3], &[0, 17, 34]);
    assert_eq!(frames.last(), Some(&(t.len() - 1)));

    let items = result["items"].as_array().unwrap();
    let names: Vec<&str> = items.iter().map(|i| i["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "rear_wheel_body",
            "rear_body",
            "front_body",
            "front_wheel_body",
            "rear_frame_tube",
            "fork_tube"
        ]
    );
    let traces = result["traces"].as_array().unwrap();
    let mut worst = [0.0f64; 3];
    for (wheel, contact, radius) in RADII {
        let item = items.iter().find(|item| item["name"] == wheel).unwrap();
        assert_eq!(item["shape"], "disc");
        assert!((num(&item["radius"]) - radius).abs() < 1e-15, "{item}");
        let trace = traces
            .iter()
            .find(|trace| trace["name"] == contact)
            .unwrap();
        let points = nums(&trace["points"]);
        let poses = result["poses"][wheel].as_array().unwrap();
        assert_eq!(poses.len(), times.len());
        for (i, pose) in poses.iter().enumerate() {
            let (centre, quaternion) = pose_of(pose);
            let lowest = lowest_point(centre, quaternion, radius);
            let on_ground = lowest[2].abs();
            let off_trace = distance(&lowest, &points[3 * i..3 * i + 3]);
            assert!(on_ground <= 1e-9, "{wheel} at frame {i}: z = {}", lowest[2]);
            assert!(
                off_trace <= 1e-9,
                "{wheel} at frame {i}: {off_trace} from its contact"
            );
            worst[0] = worst[0].max(on_ground);
            worst[1] = worst[1].max(off_trace);
        }
    }
    let [x_p, y_p, psi, phi] = columns(&run.table, ["x_p", "y_p", "psi", "phi"]);
    let rear = result["poses"]["rear_wheel_body"].as_array().unwrap();
    for (i, (&row, pose)) in frames.iter().zip(rear).enumerate() {
        let (centre, _) = pose_of(pose);
        let expected = rear_centre(x_p[row], y_p[row], psi[row], phi[row]);
        let error = distance(&centre, &expected);
        assert!(
            error <= 1e-9,
            "the rear wheel's centre at frame {i}: {centre:?}, {expected:?}"
        );
        worst[2] = worst[2].max(error);
    }
    // it rolled some 6 m, weaving, and fell
    let last = *frames.last().unwrap();
    assert!(
        x_p[last] > 5.0 && phi[last].abs() >= 1.2,
        "{} {}",
        x_p[last],
        phi[last]
    );
    eprintln!(
        "worst: lowest point's height {:.1e}, from its contact {:.1e}, rear centre {:.1e}",
        worst[0], worst[1], worst[2]
    );
    screenshot(&run.page, 0.9 * t[last], "bicycle-fall", &run.directory);
}

/// The angle `a` in `(-pi, pi]` plus a whole number of turns nearest `b`,
/// minus `b`.
fn angle_difference(a: f64, b: f64) -> f64 {
    let d = a - b;
    d - 2.0 * PI * (d / (2.0 * PI)).round()
}

/// The heading of a turn about z alone, after checking it is one.
fn heading_of(quaternion: [f64; 4], what: &str) -> f64 {
    let [i, j, k, w] = quaternion;
    assert!(i.abs() < 1e-15 && j.abs() < 1e-15, "{what}: {quaternion:?}");
    2.0 * k.atan2(w)
}

/// `v` turned by the unit quaternion `[i, j, k, w]`.
fn turned_by(quaternion: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let [i, j, k, w] = quaternion;
    let u = [i, j, k];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let t = cross(u, v).map(|c| 2.0 * c);
    let ut = cross(u, t);
    [0, 1, 2].map(|a| v[a] + w * t[a] + ut[a])
}

#[test]
fn the_snakeboard_s_gait_turns_its_board_by_theta_in_the_page() {
    let (run, result) = runs().get("snakeboard-gait");
    let [t, x, y, theta, psi, phi] = columns(&run.table, ["t", "x", "y", "theta", "psi", "phi"]);
    // one period of 2000 steps, from rest to x = -0.807
    assert_eq!(t.len(), 2001);
    assert!((x[2000] + 0.807).abs() < 1e-3, "{}", x[2000]);
    let Some(result) = result else {
        return;
    };
    let frames = frame_rows(&t, &nums(&result["times"]));
    let board = result["poses"]["board"].as_array().unwrap();
    let axle = result["poses"]["front_axle"].as_array().unwrap();
    let rotor = result["poses"]["torso"].as_array().unwrap();
    let wheel = result["poses"]["front_right_wheel"].as_array().unwrap();
    let items = result["items"].as_array().unwrap();
    let radius = num(&items
        .iter()
        .find(|i| i["name"] == "front_right_wheel")
        .unwrap()["radius"]);
    let length = items.iter().find(|i| i["name"] == "front_axle").unwrap();
    assert!((num(&length["length"]) - 0.4).abs() < 1e-15, "{length}");
    let mut worst = [0.0f64; 4];
    for (i, &row) in frames.iter().enumerate() {
        let (position, quaternion) = pose_of(&board[i]);
        let heading = angle_difference(heading_of(quaternion, "board"), theta[row]);
        let off = distance(&position, &[x[row], y[row], 0.18]);
        assert!(heading.abs() <= 1e-9, "the board at frame {i}: {heading}");
        assert!(off <= 1e-9, "the board at frame {i}: {position:?}");
        // the front axle, from its first end to its second, points to the
        // left of the direction theta + phi the wheels roll in, r ahead
        let (position, quaternion) = pose_of(&axle[i]);
        let across = theta[row] + phi[row] + PI / 2.0;
        let turned = angle_difference(heading_of(quaternion, "front_axle"), across);
        let ahead = [
            x[row] + SNAKEBOARD_R * theta[row].cos(),
            y[row] + SNAKEBOARD_R * theta[row].sin(),
            0.08,
        ];
        let axle_off = distance(&position, &ahead);
        assert!(
            turned.abs() <= 1e-9,
            "the front axle at frame {i}: {turned}"
        );
        assert!(
            axle_off <= 1e-9,
            "the front axle at frame {i}: {position:?}"
        );
        // the front right wheel, a disc on the ground at the axle's end
        let (position, _) = pose_of(&wheel[i]);
        let steered = theta[row] + phi[row];
        let end = [
            ahead[0] + 0.2 * steered.sin(),
            ahead[1] - 0.2 * steered.cos(),
            radius,
        ];
        assert!(distance(&position, &end) <= 1e-9, "the wheel: {position:?}");
        assert!(
            (ahead[2] - radius).abs() <= 1e-15,
            "the axle at the wheels' centres"
        );
        // the rotor, a disc on a vertical axle above the board, its spoke
        // (local x) along theta + psi
        let (position, quaternion) = pose_of(&rotor[i]);
        let [spoke, up] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].map(|v| turned_by(quaternion, v));
        let spun = angle_difference(spoke[1].atan2(spoke[0]), theta[row] + psi[row]);
        assert!(spun.abs() <= 1e-9, "the rotor at frame {i}: {spun}");
        assert!(
            distance(&up, &[0.0, 0.0, 1.0]) <= 1e-9,
            "the rotor's axle: {up:?}"
        );
        assert!(
            distance(&position, &[x[row], y[row], 0.5]) <= 1e-9,
            "{position:?}"
        );
        for (worst, error) in worst.iter_mut().zip([heading, off, turned, axle_off]) {
            *worst = worst.max(error.abs());
        }
    }
    eprintln!(
        "worst: board heading {:.1e}, centre {:.1e}; front axle {:.1e}, {:.1e}",
        worst[0], worst[1], worst[2], worst[3]
    );
    screenshot(&run.page, 0.8 * t[2000], "snakeboard-gait", &run.directory);
}

#[test]
fn the_rolling_disk_s_disc_turns_and_rolls_with_its_coordinates_in_the_page() {
    let (run, result) = runs().get("rolling-disk");
    let Some(result) = result else {
        return;
    };
    let [t, x, y, theta, phi] = columns(&run.table, ["t", "x", "y", "theta", "phi"]);
    let frames = frame_rows(&t, &nums(&result["times"]));
    let disk = result["poses"]["disk"].as_array().unwrap();
    let r = 0.5;
    for (i, &row) in frames.iter().enumerate() {
        let (position, quaternion) = pose_of(&disk[i]);
        let expected = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), theta[row])
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), phi[row]);
        let angle = rotation(quaternion).angle_to(&expected);
        assert!(angle <= 1e-9, "the disk at frame {i}: {angle}");
        let off = distance(&position, &[x[row], y[row], r]);
        assert!(off <= 1e-9, "the disk at frame {i}: {position:?}");
    }
    // it rolled: its spin and heading changed
    let last = *frames.last().unwrap();
    assert!(phi[last].abs() > 0.1 && theta[last].abs() > 0.1);
}

/// The item named `name` of a probe's result.
fn item<'a>(result: &'a Value, name: &str) -> &'a Value {
    (result["items"].as_array().unwrap().iter())
        .find(|item| item["name"] == name)
        .unwrap_or_else(|| panic!("an item `{name}`"))
}

#[test]
fn the_chaplygin_ball_s_sphere_rolls_on_the_ground_turned_by_its_euler_parameters() {
    let (run, result) = runs().get("chaplygin-ball");
    let Some(result) = result else {
        return;
    };
    let [t, x, y, e0, e1, e2, e3] = columns(&run.table, ["t", "x", "y", "e0", "e1", "e2", "e3"]);
    let frames = frame_rows(&t, &nums(&result["times"]));
    let shell = item(result, "shell");
    assert_eq!(shell["shape"], "sphere");
    // the model's r
    let radius = num(&shell["radius"]);
    assert!((radius - 0.5).abs() < 1e-12, "{shell}");
    let poses = result["poses"]["shell"].as_array().unwrap();
    let mut worst = [0.0f64; 3];
    for (i, &row) in frames.iter().enumerate() {
        let (centre, quaternion) = pose_of(&poses[i]);
        let lowest = centre[2] - radius;
        assert!(lowest.abs() <= 1e-9, "the ball at frame {i}: z = {lowest}");
        let off = distance(&centre[..2], &[x[row], y[row]]);
        assert!(off <= 1e-9, "the ball at frame {i}: {centre:?}");
        // the frame `ball` is turned by the quaternion e0 + e1 i + e2 j + e3 k
        let norm = [e0[row], e1[row], e2[row], e3[row]]
            .iter()
            .map(|e| e * e)
            .sum::<f64>();
        let turned = rotation([e1[row], e2[row], e3[row], e0[row]].map(|e| e / norm.sqrt()));
        let angle = rotation(quaternion).angle_to(&turned);
        assert!(angle <= 1e-9, "the ball at frame {i}: {angle} rad off");
        for (worst, error) in worst.iter_mut().zip([lowest, off, angle]) {
            *worst = worst.max(error.abs());
        }
    }
    // it turned, and rolled
    let (first, last) = (pose_of(&poses[0]), pose_of(poses.last().unwrap()));
    let turn = rotation(first.1).angle_to(&rotation(last.1));
    assert!(turn > 1.0, "the ball turned by {turn} rad");
    assert!(distance(&first.0, &last.0) > 0.5, "{first:?} {last:?}");
    eprintln!(
        "worst: lowest point's height {:.1e}, centre {:.1e}, turn {:.1e}",
        worst[0], worst[1], worst[2]
    );
    screenshot(
        &run.page,
        0.9 * t[t.len() - 1],
        "chaplygin-ball",
        &run.directory,
    );
}

/// The Ackermann car's wheelbase `l`, half track `b` and wheel radius `r`.
const CAR_SIZES: (f64, f64, f64) = (1.0, 0.4, 0.15);

/// The car's contact points with its rear axle's middle at `(x, y)`,
/// heading `theta`: `b` to either side of the rear axle's middle and of the
/// front one's, `l` ahead, on the ground.
fn car_contacts(x: f64, y: f64, theta: f64) -> [[f64; 3]; 4] {
    let (l, b, _) = CAR_SIZES;
    let (s, c) = theta.sin_cos();
    [(0.0, b), (0.0, -b), (l, b), (l, -b)]
        .map(|(ahead, left)| [x + ahead * c - left * s, y + ahead * s + left * c, 0.0])
}

#[test]
fn the_ackermann_car_s_chassis_spans_its_wheels_contacts_in_the_page() {
    let (run, result) = runs().get("ackermann-car");
    let Some(result) = result else {
        return;
    };
    let [t, x, y, theta] = columns(&run.table, ["t", "x", "y", "theta"]);
    let frames = frame_rows(&t, &nums(&result["times"]));
    let chassis = item(result, "chassis");
    assert_eq!(chassis["shape"], "box");
    let size = nums(&chassis["size"]);
    let thickness = num(&item(result, "rear_left")["thickness"]);
    let poses = result["poses"]["chassis"].as_array().unwrap();
    let mut worst = 0.0f64;
    for (i, &row) in frames.iter().enumerate() {
        let (centre, quaternion) = pose_of(&poses[i]);
        // at the rear axle's height, r
        assert!((centre[2] - CAR_SIZES.2).abs() <= 1e-9, "{centre:?}");
        let to_box = rotation(quaternion).inverse();
        let local = car_contacts(x[row], y[row], theta[row])
            .map(|p| to_box * (Vector3::from(p) - Vector3::from(centre)));
        // the box's sides along its local x and y are the contacts' extremes
        for k in 0..2 {
            let low = local.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let high = local.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            let off = (low + size[k] / 2.0)
                .abs()
                .max((high - size[k] / 2.0).abs());
            assert!(
                off <= thickness,
                "frame {i}, axis {k}: the contacts from {low} to {high}, the box {}",
                size[k]
            );
            worst = worst.max(off);
        }
    }
    eprintln!("worst: the chassis's sides from its contacts' extremes {worst:.1e}");
    // it drove round: its heading turned
    assert!(theta[t.len() - 1].abs() > 0.5, "{}", theta[t.len() - 1]);
    screenshot(
        &run.page,
        0.9 * t[t.len() - 1],
        "ackermann-car",
        &run.directory,
    );
}

#[test]
fn a_model_with_nothing_to_draw_is_not_animated() {
    let directory = scratch("animation-refused");
    let model = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/sleigh_no_symmetry.model"
    );
    let output = chaplygin(&[
        "simulate",
        model,
        "--t-end",
        "0.1",
        "--animate",
        "--out",
        directory.path().to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    let expected = format!("error: `{model}` has nothing to draw");
    assert!(stderr.starts_with(&expected), "{stderr}");
    assert!(!directory.path().join("trajectory.csv").exists());
}

#[test]
fn a_model_file_s_bad_drawing_items_are_reported_at_their_tokens() {
    let directory = scratch("animation-bad-drawing");
    let file = directory.path().join("sleigh.model");
    let text = include_str!("../../models/sleigh.model")
        .replace("heading = theta,\n", "heading = theta, colour = 1,\n")
        .replace("mass_center = sphere", "sled = sphere");
    std::fs::write(&file, &text).unwrap();
    let output = chaplygin(&["simulate", file.to_str().unwrap(), "--animate"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    let at = |token: &str, message: &str| {
        let (line, text) = (text.lines().enumerate())
            .find(|(_, line)| line.contains(token))
            .unwrap_or_else(|| panic!("`{token}` in the model"));
        let column = text.find(token).unwrap() + 1;
        format!("{}:{}:{column}: error: {message}", file.display(), line + 1)
    };
    for expected in [
        at("colour", "unknown keyword argument `colour` of `box`"),
        at("sled = sphere", "`sled` is declared twice in this section"),
    ] {
        assert!(stderr.contains(&expected), "{expected}\nin\n{stderr}");
    }
    assert!(!directory.path().join("animation.html").exists());
}
