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
use crate::sym::modular::{self, ModularError};
use crate::sym::residues::Values;
use crate::sym::{
    ExprId, Function, Matrix, RationalFunction, Store, SymError, SymbolId, SymbolKind,
};
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
    store: &mut Store,
    symmetry: &Symmetry,
    model: &Invariants,
) -> Result<Option<Broken>, SymError> {
    let action = group_action(store, symmetry, model.coordinates, model.velocities)?;
    if !preserved(store, model.kinetic_energy, &action)? {
        return Ok(Some(Broken::KineticEnergy));
    }
    if !preserved(store, model.potential_energy, &action)? {
        return Ok(Some(Broken::PotentialEnergy));
    }
    let rows = (model.constraint_matrix, model.constraint_expressions);
    if !constraints_preserved(store, rows, model.velocities, &action)? {
        return Ok(Some(Broken::Constraints));
    }
    Ok(None)
}

/// The substitution `q -> g q`, `qdot -> g_* qdot` for a generic group element.
fn group_action(
    store: &mut Store,
    symmetry: &Symmetry,
    coordinates: &[Variable],
    velocities: &[SymbolId],
) -> Result<HashMap<SymbolId, ExprId>, SymError> {
    let mut action = HashMap::new();
    for (index, factor) in symmetry.factors.iter().enumerate() {
        let parameter = |store: &mut Store, role: &str| {
            let symbol = store.declare(&format!("group {role} {index}"), SymbolKind::Auxiliary);
            store.symbol(symbol)
        };
        match *factor {
            GroupFactor::Se2 { x, y, theta } => {
                let (angle, shift_x, shift_y) = (
                    parameter(store, "angle"),
                    parameter(store, "shift x"),
                    parameter(store, "shift y"),
                );
                let (cos, sin) = (
                    store.apply(Function::Cos, angle)?,
                    store.apply(Function::Sin, angle)?,
                );
                let rotate = |store: &mut Store, u: ExprId, v: ExprId| {
                    let (uc, vs) = (store.mul2(u, cos), store.mul2(v, sin));
                    let (us, vc) = (store.mul2(u, sin), store.mul2(v, cos));
                    (store.sub(uc, vs), store.add2(us, vc))
                };
                let (qx, qy, qt) = (
                    store.symbol(coordinates[x].symbol),
                    store.symbol(coordinates[y].symbol),
                    store.symbol(coordinates[theta].symbol),
                );
                let (rx, ry) = rotate(store, qx, qy);
                action.insert(coordinates[x].symbol, store.add2(rx, shift_x));
                action.insert(coordinates[y].symbol, store.add2(ry, shift_y));
                action.insert(coordinates[theta].symbol, store.add2(qt, angle));
                let (vx, vy) = (store.symbol(velocities[x]), store.symbol(velocities[y]));
                let (wx, wy) = rotate(store, vx, vy);
                action.insert(velocities[x], wx);
                action.insert(velocities[y], wy);
            }
            GroupFactor::Translation(q) | GroupFactor::Rotation(q) => {
                let shift = parameter(store, "shift");
                let coordinate = store.symbol(coordinates[q].symbol);
                action.insert(coordinates[q].symbol, store.add2(coordinate, shift));
            }
        }
    }
    Ok(action)
}

/// `f(g q, g_* qdot) = f(q, qdot)`, of the normal form `form` computed by
/// `expression`.
fn preserved(
    store: &mut Store,
    (form, expression): (&RationalFunction, ExprId),
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    let exact = |store: &mut Store| exactly_preserved(store, form, action);
    if form.is_written_out()
        && let Some(decided) = store.attempt(EXACT_INVARIANCE_PRODUCTS, exact)
    {
        return decided;
    }
    match preserved_at_points(store, expression, action)? {
        Ok(preserved) => Ok(preserved),
        Err(_) => exact(store),
    }
}

/// `f(g q, g_* qdot) - f(q, qdot)` at two random points.
fn preserved_at_points(
    store: &mut Store,
    expression: ExprId,
    action: &HashMap<SymbolId, ExprId>,
) -> Result<Result<bool, ModularError>, SymError> {
    let moved = store.substitute(expression, action)?;
    let difference = store.sub(moved, expression);
    Ok(all_zero_at_points(store, &[], &[difference], |values| {
        values[0] == 0
    }))
}

/// `f(g q, g_* qdot) = f(q, qdot)` by the normal form of the difference.
fn exactly_preserved(
    store: &mut Store,
    form: &RationalFunction,
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    let moved = transformed(store, form, action)?;
    Ok(moved.sub(form, store.atoms()).is_zero())
}

