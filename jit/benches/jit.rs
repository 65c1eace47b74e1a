//! Compiling every program of a model with the JIT, and the per-call time
//! of its `acceleration` and `reduced_rhs_jacobian` programs natively and
//! through the interpreter (`Program::evaluate`), for the snakeboard and the
//! benchmark bicycle.
//!
//! Run with `cargo bench -p chaplygin-jit`.

use chaplygin_codegen::interpret::InterpretedModel;
use chaplygin_codegen::ir::Program;
use chaplygin_jit::NativePrograms;
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

/// The models timed, each `models/<name>.model`.
const MODELS: [&str; 2] = ["snakeboard", "bicycle"];

/// The programs timed per call (chart 0's, where other charts have their own).
const TIMED: [&str; 2] = ["acceleration", "reduced_rhs_jacobian"];

fn model(name: &str) -> InterpretedModel {
    let path = format!("{}/../models/{name}.model", env!("CARGO_MANIFEST_DIR"));
    let source = std::fs::read_to_string(&path).unwrap_or_else(|error| panic!("{path}: {error}"));
    InterpretedModel::from_source(&source).unwrap_or_else(|error| panic!("{path}: {error:?}"))
}

/// The program's inputs: the arguments `0.15 (i mod 8 + 1)`, then the
/// model's parameters.
fn inputs(model: &InterpretedModel, program: &Program) -> Vec<f64> {
    let parameters = model.parameter_values();
    let arguments = program.input_count() - parameters.len();
    (0..arguments)
        .map(|i| 0.15 * (i % 8 + 1) as f64)
        .chain(parameters.iter().copied())
        .collect()
}

fn compile_all(c: &mut Criterion, name: &str, programs: &[&Program]) {
    c.bench_function(&format!("{name}/compile all"), |b| {
        b.iter(|| NativePrograms::compile(black_box(programs)).expect("compiles"))
    });
}

fn per_call(c: &mut Criterion, name: &str, model: &InterpretedModel, native: &NativePrograms) {
    for function in TIMED {
        let Some((index, (_, program))) = model
            .programs()
            .enumerate()
            .find(|(_, (name, _))| *name == function)
        else {
            continue;
        };
        let inputs = inputs(model, program);
        let mut outputs = vec![0.0; program.outputs().len()];
        c.bench_function(&format!("{name}/{function}/native"), |b| {
            b.iter(|| native.evaluate(index, black_box(&inputs), &mut outputs))
        });
        let mut scratch = Vec::new();
        c.bench_function(&format!("{name}/{function}/interpreter"), |b| {
            b.iter(|| program.evaluate(black_box(&inputs), &mut scratch, &mut outputs))
        });
    }
}

fn bench(c: &mut Criterion) {
    for name in MODELS {
        let model = model(name);
        let programs: Vec<&Program> = model.programs().map(|(_, program)| program).collect();
        compile_all(c, name, &programs);
        let native = NativePrograms::compile(&programs).expect("compiles");
        per_call(c, name, &model, &native);
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
