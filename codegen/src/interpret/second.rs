//! The accelerations' derivatives beyond `acceleration_jacobian`, for
//! optimal control and identification (MATH.md section 6), by forward
//! differentiation of the programs at run time ([`crate::ir::Program::tangents`]):
//!
//! ```text
//! acceleration_parameter_jacobian(q, qdot, u, theta)  d qddot / d theta  (n x P')
//! acceleration_hessian(q, qdot, u, w)           d^2 (w^T qddot) / dy^2   (m x m)
//! reduced_rhs_hessian(x, u, w)                  d^2 (w^T f) / dy'^2      (m' x m')
//! acceleration_parameter_hessian(q, qdot, u, w, theta)
//!     d^2 (w^T qddot) / dy dtheta (m x P'),  d^2 (w^T qddot) / dtheta^2 (P' x P')
//! ```
//!
//! with `y = (q, qdot, u)`, `m = 2n + p`, and for the reduced equations
//! `xdot = f(x, u)` (MATH.md section 3) `y' = (x, u)`, `m' = s + p`. The parameters are inputs of
//! every program, so the first is the `acceleration` program differentiated
//! along them. The second is the exact Jacobian `acceleration_jacobian`
//! (the derivation's symbolic derivative, MATH.md section 6) differentiated
//! along `y`, its rows contracted with `w`,
//!
//! ```text
//! H_jk = sum_i w_i d/dy_k (d qddot_i / dy_j),
//! ```
//!
//! and symmetrized, `(H + H^T)/2`: the two orders of differentiation agree
//! to round-off, and the mean is the symmetric matrix nearest both. The
//! third is the same for the exact `reduced_rhs_jacobian` (`df/dx`)
//! differentiated along `y'`; `f` is affine in `u`, so its `(u, u)` block
//! is zero and its `(u, x)` block the transpose of the `(x, u)` one. The
//! blocks by the `P'` parameters `theta` chosen among them are the same
//! Jacobian differentiated along `theta`, and the `acceleration` program's
//! second derivatives along `theta` ([`crate::ir::Program::curvatures`]).
//! Nothing is derived or emitted for them: the cost is paid per call,
//! `m` derivatives carried by each of the Jacobian program's values
//! (BENCHMARKS.md, "Exact second derivatives").

use super::{CallError, Interpreted, InterpretedModel, check_arguments, function_among};
use crate::ir::Tangents;

