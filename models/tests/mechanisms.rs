//! Models declared as mechanisms against their hand derivations: the
//! derived `T`, `V` and constraint row space equal the hand-written energy
//! forms exactly (normal form); a leaning rolling disk turns steadily as
//! the closed form of its steady motion says; orientations and positions
//! equal the rotation chain by hand; the holonomic Jacobian equals finite
//! differences of the residual.

use chaplygin::runtime::system::Holonomic;
use chaplygin_codegen::model::{Model, check};
use chaplygin_codegen::sym::{Context, Matrix, RationalFunction};
use chaplygin_codegen::syntax::parse_str;
use chaplygin_models::rolling_disk_3d::RollingDisk3d;
use chaplygin_models::{
    caster_robot, rolling_disk_3d, sleigh, sleigh_bodies, snakeboard, snakeboard_bodies,
};

fn checked(source: &str) -> (Model, Context) {
    let syntax = parse_str(source).expect("parses");
    check(&syntax).unwrap_or_else(|e| panic!("{}", e.render("test.model")))
}

fn normal(model: &Model, cx: &mut Context, text: &str) -> RationalFunction {
    model
        .normal_of_text(cx, text)
        .unwrap_or_else(|e| panic!("{}", e.render("hand form")))
}

/// `T` and `V` of `model` equal the hand forms, exactly.
fn assert_energies(model: &Model, cx: &mut Context, kinetic: &str, potential: &str) {
    let atoms = cx.atoms().clone();
    let t = normal(model, cx, kinetic);
    let v = normal(model, cx, potential);
    assert!(model.kinetic_energy.sub(&t, &atoms).is_zero(), "T differs");
    assert!(
        model.potential_energy.sub(&v, &atoms).is_zero(),
        "V differs"
    );
}

/// The rows of `A` (linear forms in the velocities) of hand-written constraints.
fn hand_rows(model: &Model, cx: &mut Context, rows: &[&str]) -> Matrix {
    let velocities = model.velocities.clone();
    let mut entries = Vec::new();
    for row in rows {
        let form = normal(model, cx, row);
        for &v in &velocities {
            entries.push(cx.derivative_of_normal(&form, v).expect("derivative"));
        }
    }
    Matrix::new(rows.len(), velocities.len(), entries).expect("shape")
}

/// The derived rows and the hand rows span the same space: each has full
/// rank and stacking them adds none.
fn assert_row_space(model: &Model, cx: &mut Context, rows: &[&str]) {
    let hand = hand_rows(model, cx, rows);
    let derived = model.constraint_matrix.clone();
    let atoms = cx.atoms().clone();
    let mut stacked = derived.entries().to_vec();
    stacked.extend_from_slice(hand.entries());
    let stacked = Matrix::new(derived.rows() + hand.rows(), derived.columns(), stacked).unwrap();
    assert_eq!(derived.rank(&atoms), rows.len());
    assert_eq!(hand.rank(&atoms), rows.len());
    assert_eq!(stacked.rank(&atoms), rows.len());
}

/// The leaning disk (lean `phi` about the heading's x axis, rolling about
/// the lean's y axis, inertias A = m r^2/4, C = m r^2/2): with the centre
/// `C = (x + r sin(psi) sin(phi), y - r cos(psi) sin(phi), r cos(phi))` and
/// `omega = (phidot, psidot sin(phi) + thetadot, psidot cos(phi))` in lean
/// axes, `T = m/2 |Cdot|^2 + A/2 (omega_1^2 + omega_3^2) + C/2 omega_2^2`,
/// `V = m g r cos(phi)`; rolling moves the contact along the heading at
/// the rim speed `r thetadot`.
const DISK_KINETIC: &str =
    "m/2*((dot(x) + r*(cos(psi)*sin(phi)*dot(psi) + sin(psi)*cos(phi)*dot(phi)))^2
    + (dot(y) + r*(sin(psi)*sin(phi)*dot(psi) - cos(psi)*cos(phi)*dot(phi)))^2
    + (r*sin(phi)*dot(phi))^2)
    + m*r^2/8*(dot(phi)^2 + cos(phi)^2*dot(psi)^2) + m*r^2/4*(sin(phi)*dot(psi) + dot(theta))^2";
