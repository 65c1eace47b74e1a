//! A model run without compiling Rust: the programs of the emitted functions,
//! interpreted.
//!
//! [`InterpretedModel::from_source`] runs the stages [`crate::generate`]
//! runs (parse, check, constraint analysis, emission) and keeps, for each
//! emitted function, the [`crate::ir::Program`] its body was emitted from.
//! Its methods have the meaning of the generated methods of the same name
//! (docs/guide/build-scripts.md, "What a model compiles into"), on slices instead of arrays:
//! `q`, `qdot` of length n, `u` of length p, `x = (q, alpha)` of length
//! s = n + k, `alpha` of length k; matrices are returned row-major.
//!
//! The programs are evaluated by [`crate::ir::Program::evaluate`], which
//! runs each operation with the `f64` method the emitted code calls (the
//! numeric solve of `acceleration` is part of its program). For the
//! built-in models the results are
//! bit-identical to the compiled ones (`models/tests/interpreter.rs`);
//! that is not promised in general, since an optimizing compiler may
//! evaluate `powi` with a constant exponent as a product chain where the
//! interpreter calls the library `powi`.
//!
//! With a symmetry, the momentum items are available through
//! [`InterpretedModel::call`] (`momentum`, `momentum_rhs`,
//! `momentum_input_matrix`, `nonholonomic_connection`, `locked_inertia`,
//! `body_velocity`), and [`InterpretedModel::shape_acceleration`] and
//! [`InterpretedModel::reconstructed_velocity`] compose `body_velocity` with
//! `acceleration` and with the group's action as the emitted code does;
//! [`InterpretedModel::momentum_form_rhs`] is the whole momentum
//! formulation's right-hand side, with its exact Jacobian and Hessian.
//!
//! A mechanism with bodies, or a model with a `drawing:` section, has, for
//! the interpreter alone, `drawing(q)`: the gravity field, the bodies'
//! centres, frames, masses and inertias, the contact points and the drawing
//! items' positions, orientations and sizes ([`InterpretedModel::bodies`],
//! [`InterpretedModel::drawing`]), what animating a run needs
//! (docs/INTERFACE.md section 10).

mod charts;
mod drawing;
mod dynamics;
mod fixed;
mod momentum;
mod second;

pub use crate::ir::{Backend, Engine, Interpreter};
pub use crate::model::drawing::{DISC_THICKNESS, DrawnItem, Figure, Orientation};
pub use drawing::{Bodies, BodyName, BodyState, ContactName, Drawing};
pub use fixed::{Fixed, SizeMismatch};
pub use second::{ParameterBlocks, ParameterCurvatures, RowCurvatures};

use crate::derive::constraints::ChartFit;
use crate::derive::port_hamiltonian::momentum_names;
use crate::diagnostic::Diagnostics;
use crate::emit::{self, Lowered};
use crate::ir::IrError;
use crate::model::{FrameTurn, GroupFactor, Model};
use crate::{Analysed, analysed_model, over_budget};
use chaplygin_runtime::simulate::GuardedValue;
use chaplygin_runtime::system::Guard;
use std::sync::Arc;

/// The names of a model and its sizes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Names {
    /// The coordinates `q`, in order.
    pub coordinates: Vec<String>,
    /// The parameters, in order.
    pub parameters: Vec<String>,
    /// The inputs `u`, in order.
    pub inputs: Vec<String>,
    /// The constraints, in declared order.
    pub constraints: Vec<String>,
    /// The reduced momenta `alpha` (the momentum basis rows).
    pub momenta: Vec<String>,
    /// The declared points (`positions` returns each one's ground position).
    pub points: Vec<String>,
    /// The configuration constraints `f(q) = 0` (`holonomic_residual`).
    pub holonomic: Vec<String>,
    /// The declared frames, in the order of `orientations`.
    pub frames: Vec<String>,
}

