use super::jacobian::implicit_jacobian;
use super::{LagrangeDalembert, Strategy, derive};
use crate::ir;
use crate::model::{Model, check};
use crate::sym::Context;
use crate::sym::zero::SplitMix;
use crate::sym::{ExprId, SymbolId};
use crate::syntax::parse_str;
use chaplygin_runtime::nalgebra::{DMatrix, DVector};
use std::collections::HashMap;

const SLEIGH: &str = include_str!("../../../../models/sleigh.model");
const ROLLING_DISK_3D: &str = include_str!("../../../../models/rolling_disk_3d.model");
const SNAKEBOARD_BODIES: &str = include_str!("../../../../models/snakeboard_bodies.model");
const BICYCLE: &str = include_str!("../../../../models/bicycle.model");
const CHAIN: &str = r#"
pub struct Chain {
coordinates: [x, y, theta, a1, a2, a3],
parameters: [m = 1.0, l = 0.7, k = 2.0],
kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + m/2*dot(theta)^2
    + m/2*((dot(x) - l*sin(theta + a1)*(dot(theta) + dot(a1)))^2
        + (dot(y) + l*cos(theta + a1)*(dot(theta) + dot(a1)))^2)
    + m/2*((dot(x) - l*sin(theta + a2)*(dot(theta) + dot(a2)))^2
        + (dot(y) + l*cos(theta + a2)*(dot(theta) + dot(a2)))^2)
    + m/2*((dot(x) - l*sin(theta + a3)*(dot(theta) + dot(a3)))^2
        + (dot(y) + l*cos(theta + a3)*(dot(theta) + dot(a3)))^2),
potential_energy: k/2*(a1^2 + a2^2 + a3^2),
constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y), locked = dot(a3) - dot(a1)],
inputs: [s1 = a1, s2 = a2],
}
"#;
const TOWED: &str = r#"
pub struct Towed {
coordinates: [x, y, theta, alpha],
parameters: [m = 1.0, inertia = 0.1, a = 0.5, mp = 0.3, l = 0.7, k = 2.0],
kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
    + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2
    + mp/2*((dot(x) - l*sin(theta + alpha)*(dot(theta) + dot(alpha)))^2
    + (dot(y) + l*cos(theta + alpha)*(dot(theta) + dot(alpha)))^2),
potential_energy: k/2*alpha^2,
constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
inputs: [steer = alpha],
}
"#;

fn derived(source: &str) -> (Model, Context, LagrangeDalembert) {
    let (model, mut cx) = check(&parse_str(source).expect("parses")).expect("checks");
    let derivation = derive(&model, &mut cx).expect("derives");
    (model, cx, derivation)
}

#[test]
fn the_closed_form_solves_the_equations_exactly() {
    for source in [crate::fixtures::SNAKEBOARD, SLEIGH] {
        let (_, cx, derivation) = derived(source);
        let atoms = cx.atoms();
        let system = &derivation.saddle_point;
        let solution = derivation.closed_form.as_ref().expect("derived");
        let a = &system.constraint_matrix;
        let balance = system
            .mass_matrix
            .mul(&solution.accelerations, atoms)
            .and_then(|m| m.sub(&a.transpose().mul(&solution.multipliers, atoms)?, atoms))
            .and_then(|m| {
                m.sub(
                    system
                        .force
                        .exact
                        .as_ref()
                        .expect("small models' force is exact"),
                    atoms,
                )
            })
            .expect("fits");
        assert!(balance.is_zero(), "g qddot - A^T lambda - f must vanish");
        let acceleration_constraint = a
            .mul(&solution.accelerations, atoms)
            .and_then(|m| {
                m.sub(
                    system.drift.exact().expect("small models' drift is exact"),
                    atoms,
                )
            })
            .expect("fits");
        assert!(
            acceleration_constraint.is_zero(),
            "A qddot + Adot qdot must vanish"
        );
    }
}

