//! Generated functions allocate nothing: a counting global allocator sees
//! zero allocations across 10^4 calls of each.

use chaplygin_models::{
    differential_drive::DifferentialDrive, rolling_disk::RollingDisk, sleigh::Sleigh,
    snakeboard::Snakeboard,
};
use std::alloc::{GlobalAlloc, Layout, System};
use std::hint::black_box;
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `work`.
fn allocations(work: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    work();
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

#[test]
fn generated_functions_do_not_allocate() {
    let board = Snakeboard::default();
    let sleigh = Sleigh::default();
    let disk = RollingDisk::default();
    let robot = DifferentialDrive::default();
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
            let q4 = [t, -t, 0.4 + t, 0.1];
            let v4 = [0.5, -0.25, t, 1.0];
            black_box(disk.mass_matrix(black_box(&q4)));
            black_box(disk.energy(black_box(&q4), black_box(&v4)));
            black_box(disk.constraint_matrix(black_box(&q4)));
            black_box(disk.constraint_residual(black_box(&q4), black_box(&v4)));
            black_box(robot.mass_matrix(black_box(&q)));
            black_box(robot.energy(black_box(&q), black_box(&qdot)));
            black_box(robot.constraint_matrix(black_box(&q)));
            black_box(robot.constraint_residual(black_box(&q), black_box(&qdot)));
        }
    });
    assert_eq!(counted, 0);
    // the counter itself works: a Vec allocates
    assert!(allocations(|| drop(black_box(vec![1u8; 16]))) > 0);
}
