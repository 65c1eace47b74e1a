use super::{AnimationError, MIN_SIZE, World, box_size, check, frame_rows, quaternion, scene};
use crate::animate::Shape;
use crate::runtime::nalgebra::{Rotation3, Unit, UnitQuaternion, Vector3};
use crate::runtime::record::Table;
use chaplygin_codegen::interpret::{Drawing, InterpretedModel};

/// A disc rolling on the ground as the benchmark bicycle's wheels are
/// declared: z down, gravity along `+z`, the centre above the contact by
/// `r` along the lean frame's `-z`; and a particle riding on its centre.
const DISK_Z_DOWN: &str = "pub struct DiskZDown {
    coordinates: [x, y, psi, phi, theta],
    parameters: [m = 2.0, r = 0.4, g = 9.81, mp = 4.1887902047863905],
    frames: [
        heading = rotate(ground, z, psi),
        lean = rotate(heading, x, phi),
        disk = rotate(lean, y, theta),
    ],
    points: [
        contact = origin + x*ground.x + y*ground.y,
        center = contact - r*lean.z,
    ],
    bodies: [
        wheel = body(disk, center, m, diag(m*r^2/4, m*r^2/2, m*r^2/4)),
        rider = particle(center, mp),
    ],
    gravity: g*ground.z,
    no_slip: [rolling = no_slip(wheel, contact, [ground.x, ground.y])],
}";

fn model(source: &str) -> InterpretedModel {
    InterpretedModel::from_source(source).unwrap_or_else(|e| panic!("{}", e.render("model")))
}

/// A model's text without its `drawing:` section (the last one).
fn without_drawing(source: &str) -> String {
    let (before, _) = source
        .split_once("    drawing: [")
        .expect("a drawing section");
    format!("{before}}}")
}

/// A table of the configurations `qs` at times 0, 0.1, ...
fn table(model: &InterpretedModel, qs: &[Vec<f64>]) -> Table {
    let mut columns = vec!["t".to_string()];
    columns.extend(model.names().coordinates.iter().cloned());
    let rows = qs
        .iter()
        .enumerate()
        .map(|(i, q)| std::iter::once(i as f64 / 10.0).chain(q.clone()).collect())
        .collect();
    Table { columns, rows }
}

#[test]
fn frames_are_every_kth_row_about_one_over_fps_apart_and_the_last_is_kept() {
    let times: Vec<f64> = (0..=1000).map(|i| f64::from(i) * 1e-3).collect();
    let rows = frame_rows(&times, 60.0);
    // 1/60 s is 16.7 rows of 1 ms: every 17th row, and the last
    assert_eq!(&rows[..3], &[0, 17, 34]);
    assert_eq!(rows[rows.len() - 2], 986);
    assert_eq!(rows.last(), Some(&1000));
    assert_eq!(rows.len(), 60);
    // fewer rows than frames: every row
    assert_eq!(frame_rows(&times[..5], 1e6), vec![0, 1, 2, 3, 4]);
    // rows a whole multiple apart: no extra last frame
    assert_eq!(frame_rows(&times[..=34], 60.0), vec![0, 17, 34]);
    assert_eq!(frame_rows(&[2.5], 60.0), vec![0]);
    assert!(frame_rows(&[], 60.0).is_empty());
    // a last row at the time of the frame before it replaces that frame
    assert_eq!(frame_rows(&[0.0, 0.5, 1.0, 1.0], 2.0), vec![0, 3]);
}

#[test]
fn a_box_of_the_sizes_has_the_body_s_inertia() {
    let (mass, sides) = (3.0, [0.9, 0.4, 0.25]);
    let inertia = |size: [f64; 3]| {
        let [a, b, c] = size.map(|s| s * s);
        [b + c, a + c, a + b].map(|sum| mass * sum / 12.0)
    };
    let moments = inertia(sides);
    let found = box_size(mass, moments);
    for (found, expected) in found.iter().zip(sides) {
        assert!((found - expected).abs() < 1e-14, "{found:?} {sides:?}");
    }
    let recomputed = inertia(found);
    for (found, expected) in recomputed.iter().zip(moments) {
        assert!((found - expected).abs() < 1e-14 * expected);
    }
    // a plate about its normal: the thickness is the minimum
    let plate = box_size(1.0, [0.0, 0.0, 0.1]);
    assert_eq!(plate[2], MIN_SIZE);
    assert!((plate[0] - 0.6f64.sqrt()).abs() < 1e-15 && plate[0] == plate[1]);
    assert_eq!(box_size(0.0, [1.0, 1.0, 1.0]), [MIN_SIZE; 3]);
}

