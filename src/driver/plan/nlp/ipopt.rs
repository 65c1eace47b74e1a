//! Ipopt (Wächter and Biegler, "On the implementation of an interior-point
//! filter line-search algorithm for large-scale nonlinear programming",
//! Math. Program. 106, 2006) behind [`Solver`], through its C interface
//! (`IpStdCInterface.h`, the same in Ipopt 3.11 to 3.14), linked from the
//! system's `libipopt` (Debian's `coinor-libipopt-dev`).
//!
//! The program `min J(z)  s.t.  c(z) = 0,  lo <= z <= hi` is Ipopt's with
//! `g_L = g_U = 0`; Ipopt's multipliers follow the convention of [`super`]
//! as they are. Ipopt's linear solver MUMPS keeps global state, so one
//! solve runs at a time in a process.

use std::ffi::{CStr, c_char, c_int, c_void};
use std::sync::Mutex;

use super::{Hessian, Iteration, Nlp, Observer, Solution, Solver};

#[cfg(test)]
mod tests;

/// Ipopt with the program's exact Hessian of the Lagrangian, or its
/// limited-memory BFGS approximation where asked or where the program has
/// none.
#[derive(Clone, Copy, Debug, Default)]
pub struct Ipopt {
    /// The Hessian it works with.
    pub hessian: Hessian,
}

impl Solver for Ipopt {
    fn name(&self, nlp: &dyn Nlp) -> &'static str {
        if self.structure(nlp).is_empty() {
            "ipopt (L-BFGS Hessian)"
        } else {
            "ipopt (exact Hessian)"
        }
    }

    fn solve(
        &self,
        nlp: &dyn Nlp,
        tol: f64,
        max_iterations: usize,
        observer: &mut Observer<'_>,
    ) -> Solution {
        let structure = self.structure(nlp);
        let options = Options {
            tol,
            max_iterations,
            lbfgs: structure.is_empty(),
        };
        let mut context = Context {
            nlp,
            structure,
            observer,
            iterations: 0,
        };
        let _serial = ONE_AT_A_TIME
            .lock()
            .unwrap_or_else(|poison| poison.into_inner());
        match Problem::create(nlp, context.structure.len(), &options) {
            Some(problem) => problem.solve(&mut context),
            None => unsolved(nlp, "Invalid_Problem_Definition"),
        }
    }
}

impl Ipopt {
    /// The Hessian's structure Ipopt is given: empty for L-BFGS.
    fn structure(&self, nlp: &dyn Nlp) -> Vec<(usize, usize)> {
        match self.hessian {
            Hessian::Exact => nlp.hessian_structure(),
            Hessian::Lbfgs => Vec::new(),
        }
    }
}

/// Held by each solve: MUMPS (sequential) is not reentrant.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// The options a solve sets.
struct Options {
    tol: f64,
    max_iterations: usize,
    lbfgs: bool,
}

/// What Ipopt's callbacks reach through their `user_data`.
struct Context<'a, 'o> {
    nlp: &'a dyn Nlp,
    structure: Vec<(usize, usize)>,
    observer: &'a mut Observer<'o>,
    /// The last iteration reported.
    iterations: usize,
}

/// The starting point with zero multipliers, for a program Ipopt refused.
fn unsolved(nlp: &dyn Nlp, status: &str) -> Solution {
    Solution {
        z: nlp.guess(),
        multipliers: vec![0.0; nlp.constraints()],
        lower: vec![0.0; nlp.variables()],
        upper: vec![0.0; nlp.variables()],
        iterations: 0,
        status: status.to_owned(),
    }
}

/// An `IpoptProblem`, freed when dropped.
struct Problem(*mut c_void);

