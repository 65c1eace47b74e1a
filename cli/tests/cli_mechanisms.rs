//! The command line on models declared as mechanisms: `list` offers them,
//! `derive` shows what the mechanism sections derived, a broken mechanism
//! file is reported at its `file:line:col`.

use crate::support::{chaplygin, read_csv, scratch};

#[test]
fn list_offers_the_mechanisms() {
    let output = chaplygin(&["list"]);
    assert!(output.status.success());
    let listing = String::from_utf8_lossy(&output.stdout).to_string();
    for name in ["rolling-disk-3d", "sleigh-bodies", "snakeboard-bodies"] {
        assert!(listing.contains(name), "{listing}");
    }
}

#[test]
fn derive_shows_the_derived_energies_and_contact_rows() {
    let output = chaplygin(&["derive", "sleigh-bodies"]);
    assert!(output.status.success());
    let text = String::from_utf8_lossy(&output.stdout).to_string();
    let section = text
        .split("Mechanism (frames, bodies, contacts)")
        .nth(1)
        .expect("a mechanism section");
    assert!(section.contains("frames: heading"), "{section}");
    assert!(section.contains("points: blade, center"), "{section}");
    // The blade's row, -sin(theta) dot(x) + cos(theta) dot(y) = 0.
    assert!(
        section.contains("blade: [-sin(theta), cos(theta), 0]"),
        "{section}"
    );
    assert!(section.contains("V of the bodies = 0"), "{section}");
    let energy_form = chaplygin(&["derive", "sleigh"]);
    let plain = String::from_utf8_lossy(&energy_form.stdout).to_string();
    assert!(!plain.contains("Mechanism ("), "{plain}");
}

#[test]
fn a_broken_mechanism_file_is_reported_at_its_token() {
    let directory = scratch("cli-mechanism-broken");
    let file = directory.path().join("disk.model");
    let text = include_str!("../../models/rolling_disk_3d.model")
        .replace("rotate(lean, y", "rotate(lean, w");
    std::fs::write(&file, &text).expect("write");
    let output = chaplygin(&["derive", file.to_str().expect("path")]);
    assert!(!output.status.success());
    let line = text
        .lines()
        .position(|l| l.contains("rotate(lean, w"))
        .expect("line")
        + 1;
    let column = text
        .lines()
        .nth(line - 1)
        .and_then(|l| l.find(", w"))
        .expect("column")
        + 3;
    let message = String::from_utf8_lossy(&output.stderr).to_string();
    let expected = format!(
        "{}:{line}:{column}: error: a frame turns about",
        file.display()
    );
    assert!(
        message.contains(&expected),
        "{message}\nexpected {expected}"
    );
}

/// Runs `simulate` into a scratch directory and returns the trajectory's
/// and the tracks' tables (`path.png` is drawn for a model with `x` and `y`).
fn simulate_tracks(name: &str, arguments: &[&str]) -> [(Vec<String>, Vec<Vec<f64>>); 2] {
    let out = scratch(&format!("cli-mechanism-{name}"));
    let mut all = vec!["simulate"];
    all.extend(arguments);
    all.extend(["--out", out.path().to_str().expect("path")]);
    let output = chaplygin(&all);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8_lossy(&output.stdout).to_string();
    assert!(stdout.contains("tracks.csv"), "{stdout}");
    let tables = [
        read_csv(&out.path().join("trajectory.csv")),
        read_csv(&out.path().join("tracks.csv")),
    ];
    let planar = ["x", "y"]
        .iter()
        .all(|c| tables[0].0.iter().any(|n| n == c));
    assert_eq!(
        out.path().join("path.png").exists(),
        planar,
        "the tracks go with the path plot"
    );
    tables
}

/// The value of `column` in `row` of a table.
fn value(table: &(Vec<String>, Vec<Vec<f64>>), row: usize, column: &str) -> f64 {
    let index = table
        .0
        .iter()
        .position(|c| c == column)
        .unwrap_or_else(|| panic!("no column {column} in {:?}", table.0));
    table.1[row][index]
}