const DISK_POTENTIAL: &str = "m*g*r*cos(phi)";
const DISK_ROWS: [&str; 2] = [
    "dot(x) - r*cos(psi)*dot(theta)",
    "dot(y) - r*sin(psi)*dot(theta)",
];

#[test]
fn the_leaning_disk_derives_its_hand_energies_and_rolling_rows() {
    let (model, mut cx) = checked(rolling_disk_3d::MODEL_TEXT);
    assert_energies(&model, &mut cx, DISK_KINETIC, DISK_POTENTIAL);
    assert_row_space(&model, &mut cx, &DISK_ROWS);
    assert_eq!(RollingDisk3d::CONSTRAINTS, ["rolling_1", "rolling_2"]);
}

#[test]
fn a_contact_point_through_a_norm_derives_the_same_rows() {
    // The contact point of a disk of any orientation: from the centre, a
    // radius along the disk's plane towards the ground. Here |a x z| = |cos(phi)|.
    let source = rolling_disk_3d::MODEL_TEXT.replace(
        "contact = origin + x*ground.x + y*ground.y,\n        center = contact + r*lean.z,",
        "center = origin + x*ground.x + y*ground.y + r*lean.z,\n        \
             contact = center + r*unit(cross(disk.y, cross(disk.y, ground.z))),",
    );
    assert_ne!(source, rolling_disk_3d::MODEL_TEXT);
    let (by_norm, mut cx) = checked(&source);
    assert_energies(&by_norm, &mut cx, DISK_KINETIC, DISK_POTENTIAL);
    assert_row_space(&by_norm, &mut cx, &DISK_ROWS);
    let (by_hand, _) = checked(rolling_disk_3d::MODEL_TEXT);
    assert_eq!(
        by_norm.constraint_matrix.rows(),
        by_hand.constraint_matrix.rows()
    );
}

#[test]
fn the_sleigh_of_bodies_is_the_sleigh_of_energies() {
    let (model, mut cx) = checked(sleigh_bodies::MODEL_TEXT);
    assert_energies(
        &model,
        &mut cx,
        "m/2*((dot(x) - a*sin(theta)*dot(theta))^2 + (dot(y) + a*cos(theta)*dot(theta))^2) \
         + inertia/2*dot(theta)^2",
        "0",
    );
    assert_row_space(&model, &mut cx, &["-sin(theta)*dot(x) + cos(theta)*dot(y)"]);
    let (energy_form, _) = checked(sleigh::MODEL_TEXT);
    assert_eq!(
        energy_form.constraint_matrix.rows(),
        model.constraint_matrix.rows()
    );
}

#[test]
fn the_snakeboard_of_bodies_is_the_snakeboard_of_energies() {
    let (model, mut cx) = checked(snakeboard_bodies::MODEL_TEXT);
    assert_energies(
        &model,
        &mut cx,
        "m/2*(dot(x)^2 + dot(y)^2) + (jt + m*r^2)/2*dot(theta)^2 + jt*dot(theta)*dot(psi) \
         + jt/2*dot(psi)^2 + jw/2*dot(phi)^2",
        "0",
    );
    assert_row_space(
        &model,
        &mut cx,
        &[
            "-sin(theta + phi)*dot(x) + cos(theta + phi)*dot(y) + r*cos(phi)*dot(theta)",
            "-sin(theta - phi)*dot(x) + cos(theta - phi)*dot(y) - r*cos(phi)*dot(theta)",
        ],
    );
    let (energy_form, _) = checked(snakeboard::MODEL_TEXT);
    assert_eq!(
        energy_form.constraint_matrix.rows(),
        model.constraint_matrix.rows()
    );
}

