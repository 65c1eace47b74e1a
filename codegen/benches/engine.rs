//! Benchmark of the symbolic engine on the snakeboard (MATH.md 3.1): the
//! kinetic energy to normal form, the mass matrix by exact second
//! derivatives, its block inverse, the constraint Gram matrix `A g^-1 A^T`,
//! and the lowering of `g^-1` and `A g^-1 A^T` to straight-line code.
//!
//! Run with `cargo bench -p chaplygin-codegen --bench engine`. Before timing,
//! it prints the operation counts of the lowered code before and after CSE.

use chaplygin_codegen::ir;
use chaplygin_codegen::sym::{
    ExprId, Function, Matrix, RationalFunction, Store, SymbolId, SymbolKind,
};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

struct Snakeboard {
    store: Store,
    coordinates: Vec<SymbolId>,
    velocities: Vec<SymbolId>,
    parameters: Vec<SymbolId>,
    kinetic_energy: ExprId,
    constraints: Vec<ExprId>,
}

fn declare() -> Snakeboard {
    let mut store = Store::new();
    let coordinates: Vec<SymbolId> = ["x", "y", "theta", "psi", "phi"]
        .iter()
        .map(|n| store.declare(n, SymbolKind::Coordinate))
        .collect();
    let velocities: Vec<SymbolId> = coordinates.iter().map(|&q| store.velocity_of(q)).collect();
    let parameters: Vec<SymbolId> = ["m", "r", "jt", "jw"]
        .iter()
        .map(|n| store.declare(n, SymbolKind::Parameter))
        .collect();
    let [m, r, jt, jw] = [0, 1, 2, 3].map(|i| store.symbol(parameters[i]));
    let [xd, yd, thd, psid, phid] = [0, 1, 2, 3, 4].map(|i| store.symbol(velocities[i]));
    let [_, _, theta, _, phi] = [0, 1, 2, 3, 4].map(|i| store.symbol(coordinates[i]));
    let half = store.number(chaplygin_codegen::sym::Rational::new(1, 2).expect("1/2"));
    let square = |s: &mut Store, e: ExprId| s.mul2(e, e);
    let r2 = square(&mut store, r);
    let mr2 = store.mul2(m, r2);
    let j = store.add2(jt, mr2);
    let (xd2, yd2, thd2, psid2, phid2) = (
        square(&mut store, xd),
        square(&mut store, yd),
        square(&mut store, thd),
        square(&mut store, psid),
        square(&mut store, phid),
    );
    let planar = store.add2(xd2, yd2);
    let terms = [
        store.mul(&[half, m, planar]),
        store.mul(&[half, j, thd2]),
        store.mul(&[jt, thd, psid]),
        store.mul(&[half, jt, psid2]),
        store.mul(&[half, jw, phid2]),
    ];
    let kinetic_energy = store.add(&terms);
    let constraints = [1i64, -1]
        .map(|sign| {
            let sign_e = store.integer(sign);
            let signed_phi = store.mul2(sign_e, phi);
            let angle = store.add2(theta, signed_phi);
            let s = store.apply(Function::Sin, angle).expect("sin");
            let c = store.apply(Function::Cos, angle).expect("cos");
            let cos_phi = store.apply(Function::Cos, phi).expect("cos");
            let minus_s = store.neg(s);
            let along = store.mul2(minus_s, xd);
            let across = store.mul2(c, yd);
            let turn = store.mul(&[sign_e, r, cos_phi, thd]);
            store.add(&[along, across, turn])
        })
        .to_vec();
    Snakeboard {
        store,
        coordinates,
        velocities,
        parameters,
        kinetic_energy,
        constraints,
    }
}

/// The mass matrix `d^2 T / d qdot_i d qdot_j`, exactly.
fn mass_matrix(board: &mut Snakeboard) -> Matrix {
    let energy = board
        .store
        .normal(board.kinetic_energy)
        .expect("T is well defined");
    let n = board.velocities.len();
    let mut entries = Vec::with_capacity(n * n);
    for &vi in &board.velocities {
        let first = board
            .store
            .derivative_of_normal(&energy, vi)
            .expect("dT/dqdot");
        for &vj in &board.velocities {
            entries.push(board.store.derivative_of_normal(&first, vj).expect("d2T"));
        }
    }
    Matrix::new(n, n, entries).expect("n x n")
}

/// The constraint rows `A`, the coefficients of the velocities.
fn constraint_matrix(board: &mut Snakeboard) -> Matrix {
    let mut entries: Vec<RationalFunction> = Vec::new();
    for &row in &board.constraints.clone() {
        let form = board.store.normal(row).expect("constraint is well defined");
        for &v in &board.velocities {
            entries.push(
                board
                    .store
                    .derivative_of_normal(&form, v)
                    .expect("coefficient"),
            );
        }
    }
    Matrix::new(board.constraints.len(), board.velocities.len(), entries).expect("c x n")
}

struct Derived {
    inverse: Matrix,
    gram: Matrix,
}

fn derive(board: &mut Snakeboard) -> Derived {
    let g = mass_matrix(board);
    let a = constraint_matrix(board);
    let atoms = board.store.atoms().clone();
    let inverse = g.inverse(&atoms).expect("g is invertible");
    let gram = a
        .mul(&inverse, &atoms)
        .and_then(|p| p.mul(&a.transpose(), &atoms))
        .expect("sizes fit");
    Derived { inverse, gram }
}

fn report_operation_counts() {
    let mut board = declare();
    let derived = derive(&mut board);
    let mut outputs = derived.inverse.to_expressions(&mut board.store);
    outputs.extend(derived.gram.to_expressions(&mut board.store));
    let inputs: Vec<SymbolId> = board
        .coordinates
        .iter()
        .chain(&board.parameters)
        .copied()
        .collect();
    let program = ir::lower(&board.store, &inputs, &outputs).expect("all symbols bound");
    let counts = program.operation_count();
    println!(
        "snakeboard g^-1 and A g^-1 A^T: {} operations before CSE, {} after",
        counts.before_cse, counts.after_cse
    );
}

fn bench_engine(c: &mut Criterion) {
    report_operation_counts();
    c.bench_function("snakeboard/normal_form_of_kinetic_energy", |b| {
        b.iter_batched(
            declare,
            |mut board| black_box(board.store.normal(board.kinetic_energy).expect("normal")),
            criterion::BatchSize::SmallInput,
        )
    });
    c.bench_function("snakeboard/mass_matrix_by_second_derivatives", |b| {
        b.iter_batched(
            declare,
            |mut board| black_box(mass_matrix(&mut board)),
            criterion::BatchSize::SmallInput,
        )
    });
    c.bench_function("snakeboard/derive_inverse_and_constraint_gram", |b| {
        b.iter_batched(
            declare,
            |mut board| black_box(derive(&mut board).gram),
            criterion::BatchSize::SmallInput,
        )
    });
}

criterion_group!(benches, bench_engine);
criterion_main!(benches);
