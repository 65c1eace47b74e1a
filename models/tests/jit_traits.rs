//! Every built-in model read from its text, its programs compiled to
//! native code by the JIT, seen through the runtime's traits at its sizes
//! (`chaplygin_codegen::interpret::Fixed`), against the rustc-compiled
//! model through the same traits: each item of every formulation (the
//! reduced form in every chart derived at build time and the first
//! run-time chart, the Lagrange-d'Alembert equations and their Jacobians,
//! the configuration constraints, the momenta, the momentum equation, the
//! names and the guards) at pseudo-random states, to 1e-12 relative to the
//! largest entry of each result; and a run of `Simulation` on the reduced
//! form of each, the runtime's own systems over both models.

use crate::common::random::Random;
use chaplygin::jit::JitModel;
use chaplygin::jit::{Fixed, SizeMismatch};
use chaplygin::runtime::integrate::Midpoint;
use chaplygin::runtime::law::Feedback;
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::linearize::Linearization;
use chaplygin::runtime::nalgebra::Const;
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::Simulation;
use chaplygin::runtime::system::{
    Domain, Holonomic, LagrangeDalembert, ModelNames, Momenta, MomentumEquations, Reduced,
    ReducedPortHamiltonian,
};
use chaplygin_models::{
    bicycle::Bicycle, caster_robot::CasterRobot, differential_drive::DifferentialDrive,
    rolling_disk::RollingDisk, rolling_disk_3d::RollingDisk3d, sleigh::Sleigh,
    sleigh_bodies::SleighBodies, snakeboard::Snakeboard, snakeboard_bodies::SnakeboardBodies,
    three_link_snake::ThreeLinkSnake,
};

const TOLERANCE: f64 = 1e-12;
const STATES: usize = 20;

/// Asserts `jit` equals `compiled` entry by entry to [`TOLERANCE`] times
/// the largest entry (NaN where the compiled value is NaN); counts them.
fn same(compared: &mut usize, what: &str, compiled: &[f64], jit: &[f64]) {
    assert_eq!(compiled.len(), jit.len(), "{what}: lengths");
    let scale = compiled
        .iter()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, (a, b)) in compiled.iter().zip(jit).enumerate() {
        let agree = match a.is_nan() {
            true => b.is_nan(),
            false => (a - b).abs() <= TOLERANCE * scale.max(f64::MIN_POSITIVE),
        };
        assert!(agree, "{what}[{i}]: rustc {a:e}, jit {b:e}");
        *compared += usize::from(a.is_finite());
    }
}