/// The caster robot by hand: the chassis translates and turns, each wheel
/// and the caster wheel spin about their axles, the fork turns at
/// `thetadot + betadot`. A wheel's contact point has the hub's velocity
/// minus `r phidot` along its rolling direction: with the hubs at
/// `(x, y) +- b heading.y`, the mount `l` behind, the trail `d` along the
/// swivel's x (so `heading.y . swivel.x = sin(beta)`,
/// `heading.y . swivel.y = cos(beta)`), rolling and no side slip read
/// as the rows below.
#[test]
fn the_caster_robot_derives_its_hand_energies_and_rolling_rows() {
    let (model, mut cx) = checked(caster_robot::MODEL_TEXT);
    assert_energies(
        &model,
        &mut cx,
        "m/2*(dot(x)^2 + dot(y)^2) + i_c/2*dot(theta)^2 + iw/2*(dot(phi_l)^2 + dot(phi_r)^2) \
         + i_s/2*(dot(theta) + dot(beta))^2 + ic/2*dot(phi_c)^2",
        "0",
    );
    assert_row_space(
        &model,
        &mut cx,
        &[
            "cos(theta)*dot(x) + sin(theta)*dot(y) - b*dot(theta) - r*dot(phi_l)",
            "-sin(theta)*dot(x) + cos(theta)*dot(y)",
            "cos(theta)*dot(x) + sin(theta)*dot(y) + b*dot(theta) - r*dot(phi_r)",
            "cos(theta + beta)*dot(x) + sin(theta + beta)*dot(y) - l*sin(beta)*dot(theta) \
             - rc*dot(phi_c)",
            "-sin(theta + beta)*dot(x) + cos(theta + beta)*dot(y) - l*cos(beta)*dot(theta) \
             - d*(dot(theta) + dot(beta))",
        ],
    );
    assert_eq!(
        caster_robot::CasterRobot::CONSTRAINTS,
        [
            "left_rolling_1",
            "left_rolling_2",
            "right_rolling",
            "caster_rolling_1",
            "caster_rolling_2"
        ]
    );
}

/// `R_z(psi) R_x(phi) R_y(theta)` by hand.
fn hand_orientation(psi: f64, phi: f64, theta: f64) -> [[[f64; 3]; 3]; 3] {
    let multiply = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        c
    };
    let (sz, cz) = psi.sin_cos();
    let (sx, cx) = phi.sin_cos();
    let (sy, cy) = theta.sin_cos();
    let heading = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
    let lean = multiply(heading, [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]]);
    let disk = multiply(lean, [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]]);
    [heading, lean, disk]
}

#[test]
fn orientations_and_positions_follow_the_rotation_chain() {
    let disk = RollingDisk3d::default();
    let q = [0.3, -1.2, 0.7, 0.4, -2.1];
    assert_eq!(RollingDisk3d::FRAMES, ["heading", "lean", "disk"]);
    assert_eq!(RollingDisk3d::POINTS, ["contact", "center"]);
    let frames = disk.orientations(&q);
    let hand = hand_orientation(q[2], q[3], q[4]);
    for (derived, expected) in frames.iter().zip(&hand) {
        for i in 0..3 {
            for j in 0..3 {
                assert!((derived[i][j] - expected[i][j]).abs() < 1e-14);
            }
        }
    }
    let [contact, center] = disk.positions(&q);
    let lean_z = [hand[1][0][2], hand[1][1][2], hand[1][2][2]];
    assert_eq!(contact, [q[0], q[1], 0.0]);
    for i in 0..3 {
        assert!((center[i] - (contact[i] + disk.r * lean_z[i])).abs() < 1e-14);
    }
}

chaplygin::model! {
    /// A spherical pendulum in Cartesian coordinates, held at length l by
    /// a holonomic constraint.
    pub struct SphericalPendulum {
        coordinates: [x, y, z],
        parameters: [m = 1.0, l = 2.0, g = 9.81],
        points: [bob = origin + x*ground.x + y*ground.y + z*ground.z],
        bodies: [ball = particle(bob, m)],
        gravity: -g*ground.z,
        holonomic: [length = inner(bob - origin, bob - origin) - l^2],
    }
}