/// Random coordinates, velocities and inputs; parameters at their defaults.
fn random_point(model: &Model, inputs: &[SymbolId], seed: u64) -> HashMap<SymbolId, f64> {
    let mut random = SplitMix::new(seed);
    let mut values: HashMap<SymbolId, f64> = model
        .parameters
        .iter()
        .map(|p| (p.variable.symbol, p.default.to_f64()))
        .collect();
    for &symbol in model
        .coordinate_symbols()
        .iter()
        .chain(&model.velocities)
        .chain(inputs)
    {
        values.insert(symbol, random.uniform(-2.0, 2.0));
    }
    values
}

/// `(qddot, lambda)` from the saddle-point pieces solved by the
/// runtime's Gaussian elimination with partial pivoting, an independent
/// solve of the same system.
fn pivoted_solution<const M: usize>(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
    values: &HashMap<SymbolId, f64>,
) -> Vec<f64> {
    let (n, c) = (model.n(), model.c());
    assert_eq!(n + c, M);
    let value_of = |s: SymbolId| values[&s];
    let system = &derivation.saddle_point;
    let g = system.mass_matrix.evaluate(cx, &value_of);
    let a = system.constraint_matrix.evaluate(cx, &value_of);
    let force: Vec<f64> = system
        .force
        .expressions
        .entries()
        .iter()
        .map(|&e| cx.evaluate(e, &value_of))
        .collect();
    let drift: Vec<f64> = system
        .drift
        .expressions(cx)
        .entries()
        .iter()
        .map(|&e| cx.evaluate(e, &value_of))
        .collect();
    let mut matrix = [[0.0; M]; M];
    for i in 0..n {
        matrix[i][..n].copy_from_slice(&g[i * n..(i + 1) * n]);
    }
    for r in 0..c {
        for j in 0..n {
            matrix[n + r][j] = a[r * n + j];
            matrix[j][n + r] = a[r * n + j];
        }
    }
    let mut rhs = [0.0; M];
    rhs[..n].copy_from_slice(&force);
    rhs[n..].copy_from_slice(&drift);
    let solution = DMatrix::from_fn(M, M, |i, j| matrix[i][j])
        .lu()
        .solve(&DVector::from_column_slice(&rhs))
        .expect("a regular saddle-point system");
    let (accelerations, mu) = solution.as_slice().split_at(n);
    accelerations
        .iter()
        .copied()
        .chain(mu.iter().map(|m| -m))
        .collect()
}

/// The closed form (when derived) and the solution by blocks against the
/// pivoted solve, at random points.
fn assert_strategies_agree<const M: usize>(source: &str) {
    let (model, mut cx, derivation) = derived(source);
    for seed in 0..20 {
        let values = random_point(&model, &derivation.inputs, seed);
        let value_of = |s: SymbolId| values[&s];
        let pivoted = pivoted_solution::<M>(&model, &mut cx, &derivation, &values);
        let by_blocks = cx.evaluate_many(&derivation.numeric_solution, &value_of);
        let mut solutions = vec![("by blocks", by_blocks)];
        if let Some(closed_form) = &derivation.closed_form {
            let mut symbolic = closed_form.accelerations.evaluate(&mut cx, &value_of);
            symbolic.extend(closed_form.multipliers.evaluate(&mut cx, &value_of));
            solutions.push(("closed form", symbolic));
        }
        for (name, solution) in solutions {
            for (s, p) in solution.iter().zip(&pivoted) {
                assert!(
                    (s - p).abs() <= 1e-10 * (1.0 + p.abs()),
                    "{name}, seed {seed}: {solution:?} vs {pivoted:?}"
                );
            }
        }
    }
}

#[test]
fn both_solutions_agree_on_the_snakeboard_and_the_sleigh() {
    assert_strategies_agree::<7>(crate::fixtures::SNAKEBOARD);
    assert_strategies_agree::<4>(SLEIGH);
}

/// The weighted cost of `outputs` once lowered ([`ir::Program::weighted_cost`]).
fn lowered_weight(model: &Model, cx: &Context, d: &LagrangeDalembert, outputs: &[ExprId]) -> u64 {
    let mut arguments = model.coordinate_symbols();
    arguments.extend(&model.velocities);
    arguments.extend(&d.inputs);
    arguments.extend(model.parameter_symbols());
    ir::lower(cx, &arguments, outputs)
        .expect("every symbol is an argument")
        .weighted_cost()
}

