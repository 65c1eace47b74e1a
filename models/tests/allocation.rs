//! Generated functions allocate nothing: a counting global allocator sees
//! zero allocations across 10^4 calls of each (counted per thread, so tests
//! running in parallel do not see each other's allocations). Non-finite input gives
//! non-finite output, without a panic.

mod common;

use chaplygin_models::{sleigh::Sleigh, snakeboard::Snakeboard};
use common::Towed;
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

/// Allocations made by `work`.
fn allocations(work: impl FnOnce()) -> usize {
    let before = allocations_so_far();
    work();
    allocations_so_far() - before
}

#[test]
fn generated_functions_do_not_allocate() {
    let board = Snakeboard::default();
    let sleigh = Sleigh::default();
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-3;
            let q = [t, -t, 0.3 + t, 0.1, 0.2 - t];
            let qdot = [1.0, 0.5, -0.2, t, 0.3];
            black_box(board.mass_matrix(black_box(&q)));
            black_box(board.energy(black_box(&q), black_box(&qdot)));
            black_box(board.constraint_matrix(black_box(&q)));
            black_box(board.constraint_residual(black_box(&q), black_box(&qdot)));
            let q3 = [t, 0.5, 0.2 + t];
            let v3 = [1.0, -0.5, t];
            black_box(sleigh.mass_matrix(black_box(&q3)));
            black_box(sleigh.energy(black_box(&q3), black_box(&v3)));
            black_box(sleigh.constraint_matrix(black_box(&q3)));
            black_box(sleigh.constraint_residual(black_box(&q3), black_box(&v3)));
        }
    });
    assert_eq!(counted, 0);
    // the counter itself works: a Vec allocates
    assert!(allocations(|| drop(black_box(vec![1u8; 16]))) > 0);
}

#[test]
fn acceleration_does_not_allocate() {
    let (board, sleigh, towed) = (Snakeboard::default(), Sleigh::default(), Towed::default());
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-3;
            let q = [t, -t, 0.3 + t, 0.1, 0.2 - t];
            let qdot = [1.0, 0.5, -0.2, t, 0.3];
            black_box(board.acceleration(black_box(&q), black_box(&qdot), black_box(&[t, 0.5])));
            let q3 = [t, 0.5, 0.2 + t];
            let v3 = [1.0, -0.5, t];
            black_box(sleigh.acceleration(black_box(&q3), black_box(&v3), black_box(&[])));
            let q4 = [t, 0.5, 0.2 + t, 0.3 - t];
            let v4 = [1.0, -0.5, t, 0.7];
            black_box(towed.acceleration(black_box(&q4), black_box(&v4), black_box(&[t])));
        }
    });
    assert_eq!(counted, 0);
    // the counter itself works: a Vec allocates
    assert!(allocations(|| drop(black_box(vec![1u8; 16]))) > 0);
}

fn has_non_finite(values: &[f64]) -> bool {
    values.iter().any(|v| !v.is_finite())
}

#[test]
fn non_finite_input_gives_non_finite_acceleration() {
    let (board, sleigh, towed) = (Snakeboard::default(), Sleigh::default(), Towed::default());
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let (qddot, lambda) = board.acceleration(&[0.1, 0.2, bad, 0.4, 0.5], &[1.0; 5], &[0.0; 2]);
        assert!(
            has_non_finite(&qddot) && has_non_finite(&lambda),
            "{qddot:?} {lambda:?}"
        );
        let (qddot, lambda) = sleigh.acceleration(&[0.1, 0.2, 0.3], &[1.0, bad, 0.5], &[]);
        assert!(
            has_non_finite(&qddot) && has_non_finite(&lambda),
            "{qddot:?} {lambda:?}"
        );
        // the run-time solve: a non-finite input spreads through the elimination
        let (qddot, lambda) = towed.acceleration(&[0.1, 0.2, 0.3, 0.4], &[1.0; 4], &[bad]);
        assert!(
            has_non_finite(&qddot) && has_non_finite(&lambda),
            "{qddot:?} {lambda:?}"
        );
        let (qddot, lambda) = towed.acceleration(&[0.1, 0.2, bad, 0.4], &[1.0; 4], &[0.0]);
        assert!(
            has_non_finite(&qddot) && has_non_finite(&lambda),
            "{qddot:?} {lambda:?}"
        );
    }
}
