//! Steady motions found (docs/INTERFACE.md section 14, MATH.md section
//! 6.1): the `--at` and `--input` expressions may read unknowns besides
//! the parameters, and `--solve` names the unknowns, such variables or
//! coordinates `--at` leaves free. From `--guess` (0 where not given),
//! `crate::runtime::linearize::find` solves for them by Gauss-Newton on
//! the exact Jacobian of the reduced flow's rates: the model's
//! `acceleration_jacobian` times the derivatives of the expressions in the
//! unknowns (forward differentiation, exact to round-off). The point found
//! is linearized as `chaplygin linearize --at` linearizes one
//! (`crate::runtime::linearize::steady`), its zero eigenvalues named by
//! the directions of the family of steady motions through it.

use super::setup::{self, Asked, InputError, Setup};
use crate::runtime::linearize::find::{self, Given};
use crate::runtime::linearize::point::velocity_names;
use crate::runtime::linearize::{
    self as runtime_linearize, Direction, FindError, LinearSystem, OperatingPoint, SteadyError,
};
use crate::runtime::nalgebra::{DMatrix, DVector};
use chaplygin_codegen::interpret::InterpretedModel;

pub mod trace;

/// What `chaplygin steady` asks, as given.
#[derive(Clone, Copy, Debug, Default)]
pub struct Request<'a> {
    /// `--param NAME=VALUE`.
    pub params: &'a [(String, f64)],
    /// `--at NAME=EXPR`: coordinates and velocities.
    pub at: &'a [(String, String)],
    /// `--input NAME=EXPR`: the inputs, constants of the parameters and
    /// the unknowns.
    pub inputs: &'a [(String, String)],
    /// `--solve NAME,...`: the unknowns.
    pub solve: &'a [String],
    /// `--guess NAME=VALUE`: where the unknowns start (0 where not given).
    pub guess: &'a [(String, f64)],
    /// `--trace VAR=...`'s variable, read by the expressions besides the
    /// unknowns.
    pub trace: Option<&'a str>,
}

/// A problem with the request, or no steady motion, in one line.
#[derive(Debug, thiserror::Error)]
pub enum SteadyMotionError {
    /// The assignments' names or values.
    #[error(transparent)]
    Input(#[from] InputError),
    /// `--solve` names nothing to solve for.
    #[error("--solve: name at least one unknown")]
    NoUnknowns,
    /// A `--solve` name cannot be an unknown.
    #[error("--solve {name}: {reason}")]
    Unknown {
        /// The name.
        name: String,
        /// Why it cannot be one.
        reason: String,
    },
    /// `--trace` names no variable of the expressions.
    #[error("--trace {name}: {reason}")]
    Trace {
        /// The name.
        name: String,
        /// Why it cannot be traced.
        reason: String,
    },
    /// `--guess` names no unknown.
    #[error("--guess {name}: not an unknown of --solve ({known})")]
    Guess {
        /// The name.
        name: String,
        /// The unknowns.
        known: String,
    },
    /// `--input` reads the time or the state.
    #[error(
        "--input: a steady motion's inputs are constants; use numbers, parameters and the unknowns"
    )]
    InputLaw,
    /// No steady motion.
    #[error(transparent)]
    Find(#[from] FindError),
    /// The linearization at the steady motion.
    #[error(transparent)]
    Linearize(#[from] SteadyError),
}

/// What an unknown is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Unknown {
    /// The variable of this index.
    Variable(usize),
    /// The coordinate of this index.
    Coordinate(usize),
}

/// A request resolved against its model: the unknowns and their guess.
pub struct Problem {
    /// The model, the assignments and the input laws.
    pub setup: Setup,
    /// The unknowns' names, as `--solve` orders them.
    pub names: Vec<String>,
    /// The names of all the unknowns `y`: `names`, and with `--trace` its
    /// variable last.
    all_names: Vec<String>,
    unknowns: Vec<Unknown>,
    variables: usize,
    guess: Vec<f64>,
}

/// A steady motion and its linearization.
#[derive(Clone, Debug)]
pub struct SteadyMotion {
    /// The unknowns' names and values.
    pub values: Vec<(String, f64)>,
    /// The point.
    pub point: OperatingPoint,
    /// The inputs there.
    pub inputs: Vec<f64>,
    /// The radius of the circle the body frame's origin follows (infinite
    /// when straight), for a model with a planar symmetry.
    pub radius: Option<f64>,
    /// The linear system about the point.
    pub linear: LinearSystem,
    /// The directions in the linear system's state along which the steady
    /// motions form a family: one per zero eigenvalue of a conserved
    /// quantity.
    pub family: Vec<Direction>,
    /// The Gauss-Newton steps taken.
    pub steps: usize,
    /// The largest rate of the reduced flow left.
    pub residual: f64,
}

