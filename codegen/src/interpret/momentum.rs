//! The momentum formulation of a model with a symmetry (MATH.md section 4;
//! Koon & Marsden 1.1-1.3) and its exact first and second derivatives.
//!
//! The state `x = (q, rdot, p)`, s = n + R + K entries (the coordinates,
//! the shape velocities, the momenta), moves by
//!
//! ```text
//! qdot  = reconstructed_velocity(q, rdot, p)   xi = body_velocity(r, rdot, p) moved to the
//!                                              coordinates' frame factor by factor (1.1),
//!                                              rdot on the shape
//! rddot = shape_acceleration(r, rdot, p, u)    the shape rows of `acceleration` at the group
//!                                              identity with the group velocities xi (1.3)
//! pdot  = momentum_rhs(r, rdot, p) + momentum_input_matrix(q) u                    (1.2)
//! ```
//!
//! with `r` the shape coordinates of `q` ([`InterpretedModel::shape`]).
//! The composition is written once, on a [`Tape`]: the plain values run
//! the programs by the model's engine with no direction carried; the
//! Jacobian by `(x, u)` carries `d = s + p` slopes through `body_velocity`,
//! the group's rotation (`sin`, `cos` of `theta` for `se2`),
//! `acceleration`, `momentum_rhs` and `momentum_input_matrix`
//! ([`crate::ir::Program::tangents_along`]), and the Hessian of `w^T f`
//! carries their `d x d` second derivatives too
//! ([`crate::ir::Program::curvatures_along`]): forward differentiation in
//! vector mode (Griewank and Walther, "Evaluating Derivatives", 2nd ed.,
//! SIAM 2008, sections 3.1 and 13.2), exact to round-off, at `d` (`d^2`
//! for the Hessian) times the cost of the values, less the directions a
//! program's inputs do not move along (the group coordinates for the
//! shape equations, `u` for all but `acceleration`).

use super::second::{RowCurvatures, RowLayout};
use super::{CallError, InterpretedModel, check_arguments, function_among};
use crate::ir::Tape;
use crate::model::GroupFactor;

/// Where the momentum formulation's state `x = (q, rdot, p)` keeps what.
struct Layout {
    /// The indices of the shape coordinates `r` in `q`, R of them.
    shape: Vec<usize>,
    /// The number K of momenta.
    momenta: usize,
    /// The state's size, s = n + R + K.
    size: usize,
}

/// The tape entries of a state `x = (q, rdot, p)` and inputs `u`, with
/// the shape coordinates `r` among `q`'s.
struct Entries {
    q: Vec<usize>,
    r: Vec<usize>,
    rdot: Vec<usize>,
    p: Vec<usize>,
    u: Vec<usize>,
}

impl InterpretedModel {
    /// The size s = n + R + K of the momentum formulation's state `(q,
    /// rdot, p)`; `None` without a momentum equation (without a symmetry,
    /// or where the holonomic constraints restrict the shape, as the
    /// benchmark bicycle's do).
    pub fn momentum_form_size(&self) -> Option<usize> {
        self.momentum_layout("momentum_form_size")
            .ok()
            .map(|layout| layout.size)
    }

    /// The momentum formulation's right-hand side `f(x, u) = (qdot, rddot,
    /// pdot)` at `x = (q, rdot, p)` (see the module documentation).
    ///
    /// # Errors
    /// [`CallError::UnknownFunction`] without a momentum equation;
    /// [`CallError::ArgumentLength`] when `x` does not have s entries or `u`
    /// p.
    pub fn momentum_form_rhs(&self, x: &[f64], u: &[f64]) -> Result<Vec<f64>, CallError> {
        let mut tape = Tape::new(0, false);
        let f = self.momentum_form_on(&mut tape, "momentum_form_rhs", x, u)?;
        Ok(tape.values(&f))
    }