/// The reduced form in `chart` at `x` with inputs `u`.
fn reduced_items<M, const S: usize, const P: usize>(
    model: &M,
    chart: usize,
    x: &[f64; S],
    u: &[f64; P],
) -> Vec<(&'static str, Vec<f64>)>
where
    M: ReducedPortHamiltonian<S, P>,
{
    vec![
        ("chart_rhs", model.chart_rhs(chart, x, u).to_vec()),
        (
            "chart_rhs_jacobian",
            model
                .chart_rhs_jacobian(chart, x, u)
                .as_flattened()
                .to_vec(),
        ),
        ("chart_hamiltonian", vec![model.chart_hamiltonian(chart, x)]),
        (
            "chart_hamiltonian_gradient",
            model.chart_hamiltonian_gradient(chart, x).to_vec(),
        ),
        (
            "chart_structure_matrix",
            model
                .chart_structure_matrix(chart, x)
                .as_flattened()
                .to_vec(),
        ),
        (
            "chart_input_matrix",
            model.chart_input_matrix(chart, x).as_flattened().to_vec(),
        ),
        (
            "chart_constraint_violation",
            vec![model.chart_constraint_violation(chart, x)],
        ),
        ("chart_regularity", vec![model.chart_regularity(chart, x)]),
        ("chart_fit", vec![model.chart_fit(chart, x)]),
        ("change_chart", model.change_chart(0, chart, x).to_vec()),
    ]
}

/// The Lagrange-d'Alembert items and the configuration constraints at
/// `(q, qdot, u)`.
fn dalembert_items<M, const N: usize, const C: usize, const P: usize, const H: usize>(
    model: &M,
    q: &[f64; N],
    qdot: &[f64; N],
    u: &[f64; P],
) -> Vec<(&'static str, Vec<f64>)>
where
    M: Linearization<N, C, P> + Holonomic<N, H> + Domain,
{
    let (qddot, lambda) = model.acceleration(q, qdot, u);
    let (by_q, by_qdot, by_u) = model.acceleration_jacobian(q, qdot, u);
    let mut domain = vec![0.0; model.guards().len()];
    model.domain(q, &mut domain);
    vec![
        ("qddot", qddot.to_vec()),
        ("lambda", lambda.to_vec()),
        ("energy", vec![LagrangeDalembert::energy(model, q, qdot)]),
        (
            "constraint_residual",
            LagrangeDalembert::constraint_residual(model, q, qdot).to_vec(),
        ),
        (
            "constraint_regularity",
            vec![model.constraint_regularity(q)],
        ),
        ("mass_matrix", model.mass_matrix(q).as_flattened().to_vec()),
        (
            "constraint_matrix",
            model.constraint_matrix(q).as_flattened().to_vec(),
        ),
        ("d qddot/dq", by_q.as_flattened().to_vec()),
        ("d qddot/dqdot", by_qdot.as_flattened().to_vec()),
        ("d qddot/du", by_u.as_flattened().to_vec()),
        ("holonomic_residual", model.holonomic_residual(q).to_vec()),
        (
            "holonomic_jacobian",
            model.holonomic_jacobian(q).as_flattened().to_vec(),
        ),
        ("domain", domain),
    ]
}

/// The momentum equation's items at `(q, qdot, u)`.
fn momentum_items<M, const N: usize, const R: usize, const K: usize, const P: usize>(
    model: &M,
    (q, qdot, u): (&[f64; N], &[f64; N], &[f64; P]),
    random: &mut Random,
) -> Vec<(&'static str, Vec<f64>)>
where
    M: MomentumEquations<N, R, K, P>,
{
    let (r, rdot, p) = (
        model.shape(q),
        random.scaled::<R>(1.0),
        random.scaled::<K>(1.0),
    );
    let mut divisors = vec![0.0; model.basis_divisor_names().len()];
    model.basis_divisors(&mut divisors);
    vec![
        ("momentum", model.momentum(q, qdot).to_vec()),
        ("momentum_rhs", model.momentum_rhs(&r, &rdot, &p).to_vec()),
        (
            "momentum_input_matrix",
            model.momentum_input_matrix(q).as_flattened().to_vec(),
        ),
        (
            "shape_acceleration",
            model.shape_acceleration(&r, &rdot, &p, u).to_vec(),
        ),
        (
            "reconstructed_velocity",
            model.reconstructed_velocity(q, &rdot, &p).to_vec(),
        ),
        ("basis_divisors", divisors),
    ]
}

/// Compares the two lists of named items.
fn same_items(
    compared: &mut usize,
    rustc: Vec<(&'static str, Vec<f64>)>,
    jit: Vec<(&'static str, Vec<f64>)>,
) {
    for ((what, a), (_, b)) in rustc.iter().zip(&jit) {
        same(compared, what, a, b);
    }
}

/// The names, guards and charts of the two models agree.
fn same_description<M, F, const S: usize, const P: usize, const N: usize, const H: usize>(
    compiled: &M,
    jit: &F,
) where
    M: ModelNames + Domain + ReducedPortHamiltonian<S, P> + Holonomic<N, H>,
    F: ModelNames + Domain + ReducedPortHamiltonian<S, P> + Holonomic<N, H>,
{
    assert_eq!(compiled.coordinate_names(), jit.coordinate_names());
    assert_eq!(compiled.momentum_names(), jit.momentum_names());
    assert_eq!(compiled.input_names(), jit.input_names());
    assert_eq!(compiled.constraint_names(), jit.constraint_names());
    assert_eq!(compiled.guards(), jit.guards());
    assert_eq!(compiled.holonomic_names(), jit.holonomic_names());
    assert_eq!(compiled.charts(), jit.charts());
    assert_eq!(compiled.switches_charts(), jit.switches_charts());
}

/// Runs the reduced form of `model` without inputs for 100 implicit
/// midpoint steps of 0.01 from `(q, qdot)`; the trajectory's rows.
fn run<M, const N: usize, const K: usize, const S: usize, const P: usize>(
    model: &M,
    q: &[f64; N],
    qdot: &[f64; N],
) -> Vec<Vec<f64>>
where
    M: ReducedPortHamiltonian<S, P> + Momenta<N, K> + ModelNames + Domain,
    Const<S>: Square,
{
    let system = Reduced::new(model, Feedback(|_t, _x: &[f64; S]| [0.0; P]));
    let x0 = system.initial_state(q, qdot);
    let mut table = Table::new();
    Simulation::new(Midpoint::default())
        .span(0.0, 1.0)
        .step(0.01)
        .run(&system, x0, &mut table)
        .expect("the run completes");
    table.rows
}

/// Compares `$compiled` (a generated struct of `$module`) with its model
/// text on the JIT at sizes `N, C, P, H, R, MP` (`K = N - C`, `S = N + K`);
/// `$momentum` says whether it derives the momentum equation; states have
/// entries below `$scale`.
macro_rules! jit_as_rustc {
    ($test:ident, $module:ident :: $compiled:ident,
     [$n:literal, $c:literal, $p:literal, $h:literal, $r:literal, $mp:literal],
     momentum: $momentum:tt, scale: $scale:literal) => {
        #[test]
        fn $test() {
            const K: usize = $n - $c;
            const S: usize = $n + K;
            let model = JitModel::from_source(chaplygin_models::$module::MODEL_TEXT)
                .expect("the model derives and compiles");
            assert_eq!(model.engine().name(), "jit");
            let jit = Fixed::<$n, $c, $p, $h, $r, $mp>::new(&model).expect("its sizes");
            let compiled = $compiled::default();
            same_description::<_, _, S, $p, $n, $h>(&compiled, &jit);
            let mut random = Random(0x9e37_79b9_7f4a_7c15);
            let mut compared = 0;
            for _ in 0..STATES {
                let (q, qdot, u) = (
                    random.scaled::<$n>($scale),
                    random.scaled::<$n>($scale),
                    random.scaled::<$p>($scale),
                );
                let x: [f64; S] = std::array::from_fn(|i| match i < $n {
                    true => q[i],
                    false => random.next(),
                });
                let charts = compiled.charts() + usize::from(compiled.switches_charts());
                for chart in 0..charts {
                    same_items(
                        &mut compared,
                        reduced_items::<_, S, $p>(&compiled, chart, &x, &u),
                        reduced_items::<_, S, $p>(&jit, chart, &x, &u),
                    );
                    let alpha: [f64; K] = compiled.chart_momenta(chart, &q, &qdot);
                    same(&mut compared, "chart_momenta", &alpha,
                        &Momenta::<$n, K>::chart_momenta(&jit, chart, &q, &qdot));
                }
                same(&mut compared, "output", &compiled.output(&x), &jit.output(&x));
                same(&mut compared, "output_jacobian",
                    compiled.output_jacobian(&x).as_flattened(),
                    ReducedPortHamiltonian::<S, $p>::output_jacobian(&jit, &x).as_flattened());
                same_items(
                    &mut compared,
                    dalembert_items::<_, $n, $c, $p, $h>(&compiled, &q, &qdot, &u),
                    dalembert_items::<_, $n, $c, $p, $h>(&jit, &q, &qdot, &u),
                );
                jit_as_rustc!(@momentum $momentum, compiled, jit, (q, qdot, u), random, compared,
                    [$n, $r, $mp, $p]);
            }
            println!("{} entries compared", compared);
            let (q0, qdot0) = (random.scaled::<$n>($scale), random.scaled::<$n>($scale));
            let qdot0: [f64; $n] = Momenta::<$n, K>::velocities(
                &compiled,
                &q0,
                &compiled.momenta(&q0, &qdot0),
            );
            let rustc_rows = run::<_, $n, K, S, $p>(&compiled, &q0, &qdot0);
            let jit_rows = run::<_, $n, K, S, $p>(&jit, &q0, &qdot0);
            assert_eq!(rustc_rows.len(), jit_rows.len());
            for (a, b) in rustc_rows.iter().zip(&jit_rows) {
                for (x, y) in a.iter().zip(b) {
                    assert!((x - y).abs() <= 1e-9 * x.abs().max(1.0), "run: rustc {x:e}, jit {y:e}");
                }
            }
        }
    };
    (@momentum true, $compiled:ident, $jit:ident, ($q:ident, $qdot:ident, $u:ident), $random:ident,
     $compared:ident, [$n:literal, $r:literal, $mp:literal, $p:literal]) => {
        assert_eq!(
            MomentumEquations::<$n, $r, $mp, $p>::shape_indices(&$compiled),
            MomentumEquations::<$n, $r, $mp, $p>::shape_indices(&$jit)
        );
        let seed = $random.0;
        let rustc = momentum_items::<_, $n, $r, $mp, $p>(&$compiled, (&$q, &$qdot, &$u), &mut $random);
        $random.0 = seed;
        let jit = momentum_items::<_, $n, $r, $mp, $p>(&$jit, (&$q, &$qdot, &$u), &mut $random);
        same_items(&mut $compared, rustc, jit);
    };
    (@momentum false, $($rest:tt)*) => {};
}

jit_as_rustc!(snakeboard, snakeboard::Snakeboard, [5, 2, 2, 0, 2, 1], momentum: true, scale: 1.0);
jit_as_rustc!(sleigh, sleigh::Sleigh, [3, 1, 0, 0, 0, 2], momentum: true, scale: 1.0);
jit_as_rustc!(rolling_disk, rolling_disk::RollingDisk, [4, 2, 2, 0, 1, 1], momentum: true, scale: 1.0);
jit_as_rustc!(
    differential_drive,
    differential_drive::DifferentialDrive,
    [5, 3, 2, 0, 2, 0],
    momentum: true,
    scale: 1.0
);
jit_as_rustc!(
    rolling_disk_3d,
    rolling_disk_3d::RollingDisk3d,
    [5, 2, 2, 0, 1, 2],
    momentum: true,
    scale: 0.5
);
jit_as_rustc!(sleigh_bodies, sleigh_bodies::SleighBodies, [3, 1, 0, 0, 0, 2], momentum: true, scale: 1.0);
jit_as_rustc!(
    snakeboard_bodies,
    snakeboard_bodies::SnakeboardBodies,
    [5, 2, 2, 0, 2, 1],
    momentum: true,
    scale: 1.0
);
jit_as_rustc!(
    three_link_snake,
    three_link_snake::ThreeLinkSnake,
    [5, 3, 2, 0, 2, 0],
    momentum: true,
    scale: 1.0
);
jit_as_rustc!(caster_robot, caster_robot::CasterRobot, [7, 5, 2, 0, 0, 0], momentum: false, scale: 0.5);
jit_as_rustc!(bicycle, bicycle::Bicycle, [8, 5, 2, 1, 0, 0], momentum: false, scale: 0.2);

/// Sizes that differ from the model's are refused, naming which.
#[test]
fn wrong_sizes_are_refused() {
    let model = JitModel::from_source(chaplygin_models::snakeboard::MODEL_TEXT).expect("derives");
    let error = Fixed::<5, 2, 3, 0, 2, 1>::new(&model).err();
    assert_eq!(
        error,
        Some(SizeMismatch {
            what: "inputs",
            model: 2,
            fixed: 3
        })
    );
    let error = Fixed::<5, 2, 2, 0>::new(&model).err().expect("refused");
    assert_eq!(
        (error.what, error.model, error.fixed),
        ("shape coordinates", 2, 0)
    );
}
