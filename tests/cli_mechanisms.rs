//! The command line on models declared as mechanisms: `list` offers them,
//! `derive` shows what the mechanism sections derived, a broken mechanism
//! file is reported at its `file:line:col`.

use std::process::{Command, Output};

fn chaplygin(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(arguments)
        .output()
        .expect("the binary runs")
}

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
    let directory = std::env::temp_dir().join(format!("cli-mechanism-{}", std::process::id()));
    std::fs::create_dir_all(&directory).expect("directory");
    let file = directory.join("disk.model");
    let text =
        include_str!("../models/rolling_disk_3d.model").replace("rotate(lean, y", "rotate(lean, w");
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
    std::fs::remove_dir_all(&directory).expect("clean up");
}
