//! The drawing section's rules on a sleigh declared by its energy and on
//! a leaning disk declared as a mechanism: what they accept, and each
//! mistake reported at its token.

use crate::model::check;
use crate::model::drawing::{Figure, Orientation};
use crate::syntax::parse_str;

/// The Chaplygin sleigh with the drawing section `drawing`.
fn sleigh(drawing: &str) -> String {
    format!(
        "pub struct Sleigh {{
    coordinates: [x, y, theta],
    parameters: [m = 1.0, inertia = 0.1, a = 0.5],
    kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
        + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
    constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    define: [speed = dot(x)],
    drawing: [
        {drawing}
    ],
}}"
    )
}

/// The leaning disk of docs/INTERFACE.md section 4 with the drawing
/// section `drawing`.
fn disk(drawing: &str) -> String {
    format!(
        "pub struct Disk {{
    coordinates: [x, y, psi, phi, theta],
    parameters: [m = 1.0, r = 0.5, g = 9.81],
    frames: [
        heading = rotate(ground, z, psi),
        lean = rotate(heading, x, phi),
        disk = rotate(lean, y, theta),
    ],
    points: [contact = origin + x*ground.x + y*ground.y, center = contact + r*lean.z],
    bodies: [wheel = body(disk, center, m, diag(m*r^2/4, m*r^2/2, m*r^2/4))],
    gravity: -g*ground.z,
    no_slip: [rolling = no_slip(wheel, contact, [ground.x, ground.y])],
    drawing: [
        {drawing}
    ],
}}"
    )
}

/// The one error of `source`, rendered: `m.model:line:column: error: ...`.
fn error(source: &str) -> String {
    let syntax = parse_str(source).expect("parses");
    let errors = check(&syntax).map(|_| ()).expect_err("rejected");
    let rendered = errors.render("m.model");
    assert_eq!(rendered.lines().count(), 1, "one error:\n{rendered}");
    rendered
}

/// The line and column of the `occurrence`-th `token` in `source` (1-based).
fn at(source: &str, token: &str, occurrence: usize) -> String {
    let offset = source
        .match_indices(token)
        .nth(occurrence - 1)
        .unwrap_or_else(|| panic!("`{token}` in the source"))
        .0;
    let line = source[..offset].matches('\n').count() + 1;
    let column = offset - source[..offset].rfind('\n').map_or(0, |i| i + 1) + 1;
    format!("m.model:{line}:{column}: error: ")
}

fn assert_error(source: &str, token: &str, occurrence: usize, message: &str) {
    let found = error(source);
    let expected = format!("{}{message}", at(source, token, occurrence));
    assert!(found.starts_with(&expected), "{found}\nexpected {expected}");
}

#[test]
fn every_shape_is_read_in_ground_axes_or_the_mechanism_s() {
    let source = sleigh(
        "sled = box(center = [x, y, 0.05], heading = theta, size = [2*a, 0.3, 0.02]),
        mark = sphere(center = [x, y, 1], radius = a/10),
        wheel = disc(center = [x, y, 0.2], axle = [-sin(theta), cos(theta), 0], radius = 0.2),
        rod = segment([x, y, 0], [x + a*cos(theta), y + a*sin(theta), 0]),
        track = trace([x, y, 0]),",
    );
    let (model, _) = check(&parse_str(&source).unwrap()).unwrap();
    assert!(!model.mechanism.is_declared());
    let drawing = model.mechanism.drawing.expect("a drawing");
    let kinds: Vec<&str> = drawing.items.iter().map(|i| i.figure.kind()).collect();
    assert_eq!(kinds, ["box", "sphere", "disc", "segment", "trace"]);
    assert!(drawing.bodies.is_empty());
    let source = disk(
        "hub = disc(center = center, frame = disk, radius = r, thickness = r/10),
        axle = segment(center - r/3*lean.y, center + r/3*lean.y),
        cap = box(center = center + r*lean.z, frame = rotate(rotate(heading, x, phi), z, 1),
            size = [r, r, r]),",
    );
    let (model, _) = check(&parse_str(&source).unwrap()).unwrap();
    let drawing = model.mechanism.drawing.expect("a drawing");
    assert_eq!(drawing.bodies.len(), 1);
    let Figure::Disc { orientation, .. } = &drawing.items[0].figure else {
        panic!("a disc");
    };
    assert!(matches!(orientation, Orientation::Axes(_)));
}