impl SteadyMotion {
    /// Whether the motion is asymptotically stable, modulo the zeros of
    /// the family's directions (as `chaplygin linearize` judges).
    pub fn stable(&self) -> bool {
        self.linear.is_stable()
    }
}

/// `request` read against `model`.
///
/// # Errors
/// An unknown name, an unknown that is a parameter or a coordinate
/// `--at` gives or that no expression reads, a guess of no unknown, input
/// laws that are not constants.
pub fn problem(
    model: InterpretedModel,
    request: &Request<'_>,
) -> Result<Problem, SteadyMotionError> {
    if request.solve.is_empty() {
        return Err(SteadyMotionError::NoUnknowns);
    }
    if let Some(name) = (request.solve.iter()).find(|name| model.names().parameters.contains(name))
    {
        return Err(SteadyMotionError::Unknown {
            name: name.clone(),
            reason: "is a parameter; name a new variable and use it in --at or --input \
                     expressions"
                .into(),
        });
    }
    let coordinates = model.names().coordinates.clone();
    let mut variables: Vec<&str> = (request.solve.iter())
        .filter(|name| !coordinates.contains(name))
        .map(String::as_str)
        .collect();
    variables.extend(request.trace);
    let asked = Asked {
        params: request.params,
        state_flag: "--at",
        state: request.at,
        variables: &variables,
        inputs: request.inputs,
        ..Asked::default()
    };
    let setup = setup::resolve(model, &asked)?;
    if !setup.inputs.is_constant() {
        return Err(SteadyMotionError::InputLaw);
    }
    let mut unknowns = (request.solve.iter())
        .map(|name| unknown(&setup, request, &variables, name))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(name) = request.trace {
        traced(&setup, request, name)?;
        unknowns.push(Unknown::Variable(variables.len() - 1));
    }
    let guess = guesses(request)?;
    let all_names = (request.solve.iter().map(String::as_str))
        .chain(request.trace)
        .map(String::from)
        .collect();
    Ok(Problem {
        setup,
        names: request.solve.to_vec(),
        all_names,
        unknowns,
        variables: variables.len(),
        guess,
    })
}

/// What the `--solve` name `name` is.
fn unknown(
    setup: &Setup,
    request: &Request<'_>,
    variables: &[&str],
    name: &str,
) -> Result<Unknown, SteadyMotionError> {
    let error = |reason: &str| SteadyMotionError::Unknown {
        name: name.to_string(),
        reason: reason.to_string(),
    };
    let coordinates = &setup.model.names().coordinates;
    if let Some(i) = coordinates.iter().position(|c| c == name) {
        return match request.at.iter().any(|(given, _)| given == name) {
            true => Err(error(
                "is given by --at; solve a coordinate --at leaves free",
            )),
            false => Ok(Unknown::Coordinate(i)),
        };
    }
    let i = (variables.iter().position(|v| *v == name)).expect("a variable");
    let read = setup.state.reads(name) || request.inputs.iter().any(|(_, text)| reads(text, name));
    match read {
        true => Ok(Unknown::Variable(i)),
        false => Err(error(
            "is neither a coordinate nor read by an --at or --input expression",
        )),
    }
}

/// Whether the `--trace` variable `name` can be traced: not a parameter, a
/// coordinate or an unknown, and read by an expression.
fn traced(setup: &Setup, request: &Request<'_>, name: &str) -> Result<(), SteadyMotionError> {
    let reason = if setup.parameters.iter().any(|(p, _)| p == name) {
        "is a parameter; trace a new variable and use it in --at or --input expressions"
    } else if setup.model.names().coordinates.iter().any(|c| c == name) {
        "is a coordinate; trace a variable and give the coordinate by it with --at"
    } else if request.solve.iter().any(|n| n == name) {
        "is an unknown of --solve"
    } else if !(setup.state.reads(name) || request.inputs.iter().any(|(_, t)| reads(t, name))) {
        "no --at or --input expression reads it"
    } else {
        return Ok(());
    };
    Err(SteadyMotionError::Trace {
        name: name.to_string(),
        reason: reason.to_string(),
    })
}

