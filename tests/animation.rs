//! `chaplygin simulate bicycle ... --animate` (docs/INTERFACE.md section
//! 10): the benchmark bicycle for a second at 3 m/s, below its weave speed,
//! pushed to lean (as `bicycle_falling` starts it), its `animation.html`
//! opened in headless Chromium with a probe that reads
//! `window.chaplygin.pose` of every item at every frame's time, the
//! embedded traces and the canvas's pixels. At every frame each wheel's
//! disc touches the ground (z = 0) at its contact point's trace, and the
//! rear wheel's centre is the one the paper's geometry gives from the
//! frame's row of `trajectory.csv` (the model's z axis points down: the
//! page shows it turned by pi about x). The page makes no request and logs
//! no error, and draws something. A model declared by its energy is
//! refused by name.

use crate::support::browser::{
    chromium, distance, dump_dom, num, nums, pose_of, probe_result, probed,
};
use crate::support::{chaplygin, column, read_csv, scratch};
use chaplygin::runtime::nalgebra::{UnitQuaternion, Vector3};
use serde_json::Value;
use std::path::PathBuf;

/// The paper's wheel radii, rear and front.
const RADII: [(&str, &str, f64); 2] = [
    ("rear_wheel_body", "rear_rolling", 0.3),
    ("front_wheel_body", "front_rolling", 0.35),
];

/// The probe's `measure()` (inside `support::browser::probed`'s start and
/// end, which record the errors): after `load` it writes
/// the items, the frames' times, every item's pose at every frame's time,
/// the embedded traces and note, the canvas's drawn pixels and the
/// resources requested as JSON into `<pre id="probe">`, every number as its
/// shortest round-trip string.
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

fn out(name: &str) -> PathBuf {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("animation-{name}"));
    let _ = std::fs::remove_dir_all(&out);
    out
}

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

/// The lowest point of a disc of `radius` at `centre` whose axle is the
/// local y axis turned by `quaternion`: the centre plus the radius along
/// world down (`-z`) made perpendicular to the axle.
fn lowest_point(centre: [f64; 3], quaternion: [f64; 4], radius: f64) -> [f64; 3] {
    let [i, j, k, w] = quaternion;
    let axle = UnitQuaternion::from_quaternion([i, j, k, w].into()) * Vector3::y();
    let down = -Vector3::z();
    let below = (down - axle * axle.dot(&down)).normalize();
    (Vector3::from(centre) + radius * below).into()
}

#[test]
fn the_falling_bicycle_s_wheels_roll_on_the_ground_in_the_page() {
    let directory = out("bicycle");
    let dir = directory.to_str().unwrap();
    let output = chaplygin(&[
        "simulate",
        "bicycle",
        "--initial",
        "dot(theta_r)=-10",
        "--initial",
        "dot(phi)=0.2",
        "--initial",
        "dot(delta)=0",
        "--fixed-step",
        "--dt",
        "0.001",
        "--t-end",
        "1",
        "--animate",
        "--out",
        dir,
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let page = directory.join("animation.html");
    let html = std::fs::read_to_string(&page).unwrap();
    let said = format!(
        "wrote {} ({} kB)",
        page.display(),
        html.len().div_ceil(1000)
    );
    assert!(stdout.contains(&said), "{said} in {stdout}");
    let (header, rows) = read_csv(&directory.join("trajectory.csv"));

    let Some(chromium) = chromium() else {
        return;
    };
    let copy = directory.join("probed.html");
    std::fs::write(&copy, probed(&html, PROBE)).unwrap();
    let result = probe_result(&dump_dom(&chromium, &copy, &scratch("animation")));
    assert_eq!(result["errors"], Value::Array(vec![]), "errors in the page");
    assert_eq!(result["resources"], Value::Array(vec![]), "requests");
    assert!(result["note"].as_str().unwrap().contains("(x, -y, -z)"));

    // The frames are rows of trajectory.csv, 1 ms apart: every 17th for
    // 60 frames per second, and the last.
    let t = column(&header, &rows, "t");
    let times = nums(&result["times"]);
    assert_eq!(times.len(), 60, "{times:?}");
    assert_eq!(times.last(), t.last());
    let frame_rows: Vec<usize> = (times.iter())
        .map(|time| {
            (t.iter().position(|row| row.to_bits() == time.to_bits()))
                .unwrap_or_else(|| panic!("a row at the frame's time {time}"))
        })
        .collect();
    assert_eq!(&frame_rows[..3], &[0, 17, 34]);

    let items = result["items"].as_array().unwrap();
    let names: Vec<&str> = items.iter().map(|i| i["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "rear_wheel_body",
            "rear_body",
            "front_body",
            "front_wheel_body"
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
    let coordinate = |name: &str| column(&header, &rows, name);
    let (x_p, y_p, psi, phi) = (
        coordinate("x_p"),
        coordinate("y_p"),
        coordinate("psi"),
        coordinate("phi"),
    );
    let rear = result["poses"]["rear_wheel_body"].as_array().unwrap();
    for (i, (&row, pose)) in frame_rows.iter().zip(rear).enumerate() {
        let (centre, _) = pose_of(pose);
        let expected = rear_centre(x_p[row], y_p[row], psi[row], phi[row]);
        let error = distance(&centre, &expected);
        assert!(
            error <= 1e-9,
            "the rear wheel's centre at frame {i}: {centre:?}, {expected:?}"
        );
        worst[2] = worst[2].max(error);
    }
    // it rolled some 3 m and turned to the right of its x axis (y_p > 0,
    // which the page shows at -y)
    let last = *frame_rows.last().unwrap();
    assert!(
        x_p[last] > 2.5 && y_p[last] > 0.2 && psi[last] > 0.2,
        "{}",
        x_p[last]
    );
    eprintln!(
        "worst: lowest point's height {:.1e}, from its contact {:.1e}, rear centre {:.1e}",
        worst[0], worst[1], worst[2]
    );

    let pixels = &result["pixels"];
    let total = num(&pixels["total"]);
    assert!(total >= 100_000.0, "{pixels}");
    assert!(num(&pixels["drawn"]) > 0.02 * total, "blank: {pixels}");
    assert!(num(&pixels["colours"]) > 50.0, "blank: {pixels}");
}

#[test]
fn a_model_declared_by_its_energy_is_not_animated() {
    let directory = out("snakeboard");
    let output = chaplygin(&[
        "simulate",
        "snakeboard",
        "--t-end",
        "0.1",
        "--animate",
        "--out",
        directory.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.starts_with("error: `snakeboard.model` declares no bodies"),
        "{stderr}"
    );
    assert!(!directory.join("trajectory.csv").exists());
}