impl InterpretedModel {
    /// `d qddot / d theta`, n x P' row-major, for the parameters `theta`
    /// (indices among the model's, `P'` of them) at the current parameter
    /// values: the `acceleration` program differentiated forward along
    /// those parameter inputs ([`crate::ir::Program::tangents`]), exact to
    /// round-off. The cost grows with `P'`: name the parameters needed.
    ///
    /// # Errors
    /// As [`InterpretedModel::call`], and [`CallError::Program`] for an
    /// index that is no parameter's.
    pub fn acceleration_parameter_jacobian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
        theta: &[usize],
    ) -> Result<Vec<f64>, CallError> {
        let (n, arguments) = (self.sizes.n, 2 * self.sizes.n + self.sizes.p);
        let seeds: Vec<usize> = theta.iter().map(|&k| arguments + k).collect();
        let function = function_among(&self.functions, "acceleration")?;
        let tangents = self.tangents(function, &[q, qdot, u], &seeds)?;
        Ok(tangents.derivatives[..n * seeds.len()].to_vec())
    }

    /// The Hessian of `w^T qddot` by `y = (q, qdot, u)`, m x m row-major
    /// (`m = 2n + p`): [`InterpretedModel::acceleration_curvatures`]
    /// contracted with `w`.
    ///
    /// # Errors
    /// As [`InterpretedModel::call`], and [`CallError::ArgumentLength`]
    /// when `w` does not have n entries.
    pub fn acceleration_hessian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
        w: &[f64],
    ) -> Result<Vec<f64>, CallError> {
        self.acceleration_curvatures(q, qdot, u)?.hessian(w)
    }

    /// The second derivatives of the rows of `qddot` by `y = (q, qdot,
    /// u)`, to be weighted: the exact `acceleration_jacobian` program
    /// differentiated forward along `y` ([`crate::ir::Program::tangents`]).
    /// Contracted with `w` ([`RowCurvatures::hessian`]), its rows give the
    /// Hessian of `w^T qddot`, symmetrized, `(H + H^T)/2`; exact to
    /// round-off.
    ///
    /// # Errors
    /// As [`InterpretedModel::call`].
    pub fn acceleration_curvatures(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
    ) -> Result<RowCurvatures, CallError> {
        let (n, p) = (self.sizes.n, self.sizes.p);
        let seeds: Vec<usize> = (0..2 * n + p).collect();
        let function = function_among(&self.functions, "acceleration_jacobian")?;
        let Tangents { derivatives, .. } = self.tangents(function, &[q, qdot, u], &seeds)?;
        Ok(RowCurvatures {
            function: "acceleration_hessian",
            form: RowLayout::Acceleration { n, p },
            values: derivatives,
        })
    }

    /// The Hessian of `w^T f` by `y = (x, u)`, m x m row-major (`m = s +
    /// p`), for the reduced equations `f(x, u) = (J - R) dH/dx + B(x) u`:
    /// [`InterpretedModel::reduced_rhs_curvatures`] contracted with `w`.
    ///
    /// # Errors
    /// As [`InterpretedModel::call`], and [`CallError::ArgumentLength`]
    /// when `w` does not have s entries.
    pub fn reduced_rhs_hessian(
        &self,
        x: &[f64],
        u: &[f64],
        w: &[f64],
    ) -> Result<Vec<f64>, CallError> {
        self.reduced_rhs_curvatures(x, u)?.hessian(w)
    }

    /// The second derivatives of the rows of the reduced equations' `f` by
    /// `y = (x, u)`, to be weighted: the exact `reduced_rhs_jacobian`
    /// program (`df/dx`) differentiated forward along `y`
    /// ([`crate::ir::Program::tangents`]). Contracted with `w`
    /// ([`RowCurvatures::hessian`]), the `(x, x)` block is symmetrized,
    /// `(H + H^T)/2`; the `(x, u)` block is `sum_i w_i dB_i./dx`, the
    /// Jacobian's tangents along `u`, and the `(u, x)` block its
    /// transpose; the `(u, u)` block is zero, `f` being affine in `u` (`B`
    /// depends on `q` only, MATH.md section 3). Exact to round-off.
    ///
    /// # Errors
    /// As [`InterpretedModel::call`].
    pub fn reduced_rhs_curvatures(&self, x: &[f64], u: &[f64]) -> Result<RowCurvatures, CallError> {
        let (s, p) = (self.sizes.s, self.sizes.p);
        let seeds: Vec<usize> = (0..s + p).collect();
        let function = function_among(&self.functions, "reduced_rhs_jacobian")?;
        let Tangents { derivatives, .. } = self.tangents(function, &[x, u], &seeds)?;
        Ok(RowCurvatures {
            function: "reduced_rhs_hessian",
            form: RowLayout::Reduced { s, p },
            values: derivatives,
        })
    }

    /// The blocks of the Hessian of `w^T qddot` by the parameters
    /// `theta` (indices among the model's, `P'` of them): by `y = (q, qdot,
    /// u)` and `theta` (m x P', row-major), the exact
    /// `acceleration_jacobian` differentiated along `theta`; and by
    /// `theta` twice (P' x P'), the `acceleration` program's second
    /// derivatives along them ([`crate::ir::Program::curvatures`]). The
    /// contraction of [`InterpretedModel::acceleration_parameter_curvatures`]
    /// with `w`.
    ///
    /// # Errors
    /// As [`InterpretedModel::acceleration_hessian`], and
    /// [`CallError::Program`] for an index that is no parameter's.
    pub fn acceleration_parameter_hessian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
        w: &[f64],
        theta: &[usize],
    ) -> Result<ParameterBlocks, CallError> {
        self.acceleration_parameter_curvatures(q, qdot, u, theta)?
            .hessian(w)
    }

    /// The second derivatives of the rows of `qddot` by the parameters
    /// `theta` at one point, before they are weighted
    /// ([`ParameterCurvatures::hessian`]).
    ///
    /// # Errors
    /// As [`InterpretedModel::acceleration_parameter_hessian`].
    pub fn acceleration_parameter_curvatures(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
        theta: &[usize],
    ) -> Result<ParameterCurvatures, CallError> {
        let (n, p) = (self.sizes.n, self.sizes.p);
        let m = 2 * n + p;
        let seeds: Vec<usize> = theta.iter().map(|&k| m + k).collect();
        let jacobian = function_among(&self.functions, "acceleration_jacobian")?;
        let Tangents { derivatives, .. } = self.tangents(jacobian, &[q, qdot, u], &seeds)?;
        let acceleration = function_among(&self.functions, "acceleration")?;
        let second = self.curvatures(acceleration, &[q, qdot, u], &seeds)?;
        Ok(ParameterCurvatures {
            n,
            p,
            count: theta.len(),
            mixed: derivatives,
            second,
        })
    }

    /// `function`'s outputs at `arguments` and the current parameters, and
    /// their derivatives by the input slots `seeds`.
    fn tangents(
        &self,
        function: &Interpreted,
        arguments: &[&[f64]],
        seeds: &[usize],
    ) -> Result<Tangents, CallError> {
        let lowered = &function.lowered;
        check_arguments(function.name, &lowered.arguments, arguments)?;
        let inputs = self.program_inputs(arguments);
        lowered
            .program
            .tangents(&inputs, seeds)
            .map_err(|source| CallError::Program {
                function: function.name.to_string(),
                source,
            })
    }

    /// `function`'s second derivatives by the input slots `seeds` at
    /// `arguments` and the current parameters, as
    /// [`crate::ir::Curvatures::second`] lays them out.
    fn curvatures(
        &self,
        function: &Interpreted,
        arguments: &[&[f64]],
        seeds: &[usize],
    ) -> Result<Vec<f64>, CallError> {
        let lowered = &function.lowered;
        check_arguments(function.name, &lowered.arguments, arguments)?;
        let inputs = self.program_inputs(arguments);
        lowered
            .program
            .curvatures(&inputs, seeds)
            .map(|curvatures| curvatures.second)
            .map_err(|source| CallError::Program {
                function: function.name.to_string(),
                source,
            })
    }

    /// A program's inputs: `arguments`, then the parameters.
    fn program_inputs(&self, arguments: &[&[f64]]) -> Vec<f64> {
        arguments
            .iter()
            .flat_map(|values| values.iter())
            .chain(&self.parameters)
            .copied()
            .collect()
    }
}

