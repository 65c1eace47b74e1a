//! The search for an optimal loop: a survey of random loops off the
//! singular set and inside the limits ([`SURVEY`] of them, each centre uniform in `[-extent,
//! extent]`, each first-harmonic amplitude in `[-3/4 extent, 3/4 extent]`,
//! the higher harmonics 0), the best `starts` of them (least cost) refined
//! by argmin's L-BFGS (memory 7) with a backtracking line search on the
//! Armijo condition, which shortens a step into the singular set or past
//! a limit (infinite cost) like any step that does not descend; the best refined loop is
//! kept.

use super::fourier::FourierLoop;
use super::score::{Evaluation, Scoring, clearances};
use super::{Cost, Direction, GaitModel, evaluate};
use argmin::core::{CostFunction, Error, Executor, Gradient, State};
use argmin::solver::linesearch::BacktrackingLineSearch;
use argmin::solver::linesearch::condition::ArmijoCondition;
use argmin::solver::quasinewton::LBFGS;
use std::cell::RefCell;
use std::f64::consts::PI;

/// What to optimize and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Design {
    /// The component maximized.
    pub direction: Direction,
    /// Per unit length, or per cycle.
    pub cost: Cost,
    /// The Fourier harmonics `N` of each shape coordinate.
    pub harmonics: usize,
    /// The period `T`.
    pub period: f64,
    /// The surveyed loops refined by L-BFGS.
    pub starts: usize,
    /// The survey's centres lie in `[-extent, extent]` in each shape
    /// coordinate.
    pub extent: f64,
    /// RK4 steps per period (even).
    pub steps: usize,
    /// Loops keep `|d(r)|` above this fraction of its largest magnitude
    /// over `[-pi, pi]` in the first two shape coordinates, and the barrier
    /// acts below twice that; the barrier of the limits acts within this
    /// fraction of the limit.
    pub margin: f64,
    /// Every shape coordinate keeps `|r_i|` below it.
    pub limit: f64,
    /// L-BFGS iterations per start, at most.
    pub iterations: u64,
    /// The seed of the starts.
    pub seed: u64,
}

impl Design {
    /// How `model`'s loops are scored under this design (the barrier's
    /// clearance from the largest `|d|` on the grid of the first two shape
    /// coordinates).
    pub fn scoring(&self, model: &dyn GaitModel) -> Scoring {
        Scoring {
            direction: self.direction,
            cost: self.cost,
            steps: self.steps,
            clearance: self.margin * largest_divisor(model, model.shape_indices().len()),
            limit: self.limit,
            limit_band: self.margin * self.limit,
            barrier_weight: BARRIER_WEIGHT,
        }
    }
}

impl Default for Design {
    fn default() -> Self {
        Design {
            direction: Direction::Forward,
            cost: Cost::Length,
            harmonics: 1,
            period: 2.0 * PI,
            starts: 8,
            extent: 2.0,
            steps: 400,
            margin: 0.25,
            limit: PI,
            iterations: 300,
            seed: 0x5eed_9a17,
        }
    }
}

/// Why no loop was found.
#[derive(Debug, thiserror::Error)]
pub enum DesignError {
    /// The request.
    #[error("{0}")]
    Request(String),
    /// No random loop off the singular set.
    #[error(
        "no random loop stays off the connection's singular set and inside the limits (margin {margin}, limit {limit})"
    )]
    NoStart {
        /// The margin asked for.
        margin: f64,
        /// The limit asked for.
        limit: f64,
    },
    /// The optimizer failed.
    #[error("the optimizer: {0}")]
    Optimizer(String),
}

/// The best loop found.
#[derive(Clone, Debug)]
pub struct Optimum {
    /// Its coefficients.
    pub shape_loop: FourierLoop,
    /// Its displacement, length and gradients.
    pub evaluation: Evaluation,
    /// How it was scored.
    pub scoring: Scoring,
    /// Each refined start's efficiency, in order.
    pub starts: Vec<f64>,
}

impl Optimum {
    /// The displacement per unit length (or per cycle) in the direction.
    pub fn efficiency(&self) -> f64 {
        self.evaluation.efficiency(&self.scoring)
    }
}

/// The loop of `design` that maximizes its efficiency on `model`.
///
/// # Errors
/// A request without shape plane, harmonics, starts or a positive period,
/// margin and limit; no random loop off the singular set and inside the
/// limits; the optimizer's failure.
pub fn optimize(model: &dyn GaitModel, design: &Design) -> Result<Optimum, DesignError> {
    let nr = model.shape_indices().len();
    if nr < 2 || design.harmonics == 0 || design.starts == 0 {
        return Err(DesignError::Request(format!(
            "a loop needs two shape coordinates (the model has {nr}), a harmonic and a start"
        )));
    }
    if !(design.period > 0.0 && design.margin > 0.0 && design.limit > 0.0 && design.steps >= 2) {
        return Err(DesignError::Request(
            "the period, the margin and the limit must be positive, the steps at least 2".into(),
        ));
    }
    let scoring = design.scoring(model);
    let mut best: Option<(FourierLoop, Evaluation)> = None;
    let mut starts = Vec::with_capacity(design.starts);
    for start in survey(model, design, &scoring)? {
        let found = descend(model, start, &scoring, design.iterations)?;
        starts.push(found.1.efficiency(&scoring));
        let better =
            |(_, old): &(FourierLoop, Evaluation)| found.1.cost(&scoring) < old.cost(&scoring);
        if best.as_ref().is_none_or(better) {
            best = Some(found);
        }
    }
    let (shape_loop, evaluation) = best.ok_or(DesignError::NoStart {
        margin: design.margin,
        limit: design.limit,
    })?;
    Ok(Optimum {
        shape_loop,
        evaluation,
        scoring,
        starts,
    })
}

