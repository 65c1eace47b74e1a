//! Running native code allocates nothing: a counting global allocator sees
//! no allocation across 10^4 evaluations of every program of a model
//! (counted per thread, so tests running in parallel do not see each
//! other's allocations).

use chaplygin_codegen::interpret::InterpretedModel;
use chaplygin_codegen::ir::Program;
use chaplygin_jit::NativePrograms;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::hint::black_box;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Counts an allocation on this thread (not during thread teardown).
fn count_one() {
    let _ = ALLOCATIONS.try_with(|count| count.set(count.get() + 1));
}

fn allocations_so_far() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_one();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_one();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn evaluation_allocates_nothing() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/snakeboard.model");
    let source = std::fs::read_to_string(path).expect("the model reads");
    let model = InterpretedModel::from_source(&source).expect("the model loads");
    let programs: Vec<&Program> = model.programs().map(|(_, program)| program).collect();
    let native = NativePrograms::compile(&programs).expect("the programs compile");
    let mut buffers: Vec<(Vec<f64>, Vec<f64>)> = programs
        .iter()
        .map(|program| {
            let inputs = (0..program.input_count())
                .map(|i| 0.1 * i as f64 + 0.3)
                .collect();
            (inputs, vec![0.0; program.outputs().len()])
        })
        .collect();
    let before = allocations_so_far();
    for _ in 0..10_000 {
        for (index, (inputs, outputs)) in buffers.iter_mut().enumerate() {
            native
                .evaluate(index, black_box(inputs), outputs)
                .expect("the native code runs");
            black_box(&outputs);
        }
    }
    assert_eq!(allocations_so_far() - before, 0);
}
