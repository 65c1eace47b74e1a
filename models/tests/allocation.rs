//! Generated functions allocate nothing: a counting global allocator sees
//! zero allocations across 10^4 calls of each.

use chaplygin_models::{sleigh::Sleigh, snakeboard::Snakeboard};
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

/// One call of every reduced port-Hamiltonian item of both models.
fn reduced_items(board: &Snakeboard, sleigh: &Sleigh, t: f64) {
    let q = [t, -t, 0.3 + t, 0.1, 0.2 - t];
    let qdot = black_box(board.velocities(black_box(&q), black_box(&[0.5, t, -0.2])));
    let alpha = black_box(board.momenta(black_box(&q), &qdot));
    let x = [q[0], q[1], q[2], q[3], q[4], alpha[0], alpha[1], alpha[2]];
    let u = [0.3, -t];
    black_box(board.hamiltonian(black_box(&x)));
    black_box(board.hamiltonian_gradient(black_box(&x)));
    black_box(board.structure_matrix(black_box(&x)));
    black_box(board.input_matrix(black_box(&x)));
    black_box(board.reduced_rhs(black_box(&x), black_box(&u)));
    black_box(board.reduced_rhs_jacobian(black_box(&x), black_box(&u)));
    black_box(board.output(black_box(&x)));
    let q3 = [t, 0.5, 0.2 + t];
    let v3 = black_box(sleigh.velocities(black_box(&q3), black_box(&[1.0, t])));
    let alpha3 = black_box(sleigh.momenta(black_box(&q3), &v3));
    let x3 = [q3[0], q3[1], q3[2], alpha3[0], alpha3[1]];
    black_box(sleigh.hamiltonian(black_box(&x3)));
    black_box(sleigh.hamiltonian_gradient(black_box(&x3)));
    black_box(sleigh.structure_matrix(black_box(&x3)));
    black_box(sleigh.input_matrix(black_box(&x3)));
    black_box(sleigh.reduced_rhs(black_box(&x3), black_box(&[])));
    black_box(sleigh.reduced_rhs_jacobian(black_box(&x3), black_box(&[])));
    black_box(sleigh.output(black_box(&x3)));
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
            reduced_items(&board, &sleigh, t);
        }
    });
    assert_eq!(counted, 0);
    // the counter itself works: a Vec allocates
    assert!(allocations(|| drop(black_box(vec![1u8; 16]))) > 0);
}
