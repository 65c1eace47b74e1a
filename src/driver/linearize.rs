//! Linearization of a model about a steady motion (docs/INTERFACE.md
//! section 5): the operating point from assignments `NAME=EXPR` of
//! coordinates and velocities (`crate::runtime::linearize::point`), the
//! linear system about it with the symmetry reduced and the constraints
//! eliminated (`crate::runtime::linearize::steady`), its eigenvalues; over
//! a sweep of a variable the assignments read, the intervals where the
//! motion is asymptotically stable and where it is neutrally stable (every
//! eigenvalue but the conserved quantities' zeros on the imaginary axis),
//! their ends refined by bisection between grid points
//! ([`sweep::refined_intervals`]); the canonical form
//! `M qddot + v C1 qdot + (g K0 + v^2 K2) q = f` of Meijaard et al. (2007)
//! ([`canonical`]).

pub mod canonical;
pub mod sweep;

use super::expression::{ExpressionError, constant};
use crate::runtime::linearize::{
    self as runtime_linearize, Dynamics, LinearSystem, OperatingPoint, PointError, SteadyError,
};
use std::collections::BTreeMap;
use sweep::{Change, Interval};

/// A problem with the assignments or the operating point, in one line.
#[derive(Debug, thiserror::Error)]
pub enum LinearizeError {
    /// An assignment names neither a coordinate nor a velocity.
    #[error("--at: unknown name `{name}` (coordinates and `dot(q)` velocities: {known})")]
    UnknownName {
        /// The name given.
        name: String,
        /// The names there are.
        known: String,
    },
    /// The sweep variable is also a parameter.
    #[error(
        "--sweep: `{0}` is a parameter; sweep a new name and use it in --at or --param expressions"
    )]
    ParameterSwept(String),
    /// An assignment's expression names what is neither a parameter nor
    /// the sweep variable.
    #[error("--at: `{text}`: unknown name `{name}` (known: {known})")]
    UnknownExpressionName {
        /// The expression.
        text: String,
        /// The name.
        name: String,
        /// The names there are.
        known: String,
    },
    /// An assignment's expression does not read.
    #[error("--at: `{text}`: {source}")]
    Expression {
        /// The expression.
        text: String,
        /// What is wrong with it.
        source: ExpressionError,
    },
    /// The operating point.
    #[error(transparent)]
    Point(#[from] PointError),
    /// The steady motion or its linearization.
    #[error(transparent)]
    Steady(#[from] SteadyError),
    /// The grid.
    #[error(transparent)]
    Sweep(#[from] sweep::SweepError),
    /// A problem at one point of a sweep.
    #[error("at {variable} = {value}: {source}")]
    AtSweepValue {
        /// The sweep variable.
        variable: String,
        /// Its value there.
        value: f64,
        /// What went wrong.
        source: Box<LinearizeError>,
    },
}

/// The point the assignments `at` describe, their expressions reading
/// `names`, linearized with the inputs zero, the entries named
/// `independent` kept in the state.
///
/// # Errors
/// An unknown name, an expression that does not read, or a point that is
/// not a steady motion.
pub fn linearize_at(
    model: &dyn Dynamics,
    names: &BTreeMap<String, f64>,
    at: &[(String, String)],
    independent: &[&str],
) -> Result<LinearSystem, LinearizeError> {
    let coordinates = model.coordinates();
    let velocities = runtime_linearize::point::velocity_names(&coordinates);
    let mut q = vec![None; coordinates.len()];
    let mut qdot = vec![None; coordinates.len()];
    for (name, text) in at {
        let value = evaluate(text, names)?;
        if let Some(i) = coordinates.iter().position(|c| c == name) {
            q[i] = Some(value);
        } else if let Some(i) = velocities.iter().position(|v| v == name) {
            qdot[i] = Some(value);
        } else {
            return Err(LinearizeError::UnknownName {
                name: name.clone(),
                known: coordinates
                    .iter()
                    .chain(&velocities)
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
    }
    let point = OperatingPoint::solve(model, &q, &qdot)?;
    let u = vec![0.0; model.inputs()];
    Ok(runtime_linearize::linearize(
        model,
        &point,
        &u,
        independent,
    )?)
}

/// The value of the expression `text` of `names` (the parameters, the
/// sweep variable) and `pi`.
///
/// # Errors
/// An unknown name, or a text that is not a finite constant.
pub fn evaluate(text: &str, names: &BTreeMap<String, f64>) -> Result<f64, LinearizeError> {
    let bound: Vec<(&str, f64)> = names.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    constant(text, &bound).map_err(|error| match error {
        ExpressionError::UnknownName { name, .. } => LinearizeError::UnknownExpressionName {
            text: text.to_string(),
            name,
            known: (names.keys().map(String::as_str).chain(["pi"]))
                .collect::<Vec<_>>()
                .join(", "),
        },
        source => LinearizeError::Expression {
            text: text.to_string(),
            source,
        },
    })
}

/// The linear systems of a sweep and where its motions are stable.
#[derive(Debug)]
pub struct SweepAnalysis {
    /// The swept variable.
    pub variable: String,
    /// Its values.
    pub values: Vec<f64>,
    /// The linear system at each value.
    pub systems: Vec<LinearSystem>,
    /// The zeros of conserved quantities every system of the family has.
    pub conserved: usize,
    /// The intervals of asymptotic stability, modulo those zeros.
    pub stable: Vec<Interval>,
    /// The intervals of neutral (spectral) stability, modulo those zeros.
    pub neutral: Vec<Interval>,
}

impl SweepAnalysis {
    /// The eigenvalues at each value, `(re, im)` by descending real part.
    pub fn eigenvalues(&self) -> Vec<Vec<(f64, f64)>> {
        self.systems
            .iter()
            .map(|linear| linear.eigenvalues.iter().map(|e| (e.re, e.im)).collect())
            .collect()
    }
}

/// Whether a linear system about a point of the sweep is stable in some
/// sense, the family's zeros of conserved quantities discounted.
type Verdict = fn(&LinearSystem, usize) -> bool;

/// The steady motions `at` over a sweep variable: the linearization at
/// each of its values, the expressions reading the parameters too.
struct Family<'a> {
    model: &'a dyn Dynamics,
    parameters: &'a BTreeMap<String, f64>,
    variable: &'a str,
    at: &'a [(String, String)],
}

impl Family<'_> {
    /// The family of `at` over `variable`, which must not be a parameter.
    fn new<'a>(
        model: &'a dyn Dynamics,
        parameters: &'a BTreeMap<String, f64>,
        variable: &'a str,
        at: &'a [(String, String)],
    ) -> Result<Family<'a>, LinearizeError> {
        if parameters.contains_key(variable) {
            return Err(LinearizeError::ParameterSwept(variable.to_string()));
        }
        Ok(Family {
            model,
            parameters,
            variable,
            at,
        })
    }

    /// The linear system at `value` of the variable.
    fn at_value(&self, value: f64) -> Result<LinearSystem, LinearizeError> {
        let mut names = self.parameters.clone();
        names.insert(self.variable.to_string(), value);
        linearize_at(self.model, &names, self.at, &[]).map_err(|source| {
            LinearizeError::AtSweepValue {
                variable: self.variable.to_string(),
                value,
                source: Box::new(source),
            }
        })
    }

    /// The linear systems at `values`, and the zeros of conserved
    /// quantities every one of them has: a point with more has an
    /// eigenvalue crossing zero.
    fn over(&self, values: &[f64]) -> Result<(Vec<LinearSystem>, usize), LinearizeError> {
        let systems = values
            .iter()
            .map(|&value| self.at_value(value))
            .collect::<Result<Vec<_>, _>>()?;
        let conserved = systems
            .iter()
            .map(LinearSystem::conserved_zeros)
            .min()
            .unwrap_or(0);
        Ok((systems, conserved))
    }

    /// The runs of `values` (where the `systems` are) where `holds`, their
    /// ends refined by bisection on `between`.
    fn intervals(
        &self,
        (values, systems): (&[f64], &[LinearSystem]),
        conserved: usize,
        (holds, between): (Verdict, Verdict),
    ) -> Result<Vec<Interval>, LinearizeError> {
        let on_grid: Vec<bool> = systems.iter().map(|l| holds(l, conserved)).collect();
        sweep::refined_intervals(values, &on_grid, |value| {
            self.at_value(value)
                .map(|linear| between(&linear, conserved))
        })
    }

    /// The intervals of asymptotic stability: a grid point is stable by a
    /// margin; between grid points the change is where the largest real
    /// part crosses zero.
    fn stable(
        &self,
        grid: (&[f64], &[LinearSystem]),
        conserved: usize,
    ) -> Result<Vec<Interval>, LinearizeError> {
        let crossed: Verdict = |linear, conserved| linear.largest_real_part_modulo(conserved) < 0.0;
        self.intervals(grid, conserved, (LinearSystem::is_stable_modulo, crossed))
    }
}

/// The point of `at` linearized at each of `values` of `variable`, the
/// expressions reading the `parameters` too, and the intervals of
/// stability. A grid point is stable by a margin; between grid points the
/// change of asymptotic stability is where the largest real part crosses
/// zero.
///
/// # Errors
/// The variable is a parameter, or a point of the sweep fails (named with
/// its value).
pub fn sweep(
    model: &dyn Dynamics,
    parameters: &BTreeMap<String, f64>,
    (variable, values): (&str, &[f64]),
    at: &[(String, String)],
) -> Result<SweepAnalysis, LinearizeError> {
    let family = Family::new(model, parameters, variable, at)?;
    let (systems, conserved) = family.over(values)?;
    let stable = family.stable((values, &systems), conserved)?;
    let neutral = LinearSystem::is_neutral_modulo;
    let neutral = family.intervals((values, &systems), conserved, (neutral, neutral))?;
    Ok(SweepAnalysis {
        variable: variable.to_string(),
        values: values.to_vec(),
        systems,
        conserved,
        stable,
        neutral,
    })
}

/// Where the steady motions of a sweep are asymptotically stable, and
/// where they gain or lose an unstable mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Stability {
    /// The zeros of conserved quantities every point of the family has.
    pub conserved: usize,
    /// The intervals of asymptotic stability, as [`mod@sweep`] finds them.
    pub stable: Vec<Interval>,
    /// Where the number of unstable modes changes ([`unstable_modes`]),
    /// in increasing order of the variable.
    pub changes: Vec<Change>,
}