/// Asserts that the tracks' columns of each point equal `expected(row)`
/// at every row, `t` included.
fn assert_tracks(
    [trajectory, tracks]: &[(Vec<String>, Vec<Vec<f64>>); 2],
    expected: &dyn Fn(usize) -> Vec<(&'static str, [f64; 3])>,
) {
    assert_eq!(trajectory.1.len(), tracks.1.len());
    assert!(tracks.1.len() > 10);
    for row in 0..tracks.1.len() {
        assert_eq!(value(trajectory, row, "t"), value(tracks, row, "t"));
        for (point, position) in expected(row) {
            for (axis, want) in ["x", "y", "z"].iter().zip(position) {
                let got = value(tracks, row, &format!("{point}.{axis}"));
                assert!(
                    (got - want).abs() < 1e-12,
                    "{point}.{axis} at row {row}: {got} != {want}"
                );
            }
        }
    }
}

#[test]
fn simulate_writes_the_leaning_disks_contact_and_centre_tracks() {
    let tables = simulate_tracks("disk-tracks", &["rolling-disk-3d", "--t-end", "1"]);
    let trajectory = &tables[0];
    // The contact is (x, y, 0); the centre is r along the leaned frame's z,
    // (x + r sin psi sin phi, y - r cos psi sin phi, r cos phi), r = 0.5.
    let r = 0.5;
    assert_tracks(&tables, &|row| {
        let at = |name| value(trajectory, row, name);
        let (x, y, psi, phi) = (at("x"), at("y"), at("psi"), at("phi"));
        vec![
            ("contact", [x, y, 0.0]),
            (
                "center",
                [
                    x + r * psi.sin() * phi.sin(),
                    y - r * psi.cos() * phi.sin(),
                    r * phi.cos(),
                ],
            ),
        ]
    });
}

#[test]
fn simulate_writes_the_caster_robots_wheel_contact_tracks() {
    let tables = simulate_tracks(
        "caster-tracks",
        &["caster-robot", "--t-end", "1", "--input", "u_left=1"],
    );
    let trajectory = &tables[0];
    // b = 0.2 half-track, l = 0.3 mount behind the axle, d = 0.04 trail:
    // the left contact is b to the left of (x, y), the caster's contact d
    // behind the mount along the swivel's heading theta + beta.
    let (b, l, d) = (0.2, 0.3, 0.04);
    assert_tracks(&tables, &|row| {
        let at = |name| value(trajectory, row, name);
        let (x, y, theta, beta) = (at("x"), at("y"), at("theta"), at("beta"));
        vec![
            (
                "left_contact",
                [x - b * theta.sin(), y + b * theta.cos(), 0.0],
            ),
            (
                "right_contact",
                [x + b * theta.sin(), y - b * theta.cos(), 0.0],
            ),
            (
                "caster_contact",
                [
                    x - l * theta.cos() - d * (theta + beta).cos(),
                    y - l * theta.sin() - d * (theta + beta).sin(),
                    0.0,
                ],
            ),
        ]
    });
    // The run turned: the tracks are not trivial.
    let last = tables[0].1.len() - 1;
    assert!(value(trajectory, last, "theta").abs() > 0.1);
}

/// The planar pendulum in Cartesian coordinates (`tests/models/planar_pendulum.model`).
const PENDULUM: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/planar_pendulum.model"
);

#[test]
fn simulate_solves_the_pendulums_height_from_its_length_constraint() {
    let [trajectory, tracks] = simulate_tracks(
        "pendulum-start",
        &[PENDULUM, "--initial", "x=0.6", "--t-end", "0.2"],
    );
    // x^2 + z^2 = l^2 = 1 with x = 0.6: z = 0.8 (Newton from the generic
    // start 0.5 above the singular height 0).
    assert_eq!(value(&trajectory, 0, "x"), 0.6);
    assert!((value(&trajectory, 0, "z") - 0.8).abs() < 1e-12);
    assert!((value(&tracks, 0, "bob.z") - 0.8).abs() < 1e-12);
}

#[test]
fn simulate_names_a_length_constraint_no_height_meets_with_its_residual() {
    for (initial, residual) in [
        // x = 2 beyond the length 1: x^2 + z^2 - 1 >= 3 for every z.
        (vec!["--initial", "x=2"], None),
        // Both given: the residual is 0.36 + 0.04 - 1 = -0.6, nothing left to solve.
        (
            vec!["--initial", "x=0.6", "--initial", "z=0.2"],
            Some("-6e-1"),
        ),
    ] {
        let out = scratch("cli-mechanism-pendulum-impossible");
        let mut arguments = vec!["simulate", PENDULUM];
        arguments.extend(&initial);
        arguments.extend(["--out", out.path().to_str().expect("path")]);
        let output = chaplygin(&arguments);
        assert!(!output.status.success());
        let message = String::from_utf8_lossy(&output.stderr).to_string();
        assert!(
            message.contains("configuration constraint `length` cannot be met"),
            "{message}"
        );
        match residual {
            Some(residual) => assert!(message.contains(residual), "{message}"),
            None => {
                // The closest Newton came is the minimum 3 (at z = 0), to a
                // few digits.
                let reached: f64 = message
                    .split("no closer than ")
                    .nth(1)
                    .and_then(|rest| rest.split_whitespace().next())
                    .and_then(|number| number.parse().ok())
                    .unwrap_or_else(|| panic!("a residual in {message}"));
                assert!((3.0..3.1).contains(&reached), "{message}");
            }
        }
        assert!(
            !out.path().join("trajectory.csv").exists(),
            "no trajectory is written"
        );
    }
}