/// The sizes of a model: `n` coordinates, `c` constraints, `k = n - c`,
/// `p` inputs, the reduced state's `s = n + k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sizes {
    /// Coordinates.
    pub n: usize,
    /// Constraints.
    pub c: usize,
    /// Degrees of freedom in velocity.
    pub k: usize,
    /// Inputs.
    pub p: usize,
    /// Reduced state.
    pub s: usize,
}

/// [`InterpretedModel::set_parameter`] was given a name the model does not declare.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown parameter `{name}`; the model's parameters are {known:?}")]
pub struct UnknownParameter {
    /// The name given.
    pub name: String,
    /// The model's parameters.
    pub known: Vec<String>,
}

/// A failed call of an interpreted function.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CallError {
    /// The model has no function of that name (the momentum items need a symmetry).
    #[error("the model has no interpreted function `{name}`")]
    UnknownFunction {
        /// The name asked for.
        name: String,
    },
    /// The number of argument slices differs from the function's.
    #[error("`{function}` takes {expected} arguments, found {found}")]
    ArgumentCount {
        /// The function.
        function: String,
        /// Its number of arguments.
        expected: usize,
        /// The number given.
        found: usize,
    },
    /// An argument slice has the wrong length.
    #[error("argument `{argument}` of `{function}` has {expected} entries, found {found}")]
    ArgumentLength {
        /// The function.
        function: String,
        /// The argument (`q`, `qdot`, `u`, `x`, `alpha`, ...).
        argument: String,
        /// Its length.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// The program itself refused the evaluation (a bug of the interpreter).
    #[error("`{function}`: {source}")]
    Program {
        /// The function.
        function: String,
        /// What the program reported.
        source: IrError,
    },
}

/// The values of a call whose arguments its caller sized: a failure is a
/// defect of the engine, reported by a panic with the engine's error
/// rather than by wrong numbers.
pub fn evaluated<T>(result: Result<T, CallError>) -> T {
    result.unwrap_or_else(|error| panic!("interpreted model: {error}"))
}

/// `(d qddot/dq, d qddot/dqdot, d qddot/du)`, each row-major.
pub type Jacobians = (Vec<f64>, Vec<f64>, Vec<f64>);

/// One emitted function's name and program, and the program's position
/// in [`InterpretedModel::programs`] (what the engine runs it by).
#[derive(Clone)]
struct Interpreted {
    name: &'static str,
    lowered: Lowered,
    index: usize,
}

/// A model's emitted functions, interpreted (see the module documentation).
///
/// A clone shares the programs and the engine (the native code of
/// [`InterpretedModel::set_engine`]) and has its own parameter values.
#[derive(Clone)]
pub struct InterpretedModel {
    names: Names,
    sizes: Sizes,
    defaults: Vec<f64>,
    parameters: Vec<f64>,
    functions: Arc<[Interpreted]>,
    /// The reduced items of each other chart of D (chart 1, 2, ...).
    chart_functions: Arc<[Vec<Interpreted>]>,
    /// How each chart derived at build time fits, chart 0 first.
    charts: Vec<ChartFit>,
    /// The guards of the model's own expressions, in the order of the
    /// `domain` function's values.
    guards: Vec<(String, Guard)>,
    /// The momentum basis's divisors that depend on the parameters alone,
    /// described, in the order of the `basis_divisors` function's values.
    basis_divisors: Vec<String>,
    report: String,
    /// What runs the programs.
    engine: Arc<dyn Engine>,
    /// With a symmetry, the coordinates the group acts on.
    group: Option<Vec<usize>>,
    /// The symmetry group's factors (empty without a symmetry).
    symmetry: Vec<GroupFactor>,
    /// The mechanism's bodies and contacts, by name (`drawing(q)`'s layout).
    bodies: drawing::Bodies,
    /// How each frame of [`Names::frames`] is turned from its parent.
    turns: Vec<FrameTurn>,
    /// The model's text, derived again by
    /// [`InterpretedModel::with_coordinate_forces_on`].
    source: Arc<str>,
}

