//! The energies: the metric from the kinetic energy or a declared mass
//! matrix, positive definite; the potential free of velocities; both joined
//! to the bodies' energies and written out as expressions.

use super::context::Context;
use super::items::row_of_expressions;
use super::mechanisms::MechanismParts;
use super::section::{Section, Sections};
use super::velocities::{check_velocity_degree, velocity_free};
use crate::model::{BodyMotion, EnergyExpressions, Mechanism, Parameter, Variable};
use crate::sym::zero::SplitMix;
use crate::sym::{ExprId, Matrix, Poly, Rational, RationalFunction, SymbolId};
use crate::syntax;
use proc_macro2::Span;

/// Random configurations at which positive definiteness is sampled.
const DEFINITENESS_SAMPLES: usize = 24;

/// `(T, g)` from whichever of `kinetic_energy`/`mass_matrix` is given, plus
/// the bodies'.
pub(super) fn metric(
    cx: &mut Context,
    sections: &Sections,
    coordinates: &[Variable],
    parameters: &[Parameter],
    mechanism: &Mechanism,
) -> Option<(RationalFunction, Matrix)> {
    let velocities: Vec<SymbolId> = coordinates
        .iter()
        .map(|c| cx.sym.velocity_of(c.symbol))
        .collect();
    let declared = if let Some(section) = sections.get(Section::KineticEnergy) {
        Some((section, metric_of_kinetic_energy(cx, section, &velocities)?))
    } else if let Some(section) = sections.get(Section::MassMatrix) {
        let g = declared_mass_matrix(cx, section, coordinates.len())?;
        let t = quadratic_form(cx, &g, &velocities);
        Some((section, (t, g)))
    } else {
        None
    };
    let bodies = hessian(cx, &mechanism.kinetic_energy, &velocities)?;
    let atoms = cx.sym.atoms().clone();
    let (section, energy, g) = match declared {
        Some((section, (t, g))) => (
            section,
            t.add(&mechanism.kinetic_energy, &atoms),
            g.add(&bodies, &atoms).ok()?,
        ),
        None => (
            sections.get(Section::Bodies)?,
            mechanism.kinetic_energy.clone(),
            bodies,
        ),
    };
    // Sampling needs every coordinate and parameter value: skip it after earlier errors.
    if cx.diagnostics.is_empty() {
        check_positive_definite(cx, &g, section.key.span(), coordinates, parameters);
    }
    Some((energy, g))
}

/// `T`, `V` and `g` as expressions: each normal form written out, or
/// when it is large ([`crate::sym::Context::compact_expression`]) the
/// declared part written out plus the bodies' part as it was derived:
/// their energies, and for `g` their Kane form
/// ([`crate::model::BodyMotion::mass_matrix`]).
pub(super) fn energy_expressions(
    cx: &mut Context,
    (kinetic, g): (&RationalFunction, &Matrix),
    potential: &RationalFunction,
    mechanism: &MechanismParts,
    velocities: &[SymbolId],
) -> Option<EnergyExpressions> {
    let (bodies_kinetic, bodies_potential) = mechanism.energies_derived_as;
    let declared_kinetic = declared_part(cx, kinetic, &mechanism.mechanism.kinetic_energy);
    let declared_potential = declared_part(cx, potential, &mechanism.mechanism.potential_energy);
    let kinetic_derived_as = cx.sym.add2(declared_kinetic, bodies_kinetic);
    let potential_derived_as = cx.sym.add2(declared_potential, bodies_potential);
    let mass_matrix = if mechanism.motions.is_empty() {
        g.to_expression_matrix(&mut cx.sym)
    } else {
        metric_derived_as(cx, g, declared_kinetic, &mechanism.motions, velocities)?
    };
    Some(EnergyExpressions {
        kinetic: cx.sym.compact_expression(kinetic, kinetic_derived_as),
        potential: cx.sym.compact_expression(potential, potential_derived_as),
        mass_matrix,
        declared_kinetic,
        bodies: mechanism.motions.clone(),
    })
}