#[test]
fn the_quaternion_of_a_rotation_matrix_is_nalgebra_s() {
    let axes = [
        Vector3::new(1.0, 2.0, 3.0),
        Vector3::x(),
        Vector3::y(),
        Vector3::z(),
        Vector3::new(-0.3, 0.1, 0.9),
        Vector3::new(1.0, -1.0, 0.0),
    ];
    let angles = [0.0, 0.4, -1.3, 2.9, std::f64::consts::PI, 3.1, -3.1];
    for axis in axes {
        for angle in angles {
            let rotation = Rotation3::from_axis_angle(&Unit::new_normalize(axis), angle);
            let m = *rotation.matrix();
            let expected = UnitQuaternion::from_matrix(&m);
            let q = quaternion(&m);
            let sign = if expected.w < 0.0 { -1.0 } else { 1.0 };
            let expected = [expected.i, expected.j, expected.k, expected.w].map(|x| sign * x);
            let error = q
                .iter()
                .zip(&expected)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            // at a half turn w = 0 and the sign of (x, y, z) is free
            let flipped = q
                .iter()
                .zip(&expected)
                .map(|(a, b)| (a + b).abs())
                .fold(0.0, f64::max);
            assert!(
                error < 1e-12 || (expected[3].abs() < 1e-12 && flipped < 1e-12),
                "{axis} {angle}: {q:?} against {expected:?}"
            );
        }
    }
}

#[test]
fn gravity_along_plus_z_turns_the_model_by_pi_about_x() {
    let drawing = |gravity| Drawing {
        gravity,
        bodies: Vec::new(),
        contacts: Vec::new(),
        items: Vec::new(),
    };
    let down = World::of(&drawing([0.0, 0.0, 9.81]));
    assert!(down.flipped);
    assert_eq!(down.point([1.0, 2.0, 3.0]), [1.0, -2.0, -3.0]);
    assert_eq!(down.turn().determinant(), 1.0);
    let up = World::of(&drawing([0.0, 0.0, -9.81]));
    assert!(!up.flipped);
    assert_eq!(up.point([1.0, 2.0, 3.0]), [1.0, 2.0, 3.0]);
    let none = World::of(&drawing([0.0; 3]));
    assert!(!none.flipped);
    assert_eq!(none.down, -Vector3::z());
}

#[test]
fn a_z_down_disc_is_a_wheel_on_the_ground_shown_with_z_up() {
    let disk = model(DISK_Z_DOWN);
    let qs = vec![
        vec![0.0, 0.0, 0.0, 0.0, 0.0],
        vec![0.3, -0.2, 0.7, 0.25, 1.1],
    ];
    let scene = scene(&disk, "disk_z_down", &table(&disk, &qs), 10.0).unwrap();
    assert!(scene.note.as_deref().unwrap().contains("(x, -y, -z)"));
    let wheel = &scene.items[0];
    assert_eq!(wheel.name, "wheel");
    let Shape::Disc { radius, .. } = wheel.shape else {
        panic!("a disc: {:?}", wheel.shape)
    };
    assert!((radius - 0.4).abs() < 1e-15);
    for (pose, q) in wheel.poses.iter().zip(&qs) {
        let (x, y, psi, phi) = (q[0], q[1], q[2], q[3]);
        // the hub, z up: above the contact by r along the lean
        let hub = [
            x - 0.4 * psi.sin() * phi.sin(),
            -(y + 0.4 * psi.cos() * phi.sin()),
            0.4 * phi.cos(),
        ];
        for (a, b) in pose.position.iter().zip(hub) {
            assert!((a - b).abs() < 1e-14, "{:?} {hub:?}", pose.position);
        }
        // the axle, local y, is the wheel's y axis turned: its lowest
        // point is on the ground
        let [i, j, k, w] = pose.quaternion;
        let rotation = UnitQuaternion::from_quaternion([i, j, k, w].into());
        let axle = rotation * Vector3::y();
        let below = (-Vector3::z() + axle * axle.z).normalize();
        assert!((pose.position[2] + radius * below.z).abs() < 1e-14);
    }
    // the particle of 4.19 kg is a ball of water: 10 cm across
    let Shape::Sphere { radius } = scene.items[1].shape else {
        panic!("a sphere: {:?}", scene.items[1].shape)
    };
    assert!((radius - 0.1).abs() < 1e-12, "{radius}");
    assert_eq!(scene.traces[0].name, "rolling");
    assert_eq!(scene.traces[0].points[1], [0.3, 0.2, -0.0]);
    let labels: Vec<&str> = scene.labels.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(labels, ["x", "y", "psi"]);
    crate::animate::page(&scene).unwrap();
}

