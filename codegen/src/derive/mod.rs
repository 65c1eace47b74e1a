//! Derivations: from a checked model to its equations of motion.
//!
//! One module per formulation, each stating its equation and citing its
//! source. [`derivation`] runs them in order after the constraint analysis
//! and decides everything emission needs: the solve of `acceleration`
//! ([`lagrange_dalembert::Strategy`]) and the form of each reduced item
//! ([`port_hamiltonian::items`]), each by a cost estimated on the expression
//! DAG. Emission lowers what it is given and decides nothing.

pub mod constraints;
pub mod lagrange_dalembert;
pub mod momentum;
pub mod port_hamiltonian;

use crate::diagnostic::{Diagnostic, Diagnostics};
use crate::ir::Backend;
use crate::model::Model;
use crate::sym::Context;
use constraints::ConstraintAnalysis;
use lagrange_dalembert::LagrangeDalembert;
use momentum::{Momentum, MomentumError};
use port_hamiltonian::PortHamiltonian;
use port_hamiltonian::items::Items;

/// Everything derived from an analysed model.
#[derive(Clone, Debug)]
pub struct Derivation {
    /// The Lagrange-d'Alembert equations and their chosen solve (MATH.md 2).
    pub lagrange_dalembert: LagrangeDalembert,
    /// The reduced port-Hamiltonian form (MATH.md 3).
    pub reduced: PortHamiltonian,
    /// The reduced form's items, each in its chosen form.
    pub reduced_items: Items,
    /// The momentum equation, for a model with a symmetry (MATH.md 4) whose
    /// holonomic constraints do not restrict the shape alone
    /// ([`MOMENTUM_WITH_HOLONOMIC`]).
    pub momentum: Option<Momentum>,
    /// The reduced form in each other chart of D
    /// ([`constraints::charts`]), in order.
    pub charts: Vec<Chart>,
}

/// The reduced form in one other chart of D: the same state layout
/// `(q, alpha)`, with `alpha` the momenta of that chart's basis.
#[derive(Clone, Debug)]
pub struct Chart {
    /// The chart's dependent speeds.
    pub dependent: Vec<usize>,
    /// How the runtime measures where it fits.
    pub fit: constraints::ChartFit,
    /// The reduced form on the chart's basis.
    pub reduced: PortHamiltonian,
    /// Its items, each in its chosen form.
    pub items: Items,
}

/// Why a model with a symmetry and holonomic constraints has no momentum
/// equation: an invariant `f(q) = 0` is a function of the shape, so its
/// velocity row restricts the shape velocities, and the momentum equation
/// (Bloch, Krishnaprasad, Marsden & Murray 1996) is stated for free ones.
/// The symmetry still reduces the linearization about relative equilibria.
pub const MOMENTUM_WITH_HOLONOMIC: &str = "not derived: the holonomic constraints restrict \
     the shape velocities, and the momentum equation needs free ones; the symmetry reduces \
     the linearization only";

/// Derives every formulation of `model` on the basis of D of `constraints`,
/// the numeric searches running their programs on the engines `backend`
/// makes.
pub fn derivation(
    model: &Model,
    cx: &mut Context,
    constraints: &ConstraintAnalysis,
    backend: &dyn Backend,
) -> Result<Derivation, Diagnostics> {
    let internal = |model: &Model, error: &dyn std::fmt::Display| {
        Diagnostics::internal(model.name.span(), error)
    };
    let lagrange_dalembert =
        lagrange_dalembert::derive(model, cx).map_err(|e| internal(model, &e))?;
    let reduced =
        port_hamiltonian::derive(model, cx, &constraints.basis).map_err(|e| internal(model, &e))?;
    let reduced_items =
        port_hamiltonian::items::items(model, cx, &reduced).map_err(|e| internal(model, &e))?;
    let momentum = match model.symmetry {
        Some(_) if !holonomic_rows_restrict_the_shape(model) => {
            Some(momentum::derive(model, cx, backend).map_err(|error| refused(model, error))?)
        }
        _ => None,
    };
    let charts = constraints
        .charts
        .alternatives
        .iter()
        .map(|basis| {
            let reduced = port_hamiltonian::derive(model, cx, basis)?;
            let items = port_hamiltonian::items::items(model, cx, &reduced)?;
            Ok(Chart {
                dependent: basis.dependent.clone(),
                fit: basis.fit(reduced.elimination()),
                reduced,
                items,
            })
        })
        .collect::<Result<Vec<_>, port_hamiltonian::PortHamiltonianError>>()
        .map_err(|e| internal(model, &e))?;
    Ok(Derivation {
        lagrange_dalembert,
        reduced,
        reduced_items,
        momentum,
        charts,
    })
}

/// Whether a holonomic constraint's velocity row (they follow the other
/// rows of `A`) is zero on every group coordinate, so that it restricts the
/// shape velocities alone ([`MOMENTUM_WITH_HOLONOMIC`]); a constraint the
/// group shifts by constants along its orbits (a trough tilted along a
/// translation) leaves the momentum equation standing.
fn holonomic_rows_restrict_the_shape(model: &Model) -> bool {
    let Some(symmetry) = &model.symmetry else {
        return false;
    };
    let group = symmetry.group_coordinates();
    let rows = model.constraint_matrix.rows();
    let first_holonomic = rows - model.mechanism.holonomic.len();
    (first_holonomic..rows).any(|i| {
        group
            .iter()
            .all(|&j| model.constraint_matrix.get(i, j).is_zero())
    })
}

/// The momentum equation's failure, on the symmetry declaration.
fn refused(model: &Model, error: MomentumError) -> Diagnostics {
    let span = model
        .symmetry
        .as_ref()
        .map_or(model.name.span(), |symmetry| symmetry.span);
    Diagnostic::new(span, error.to_string()).into()
}