/// `derive MODEL --format FORMAT`'s standard output.
fn derived(model: &str, format: &str) -> String {
    let output = chaplygin(&["derive", model, "--format", format]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).to_string()
}

/// The text format's mechanism lines `NAME: VALUE` under `heading`.
fn text_entries(text: &str, heading: &str) -> Vec<(String, String)> {
    text.lines()
        .skip_while(|line| !line.contains(heading))
        .skip(1)
        .take_while(|line| line.starts_with("    "))
        .filter(|line| line.trim() != "none")
        .map(|line| {
            let (name, value) = line.trim().split_once(": ").expect("NAME: VALUE");
            (name.to_string(), value.to_string())
        })
        .collect()
}

#[test]
fn derive_json_has_the_mechanism_object_with_the_texts_values() {
    for model in ["caster-robot", "rolling-disk-3d", PENDULUM] {
        let text = derived(model, "text");
        let json: serde_json::Value =
            serde_json::from_str(&derived(model, "json")).expect("the JSON parses");
        let mechanism = &json["mechanism"];
        let line_value = |label: &str| {
            text.lines()
                .find_map(|line| line.trim().strip_prefix(label))
                .unwrap_or_else(|| panic!("{label} in {text}"))
                .to_string()
        };
        let names = |key: &str| {
            let names: Vec<&str> = mechanism[key]
                .as_array()
                .unwrap_or_else(|| panic!("{key} in {mechanism}"))
                .iter()
                .map(|name| name.as_str().expect("a name"))
                .collect();
            names.join(", ")
        };
        assert_eq!(names("frames"), line_value("frames: ").replace("none", ""));
        assert_eq!(names("points"), line_value("points: "));
        assert_eq!(
            mechanism["kinetic_energy"]["text"],
            line_value("T of the bodies = ")
        );
        assert_eq!(
            mechanism["potential_energy"]["text"],
            line_value("V of the bodies = ")
        );
        assert!(mechanism["kinetic_energy"]["latex"].is_string());
        let contacts = text_entries(&text, "rolling contacts");
        assert_eq!(
            contacts.len(),
            mechanism["contacts"].as_object().unwrap().len()
        );
        for (name, row) in contacts {
            let entries: Vec<&str> = mechanism["contacts"][&name]["text"]
                .as_array()
                .unwrap_or_else(|| panic!("{name} in {mechanism}"))
                .iter()
                .map(|e| e.as_str().expect("an entry"))
                .collect();
            assert_eq!(format!("[{}]", entries.join(", ")), row);
            assert_eq!(
                mechanism["contacts"][&name]["latex"]
                    .as_array()
                    .unwrap()
                    .len(),
                entries.len()
            );
        }
        let holonomic = text_entries(&text, "holonomic constraints");
        assert_eq!(
            holonomic.len(),
            mechanism["holonomic"].as_object().unwrap().len()
        );
        for (name, residual) in holonomic {
            assert_eq!(mechanism["holonomic"][&name]["text"], residual.as_str());
        }
        // The rest of the document is there too.
        assert!(json["constraints"].is_object() && json["report"].is_object());
    }
    // The pendulum's constraint, x^2 + z^2 - l^2, by hand.
    let json: serde_json::Value = serde_json::from_str(&derived(PENDULUM, "json")).unwrap();
    let length = json["mechanism"]["holonomic"]["length"]["text"]
        .as_str()
        .expect("the length constraint");
    for term in ["x^2", "z^2", "- l^2"] {
        assert!(length.contains(term), "{length}");
    }
}

#[test]
fn derive_latex_has_the_mechanism_section_before_the_constraint_analysis() {
    let latex = derived("sleigh-bodies", "latex");
    let mechanism = latex
        .find("\\section*{Mechanism (frames, bodies, contacts)}")
        .expect("a mechanism section");
    let analysis = latex
        .find("\\section*{Constraint analysis")
        .expect("the analysis");
    assert!(mechanism < analysis);
    let section = &latex[mechanism..analysis];
    assert!(
        section.contains("\\item[points] blade, center"),
        "{section}"
    );
    // The blade's row, -sin(theta) dot(x) + cos(theta) dot(y) = 0.
    assert!(
        section.contains(
            "A_{\\text{blade}} = \\begin{bmatrix} -\\sin\\theta & \\cos\\theta & 0 \\end{bmatrix}"
        ),
        "{section}"
    );
    assert!(section.contains("V_{\\text{bodies}} = 0"), "{section}");
    let pendulum = derived(PENDULUM, "latex");
    assert!(pendulum.contains("f_{\\text{length}}(q) = "), "{pendulum}");
    let caster = derived("caster-robot", "latex");
    assert!(
        caster.contains("\\item[points] center, left\\_hub"),
        "{caster}"
    );
    let energy_form = derived("sleigh", "latex");
    assert!(!energy_form.contains("Mechanism ("), "{energy_form}");
}
