//! Generated functions and the runtime's integrator steps allocate nothing:
//! a counting global allocator sees zero allocations across 10^4 calls of each (counted per thread, so tests
//! running in parallel do not see each other's allocations). Non-finite input gives
//! non-finite output, without a panic.

mod common;

use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, FixedStep, Midpoint, Rk4};
use chaplygin::runtime::system::{Dalembert, Reduced, ReducedPortHamiltonian};
use chaplygin_models::energy_control::{ClosedLoop, EnergyController, closed_loop_state};
use chaplygin_models::{
    differential_drive::DifferentialDrive, rolling_disk::RollingDisk, sleigh::Sleigh,
    snakeboard::Snakeboard,
};
use common::towed::Towed;
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

/// One call of every reduced port-Hamiltonian item of both models.
/// Calls every reduced port-Hamiltonian item of a model once, at a state
/// built from `t` through `velocities` and `momenta`.
macro_rules! reduced_items {
    ($model:expr, $type:ty, $t:expr) => {{
        let t: f64 = $t;
        let mut q = [0.0; <$type>::N];
        for (i, value) in q.iter_mut().enumerate() {
            *value = 0.1 * i as f64 + t;
        }
        let mut seed = [0.0; <$type>::K];
        for (i, value) in seed.iter_mut().enumerate() {
            *value = 0.5 - 0.2 * i as f64 + t;
        }
        let qdot = black_box($model.velocities(black_box(&q), black_box(&seed)));
        let alpha = black_box($model.momenta(black_box(&q), &qdot));
        let mut x = [0.0; <$type>::S];
        x[..<$type>::N].copy_from_slice(&q);
        x[<$type>::N..].copy_from_slice(&alpha);
        let u = [0.3 - t; <$type>::P];
        black_box($model.hamiltonian(black_box(&x)));
        black_box($model.hamiltonian_gradient(black_box(&x)));
        black_box($model.structure_matrix(black_box(&x)));
        black_box($model.input_matrix(black_box(&x)));
        black_box($model.reduced_rhs(black_box(&x), black_box(&u)));
        black_box($model.reduced_rhs_jacobian(black_box(&x), black_box(&u)));
        black_box($model.output(black_box(&x)));
    }};
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
            reduced_items!(board, Snakeboard, t);
            reduced_items!(sleigh, Sleigh, t);
            reduced_items!(disk, RollingDisk, t);
            reduced_items!(robot, DifferentialDrive, t);
        }
    });
    assert_eq!(counted, 0);
    // the counter itself works: a Vec allocates
    assert!(allocations(|| drop(black_box(vec![1u8; 16]))) > 0);
}

#[test]
fn acceleration_does_not_allocate() {
    let (board, sleigh, towed) = (Snakeboard::default(), Sleigh::default(), Towed::default());
    let (disk, robot) = (RollingDisk::default(), DifferentialDrive::default());
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
            black_box(disk.acceleration(black_box(&q4), black_box(&v4), black_box(&[t, 0.2])));
            black_box(robot.acceleration(black_box(&q), black_box(&qdot), black_box(&[0.1, t])));
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

#[test]
fn integrator_steps_do_not_allocate() {
    let board = Snakeboard::default();
    let reduced = Reduced::constant(&board, [0.1, -0.2]);
    // phi'' = -0.4 cos t from rest at phi = 0.3: phi stays in [-0.5, 0.3]
    let dalembert = Dalembert::new(&board, |t: f64| [0.1 * t.sin(), -0.02 * t.cos()]);
    let tight = DormandPrince {
        rtol: 1e-10,
        atol: 1e-10,
        ..Default::default()
    };
    let (mut x, mut y) = (
        [0.1, -0.2, 0.3, 0.0, 0.3, 1.0, 0.5, 0.025],
        [0.1, -0.2, 0.3, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0],
    );
    let closed_loop = ClosedLoop::new(
        board,
        EnergyController {
            a: 1.0,
            kt: 2.0,
            kw: 1.0,
        },
    );
    let mut z = closed_loop_state(&[0.0, 0.0, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0], 1.0, 0.5);
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-3;
            x = Rk4.step(&reduced, t, black_box(&x), 1e-3).unwrap();
            x = Midpoint::default()
                .step(&reduced, t, black_box(&x), 1e-3)
                .unwrap();
            y = Rk4.step(&dalembert, t, black_box(&y), 1e-3).unwrap();
            z = Midpoint::default()
                .step(&closed_loop, t, black_box(&z), 1e-3)
                .unwrap();
            z = DiscreteGradient::default()
                .step(&closed_loop, t, black_box(&z), 1e-3)
                .unwrap();
            black_box(board.regularity(black_box(&x)));
            black_box(board.constraint_violation(black_box(&x)));
        }
        x = tight
            .integrate(&reduced, (0.0, black_box(x)), 1.0)
            .unwrap()
            .x;
    });
    assert_eq!(counted, 0);
    assert!(
        x.iter().chain(&y).chain(&z).all(|v| v.is_finite()),
        "{x:?} {y:?} {z:?}"
    );
}