/// `R_jk = sum_i w_i d out_{entry(i, j)} / d seed_k` for `rows` j and
/// `seeds` k (rows x seeds, row-major), from the tangents `derivatives`
/// (each output's derivatives by the seeds in a row).
fn contracted(
    derivatives: &[f64],
    w: &[f64],
    (rows, seeds): (usize, usize),
    entry: impl Fn(usize, usize) -> usize,
) -> Vec<f64> {
    let mut result = vec![0.0; rows * seeds];
    for (j, row) in result.chunks_exact_mut(seeds).enumerate() {
        for (i, weight) in w.iter().enumerate() {
            let slopes = &derivatives[entry(i, j) * seeds..(entry(i, j) + 1) * seeds];
            for (h, slope) in row.iter_mut().zip(slopes) {
                *h += weight * slope;
            }
        }
    }
    result
}

/// Replaces the leading `block` x `block` of `hessian` (m x m, row-major)
/// by its symmetric part, `(H + H^T)/2`: the two orders of
/// differentiation agree to round-off, and the mean is the symmetric
/// matrix nearest both.
fn symmetrize(hessian: &mut [f64], m: usize, block: usize) {
    for j in 0..block {
        for k in 0..j {
            let mean = 0.5 * (hessian[j * m + k] + hessian[k * m + j]);
            (hessian[j * m + k], hessian[k * m + j]) = (mean, mean);
        }
    }
}

