//! A nonlinear program with equality constraints and bounds,
//!
//! ```text
//! minimize J(z)  subject to  c(z) = 0,  lo <= z <= hi,
//! ```
//!
//! and the solvers that solve one behind one trait ([`Solver`]). The
//! solver's answer is a candidate: `kkt` verifies it.
//!
//! The multipliers follow Ipopt's convention (Wächter and Biegler, "On the
//! implementation of an interior-point filter line-search algorithm",
//! Math. Program. 106, 2006, eq. 4): the Lagrangian's gradient is
//! `grad J + Jc^T lambda - z_lo + z_hi`, with `z_lo, z_hi >= 0`.
//!
//! A solver reports each iteration to an [`Observer`] (its objective and
//! its primal and dual infeasibility, as Ipopt's iteration log shows
//! them), which may stop it there: the answer is then the last iterate.

use std::ffi::{c_int, c_void};
use std::ops::ControlFlow;

#[cfg(feature = "ipopt")]
pub mod ipopt;

/// A nonlinear program: every constraint is an equality `c_i(z) = 0`.
pub trait Nlp {
    /// The number of variables.
    fn variables(&self) -> usize;
    /// The number of constraints.
    fn constraints(&self) -> usize;
    /// The lower and upper bounds of the variables (infinite where none).
    fn bounds(&self) -> (&[f64], &[f64]);
    /// Where the solver starts.
    fn guess(&self) -> Vec<f64>;
    /// `J(z)`; `None` where it is not finite.
    fn objective(&self, z: &[f64]) -> Option<f64>;
    /// `grad J(z)` into `gradient`; whether it is finite.
    fn gradient(&self, z: &[f64], gradient: &mut [f64]) -> bool;
    /// `c(z)` into `residuals`; whether they are finite.
    fn residuals(&self, z: &[f64], residuals: &mut [f64]) -> bool;
    /// The (row, column) of each structurally nonzero entry of `dc/dz`.
    fn jacobian_structure(&self) -> &[(usize, usize)];
    /// The entries of `dc/dz` in the order of
    /// [`Nlp::jacobian_structure`]; whether they are finite.
    fn jacobian_values(&self, z: &[f64], values: &mut [f64]) -> bool;
    /// What constraint `row` holds at `z`, in words, for a message.
    fn describe_row(&self, _z: &[f64], row: usize) -> String {
        format!("constraint {row}")
    }
    /// The (row, column), row >= column, of each entry of the lower
    /// triangle of the Lagrangian's Hessian that may be nonzero; none when
    /// the program has no exact Hessian.
    fn hessian_structure(&self) -> Vec<(usize, usize)> {
        Vec::new()
    }
    /// The entries of the Lagrangian's Hessian `objective_factor hess J +
    /// sum_i lambda_i hess c_i` in the order of [`Nlp::hessian_structure`];
    /// whether they are finite.
    fn hessian_values(
        &self,
        _z: &[f64],
        _objective_factor: f64,
        _multipliers: &[f64],
        _values: &mut [f64],
    ) -> bool {
        false
    }
}

/// What a solver returns: a candidate optimum and its multipliers.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The variables.
    pub z: Vec<f64>,
    /// The constraints' multipliers `lambda`.
    pub multipliers: Vec<f64>,
    /// The lower bounds' multipliers `z_lo`.
    pub lower: Vec<f64>,
    /// The upper bounds' multipliers `z_hi`.
    pub upper: Vec<f64>,
    /// The solver's iterations.
    pub iterations: usize,
    /// The solver's own word on the outcome (not trusted: see `kkt`).
    pub status: String,
}

/// One iteration of a solver, as its log shows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    /// The iteration's number (0 for the starting point).
    pub number: usize,
    /// The objective `J(z)`.
    pub objective: f64,
    /// The primal infeasibility (the largest constraint violation).
    pub primal: f64,
    /// The dual infeasibility (the largest entry of the Lagrangian's
    /// gradient).
    pub dual: f64,
}

/// What watches a solve: told of each iteration, it says whether the
/// solver goes on (`Continue`) or stops at that iterate (`Break`).
pub type Observer<'a> = dyn FnMut(&Iteration) -> ControlFlow<()> + 'a;

/// A solver of [`Nlp`]s.
pub trait Solver {
    /// Its name, as `plan.json` reports it, when it solves `nlp`.
    fn name(&self, nlp: &dyn Nlp) -> &'static str;
    /// Solves `nlp` to the tolerance `tol` in at most `max_iterations`,
    /// telling `observer` of each iteration.
    fn solve(
        &self,
        nlp: &dyn Nlp,
        tol: f64,
        max_iterations: usize,
        observer: &mut Observer<'_>,
    ) -> Solution;
}

/// The Hessian of the Lagrangian a solver works with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Hessian {
    /// The program's own, [`Nlp::hessian_values`].
    #[default]
    Exact,
    /// Approximated by limited-memory BFGS from the gradients (Nocedal and
    /// Wright, "Numerical Optimization", 2nd ed., section 7.2).
    Lbfgs,
}

/// `ripopt`, a pure-Rust primal-dual interior point method after Ipopt,
/// with the program's exact Hessian of the Lagrangian, or its L-BFGS
/// approximation where asked or where the program has none.
#[derive(Clone, Copy, Debug, Default)]
pub struct Ripopt {
    /// The Hessian it works with.
    pub hessian: Hessian,
}

