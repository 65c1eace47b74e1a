//! Generated functions, the runtime's integrator steps, its projection
//! onto configuration constraints, its linear algebra on fixed sizes
//! (nalgebra's LU, Cholesky and real Schur form) and a model's reduced form
//! compiled by the JIT from its text allocate nothing:
//! a counting global allocator sees zero allocations across 10^4 calls of each (counted per thread, so tests
//! running in parallel do not see each other's allocations). Non-finite input gives
//! non-finite output, without a panic.

use crate::common::towed::Towed;
use crate::snake3::Snake3;
use chaplygin::energy_control::{ClosedLoop, EnergyController, closed_loop_state};
use chaplygin::jit::{Fixed, JitModel};
use chaplygin::runtime::arrays::matrix_from_rows;
use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, FixedStep, Midpoint, Rk4};
use chaplygin::runtime::linalg::{eigenvalues, solve, solve_positive_definite};
use chaplygin::runtime::linearize::Linearization;
use chaplygin::runtime::projection::Surface;
use chaplygin::runtime::simulate::Observed;
use chaplygin::runtime::system::LagrangeDalembert;
use chaplygin::runtime::system::{Constant, Dalembert, Reduced, ReducedPortHamiltonian};
use chaplygin_models::{
    bicycle::Bicycle, caster_robot::CasterRobot, differential_drive::DifferentialDrive,
    rolling_disk::RollingDisk, rolling_disk_3d::RollingDisk3d, sleigh::Sleigh,
    sleigh_bodies::SleighBodies, snakeboard::Snakeboard, snakeboard_bodies::SnakeboardBodies,
};

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

/// Calls every chart item of a model with several charts of D (the
/// `ReducedPortHamiltonian` chart methods, which call the `..._chart{i}`
/// items) in every chart, at a state of chart 0 moved into each.
macro_rules! chart_items {
    ($model:expr, $type:ty, $t:expr) => {{
        let t: f64 = $t;
        let model = &$model;
        let mut x = [0.0; <$type>::S];
        for (i, value) in x.iter_mut().enumerate() {
            *value = 0.1 * i as f64 + t;
        }
        let u = [0.3 - t; <$type>::P];
        for chart in 0..ReducedPortHamiltonian::charts(model) {
            let x = black_box(model.change_chart(0, chart, black_box(&x)));
            black_box(model.chart_fit(chart, &x));
            black_box(model.chart_rhs(chart, &x, &u));
            black_box(model.chart_rhs_jacobian(chart, &x, &u));
            black_box(model.chart_hamiltonian(chart, &x));
            black_box(model.chart_hamiltonian_gradient(chart, &x));
            black_box(model.chart_structure_matrix(chart, &x));
            black_box(model.chart_input_matrix(chart, &x));
            black_box(model.chart_constraint_violation(chart, &x));
            black_box(model.chart_regularity(chart, &x));
        }
    }};
}

#[test]
fn generated_functions_do_not_allocate() {
    let board = Snakeboard::default();
    let sleigh = Sleigh::default();
    let disk = RollingDisk::default();
    let robot = DifferentialDrive::default();
    let snake = Snake3::default();
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
            reduced_items!(snake, Snake3, t);
        }
    });
    assert_eq!(counted, 0);
    // the counter itself works: a Vec allocates
    assert!(allocations(|| drop(black_box(vec![1u8; 16]))) > 0);
}

chaplygin::model! {
    /// A particle held on a sphere by a holonomic constraint.
    struct OnSphere {
        coordinates: [x, y, z],
        parameters: [m = 1.0, l = 2.0, g = 9.81],
        points: [bob = origin + x*ground.x + y*ground.y + z*ground.z],
        bodies: [ball = particle(bob, m)],
        gravity: -g*ground.z,
        holonomic: [length = norm(bob - origin) - l],
    }
}