/// `holds` at two random points where the normal forms `forms` and the
/// expressions `expressions` are defined (their values, in that order);
/// false at the first point where it fails.
fn all_zero_at_points(
    store: &mut Store,
    forms: &[RationalFunction],
    expressions: &[ExprId],
    holds: impl Fn(&[u64]) -> bool,
) -> Result<bool, ModularError> {
    let verdicts = modular::at_defined_points(modular::SEEDS.len(), |point| {
        let mut values = Values::at(point);
        let mut evaluated = store.evaluate_normal_modular(forms, &mut values)?;
        evaluated.extend(values.of(store, expressions)?);
        Ok(holds(&evaluated))
    })?;
    Ok(verdicts.into_iter().all(|holds| holds))
}

fn transformed(
    store: &mut Store,
    form: &RationalFunction,
    action: &HashMap<SymbolId, ExprId>,
) -> Result<RationalFunction, SymError> {
    let expression = store.expression_of(form);
    let moved = store.substitute(expression, action)?;
    store.normal(moved)
}

/// The transformed constraint rows stay in the row space of `A(q)`.
fn constraints_preserved(
    store: &mut Store,
    (a, expressions): (&Matrix, &Matrix<ExprId>),
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    if a.rows() == 0 {
        return Ok(true);
    }
    let exact = |store: &mut Store| exactly_constraints_preserved(store, a, velocities, action);
    if a.is_written_out()
        && let Some(decided) = store.attempt(EXACT_INVARIANCE_PRODUCTS, exact)
    {
        return decided;
    }
    match constraints_preserved_at_points(store, expressions, velocities, action)? {
        Ok(preserved) => Ok(preserved),
        Err(_) => exact(store),
    }
}

/// The rank of `A(q)` stacked on the transformed rows at two random points.
fn constraints_preserved_at_points(
    store: &mut Store,
    a: &Matrix<ExprId>,
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<Result<bool, ModularError>, SymError> {
    let (c, n) = (a.rows(), a.columns());
    let mut stacked = a.entries().to_vec();
    for i in 0..c {
        let residual = moved_residual(store, a, i, velocities, action)?;
        for &velocity in velocities {
            stacked.push(store.derivative(residual, velocity));
        }
    }
    let in_row_space = |values: &[u64]| modular::rank(values.to_vec(), 2 * c, n) == c;
    Ok(all_zero_at_points(store, &[], &stacked, in_row_space))
}

/// `sum_j A_ij(g q) (g_* qdot)_j` as an expression.
fn moved_residual(
    store: &mut Store,
    a: &Matrix<ExprId>,
    i: usize,
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<ExprId, SymError> {
    let terms: Vec<ExprId> = velocities
        .iter()
        .enumerate()
        .map(|(j, &velocity)| {
            let velocity = store.symbol(velocity);
            store.mul2(*a.get(i, j), velocity)
        })
        .collect();
    let residual = store.add(&terms);
    store.substitute(residual, action)
}

/// The exact rank of `A(q)` stacked on the transformed rows is `c`.
fn exactly_constraints_preserved(
    store: &mut Store,
    a: &Matrix,
    velocities: &[SymbolId],
    action: &HashMap<SymbolId, ExprId>,
) -> Result<bool, SymError> {
    let (c, n) = (a.rows(), a.columns());
    let atoms = store.atoms().clone();
    let mut stacked = a.entries().to_vec();
    for i in 0..c {
        // the residual row i, moved: sum_j A_ij(g q) (g_* qdot)_j
        let mut residual = RationalFunction::zero();
        for (j, &velocity) in velocities.iter().enumerate() {
            let atom = store.symbol_atom(velocity);
            let term = a.get(i, j).mul(
                &RationalFunction::from_poly(crate::sym::Poly::atom(atom)),
                &atoms,
            );
            residual = residual.add(&term, &atoms);
        }
        let moved = transformed(store, &residual, action)?;
        for &velocity in velocities {
            stacked.push(store.derivative_of_normal(&moved, velocity)?);
        }
    }
    let atoms = store.atoms().clone();
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
        let mut model = check(&parse_str(SLEIGH).expect("parses")).expect("checks");
        let symmetry = model.symmetry.clone().expect("se2");
        let velocities = model.velocities.clone();
        let store = &mut model.store;
        let action =
            group_action(store, &symmetry, &model.coordinates, &velocities).expect("an action");
        let x =
            RationalFunction::from_poly(Poly::atom(store.symbol_atom(model.coordinates[0].symbol)));
        for (form, invariant) in [(&model.kinetic_energy, true), (&x, false)] {
            let expression = store.expression_of(form);
            let decided = preserved_at_points(store, expression, &action)
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
            let rows = rows.to_expression_matrix(store);
            let decided = constraints_preserved_at_points(store, &rows, &velocities, &action)
                .expect("substitutes")
                .expect("in the class");
            assert_eq!(decided, invariant, "{rows:?}");
        }
    }
}