/// Where `d qddot_i / dy_j` is among `acceleration_jacobian`'s outputs
/// (by `q`, then `qdot`, then `u`, each n x . row-major).
fn jacobian_entry(n: usize, p: usize, i: usize, j: usize) -> usize {
    match j {
        j if j < n => i * n + j,
        j if j < 2 * n => n * n + i * n + (j - n),
        j => 2 * n * n + i * p + (j - 2 * n),
    }
}

/// The second derivatives of a right-hand side's rows at one point, before
/// they are weighted: what [`InterpretedModel::acceleration_hessian`],
/// [`InterpretedModel::reduced_rhs_hessian`] and
/// [`InterpretedModel::momentum_form_hessian`] contract with their weights.
/// One evaluation serves every weighting at the point: a collocation's
/// node is a stage of the intervals on both sides, and Hermite-Simpson's
/// slopes weigh it once more.
#[derive(Clone, Debug)]
pub struct RowCurvatures {
    /// The function whose weights [`RowCurvatures::hessian`] checks.
    pub(super) function: &'static str,
    pub(super) form: RowLayout,
    /// The derivatives, as `form` lays them out.
    pub(super) values: Vec<f64>,
}

/// How [`RowCurvatures`] lays out its derivatives.
#[derive(Clone, Copy, Debug)]
pub(super) enum RowLayout {
    /// The tangents of `acceleration_jacobian`'s outputs along `y = (q,
    /// qdot, u)`, `m = 2n + p` each.
    Acceleration { n: usize, p: usize },
    /// The tangents of `reduced_rhs_jacobian`'s outputs along `y = (x,
    /// u)`, `m = s + p` each.
    Reduced { s: usize, p: usize },
    /// Each of `rows` rows' m x m block, row-major.
    Blocks { rows: usize, m: usize },
}

impl RowCurvatures {
    /// The number of rows: the weights' length.
    pub fn rows(&self) -> usize {
        match self.form {
            RowLayout::Acceleration { n, .. } => n,
            RowLayout::Reduced { s, .. } => s,
            RowLayout::Blocks { rows, .. } => rows,
        }
    }

    /// The Hessian of `w^T f`, m x m row-major, exact to round-off.
    ///
    /// # Errors
    /// [`CallError::ArgumentLength`] when `w` does not have
    /// [`RowCurvatures::rows`] entries.
    pub fn hessian(&self, w: &[f64]) -> Result<Vec<f64>, CallError> {
        check_arguments(self.function, &[("w", self.rows())], &[w])?;
        Ok(match self.form {
            RowLayout::Acceleration { n, p } => {
                let m = 2 * n + p;
                let mut hessian =
                    contracted(&self.values, w, (m, m), |i, j| jacobian_entry(n, p, i, j));
                symmetrize(&mut hessian, m, m);
                hessian
            }
            RowLayout::Reduced { s, p } => {
                let m = s + p;
                let by_x = contracted(&self.values, w, (s, m), |i, j| i * s + j);
                let mut hessian = vec![0.0; m * m];
                hessian[..s * m].copy_from_slice(&by_x);
                for l in s..m {
                    for j in 0..s {
                        hessian[l * m + j] = hessian[j * m + l];
                    }
                }
                symmetrize(&mut hessian, m, s);
                hessian
            }
            RowLayout::Blocks { m, .. } => {
                let mut hessian = vec![0.0; m * m];
                for (block, weight) in self.values.chunks_exact(m * m).zip(w) {
                    for (h, second) in hessian.iter_mut().zip(block) {
                        *h += weight * second;
                    }
                }
                hessian
            }
        })
    }
}

