//! The IR interpreter of a model text against the compiled model: every
//! built-in model (and the dense test model `Towed`, whose `acceleration`
//! is the run-time saddle-point solve, and the three-link wheeled snake,
//! whose reduced form is the structured one) at pseudo-random states, with the
//! default parameters and with one parameter changed; the momentum items of
//! the built-in models, which all declare a symmetry, likewise.
//!
//! The interpreter runs the very programs the compiled bodies were emitted
//! from, with the same `f64` operations and the same elimination, so the
//! values agree; the tolerance is 1e-13 relative to the largest entry of
//! each result, and the test prints how many entries are bit-identical (all
//! of them, in debug and in release builds, when this test was written). Bit-identity is not asserted: an optimizing
//! compiler may expand `powi` with a constant exponent into a product chain,
//! which the interpreter's library `powi` need not match in the last bit.

use crate::common::random::Random;
use crate::common::towed::Towed;
use crate::snake3::Snake3;
use chaplygin::runtime::system::MomentumEquations;
use chaplygin_codegen::derive::constraints::{ChartFit, Elimination};
use chaplygin_codegen::interpret::{CallError, InterpretedModel};
use chaplygin_models::differential_drive::DifferentialDrive;
use chaplygin_models::rolling_disk::RollingDisk;
use chaplygin_models::sleigh::Sleigh;
use chaplygin_models::snakeboard::Snakeboard;

const TOLERANCE: f64 = 1e-13;
const STATES: usize = 50;

/// The body of the `chaplygin::model! { ... }` invocation declaring `name` in `file`.
fn macro_body(file: &str, name: &str) -> String {
    let text = std::fs::read_to_string(file).expect("readable source");
    let declaration = format!("pub struct {name} {{");
    let at = text.find(&declaration).expect("the model is declared");
    let open =
        text[..at].rfind("chaplygin::model! {").expect("in a macro") + "chaplygin::model! ".len();
    let mut depth = 0;
    for (offset, character) in text[open..].char_indices() {
        match character {
            '{' => depth += 1,
            '}' => depth -= 1,
            _ => {}
        }
        if depth == 0 {
            return text[open + 1..open + offset].to_string();
        }
    }
    panic!("unbalanced braces in {file}");
}

fn source(name: &str) -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let file = match name {
        "Towed" => return macro_body(&format!("{root}/tests/common/towed.rs"), name),
        "Snake3" => return chaplygin_models::n_link_snake(3),
        "Snakeboard" => "snakeboard",
        "Sleigh" => "sleigh",
        "RollingDisk" => "rolling_disk",
        _ => "differential_drive",
    };
    std::fs::read_to_string(format!("{root}/{file}.model")).expect("readable")
}

/// Counts of compared entries and of bit-identical ones.
#[derive(Default)]
struct Agreement {
    compared: usize,
    identical: usize,
}

impl Agreement {
    fn check(&mut self, what: &str, compiled: &[f64], interpreted: &[f64]) {
        assert_eq!(compiled.len(), interpreted.len(), "{what}: lengths");
        let scale = compiled.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, (a, b)) in compiled.iter().zip(interpreted).enumerate() {
            assert!(
                (a - b).abs() <= TOLERANCE * scale,
                "{what}[{i}]: compiled {a:e}, interpreted {b:e}"
            );
            self.compared += 1;
            self.identical += usize::from(a.to_bits() == b.to_bits());
        }
    }

    fn report(&self, what: &str) {
        println!(
            "{what}: {} entries within {TOLERANCE:e}, {} bit-identical",
            self.compared, self.identical
        );
    }
}

/// Runs `check` at `STATES` states with the default parameters, then again
/// with the parameter `name` (the field `parameter` of the compiled model)
/// scaled by 1.3 in both models.
fn at_both_parameter_values<M>(
    compiled: &mut M,
    interpreted: &mut InterpretedModel,
    name: &str,
    parameter: fn(&mut M) -> &mut f64,
    mut check: impl FnMut(&M, &InterpretedModel),
) {
    for round in 0..2 {
        if round == 1 {
            let value = 1.3 * *parameter(compiled);
            *parameter(compiled) = value;
            interpreted.set_parameter(name, value).expect("declared");
        }
        for _ in 0..STATES {
            check(compiled, interpreted);
        }
    }
}