    /// The exact Jacobians of [`InterpretedModel::momentum_form_rhs`],
    /// `(df/dx, df/du)`, s x s and s x p row-major: its composition
    /// differentiated forward along `(x, u)`.
    ///
    /// # Errors
    /// As [`InterpretedModel::momentum_form_rhs`].
    pub fn momentum_form_jacobian(
        &self,
        x: &[f64],
        u: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>), CallError> {
        let mut tape = Tape::new(x.len() + u.len(), false);
        let f = self.momentum_form_on(&mut tape, "momentum_form_jacobian", x, u)?;
        let s = x.len();
        let (mut by_x, mut by_u) = (Vec::new(), Vec::new());
        for &entry in &f {
            let (along_x, along_u) = tape.slopes(entry).split_at(s);
            by_x.extend_from_slice(along_x);
            by_u.extend_from_slice(along_u);
        }
        Ok((by_x, by_u))
    }

    /// The exact Hessian of `w^T f` by `(x, u)`, `(s + p) x (s + p)`
    /// row-major and symmetric, `f` the right-hand side of
    /// [`InterpretedModel::momentum_form_rhs`]:
    /// [`InterpretedModel::momentum_form_curvatures`] contracted with `w`.
    ///
    /// # Errors
    /// As [`InterpretedModel::momentum_form_rhs`], and
    /// [`CallError::ArgumentLength`] when `w` does not have s entries.
    pub fn momentum_form_hessian(
        &self,
        x: &[f64],
        u: &[f64],
        w: &[f64],
    ) -> Result<Vec<f64>, CallError> {
        self.momentum_form_curvatures(x, u)?.hessian(w)
    }

    /// The second derivatives of the rows of
    /// [`InterpretedModel::momentum_form_rhs`]'s `f` by `(x, u)`, to be
    /// weighted ([`RowCurvatures::hessian`]): its composition's second
    /// derivatives along `(x, u)`, each row's exact.
    ///
    /// # Errors
    /// As [`InterpretedModel::momentum_form_rhs`].
    pub fn momentum_form_curvatures(
        &self,
        x: &[f64],
        u: &[f64],
    ) -> Result<RowCurvatures, CallError> {
        let name = "momentum_form_hessian";
        let m = x.len() + u.len();
        let mut tape = Tape::new(m, true);
        let f = self.momentum_form_on(&mut tape, name, x, u)?;
        Ok(RowCurvatures {
            function: name,
            form: RowLayout::Blocks { rows: f.len(), m },
            values: f
                .iter()
                .flat_map(|&entry| tape.second(entry))
                .copied()
                .collect(),
        })
    }

    /// The velocity `qdot` of the whole configuration from `(q, rdot, p)`,
    /// as the emitted `reconstructed_velocity`: the body velocity
    /// `body_velocity(r, rdot, p)` moved to the coordinates' frame factor by
    /// factor (`R(theta) (v1, v2)` and `omega` for `se2`, the velocity itself
    /// for a translation or a rotation), `rdot` on the shape.
    ///
    /// # Errors
    /// [`CallError::UnknownFunction`] without a momentum equation;
    /// [`CallError::ArgumentLength`] for an argument of the wrong length.
    pub fn reconstructed_velocity(
        &self,
        q: &[f64],
        rdot: &[f64],
        p: &[f64],
    ) -> Result<Vec<f64>, CallError> {
        let name = "reconstructed_velocity";
        let Layout { shape, momenta, .. } = self.momentum_layout(name)?;
        let lengths = [("q", self.sizes.n), ("rdot", shape.len()), ("p", momenta)];
        check_arguments(name, &lengths, &[q, rdot, p])?;
        let mut tape = Tape::new(0, false);
        let at = Entries::on(&mut tape, &shape, q, rdot, p, &[]);
        let xi = self.call_on(&mut tape, "body_velocity", &[&at.r, &at.rdot, &at.p])?;
        let qdot = self.reconstruction_on(&mut tape, &shape, &at, &xi);
        Ok(tape.values(&qdot))
    }