#[test]
fn the_sleigh_is_a_box_of_its_inertia_turned_with_it() {
    let sleigh = model(&without_drawing(include_str!(
        "../../../models/sleigh_bodies.model"
    )));
    let qs = vec![vec![0.0, 0.0, 0.0], vec![1.0, 0.5, 0.8]];
    let scene = scene(&sleigh, "sleigh_bodies", &table(&sleigh, &qs), 10.0).unwrap();
    assert_eq!(scene.note, None);
    let sled = &scene.items[0];
    let Shape::Box { size } = sled.shape else {
        panic!("a box: {:?}", sled.shape)
    };
    // m = 1, I = diag(0, 0, 0.1): a plate sqrt(0.6) square
    assert!((size[0] - 0.6f64.sqrt()).abs() < 1e-15 && size[1] == size[0]);
    assert_eq!(size[2], MIN_SIZE);
    let expected = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.8);
    let [i, j, k, w] = sled.poses[1].quaternion;
    assert!((UnitQuaternion::from_quaternion([i, j, k, w].into()).angle_to(&expected)) < 1e-12);
    // the centre is a = 0.5 ahead of the blade
    let [x, y, _] = sled.poses[1].position;
    assert!(
        (x - 1.0 - 0.5 * 0.8f64.cos()).abs() < 1e-15
            && (y - 0.5 - 0.5 * 0.8f64.sin()).abs() < 1e-15
    );
}

/// The Euler parameters `[e0, e1, e2, e3]` of the turn by `angle` about
/// `axis`, and the page's quaternion of it `[e1, e2, e3, e0]` as nalgebra
/// makes it.
fn turn(axis: [f64; 3], angle: f64) -> ([f64; 4], [f64; 4]) {
    let q = UnitQuaternion::from_axis_angle(&Unit::new_normalize(Vector3::from(axis)), angle);
    ([q.w, q.i, q.j, q.k], [q.i, q.j, q.k, q.w])
}

#[test]
fn the_chaplygin_ball_is_a_sphere_of_its_radius_on_the_ground_turned_with_it() {
    let ball = model(include_str!("../../../models/chaplygin_ball.model"));
    let turns = [
        turn([1.0, 0.0, 0.0], 0.0),
        turn([0.3, -0.5, 0.8], 1.1),
        turn([-0.7, 0.2, 0.4], 2.6),
    ];
    let qs: Vec<Vec<f64>> = (turns.iter().enumerate())
        .map(|(i, (e, _))| [vec![0.4 * i as f64, -0.3 * i as f64], e.to_vec()].concat())
        .collect();
    let drawn = scene(&ball, "chaplygin_ball", &table(&ball, &qs), 10.0).unwrap();
    let shell = &drawn.items[0];
    // the model's r = 0.5
    assert_eq!(shell.shape, Shape::Sphere { radius: 0.5 });
    for ((pose, q), (_, quaternion)) in shell.poses.iter().zip(&qs).zip(turns) {
        assert_near(&pose.position, &[q[0], q[1], 0.5], "the ball's centre");
        assert_near(&pose.quaternion, &quaternion, "the ball's turn");
    }
    // at rest, its contact kept at one place in its axes by the run: the
    // same sphere, from the samples each moving one Euler parameter
    let rest = scene(&ball, "chaplygin_ball", &table(&ball, &qs[..1]), 10.0).unwrap();
    assert_eq!(rest.items[0].shape, Shape::Sphere { radius: 0.5 });
    // by z-x-z angles, turned as much, the same sphere
    let zxz = model(include_str!(
        "../../../tests/models/chaplygin_ball_zxz.model"
    ));
    let qs = vec![
        vec![0.0, 0.0, 0.3, 0.5, 0.7],
        vec![0.2, 0.1, 1.0, 1.2, -0.4],
        vec![0.5, -0.3, 2.0, 0.4, 2.5],
    ];
    let drawn = scene(&zxz, "chaplygin_ball_zxz", &table(&zxz, &qs), 10.0).unwrap();
    let Shape::Sphere { radius } = drawn.items[0].shape else {
        panic!("a sphere: {:?}", drawn.items[0].shape)
    };
    assert!((radius - 0.5).abs() < 1e-15, "{radius}");
}