impl Problem {
    /// Ipopt's problem for `nlp` with `hessian_entries` entries in the
    /// Hessian's lower triangle, its options set; `None` where Ipopt
    /// refuses the program or an option.
    fn create(nlp: &dyn Nlp, hessian_entries: usize, options: &Options) -> Option<Self> {
        let (lo, hi) = nlp.bounds();
        let zeros = vec![0.0; nlp.constraints()];
        // SAFETY: the bounds are arrays of n and m entries that Ipopt
        // copies before returning; the callbacks match the C signatures.
        let raw = unsafe {
            CreateIpoptProblem(
                index(nlp.variables())?,
                lo.as_ptr().cast_mut(),
                hi.as_ptr().cast_mut(),
                index(nlp.constraints())?,
                zeros.as_ptr().cast_mut(),
                zeros.as_ptr().cast_mut(),
                index(nlp.jacobian_structure().len())?,
                index(hessian_entries)?,
                0,
                eval_f,
                eval_g,
                eval_grad_f,
                eval_jac_g,
                eval_h,
            )
        };
        let problem = (!raw.is_null()).then_some(Self(raw))?;
        problem.configure(options).then_some(problem)
    }

    /// Sets the options; whether Ipopt took each.
    fn configure(&self, options: &Options) -> bool {
        let hessian: &CStr = if options.lbfgs {
            c"limited-memory"
        } else {
            c"exact"
        };
        let Some(max_iterations) = index(options.max_iterations) else {
            return false;
        };
        // SAFETY: `self.0` is a live problem; the strings are
        // NUL-terminated and Ipopt copies them.
        unsafe {
            AddIpoptIntOption(self.0, c"print_level".as_ptr().cast_mut(), 0) != 0
                && AddIpoptStrOption(
                    self.0,
                    c"sb".as_ptr().cast_mut(),
                    c"yes".as_ptr().cast_mut(),
                ) != 0
                && AddIpoptNumOption(self.0, c"tol".as_ptr().cast_mut(), options.tol) != 0
                && AddIpoptIntOption(self.0, c"max_iter".as_ptr().cast_mut(), max_iterations) != 0
                && AddIpoptStrOption(
                    self.0,
                    c"hessian_approximation".as_ptr().cast_mut(),
                    hessian.as_ptr().cast_mut(),
                ) != 0
                && SetIntermediateCallback(self.0, intermediate) != 0
        }
    }

    /// Runs Ipopt from the program's guess.
    fn solve(&self, context: &mut Context<'_, '_>) -> Solution {
        let nlp = context.nlp;
        let mut z = nlp.guess();
        let mut multipliers = vec![0.0; nlp.constraints()];
        let mut lower = vec![0.0; nlp.variables()];
        let mut upper = vec![0.0; nlp.variables()];
        let mut objective = 0.0;
        // SAFETY: `self.0` is a live problem whose sizes the arrays match;
        // `context` outlives the call and is reached only by the callbacks.
        let status = unsafe {
            IpoptSolve(
                self.0,
                z.as_mut_ptr(),
                std::ptr::null_mut(),
                &raw mut objective,
                multipliers.as_mut_ptr(),
                lower.as_mut_ptr(),
                upper.as_mut_ptr(),
                std::ptr::from_mut(context).cast(),
            )
        };
        Solution {
            z,
            multipliers,
            lower,
            upper,
            iterations: context.iterations,
            status: status_name(status).to_owned(),
        }
    }
}

impl Drop for Problem {
    fn drop(&mut self) {
        // SAFETY: `self.0` came from `CreateIpoptProblem` and is freed once.
        unsafe { FreeIpoptProblem(self.0) }
    }
}

/// A count as Ipopt's `Index`; `None` past its range.
fn index(count: usize) -> Option<c_int> {
    c_int::try_from(count).ok()
}

/// Ipopt's `ApplicationReturnStatus` by its name (`IpReturnCodes_inc.h`).
fn status_name(status: c_int) -> &'static str {
    match status {
        0 => "Solve_Succeeded",
        1 => "Solved_To_Acceptable_Level",
        2 => "Infeasible_Problem_Detected",
        3 => "Search_Direction_Becomes_Too_Small",
        4 => "Diverging_Iterates",
        5 => "User_Requested_Stop",
        6 => "Feasible_Point_Found",
        -1 => "Maximum_Iterations_Exceeded",
        -2 => "Restoration_Failed",
        -3 => "Error_In_Step_Computation",
        -4 => "Maximum_CpuTime_Exceeded",
        -10 => "Not_Enough_Degrees_Of_Freedom",
        -11 => "Invalid_Problem_Definition",
        -12 => "Invalid_Option",
        -13 => "Invalid_Number_Detected",
        -100 => "Unrecoverable_Exception",
        -101 => "NonIpopt_Exception_Thrown",
        -102 => "Insufficient_Memory",
        _ => "Internal_Error",
    }
}