#[test]
fn the_holonomic_jacobian_is_the_residuals_derivative() {
    let pendulum = SphericalPendulum::default();
    assert_eq!(SphericalPendulum::HOLONOMIC, ["length"]);
    assert_eq!(SphericalPendulum::CONSTRAINTS, ["length"]);
    let q = [0.4, -0.9, -1.7];
    let [f] = pendulum.holonomic_residual(&q);
    assert!((f - (0.16 + 0.81 + 2.89 - 4.0)).abs() < 1e-14);
    let [row] = Holonomic::holonomic_jacobian(&pendulum, &q);
    let step = 1e-6;
    for i in 0..3 {
        let (mut ahead, mut behind) = (q, q);
        ahead[i] += step;
        behind[i] -= step;
        let difference = (pendulum.holonomic_residual(&ahead)[0]
            - pendulum.holonomic_residual(&behind)[0])
            / (2.0 * step);
        assert!((row[i] - difference).abs() < 1e-8, "column {i}");
    }
    // The velocity form joins the constraint rows: A = df/dq.
    assert_eq!(pendulum.constraint_matrix(&q), [row]);
    // V = m g z.
    assert!((pendulum.energy(&q, &[0.0; 3]) - 9.81 * q[2]).abs() < 1e-14);
}

#[test]
fn models_without_holonomic_constraints_have_none() {
    let disk = RollingDisk3d::default();
    let none: [f64; 0] = Holonomic::holonomic_residual(&disk, &[0.0; 5]);
    assert_eq!(none.len(), 0);
    assert_eq!(Holonomic::<5, 0>::holonomic_names(&disk).len(), 0);
}

/// One classical Runge-Kutta step of `(q, qdot)` under the Lagrange-d'Alembert equations.
fn rk4_step(disk: &RollingDisk3d, q: &mut [f64; 5], qdot: &mut [f64; 5], h: f64) {
    let rate = |q: &[f64; 5], qdot: &[f64; 5]| disk.acceleration(q, qdot, &[0.0; 2]).0;
    let shifted = |base: &[f64; 5], slope: &[f64; 5], by: f64| -> [f64; 5] {
        std::array::from_fn(|i| base[i] + by * slope[i])
    };
    let a1 = rate(q, qdot);
    let (q2, v2) = (shifted(q, qdot, h / 2.0), shifted(qdot, &a1, h / 2.0));
    let a2 = rate(&q2, &v2);
    let (q3, v3) = (shifted(q, &v2, h / 2.0), shifted(qdot, &a2, h / 2.0));
    let a3 = rate(&q3, &v3);
    let (q4, v4) = (shifted(q, &v3, h), shifted(qdot, &a3, h));
    let a4 = rate(&q4, &v4);
    for i in 0..5 {
        q[i] += h / 6.0 * (qdot[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
        qdot[i] += h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i]);
    }
}