/// The number of the eigenvalues of `linear` but `conserved` zeros of
/// conserved quantities whose real part is not below `-margin max(1, max
/// |A_ij|)` (every eigenvalue where they are undefined: a Jordan chain at
/// zero). Zero exactly where the motion is asymptotically stable.
pub fn unstable_modes(linear: &LinearSystem, conserved: usize, margin: f64) -> usize {
    let bound = -margin * linear.a.amax().max(1.0);
    linear
        .free_eigenvalues(conserved)
        .map_or(linear.eigenvalues.len(), |free| {
            free.iter().filter(|e| e.re >= bound).count()
        })
}

/// The intervals of asymptotic stability of the steady motions `at` over
/// `values` of `variable` (the expressions reading the `parameters` too),
/// as [`mod@sweep`] finds them, and the values where the number of unstable
/// modes changes: between grid values where it differs (counted with
/// [`LinearSystem::MARGIN`]), located by bisection on the count without
/// margin (to [`sweep::REFINED`]). Neither the eigenvalues nor the neutral
/// intervals are kept.
///
/// # Errors
/// The variable is a parameter, or a point of the sweep fails (named with
/// its value).
pub fn stability(
    model: &dyn Dynamics,
    parameters: &BTreeMap<String, f64>,
    (variable, values): (&str, &[f64]),
    at: &[(String, String)],
) -> Result<Stability, LinearizeError> {
    let family = Family::new(model, parameters, variable, at)?;
    let (systems, conserved) = family.over(values)?;
    let stable = family.stable((values, &systems), conserved)?;
    let counts: Vec<usize> = (systems.iter())
        .map(|linear| unstable_modes(linear, conserved, LinearSystem::MARGIN))
        .collect();
    let changes = sweep::changes(values, &counts, |value| {
        (family.at_value(value)).map(|linear| unstable_modes(&linear, conserved, 0.0))
    })?;
    Ok(Stability {
        conserved,
        stable,
        changes,
    })
}