impl Solver for Ripopt {
    fn name(&self, nlp: &dyn Nlp) -> &'static str {
        match self.hessian {
            Hessian::Exact if !nlp.hessian_structure().is_empty() => "ripopt (exact Hessian)",
            _ => "ripopt (L-BFGS Hessian)",
        }
    }

    fn solve(
        &self,
        nlp: &dyn Nlp,
        tol: f64,
        max_iterations: usize,
        observer: &mut Observer<'_>,
    ) -> Solution {
        let structure = match self.hessian {
            Hessian::Exact => nlp.hessian_structure(),
            Hessian::Lbfgs => Vec::new(),
        };
        let lbfgs = structure.is_empty();
        let options = ripopt::SolverOptions {
            tol,
            max_iter: max_iterations,
            print_level: 0,
            hessian_approximation_lbfgs: lbfgs,
            ..ripopt::SolverOptions::default()
        };
        let result = {
            let mut observer = observer;
            let _watched = Watched::install(&mut observer);
            ripopt::solve(&Problem { nlp, structure }, &options)
        };
        Solution {
            z: result.x,
            multipliers: result.constraint_multipliers,
            lower: result.bound_multipliers_lower,
            upper: result.bound_multipliers_upper,
            iterations: result.iterations,
            status: format!("{:?}", result.status),
        }
    }
}

/// ripopt's intermediate callback (Ipopt's `Intermediate_CB`), installed
/// for this thread while a solve runs and removed when it ends, even by a
/// panic.
struct Watched<'a> {
    /// The observer the callback's `user_data` points to, borrowed.
    observer: std::marker::PhantomData<&'a mut ()>,
}

impl<'a> Watched<'a> {
    fn install(observer: &'a mut &mut Observer<'_>) -> Self {
        let user_data = std::ptr::from_mut(observer).cast::<c_void>();
        ripopt::intermediate::set_intermediate_callback(Some((on_iteration, user_data)));
        Self {
            observer: std::marker::PhantomData,
        }
    }
}

impl Drop for Watched<'_> {
    fn drop(&mut self) {
        ripopt::intermediate::set_intermediate_callback(None);
    }
}

/// Tells the observer behind `user_data` of an iteration; 1 goes on, 0
/// stops the solve (ripopt's `UserRequestedStop`, at this iterate).
#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn on_iteration(
    _mode: c_int,
    number: c_int,
    objective: f64,
    primal: f64,
    dual: f64,
    _barrier: f64,
    _step: f64,
    _regularization: f64,
    _dual_step_length: f64,
    _primal_step_length: f64,
    _line_search_trials: c_int,
    user_data: *mut c_void,
) -> c_int {
    // SAFETY: `user_data` is the `&mut Observer` that `Watched::install`
    // borrowed for the solve, the only one running on this thread.
    let observer = unsafe { &mut *user_data.cast::<&mut Observer<'_>>() };
    let iteration = Iteration {
        number: usize::try_from(number).unwrap_or(0),
        objective,
        primal,
        dual,
    };
    c_int::from(observer(&iteration).is_continue())
}

/// An [`Nlp`] as ripopt's problem, with the structure of its Hessian
/// (empty when approximated).
struct Problem<'a> {
    nlp: &'a dyn Nlp,
    structure: Vec<(usize, usize)>,
}

impl ripopt::NlpProblem for Problem<'_> {
    fn num_variables(&self) -> usize {
        self.nlp.variables()
    }

    fn num_constraints(&self) -> usize {
        self.nlp.constraints()
    }

    fn bounds(&self, x_l: &mut [f64], x_u: &mut [f64]) {
        let (lo, hi) = self.nlp.bounds();
        x_l.copy_from_slice(lo);
        x_u.copy_from_slice(hi);
    }

    fn constraint_bounds(&self, g_l: &mut [f64], g_u: &mut [f64]) {
        g_l.fill(0.0);
        g_u.fill(0.0);
    }

    fn initial_point(&self, x0: &mut [f64]) {
        x0.copy_from_slice(&self.nlp.guess());
    }

    fn objective(&self, x: &[f64], _new_x: bool, obj: &mut f64) -> bool {
        self.nlp.objective(x).map(|value| *obj = value).is_some()
    }

    fn gradient(&self, x: &[f64], _new_x: bool, grad: &mut [f64]) -> bool {
        self.nlp.gradient(x, grad)
    }

    fn constraints(&self, x: &[f64], _new_x: bool, g: &mut [f64]) -> bool {
        self.nlp.residuals(x, g)
    }

    fn jacobian_structure(&self) -> (Vec<usize>, Vec<usize>) {
        self.nlp.jacobian_structure().iter().copied().unzip()
    }

    fn jacobian_values(&self, x: &[f64], _new_x: bool, vals: &mut [f64]) -> bool {
        self.nlp.jacobian_values(x, vals)
    }

    fn hessian_structure(&self) -> (Vec<usize>, Vec<usize>) {
        self.structure.iter().copied().unzip()
    }

    fn hessian_values(
        &self,
        x: &[f64],
        _new_x: bool,
        obj_factor: f64,
        lambda: &[f64],
        vals: &mut [f64],
    ) -> bool {
        self.nlp.hessian_values(x, obj_factor, lambda, vals)
    }
}
