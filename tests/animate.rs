//! `chaplygin::animate`'s page opened in headless Chromium: a disc rolling
//! without slipping on a circle, its axle, a box sliding and turning, a
//! ball, and the trace of the disc's contact point, every pose from closed
//! forms. A copy of the page with a probe script records console errors,
//! failed or blocked loads and resource requests, evaluates
//! `window.chaplygin.pose` at every frame's time and between frames, and
//! reads the canvas's pixels; the test checks them against the closed
//! forms and against docs/INTERFACE.md section 10.
//!
//! Chromium runs the page as `support::browser` says (skipped without it
//! unless `CHAPLYGIN_BROWSER_TESTS=require`).

use crate::support::browser::{
    chromium, distance, dump_dom, num, nums, pose_of, probe_result, probed,
};
use crate::support::scratch;
use chaplygin::animate::{Item, Label, Pose, Scene, Shape, Trace, page};
use chaplygin::runtime::nalgebra::{UnitQuaternion, Vector3};
use serde_json::Value;
use std::f64::consts::PI;

/// The disc's radius, the radius of the circle its contact point runs on,
/// the rate its heading turns at, and the frames: 30 per second for 4 s.
const R_DISC: f64 = 0.3;
const R_CIRCLE: f64 = 1.5;
const TURN_RATE: f64 = PI / 2.0;
const FPS: f64 = 30.0;
const FRAMES: usize = 121;
/// The disc's spin about its axle, rolling without slipping: the centre
/// moves at `R_CIRCLE * TURN_RATE` along the circle, so the disc turns
/// about its axle at that speed over its radius.
const SPIN_RATE: f64 = -R_CIRCLE * TURN_RATE / R_DISC;
/// The box: its size, its heading's rate, its velocity.
const BOARD: [f64; 3] = [0.8, 0.3, 0.1];
const BOARD_TURN_RATE: f64 = 1.0;
const BOARD_VELOCITY: [f64; 2] = [0.25, -0.1];

/// The rotation about z by `a` followed by the rotation about y by `b` in
/// the body: `q_z(a) q_y(b)`, multiplied out by hand.
fn yaw_spin(a: f64, b: f64) -> [f64; 4] {
    let (s1, c1) = (a / 2.0).sin_cos();
    let (s2, c2) = (b / 2.0).sin_cos();
    [-s1 * s2, c1 * s2, s1 * c2, c1 * c2]
}

fn yaw(a: f64) -> [f64; 4] {
    let (s, c) = (a / 2.0).sin_cos();
    [0.0, 0.0, s, c]
}

/// The disc at time t: its centre above the circle, its axle (local y)
/// pointing away from the circle's centre, rotated by the spin about it.
/// The heading is `psi = TURN_RATE t`; the axle is radial, so the yaw of
/// the local frame is `psi - pi/2`.
fn disc(t: f64) -> Pose {
    let psi = TURN_RATE * t;
    Pose {
        position: [R_CIRCLE * psi.cos(), R_CIRCLE * psi.sin(), R_DISC],
        quaternion: yaw_spin(psi - PI / 2.0, SPIN_RATE * t),
    }
}

/// The disc's axle as a segment along its local x: radial, at the centre.
fn axle(t: f64) -> Pose {
    Pose {
        position: disc(t).position,
        quaternion: yaw(TURN_RATE * t),
    }
}

fn board(t: f64) -> Pose {
    Pose {
        position: [
            -0.5 + BOARD_VELOCITY[0] * t,
            0.8 + BOARD_VELOCITY[1] * t,
            BOARD[2] / 2.0,
        ],
        quaternion: yaw(0.3 + BOARD_TURN_RATE * t),
    }
}

fn ball(_t: f64) -> Pose {
    Pose::at([0.0, 0.0, 0.2])
}

fn contact(t: f64) -> [f64; 3] {
    let psi = TURN_RATE * t;
    [R_CIRCLE * psi.cos(), R_CIRCLE * psi.sin(), 0.0]
}

type Motion = fn(f64) -> Pose;