#[test]
fn a_car_s_flat_chassis_spans_its_wheels_contacts() {
    let car = model(include_str!("../../../tests/models/car.model"));
    let qs = vec![
        vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        vec![1.5, -0.5, 0.9, 0.3, 0.25, 2.0, 2.1, 1.9, 2.2],
    ];
    let drawn = scene(&car, "car", &table(&car, &qs), 10.0).unwrap();
    let names: Vec<&str> = drawn.items.iter().map(|item| item.name.as_str()).collect();
    let wheels = ["rear_left", "rear_right", "front_left", "front_right"];
    assert_eq!(names, [&["chassis"][..], &wheels].concat());
    assert_eq!(
        drawn.note.as_deref(),
        Some("not drawn (no mass): knuckle_left, knuckle_right")
    );
    // l = 1 from the rear axle to the front one, 2 b = 0.8 across, at the
    // rear axle's height r = 0.15
    let (l, b, r) = (1.0, 0.4, 0.15);
    let chassis = &drawn.items[0];
    assert_eq!(
        chassis.shape,
        Shape::Box {
            size: [l, 2.0 * b, MIN_SIZE]
        }
    );
    for (pose, q) in chassis.poses.iter().zip(&qs) {
        let (x, y, theta) = (q[0], q[1], q[2]);
        let middle = [x + l / 2.0 * theta.cos(), y + l / 2.0 * theta.sin(), r];
        assert_near(&pose.position, &middle, "the chassis");
        assert_near(&pose.quaternion, &yaw(theta), "the chassis");
    }
    // a run of one frame: the same chassis, from the samples each moving
    // one coordinate
    let parked = scene(&car, "car", &table(&car, &qs[1..]), 10.0).unwrap();
    let Shape::Box { size } = parked.items[0].shape else {
        panic!("a box: {:?}", parked.items[0].shape)
    };
    assert_near(&size, &[l, 2.0 * b, MIN_SIZE], "parked");
    assert_near(
        &parked.items[0].poses[0].position,
        &chassis.poses[1].position,
        "parked",
    );
    for item in &drawn.items[1..] {
        let Shape::Disc { radius, thickness } = item.shape else {
            panic!("{}: a disc, {:?}", item.name, item.shape)
        };
        assert_near(&[radius, thickness], &[r, r / 5.0], &item.name);
    }
}

#[test]
fn massless_bodies_without_a_wheel_are_not_drawn_and_named_in_the_note() {
    let board = model(&without_drawing(include_str!(
        "../../../models/snakeboard_bodies.model"
    )));
    let qs = vec![vec![0.0; 5]];
    let scene = scene(&board, "snakeboard_bodies", &table(&board, &qs), 60.0).unwrap();
    let names: Vec<&str> = scene.items.iter().map(|item| item.name.as_str()).collect();
    assert_eq!(names, ["deck"]);
    assert_eq!(
        scene.note.as_deref(),
        Some("not drawn (no mass): rider, wheels")
    );
}

