//! The charts of D of an interpreted model: those derived at build time
//! ([`crate::derive::constraints::charts`]) and, after them, the run-time
//! charts of coordinate partitioning (`chaplygin_runtime::partition`),
//! numbered as the generated code numbers them.

use super::{CallError, Interpreted, InterpretedModel, check_arguments, function_among};
use crate::derive::constraints::{ChartFit, Elimination};
use crate::ir::IrError;
use chaplygin_runtime::monitor::{
    at_group_identity, declared_basis_fit, elimination_ratio, hadamard_ratio, signed_pivot_ratio,
};
use chaplygin_runtime::nalgebra::{DMatrix, DVector, Dyn};
use chaplygin_runtime::partition::{self, Constrained, RuntimeChart};

impl Constrained for InterpretedModel {
    type N = Dyn;
    type C = Dyn;
    type K = Dyn;
    type P = Dyn;

    fn dimensions(&self) -> (Dyn, Dyn, Dyn, Dyn) {
        let sizes = self.sizes;
        (Dyn(sizes.n), Dyn(sizes.c), Dyn(sizes.k), Dyn(sizes.p))
    }

    /// NaN entries where the interpreter refuses the call (it cannot for
    /// the sizes the run-time chart passes).
    fn constraint_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        let (n, c) = (self.sizes.n, self.sizes.c);
        let values =
            InterpretedModel::constraint_matrix(self, q).unwrap_or_else(|_| vec![f64::NAN; c * n]);
        DMatrix::from_row_slice(c, n, &values)
    }

    fn mass_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        let n = self.sizes.n;
        let values =
            InterpretedModel::mass_matrix(self, q).unwrap_or_else(|_| vec![f64::NAN; n * n]);
        DMatrix::from_row_slice(n, n, &values)
    }

    fn acceleration(&self, q: &[f64], qdot: &[f64], u: &[f64]) -> DVector<f64> {
        let n = self.sizes.n;
        let qddot = InterpretedModel::acceleration(self, q, qdot, u)
            .map_or_else(|_| vec![f64::NAN; n], |(qddot, _)| qddot);
        DVector::from_vec(qddot)
    }

    fn energy(&self, q: &[f64], qdot: &[f64]) -> f64 {
        InterpretedModel::energy(self, q, qdot).unwrap_or(f64::NAN)
    }
}

impl InterpretedModel {
    /// How each chart of D derived at build time fits, chart 0 (the basis
    /// the other functions use) first; one chart unless that basis
    /// degenerates where the constraint rows stay independent. Charts from
    /// `charts().len()` on are run-time charts.
    pub fn charts(&self) -> &[ChartFit] {
        &self.charts
    }

    /// How well `chart` fits at `q`, in `[0, 1]` (as the generated
    /// `chart_fit`): a pivot ratio, or for a declared momentum basis
    /// `|det[A; V^T]|` over its rows' norms; 0 past the last chart.
    pub fn chart_fit(&self, chart: usize, q: &[f64]) -> Result<f64, CallError> {
        Ok(match self.charts.get(chart) {
            Some(ChartFit::Coordinates(dependent, elimination)) => fit_of(
                &Constrained::constraint_matrix(self, q),
                dependent,
                *elimination,
            ),
            Some(ChartFit::Body(dependent, elimination)) => {
                let identity = at_group_identity(&self.symmetry, q.to_vec());
                let rows = Constrained::constraint_matrix(self, &identity);
                fit_of(&rows, dependent, *elimination)
            }
            Some(ChartFit::Declared) => declared_basis_fit(
                self.chart_regularity(chart, q)?,
                &self.unit_energies(q)?,
                &self.unit_energies(&vec![0.0; q.len()])?,
            ),
            None => self
                .runtime_chart(chart)
                .map_or(0.0, |runtime| runtime.fit(q)),
        })
    }

    /// `det[A; V^T]` over its rows' norms in `chart`, `V` the velocities
    /// of unit momenta (`chaplygin_runtime::monitor::reduced_regularity`).
    pub fn chart_regularity(&self, chart: usize, q: &[f64]) -> Result<f64, CallError> {
        let (n, k) = (self.sizes.n, self.sizes.k);
        let mut rows = InterpretedModel::constraint_matrix(self, q)?;
        for j in 0..k {
            let unit: Vec<f64> = (0..k).map(|i| f64::from(u8::from(i == j))).collect();
            rows.extend(self.call_in_chart(chart, "velocities", &[q, &unit])?);
        }
        Ok(hadamard_ratio(DMatrix::from_row_slice(n, n, &rows)))
    }

    /// The kinetic energy of each unit momentum of chart 0 at `q`
    /// (`chaplygin_runtime::monitor::declared_basis_fit`).
    fn unit_energies(&self, q: &[f64]) -> Result<Vec<f64>, CallError> {
        let (n, k) = (self.sizes.n, self.sizes.k);
        let rest = InterpretedModel::energy(self, q, &vec![0.0; n])?;
        (0..k)
            .map(|j| {
                let unit: Vec<f64> = (0..k).map(|i| f64::from(u8::from(i == j))).collect();
                let qdot = self.call("velocities", &[q, &unit])?;
                Ok(InterpretedModel::energy(self, q, &qdot)? - rest)
            })
            .collect()
    }