fn motions() -> [(&'static str, Shape, Motion); 4] {
    [
        (
            "wheel",
            Shape::Disc {
                radius: R_DISC,
                thickness: 0.04,
            },
            disc,
        ),
        ("axle", Shape::Segment { length: 0.3 }, axle),
        ("board", Shape::Box { size: BOARD }, board),
        ("ball", Shape::Sphere { radius: 0.2 }, ball),
    ]
}

fn times() -> Vec<f64> {
    (0..FRAMES).map(|k| k as f64 / FPS).collect()
}

fn scene() -> Scene {
    let times = times();
    Scene {
        title: "A disc rolling on a circle".into(),
        note: Some("closed-form motion; z up".into()),
        items: (motions().into_iter())
            .map(|(name, shape, motion)| Item {
                name: name.into(),
                shape,
                poses: times.iter().map(|&t| motion(t)).collect(),
            })
            .collect(),
        labels: vec![
            Label {
                name: "psi".into(),
                values: times.iter().map(|t| TURN_RATE * t).collect(),
            },
            Label {
                name: "phi".into(),
                values: times.iter().map(|t| SPIN_RATE * t).collect(),
            },
        ],
        traces: vec![Trace {
            name: "contact".into(),
            points: times.iter().map(|&t| contact(t)).collect(),
        }],
        times,
    }
}

/// The probe's measurements (`measure()` and its helpers), run after
/// `load` between the shared start and end of `support::browser::probed`,
/// which record the errors and write the findings as JSON.
const PROBE: &str = r#"  function pixels(canvas) {
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext('2d');
    context.drawImage(canvas, 0, 0);
    return context.getImageData(0, 0, copy.width, copy.height).data;
  }

  async function measure() {
    const c = window.chaplygin;
    await c.ready;
    const canvas = document.querySelector('#view canvas');
    const data = JSON.parse(document.getElementById('chaplygin-data').textContent);
    const result = { errors };
    result.duration = c.duration;
    result.times = Array.from(c.times);
    result.timesIsFloat64Array = c.times instanceof Float64Array;
    result.items = c.items;
    result.frames = {};
    result.midpoints = {};
    result.clamped = {};
    result.exactMismatches = [];
    for (const [k, item] of data.items.entries()) {
      const name = item.name;
      result.frames[name] = [];
      result.midpoints[name] = [];
      c.times.forEach((t, i) => {
        const p = c.pose(name, t);
        result.frames[name].push(p);
        const expected = item.position.slice(3 * i, 3 * i + 3).concat(item.quaternion.slice(4 * i, 4 * i + 4));
        const found = p.position.concat(p.quaternion);
        if (found.length !== 7 || found.some((x, j) => !Object.is(x, expected[j]))) result.exactMismatches.push([name, i]);
        if (i + 1 < c.times.length) result.midpoints[name].push(c.pose(name, (t + c.times[i + 1]) / 2));
      });
      result.clamped[name] = [c.pose(name, c.times[0] - 1), c.pose(name, c.times[c.times.length - 1] + 1)];
    }
    try { c.pose('no such item', 0); result.unknownItem = 'no error'; } catch (e) { result.unknownItem = e.message; }

    result.canvas = { width: canvas.width, height: canvas.height };
    const first = pixels(canvas);
    c.seek(c.times[Math.floor(c.times.length / 2)]);
    const middle = pixels(canvas);
    const background = [middle[0], middle[1], middle[2]];
    let drawn = 0;
    let changed = 0;
    const colours = new Set();
    for (let i = 0; i < middle.length; i += 4) {
      if (Math.abs(middle[i] - background[0]) + Math.abs(middle[i + 1] - background[1]) + Math.abs(middle[i + 2] - background[2]) > 24) drawn++;
      if (middle[i] !== first[i] || middle[i + 1] !== first[i + 1] || middle[i + 2] !== first[i + 2]) changed++;
      colours.add((middle[i] << 16) | (middle[i + 1] << 8) | middle[i + 2]);
    }
    result.pixels = { total: middle.length / 4, background, drawn, changed, colours: colours.size };

    c.play();
    await new Promise((resolve) => setTimeout(resolve, 500));
    c.pause();

    // the keys: arrows step one frame (the slider follows, its value rounded
    // by Chromium to 15 digits), space plays and pauses
    const press = (key) => window.dispatchEvent(new KeyboardEvent('keydown', { key, bubbles: true, cancelable: true }));
    const slider = document.getElementById('time');
    const button = document.getElementById('play');
    const at = (t) => Math.abs(Number(slider.value) - t) < 1e-9;
    c.seek(c.times[0]);
    press('ArrowRight');
    press('ArrowRight');
    result.keys = { twoRight: at(c.times[2]) };
    press('ArrowLeft');
    result.keys.oneLeft = at(c.times[1]);
    press(' ');
    result.keys.spacePlays = button.textContent;
    press(' ');
    result.keys.spacePauses = button.textContent;
    result.clock = document.getElementById('clock').textContent;
    result.resources = performance.getEntriesByType('resource').map((entry) => entry.name);
    result.errors = errors;
    return result;
  }
"#;

/// The angle of the rotation between two unit quaternions.
fn angle_between(a: [f64; 4], b: [f64; 4]) -> f64 {
    let dot: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
    2.0 * dot.abs().min(1.0).acos()
}