    /// The shape equations (Koon & Marsden 1.3): the shape rows of
    /// `acceleration` at the group identity (group coordinates 0, shape
    /// coordinates `r`) with the velocity `rdot` on the shape and
    /// `body_velocity(r, rdot, p)` on the group coordinates, in coordinate
    /// order, as the emitted `shape_acceleration` assembles it.
    ///
    /// # Errors
    /// As [`InterpretedModel::reconstructed_velocity`].
    pub fn shape_acceleration(
        &self,
        r: &[f64],
        rdot: &[f64],
        p: &[f64],
        u: &[f64],
    ) -> Result<Vec<f64>, CallError> {
        let name = "shape_acceleration";
        let Layout { shape, momenta, .. } = self.momentum_layout(name)?;
        let lengths = [
            ("r", shape.len()),
            ("rdot", shape.len()),
            ("p", momenta),
            ("u", self.sizes.p),
        ];
        check_arguments(name, &lengths, &[r, rdot, p, u])?;
        let mut tape = Tape::new(0, false);
        let mut q = vec![0.0; self.sizes.n];
        for (a, &i) in shape.iter().enumerate() {
            q[i] = r[a];
        }
        let at = Entries::on(&mut tape, &shape, &q, rdot, p, u);
        let xi = self.call_on(&mut tape, "body_velocity", &[&at.r, &at.rdot, &at.p])?;
        let rddot = self.shape_acceleration_on(&mut tape, &shape, &at, &xi)?;
        Ok(tape.values(&rddot))
    }

    /// The layout of the momentum formulation's state; for a model without
    /// a momentum equation (no symmetry, or one whose holonomic constraints
    /// restrict the shape), [`CallError::UnknownFunction`] naming
    /// `function`.
    fn momentum_layout(&self, function: &str) -> Result<Layout, CallError> {
        let unknown = || CallError::UnknownFunction {
            name: function.to_string(),
        };
        let shape = self.shape().ok_or_else(unknown)?;
        let momenta = function_among(&self.functions, "body_velocity")
            .ok()
            .and_then(|body_velocity| body_velocity.lowered.arguments.get(2))
            .ok_or_else(unknown)?
            .1;
        Ok(Layout {
            size: self.sizes.n + shape.len() + momenta,
            shape,
            momenta,
        })
    }

    /// The entries of `f(x, u)` on `tape`, `x` and `u` moving along the
    /// tape's first directions (see the module documentation); `function`
    /// names the caller in errors.
    fn momentum_form_on(
        &self,
        tape: &mut Tape,
        function: &str,
        x: &[f64],
        u: &[f64],
    ) -> Result<Vec<usize>, CallError> {
        let Layout { shape, size, .. } = self.momentum_layout(function)?;
        check_arguments(function, &[("x", size), ("u", self.sizes.p)], &[x, u])?;
        let (q, rest) = x.split_at(self.sizes.n);
        let (rdot, p) = rest.split_at(shape.len());
        let at = Entries::on(tape, &shape, q, rdot, p, u);
        let xi = self.call_on(tape, "body_velocity", &[&at.r, &at.rdot, &at.p])?;
        let mut f = self.reconstruction_on(tape, &shape, &at, &xi);
        f.extend(self.shape_acceleration_on(tape, &shape, &at, &xi)?);
        let unforced = self.call_on(tape, "momentum_rhs", &[&at.r, &at.rdot, &at.p])?;
        let input_matrix = self.call_on(tape, "momentum_input_matrix", &[&at.q])?;
        let inputs = at.u.len();
        f.extend(unforced.iter().enumerate().map(|(i, &unforced)| {
            let products: Vec<(f64, usize, usize)> = (0..inputs)
                .map(|l| (1.0, input_matrix[i * inputs + l], at.u[l]))
                .collect();
            tape.combination(&[unforced], &products)
        }));
        Ok(f)
    }