    /// The run-time chart partial pivoting picks at `q`; `None` without
    /// constraint rows or where they are dependent.
    pub fn pivoted_chart(&self, q: &[f64]) -> Option<usize> {
        partition::pivoted(self, q).map(|index| self.charts.len() + index)
    }

    /// The reduced item `name` (`velocities`, `momenta`, `hamiltonian`,
    /// `hamiltonian_gradient`, `structure_matrix`, `input_matrix`,
    /// `reduced_rhs`, `reduced_rhs_jacobian`) in `chart`, as
    /// [`InterpretedModel::call`]; chart 0 is [`InterpretedModel::call`].
    pub fn call_in_chart(
        &self,
        chart: usize,
        name: &str,
        arguments: &[&[f64]],
    ) -> Result<Vec<f64>, CallError> {
        match self.compiled_in_chart(chart, name)? {
            Some(function) => self.evaluate(function, arguments),
            None => self.call_in_runtime_chart(chart, name, arguments),
        }
    }

    /// The function `name` of `chart` compiled at build time (chart 0's
    /// or a derived chart's); `None` in a run-time chart.
    fn compiled_in_chart(
        &self,
        chart: usize,
        name: &str,
    ) -> Result<Option<&Interpreted>, CallError> {
        let functions = match chart.checked_sub(1) {
            None => &self.functions[..],
            Some(other) if other < self.chart_functions.len() => &self.chart_functions[other],
            Some(_) => return Ok(None),
        };
        function_among(functions, name).map(Some)
    }

    /// [`InterpretedModel::call_in_chart`] into `outputs`, as
    /// [`InterpretedModel::call_into`]: in chart 0 and the compiled charts
    /// a call on the JIT allocates nothing once the input buffer has grown;
    /// in a run-time chart the item is composed from chart 0's functions
    /// into a new vector first.
    ///
    /// # Errors
    /// As [`InterpretedModel::call_into`].
    pub fn call_in_chart_into(
        &self,
        chart: usize,
        name: &str,
        arguments: &[&[f64]],
        outputs: &mut [f64],
    ) -> Result<(), CallError> {
        match self.compiled_in_chart(chart, name)? {
            Some(function) => self.evaluate_into(function, arguments, outputs),
            None => {
                let values = self.call_in_runtime_chart(chart, name, arguments)?;
                if values.len() != outputs.len() {
                    return Err(CallError::Program {
                        function: name.to_string(),
                        source: IrError::OutputCount {
                            expected: values.len(),
                            found: outputs.len(),
                        },
                    });
                }
                outputs.copy_from_slice(&values);
                Ok(())
            }
        }
    }

    /// The run-time chart `chart`, if it is one.
    fn runtime_chart(&self, chart: usize) -> Option<RuntimeChart<'_, InterpretedModel>> {
        let index = chart.checked_sub(self.charts.len())?;
        RuntimeChart::new(self, index)
    }

    /// [`InterpretedModel::call_in_chart`] in a run-time chart; the
    /// arguments are checked against chart 0's function of that name.
    fn call_in_runtime_chart(
        &self,
        chart: usize,
        name: &str,
        arguments: &[&[f64]],
    ) -> Result<Vec<f64>, CallError> {
        let unknown = || CallError::UnknownFunction {
            name: format!("{name} (in chart {chart})"),
        };
        let layout = self.arguments(name).ok_or_else(unknown)?;
        check_arguments(name, &layout, arguments)?;
        let runtime = self.runtime_chart(chart).ok_or_else(unknown)?;
        let (s, p) = (self.sizes.s, self.sizes.p);
        let sized = |len: usize, fill: &dyn Fn(&mut [f64])| {
            let mut out = vec![f64::NAN; len];
            fill(&mut out);
            out
        };
        Ok(match (name, arguments) {
            ("velocities", [q, alpha]) => sized(q.len(), &|out| runtime.velocities(q, alpha, out)),
            ("momenta", [_, qdot]) => sized(self.sizes.k, &|out| runtime.momenta(qdot, out)),
            ("reduced_rhs", [x, u]) => sized(s, &|out| runtime.rhs(x, u, out)),
            ("reduced_rhs_jacobian", [x, u]) => {
                sized(s * s, &|out| runtime.rhs_jacobian(x, u, out))
            }
            ("hamiltonian", [x]) => vec![runtime.hamiltonian(x)],
            ("hamiltonian_gradient", [x]) => sized(s, &|out| runtime.hamiltonian_gradient(x, out)),
            ("structure_matrix", [x]) => sized(s * s, &|out| runtime.structure_matrix(x, out)),
            ("input_matrix", [x]) => sized(s * p, &|out| runtime.input_matrix(x, out)),
            _ => return Err(unknown()),
        })
    }
}

/// A chart's fit on its rows: the pivot ratio of its dependent speeds, of
/// the leading minors where the chart eliminates in order.
fn fit_of(rows: &DMatrix<f64>, dependent: &[usize], elimination: Elimination) -> f64 {
    match elimination {
        Elimination::Exact => signed_pivot_ratio(rows, dependent).abs(),
        Elimination::InOrder => elimination_ratio(rows, dependent),
    }
}
