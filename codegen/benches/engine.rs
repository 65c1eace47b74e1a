//! Benchmark of the symbolic engine on the snakeboard (MATH.md 3.1): the
//! kinetic energy to normal form, the mass matrix by exact second
//! derivatives, its block inverse, the constraint Gram matrix `A g^-1 A^T`,
//! and the lowering of `g^-1` and `A g^-1 A^T` to straight-line code.
//!
//! Run with `cargo bench -p chaplygin-codegen --bench engine`. Before timing,
//! it prints the operation counts of the lowered code before and after CSE.

use chaplygin_codegen::ir;
use chaplygin_codegen::sym::{
    Context, ExprId, Function, Matrix, RationalFunction, SymbolId, SymbolKind,
};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

struct Snakeboard {
    cx: Context,
    coordinates: Vec<SymbolId>,
    velocities: Vec<SymbolId>,
    parameters: Vec<SymbolId>,
    kinetic_energy: ExprId,
    constraints: Vec<ExprId>,
}

fn declare() -> Snakeboard {
    let mut cx = Context::new();
    let coordinates: Vec<SymbolId> = ["x", "y", "theta", "psi", "phi"]
        .iter()
        .map(|n| cx.declare(n, SymbolKind::Coordinate))
        .collect();
    let velocities: Vec<SymbolId> = coordinates.iter().map(|&q| cx.velocity_of(q)).collect();
    let parameters: Vec<SymbolId> = ["m", "r", "jt", "jw"]
        .iter()
        .map(|n| cx.declare(n, SymbolKind::Parameter))
        .collect();
    let [m, r, jt, jw] = [0, 1, 2, 3].map(|i| cx.symbol(parameters[i]));
    let [xd, yd, thd, psid, phid] = [0, 1, 2, 3, 4].map(|i| cx.symbol(velocities[i]));
    let [_, _, theta, _, phi] = [0, 1, 2, 3, 4].map(|i| cx.symbol(coordinates[i]));
    let half = cx.number(chaplygin_codegen::sym::Rational::new(1, 2).expect("1/2"));
    let square = |s: &mut Context, e: ExprId| s.mul2(e, e);
    let r2 = square(&mut cx, r);
    let mr2 = cx.mul2(m, r2);
    let j = cx.add2(jt, mr2);
    let (xd2, yd2, thd2, psid2, phid2) = (
        square(&mut cx, xd),
        square(&mut cx, yd),
        square(&mut cx, thd),
        square(&mut cx, psid),
        square(&mut cx, phid),
    );
    let planar = cx.add2(xd2, yd2);
    let terms = [
        cx.mul(&[half, m, planar]),
        cx.mul(&[half, j, thd2]),
        cx.mul(&[jt, thd, psid]),
        cx.mul(&[half, jt, psid2]),
        cx.mul(&[half, jw, phid2]),
    ];
    let kinetic_energy = cx.add(&terms);
    let constraints = [1i64, -1]
        .map(|sign| {
            let sign_e = cx.integer(sign);
            let signed_phi = cx.mul2(sign_e, phi);
            let angle = cx.add2(theta, signed_phi);
            let s = cx.apply(Function::Sin, angle).expect("sin");
            let c = cx.apply(Function::Cos, angle).expect("cos");
            let cos_phi = cx.apply(Function::Cos, phi).expect("cos");
            let minus_s = cx.neg(s);
            let along = cx.mul2(minus_s, xd);
            let across = cx.mul2(c, yd);
            let turn = cx.mul(&[sign_e, r, cos_phi, thd]);
            cx.add(&[along, across, turn])
        })
        .to_vec();
    Snakeboard {
        cx,
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
        .cx
        .normal(board.kinetic_energy)
        .expect("T is well defined");
    let n = board.velocities.len();
    let mut entries = Vec::with_capacity(n * n);
    for &vi in &board.velocities {
        let first = board
            .cx
            .derivative_of_normal(&energy, vi)
            .expect("dT/dqdot");
        for &vj in &board.velocities {
            entries.push(board.cx.derivative_of_normal(&first, vj).expect("d2T"));
        }
    }
    Matrix::new(n, n, entries).expect("n x n")
}

/// The constraint rows `A`, the coefficients of the velocities.
fn constraint_matrix(board: &mut Snakeboard) -> Matrix {
    let mut entries: Vec<RationalFunction> = Vec::new();
    for &row in &board.constraints.clone() {
        let form = board.cx.normal(row).expect("constraint is well defined");
        for &v in &board.velocities {
            entries.push(
                board
                    .cx
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
    let atoms = board.cx.atoms().clone();
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
    let mut outputs = derived.inverse.to_expressions(&mut board.cx);
    outputs.extend(derived.gram.to_expressions(&mut board.cx));
    let inputs: Vec<SymbolId> = board
        .coordinates
        .iter()
        .chain(&board.parameters)
        .copied()
        .collect();
    let program = ir::lower(&board.cx, &inputs, &outputs).expect("all symbols bound");
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
            |mut board| black_box(board.cx.normal(board.kinetic_energy).expect("normal")),
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