/// Whether the expression `text` names `name` (as a whole word).
fn reads(text: &str, name: &str) -> bool {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .any(|word| word == name)
}

/// The guess of each unknown, 0 where not given.
fn guesses(request: &Request<'_>) -> Result<Vec<f64>, SteadyMotionError> {
    let mut guess = vec![0.0; request.solve.len()];
    for (name, value) in request.guess {
        let i = (request.solve.iter().position(|n| n == name)).ok_or_else(|| {
            SteadyMotionError::Guess {
                name: name.clone(),
                known: request.solve.join(", "),
            }
        })?;
        guess[i] = *value;
    }
    Ok(guess)
}

impl Problem {
    /// The variables' values at the unknowns `x`.
    fn variables_at(&self, x: &[f64]) -> Vec<f64> {
        let mut variables = vec![0.0; self.variables];
        for (unknown, value) in self.unknowns.iter().zip(x) {
            if let Unknown::Variable(i) = unknown {
                variables[*i] = *value;
            }
        }
        variables
    }

    /// The point's fixed part at `x` and its derivatives.
    ///
    /// # Errors
    /// A value that is not finite, an assignment by a frame.
    fn given(&self, x: &[f64]) -> Result<Given, InputError> {
        let variables = self.variables_at(x);
        let assigned = self.setup.state.at(&variables)?;
        if let Some(asked) = assigned.angular_velocities.first() {
            let (flag, name) = asked.given.clone();
            let reason = "give the velocities `dot(q)` of a steady motion".to_string();
            return Err(InputError::FrameState { flag, name, reason });
        }
        let (n, k) = (assigned.q.len(), x.len());
        let inputs = self.setup.inputs.slopes(&variables, usize::MAX);
        let mut given = Given {
            q: assigned.q,
            qdot: assigned.qdot,
            u: inputs.iter().map(|(value, _)| *value).collect(),
            dq: DMatrix::zeros(n, k),
            dqdot: DMatrix::zeros(n, k),
            du: DMatrix::zeros(inputs.len(), k),
        };
        for (j, unknown) in self.unknowns.iter().enumerate() {
            match *unknown {
                Unknown::Coordinate(i) => {
                    given.q[i] = Some(x[j]);
                    given.dq[(i, j)] = 1.0;
                }
                Unknown::Variable(v) => {
                    let (dq, dqdot) = self.setup.state.slopes(&variables, v)?;
                    given.dq.set_column(j, &DVector::from_vec(dq));
                    given.dqdot.set_column(j, &DVector::from_vec(dqdot));
                    for (row, (_, slope)) in
                        self.setup.inputs.slopes(&variables, v).iter().enumerate()
                    {
                        given.du[(row, j)] = *slope;
                    }
                }
            }
        }
        Ok(given)
    }

    /// The steady motion near the guess, linearized (a traced variable
    /// at 0).
    ///
    /// # Errors
    /// The guess's point does not read, no steady motion near it, or its
    /// linearization fails.
    pub fn solve(&self) -> Result<SteadyMotion, SteadyMotionError> {
        let (all, k) = (self.unknowns.len(), self.names.len());
        let map = Affine {
            origin: DVector::zeros(all),
            basis: DMatrix::from_fn(all, k, |i, j| f64::from(u8::from(i == j))),
        };
        Ok(self.solve_on(&map, &self.guess)?.0)
    }

    /// The steady motion of the unknowns `y = origin + basis z` near
    /// `z = start`, and its `y`.
    ///
    /// # Errors
    /// As [`Self::solve`].
    pub(crate) fn solve_on(
        &self,
        map: &Affine,
        start: &[f64],
    ) -> Result<(SteadyMotion, Vec<f64>), SteadyMotionError> {
        let model = &self.setup.model;
        let first = self.given(&map.at(start))?;
        let given = |z: &[f64]| {
            (self.given(&map.at(z)).map(|given| map.pulled_back(given)))
                .unwrap_or_else(|_| not_finite(&first))
        };
        let values = |z: &[f64]| map.at(z);
        let named = find::Named {
            names: &self.all_names,
            values: &values,
        };
        let found = find::find(model, &given, &named, start)?;
        let linear = runtime_linearize::linearize(model, &found.point, &found.u, &[])?;
        let y = map.at(&found.x);
        let motion = SteadyMotion {
            values: self.names.iter().cloned().zip(y.iter().copied()).collect(),
            radius: find::radius(model, &found.point),
            family: find::family_directions(&linear),
            point: found.point,
            inputs: found.u,
            linear,
            steps: found.steps,
            residual: found.residual,
        };
        Ok((motion, y))
    }

