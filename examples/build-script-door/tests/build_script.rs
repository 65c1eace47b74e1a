//! The example `build_script` run in this process (its file a module
//! here, with the model `build.rs` generated): what it prints holds the
//! sleigh's known constraint analysis (its blade's velocities and their
//! bracket span every velocity: growth vector (2, 3), completely
//! nonholonomic; Bloch, *Nonholonomic Mechanics and Control*, section 1.7)
//! and the power balance of the push, the only force that works.

#[allow(dead_code)]
#[path = "../examples/build_script.rs"]
mod build_script;

/// The word of `text` just before the first `what`, as a number.
fn number_before(text: &str, what: &str) -> f64 {
    let at = text
        .find(what)
        .unwrap_or_else(|| panic!("`{what}` in\n{text}"));
    let word = text[..at].split_whitespace().last().expect("a number");
    word.parse()
        .unwrap_or_else(|_| panic!("`{word}` before `{what}`"))
}

#[test]
fn the_pushed_sleigh_gains_the_pushs_work() {
    let mut out = Vec::new();
    build_script::report(&mut out).expect("the example runs");
    let text = String::from_utf8(out).expect("UTF-8");
    assert!(text.contains("growth vector (2, 3)"), "{text}");
    assert!(
        text.contains("classification: completely nonholonomic"),
        "{text}"
    );
    let travelled = number_before(&text, " m and the sleigh gained");
    let gained = number_before(&text, " J,\n");
    assert!(travelled > 10.0, "{text}");
    // the midpoint rule's power balance is exact; the chords of the
    // recorded path fall short of its length by (h w)^2 / 24 relative
    assert!(
        (gained - build_script::PUSH * travelled).abs() <= 1e-5 * gained,
        "{text}"
    );
    assert!(number_before(&text, " m/s at most") < 1e-12, "{text}");
}
