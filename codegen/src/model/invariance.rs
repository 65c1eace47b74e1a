//! Invariance of a model under its declared symmetry group.
//!
//! The group acts on the coordinates: `se2(x, y, theta)` by
//! `(x, y, theta) -> (x cos a - y sin a + b_x, x sin a + y cos a + b_y, theta + a)`,
//! `translation(q)` and `rotation(q)` by `q -> q + b`; velocities transform by
//! the tangent map (`xdot -> xdot cos a - ydot sin a`, ...). The group
//! parameters are fresh symbols, so the checks hold for every group element:
//! `T(g q, g qdot) = T(q, qdot)` and `V(g q) = V(q)` exactly (normal form of
//! the difference), and the constraint distribution is carried to itself, i.e.
//! the transformed rows `A(g q) g_*` lie in the row space of `A(q)`: the
//! exact rank of the stacked rows stays `c` (Koon & Marsden, section 2).
//!
//! Each part is decided exactly within [`EXACT_INVARIANCE_PRODUCTS`] term
//! products when its normal forms are written out
//! ([`Matrix::is_written_out`]). Beyond (a
//! bicycle's rolling rows carry a square root in every entry), it is decided
//! by evaluation modulo a prime at random points ([`crate::sym::modular`]),
//! the rows as the expressions they were derived as: a non-zero difference,
//! or a stacked rank above `c`, at a point proves the part not invariant;
//! agreement at two points holds for every group element with probability
//! above `1 - 1e-15`.

use super::{GroupFactor, Symmetry, Variable};
use crate::sym::Context;
use crate::sym::modular::{self, ModularError};
use crate::sym::residues::Values;
use crate::sym::{ExprId, Function, Matrix, RationalFunction, SymError, SymbolId, SymbolKind};
use std::collections::HashMap;

/// The term products each exact invariance check may take.
const EXACT_INVARIANCE_PRODUCTS: u64 = 2_000_000;

/// Which part of the model the group does not preserve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Broken {
    KineticEnergy,
    PotentialEnergy,
    Constraints,
}

impl Broken {
    /// The subject and verb of the error message.
    pub(super) fn describe(self) -> &'static str {
        match self {
            Broken::KineticEnergy => "the kinetic energy is",
            Broken::PotentialEnergy => "the potential energy is",
            Broken::Constraints => "the constraints are",
        }
    }
}