#[test]
fn the_hand_multiplied_quaternion_is_nalgebra_s_product() {
    for (a, b) in [(0.0, 0.0), (0.7, -2.1), (-3.0, 5.5), (PI, PI / 3.0)] {
        let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), a)
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), b);
        let expected = [q.i, q.j, q.k, q.w];
        assert!(distance(&yaw_spin(a, b), &expected) < 1e-15, "{a} {b}");
        // the axle, local y, points along (cos(a + pi/2), sin(a + pi/2), 0)
        let axle = q * Vector3::y();
        assert!((axle - Vector3::new(-a.sin(), a.cos(), 0.0)).norm() < 1e-15);
    }
    // rolling without slipping: the contact point's velocity is zero
    let (t, h) = (1.234, 1e-6);
    let velocity = |f: fn(f64) -> Pose| {
        let (a, b) = (f(t - h), f(t + h));
        Vector3::from_fn(|i, _| (b.position[i] - a.position[i]) / (2.0 * h))
    };
    let (q0, q1) = (disc(t - h).quaternion, disc(t + h).quaternion);
    let rotation = |q: [f64; 4]| UnitQuaternion::from_quaternion([q[0], q[1], q[2], q[3]].into());
    let omega = (rotation(q1) * rotation(q0).inverse()).scaled_axis() / (2.0 * h);
    let contact_velocity = velocity(disc) + omega.cross(&Vector3::new(0.0, 0.0, -R_DISC));
    assert!(contact_velocity.norm() < 1e-7, "{contact_velocity}");
}