impl std::fmt::Debug for InterpretedModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InterpretedModel")
            .field("names", &self.names)
            .field("sizes", &self.sizes)
            .field("parameters", &self.parameters)
            .finish_non_exhaustive()
    }
}

impl InterpretedModel {
    /// Parses, checks, analyses and emits the model text (the text
    /// [`crate::generate`] takes), keeping the functions' programs, which
    /// the [`Interpreter`] runs.
    pub fn from_source(source: &str) -> Result<InterpretedModel, Diagnostics> {
        InterpretedModel::from_source_on(source, &Interpreter)
    }

    /// [`InterpretedModel::from_source`], the programs run by the engine
    /// `backend` makes of them, and the derivation's own numeric searches
    /// (the charts' singular sets) by the engines it makes of theirs.
    pub fn from_source_on(
        source: &str,
        backend: &dyn Backend,
    ) -> Result<InterpretedModel, Diagnostics> {
        InterpretedModel::forced_on(source, backend, &[])
    }

    /// This model derived again with a generalized force along each
    /// coordinate of `forced` (indices into [`Names::coordinates`]) as an
    /// input after the declared ones, named `force(q)`, its column of
    /// `B(q)` the unit vector of `q` (`Model::with_coordinate_forces`);
    /// its programs run by the engine `backend` makes, its parameters'
    /// values kept.
    pub fn with_coordinate_forces_on(
        &self,
        forced: &[usize],
        backend: &dyn Backend,
    ) -> Result<InterpretedModel, Diagnostics> {
        let mut forced = InterpretedModel::forced_on(&self.source, backend, forced)?;
        forced.parameters.clone_from(&self.parameters);
        Ok(forced)
    }

    /// [`InterpretedModel::from_source_on`] with the forces of
    /// [`InterpretedModel::with_coordinate_forces_on`].
    fn forced_on(
        source: &str,
        backend: &dyn Backend,
        forced: &[usize],
    ) -> Result<InterpretedModel, Diagnostics> {
        let Analysed {
            model,
            mut cx,
            constraints,
        } = analysed_model(source, backend)?;
        let mut model = model.with_coordinate_forces(forced);
        model.emits_rust = false;
        let emitted = crate::derive::derivation(&model, &mut cx, &constraints, backend)
            .and_then(|derivation| emit::emit(&model, &mut cx, &constraints, &derivation));
        over_budget(&model, &cx)?;
        let emitted = emitted?;
        let mut indices = 0..;
        let functions = interpreted(emitted.functions, &mut indices).into();
        let chart_functions = emitted
            .chart_functions
            .into_iter()
            .map(|functions| interpreted(functions, &mut indices))
            .collect();
        let (n, c, k, p) = (model.n(), model.c(), model.k(), model.p());
        let defaults = model.parameter_defaults();
        let mut interpreted = InterpretedModel {
            names: names(&model),
            sizes: Sizes {
                n,
                c,
                k,
                p,
                s: n + k,
            },
            parameters: defaults.clone(),
            defaults,
            functions,
            chart_functions,
            charts: emitted.charts,
            guards: emitted
                .guards
                .into_iter()
                .map(|guarded| (guarded.description, guarded.guard))
                .collect(),
            basis_divisors: emitted.basis_divisors,
            report: emitted.report,
            engine: Arc::new(Interpreter),
            group: model
                .symmetry
                .as_ref()
                .map(|symmetry| symmetry.group_coordinates()),
            symmetry: model
                .symmetry
                .as_ref()
                .map(|symmetry| symmetry.factors.clone())
                .unwrap_or_default(),
            bodies: drawing::bodies(&model),
            turns: model.mechanism.turns.clone(),
            source: source.into(),
        };
        let programs: Vec<_> = interpreted.programs().map(|(_, program)| program).collect();
        interpreted.engine = Arc::from(backend.engine(&programs));
        Ok(interpreted)
    }

