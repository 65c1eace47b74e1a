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

/// A solver of [`Nlp`]s.
pub trait Solver {
    /// Its name, as `plan.json` reports it.
    fn name(&self) -> &'static str;
    /// Solves `nlp` to the tolerance `tol` in at most `max_iterations`.
    fn solve(&self, nlp: &dyn Nlp, tol: f64, max_iterations: usize) -> Solution;
}

/// `ripopt`, a pure-Rust primal-dual interior point method after Ipopt,
/// its Hessian of the Lagrangian approximated by limited-memory BFGS.
pub struct Ripopt;

impl Solver for Ripopt {
    fn name(&self) -> &'static str {
        "ripopt (L-BFGS Hessian)"
    }

    fn solve(&self, nlp: &dyn Nlp, tol: f64, max_iterations: usize) -> Solution {
        let options = ripopt::SolverOptions {
            tol,
            max_iter: max_iterations,
            print_level: 0,
            hessian_approximation_lbfgs: true,
            ..ripopt::SolverOptions::default()
        };
        let result = ripopt::solve(&Problem(nlp), &options);
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

/// An [`Nlp`] as ripopt's problem.
struct Problem<'a>(&'a dyn Nlp);

impl ripopt::NlpProblem for Problem<'_> {
    fn num_variables(&self) -> usize {
        self.0.variables()
    }

    fn num_constraints(&self) -> usize {
        self.0.constraints()
    }

    fn bounds(&self, x_l: &mut [f64], x_u: &mut [f64]) {
        let (lo, hi) = self.0.bounds();
        x_l.copy_from_slice(lo);
        x_u.copy_from_slice(hi);
    }

    fn constraint_bounds(&self, g_l: &mut [f64], g_u: &mut [f64]) {
        g_l.fill(0.0);
        g_u.fill(0.0);
    }

    fn initial_point(&self, x0: &mut [f64]) {
        x0.copy_from_slice(&self.0.guess());
    }

    fn objective(&self, x: &[f64], _new_x: bool, obj: &mut f64) -> bool {
        self.0.objective(x).map(|value| *obj = value).is_some()
    }

    fn gradient(&self, x: &[f64], _new_x: bool, grad: &mut [f64]) -> bool {
        self.0.gradient(x, grad)
    }

    fn constraints(&self, x: &[f64], _new_x: bool, g: &mut [f64]) -> bool {
        self.0.residuals(x, g)
    }

    fn jacobian_structure(&self) -> (Vec<usize>, Vec<usize>) {
        self.0.jacobian_structure().iter().copied().unzip()
    }

    fn jacobian_values(&self, x: &[f64], _new_x: bool, vals: &mut [f64]) -> bool {
        self.0.jacobian_values(x, vals)
    }

    /// Not called: the Hessian is approximated by L-BFGS.
    fn hessian_structure(&self) -> (Vec<usize>, Vec<usize>) {
        (Vec::new(), Vec::new())
    }

    /// Not called: the Hessian is approximated by L-BFGS.
    fn hessian_values(
        &self,
        _x: &[f64],
        _new_x: bool,
        _obj_factor: f64,
        _lambda: &[f64],
        _vals: &mut [f64],
    ) -> bool {
        false
    }
}
