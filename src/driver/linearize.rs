//! Linearization of a model about a steady motion (docs/INTERFACE.md
//! section 5): the operating point from the assignments `NAME=EXPR` of
//! coordinates and velocities of a resolved request
//! (`crate::driver::setup`, solved by `crate::runtime::linearize::point`), the
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

use super::setup::{InputError, Setup};
use crate::runtime::linearize::{
    self as runtime_linearize, LinearSystem, OperatingPoint, PointError, SteadyError,
};
use sweep::{Change, Interval};

/// A problem with the request or the operating point, in one line.
#[derive(Debug, thiserror::Error)]
pub enum LinearizeError {
    /// The assignments' names or values.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The sweep variable is also a parameter.
    #[error(
        "--sweep: `{0}` is a parameter; sweep a new name and use it in --at or --param expressions"
    )]
    ParameterSwept(String),
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

/// The point the state assignments of `setup` give at the values of its
/// `variables`, linearized with the inputs zero, the entries named
/// `independent` kept in the state.
///
/// # Errors
/// A value that is not finite, or a point that is not a steady motion.
pub fn linearize_at(
    setup: &Setup,
    variables: &[f64],
    independent: &[&str],
) -> Result<LinearSystem, LinearizeError> {
    let assigned = setup.state.at(variables)?;
    if let Some(asked) = assigned.angular_velocities.first() {
        let (flag, name) = asked.given.clone();
        let reason = "a frame's angular velocity sets a run's start (--initial): give the \
                      velocities `dot(q)` here"
            .to_string();
        return Err(InputError::FrameState { flag, name, reason }.into());
    }
    let point = OperatingPoint::solve(&setup.model, &assigned.q, &assigned.qdot)?;
    let u = vec![0.0; setup.model.sizes().p];
    Ok(runtime_linearize::linearize(
        &setup.model,
        &point,
        &u,
        independent,
    )?)
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

/// The steady motions of a setup's state assignments over its one
/// variable: the linearization at each of its values.
struct Family<'a> {
    setup: &'a Setup,
    variable: &'a str,
}

impl Family<'_> {
    /// The family of `setup` over `variable`, which must not be a
    /// parameter.
    fn new<'a>(setup: &'a Setup, variable: &'a str) -> Result<Family<'a>, LinearizeError> {
        if setup.parameters.iter().any(|(name, _)| name == variable) {
            return Err(LinearizeError::ParameterSwept(variable.to_string()));
        }
        Ok(Family { setup, variable })
    }

    /// The linear system at `value` of the variable.
    fn at_value(&self, value: f64) -> Result<LinearSystem, LinearizeError> {
        linearize_at(self.setup, &[value], &[]).map_err(|source| LinearizeError::AtSweepValue {
            variable: self.variable.to_string(),
            value,
            source: Box::new(source),
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

/// The point of the state assignments of `setup` linearized at each of
/// `values` of its `variable`, and the intervals of stability. A grid point is stable by a margin; between grid points the
/// change of asymptotic stability is where the largest real part crosses
/// zero.
///
/// # Errors
/// The variable is a parameter, or a point of the sweep fails (named with
/// its value).
pub fn sweep(
    setup: &Setup,
    (variable, values): (&str, &[f64]),
) -> Result<SweepAnalysis, LinearizeError> {
    let family = Family::new(setup, variable)?;
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
    /// The intervals of asymptotic stability, as [`sweep()`] finds them.
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

/// The intervals of asymptotic stability of the steady motions of the
/// state assignments of `setup` over `values` of its `variable`, as
/// [`sweep()`] finds them, and the values where the number of unstable
/// modes changes: between grid values where it differs (counted with
/// [`LinearSystem::MARGIN`]), located by bisection on the count without
/// margin (to [`sweep::REFINED`]). Neither the eigenvalues nor the neutral
/// intervals are kept.
///
/// # Errors
/// The variable is a parameter, or a point of the sweep fails (named with
/// its value).
pub fn stability(
    setup: &Setup,
    (variable, values): (&str, &[f64]),
) -> Result<Stability, LinearizeError> {
    let family = Family::new(setup, variable)?;
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