    /// Runs the programs by the engine `compile` makes of them (given in
    /// the order of [`InterpretedModel::programs`]), for example native
    /// code compiled at run time; where `compile` fails, its error is
    /// returned and the engine stays as it was.
    pub fn set_engine<E>(
        &mut self,
        compile: impl FnOnce(&[&crate::ir::Program]) -> Result<Box<dyn Engine>, E>,
    ) -> Result<(), E> {
        let programs: Vec<_> = self.programs().map(|(_, program)| program).collect();
        self.engine = Arc::from(compile(&programs)?);
        Ok(())
    }

    /// The engine that runs the programs ([`Interpreter`] unless loaded on
    /// another backend or [`InterpretedModel::set_engine`] set another).
    pub fn engine(&self) -> &dyn Engine {
        self.engine.as_ref()
    }

    /// The names of the coordinates, parameters, inputs, constraints,
    /// momenta, points and configuration constraints.
    pub fn names(&self) -> &Names {
        &self.names
    }

    /// How each frame of [`Names::frames`] is turned from its parent.
    pub fn turns(&self) -> &[FrameTurn] {
        &self.turns
    }

    /// The sizes n, c, k, p, s.
    pub fn sizes(&self) -> Sizes {
        self.sizes
    }

    /// The symmetry group's factors, as declared (empty without a symmetry).
    pub fn symmetry(&self) -> &[GroupFactor] {
        &self.symmetry
    }

    /// The derivation report, the generated `REPORT`.
    pub fn report(&self) -> &str {
        &self.report
    }

    /// The declared defaults of the parameters, in order.
    pub fn parameter_defaults(&self) -> &[f64] {
        &self.defaults
    }

    /// The current parameter values, in order.
    pub fn parameter_values(&self) -> &[f64] {
        &self.parameters
    }