/// The items of every model's mechanism: `orientations`, `positions`,
/// `holonomic_residual`, `holonomic_jacobian` (empty for energy-declared
/// models), and the mechanism-declared models' other items.
#[test]
fn mechanism_items_do_not_allocate() {
    let disk = RollingDisk3d::default();
    let sleigh = SleighBodies::default();
    let board = SnakeboardBodies::default();
    let sphere = OnSphere::default();
    let plain = Snakeboard::default();
    let caster = CasterRobot::default();
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-3;
            let q = [t, -t, 0.3 + t, 0.1, 0.2 - t];
            let qdot = [1.0, 0.5, -0.2, t, 0.3];
            let q3 = [t, 0.5, -1.0 - t];
            black_box(disk.orientations(black_box(&q)));
            black_box(disk.positions(black_box(&q)));
            black_box(disk.holonomic_residual(black_box(&q)));
            black_box(disk.holonomic_jacobian(black_box(&q)));
            black_box(disk.acceleration(black_box(&q), black_box(&qdot), &[0.0; 2]));
            black_box(board.orientations(black_box(&q)));
            black_box(board.positions(black_box(&q)));
            black_box(board.acceleration(black_box(&q), black_box(&qdot), &[0.0; 2]));
            black_box(sleigh.orientations(black_box(&q3)));
            black_box(sleigh.positions(black_box(&q3)));
            black_box(sphere.holonomic_residual(black_box(&q3)));
            black_box(sphere.holonomic_jacobian(black_box(&q3)));
            black_box(sphere.positions(black_box(&q3)));
            black_box(plain.orientations(black_box(&q)));
            black_box(plain.positions(black_box(&q)));
            black_box(plain.holonomic_residual(black_box(&q)));
            black_box(plain.holonomic_jacobian(black_box(&q)));
            reduced_items!(disk, RollingDisk3d, t);
            reduced_items!(sleigh, SleighBodies, t);
            reduced_items!(board, SnakeboardBodies, t);
            let q7 = [t, -t, 0.3 + t, 0.1, 0.2 - t, 0.4, t];
            let v7 = [1.0, 0.5, -0.2, t, 0.3, 0.1, -t];
            black_box(caster.orientations(black_box(&q7)));
            black_box(caster.positions(black_box(&q7)));
            black_box(caster.acceleration(black_box(&q7), black_box(&v7), &[0.0; 2]));
            reduced_items!(caster, CasterRobot, t);
            chart_items!(caster, CasterRobot, t);
        }
    });
    assert_eq!(counted, 0);
    assert_eq!(CasterRobot::CHARTS.len(), 2);
}

/// Every item of the benchmark bicycle, the largest built-in model.
#[test]
fn the_bicycles_items_do_not_allocate() {
    let bicycle = Bicycle::default();
    let counted = allocations(|| {
        for i in 0..100 {
            let t = i as f64 * 1e-2;
            let q = [t, -t, 0.3 + t, 0.1, 0.05 - t / 10.0, 0.2 - t, 1.0, -t];
            let qdot = [1.0, 0.5, -0.2, t, 0.3, 0.1, -10.0, -8.0];
            let u = [t, 0.5];
            black_box(bicycle.mass_matrix(black_box(&q)));
            black_box(bicycle.energy(black_box(&q), black_box(&qdot)));
            black_box(bicycle.constraint_matrix(black_box(&q)));
            black_box(bicycle.constraint_residual(black_box(&q), black_box(&qdot)));
            black_box(bicycle.orientations(black_box(&q)));
            black_box(bicycle.positions(black_box(&q)));
            black_box(bicycle.holonomic_residual(black_box(&q)));
            black_box(bicycle.holonomic_jacobian(black_box(&q)));
            black_box(bicycle.acceleration(black_box(&q), black_box(&qdot), black_box(&u)));
            black_box(bicycle.acceleration_jacobian(
                black_box(&q),
                black_box(&qdot),
                black_box(&u),
            ));
            reduced_items!(bicycle, Bicycle, t);
        }
    });
    assert_eq!(counted, 0);
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

#[test]
fn acceleration_jacobian_does_not_allocate() {
    let (board, sleigh, towed) = (Snakeboard::default(), Sleigh::default(), Towed::default());
    let (disk, robot, snake) = (
        RollingDisk::default(),
        DifferentialDrive::default(),
        Snake3::default(),
    );
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-3;
            let q = [t, -t, 0.3 + t, 0.1, 0.2 - t];
            let qdot = [1.0, 0.5, -0.2, t, 0.3];
            let u = [t, 0.5];
            black_box(board.acceleration_jacobian(black_box(&q), black_box(&qdot), black_box(&u)));
            let q3 = [t, 0.5, 0.2 + t];
            let v3 = [1.0, -0.5, t];
            black_box(sleigh.acceleration_jacobian(black_box(&q3), black_box(&v3), &[]));
            let q4 = [t, 0.5, 0.2 + t, 0.3 - t];
            let v4 = [1.0, -0.5, t, 0.7];
            black_box(towed.acceleration_jacobian(black_box(&q4), black_box(&v4), &[t]));
            black_box(disk.acceleration_jacobian(black_box(&q4), black_box(&v4), &[t, 0.2]));
            black_box(robot.acceleration_jacobian(black_box(&q), black_box(&qdot), &[0.1, t]));
            let qs = [0.1 + t; Snake3::N];
            let vs = [0.2 - t; Snake3::N];
            let us = [t; Snake3::P];
            black_box(snake.acceleration_jacobian(black_box(&qs), black_box(&vs), &us));
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
        EnergyController::new(1.0, 2.0, 1.0, &Snakeboard::COORDINATES).expect("phi"),
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

#[test]
fn fixed_size_linear_algebra_does_not_allocate() {
    let board = Snakeboard::default();
    let dalembert = Dalembert::new(&board, |t: f64| [0.1 * t.sin(), -0.02 * t.cos()]);
    let mut y = [0.1, -0.2, 0.3, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0];
    let (mut found, mut regularity) = (0.0, 0.0);
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-3;
            let q = [t, -t, 0.3 + t, 0.1, 0.2 - t];
            let g = board.mass_matrix(black_box(&q));
            let a = board.constraint_matrix(black_box(&q));
            let x = black_box(solve_positive_definite(&g, &q).unwrap());
            let jacobian =
                board.reduced_rhs_jacobian(&[t, 0.0, 0.3, 0.1, 0.2, 1.0, 0.5, t], &[t, 0.0]);
            let shifted: [[f64; 8]; 8] = core::array::from_fn(|r| {
                core::array::from_fn(|c| f64::from(u8::from(r == c)) - 0.1 * jacobian[r][c])
            });
            let z = black_box(solve(&shifted, &[1.0; 8]).unwrap());
            let lambda = black_box(eigenvalues(matrix_from_rows(&jacobian)).unwrap());
            regularity += board.constraint_regularity(black_box(&q));
            found += x[0] + z[0] + lambda[0].re + a[0][0];
            y = Midpoint::default()
                .step(&dalembert, t, black_box(&y), 1e-3)
                .unwrap();
            // the projection onto ker A(q) after each step
            y = dalembert.project(black_box(y)).unwrap();
        }
    });
    assert_eq!(counted, 0);
    assert!(
        found.is_finite() && regularity > 0.0,
        "{found} {regularity}"
    );
    assert!(y.iter().all(|v| v.is_finite()), "{y:?}");
}