    /// The rates of the reduced flow and their Jacobian in all the
    /// unknowns (with `--trace`, its variable last) at `y`.
    ///
    /// # Errors
    /// The point does not read or cannot be completed.
    pub(crate) fn conditions(
        &self,
        y: &[f64],
    ) -> Result<(DVector<f64>, DMatrix<f64>), SteadyMotionError> {
        let given = self.given(y)?;
        find::conditions(&self.setup.model, &given).map_err(|source| {
            let at: Vec<String> = (self.all_names.iter().zip(y))
                .map(|(name, value)| format!("{name}={value}"))
                .collect();
            let at = at.join(", ");
            SteadyMotionError::Find(FindError::Point { at, source })
        })
    }

    /// Where the unknowns start.
    pub fn guess(&self) -> &[f64] {
        &self.guess
    }
}

/// The unknowns `y = origin + basis z` of the fewer unknowns `z`.
pub(crate) struct Affine {
    /// `y` at `z = 0`.
    pub origin: DVector<f64>,
    /// `dy/dz`.
    pub basis: DMatrix<f64>,
}

impl Affine {
    /// `y` at `z`.
    pub(crate) fn at(&self, z: &[f64]) -> Vec<f64> {
        let y = &self.origin + &self.basis * DVector::from_column_slice(z);
        y.as_slice().to_vec()
    }

    /// `given`'s derivatives in `y` taken to `z`.
    fn pulled_back(&self, mut given: Given) -> Given {
        given.dq = &given.dq * &self.basis;
        given.dqdot = &given.dqdot * &self.basis;
        given.du = &given.du * &self.basis;
        given
    }
}

/// The model's names the columns of `steady.csv` take.
#[derive(Clone, Copy, Debug)]
pub struct Columns<'a> {
    /// The coordinates.
    pub coordinates: &'a [String],
    /// The inputs.
    pub inputs: &'a [String],
}

/// The columns of a row of `steady.csv` after VAR: the unknowns that are
/// not coordinates, the coordinates, the velocities, the inputs, `radius`
/// with a planar symmetry, the eigenvalues and `stable`.
pub fn header(columns: &Columns<'_>, motion: &SteadyMotion) -> Vec<String> {
    let variables = (motion.values.iter()).filter(|(name, _)| !columns.coordinates.contains(name));
    let mut header: Vec<String> = variables.map(|(n, _)| n.clone()).collect();
    header.extend(columns.coordinates.iter().cloned());
    header.extend(velocity_names(columns.coordinates));
    header.extend(columns.inputs.iter().cloned());
    if motion.radius.is_some() {
        header.push("radius".into());
    }
    for i in 1..=motion.linear.eigenvalues.len() {
        header.extend([format!("re_{i}"), format!("im_{i}")]);
    }
    header.push("stable".into());
    header
}

/// The values of [`header`]'s columns.
pub fn row(columns: &Columns<'_>, motion: &SteadyMotion) -> Vec<f64> {
    let variables = (motion.values.iter()).filter(|(name, _)| !columns.coordinates.contains(name));
    let mut row: Vec<f64> = variables.map(|(_, v)| *v).collect();
    row.extend(&motion.point.q);
    row.extend(&motion.point.qdot);
    row.extend(&motion.inputs);
    row.extend(motion.radius);
    for eigenvalue in &motion.linear.eigenvalues {
        row.extend([eigenvalue.re, eigenvalue.im]);
    }
    row.push(f64::from(u8::from(motion.stable())));
    row
}

/// A point no iterate accepts: `start`'s shape, its values not finite.
fn not_finite(start: &Given) -> Given {
    let mut given = start.clone();
    given.u.iter_mut().for_each(|u| *u = f64::NAN);
    given.q.iter_mut().for_each(|q| *q = Some(f64::NAN));
    given
}

/// The steady motion of `request` on `model`.
///
/// # Errors
/// [`SteadyMotionError`].
pub fn steady(
    model: InterpretedModel,
    request: &Request<'_>,
) -> Result<SteadyMotion, SteadyMotionError> {
    problem(model, request)?.solve()
}