#[test]
fn a_shape_is_one_of_five_and_takes_its_own_keyword_arguments() {
    let source = sleigh("sled = cube(center = [x, y, 0], size = [1, 1, 1]),");
    assert_error(
        &source,
        "cube",
        1,
        "unknown shape `cube`: a drawing item is",
    );
    let source = sleigh("sled = box(center = [x, y, 0], size = [1, 1, 1], colour = 1),");
    assert_error(
        &source,
        "colour",
        1,
        "unknown keyword argument `colour` of `box`: it takes center, size, frame, heading",
    );
    let source = sleigh("sled = box(center = [x, y, 0], size = [1, 1, 1], axle = [0, 1, 0]),");
    assert_error(
        &source,
        "axle",
        1,
        "unknown keyword argument `axle` of `box`",
    );
    let source = sleigh("sled = box(center = [x, y, 0], center = [x, y, 1], size = [1, 1, 1]),");
    assert_error(&source, "center", 2, "`center` is given twice");
    let source = sleigh("sled = box(center = [x, y, 0]),");
    assert_error(&source, "box", 1, "`box` needs `size = [a, b, c]`");
    let source = sleigh("sled = box([x, y, 0], size = [1, 1, 1]),");
    assert_error(
        &source,
        "[x, y, 0]",
        1,
        "`box` takes keyword arguments only",
    );
    let source = sleigh(
        "sled = box(center = [x, y, 0], size = [1, 1, 1], heading = theta, frame = ground),",
    );
    assert_error(
        &source,
        "frame",
        1,
        "`heading` and `frame` both orient the shape",
    );
    let source = sleigh("rod = segment([x, y, 0]),");
    assert_error(
        &source,
        "segment",
        1,
        "`segment` takes its two ends, `segment(A, B)`: 2 argument(s), found 1",
    );
    let source = sleigh("rod = segment(from = [x, y, 0], to = [0, 0, 0]),");
    assert_error(&source, "from", 1, "`segment` takes its two ends");
    let source = sleigh("sled = 3,");
    assert_error(&source, "3,", 1, "a drawing item is");
    let source = sleigh("box(center = [x, y, 0], size = [1, 1, 1]),");
    assert_error(
        &source,
        "box",
        1,
        "expected `name = ...` for a drawing item",
    );
}

#[test]
fn names_are_unique_and_positions_are_three_entries_of_the_configuration() {
    let source = sleigh("mark = trace([x, y, 0]), mark = trace([x, 0, 0]),");
    assert_error(
        &source,
        "mark",
        2,
        "`mark` is declared twice in this section",
    );
    let source = sleigh("mark = trace([x, y]),");
    assert_error(
        &source,
        "[x, y]",
        1,
        "a traced point is a list of 3 entries `[x, y, z]` in ground axes, found 2",
    );
    let source = sleigh("mark = trace([x, y, thetta]),");
    assert_error(&source, "thetta", 1, "unknown name `thetta`");
    let source = sleigh("mark = trace([x, y, speed]),");
    assert_error(
        &source,
        "speed",
        2,
        "a traced point depends on the configuration only",
    );
    let source = sleigh("mark = trace([x, y, 1 +]),");
    let syntax = parse_str(&source);
    assert!(syntax.is_err(), "a bad expression is the grammar's error");
    let source = sleigh("mark = trace(inertia),");
    assert_error(&source, "inertia)", 1, "a scalar where a point belongs");
}

#[test]
fn sizes_are_positive_constants_of_the_parameters() {
    let source = sleigh("mark = sphere(center = [x, y, 0], radius = 0),");
    assert_error(&source, "0)", 1, "a size is positive: this one is 0\n");
    let source = sleigh("mark = sphere(center = [x, y, 0], radius = 0.1 - a),");
    assert_error(
        &source,
        "0.1 - a",
        1,
        "a size is positive: this one is -0.4 at the default parameters",
    );
    let source = sleigh("mark = sphere(center = [x, y, 0], radius = 0.1 + x),");
    assert_error(
        &source,
        "0.1 + x",
        1,
        "a size depends on the parameters only",
    );
    let source = sleigh("sled = box(center = [x, y, 0], size = [1, 1]),");
    assert_error(
        &source,
        "[1, 1]",
        1,
        "a box's size is a list of 3 edge lengths",
    );
}

#[test]
fn orientations_name_frames_and_axles_are_vectors() {
    let source = disk("hub = disc(center = center, frame = dsk, radius = r),");
    assert_error(&source, "dsk", 1, "unknown frame `dsk`");
    let source = disk("hub = disc(center = center, frame = rotate(disk, w, 1), radius = r),");
    assert_error(
        &source,
        "w, 1",
        1,
        "a frame turns about its parent's `x`, `y` or `z` axis",
    );
    let source = disk("hub = disc(center = center, axle = lean, radius = r),");
    assert_error(&source, "lean, radius", 1, "`lean` is a frame, not a value");
    let source = disk("hub = disc(center = center, axle = [0, 0, 0], radius = r),");
    assert_error(&source, "[0, 0, 0]", 1, "an axle is a nonzero vector");
    let source = disk("hub = disc(center = center + lean.y, axle = center, radius = r),");
    assert_error(
        &source,
        "center, radius",
        1,
        "a point where a vector belongs",
    );
    let source = disk("hub = disc(center = center, heading = psi + dot(psi), radius = r),");
    assert_error(
        &source,
        "dot(psi)",
        1,
        "a frame's angle depends on the configuration only",
    );
}

#[test]
fn keyword_arguments_belong_to_the_drawing_s_shapes_alone() {
    let source = sleigh("mark = sphere(center = [x, y, sin(t = 0)], radius = 0.1),");
    assert_error(
        &source,
        "t = 0",
        1,
        "`t = ...` is a keyword argument, which `sin` does not take",
    );
    let source = sleigh("mark = trace([x, y, 0]),").replace(
        "inertia/2*dot(theta)^2,",
        "inertia/2*dot(theta)^2 + 0*sin(a = theta),",
    );
    assert_error(&source, "a = theta", 1, "`a = ...` is a keyword argument");
}