/// What the check needs of the model.
pub(super) struct Invariants<'a> {
    pub(super) coordinates: &'a [Variable],
    pub(super) velocities: &'a [SymbolId],
    /// `T`: its normal form and the expression it is computed by.
    pub(super) kinetic_energy: (&'a RationalFunction, ExprId),
    /// `V`: its normal form and the expression it is computed by.
    pub(super) potential_energy: (&'a RationalFunction, ExprId),
    pub(super) constraint_matrix: &'a Matrix,
    /// `A` as the expressions its rows were derived as.
    pub(super) constraint_expressions: &'a Matrix<ExprId>,
}

/// The first part of the model the group does not preserve, if any.
pub(super) fn first_broken(
    cx: &mut Context,
    symmetry: &Symmetry,
    model: &Invariants,
) -> Result<Option<Broken>, SymError> {
    let action = group_action(cx, symmetry, model.coordinates, model.velocities)?;
    if !preserved(cx, model.kinetic_energy, &action)? {
        return Ok(Some(Broken::KineticEnergy));
    }
    if !preserved(cx, model.potential_energy, &action)? {
        return Ok(Some(Broken::PotentialEnergy));
    }
    let rows = (model.constraint_matrix, model.constraint_expressions);
    if !constraints_preserved(cx, rows, model.velocities, &action)? {
        return Ok(Some(Broken::Constraints));
    }
    Ok(None)
}

/// The substitution `q -> g q`, `qdot -> g_* qdot` for a generic group element.
fn group_action(
    cx: &mut Context,
    symmetry: &Symmetry,
    coordinates: &[Variable],
    velocities: &[SymbolId],
) -> Result<HashMap<SymbolId, ExprId>, SymError> {
    let mut action = HashMap::new();
    for (index, factor) in symmetry.factors.iter().enumerate() {
        let parameter = |cx: &mut Context, role: &str| {
            let symbol = cx.declare(&format!("group {role} {index}"), SymbolKind::Auxiliary);
            cx.symbol(symbol)
        };
        match *factor {
            GroupFactor::Se2 { x, y, theta } => {
                let (angle, shift_x, shift_y) = (
                    parameter(cx, "angle"),
                    parameter(cx, "shift x"),
                    parameter(cx, "shift y"),
                );
                let (cos, sin) = (
                    cx.apply(Function::Cos, angle)?,
                    cx.apply(Function::Sin, angle)?,
                );
                let rotate = |cx: &mut Context, u: ExprId, v: ExprId| {
                    let (uc, vs) = (cx.mul2(u, cos), cx.mul2(v, sin));
                    let (us, vc) = (cx.mul2(u, sin), cx.mul2(v, cos));
                    (cx.sub(uc, vs), cx.add2(us, vc))
                };
                let (qx, qy, qt) = (
                    cx.symbol(coordinates[x].symbol),
                    cx.symbol(coordinates[y].symbol),
                    cx.symbol(coordinates[theta].symbol),
                );
                let (rx, ry) = rotate(cx, qx, qy);
                action.insert(coordinates[x].symbol, cx.add2(rx, shift_x));
                action.insert(coordinates[y].symbol, cx.add2(ry, shift_y));
                action.insert(coordinates[theta].symbol, cx.add2(qt, angle));
                let (vx, vy) = (cx.symbol(velocities[x]), cx.symbol(velocities[y]));
                let (wx, wy) = rotate(cx, vx, vy);
                action.insert(velocities[x], wx);
                action.insert(velocities[y], wy);
            }
            GroupFactor::Translation(q) | GroupFactor::Rotation(q) => {
                let shift = parameter(cx, "shift");
                let coordinate = cx.symbol(coordinates[q].symbol);
                action.insert(coordinates[q].symbol, cx.add2(coordinate, shift));
            }
        }
    }
    Ok(action)
}

/// `f(g q, g_* qdot) = f(q, qdot)`, of the normal form `form` computed by
/// `expression`.
fn preserved(
    cx: &mut Context,
    (form, expression): (&RationalFunction, ExprId),
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    let exact = |cx: &mut Context| exactly_preserved(cx, form, action);
    if form.is_written_out()
        && let Some(decided) = cx.attempt(EXACT_INVARIANCE_PRODUCTS, exact)
    {
        return decided;
    }
    match preserved_at_points(cx, expression, action)? {
        Ok(preserved) => Ok(preserved),
        Err(_) => exact(cx),
    }
}

/// `f(g q, g_* qdot) - f(q, qdot)` at two random points.
fn preserved_at_points(
    cx: &mut Context,
    expression: ExprId,
    action: &HashMap<SymbolId, ExprId>,
) -> Result<Result<bool, ModularError>, SymError> {
    let moved = cx.substitute(expression, action)?;
    let difference = cx.sub(moved, expression);
    Ok(all_zero_at_points(cx, &[], &[difference], |values| {
        values[0] == 0
    }))
}

/// `f(g q, g_* qdot) = f(q, qdot)` by the normal form of the difference.
fn exactly_preserved(
    cx: &mut Context,
    form: &RationalFunction,
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    let moved = transformed(cx, form, action)?;
    Ok(moved.sub(form, cx.atoms()).is_zero())
}

/// `holds` at two random points where the normal forms `forms` and the
/// expressions `expressions` are defined (their values, in that order);
/// false at the first point where it fails.
fn all_zero_at_points(
    cx: &mut Context,
    forms: &[RationalFunction],
    expressions: &[ExprId],
    holds: impl Fn(&[u64]) -> bool,
) -> Result<bool, ModularError> {
    let verdicts = modular::at_defined_points(modular::SEEDS.len(), |point| {
        let mut values = Values::at(point);
        let mut evaluated = cx.evaluate_normal_modular(forms, &mut values)?;
        evaluated.extend(values.of(cx, expressions)?);
        Ok(holds(&evaluated))
    })?;
    Ok(verdicts.into_iter().all(|holds| holds))
}

fn transformed(
    cx: &mut Context,
    form: &RationalFunction,
    action: &HashMap<SymbolId, ExprId>,
) -> Result<RationalFunction, SymError> {
    let expression = cx.expression_of(form);
    let moved = cx.substitute(expression, action)?;
    cx.normal(moved)
}

/// The transformed constraint rows stay in the row space of `A(q)`.
fn constraints_preserved(
    cx: &mut Context,
    (a, expressions): (&Matrix, &Matrix<ExprId>),
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    if a.rows() == 0 {
        return Ok(true);
    }
    let exact = |cx: &mut Context| exactly_constraints_preserved(cx, a, velocities, action);
    if a.is_written_out()
        && let Some(decided) = cx.attempt(EXACT_INVARIANCE_PRODUCTS, exact)
    {
        return decided;
    }
    match constraints_preserved_at_points(cx, expressions, velocities, action)? {
        Ok(preserved) => Ok(preserved),
        Err(_) => exact(cx),
    }
}

/// The rank of `A(q)` stacked on the transformed rows at two random points.
fn constraints_preserved_at_points(
    cx: &mut Context,
    a: &Matrix<ExprId>,
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<Result<bool, ModularError>, SymError> {
    let (c, n) = (a.rows(), a.columns());
    let mut stacked = a.entries().to_vec();
    for i in 0..c {
        let residual = moved_residual(cx, a, i, velocities, action)?;
        for &velocity in velocities {
            stacked.push(cx.derivative(residual, velocity));
        }
    }
    let in_row_space = |values: &[u64]| modular::rank(values.to_vec(), 2 * c, n) == c;
    Ok(all_zero_at_points(cx, &[], &stacked, in_row_space))
}

/// `sum_j A_ij(g q) (g_* qdot)_j` as an expression.
fn moved_residual(
    cx: &mut Context,
    a: &Matrix<ExprId>,
    i: usize,
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<ExprId, SymError> {
    let terms: Vec<ExprId> = velocities
        .iter()
        .enumerate()
        .map(|(j, &velocity)| {
            let velocity = cx.symbol(velocity);
            cx.mul2(*a.get(i, j), velocity)
        })
        .collect();
    let residual = cx.add(&terms);
    cx.substitute(residual, action)
}

/// The exact rank of `A(q)` stacked on the transformed rows is `c`.
fn exactly_constraints_preserved(
    cx: &mut Context,
    a: &Matrix,
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    let (c, n) = (a.rows(), a.columns());
    let atoms = cx.atoms().clone();
    let mut stacked = a.entries().to_vec();
    for i in 0..c {
        // the residual row i, moved: sum_j A_ij(g q) (g_* qdot)_j
        let mut residual = RationalFunction::zero();
        for (j, &velocity) in velocities.iter().enumerate() {
            let atom = cx.symbol_atom(velocity);
            let term = a.get(i, j).mul(
                &RationalFunction::from_poly(crate::sym::Poly::atom(atom)),
                &atoms,
            );
            residual = residual.add(&term, &atoms);
        }
        let moved = transformed(cx, &residual, action)?;
        for &velocity in velocities {
            stacked.push(cx.derivative_of_normal(&moved, velocity)?);
        }
    }
    let atoms = cx.atoms().clone();
    let rank = Matrix::new(2 * c, n, stacked).map_or(0, |m| m.rank(&atoms));
    Ok(rank == c)
}

#[cfg(test)]
mod tests {
    use super::{constraints_preserved_at_points, group_action, preserved_at_points};
    use crate::model::check;
    use crate::sym::{Matrix, Poly, RationalFunction};
    use crate::syntax::parse_str;

    const SLEIGH: &str = include_str!("../../../models/sleigh.model");

    /// At random points, as exactly: the sleigh's energy and blade row are
    /// invariant under its se2, a potential `x` and a row `dot(x) = 0` are not.
    #[test]
    fn invariance_is_decided_at_points_as_by_normal_forms() {
        let (model, mut cx) = check(&parse_str(SLEIGH).expect("parses")).expect("checks");
        let symmetry = model.symmetry.clone().expect("se2");
        let velocities = model.velocities.clone();
        let action =
            group_action(&mut cx, &symmetry, &model.coordinates, &velocities).expect("an action");
        let x =
            RationalFunction::from_poly(Poly::atom(cx.symbol_atom(model.coordinates[0].symbol)));
        for (form, invariant) in [(&model.kinetic_energy, true), (&x, false)] {
            let expression = cx.expression_of(form);
            let decided = preserved_at_points(&mut cx, expression, &action)
                .expect("substitutes")
                .expect("in the class");
            assert_eq!(decided, invariant, "{form:?}");
        }
        let forward = Matrix::new(
            1,
            3,
            vec![
                RationalFunction::one(),
                RationalFunction::zero(),
                RationalFunction::zero(),
            ],
        )
        .expect("1 x 3");
        for (rows, invariant) in [(&model.constraint_matrix, true), (&forward, false)] {
            let rows = rows.to_expression_matrix(&mut cx);
            let decided = constraints_preserved_at_points(&mut cx, &rows, &velocities, &action)
                .expect("substitutes")
                .expect("in the class");
            assert_eq!(decided, invariant, "{rows:?}");
        }
    }
}