    /// The entries of `qdot`: the body velocities `xi` moved to the
    /// coordinates' frame factor by factor, `rdot` on the shape.
    fn reconstruction_on(
        &self,
        tape: &mut Tape,
        shape: &[usize],
        at: &Entries,
        xi: &[usize],
    ) -> Vec<usize> {
        let mut qdot = vec![0; self.sizes.n];
        let mut offset = 0;
        for factor in &self.symmetry {
            match *factor {
                GroupFactor::Se2 { x, y, theta } => {
                    let (sin, cos) = tape.sin_cos(at.q[theta]);
                    let (v1, v2) = (xi[offset], xi[offset + 1]);
                    qdot[x] = tape.combination(&[], &[(1.0, cos, v1), (-1.0, sin, v2)]);
                    qdot[y] = tape.combination(&[], &[(1.0, sin, v1), (1.0, cos, v2)]);
                    qdot[theta] = xi[offset + 2];
                    offset += 3;
                }
                GroupFactor::Translation(i) | GroupFactor::Rotation(i) => {
                    qdot[i] = xi[offset];
                    offset += 1;
                }
            }
        }
        for (&i, &rate) in shape.iter().zip(&at.rdot) {
            qdot[i] = rate;
        }
        qdot
    }

    /// The entries of the shape rows of `acceleration` at the group
    /// identity, with `rdot` on the shape and the body velocities `xi` on
    /// the group coordinates, in coordinate order.
    fn shape_acceleration_on(
        &self,
        tape: &mut Tape,
        shape: &[usize],
        at: &Entries,
        xi: &[usize],
    ) -> Result<Vec<usize>, CallError> {
        let n = self.sizes.n;
        let identity = tape.constants(&[0.0]).start;
        let (mut q, mut qdot) = (vec![identity; n], vec![identity; n]);
        for ((&i, &r), &rate) in shape.iter().zip(&at.r).zip(&at.rdot) {
            q[i] = r;
            qdot[i] = rate;
        }
        let group = (0..n).filter(|i| !shape.contains(i));
        for (&velocity, i) in xi.iter().zip(group) {
            qdot[i] = velocity;
        }
        let accelerations = self.call_on(tape, "acceleration", &[&q, &qdot, &at.u])?;
        Ok(shape.iter().map(|&i| accelerations[i]).collect())
    }

    /// The outputs of the function `name` at the tape's entries
    /// `arguments` (its arguments, in order) and the current parameters,
    /// appended to `tape`: by the model's engine when no direction is
    /// carried, else with their derivatives.
    fn call_on(
        &self,
        tape: &mut Tape,
        name: &str,
        arguments: &[&[usize]],
    ) -> Result<Vec<usize>, CallError> {
        let function = function_among(&self.functions, name)?;
        let values: Vec<Vec<f64>> = arguments
            .iter()
            .map(|entries| tape.values(entries))
            .collect();
        let slices: Vec<&[f64]> = values.iter().map(Vec::as_slice).collect();
        check_arguments(function.name, &function.lowered.arguments, &slices)?;
        if tape.directions() == 0 {
            let outputs = self.evaluate(function, &slices)?;
            return Ok(tape.constants(&outputs).collect());
        }
        tape.apply(
            &function.lowered.program,
            &arguments.concat(),
            &self.parameters,
        )
        .map(Iterator::collect)
        .map_err(|source| CallError::Program {
            function: function.name.to_string(),
            source,
        })
    }
}