/// `g_ij` written out, or when large as `d^2 T / d qdot_i d qdot_j` of
/// the declared `T` plus the bodies' Kane form.
fn metric_derived_as(
    cx: &mut Context,
    g: &Matrix,
    declared_kinetic: ExprId,
    bodies: &[BodyMotion],
    velocities: &[SymbolId],
) -> Option<Matrix<ExprId>> {
    let rates: Vec<ExprId> = velocities
        .iter()
        .map(|&v| cx.sym.derivative(declared_kinetic, v))
        .collect();
    let n = velocities.len();
    let mut entries = vec![cx.sym.integer(0); n * n];
    for (j, &vj) in velocities.iter().enumerate() {
        for (i, declared) in cx.sym.derivatives(&rates, vj).into_iter().enumerate() {
            entries[i * n + j] = declared;
        }
    }
    for body in bodies {
        let body_entries = body.mass_matrix(&mut cx.sym, velocities);
        for (entry, body_entry) in entries.iter_mut().zip(body_entries) {
            *entry = cx.sym.add2(*entry, body_entry);
        }
    }
    for (index, entry) in entries.iter_mut().enumerate() {
        *entry = cx
            .sym
            .compact_expression(g.get(index / n, index % n), *entry);
    }
    Matrix::new(n, n, entries).ok()
}

/// The declared part of an energy, `total - bodies`, written out.
fn declared_part(cx: &mut Context, total: &RationalFunction, bodies: &RationalFunction) -> ExprId {
    let declared = total.sub(bodies, cx.sym.atoms());
    cx.sym.expression_of(&declared)
}

/// `(T, g)` of a declared kinetic energy, quadratic in the velocities.
fn metric_of_kinetic_energy(
    cx: &mut Context,
    section: &syntax::Section,
    velocities: &[SymbolId],
) -> Option<(RationalFunction, Matrix)> {
    let expr = cx.expression(section)?;
    let id = cx.lower(expr)?;
    let energy = cx.normal(id, expr.first_span())?;
    if !check_velocity_degree(
        cx,
        &energy,
        expr,
        2,
        "the kinetic energy must be quadratic in the velocities (every term a product of \
         exactly two velocities)",
    ) {
        return None;
    }
    let g = hessian(cx, &energy, velocities)?;
    Some((energy, g))
}

/// `g_ij = d^2 T / d qdot_i d qdot_j`.
fn hessian(cx: &mut Context, energy: &RationalFunction, velocities: &[SymbolId]) -> Option<Matrix> {
    let mut entries = Vec::with_capacity(velocities.len().pow(2));
    for &vi in velocities {
        let first = cx.sym.derivative_of_normal(energy, vi).ok()?;
        for &vj in velocities {
            entries.push(cx.sym.derivative_of_normal(&first, vj).ok()?);
        }
    }
    Matrix::new(velocities.len(), velocities.len(), entries).ok()
}

/// `T = 1/2 qdot^T g qdot`.
fn quadratic_form(cx: &mut Context, g: &Matrix, velocities: &[SymbolId]) -> RationalFunction {
    let atoms: Vec<RationalFunction> = velocities
        .iter()
        .map(|&v| {
            let atom = cx.sym.symbol_atom(v);
            RationalFunction::from_poly(Poly::atom(atom))
        })
        .collect();
    let table = cx.sym.atoms().clone();
    let mut sum = RationalFunction::zero();
    for (i, vi) in atoms.iter().enumerate() {
        for (j, vj) in atoms.iter().enumerate() {
            let term = g.get(i, j).mul(&vi.mul(vj, &table), &table);
            sum = sum.add(&term, &table);
        }
    }
    sum.scale(&Rational::HALF)
}