/// Compares every item of the compiled `$model` with the interpreter of its
/// text, at default parameters and with `$parameter` scaled by 1.3.
macro_rules! differential_test {
    ($test:ident, $model:ident, $parameter:ident) => {
        #[test]
        fn $test() {
            let mut interpreted =
                InterpretedModel::from_source(&source(stringify!($model))).expect("compiles");
            let mut compiled = $model::default();
            assert_eq!(
                interpreted.parameter_values(),
                interpreted.parameter_defaults()
            );
            let sizes = interpreted.sizes();
            assert_eq!(
                (sizes.n, sizes.c, sizes.k, sizes.p, sizes.s),
                ($model::N, $model::C, $model::K, $model::P, $model::S)
            );
            assert_eq!(interpreted.names().coordinates, $model::COORDINATES);
            assert_eq!(interpreted.names().parameters, $model::PARAMETERS);
            assert_eq!(interpreted.names().inputs, $model::INPUTS);
            assert_eq!(interpreted.names().constraints, $model::CONSTRAINTS);
            assert_eq!(interpreted.report(), $model::REPORT);
            let mut agreement = Agreement::default();
            let mut random = Random(0x9e37_79b9_7f4a_7c15);
            at_both_parameter_values(
                &mut compiled,
                &mut interpreted,
                stringify!($parameter),
                |model| &mut model.$parameter,
                |compiled, interpreted| {
                    compare::<
                        { $model::N },
                        { $model::C },
                        { $model::P },
                        { $model::S },
                        { $model::K },
                    >(compiled, interpreted, &mut random, &mut agreement)
                },
            );
            agreement.report(stringify!($model));
        }

        impl Items<{ $model::N }, { $model::C }, { $model::P }, { $model::S }, { $model::K }>
            for $model
        {
            fn items(
                &self,
                q: &[f64; $model::N],
                qdot: &[f64; $model::N],
                u: &[f64; $model::P],
                x: &[f64; $model::S],
                alpha: &[f64; $model::K],
            ) -> Vec<(&'static str, Vec<f64>)> {
                let (qddot, lambda) = self.acceleration(q, qdot, u);
                let (by_q, by_qdot, by_u) = self.acceleration_jacobian(q, qdot, u);
                vec![
                    ("mass_matrix", self.mass_matrix(q).concat()),
                    ("energy", vec![self.energy(q, qdot)]),
                    ("constraint_matrix", self.constraint_matrix(q).concat()),
                    (
                        "constraint_residual",
                        self.constraint_residual(q, qdot).to_vec(),
                    ),
                    (
                        "acceleration",
                        [qddot.as_slice(), lambda.as_slice()].concat(),
                    ),
                    (
                        "acceleration_jacobian",
                        [by_q.concat(), by_qdot.concat(), by_u.concat()].concat(),
                    ),
                    ("momenta", self.momenta(q, qdot).to_vec()),
                    ("velocities", self.velocities(q, alpha).to_vec()),
                    ("hamiltonian", vec![self.hamiltonian(x)]),
                    (
                        "hamiltonian_gradient",
                        self.hamiltonian_gradient(x).to_vec(),
                    ),
                    ("structure_matrix", self.structure_matrix(x).concat()),
                    ("input_matrix", self.input_matrix(x).concat()),
                    ("reduced_rhs", self.reduced_rhs(x, u).to_vec()),
                    (
                        "reduced_rhs_jacobian",
                        self.reduced_rhs_jacobian(x, u).concat(),
                    ),
                    ("output", self.output(x).to_vec()),
                ]
            }
        }
    };
}

