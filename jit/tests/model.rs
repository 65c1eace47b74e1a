//! A model loaded on the JIT: every function of the interpreted model, run
//! as native code, with the interpreter's values; errors of the text with
//! their line and column.

use chaplygin_codegen::document::{Format, derive_document};
use chaplygin_codegen::interpret::InterpretedModel;
use chaplygin_codegen::interpret::{Backend, Engine, Interpreter};
use chaplygin_codegen::ir::Program;
use chaplygin_jit::{JitModel, LoadError, Native, OnDemand};
use std::cell::RefCell;

const SNAKEBOARD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/snakeboard.model");

/// MATH.md 3.1 at a state: `alpha1dot = -(sin phi / r) u1`, `alpha2dot = u1`,
/// `alpha3dot = u2`, `phidot = alpha3 / Jw`; and every function's values
/// equal the interpreter's bit for bit.
#[test]
fn the_snakeboard_on_the_jit_is_the_interpreted_snakeboard() {
    let mut jit = JitModel::from_file(SNAKEBOARD).expect("loads");
    assert_eq!(jit.engine().name(), "jit");
    jit.set_parameter("jw", 0.07).expect("declared");
    let text = std::fs::read_to_string(SNAKEBOARD).expect("reads");
    let mut interpreted = InterpretedModel::from_source(&text).expect("loads");
    interpreted.set_parameter("jw", 0.07).expect("declared");
    assert_eq!(interpreted.engine().name(), "interpret");
    let phi = 0.7f64;
    let x = [0.1, -0.2, 0.4, 0.3, phi, 1.3, -0.6, 0.8];
    let u = [0.25, -1.5];
    let xdot = jit.reduced_rhs(&x, &u).expect("evaluates");
    let r = 0.5;
    assert!((xdot[5] + phi.sin() / r * u[0]).abs() < 1e-15);
    assert_eq!(xdot[6], u[0]);
    assert_eq!(xdot[7], u[1]);
    assert!((xdot[4] - 0.8 / 0.07).abs() < 1e-12);
    for name in ["reduced_rhs", "reduced_rhs_jacobian"] {
        let native = jit.call(name, &[&x, &u]).expect("evaluates");
        let reference = interpreted.call(name, &[&x, &u]).expect("evaluates");
        let bits = |values: &[f64]| values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&native), bits(&reference), "{name}");
    }
}

/// A misspelt coordinate is reported at its line and column, a missing file
/// by its path.
#[test]
fn bad_text_and_missing_files_are_errors() {
    let text = "pub struct Broken {\n    coordinates: [x],\n    kinetic_energy: dot(y)^2,\n}\n";
    match JitModel::from_source(text) {
        Err(LoadError::Model {
            diagnostics,
            rendered,
        }) => {
            assert!(!diagnostics.is_empty());
            assert!(rendered.starts_with("model:3:"), "{rendered}");
        }
        other => panic!("expected a model error, got {other:?}"),
    }
    let missing = JitModel::from_file("/nonexistent/model.model");
    assert!(
        matches!(&missing, Err(LoadError::Read { path, .. }) if path == "/nonexistent/model.model"),
        "{missing:?}"
    );
}

/// The engine of a loaded model compiles a program the first time it runs
/// and no other: after one call of each of two functions two programs are
/// native, and every program gives the interpreter's bits.
#[test]
fn programs_are_compiled_when_first_run() {
    let text = std::fs::read_to_string(SNAKEBOARD).expect("reads");
    let model = InterpretedModel::from_source(&text).expect("loads");
    let programs: Vec<_> = model.programs().map(|(_, program)| program).collect();
    let engine = OnDemand::new(programs.len());
    assert_eq!(engine.compiled(), 0);
    let run = |index: usize| {
        let program = programs[index];
        let inputs: Vec<f64> = (0..program.input_count())
            .map(|i| 0.1 * i as f64 - 0.4)
            .collect();
        let mut native = vec![0.0; program.outputs().len()];
        engine
            .evaluate(index, program, &inputs, &mut native)
            .expect("runs");
        let reference = program.evaluate_vec(&inputs).expect("runs");
        let bits = |values: &[f64]| values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&native), bits(&reference), "program {index}");
    };
    run(3);
    run(3);
    run(5);
    assert_eq!(engine.compiled(), 2);
    (0..programs.len()).for_each(run);
    assert_eq!(engine.compiled(), programs.len());
}

/// A model loaded on the native backend searches for where its charts of D
/// degenerate on that backend too: the backend makes an engine of the
/// search's one program, then one of the model's programs, and the search
/// finds what it finds on the interpreter (the engines agree bit for bit);
/// so does the derivation document made on it.
#[test]
fn the_chart_search_runs_on_the_backend_the_model_loads_on() {
    struct Recording {
        native: Native,
        programs: RefCell<Vec<usize>>,
    }
    impl Backend for Recording {
        fn engine(&self, programs: &[&Program]) -> Box<dyn Engine> {
            self.programs.borrow_mut().push(programs.len());
            self.native.engine(programs)
        }
    }
    let text = include_str!("../../tests/models/sleigh_no_symmetry.model");
    let recording = Recording {
        native: Native::for_host().expect("Cranelift supports the host"),
        programs: RefCell::default(),
    };
    let native = InterpretedModel::from_source_on(text, &recording).expect("loads");
    let interpreted = InterpretedModel::from_source(text).expect("loads");
    assert_eq!(native.engine().name(), "jit");
    let made = recording.programs.take();
    assert_eq!(made, [1, native.programs().count()]);
    assert!(
        native.report().contains("cos(theta)"),
        "{}",
        native.report()
    );
    assert_eq!(native.report(), interpreted.report());
    let document = |backend: &dyn Backend| {
        derive_document(text, Format::Text, backend).expect("the model derives")
    };
    let on_native = document(&recording.native);
    assert!(on_native.contains("cos(theta)"), "{on_native}");
    assert_eq!(on_native, document(&Interpreter));
}