#[test]
fn a_model_with_nothing_to_draw_is_refused_by_name() {
    let board = model(&without_drawing(include_str!(
        "../../../models/snakeboard.model"
    )));
    let error = check(&board, "snakeboard").unwrap_err();
    assert!(matches!(error, AnimationError::NothingToDraw { .. }));
    let message = error.to_string();
    assert!(
        message.starts_with("`snakeboard` has nothing to draw"),
        "{message}"
    );
    let qs = vec![vec![0.0; 5]];
    assert!(matches!(
        scene(&board, "snakeboard", &table(&board, &qs), 60.0),
        Err(AnimationError::NothingToDraw { .. })
    ));
}

/// A model declared by its energy, drawn by every kind of drawing item.
const DRAWN: &str = "pub struct Drawn {
    coordinates: [x, y, theta, phi],
    parameters: [m = 1.0, r = 0.3, l = 0.8],
    kinetic_energy: m/2*(dot(x)^2 + dot(y)^2 + dot(theta)^2 + dot(phi)^2),
    drawing: [
        board = box(center = [x, y, 0.05], heading = theta, size = [2*l, 0.3, 0.02]),
        wheel = disc(center = [x, y, r], frame = rotate(rotate(ground, z, theta), y, phi),
            radius = r),
        rim = disc(center = origin + x*ground.x + y*ground.y + r*ground.z,
            axle = [-sin(theta), cos(theta), 0], radius = r, thickness = 0.05),
        rod = segment([x, y, 0.1], [x + l*cos(theta), y + l*sin(theta), 0.1]),
        ball = sphere(center = [x, y, 1], radius = 0.1),
        track = trace([x, y, 0]),
    ],
}";

/// The turn about z by `a`, `[x, y, z, w]`.
fn yaw(a: f64) -> [f64; 4] {
    let (s, c) = (a / 2.0).sin_cos();
    [0.0, 0.0, s, c]
}

/// The turn about z by `a`, then about the turned y by `b`: `q_z(a) q_y(b)`
/// multiplied out by hand, its w made positive.
fn yaw_spin(a: f64, b: f64) -> [f64; 4] {
    let (s1, c1) = (a / 2.0).sin_cos();
    let (s2, c2) = (b / 2.0).sin_cos();
    let q = [-s1 * s2, c1 * s2, s1 * c2, c1 * c2];
    let sign = if q[3] < 0.0 { -1.0 } else { 1.0 };
    q.map(|x| sign * x)
}

fn assert_near(found: &[f64], expected: &[f64], what: &str) {
    let error = (found.iter().zip(expected))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(error < 1e-14, "{what}: {found:?} against {expected:?}");
}

#[test]
fn drawing_items_are_posed_by_the_model_s_expressions() {
    let drawn = model(DRAWN);
    let qs = vec![
        vec![0.0, 0.0, 0.0, 0.0],
        vec![1.0, -0.5, 0.7, 2.0],
        vec![-0.4, 2.0, -2.5, -1.0],
    ];
    let scene = scene(&drawn, "drawn", &table(&drawn, &qs), 10.0).unwrap();
    let names: Vec<&str> = scene.items.iter().map(|item| item.name.as_str()).collect();
    assert_eq!(names, ["board", "wheel", "rim", "rod", "ball"]);
    let shapes: Vec<Shape> = scene.items.iter().map(|item| item.shape).collect();
    assert_eq!(
        shapes,
        [
            Shape::Box {
                size: [1.6, 0.3, 0.02]
            },
            Shape::Disc {
                radius: 0.3,
                thickness: 0.3 / 5.0
            },
            Shape::Disc {
                radius: 0.3,
                thickness: 0.05
            },
            Shape::Segment { length: 0.8 },
            Shape::Sphere { radius: 0.1 },
        ]
    );
    for (frame, q) in qs.iter().enumerate() {
        let (x, y, theta, phi) = (q[0], q[1], q[2], q[3]);
        let expected: [([f64; 3], [f64; 4]); 5] = [
            ([x, y, 0.05], yaw(theta)),
            ([x, y, 0.3], yaw_spin(theta, phi)),
            ([x, y, 0.3], yaw(theta)),
            (
                [x + 0.4 * theta.cos(), y + 0.4 * theta.sin(), 0.1],
                yaw(theta),
            ),
            ([x, y, 1.0], [0.0, 0.0, 0.0, 1.0]),
        ];
        for (item, (position, quaternion)) in scene.items.iter().zip(expected) {
            let pose = &item.poses[frame];
            let what = format!("{} at frame {frame}", item.name);
            assert_near(&pose.position, &position, &what);
            assert_near(&pose.quaternion, &quaternion, &what);
        }
        assert_eq!(scene.traces[0].points[frame], [x, y, 0.0]);
    }
    assert_eq!(scene.traces[0].name, "track");
    assert_eq!(scene.note, None);
    crate::animate::page(&scene).unwrap();
}