/// The context behind a callback's `user_data`.
///
/// # Safety
/// `user_data` is the `Context` that [`Problem::solve`] passed to
/// `IpoptSolve`, which is running.
unsafe fn context<'c>(user_data: *mut c_void) -> &'c mut Context<'c, 'c> {
    // SAFETY: as the caller promises.
    unsafe { &mut *user_data.cast() }
}

/// The `len` entries at `pointer`; none where `len` is not positive (the
/// pointer may then be null).
///
/// # Safety
/// `pointer` points to `len` initialized entries when `len > 0`.
unsafe fn entries<'s, T>(pointer: *const T, len: c_int) -> &'s [T] {
    match usize::try_from(len) {
        // SAFETY: as the caller promises.
        Ok(len) if len > 0 => unsafe { std::slice::from_raw_parts(pointer, len) },
        _ => &[],
    }
}

/// The mutable counterpart of [`entries`].
///
/// # Safety
/// `pointer` points to `len` writable entries when `len > 0`.
unsafe fn entries_mut<'s, T>(pointer: *mut T, len: c_int) -> &'s mut [T] {
    match usize::try_from(len) {
        // SAFETY: as the caller promises.
        Ok(len) if len > 0 => unsafe { std::slice::from_raw_parts_mut(pointer, len) },
        _ => &mut [],
    }
}

unsafe extern "C" fn eval_f(
    n: c_int,
    x: *mut f64,
    _new_x: c_int,
    objective: *mut f64,
    user_data: *mut c_void,
) -> c_int {
    // SAFETY: Ipopt passes `n` variables and one objective to write.
    let (nlp, x) = unsafe { (context(user_data).nlp, entries(x, n)) };
    nlp.objective(x)
        // SAFETY: as above.
        .map(|value| unsafe { *objective = value })
        .is_some()
        .into()
}

unsafe extern "C" fn eval_grad_f(
    n: c_int,
    x: *mut f64,
    _new_x: c_int,
    gradient: *mut f64,
    user_data: *mut c_void,
) -> c_int {
    // SAFETY: Ipopt passes `n` variables and `n` entries to write.
    let (nlp, x, gradient) = unsafe {
        (
            context(user_data).nlp,
            entries(x, n),
            entries_mut(gradient, n),
        )
    };
    nlp.gradient(x, gradient).into()
}

unsafe extern "C" fn eval_g(
    n: c_int,
    x: *mut f64,
    _new_x: c_int,
    m: c_int,
    g: *mut f64,
    user_data: *mut c_void,
) -> c_int {
    // SAFETY: Ipopt passes `n` variables and `m` entries to write.
    let (nlp, x, g) = unsafe { (context(user_data).nlp, entries(x, n), entries_mut(g, m)) };
    nlp.residuals(x, g).into()
}