/// The compiled model's items at one state, flattened row-major.
trait Items<const N: usize, const C: usize, const P: usize, const S: usize, const K: usize> {
    fn items(
        &self,
        q: &[f64; N],
        qdot: &[f64; N],
        u: &[f64; P],
        x: &[f64; S],
        alpha: &[f64; K],
    ) -> Vec<(&'static str, Vec<f64>)>;
}

/// The interpreter's items at the same state, in the same order.
fn interpreted_items(
    model: &InterpretedModel,
    [q, qdot, u, x, alpha]: [&[f64]; 5],
) -> Result<Vec<Vec<f64>>, CallError> {
    let (qddot, lambda) = model.acceleration(q, qdot, u)?;
    let (by_q, by_qdot, by_u) = model.acceleration_jacobian(q, qdot, u)?;
    Ok(vec![
        model.mass_matrix(q)?,
        vec![model.energy(q, qdot)?],
        model.constraint_matrix(q)?,
        model.constraint_residual(q, qdot)?,
        [qddot, lambda].concat(),
        [by_q, by_qdot, by_u].concat(),
        model.momenta(q, qdot)?,
        model.velocities(q, alpha)?,
        vec![model.hamiltonian(x)?],
        model.hamiltonian_gradient(x)?,
        model.structure_matrix(x)?,
        model.input_matrix(x)?,
        model.reduced_rhs(x, u)?,
        model.reduced_rhs_jacobian(x, u)?,
        model.output(x)?,
    ])
}

fn compare<const N: usize, const C: usize, const P: usize, const S: usize, const K: usize>(
    compiled: &impl Items<N, C, P, S, K>,
    interpreted: &InterpretedModel,
    random: &mut Random,
    agreement: &mut Agreement,
) {
    let (q, qdot, u, x, alpha) = (
        random.array::<N>(),
        random.array::<N>(),
        random.array::<P>(),
        random.array::<S>(),
        random.array::<K>(),
    );
    let expected = compiled.items(&q, &qdot, &u, &x, &alpha);
    let found = interpreted_items(interpreted, [&q, &qdot, &u, &x, &alpha]).expect("evaluates");
    for ((name, compiled), interpreted) in expected.iter().zip(&found) {
        agreement.check(name, compiled, interpreted);
    }
}

/// Compares the momentum items of the compiled `$model` (which has a
/// symmetry) with the interpreter's, at default parameters and with
/// `$parameter` scaled by 1.3.
macro_rules! momentum_test {
    ($test:ident, $model:ident, $parameter:ident) => {
        #[test]
        fn $test() {
            let mut interpreted =
                InterpretedModel::from_source(&source(stringify!($model))).expect("compiles");
            let mut compiled = $model::default();
            let mut agreement = Agreement::default();
            let mut random = Random(0x2545_f491_4f6c_dd1d);
            at_both_parameter_values(
                &mut compiled,
                &mut interpreted,
                stringify!($parameter),
                |model| &mut model.$parameter,
                |compiled, interpreted| {
                    let (q, qdot, u, r, rdot, p) = (
                        random.array(),
                        random.array(),
                        random.array(),
                        random.array(),
                        random.array(),
                        random.array(),
                    );
                    let expected = [
                        ("momentum", compiled.momentum(&q, &qdot).to_vec()),
                        (
                            "momentum_rhs",
                            compiled.momentum_rhs(&r, &rdot, &p).to_vec(),
                        ),
                        (
                            "momentum_input_matrix",
                            compiled.momentum_input_matrix(&q).concat(),
                        ),
                        (
                            "nonholonomic_connection",
                            compiled.nonholonomic_connection(&r).concat(),
                        ),
                        ("locked_inertia", compiled.locked_inertia(&r).concat()),
                        (
                            "body_velocity",
                            compiled.body_velocity(&r, &rdot, &p).to_vec(),
                        ),
                    ];
                    let arguments: [&[&[f64]]; 6] = [
                        &[&q, &qdot],
                        &[&r, &rdot, &p],
                        &[&q],
                        &[&r],
                        &[&r],
                        &[&r, &rdot, &p],
                    ];
                    for ((name, values), arguments) in expected.iter().zip(arguments) {
                        let found = interpreted.call(name, arguments).expect("evaluates");
                        agreement.check(name, values, &found);
                    }
                    let shape = interpreted
                        .shape_acceleration(&r, &rdot, &p, &u)
                        .expect("evaluates");
                    agreement.check(
                        "shape_acceleration",
                        &compiled.shape_acceleration(&r, &rdot, &p, &u),
                        &shape,
                    );
                    let reconstructed = interpreted
                        .reconstructed_velocity(&q, &rdot, &p)
                        .expect("evaluates");
                    agreement.check(
                        "reconstructed_velocity",
                        &MomentumEquations::reconstructed_velocity(compiled, &q, &rdot, &p),
                        &reconstructed,
                    );
                },
            );
            agreement.report(concat!(stringify!($model), " momentum items"));
        }
    };
}

momentum_test!(
    snakeboard_momentum_items_interpreted_as_compiled,
    Snakeboard,
    r
);
momentum_test!(
    sleigh_momentum_items_interpreted_as_compiled,
    Sleigh,
    inertia
);
momentum_test!(
    rolling_disk_momentum_items_interpreted_as_compiled,
    RollingDisk,
    r
);
momentum_test!(
    differential_drive_momentum_items_interpreted_as_compiled,
    DifferentialDrive,
    b
);

differential_test!(snakeboard_interpreted_as_compiled, Snakeboard, jt);
differential_test!(sleigh_interpreted_as_compiled, Sleigh, a);
differential_test!(rolling_disk_interpreted_as_compiled, RollingDisk, m);
differential_test!(
    differential_drive_interpreted_as_compiled,
    DifferentialDrive,
    m
);
differential_test!(
    three_link_snake_interpreted_as_compiled_through_the_structured_form,
    Snake3,
    l
);
differential_test!(
    towed_interpreted_as_compiled_through_the_run_time_solve,
    Towed,
    l
);

#[test]
fn the_towed_model_takes_the_run_time_solve() {
    assert!(Towed::REPORT.contains("solve: numeric solve of the saddle-point system"));
}

#[test]
fn wrong_lengths_and_names_are_structured_errors() {
    let mut sleigh = InterpretedModel::from_source(&source("Sleigh")).expect("compiles");
    assert_eq!(
        sleigh.mass_matrix(&[0.0; 2]),
        Err(CallError::ArgumentLength {
            function: "mass_matrix".into(),
            argument: "q".into(),
            expected: 3,
            found: 2,
        })
    );
    assert_eq!(
        sleigh.call("energy", &[&[0.0; 3]]),
        Err(CallError::ArgumentCount {
            function: "energy".into(),
            expected: 2,
            found: 1,
        })
    );
    assert!(matches!(
        sleigh.call("warp_drive", &[]),
        Err(CallError::UnknownFunction { .. })
    ));
    let towed = InterpretedModel::from_source(&source("Towed")).expect("compiles");
    assert!(matches!(
        towed.shape_acceleration(&[0.0], &[0.0], &[0.0], &[0.0]),
        Err(CallError::UnknownFunction { .. })
    ));
    assert!(matches!(
        sleigh.shape_acceleration(&[], &[], &[0.0], &[]),
        Err(CallError::ArgumentLength { .. })
    ));
    let error = sleigh.set_parameter("mass", 2.0).expect_err("not declared");
    assert_eq!(error.name, "mass");
    assert_eq!(error.known, ["m", "inertia", "a"]);
}

/// The towed sleigh has no symmetry and two charts of D (its blade solved
/// for `dot(y)`, then for `dot(x)`): the second chart's items, interpreted
/// through `call_in_chart`, agree with the compiled `..._chart1` items, and
/// `chart_fit` with the compiled pivot ratio.
#[test]
fn the_second_charts_items_are_interpreted_as_compiled() {
    use chaplygin::runtime::system::ReducedPortHamiltonian;
    let interpreted = InterpretedModel::from_source(&source("Towed")).expect("compiles");
    assert_eq!(
        interpreted.charts(),
        [
            ChartFit::Coordinates(vec![1], Elimination::Exact),
            ChartFit::Coordinates(vec![0], Elimination::Exact)
        ]
    );
    let towed = Towed::default();
    let mut random = Random(0x5eed_c4a7);
    let mut agreement = Agreement::default();
    let call = |name: &str, arguments: &[&[f64]]| {
        interpreted
            .call_in_chart(1, name, arguments)
            .expect("evaluates")
    };
    for _ in 0..STATES {
        let (x, u): ([f64; 7], [f64; 1]) = (random.array(), random.array());
        let (q, alpha) = ([x[0], x[1], x[2], x[3]], [x[4], x[5], x[6]]);
        let qdot = towed.velocities_chart1(&q, &alpha);
        agreement.check("velocities", &qdot, &call("velocities", &[&q, &alpha]));
        let momenta = towed.momenta_chart1(&q, &qdot);
        agreement.check("momenta", &momenta, &call("momenta", &[&q, &qdot]));
        let hamiltonian = towed.hamiltonian_chart1(&x);
        agreement.check("hamiltonian", &[hamiltonian], &call("hamiltonian", &[&x]));
        let gradient = towed.hamiltonian_gradient_chart1(&x);
        let found = call("hamiltonian_gradient", &[&x]);
        agreement.check("hamiltonian_gradient", &gradient, &found);
        let structure = towed.structure_matrix_chart1(&x);
        let found = call("structure_matrix", &[&x]);
        agreement.check("structure_matrix", structure.as_flattened(), &found);
        let input = towed.input_matrix_chart1(&x);
        let found = call("input_matrix", &[&x]);
        agreement.check("input_matrix", input.as_flattened(), &found);
        let rhs = towed.reduced_rhs_chart1(&x, &u);
        agreement.check("reduced_rhs", &rhs, &call("reduced_rhs", &[&x, &u]));
        let jacobian = towed.reduced_rhs_jacobian_chart1(&x, &u);
        let found = call("reduced_rhs_jacobian", &[&x, &u]);
        agreement.check("reduced_rhs_jacobian", jacobian.as_flattened(), &found);
        let fit = interpreted.chart_fit(1, &q).expect("evaluates");
        agreement.check("chart_fit", &[towed.chart_fit(1, &x)], &[fit]);
    }
    agreement.report("Towed, chart 1");
}
