//! Every program of every built-in model (`models/*.model`) and of every
//! fixture (`tests/models/*.model`), compiled natively, equals the
//! interpreter to 1e-12 relative at pseudo-random arguments in [-1, 1],
//! the parameters at their defaults.

use chaplygin_codegen::interpret::InterpretedModel;
use chaplygin_codegen::ir::Program;
use chaplygin_jit::NativePrograms;
use std::path::{Path, PathBuf};

/// Arguments drawn per program.
const DRAWS: usize = 3;

/// The largest difference allowed, relative to `max(|interpreted|, 1)`.
const TOLERANCE: f64 = 1e-12;

/// The `.model` files of a directory of the workspace, sorted.
fn model_files(directory: &str) -> Vec<PathBuf> {
    let directory = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(directory);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&directory)
        .unwrap_or_else(|error| panic!("{}: {error}", directory.display()))
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| {
            path.extension()
                .is_some_and(|extension| extension == "model")
        })
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no models in {}", directory.display());
    files
}

/// SplitMix64: a deterministic stream of numbers in [-1, 1].
struct Draws(u64);

impl Draws {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Whether the native value is within [`TOLERANCE`] of the interpreted one
/// (or both are NaN).
fn close(native: f64, interpreted: f64) -> bool {
    (native.is_nan() && interpreted.is_nan())
        || native == interpreted
        || (native - interpreted).abs() <= TOLERANCE * interpreted.abs().max(1.0)
}

/// Compiles every program of the model and compares each with the
/// interpreter at [`DRAWS`] arguments.
fn assert_model_matches(path: &Path, model: &InterpretedModel) {
    let programs: Vec<(&str, &Program)> = model.programs().collect();
    let list: Vec<&Program> = programs.iter().map(|&(_, program)| program).collect();
    let native = NativePrograms::compile_verified(&list).expect("the programs compile");
    assert_eq!(native.len(), programs.len());
    let parameters = model.parameter_values();
    let mut draws = Draws(0x5eed);
    for (index, &(name, program)) in programs.iter().enumerate() {
        for _ in 0..DRAWS {
            let arguments = program.input_count() - parameters.len();
            let inputs: Vec<f64> = (0..arguments)
                .map(|_| draws.next())
                .chain(parameters.iter().copied())
                .collect();
            let expected = program.evaluate_vec(&inputs).expect("the interpreter runs");
            let mut outputs = vec![0.0; expected.len()];
            native
                .evaluate(index, &inputs, &mut outputs)
                .expect("the native code runs");
            for (j, (&got, &wanted)) in outputs.iter().zip(&expected).enumerate() {
                assert!(
                    close(got, wanted),
                    "{} `{name}` (program {index}) output {j} at {inputs:?}: native {got:e}, interpreter {wanted:e}",
                    path.display()
                );
            }
        }
    }
}

#[test]
fn every_program_of_every_built_in_model_equals_the_interpreter() {
    for path in model_files("models") {
        let source = std::fs::read_to_string(&path).expect("the model reads");
        let model = InterpretedModel::from_source(&source)
            .unwrap_or_else(|error| panic!("{}: {error:?}", path.display()));
        assert_model_matches(&path, &model);
    }
}

/// A fixture the interpreter cannot load (one that exists to be rejected)
/// is skipped: there is no reference to compare with.
#[test]
fn every_program_of_every_loadable_fixture_equals_the_interpreter() {
    for path in model_files("tests/models") {
        let source = std::fs::read_to_string(&path).expect("the fixture reads");
        match InterpretedModel::from_source(&source) {
            Ok(model) => assert_model_matches(&path, &model),
            Err(_) => eprintln!("skipped {}: the interpreter rejects it", path.display()),
        }
    }
}