/// Writes a sparse matrix's (row, column) pairs into Ipopt's arrays.
fn write_structure(structure: &[(usize, usize)], rows: &mut [c_int], columns: &mut [c_int]) {
    for ((&(row, column), r), c) in structure.iter().zip(rows).zip(columns) {
        (*r, *c) = (index(row).unwrap_or(0), index(column).unwrap_or(0));
    }
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn eval_jac_g(
    n: c_int,
    x: *mut f64,
    _new_x: c_int,
    _m: c_int,
    entries_count: c_int,
    rows: *mut c_int,
    columns: *mut c_int,
    values: *mut f64,
    user_data: *mut c_void,
) -> c_int {
    // SAFETY: Ipopt asks for the structure (`values` null, `rows` and
    // `columns` of `entries_count`) or the values at `n` variables.
    unsafe {
        let nlp = context(user_data).nlp;
        if values.is_null() {
            let (rows, columns) = (
                entries_mut(rows, entries_count),
                entries_mut(columns, entries_count),
            );
            write_structure(nlp.jacobian_structure(), rows, columns);
            return 1;
        }
        nlp.jacobian_values(entries(x, n), entries_mut(values, entries_count))
            .into()
    }
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn eval_h(
    n: c_int,
    x: *mut f64,
    _new_x: c_int,
    objective_factor: f64,
    m: c_int,
    lambda: *mut f64,
    _new_lambda: c_int,
    entries_count: c_int,
    rows: *mut c_int,
    columns: *mut c_int,
    values: *mut f64,
    user_data: *mut c_void,
) -> c_int {
    // SAFETY: as in `eval_jac_g`, with `m` multipliers.
    unsafe {
        let context = context(user_data);
        if values.is_null() {
            let (rows, columns) = (
                entries_mut(rows, entries_count),
                entries_mut(columns, entries_count),
            );
            write_structure(&context.structure, rows, columns);
            return 1;
        }
        let values = entries_mut(values, entries_count);
        context
            .nlp
            .hessian_values(entries(x, n), objective_factor, entries(lambda, m), values)
            .into()
    }
}

/// Tells the observer of an iteration; 1 goes on, 0 stops Ipopt
/// (`User_Requested_Stop`, at this iterate).
#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn intermediate(
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
    // SAFETY: `user_data` is the running solve's context.
    let context = unsafe { context(user_data) };
    context.iterations = usize::try_from(number).unwrap_or(0);
    let iteration = Iteration {
        number: context.iterations,
        objective,
        primal,
        dual,
    };
    c_int::from((context.observer)(&iteration).is_continue())
}

type EvalF = unsafe extern "C" fn(c_int, *mut f64, c_int, *mut f64, *mut c_void) -> c_int;
type EvalG = unsafe extern "C" fn(c_int, *mut f64, c_int, c_int, *mut f64, *mut c_void) -> c_int;
type EvalJacG = unsafe extern "C" fn(
    c_int,
    *mut f64,
    c_int,
    c_int,
    c_int,
    *mut c_int,
    *mut c_int,
    *mut f64,
    *mut c_void,
) -> c_int;
type EvalH = unsafe extern "C" fn(
    c_int,
    *mut f64,
    c_int,
    f64,
    c_int,
    *mut f64,
    c_int,
    c_int,
    *mut c_int,
    *mut c_int,
    *mut f64,
    *mut c_void,
) -> c_int;
type IntermediateCb = unsafe extern "C" fn(
    c_int,
    c_int,
    f64,
    f64,
    f64,
    f64,
    f64,
    f64,
    f64,
    f64,
    c_int,
    *mut c_void,
) -> c_int;

#[link(name = "ipopt")]
unsafe extern "C" {
    fn CreateIpoptProblem(
        n: c_int,
        x_l: *mut f64,
        x_u: *mut f64,
        m: c_int,
        g_l: *mut f64,
        g_u: *mut f64,
        jacobian_entries: c_int,
        hessian_entries: c_int,
        index_style: c_int,
        eval_f: EvalF,
        eval_g: EvalG,
        eval_grad_f: EvalF,
        eval_jac_g: EvalJacG,
        eval_h: EvalH,
    ) -> *mut c_void;
    fn FreeIpoptProblem(problem: *mut c_void);
    fn AddIpoptStrOption(problem: *mut c_void, keyword: *mut c_char, value: *mut c_char) -> c_int;
    fn AddIpoptNumOption(problem: *mut c_void, keyword: *mut c_char, value: f64) -> c_int;
    fn AddIpoptIntOption(problem: *mut c_void, keyword: *mut c_char, value: c_int) -> c_int;
    fn SetIntermediateCallback(problem: *mut c_void, callback: IntermediateCb) -> c_int;
    fn IpoptSolve(
        problem: *mut c_void,
        x: *mut f64,
        g: *mut f64,
        objective: *mut f64,
        mult_g: *mut f64,
        mult_x_l: *mut f64,
        mult_x_u: *mut f64,
        user_data: *mut c_void,
    ) -> c_int;
}