/// The strategy the DAG estimate chooses is the one whose lowered
/// program weighs less (the closed form on a tie): the sleigh's and the
/// snakeboard's closed forms are cheap, the towed sleigh's dense coupled
/// metric does not invert cheaply in closed form.
#[test]
fn the_estimate_chooses_the_strategy_that_lowers_cheaper() {
    for (name, source) in [
        ("snakeboard", crate::fixtures::SNAKEBOARD),
        ("sleigh", SLEIGH),
        ("towed", TOWED),
    ] {
        let (model, mut cx, d) = derived(source);
        let closed_form = d.closed_form.as_ref().expect("within the limits");
        let closed_form = closed_form.outputs(&mut cx);
        let symbolic = lowered_weight(&model, &cx, &d, &closed_form);
        let numeric = lowered_weight(&model, &cx, &d, &d.numeric_solution);
        println!(
            "{name}: lowered weights closed form {symbolic}, by blocks {numeric}; \
             estimated {:?} -> {:?}",
            d.weighted_costs, d.strategy
        );
        let expected = if symbolic <= numeric {
            Strategy::Symbolic
        } else {
            Strategy::Numeric
        };
        assert_eq!(d.strategy, expected, "{name}");
    }
    assert_strategies_agree::<5>(TOWED);
}

/// A sleigh towing three pendulums: one dense 6 x 6 block of `g`, past
/// the limit, so no closed form is attempted (it would not finish).
#[test]
fn a_large_dense_metric_goes_numeric_without_a_closed_form() {
    let (model, _, d) = derived(CHAIN);
    assert_eq!(
        model.mass_matrix.diagonal_blocks(),
        [vec![0, 1, 2, 3, 4, 5]]
    );
    assert!(d.closed_form.is_none() && d.weighted_costs.0.is_none());
    assert_eq!(d.strategy, Strategy::Numeric);
    assert_strategies_agree::<8>(CHAIN);
}

/// The structured `-Adot qdot` (derivatives of the rows' expressions) takes
/// the values of the exact one at random states.
#[test]
fn the_structured_drift_is_the_exact_drift() {
    for source in [crate::fixtures::SNAKEBOARD, SLEIGH, CHAIN] {
        let (model, mut cx, derivation) = derived(source);
        let exact = derivation
            .saddle_point
            .drift
            .exact()
            .expect("small models' drift is exact")
            .clone();
        let structured = super::structured_drift(&model, &mut cx);
        for seed in 1..=5 {
            let values = random_point(&model, &derivation.inputs, seed);
            let value_of = |s: SymbolId| values[&s];
            let exact_values = exact.evaluate(&mut cx, &value_of);
            for (i, &entry) in structured.entries().iter().enumerate() {
                let value = cx.evaluate(entry, &value_of);
                assert!(
                    (value - exact_values[i]).abs() <= 1e-12 * (1.0 + exact_values[i].abs()),
                    "row {i}: {value} vs {}",
                    exact_values[i]
                );
            }
        }
    }
}

/// The structured force (derivatives of the energies' expressions) has the
/// exact force's normal form, on declared energies and on mechanisms, and
/// the force emitted takes its values at random states.
#[test]
fn the_structured_force_is_the_exact_force() {
    for source in [
        crate::fixtures::SNAKEBOARD,
        TOWED,
        CHAIN,
        ROLLING_DISK_3D,
        SNAKEBOARD_BODIES,
    ] {
        let (model, mut cx, derivation) = derived(source);
        let force = &derivation.saddle_point.force;
        let exact = force.exact.clone().expect("small models' force is exact");
        let structured =
            super::structured_force(&model, &mut cx, &derivation.inputs).expect("fits");
        for (i, &entry) in structured.entries().iter().enumerate() {
            let form = cx.normal(entry).expect("within budget");
            let difference = form.sub(exact.get(i, 0), cx.atoms());
            assert!(difference.is_zero(), "{}: entry {i}", model.name);
        }
        assert_force_values(&model, &mut cx, &derivation, 5, 1e-12);
    }
}