    /// Sets the parameter `name` to `value`.
    pub fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), UnknownParameter> {
        let index = self
            .names
            .parameters
            .iter()
            .position(|p| p == name)
            .ok_or_else(|| UnknownParameter {
                name: name.to_string(),
                known: self.names.parameters.clone(),
            })?;
        self.parameters[index] = value;
        Ok(())
    }

    /// The names of the interpreted functions, in emission order.
    pub fn functions(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.functions.iter().map(|f| f.name)
    }

    /// Every program the model runs, with its function's name: chart 0's
    /// functions in emission order, then each other chart's reduced items.
    /// A program's inputs are its function's arguments, concatenated in
    /// order, then the parameters.
    pub fn programs(&self) -> impl Iterator<Item = (&'static str, &crate::ir::Program)> + '_ {
        self.functions
            .iter()
            .chain(self.chart_functions.iter().flatten())
            .map(|f| (f.name, &f.lowered.program))
    }

    /// The arguments of the function `name`: each array's name and length, in order.
    pub fn arguments(&self, name: &str) -> Option<Vec<(&'static str, usize)>> {
        self.functions
            .iter()
            .find(|f| f.name == name)
            .map(|f| f.lowered.arguments.clone())
    }

    /// The function `name` at the argument slices, in its argument order;
    /// a matrix is returned row-major. `acceleration` returns `qddot` then
    /// `lambda`.
    pub fn call(&self, name: &str, arguments: &[&[f64]]) -> Result<Vec<f64>, CallError> {
        self.evaluate(function_among(&self.functions, name)?, arguments)
    }

    /// [`InterpretedModel::call`] into `outputs`, which must have the
    /// function's length. The program's inputs are gathered in a buffer of
    /// the calling thread, kept from call to call: once it has grown to the
    /// largest program's inputs, a call on the JIT allocates nothing.
    ///
    /// # Errors
    /// As [`InterpretedModel::call`], and [`CallError::Program`] with
    /// [`IrError::OutputCount`] when `outputs` has the wrong length.
    pub fn call_into(
        &self,
        name: &str,
        arguments: &[&[f64]],
        outputs: &mut [f64],
    ) -> Result<(), CallError> {
        self.evaluate_into(function_among(&self.functions, name)?, arguments, outputs)
    }

    /// The model's guarded expressions at `q` (the generated `DOMAIN` and
    /// `domain`).
    pub fn domain(&self, q: &[f64]) -> Result<Vec<GuardedValue<'_>>, CallError> {
        let values = self.call("domain", &[q])?;
        Ok(self
            .guards
            .iter()
            .zip(values)
            .map(|((description, guard), value)| GuardedValue {
                description: description.as_str().into(),
                guard: *guard,
                value,
            })
            .collect())
    }

    /// The momentum basis's divisors that depend on the parameters alone
    /// (the generated `BASIS_DIVISORS` and `basis_divisors`), as guards
    /// that must not vanish; none without a momentum equation.
    pub fn basis_divisors(&self) -> Result<Vec<GuardedValue<'_>>, CallError> {
        if self.basis_divisors.is_empty() {
            return Ok(Vec::new());
        }
        let values = self.call("basis_divisors", &[])?;
        Ok(self
            .basis_divisors
            .iter()
            .zip(values)
            .map(|(description, value)| GuardedValue {
                description: description.as_str().into(),
                guard: Guard::NonZero,
                value,
            })
            .collect())
    }

    /// The names of the constraint rows that are dependent at `q`
    /// (`chaplygin_runtime::monitor::dependent_rows`).
    pub fn dependent_rows(&self, q: &[f64]) -> Result<Vec<String>, CallError> {
        let (n, c) = (self.sizes.n, self.sizes.c);
        let rows = self.constraint_matrix(q)?;
        let rows = chaplygin_runtime::nalgebra::DMatrix::from_row_slice(c, n, &rows);
        Ok(chaplygin_runtime::monitor::dependent_rows(&rows)
            .into_iter()
            .map(|i| self.names.constraints[i].clone())
            .collect())
    }

    /// Runs `function` at `arguments` into a new vector.
    fn evaluate(
        &self,
        function: &Interpreted,
        arguments: &[&[f64]],
    ) -> Result<Vec<f64>, CallError> {
        let mut outputs = vec![0.0; function.lowered.program.outputs().len()];
        self.evaluate_into(function, arguments, &mut outputs)?;
        Ok(outputs)
    }

    /// Runs `function` at `arguments` into `outputs`, its inputs gathered
    /// in the calling thread's [`PROGRAM_INPUTS`].
    fn evaluate_into(
        &self,
        function: &Interpreted,
        arguments: &[&[f64]],
        outputs: &mut [f64],
    ) -> Result<(), CallError> {
        let lowered = &function.lowered;
        check_arguments(function.name, &lowered.arguments, arguments)?;
        PROGRAM_INPUTS.with_borrow_mut(|inputs| {
            inputs.clear();
            arguments
                .iter()
                .for_each(|values| inputs.extend_from_slice(values));
            inputs.extend_from_slice(&self.parameters);
            self.engine
                .evaluate(function.index, &lowered.program, inputs, outputs)
                .map_err(|source| CallError::Program {
                    function: function.name.to_string(),
                    source,
                })
        })
    }

    /// The mass matrix `g(q)`, n x n.
    pub fn mass_matrix(&self, q: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("mass_matrix", &[q])
    }

    /// The total energy `T + V`.
    pub fn energy(&self, q: &[f64], qdot: &[f64]) -> Result<f64, CallError> {
        self.call("energy", &[q, qdot]).map(|values| values[0])
    }

    /// The constraint rows `A(q)`, c x n.
    pub fn constraint_matrix(&self, q: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("constraint_matrix", &[q])
    }

    /// The constraint residual `A(q) qdot`.
    pub fn constraint_residual(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("constraint_residual", &[q, qdot])
    }

    /// The Lagrange-d'Alembert accelerations and multipliers `(qddot, lambda)`.
    pub fn acceleration(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>), CallError> {
        let mut values = self.call("acceleration", &[q, qdot, u])?;
        let multipliers = values.split_off(self.sizes.n);
        Ok((values, multipliers))
    }

    /// The exact Jacobians of `qddot`, `(d qddot/dq, d qddot/dqdot,
    /// d qddot/du)`, each row-major (n x n, n x n, n x p).
    pub fn acceleration_jacobian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
    ) -> Result<Jacobians, CallError> {
        let n = self.sizes.n;
        let mut by_q = self.call("acceleration_jacobian", &[q, qdot, u])?;
        let mut by_qdot = by_q.split_off(n * n);
        let by_u = by_qdot.split_off(n * n);
        Ok((by_q, by_qdot, by_u))
    }

    /// The reduced momenta `alpha = P g qdot`.
    pub fn momenta(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("momenta", &[q, qdot])
    }

    /// The velocities `qdot = g^-1 h^T alpha`.
    pub fn velocities(&self, q: &[f64], alpha: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("velocities", &[q, alpha])
    }

    /// The reduced energy `Hbar(x)`.
    pub fn hamiltonian(&self, x: &[f64]) -> Result<f64, CallError> {
        self.call("hamiltonian", &[x]).map(|values| values[0])
    }

    /// The gradient `dHbar/dx`.
    pub fn hamiltonian_gradient(&self, x: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("hamiltonian_gradient", &[x])
    }

    /// The structure matrix `Jbar(x)`, s x s.
    pub fn structure_matrix(&self, x: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("structure_matrix", &[x])
    }

    /// The reduced input matrix `Bbar(x)`, s x p.
    pub fn input_matrix(&self, x: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("input_matrix", &[x])
    }

    /// The reduced equations `xdot = Jbar dHbar/dx + Bbar u`.
    pub fn reduced_rhs(&self, x: &[f64], u: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("reduced_rhs", &[x, u])
    }

    /// Their Jacobian `d xdot / dx`, s x s.
    pub fn reduced_rhs_jacobian(&self, x: &[f64], u: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("reduced_rhs_jacobian", &[x, u])
    }

    /// The output `y = Bbar^T dHbar/dx`.
    pub fn output(&self, x: &[f64]) -> Result<Vec<f64>, CallError> {
        self.call("output", &[x])
    }

    /// With a symmetry, the indices of the shape coordinates `r` in `q`
    /// (those the group does not act on), in declared order.
    pub fn shape(&self) -> Option<Vec<usize>> {
        let group = self.group.as_ref()?;
        Some((0..self.sizes.n).filter(|i| !group.contains(i)).collect())
    }
}