/// The barrier's weight against the efficiency.
const BARRIER_WEIGHT: f64 = 1.0;

/// The random loops surveyed for starts.
pub const SURVEY: usize = 200;

/// Random loops tried for the survey before giving up.
const TRIES: usize = 20 * SURVEY;

/// `|d|`'s largest value on a grid over `[-pi, pi]` in each of the first
/// two shape coordinates (the others 0), 33 points per side.
fn largest_divisor(model: &dyn GaitModel, nr: usize) -> f64 {
    let side = 33;
    let at = |k: usize| -PI + 2.0 * PI * k as f64 / (side - 1) as f64;
    let mut largest: f64 = 0.0;
    let mut r = vec![0.0; nr];
    for i in 0..side {
        for j in 0..side {
            (r[0], r[1]) = (at(i), at(j));
            let d = model.divisor(&r).0.abs();
            if d.is_finite() {
                largest = largest.max(d);
            }
        }
    }
    largest
}

/// The `design.starts` best of [`SURVEY`] random loops off the singular
/// set, scored with a quarter of the steps.
fn survey(
    model: &dyn GaitModel,
    design: &Design,
    scoring: &Scoring,
) -> Result<Vec<FourierLoop>, DesignError> {
    let nr = model.shape_indices().len();
    let per = 2 * design.harmonics + 1;
    let quick = Scoring {
        steps: (scoring.steps / 4).max(2),
        ..*scoring
    };
    let mut random = SplitMix(design.seed);
    let mut found: Vec<(f64, FourierLoop)> = Vec::with_capacity(SURVEY);
    for _ in 0..TRIES {
        if found.len() == SURVEY {
            break;
        }
        let mut coefficients = vec![0.0; nr * per];
        for i in 0..nr {
            let amplitude = 0.75 * design.extent;
            coefficients[i * per] = random.uniform(-design.extent, design.extent);
            coefficients[i * per + 1] = random.uniform(-amplitude, amplitude);
            coefficients[i * per + 2] = random.uniform(-amplitude, amplitude);
        }
        let candidate = FourierLoop {
            period: design.period,
            harmonics: design.harmonics,
            coefficients,
        };
        if clearances(model, &candidate, &quick, quick.steps).any(|s| s <= 1.0) {
            continue;
        }
        let cost = evaluate(model, &candidate, &quick).cost(&quick);
        if cost.is_finite() {
            found.push((cost, candidate));
        }
    }
    if found.is_empty() {
        return Err(DesignError::NoStart {
            margin: design.margin,
            limit: design.limit,
        });
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(found
        .into_iter()
        .take(design.starts)
        .map(|(_, shape_loop)| shape_loop)
        .collect())
}

/// L-BFGS from `start`: the loop it ends at and its evaluation.
fn descend(
    model: &dyn GaitModel,
    start: FourierLoop,
    scoring: &Scoring,
    iterations: u64,
) -> Result<(FourierLoop, Evaluation), DesignError> {
    let problem = Problem {
        model,
        template: start.clone(),
        scoring: *scoring,
        last: RefCell::new(None),
    };
    let failed = |error: Error| DesignError::Optimizer(error.to_string());
    let line_search = BacktrackingLineSearch::new(ArmijoCondition::new(1e-4).map_err(failed)?)
        .rho(0.5)
        .map_err(failed)?;
    let solver = LBFGS::new(line_search, 7)
        .with_tolerance_grad(1e-10)
        .and_then(|solver| solver.with_tolerance_cost(1e-15))
        .map_err(failed)?;
    let result = Executor::new(problem, solver)
        .configure(|state| {
            state
                .param(start.coefficients.clone())
                .max_iters(iterations)
        })
        .run()
        .map_err(failed)?;
    let coefficients = result
        .state()
        .get_best_param()
        .cloned()
        .unwrap_or(start.coefficients);
    let found = FourierLoop {
        coefficients,
        ..start
    };
    let evaluation = evaluate(model, &found, scoring);
    Ok((found, evaluation))
}

/// The optimizer's view: cost and gradient of the coefficients, the last
/// evaluation kept for the gradient that follows its cost.
struct Problem<'m> {
    model: &'m dyn GaitModel,
    template: FourierLoop,
    scoring: Scoring,
    last: RefCell<Option<(Vec<f64>, Evaluation)>>,
}

impl Problem<'_> {
    fn at<T>(&self, coefficients: &[f64], read: impl Fn(&Evaluation) -> T) -> T {
        let mut last = self.last.borrow_mut();
        if let Some((at, evaluation)) = last.as_ref()
            && at.as_slice() == coefficients
        {
            return read(evaluation);
        }
        let shape_loop = FourierLoop {
            coefficients: coefficients.to_vec(),
            ..self.template.clone()
        };
        let evaluation = evaluate(self.model, &shape_loop, &self.scoring);
        let value = read(&evaluation);
        *last = Some((coefficients.to_vec(), evaluation));
        value
    }
}

impl CostFunction for Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, coefficients: &Vec<f64>) -> Result<f64, Error> {
        Ok(self.at(coefficients, |e| e.cost(&self.scoring)))
    }
}

impl Gradient for Problem<'_> {
    type Param = Vec<f64>;
    type Gradient = Vec<f64>;

    fn gradient(&self, coefficients: &Vec<f64>) -> Result<Vec<f64>, Error> {
        Ok(self.at(coefficients, |e| e.cost_gradient(&self.scoring)))
    }
}

/// SplitMix64: the starts' deterministic random numbers.
struct SplitMix(u64);

impl SplitMix {
    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        low + (high - low) * (z >> 11) as f64 / (1u64 << 53) as f64
    }
}