/// The force emitted takes the exact force's values at `points` random
/// states, to `tolerance` relative.
fn assert_force_values(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
    points: u64,
    tolerance: f64,
) {
    let force = &derivation.saddle_point.force;
    let exact = force.exact.as_ref().expect("exact");
    for seed in 1..=points {
        let values = random_point(model, &derivation.inputs, seed);
        let value_of = |s: SymbolId| values[&s];
        let exact_values = exact.evaluate(cx, &value_of);
        for (i, &entry) in force.expressions.entries().iter().enumerate() {
            let value = cx.evaluate(entry, &value_of);
            assert!(
                (value - exact_values[i]).abs() <= tolerance * (1.0 + exact_values[i].abs()),
                "{}, entry {i}: {value} vs {}",
                model.name,
                exact_values[i]
            );
        }
    }
}

/// The benchmark bicycle's metric is not written out, so its exact force
/// is not derived and the structured one (Kane's form of its four bodies'
/// inertia forces) is emitted; the normal forms, derived here, weigh more
/// than ten times as much, and the emitted force takes their values at
/// random states.
#[test]
fn the_bicycle_emits_its_structured_force() {
    let (model, mut cx, mut derivation) = derived(BICYCLE);
    assert!(derivation.saddle_point.force.exact.is_none());
    let exact = super::exact_force(&model, &mut cx, &derivation.inputs).expect("fits");
    let written = exact.to_expression_matrix(&mut cx);
    let force = &derivation.saddle_point.force;
    let weight = |entries: &[ExprId]| ir::estimated_weight(&cx, entries);
    let (emitted, written) = (
        weight(force.expressions.entries()),
        weight(written.entries()),
    );
    println!("bicycle force: emitted {emitted}, written out {written}");
    assert!(emitted * 10 < written, "{emitted} vs {written}");
    derivation.saddle_point.force.exact = Some(exact);
    assert_force_values(&model, &mut cx, &derivation, 3, 1e-10);
}

/// The Jacobian of `qddot` by implicit differentiation takes the values of
/// the solution by blocks differentiated through its factorization, at
/// random states: by `q`, `qdot` and `u`, about the closed form and about
/// the solution by blocks alike (to round-off relative to the largest
/// entry: the 3D disk's are a million times its smallest).
#[test]
fn the_implicit_jacobian_is_the_derivative_of_the_solve() {
    for source in [
        crate::fixtures::SNAKEBOARD,
        SLEIGH,
        TOWED,
        CHAIN,
        ROLLING_DISK_3D,
    ] {
        let (model, mut cx, d) = derived(source);
        let variables = [
            model.coordinate_symbols().as_slice(),
            &model.velocities,
            &d.inputs,
        ]
        .concat();
        let accelerations = &d.numeric_solution[..model.n()];
        let differentiated: Vec<ExprId> = variables
            .iter()
            .flat_map(|&v| cx.derivatives(accelerations, v))
            .collect();
        let mut solutions = vec![d.numeric_solution.clone()];
        solutions.extend(d.closed_form.as_ref().map(|form| form.outputs(&mut cx)));
        for solution in solutions {
            let implicit = implicit_jacobian(&model, &mut cx, &d, &solution, &variables)
                .expect("solves")
                .transpose();
            for seed in 1..=5 {
                let values = random_point(&model, &d.inputs, seed);
                let value_of = |s: SymbolId| values[&s];
                let expected = cx.evaluate_many(&differentiated, &value_of);
                let found = cx.evaluate_many(implicit.entries(), &value_of);
                let scale = expected.iter().fold(1.0_f64, |m, e| m.max(e.abs()));
                for (e, f) in expected.iter().zip(&found) {
                    assert!(
                        (e - f).abs() <= 1e-9 * scale,
                        "{}, seed {seed}: {found:?} vs {expected:?}",
                        model.name
                    );
                }
            }
        }
    }
}