/// Steady turning of a uniform disk (Euler's equations about the centre
/// with the contact force from Newton's; e.g. Greenwood, *Advanced
/// Dynamics*, 2003, section 4.4): at lean `phi`, heading rate `Omega` and
/// `u = Omega sin(phi) + thetadot`,
/// `(r/4) Omega^2 sin(phi) cos(phi) - (3r/2) u Omega cos(phi) = g sin(phi)`;
/// the contact point runs on a circle of radius `r |thetadot / Omega|`.
#[test]
fn a_leaning_disk_turns_steadily_as_the_closed_form_says() {
    let disk = RollingDisk3d::default();
    let (r, g) = (disk.r, disk.g);
    let (phi, omega) = (0.3_f64, 4.0_f64);
    let u = (r / 4.0 * omega * omega * phi.sin() * phi.cos() - g * phi.sin())
        / (1.5 * r * omega * phi.cos());
    let spin = u - omega * phi.sin();
    let mut q = [0.0, 0.0, 0.0, phi, 0.0];
    let mut qdot = [r * spin, 0.0, omega, 0.0, spin];
    assert!(
        disk.constraint_residual(&q, &qdot)
            .iter()
            .all(|c| c.abs() < 1e-14)
    );
    let radius = (r * spin / omega).abs();
    let centre = [0.0, r * spin / omega];
    let h = 1e-3;
    for _ in 0..3000 {
        rk4_step(&disk, &mut q, &mut qdot, h);
        assert!((q[3] - phi).abs() < 1e-8, "lean drifts: {}", q[3]);
        assert!(
            (qdot[2] - omega).abs() < 1e-8,
            "heading rate drifts: {}",
            qdot[2]
        );
        assert!((qdot[4] - spin).abs() < 1e-8, "spin drifts: {}", qdot[4]);
        let distance = (q[0] - centre[0]).hypot(q[1] - centre[1]);
        assert!(
            (distance - radius).abs() < 1e-8,
            "off the circle: {distance}"
        );
    }
}

/// A mechanism's error through the build-script door carries the file,
/// line and column of the offending token, as the macro's does.
#[test]
fn a_broken_mechanism_file_is_reported_with_file_line_and_column() {
    let directory = tempfile::Builder::new()
        .prefix("chaplygin-mechanism-door-")
        .tempdir()
        .expect("a scratch directory under the temporary directory");
    let file = directory.path().join("rolling_disk_3d.model");
    let broken =
        rolling_disk_3d::MODEL_TEXT.replace("rotate(heading, x, phi)", "rotate(heding, x, phi)");
    assert_ne!(broken, rolling_disk_3d::MODEL_TEXT);
    std::fs::write(&file, &broken).expect("write");
    let error = chaplygin_codegen::Builder::new()
        .model_file(&file)
        .out_dir(directory.path())
        .write_to_out_dir()
        .expect_err("rejected");
    let line = broken
        .lines()
        .position(|l| l.contains("heding"))
        .expect("line")
        + 1;
    let column = broken
        .lines()
        .nth(line - 1)
        .and_then(|l| l.find("heding"))
        .expect("column")
        + 1;
    let expected = format!(
        "{}:{line}:{column}: error: unknown frame `heding`",
        file.display()
    );
    assert!(
        error.to_string().contains(&expected),
        "{error}\nexpected {expected}"
    );
    assert_eq!(error.to_string().lines().count(), 1, "{error}");
}

/// A `.model` file with mechanism sections runs through the interpreter,
/// mechanism items included, as the compiled model does.
#[test]
fn the_interpreter_runs_a_mechanism_as_compiled() {
    use chaplygin_codegen::interpret::InterpretedModel;
    let interpreted = InterpretedModel::from_source(rolling_disk_3d::MODEL_TEXT).expect("compiles");
    let disk = RollingDisk3d::default();
    let q = [0.3, -1.2, 0.7, 0.4, -2.1];
    let qdot = [0.2, 0.1, -0.5, 0.3, 1.5];
    let (qddot, _) = disk.acceleration(&q, &qdot, &[0.1, -0.2]);
    let interpreted_qddot = interpreted
        .acceleration(&q, &qdot, &[0.1, -0.2])
        .expect("runs")
        .0;
    for (a, b) in qddot.iter().zip(&interpreted_qddot) {
        assert!((a - b).abs() < 1e-12 * (1.0 + a.abs()), "{a} vs {b}");
    }
    let positions = interpreted.call("positions", &[&q]).expect("runs");
    let compiled: Vec<f64> = disk.positions(&q).into_iter().flatten().collect();
    assert_eq!(positions.len(), compiled.len());
    for (a, b) in positions.iter().zip(&compiled) {
        assert!((a - b).abs() < 1e-14, "{a} vs {b}");
    }
}