/// Keeping a state on its configuration constraint
/// (`projection::Surface`: Newton's projection of `q`, the velocity's
/// projection, the state rebuilt) allocates nothing, in the
/// Lagrange-d'Alembert and the reduced forms.
#[test]
fn keeping_the_configuration_constraints_does_not_allocate() {
    let sphere = OnSphere::default();
    let lagrange = Surface::dalembert(Dalembert::new(&sphere, Constant([])));
    let reduced = Surface::reduced(Reduced::new(&sphere, Constant([])));
    let (mut on_lagrange, mut on_reduced) = (0.0, 0.0);
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-4;
            // off the sphere of radius 2 by about 0.05
            let x = [0.3 + t, 0.4, -1.9, 0.1, t, 0.2];
            let kept = lagrange.project(black_box(x)).unwrap();
            on_lagrange += lagrange.holonomic_residual(&kept).unwrap();
            let kept = reduced
                .project(black_box([0.3 + t, 0.4, -1.9, 0.1, t]))
                .unwrap();
            on_reduced += reduced.holonomic_residual(&kept).unwrap();
        }
    });
    assert_eq!(counted, 0);
    assert!(
        on_lagrange <= 1e-8 && on_reduced <= 1e-8,
        "{on_lagrange} {on_reduced}"
    );
}

/// The snakeboard read from its text and compiled by the JIT, at fixed
/// sizes through the runtime's traits (`chaplygin::jit::Fixed`): once the
/// first calls have grown the input buffer, its reduced form's items, the
/// matrices of its Lagrange-d'Alembert form and the integrator steps on
/// its reduced system allocate nothing, as the generated struct's; and they
/// give the generated struct's values.
#[test]
fn the_jit_compiled_reduced_form_does_not_allocate() {
    let model = JitModel::from_source(chaplygin_models::snakeboard::MODEL_TEXT).expect("derives");
    let jit = Fixed::<5, 2, 2, 0, 2, 1>::new(&model).expect("the snakeboard's sizes");
    let reduced = Reduced::constant(&jit, [0.1, -0.2]);
    let compiled_board = Snakeboard::default();
    let compiled = Reduced::constant(&compiled_board, [0.1, -0.2]);
    let x0 = [0.1, -0.2, 0.3, 0.0, 0.3, 1.0, 0.5, 0.025];
    let u = [0.3, -0.1];
    let items = |x: &[f64; 8]| {
        black_box(jit.hamiltonian(black_box(x)));
        black_box(jit.hamiltonian_gradient(black_box(x)));
        black_box(jit.structure_matrix(black_box(x)));
        black_box(jit.input_matrix(black_box(x)));
        black_box(jit.reduced_rhs(black_box(x), &u));
        black_box(jit.reduced_rhs_jacobian(black_box(x), &u));
        black_box(jit.output(black_box(x)));
        let q: [f64; 5] = core::array::from_fn(|i| x[i]);
        black_box(Linearization::<5, 2, 2>::mass_matrix(&jit, black_box(&q)));
        black_box(Linearization::<5, 2, 2>::constraint_matrix(
            &jit,
            black_box(&q),
        ));
    };
    items(&x0);
    let mut x = x0;
    let counted = allocations(|| {
        for i in 0..10_000 {
            let t = i as f64 * 1e-3;
            items(&x);
            x = Rk4.step(&reduced, t, black_box(&x), 1e-3).unwrap();
            x = DiscreteGradient::default()
                .step(&reduced, t, black_box(&x), 1e-3)
                .unwrap();
        }
    });
    assert_eq!(counted, 0);
    let mut y = x0;
    for i in 0..10_000 {
        let t = i as f64 * 1e-3;
        y = Rk4.step(&compiled, t, &y, 1e-3).unwrap();
        y = DiscreteGradient::default()
            .step(&compiled, t, &y, 1e-3)
            .unwrap();
    }
    let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let difference = x
        .iter()
        .zip(&y)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(difference <= 1e-9 * scale, "JIT {x:?}, compiled {y:?}");
}
