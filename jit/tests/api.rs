//! The contract of `NativePrograms` beyond the values: the length errors of
//! `Program::evaluate`, the panic on a missing program, sharing between
//! threads.

use chaplygin_codegen::ir::{IrError, Program, lower};
use chaplygin_codegen::sym::{Function, Store, SymbolKind};
use chaplygin_jit::NativePrograms;

/// `sin(a) * b` and `a + b` of the inputs `[a, b]`.
fn two_outputs() -> Program {
    let mut store = Store::new();
    let symbols = [
        store.declare("a", SymbolKind::Coordinate),
        store.declare("b", SymbolKind::Coordinate),
    ];
    let (a, b) = (store.symbol(symbols[0]), store.symbol(symbols[1]));
    let sine = store.apply(Function::Sin, a).expect("sin a");
    let outputs = [store.mul2(sine, b), store.add2(a, b)];
    lower(&store, &symbols, &outputs).expect("the outputs lower")
}

/// The interpreter's error for the same slices.
fn interpreter_error(program: &Program, inputs: &[f64], outputs: usize) -> IrError {
    let mut outputs = vec![0.0; outputs];
    program
        .evaluate(inputs, &mut Vec::new(), &mut outputs)
        .expect_err("the interpreter refuses")
}

#[test]
fn wrong_lengths_fail_as_in_the_interpreter() {
    let program = two_outputs();
    let native = NativePrograms::compile(&[&program]).expect("the program compiles");
    let cases: [(&[f64], usize); 4] = [
        (&[1.0], 2),
        (&[1.0, 2.0, 3.0], 2),
        (&[1.0, 2.0], 1),
        (&[1.0], 3),
    ];
    for (inputs, outputs) in cases {
        let mut buffer = vec![0.0; outputs];
        let error = native
            .evaluate(0, inputs, &mut buffer)
            .expect_err("a wrong length fails");
        assert_eq!(error, interpreter_error(&program, inputs, outputs));
    }
    let mut buffer = [0.0; 3];
    assert_eq!(
        native.evaluate(0, &[1.0, 2.0], &mut buffer),
        Err(IrError::OutputCount {
            expected: 2,
            found: 3
        })
    );
    assert_eq!(
        native.evaluate(0, &[1.0], &mut buffer[..2]),
        Err(IrError::InputCount {
            expected: 2,
            found: 1
        })
    );
}

#[test]
fn a_failed_evaluation_leaves_the_outputs_alone() {
    let program = two_outputs();
    let native = NativePrograms::compile(&[&program]).expect("the program compiles");
    let mut buffer = [7.0; 2];
    assert!(native.evaluate(0, &[1.0], &mut buffer).is_err());
    assert_eq!(buffer, [7.0; 2]);
}

#[test]
#[should_panic(expected = "index out of bounds")]
fn a_missing_program_panics() {
    let program = two_outputs();
    let native = NativePrograms::compile(&[&program]).expect("the program compiles");
    let _ = native.evaluate(1, &[1.0, 2.0], &mut [0.0; 2]);
}

#[test]
fn programs_keep_their_order_and_count() {
    let program = two_outputs();
    let empty = NativePrograms::compile(&[]).expect("nothing compiles");
    assert!(empty.is_empty());
    assert_eq!(empty.len(), 0);
    let native =
        NativePrograms::compile(&[&program, &program, &program]).expect("the programs compile");
    assert_eq!(native.len(), 3);
    assert!(!native.is_empty());
    assert_eq!(format!("{native:?}"), "NativePrograms { programs: 3, .. }");
    let expected = program
        .evaluate_vec(&[0.5, -2.0])
        .expect("the interpreter runs");
    for index in 0..3 {
        let mut outputs = [0.0; 2];
        native
            .evaluate(index, &[0.5, -2.0], &mut outputs)
            .expect("the native code runs");
        assert_eq!(
            outputs.map(f64::to_bits),
            [expected[0].to_bits(), expected[1].to_bits()]
        );
    }
}

#[test]
fn threads_share_and_move_the_code() {
    fn send_and_sync<T: Send + Sync>(value: T) -> T {
        value
    }
    let program = two_outputs();
    let native = send_and_sync(NativePrograms::compile(&[&program]).expect("the program compiles"));
    std::thread::scope(|scope| {
        for k in 0..4 {
            let (native, program) = (&native, &program);
            scope.spawn(move || {
                for i in 0..1000 {
                    let inputs = [f64::from(k) * 0.25, f64::from(i) * 1e-3];
                    let mut outputs = [0.0; 2];
                    native
                        .evaluate(0, &inputs, &mut outputs)
                        .expect("the native code runs");
                    let expected = program.evaluate_vec(&inputs).expect("the interpreter runs");
                    assert_eq!(
                        outputs.map(f64::to_bits),
                        [expected[0].to_bits(), expected[1].to_bits()]
                    );
                }
            });
        }
    });
    let moved = std::thread::spawn(move || native.len())
        .join()
        .expect("the thread ends");
    assert_eq!(moved, 1);
}