#[test]
fn a_drawing_item_named_like_a_body_replaces_its_shape() {
    let sleigh = model(include_str!("../../../models/sleigh_bodies.model"));
    let qs = vec![vec![0.0, 0.0, 0.0], vec![1.0, 0.5, 0.8]];
    let scene = scene(&sleigh, "sleigh_bodies", &table(&sleigh, &qs), 10.0).unwrap();
    let names: Vec<&str> = scene.items.iter().map(|item| item.name.as_str()).collect();
    assert_eq!(names, ["sled", "knife"]);
    assert_eq!(
        scene.items[0].shape,
        Shape::Box {
            size: [0.9, 0.3, 0.05]
        }
    );
    // a = 0.5: the box's centre a/2 ahead of the blade, 8 cm up
    let pose = &scene.items[0].poses[1];
    let ahead = [1.0 + 0.25 * 0.8f64.cos(), 0.5 + 0.25 * 0.8f64.sin(), 0.08];
    assert_near(&pose.position, &ahead, "sled");
    assert_near(&pose.quaternion, &yaw(0.8), "sled");
    assert_eq!(scene.traces[0].name, "blade");
}

#[test]
fn a_drawing_item_that_cannot_be_placed_is_an_error_naming_it() {
    let text = |item: &str| {
        format!(
            "pub struct Bad {{
                coordinates: [x],
                parameters: [m = 1.0],
                kinetic_energy: m/2*dot(x)^2,
                drawing: [{item}],
            }}"
        )
    };
    for (item, start, frame, reason) in [
        (
            "rod = segment([0, 0, 0], [x, 0, 0])",
            1.0,
            1,
            "a segment is rigid",
        ),
        (
            "rod = segment([x, 0, 0], [2*x, 0, 0])",
            0.0,
            0,
            "its ends coincide",
        ),
        (
            "wheel = disc(center = [0, 0, 1], axle = [x, 0, 0], radius = 1)",
            1.0,
            2,
            "its axle is zero",
        ),
    ] {
        let qs = vec![vec![start], vec![2.0], vec![0.0]];
        let bad = model(&text(item));
        let error = scene(&bad, "bad", &table(&bad, &qs), 10.0).unwrap_err();
        let AnimationError::Item {
            time,
            reason: found,
            ..
        } = &error
        else {
            panic!("{item}: {error}");
        };
        assert_eq!(*time, frame as f64 / 10.0, "{item}");
        assert!(found.contains(reason), "{item}: {error}");
        assert!(error.to_string().starts_with("drawing item `"), "{error}");
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let disk = model(DISK_Z_DOWN);
    let qs = vec![vec![0.0; 5]];
    let good = table(&disk, &qs);
    for fps in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            scene(&disk, "d", &good, fps),
            Err(AnimationError::Fps { .. })
        ));
    }
    let empty = Table {
        columns: good.columns.clone(),
        rows: Vec::new(),
    };
    assert!(matches!(
        scene(&disk, "d", &empty, 60.0),
        Err(AnimationError::NoRows)
    ));
    let mut renamed = good.clone();
    renamed.columns[1] = "q1".into();
    assert!(matches!(
        scene(&disk, "d", &renamed, 60.0),
        Err(AnimationError::Columns { .. })
    ));
    let mut short = good.clone();
    short.rows[0].pop();
    assert!(matches!(
        scene(&disk, "d", &short, 60.0),
        Err(AnimationError::RowLength { row: 0, .. })
    ));
    let mut not_finite = good;
    not_finite.rows[0][1] = f64::NAN;
    assert!(matches!(
        super::page(&disk, "d", &not_finite, 60.0),
        Err(AnimationError::Page(_))
    ));
}