#[test]
fn the_page_runs_in_headless_chromium() {
    let Some(chromium) = chromium() else {
        return;
    };
    let scene = scene();
    let html = page(&scene).unwrap();
    let directory = scratch("animate");
    std::fs::write(directory.path().join("animation.html"), &html).unwrap();
    let copy = directory.path().join("probed.html");
    std::fs::write(&copy, probed(&html, PROBE)).unwrap();

    let dom = dump_dom(&chromium, &copy, &directory.path().join("profile"));
    let result = probe_result(&dom);

    assert_eq!(result["errors"], Value::Array(vec![]), "errors in the page");
    assert_eq!(
        result["resources"],
        Value::Array(vec![]),
        "the page requested resources"
    );

    // duration, times, items as given
    let times = times();
    assert_eq!(num(&result["duration"]), times[FRAMES - 1] - times[0]);
    assert_eq!(result["timesIsFloat64Array"], true);
    let found_times = nums(&result["times"]);
    assert_eq!(found_times.len(), FRAMES);
    for (found, expected) in found_times.iter().zip(&times) {
        assert_eq!(found.to_bits(), expected.to_bits());
    }
    let items = result["items"].as_array().unwrap();
    assert_eq!(items.len(), 4);
    for (item, (name, shape, _)) in items.iter().zip(motions()) {
        assert_eq!(item["name"], name);
        assert_eq!(item["shape"], shape.kind());
        let keys: Vec<&str> = item
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        match shape {
            Shape::Disc { radius, thickness } => {
                assert_eq!(
                    (num(&item["radius"]), num(&item["thickness"])),
                    (radius, thickness)
                );
                assert_eq!(keys.len(), 4);
            }
            Shape::Box { size } => {
                assert_eq!(nums(&item["size"]), size);
                assert_eq!(keys.len(), 3);
            }
            Shape::Sphere { radius } => {
                assert_eq!(num(&item["radius"]), radius);
                assert_eq!(keys.len(), 3);
            }
            Shape::Segment { length } => {
                assert_eq!(num(&item["length"]), length);
                assert_eq!(keys.len(), 3);
            }
        }
    }
    assert_eq!(
        result["unknownItem"],
        "chaplygin.pose: no item named \"no such item\""
    );

    // At a frame's time: the embedded numbers themselves, which are the
    // closed forms.
    let mismatches = result["exactMismatches"].as_array().unwrap();
    assert!(
        mismatches.is_empty(),
        "{} poses at frames' times are not the embedded numbers, the first ones (item, frame): {:?}",
        mismatches.len(),
        &mismatches[..mismatches.len().min(5)]
    );
    let h = 1.0 / FPS;
    for (name, _, motion) in motions() {
        let frames = result["frames"][name].as_array().unwrap();
        assert_eq!(frames.len(), FRAMES);
        for (i, frame) in frames.iter().enumerate() {
            let (position, quaternion) = pose_of(frame);
            let expected = motion(times[i]);
            assert!(
                distance(&position, &expected.position) <= 1e-12,
                "{name} at frame {i}: {position:?}"
            );
            assert!(
                distance(&quaternion, &expected.quaternion) <= 1e-12,
                "{name} at frame {i}: {quaternion:?}"
            );
            assert_eq!(
                position.map(f64::to_bits),
                expected.position.map(f64::to_bits),
                "{name} at frame {i}"
            );
            assert_eq!(
                quaternion.map(f64::to_bits),
                expected.quaternion.map(f64::to_bits),
                "{name} at frame {i}"
            );
        }
        let clamped = result["clamped"][name].as_array().unwrap();
        assert_eq!(
            pose_of(&clamped[0]),
            pose_of(&frames[0]),
            "{name} before the first frame"
        );
        assert_eq!(
            pose_of(&clamped[1]),
            pose_of(&frames[FRAMES - 1]),
            "{name} after the last frame"
        );
    }

    // Between frames, the interpolation's error from the closed form. The
    // box and the axle move along straight lines or stand still and turn
    // about a fixed axis at a constant rate: linear interpolation of the
    // position and spherical interpolation of the quaternion are exact.
    for name in ["board", "axle", "ball"] {
        let (_, _, motion) = motions().into_iter().find(|m| m.0 == name).unwrap();
        for (i, midpoint) in result["midpoints"][name]
            .as_array()
            .unwrap()
            .iter()
            .enumerate()
        {
            let (position, quaternion) = pose_of(midpoint);
            let expected = motion(times[i] + h / 2.0);
            if name != "axle" {
                assert!(
                    distance(&position, &expected.position) <= 1e-12,
                    "{name} between frames {i} and {}",
                    i + 1
                );
            }
            assert!(
                distance(&quaternion, &expected.quaternion) <= 1e-12,
                "{name} between frames {i} and {}",
                i + 1
            );
        }
    }
    // The disc's centre (and the axle's) runs on a circle: halfway between
    // frames the chord's midpoint is R (1 - cos(turn / 2)) inside the arc.
    // Its orientation q_z(psi) q_y(phi) turns at the angular velocity
    // w = psi' e_z + phi' e_axle, whose rate of change has the norm
    // psi' phi' (e_axle turns at psi' about e_z): halfway, the geodesic
    // between the frames' orientations misses the true one by
    // (h^2 / 8) psi' phi' to second order in the step h.
    let chord = R_CIRCLE * (1.0 - (TURN_RATE * h / 2.0).cos());
    let slerp_bound = h * h / 8.0 * (TURN_RATE * SPIN_RATE).abs();
    let (mut worst_position, mut worst_angle) = (0.0f64, 0.0f64);
    for name in ["wheel", "axle"] {
        let (_, _, motion) = motions().into_iter().find(|m| m.0 == name).unwrap();
        for (i, midpoint) in result["midpoints"][name]
            .as_array()
            .unwrap()
            .iter()
            .enumerate()
        {
            let (position, quaternion) = pose_of(midpoint);
            let expected = motion(times[i] + h / 2.0);
            let error = distance(&position, &expected.position);
            assert!(
                (error - chord).abs() <= 1e-12,
                "{name} between frames {i} and {}: {error} from the arc",
                i + 1
            );
            let norm = distance(&quaternion, &[0.0; 4]);
            assert!(
                (norm - 1.0).abs() < 1e-15,
                "{name}: the interpolated quaternion's norm {norm}"
            );
            let angle = angle_between(quaternion, expected.quaternion);
            assert!(
                angle <= 1.05 * slerp_bound + 1e-12,
                "{name} between frames {i} and {}: {angle} rad off",
                i + 1
            );
            worst_position = worst_position.max(error);
            worst_angle = worst_angle.max(angle);
        }
    }
    eprintln!(
        "between frames: {worst_position:.3e} m (chord {chord:.3e}), {worst_angle:.3e} rad (bound {slerp_bound:.3e})"
    );

    // the canvas: drawn, and different at another time
    let pixels = &result["pixels"];
    let total = num(&pixels["total"]);
    assert!(total >= 100_000.0, "a canvas of {total} pixels: {pixels}");
    assert!(
        num(&pixels["drawn"]) > 0.02 * total,
        "the canvas looks blank: {pixels}"
    );
    assert!(
        num(&pixels["colours"]) > 50.0,
        "the canvas looks blank: {pixels}"
    );
    assert!(
        num(&pixels["changed"]) > 0.001 * total,
        "the picture did not change with the time: {pixels}"
    );
    assert!(
        result["clock"].as_str().unwrap().starts_with("t = "),
        "{}",
        result["clock"]
    );
    let keys = &result["keys"];
    assert_eq!(
        (&keys["twoRight"], &keys["oneLeft"]),
        (&Value::Bool(true), &Value::Bool(true)),
        "{keys}"
    );
    assert_eq!(
        (&keys["spacePlays"], &keys["spacePauses"]),
        (&Value::from("Pause"), &Value::from("Play")),
        "{keys}"
    );
}
