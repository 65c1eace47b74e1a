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