/// A declared mass matrix is n x n, free of velocities, and symmetric.
fn declared_mass_matrix(cx: &mut Context, section: &syntax::Section, n: usize) -> Option<Matrix> {
    let list = cx.list(section)?;
    if list.items.len() != n {
        cx.diagnostics.error(
            list.span,
            format!(
                "the mass matrix must be {n} x {n} (one row per coordinate), found {} rows",
                list.items.len()
            ),
        );
        return None;
    }
    let mut entries = Vec::with_capacity(n * n);
    let mut spans = Vec::with_capacity(n * n);
    for item in &list.items {
        let row = row_of_expressions(cx, item, n, "a mass-matrix row")?;
        for expr in row {
            let form = velocity_free(
                cx,
                expr,
                "the mass matrix depends on the configuration only: no velocities",
            )?;
            entries.push(form);
            spans.push(expr.first_span());
        }
    }
    let g = Matrix::new(n, n, entries).ok()?;
    check_symmetric(cx, &g, &spans).then_some(g)
}

/// The mass matrix equals its transpose.
fn check_symmetric(cx: &mut Context, g: &Matrix, spans: &[Span]) -> bool {
    let n = g.rows();
    for i in 0..n {
        for j in i + 1..n {
            if g.get(i, j).sub(g.get(j, i), cx.sym.atoms()).is_zero() {
                continue;
            }
            cx.diagnostics.error(
                spans[i * n + j],
                format!(
                    "the mass matrix must be symmetric: entry ({}, {}) differs from entry ({}, {})",
                    i + 1,
                    j + 1,
                    j + 1,
                    i + 1
                ),
            );
            return false;
        }
    }
    true
}

/// The metric is positive definite at the default parameters at a sample
/// of random configurations. Singular sets of measure zero, such as
/// `r = 0` of polar coordinates, are coordinate singularities, not errors,
/// and random samples do not land on them.
fn check_positive_definite(
    cx: &mut Context,
    g: &Matrix,
    span: Span,
    coordinates: &[Variable],
    parameters: &[Parameter],
) {
    let mut generator = SplitMix::new(0x9d2c_5680);
    let n = coordinates.len();
    for _ in 0..DEFINITENESS_SAMPLES {
        let configuration: Vec<f64> = (0..n).map(|_| generator.uniform(-3.0, 3.0)).collect();
        let value_of = |s: SymbolId| {
            coordinates
                .iter()
                .position(|c| c.symbol == s)
                .map(|i| configuration[i])
                .or_else(|| {
                    parameters
                        .iter()
                        .find(|p| p.variable.symbol == s)
                        .map(|p| p.default.to_f64())
                })
                .unwrap_or(f64::NAN)
        };
        let values = g.evaluate(&mut cx.sym, &value_of);
        if let Some(minor) = failed_cholesky_minor(&values, n) {
            let at: Vec<String> = coordinates
                .iter()
                .zip(&configuration)
                .map(|(c, v)| format!("{} = {v:.3}", c.declared.name))
                .collect();
            cx.diagnostics.error(
                span,
                format!(
                    "the mass matrix is not positive definite at the default parameters: at \
                     {} its leading {minor} x {minor} block is not positive definite",
                    at.join(", ")
                ),
            );
            return;
        }
    }
}

/// `V`: the declared potential (default 0) plus the bodies' in the gravity field.
pub(super) fn potential(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    mechanism: &Mechanism,
) -> Option<RationalFunction> {
    let declared = match section {
        Some(section) => {
            let expr = cx.expression(section)?;
            velocity_free(
                cx,
                expr,
                "the potential energy depends on the configuration only: no velocities",
            )?
        }
        None => RationalFunction::zero(),
    };
    Some(declared.add(&mechanism.potential_energy, cx.sym.atoms()))
}

/// The size of the first leading block whose Cholesky pivot is not positive
/// (or not finite), if any.
fn failed_cholesky_minor(values: &[f64], n: usize) -> Option<usize> {
    let mut l = vec![0.0f64; n * n];
    for j in 0..n {
        let mut pivot = values[j * n + j];
        for k in 0..j {
            pivot -= l[j * n + k] * l[j * n + k];
        }
        if !(pivot > 0.0 && pivot.is_finite()) {
            return Some(j + 1);
        }
        let root = pivot.sqrt();
        l[j * n + j] = root;
        for i in j + 1..n {
            let mut sum = values[i * n + j];
            for k in 0..j {
                sum -= l[i * n + k] * l[j * n + k];
            }
            l[i * n + j] = sum / root;
        }
    }
    None
}