/// The Hessian blocks of [`InterpretedModel::acceleration_parameter_hessian`].
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterBlocks {
    /// By `y = (q, qdot, u)` and the parameters, m x P' row-major.
    pub mixed: Vec<f64>,
    /// By the parameters twice, P' x P' row-major.
    pub by_parameters: Vec<f64>,
}

/// The second derivatives of the rows of `qddot` by the parameters at one
/// point, before they are weighted: what
/// [`InterpretedModel::acceleration_parameter_hessian`] contracts with its
/// weights, one evaluation for every weighting at the point (as
/// [`RowCurvatures`]).
#[derive(Clone, Debug)]
pub struct ParameterCurvatures {
    n: usize,
    p: usize,
    /// The parameters differentiated by.
    count: usize,
    /// The tangents of `acceleration_jacobian`'s outputs along them.
    mixed: Vec<f64>,
    /// Each row's `count` x `count` block, row-major.
    second: Vec<f64>,
}

impl ParameterCurvatures {
    /// The blocks of the Hessian of `w^T qddot`, exact to round-off.
    ///
    /// # Errors
    /// [`CallError::ArgumentLength`] when `w` does not have one entry a
    /// coordinate.
    pub fn hessian(&self, w: &[f64]) -> Result<ParameterBlocks, CallError> {
        let (n, p, count) = (self.n, self.p, self.count);
        check_arguments("acceleration_parameter_hessian", &[("w", n)], &[w])?;
        let mixed = contracted(&self.mixed, w, (2 * n + p, count), |i, j| {
            jacobian_entry(n, p, i, j)
        });
        let block = count * count;
        let mut by_parameters = vec![0.0; block];
        for (i, weight) in w.iter().enumerate() {
            let rows = &self.second[i * block..(i + 1) * block];
            for (h, d) in by_parameters.iter_mut().zip(rows) {
                *h += weight * d;
            }
        }
        Ok(ParameterBlocks {
            mixed,
            by_parameters,
        })
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::InterpretedModel;
    use crate::fixtures::SNAKEBOARD;
    use std::sync::OnceLock;

    /// Each model of `sources` derived, with a point of `size(model)`
    /// entries, the `j`-th `value(j)`.
    pub(crate) fn models_at(
        sources: &[&str],
        size: impl Fn(&InterpretedModel) -> usize,
        value: impl Fn(f64) -> f64,
    ) -> Vec<(InterpretedModel, Vec<f64>)> {
        (sources.iter())
            .map(|source| {
                let model = InterpretedModel::from_source(source).expect("derives");
                let y = (0..size(&model)).map(|j| value(j as f64)).collect();
                (model, y)
            })
            .collect()
    }

    /// The snakeboard, the differential drive and the benchmark bicycle,
    /// each with a state and inputs where every entry is nonzero: derived
    /// once for this module's tests (the bicycle takes 5 s unoptimized).
    fn models() -> Vec<(InterpretedModel, Vec<f64>)> {
        static MODELS: OnceLock<Vec<(InterpretedModel, Vec<f64>)>> = OnceLock::new();
        let sources = [
            SNAKEBOARD,
            include_str!("../../../models/differential_drive.model"),
            include_str!("../../../models/bicycle.model"),
        ];
        let derived = MODELS.get_or_init(|| {
            models_at(
                &sources,
                |model| 2 * model.sizes().n + model.sizes().p,
                |j| 0.2 * (0.9 * j).sin() + 0.05,
            )
        });
        derived.clone()
    }

    /// `(q, qdot, u)` of `y`.
    fn split(model: &InterpretedModel, y: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = model.sizes().n;
        (y[..n].to_vec(), y[n..2 * n].to_vec(), y[2 * n..].to_vec())
    }

    /// `|found - expected| <= 1e-6 (1 + |expected|)`, with a message.
    pub(crate) fn assert_close(found: f64, expected: f64, what: &str) {
        assert!(
            (found - expected).abs() <= 1e-6 * (1.0 + expected.abs()),
            "{what}: {found} vs {expected}"
        );
    }

    /// `hessian` (m x m, row-major, `m = y.len()`) against central
    /// differences of the exact `gradient` at `y`, entry by entry; returns
    /// the differences, `(j, k)` being `d gradient_j / d y_k`.
    pub(crate) fn assert_hessian_agrees(
        hessian: &[f64],
        y: &[f64],
        gradient: impl Fn(&[f64]) -> Vec<f64>,
    ) -> Vec<f64> {
        let m = y.len();
        let mut numeric = vec![0.0; m * m];
        for k in 0..m {
            let step = 1e-6;
            let (mut plus, mut minus) = (y.to_vec(), y.to_vec());
            plus[k] += step;
            minus[k] -= step;
            let (above, below) = (gradient(&plus), gradient(&minus));
            for j in 0..m {
                numeric[j * m + k] = (above[j] - below[j]) / (2.0 * step);
                assert_close(
                    hessian[j * m + k],
                    numeric[j * m + k],
                    &format!("({j}, {k})"),
                );
            }
        }
        numeric
    }

    #[test]
    fn the_parameter_jacobian_agrees_with_central_differences_of_acceleration() {
        for (model, y) in models() {
            let (q, qdot, u) = split(&model, &y);
            let parameters = model.parameter_values().len();
            let all: Vec<usize> = (0..parameters).collect();
            let exact = model
                .acceleration_parameter_jacobian(&q, &qdot, &u, &all)
                .expect("evaluates");
            for (l, name) in model.names().parameters.iter().enumerate() {
                let value = model.parameter_values()[l];
                let step = 1e-6 * value.abs().max(1.0);
                let at = |shifted: f64| {
                    let mut moved = model.clone();
                    moved.set_parameter(name, shifted).expect("declared");
                    moved.acceleration(&q, &qdot, &u).expect("evaluates").0
                };
                let (plus, minus) = (at(value + step), at(value - step));
                for i in 0..model.sizes().n {
                    let numeric = (plus[i] - minus[i]) / (2.0 * step);
                    assert_close(exact[i * parameters + l], numeric, name);
                }
            }
        }
    }

    #[test]
    fn the_hessian_agrees_with_central_differences_of_the_jacobian() {
        for (model, y) in models() {
            let (n, m) = (model.sizes().n, y.len());
            let w: Vec<f64> = (0..n).map(|i| 0.7 - 0.3 * i as f64).collect();
            let (q, qdot, u) = split(&model, &y);
            let hessian = model
                .acceleration_hessian(&q, &qdot, &u, &w)
                .expect("evaluates");
            let gradient = |y: &[f64]| -> Vec<f64> {
                let (q, qdot, u) = split(&model, y);
                let (by_q, by_qdot, by_u) = model
                    .acceleration_jacobian(&q, &qdot, &u)
                    .expect("evaluates");
                let p = u.len();
                (0..m)
                    .map(|j| {
                        let entry = |i: usize| match j {
                            j if j < n => by_q[i * n + j],
                            j if j < 2 * n => by_qdot[i * n + j - n],
                            j => by_u[i * p + j - 2 * n],
                        };
                        (0..n).map(|i| w[i] * entry(i)).sum()
                    })
                    .collect()
            };
            assert_hessian_agrees(&hessian, &y, gradient);
        }
    }

    /// The reduced state and inputs `(x, u)` of a model, every entry
    /// nonzero.
    fn reduced_point(model: &InterpretedModel) -> Vec<f64> {
        let m = model.sizes().s + model.sizes().p;
        (0..m)
            .map(|j| 0.3 * (1.1 * j as f64).cos() + 0.07)
            .collect()
    }

    /// `reduced_rhs_hessian` against central differences of `w^T
    /// reduced_rhs_jacobian` and `w^T input_matrix`, the exact gradient of
    /// `w^T f` by `(x, u)`; the snakeboard's and the bicycle's `B(x)` vary
    /// with `x`, so the `(x, u)` block is not zero.
    #[test]
    fn the_reduced_hessian_agrees_with_central_differences_of_the_jacobian() {
        let mut curved = 0.0_f64;
        for (model, _) in models() {
            let (s, p) = (model.sizes().s, model.sizes().p);
            let (m, y) = (s + p, reduced_point(&model));
            let w: Vec<f64> = (0..s).map(|i| 0.6 - 0.25 * i as f64).collect();
            let hessian = model
                .reduced_rhs_hessian(&y[..s], &y[s..], &w)
                .expect("evaluates");
            let gradient = |y: &[f64]| -> Vec<f64> {
                let (x, u) = y.split_at(s);
                let by_x = model.reduced_rhs_jacobian(x, u).expect("evaluates");
                let by_u = model.input_matrix(x).expect("evaluates");
                let contract = |matrix: &[f64], columns: usize, j: usize| -> f64 {
                    (0..s).map(|i| w[i] * matrix[i * columns + j]).sum()
                };
                (0..s)
                    .map(|j| contract(&by_x, s, j))
                    .chain((0..p).map(|l| contract(&by_u, p, l)))
                    .collect()
            };
            let numeric = assert_hessian_agrees(&hessian, &y, gradient);
            for j in 0..s {
                for k in s..m {
                    curved = curved.max(numeric[j * m + k].abs());
                }
            }
        }
        assert!(curved > 1e-3, "some B(x) varies with x: {curved}");
    }

    #[test]
    fn the_parameter_blocks_agree_with_central_differences_of_the_jacobians() {
        for (model, y) in models() {
            let (n, m) = (model.sizes().n, y.len());
            let w: Vec<f64> = (0..n).map(|i| 0.7 - 0.3 * i as f64).collect();
            let (q, qdot, u) = split(&model, &y);
            let all = model.parameter_values().len();
            let theta: Vec<usize> = [0, all / 2, all - 1].to_vec();
            let blocks = model
                .acceleration_parameter_hessian(&q, &qdot, &u, &w, &theta)
                .expect("evaluates");
            let contracted = |moved: &InterpretedModel| -> (Vec<f64>, Vec<f64>) {
                let (by_q, by_qdot, by_u) = moved
                    .acceleration_jacobian(&q, &qdot, &u)
                    .expect("evaluates");
                let by_y = (0..m)
                    .map(|j| {
                        let entry = |i: usize| match j {
                            j if j < n => by_q[i * n + j],
                            j if j < 2 * n => by_qdot[i * n + j - n],
                            j => by_u[i * u.len() + j - 2 * n],
                        };
                        (0..n).map(|i| w[i] * entry(i)).sum()
                    })
                    .collect();
                let by = moved
                    .acceleration_parameter_jacobian(&q, &qdot, &u, &theta)
                    .expect("evaluates");
                let by_theta = (0..theta.len())
                    .map(|l| (0..n).map(|i| w[i] * by[i * theta.len() + l]).sum())
                    .collect();
                (by_y, by_theta)
            };
            let count = theta.len();
            for (l, &k) in theta.iter().enumerate() {
                let name = &model.names().parameters[k];
                let value = model.parameter_values()[k];
                let step = 1e-6 * value.abs().max(1.0);
                let at = |shifted: f64| {
                    let mut moved = model.clone();
                    moved.set_parameter(name, shifted).expect("declared");
                    contracted(&moved)
                };
                let (plus, minus) = (at(value + step), at(value - step));
                for j in 0..m {
                    let numeric = (plus.0[j] - minus.0[j]) / (2.0 * step);
                    assert_close(blocks.mixed[j * count + l], numeric, &format!("{name} {j}"));
                }
                for r in 0..count {
                    let numeric = (plus.1[r] - minus.1[r]) / (2.0 * step);
                    let exact = blocks.by_parameters[r * count + l];
                    assert_close(exact, numeric, &format!("{name} {r}"));
                }
            }
        }
    }
}