impl Entries {
    /// `q`, `rdot`, `p`, `u` appended to `tape`, each moving along the
    /// next of its directions, in that order.
    fn on(
        tape: &mut Tape,
        shape: &[usize],
        q: &[f64],
        rdot: &[f64],
        p: &[f64],
        u: &[f64],
    ) -> Entries {
        let q: Vec<usize> = tape.seeded(q, 0).collect();
        let rdot: Vec<usize> = tape.seeded(rdot, q.len()).collect();
        let p: Vec<usize> = tape.seeded(p, q.len() + rdot.len()).collect();
        let u = tape.seeded(u, q.len() + rdot.len() + p.len()).collect();
        Entries {
            r: shape.iter().map(|&i| q[i]).collect(),
            q,
            rdot,
            p,
            u,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::InterpretedModel;
    use crate::fixtures::SNAKEBOARD;
    use crate::interpret::CallError;
    use crate::interpret::second::tests::{assert_close, assert_hessian_agrees, models_at};

    /// The snakeboard, the differential drive and the rolling disk in
    /// space (`se2(x, y, psi) * rotation(theta)`, under gravity), each with
    /// a state `x = (q, rdot, p)` and inputs `u` where every entry is
    /// nonzero, concatenated.
    fn models() -> Vec<(InterpretedModel, Vec<f64>)> {
        let sources = [
            SNAKEBOARD,
            include_str!("../../../models/differential_drive.model"),
            include_str!("../../../models/rolling_disk_3d.model"),
        ];
        models_at(
            &sources,
            |model| model.momentum_form_size().expect("a symmetry") + model.sizes().p,
            |j| 0.3 * (1.3 * j + 0.4).sin() + 0.05,
        )
    }

    /// `(q, rdot, p)` of `x`.
    fn split<'x>(model: &InterpretedModel, x: &'x [f64]) -> (&'x [f64], &'x [f64], &'x [f64]) {
        let n = model.sizes().n;
        let rates = model.shape().expect("a symmetry").len();
        (&x[..n], &x[n..n + rates], &x[n + rates..])
    }

    /// `|found - expected| <= 1e-8 (|expected| + scale)`, entry by entry.
    fn assert_relative(found: &[f64], expected: &[f64], scale: f64, what: &str) {
        assert_eq!(found.len(), expected.len(), "{what}");
        for (i, (f, e)) in found.iter().zip(expected).enumerate() {
            assert!(
                (f - e).abs() <= 1e-8 * (e.abs() + scale),
                "{what} {i}: {f} vs {e}"
            );
        }
    }

    /// The right-hand side against the Lagrange-d'Alembert equations at the
    /// reconstructed velocity `qdot` (MATH.md section 2): the shape rows of
    /// `acceleration(q, qdot, u)` at `q` itself, not the group identity, and
    /// the time derivative of `momentum(q, qdot)` along their flow, the
    /// `momentum` program's derivative along `(qdot, qddot)`.
    #[test]
    fn the_right_hand_side_is_that_of_the_lagrange_dalembert_equations() {
        for (model, y) in models() {
            let (n, p) = (model.sizes().n, model.sizes().p);
            let (x, u) = y.split_at(y.len() - p);
            let (q, rdot, momenta) = split(&model, x);
            let f = model.momentum_form_rhs(x, u).expect("evaluates");
            let qdot = model
                .reconstructed_velocity(q, rdot, momenta)
                .expect("evaluates");
            let (qddot, _) = model.acceleration(q, &qdot, u).expect("evaluates");
            let shape = model.shape().expect("a symmetry");
            let rddot: Vec<f64> = shape.iter().map(|&i| qddot[i]).collect();
            let program = model
                .programs()
                .find(|(name, _)| *name == "momentum")
                .expect("emitted")
                .1;
            let inputs: Vec<f64> = [q, &qdot, model.parameter_values()].concat();
            let mut slopes: Vec<f64> = [qdot.as_slice(), &qddot].concat();
            slopes.resize(inputs.len(), 0.0);
            let along_flow = program
                .tangents_along(&inputs, &slopes, 1)
                .expect("evaluates");
            let scale = f.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            assert_relative(&along_flow.values, momenta, scale, "momentum");
            assert_eq!(&f[..n], qdot.as_slice());
            let (rates, pdot) = f[n..].split_at(shape.len());
            assert_relative(rates, &rddot, scale, "shape accelerations");
            assert_relative(pdot, &along_flow.derivatives, scale, "momentum rates");
        }
    }

    #[test]
    fn the_jacobian_agrees_with_central_differences_of_the_right_hand_side() {
        for (model, y) in models() {
            let p = model.sizes().p;
            let s = y.len() - p;
            let (by_x, by_u) = model
                .momentum_form_jacobian(&y[..s], &y[s..])
                .expect("evaluates");
            for k in 0..s + p {
                let step = 1e-6;
                let shifted = |by: f64| {
                    let mut at = y.clone();
                    at[k] += by;
                    model
                        .momentum_form_rhs(&at[..s], &at[s..])
                        .expect("evaluates")
                };
                let (plus, minus) = (shifted(step), shifted(-step));
                for i in 0..s {
                    let numeric = (plus[i] - minus[i]) / (2.0 * step);
                    let exact = if k < s {
                        by_x[i * s + k]
                    } else {
                        by_u[i * p + k - s]
                    };
                    assert_close(exact, numeric, &format!("({i}, {k})"));
                }
            }
        }
    }

    /// The Hessian against central differences of `w^T` the exact
    /// Jacobian, exactly symmetric; each model's `(x, x)` block has entries
    /// far from zero, and some model's `(x, u)` block (`momentum_input_matrix`
    /// varies with `q`).
    #[test]
    fn the_hessian_agrees_with_central_differences_of_the_jacobian() {
        let mut by_state_and_input = 0.0_f64;
        for (model, y) in models() {
            let p = model.sizes().p;
            let (s, m) = (y.len() - p, y.len());
            let w: Vec<f64> = (0..s).map(|i| 0.6 - 0.15 * i as f64).collect();
            let hessian = model
                .momentum_form_hessian(&y[..s], &y[s..], &w)
                .expect("evaluates");
            let gradient = |y: &[f64]| -> Vec<f64> {
                let (by_x, by_u) = model
                    .momentum_form_jacobian(&y[..s], &y[s..])
                    .expect("evaluates");
                let contract = |matrix: &[f64], columns: usize, j: usize| -> f64 {
                    (0..s).map(|i| w[i] * matrix[i * columns + j]).sum()
                };
                (0..s)
                    .map(|j| contract(&by_x, s, j))
                    .chain((0..p).map(|l| contract(&by_u, p, l)))
                    .collect()
            };
            let numeric = &assert_hessian_agrees(&hessian, &y, gradient);
            for j in 0..m {
                for k in 0..j {
                    assert_eq!(hessian[j * m + k], hessian[k * m + j], "({j}, {k})");
                }
            }
            let largest = move |rows: std::ops::Range<usize>, columns: std::ops::Range<usize>| {
                rows.flat_map(|j| columns.clone().map(move |k| numeric[j * m + k].abs()))
                    .fold(0.0_f64, f64::max)
            };
            assert!(largest(0..s, 0..s) > 1e-3, "{:?}: (x, x)", model.names());
            by_state_and_input = by_state_and_input.max(largest(0..s, s..m));
        }
        assert!(by_state_and_input > 0.1, "(x, u): {by_state_and_input}");
    }

    #[test]
    fn wrong_lengths_and_models_without_a_symmetry_are_errors() {
        let snakeboard = InterpretedModel::from_source(SNAKEBOARD).expect("derives");
        assert_eq!(
            snakeboard.momentum_form_jacobian(&[0.0; 7], &[0.0; 2]),
            Err(CallError::ArgumentLength {
                function: "momentum_form_jacobian".into(),
                argument: "x".into(),
                expected: 8,
                found: 7,
            })
        );
        assert!(matches!(
            snakeboard.momentum_form_hessian(&[0.0; 8], &[0.0; 2], &[0.0; 3]),
            Err(CallError::ArgumentLength { .. })
        ));
        let free = "pub struct Particle {\n    coordinates: [x],\n    parameters: [m = 1.0],\n    \
                    kinetic_energy: m/2*dot(x)^2,\n    potential_energy: 0,\n    \
                    inputs: [push = x],\n}\n";
        let particle = InterpretedModel::from_source(free).expect("derives");
        assert_eq!(particle.momentum_form_size(), None);
        assert_eq!(
            particle.momentum_form_rhs(&[0.0; 2], &[0.0]),
            Err(CallError::UnknownFunction {
                name: "momentum_form_rhs".into()
            })
        );
    }
}