/// The emitted functions that have a program, by name, numbered on from
/// `indices`.
fn interpreted(
    functions: Vec<emit::Function>,
    indices: &mut std::ops::RangeFrom<usize>,
) -> Vec<Interpreted> {
    functions
        .into_iter()
        .filter_map(|function| {
            let name = function.name;
            function.lowered.map(|lowered| Interpreted {
                name,
                lowered,
                index: indices.next().unwrap_or_default(),
            })
        })
        .collect()
}

thread_local! {
    /// The inputs of the program being run (its arguments, then the
    /// parameters), kept from call to call so that a call allocates only
    /// until the buffer has grown to the largest program's inputs.
    static PROGRAM_INPUTS: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The function `name` among `functions`.
fn function_among<'f>(
    functions: &'f [Interpreted],
    name: &str,
) -> Result<&'f Interpreted, CallError> {
    functions
        .iter()
        .find(|f| f.name == name)
        .ok_or_else(|| CallError::UnknownFunction {
            name: name.to_string(),
        })
}

/// `Err` unless `arguments` has the number and the lengths of `layout`,
/// the arguments of `function`.
fn check_arguments(
    function: &str,
    layout: &[(&'static str, usize)],
    arguments: &[&[f64]],
) -> Result<(), CallError> {
    if layout.len() != arguments.len() {
        return Err(CallError::ArgumentCount {
            function: function.to_string(),
            expected: layout.len(),
            found: arguments.len(),
        });
    }
    for (&(argument, expected), values) in layout.iter().zip(arguments) {
        if values.len() != expected {
            return Err(CallError::ArgumentLength {
                function: function.to_string(),
                argument: argument.to_string(),
                expected,
                found: values.len(),
            });
        }
    }
    Ok(())
}

fn names(model: &Model) -> Names {
    let declared = |list: &[crate::model::Declared]| list.iter().map(|d| d.name.clone()).collect();
    Names {
        coordinates: model
            .coordinates
            .iter()
            .map(|c| c.declared.name.clone())
            .collect(),
        parameters: model
            .parameters
            .iter()
            .map(|p| p.variable.declared.name.clone())
            .collect(),
        inputs: declared(&model.inputs),
        constraints: declared(&model.constraints),
        momenta: momentum_names(model),
        points: declared(&model.mechanism.points),
        holonomic: declared(&model.mechanism.holonomic),
        frames: declared(&model.mechanism.frames),
    }
}

#[cfg(test)]
mod tests {
    use super::InterpretedModel;
    use crate::fixtures::SNAKEBOARD;

    /// MATH.md 3.1 at a state, with `m` and `jt` changed from their defaults:
    /// `xdot = (alpha1/m) cos phi cos theta`, `ydot = (alpha1/m) cos phi sin theta`,
    /// `thetadot = alpha1 sin phi / (m r)`, `psidot = alpha2/Jt - alpha1 sin phi / (m r)`,
    /// `phidot = alpha3/Jw`, `alpha1dot = -(sin phi / r) u1`, `alpha2dot = u1`,
    /// `alpha3dot = u2`.
    #[test]
    fn the_snakeboard_reduced_equations_are_those_of_math_3_1() {
        let mut snakeboard = InterpretedModel::from_source(SNAKEBOARD).expect("compiles");
        snakeboard.set_parameter("m", 2.5).expect("declared");
        snakeboard.set_parameter("jt", 0.7).expect("declared");
        let (m, r, jt, jw) = (2.5, 0.5, 0.7, 0.05);
        let (theta, phi) = (0.4f64, -0.9f64);
        let (a1, a2, a3) = (1.3, -0.6, 0.8);
        let (u1, u2) = (0.25, -1.5);
        let x = [0.1, -0.2, theta, 0.3, phi, a1, a2, a3];
        let expected = [
            a1 / m * phi.cos() * theta.cos(),
            a1 / m * phi.cos() * theta.sin(),
            a1 * phi.sin() / (m * r),
            a2 / jt - a1 * phi.sin() / (m * r),
            a3 / jw,
            -(phi.sin() / r) * u1,
            u1,
            u2,
        ];
        let found = snakeboard.reduced_rhs(&x, &[u1, u2]).expect("evaluates");
        for (i, (f, e)) in found.iter().zip(expected).enumerate() {
            assert!((f - e).abs() <= 1e-14 * e.abs().max(1.0), "{i}: {f} vs {e}");
        }
        assert_eq!(snakeboard.parameter_values(), [2.5, 0.5, 0.7, 0.05]);
        assert_eq!(snakeboard.parameter_defaults(), [1.0, 0.5, 0.3, 0.05]);
        assert_eq!(snakeboard.names().momenta, ["group", "torso", "wheels"]);
        let hamiltonian = snakeboard.hamiltonian(&x).expect("evaluates");
        let energy = a1 * a1 / (2.0 * m) + a2 * a2 / (2.0 * jt) + a3 * a3 / (2.0 * jw);
        assert!((hamiltonian - energy).abs() <= 1e-14 * energy);
    }
}