/// A bead in the plane, `V = k/2 atan2(y, x)^2 + c atan(x y) + asin(x/3)
/// acos(y/3)`: `qddot = -grad V / m`, the gradient from the slopes of
/// `f64`'s functions, on the JIT and on the interpreter.
const INVERSE_BEAD: &str = "
    pub struct InverseBead {
        coordinates: [x, y],
        parameters: [m = 2.0, k = 3.0, c = 0.5],
        define: [angle = atan2(y, x)],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2),
        potential_energy: k/2*angle^2 + c*atan(x*y) + asin(x/3)*acos(y/3),
    }
";

#[test]
fn inverse_functions_run_as_f64_computes_them() {
    let (m, k, c) = (2.0, 3.0, 0.5);
    for (x, y) in [(-0.8f64, 0.6f64), (0.5, -1.1), (-1.3, -0.2)] {
        let radius_square = x * x + y * y;
        let angle = y.atan2(x);
        let by_product = 1.0 + (x * y).powi(2);
        let d_asin = (1.0 / 3.0) / (1.0 - x * x / 9.0).sqrt();
        let d_acos = -(1.0 / 3.0) / (1.0 - y * y / 9.0).sqrt();
        let gradient = [
            -k * angle * y / radius_square + c * y / by_product + d_asin * (y / 3.0).acos(),
            k * angle * x / radius_square + c * x / by_product + (x / 3.0).asin() * d_acos,
        ];
        let jit = JitModel::from_source(INVERSE_BEAD).expect("loads");
        let interpreted = InterpretedModel::from_source(INVERSE_BEAD).expect("loads");
        for model in [&*jit, &interpreted] {
            let (qddot, _) = model
                .acceleration(&[x, y], &[0.3, -0.2], &[])
                .expect("runs");
            for (a, g) in qddot.iter().zip(gradient) {
                assert!(
                    (a + g / m).abs() < 1e-13,
                    "{qddot:?} vs {gradient:?} at ({x}, {y})"
                );
            }
        }
    }
}

/// Two steering arms tied by the Ackermann condition, the right angle
/// `f(delta_l) = atan(l tan(delta_l) / (l + 2 b tan(delta_l)))`: with
/// `delta_r = f(delta_l)` the arms (particles at radius `w`) have the
/// inertia `I = m w^2 (1 + f'^2)`, so `I delta_l'' + I'/2 delta_l'^2 = u`.
const ACKERMANN: &str = "
    pub struct Ackermann {
        coordinates: [delta_l, delta_r],
        parameters: [m = 1.5, w = 0.3, l = 1.2, b = 0.4],
        define: [ratio = l*tan(delta_l)/(l + 2*b*tan(delta_l))],
        frames: [left = rotate(ground, z, delta_l), right = rotate(ground, z, delta_r)],
        points: [
            left_tip = origin + b*ground.y + w*left.x,
            right_tip = origin - b*ground.y + w*right.x,
        ],
        bodies: [left_arm = particle(left_tip, m), right_arm = particle(right_tip, m)],
        holonomic: [ackermann = delta_r - atan(ratio)],
        inputs: [steer = delta_l],
    }
";

#[test]
fn a_holonomic_constraint_written_with_atan_derives_and_runs() {
    let (m, w, l, b) = (1.5, 0.3, 1.2, 0.4);
    let f = |delta: f64| (l * delta.tan() / (l + 2.0 * b * delta.tan())).atan();
    let h = 1e-4;
    let delta: f64 = 0.35;
    let slope = (f(delta + h) - f(delta - h)) / (2.0 * h);
    let curvature = (f(delta + h) - 2.0 * f(delta) + f(delta - h)) / (h * h);
    let (rate, u) = (0.8, 0.05);
    let inertia = m * w * w * (1.0 + slope * slope);
    let expected = (u - m * w * w * slope * curvature * rate * rate) / inertia;
    let jit = JitModel::from_source(ACKERMANN).expect("derives");
    let interpreted = InterpretedModel::from_source(ACKERMANN).expect("derives");
    for model in [&*jit, &interpreted] {
        let q = [delta, f(delta) + 0.01];
        let residual = model.call("holonomic_residual", &[&q]).expect("runs");
        assert!((residual[0] - 0.01).abs() < 1e-15, "{residual:?}");
        let q = [delta, f(delta)];
        let (qddot, _) = model
            .acceleration(&q, &[rate, slope * rate], &[u])
            .expect("runs");
        assert!(
            (qddot[0] - expected).abs() < 1e-6,
            "{qddot:?} vs {expected}"
        );
        let right = slope * qddot[0] + curvature * rate * rate;
        assert!((qddot[1] - right).abs() < 1e-6, "{qddot:?} vs {right}");
    }
}
