//! The linear system about a steady motion (MATH.md section 6).
//!
//! **Reduced state.** The symmetry group's coordinates are quotiented out:
//! the state is `z = (r, w)`, the shape `r` (the coordinates the group
//! does not act on; all of them without a symmetry) and the velocity `w`
//! moved to the group's identity: `w = qdot`, except that for an `se2`
//! factor `(w_x, w_y) = R(-theta) (xdot, ydot)` (the body velocity, named
//! `body(dot(x))`, `body(dot(y))`). Invariance makes the flow
//!
//! ```text
//! r' = w_r
//! w' = qddot(q_e(r), w, u) + (w_theta w_y, -w_theta w_x) on each se2 factor's (x, y)
//! ```
//!
//! independent of the group, `q_e(r)` being the configuration with the
//! group's coordinates 0 (the second term is `d/dt R(-theta)` applied to
//! `(xdot, ydot)`). A steady motion is a zero of this flow: with a
//! symmetry, shape at rest and `w`, hence the momentum, constant (a
//! relative equilibrium); without one, an equilibrium.
//!
//! **Constraints eliminated.** The motion stays on
//! `{f(q_e(r)) = 0, A(q_e(r)) w = 0}`; its tangent at the point is the
//! kernel of `Phi = [[df/dr, 0], [d(A w)/dr, A]]`. The state of the linear
//! system is a set of *independent coordinates and speeds* `y`, entries of
//! `z`: the other entries (the dependent ones, one per independent row of
//! `Phi`) are `z_d = -Phi_d^-1 Phi_y y`. The Jacobian `dz'/dz` (exact, from
//! the model's `acceleration_jacobian`; `d(A w)/dr` by Richardson-extrapolated
//! central differences, error of order `eps^(4/5)`) maps the tangent into
//! itself at a steady motion, so `y' = A y + B u` with `A` the rows `y` of
//! `(dz'/dz) dz/dy` and `B` the rows `y` of `dz'/du`.
//!
//! The dependent entries are chosen by Gaussian elimination on `Phi`,
//! preferring (among columns within a factor 10 of the largest pivot) the
//! group's velocities, then the shape velocities and then the shape
//! coordinates, each last declared first; entries the caller names as
//! independent are never chosen.
//!
//! **Canonical form (Meijaard et al. 2007).** With the coordinates `q`
//! and their speeds named independent and one input on each coordinate,
//! two speeds give `M`, `C1`, `K0`, `K2` ([`super::canonical`]); for the
//! benchmark bicycle `y = (phi, delta, dot(phi), dot(delta), dot(theta_r))`.

use super::GroupFactor;
use super::point::OperatingPoint;
use super::{Dynamics, largest, pivots};
use crate::linalg::{self, MatrixError};
use nalgebra::{Complex, DMatrix, DVector};

/// The linear system `y' = A y + B u` about a steady motion.
#[derive(Clone, Debug)]
pub struct LinearSystem {
    /// The names of the independent coordinates and speeds `y`.
    pub state: Vec<String>,
    /// `A = dy'/dy`.
    pub a: DMatrix<f64>,
    /// `B = dy'/du`.
    pub b: DMatrix<f64>,
    /// The eigenvalues of `A`, by descending real part (then imaginary).
    pub eigenvalues: Vec<Complex<f64>>,
}

impl LinearSystem {
    /// Below this times `max(1, max |A_ij|)` an eigenvalue counts as a zero
    /// of a conserved quantity (the square root of round-off: a double zero
    /// of a Jordan block splits by that much).
    pub const ZERO: f64 = 1e-7;

    /// Whether `eigenvalue` is one of the zeros conserved quantities give.
    pub fn is_zero(&self, eigenvalue: Complex<f64>) -> bool {
        eigenvalue.norm() <= Self::ZERO * self.a.amax().max(1.0)
    }

    /// A real part counts as negative below `-MARGIN max(1, max |A_ij|)`:
    /// round-off does not make a centre's eigenvalues stable.
    pub const MARGIN: f64 = 1e-10;

    /// The number of eigenvalues that are zero ([`Self::is_zero`]).
    pub fn zeros(&self) -> usize {
        self.eigenvalues
            .iter()
            .filter(|&&e| self.is_zero(e))
            .count()
    }

    /// `dim ker A`: the directions of a family of steady motions through
    /// the point, one per conserved quantity (numerical rank by the singular
    /// values, below [`Self::ZERO`] `max(1, max |A_ij|)` counting as zero).
    /// Fewer than [`Self::zeros`] means a Jordan chain at zero: a drift that
    /// grows linearly, no conserved quantity.
    pub fn kernel_dimension(&self) -> usize {
        let order = self.a.nrows();
        if order == 0 {
            return 0;
        }
        let tolerance = Self::ZERO * self.a.amax().max(1.0);
        self.a
            .clone()
            .try_svd(false, false, f64::EPSILON, 10_000)
            .map_or(order, |svd| {
                svd.singular_values
                    .iter()
                    .filter(|&&sigma| sigma <= tolerance)
                    .count()
            })
    }

    /// The zeros counted as those of conserved quantities at this point:
    /// the zero eigenvalues with eigenvectors, `min(zeros, dim ker A)`.
    pub fn conserved_zeros(&self) -> usize {
        self.zeros().min(self.kernel_dimension())
    }

    /// Whether the motion is asymptotically stable: every eigenvalue but
    /// the [`Self::conserved_zeros`] in the open left half plane (by
    /// [`Self::MARGIN`]). At a point where an eigenvalue crosses zero this
    /// can overcount; over a family of steady motions
    /// [`Self::is_stable_modulo`] with the family's fewest conserved zeros
    /// does not.
    pub fn is_stable(&self) -> bool {
        self.is_stable_modulo(self.conserved_zeros())
    }

    /// Whether every eigenvalue but `conserved` zeros of conserved
    /// quantities ([`Self::free_eigenvalues`]) lies in the open left half
    /// plane (by [`Self::MARGIN`]).
    pub fn is_stable_modulo(&self, conserved: usize) -> bool {
        let bound = -Self::MARGIN * self.a.amax().max(1.0);
        self.free_eigenvalues(conserved)
            .is_some_and(|free| free.iter().all(|e| e.re < bound))
    }

    /// The largest real part of the eigenvalues but `conserved` zeros of
    /// conserved quantities ([`Self::free_eigenvalues`]; infinite where
    /// `A` has fewer null directions): negative where the motion is
    /// asymptotically stable, it crosses zero where stability is gained or
    /// lost (bisected without [`Self::MARGIN`], which would move the
    /// crossing by the margin over the rate of the real part).
    pub fn largest_real_part_modulo(&self, conserved: usize) -> f64 {
        self.free_eigenvalues(conserved)
            .map_or(f64::INFINITY, |free| {
                free.iter().map(|e| e.re).fold(f64::NEG_INFINITY, f64::max)
            })
    }

    /// Whether the motion is neutrally (spectrally) stable: every
    /// eigenvalue but `conserved` zeros of conserved quantities
    /// ([`Self::free_eigenvalues`]) on the imaginary axis to round-off
    /// (`|re|` within [`Self::MARGIN`]), as a conservative system's are
    /// where it is stable.
    pub fn is_neutral_modulo(&self, conserved: usize) -> bool {
        let bound = Self::MARGIN * self.a.amax().max(1.0);
        self.free_eigenvalues(conserved)
            .is_some_and(|free| free.iter().all(|e| e.re.abs() <= bound))
    }

    /// The eigenvalues of `A` but `conserved` zeros of conserved
    /// quantities, `None` where `A` has fewer null directions (singular
    /// values within [`Self::ZERO`] `max(1, max |A_ij|)`). The null
    /// directions are deflated exactly: with `K` the right singular vectors
    /// of the `conserved` smallest singular values and `L` the others,
    /// `A K = 0` makes `[L K]^T A [L K]` block triangular, so the other
    /// eigenvalues are those of `L^T A L`. Computed from `A` itself, a
    /// cluster of zeros would spread its rounding, of order the square root
    /// of round-off and more, onto an eigenvalue near it (the upright disk
    /// near its critical spin, where a pair of imaginary eigenvalues meets
    /// the zeros).
    pub fn free_eigenvalues(&self, conserved: usize) -> Option<Vec<Complex<f64>>> {
        if conserved == 0 {
            return Some(self.eigenvalues.clone());
        }
        let order = self.a.nrows();
        let svd = self.a.clone().try_svd(false, true, f64::EPSILON, 10_000)?;
        let v_t = svd.v_t?;
        let mut by_value: Vec<usize> = (0..svd.singular_values.len()).collect();
        by_value.sort_by(|&i, &j| svd.singular_values[j].total_cmp(&svd.singular_values[i]));
        let (kept, null) = by_value.split_at(order.checked_sub(conserved)?);
        let tolerance = Self::ZERO * self.a.amax().max(1.0);
        if null.iter().any(|&i| svd.singular_values[i] > tolerance) {
            return None;
        }
        let l = v_t.select_rows(kept).transpose();
        let free = linalg::eigenvalues(l.transpose() * &self.a * l).ok()?;
        Some(free.iter().copied().collect())
    }
}

/// Why a point could not be linearized.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SteadyError {
    /// The point is not a steady motion.
    #[error("not a steady motion ({kind}): the largest residual is d/dt {quantity} = {residual:e}")]
    NotSteady {
        /// "a relative equilibrium: shape at rest, momentum constant" or
        /// "an equilibrium".
        kind: &'static str,
        /// The reduced state entry whose rate is largest.
        quantity: String,
        /// That rate.
        residual: f64,
    },
    /// The mass matrix is singular or indefinite at the point.
    #[error("the mass matrix at the operating point: {0}")]
    MassMatrix(MatrixError),
    /// The equations are not finite at the point.
    #[error("the equations of motion are not finite at the operating point")]
    NonFinite,
    /// The names asked to be independent are not.
    #[error("{names} cannot all be independent: the constraints fix a combination of them")]
    NotIndependent {
        /// The names, joined.
        names: String,
    },
    /// A name asked to be independent is no entry of the reduced state.
    #[error("`{name}` is not an entry of the reduced state ({known})")]
    UnknownName {
        /// The name.
        name: String,
        /// The entries there are.
        known: String,
    },
    /// The eigenvalues could not be computed.
    #[error("eigenvalues: {0}")]
    Eigenvalues(MatrixError),
}

/// The reduced state's layout: shape and group coordinates, and names.
pub(super) struct Layout {
    pub(super) shape: Vec<usize>,
    pub(super) se2: Vec<(usize, usize, usize)>,
    pub(super) group: Vec<usize>,
    pub(super) names: Vec<String>,
}

impl Layout {
    pub(super) fn of(model: &dyn Dynamics) -> Layout {
        let coordinates = model.coordinates();
        let mut group = Vec::new();
        let mut se2 = Vec::new();
        for factor in model.symmetry() {
            match factor {
                GroupFactor::Se2 { x, y, theta } => {
                    group.extend([x, y, theta]);
                    se2.push((x, y, theta));
                }
                GroupFactor::Translation(i) | GroupFactor::Rotation(i) => group.push(i),
            }
        }
        let shape: Vec<usize> = (0..coordinates.len())
            .filter(|i| !group.contains(i))
            .collect();
        let mut names: Vec<String> = shape.iter().map(|&i| coordinates[i].clone()).collect();
        names.extend(coordinates.iter().enumerate().map(|(i, c)| {
            if se2.iter().any(|&(x, y, _)| i == x || i == y) {
                format!("body(dot({c}))")
            } else {
                format!("dot({c})")
            }
        }));
        Layout {
            shape,
            se2,
            group,
            names,
        }
    }

    pub(super) fn nr(&self) -> usize {
        self.shape.len()
    }

    /// `(q_e(r), w)` of a point.
    pub(super) fn reduce(&self, point: &OperatingPoint) -> (Vec<f64>, Vec<f64>) {
        let mut q = point.q.clone();
        let mut w = point.qdot.clone();
        for &(x, y, theta) in &self.se2 {
            let (sin, cos) = point.q[theta].sin_cos();
            w[x] = cos * point.qdot[x] + sin * point.qdot[y];
            w[y] = -sin * point.qdot[x] + cos * point.qdot[y];
        }
        for &i in &self.group {
            q[i] = 0.0;
        }
        (q, w)
    }

    /// `z' = F(z)` at `(q_e, w)`.
    pub(super) fn flow(
        &self,
        model: &dyn Dynamics,
        q: &[f64],
        w: &[f64],
        u: &[f64],
    ) -> DVector<f64> {
        let qddot = model.acceleration(q, w, u);
        let mut rate = DVector::zeros(self.nr() + w.len());
        for (a, &i) in self.shape.iter().enumerate() {
            rate[a] = w[i];
        }
        for (i, value) in qddot.iter().enumerate() {
            rate[self.nr() + i] = *value;
        }
        for &(x, y, theta) in &self.se2 {
            rate[self.nr() + x] += w[theta] * w[y];
            rate[self.nr() + y] -= w[theta] * w[x];
        }
        rate
    }

    /// `(dz'/dz, dz'/du)` at `(q_e, w)`.
    pub(super) fn jacobian(
        &self,
        model: &dyn Dynamics,
        q: &[f64],
        w: &[f64],
        u: &[f64],
    ) -> (DMatrix<f64>, DMatrix<f64>) {
        let (nr, n) = (self.nr(), w.len());
        let (by_q, by_qdot, by_u) = model.acceleration_jacobian(q, w, u);
        let mut jacobian = DMatrix::zeros(nr + n, nr + n);
        for (a, &i) in self.shape.iter().enumerate() {
            jacobian[(a, nr + i)] = 1.0;
            for row in 0..n {
                jacobian[(nr + row, a)] = by_q[(row, i)];
            }
        }
        jacobian.view_mut((nr, nr), (n, n)).copy_from(&by_qdot);
        for &(x, y, theta) in &self.se2 {
            jacobian[(nr + x, nr + y)] += w[theta];
            jacobian[(nr + x, nr + theta)] += w[y];
            jacobian[(nr + y, nr + x)] -= w[theta];
            jacobian[(nr + y, nr + theta)] -= w[x];
        }
        let mut input = DMatrix::zeros(nr + n, by_u.ncols());
        input.view_mut((nr, 0), (n, by_u.ncols())).copy_from(&by_u);
        (jacobian, input)
    }

    /// `Phi = [[df/dr, 0], [d(A w)/dr, A]]` at `(q_e, w)`.
    pub(super) fn constraint_jacobian(
        &self,
        model: &dyn Dynamics,
        q: &[f64],
        w: &[f64],
    ) -> DMatrix<f64> {
        let (nr, n) = (self.nr(), w.len());
        let holonomic = model.holonomic_jacobian(q);
        let a = model.constraint_matrix(q);
        let (h, c) = (holonomic.nrows(), a.nrows());
        let mut phi = DMatrix::zeros(h + c, nr + n);
        let velocity = DVector::from_column_slice(w);
        for (column, &i) in self.shape.iter().enumerate() {
            for row in 0..h {
                phi[(row, column)] = holonomic[(row, i)];
            }
            let derivative = richardson(|step| {
                let mut moved = q.to_vec();
                moved[i] += step;
                model.constraint_matrix(&moved) * &velocity
            });
            for row in 0..c {
                phi[(h + row, column)] = derivative[row];
            }
        }
        phi.view_mut((h, nr), (c, n)).copy_from(&a);
        phi
    }

    /// The preferred order of dependent entries, without `independent`.
    fn dependent_candidates(&self, independent: &[usize]) -> Vec<usize> {
        let nr = self.nr();
        let group_velocities = self.group.iter().map(|&i| nr + i);
        let shape_velocities = self.shape.iter().rev().map(|&i| nr + i);
        let shape = (0..nr).rev();
        group_velocities
            .chain(shape_velocities)
            .chain(shape)
            .filter(|z| !independent.contains(z))
            .collect()
    }
}

/// `d g(x + s)/ds` at `s = 0` by central differences extrapolated once
/// (Richardson): error of order `h^4` with `h = eps^(1/5)`.
pub(super) fn richardson(g: impl Fn(f64) -> DVector<f64>) -> DVector<f64> {
    let h = f64::EPSILON.powf(0.2);
    let central = |step: f64| (g(step) - g(-step)) / (2.0 * step);
    let (coarse, fine) = (central(h), central(h / 2.0));
    (fine * 4.0 - coarse) / 3.0
}

/// Linearizes `model` at `point` with the inputs `u` (see the module
/// documentation), the entries named in `independent` kept in the state.
///
/// # Errors
/// [`SteadyError`]: not a steady motion, a mass matrix that is not positive
/// definite, non-finite equations, an impossible choice of independent
/// entries, eigenvalues that do not converge.
pub fn linearize(
    model: &dyn Dynamics,
    point: &OperatingPoint,
    u: &[f64],
    independent: &[&str],
) -> Result<LinearSystem, SteadyError> {
    let layout = Layout::of(model);
    let (q, w) = layout.reduce(point);
    linalg::cholesky(model.mass_matrix(&q)).map_err(SteadyError::MassMatrix)?;
    check_steady(&layout, &layout.flow(model, &q, &w, u), &w)?;
    let (jacobian, input) = layout.jacobian(model, &q, &w, u);
    let phi = layout.constraint_jacobian(model, &q, &w);
    if jacobian
        .iter()
        .chain(input.iter())
        .chain(phi.iter())
        .any(|x| !x.is_finite())
    {
        return Err(SteadyError::NonFinite);
    }
    let named = named_entries(&layout, independent)?;
    let candidates = layout.dependent_candidates(&named);
    let chosen = pivots(&phi, &candidates, 0.1, 1e-10 * phi.amax().max(1.0));
    let full_rank = pivots(
        &phi,
        &(0..phi.ncols()).collect::<Vec<_>>(),
        1.0,
        1e-10 * phi.amax().max(1.0),
    );
    if chosen.len() < full_rank.len() {
        return Err(SteadyError::NotIndependent {
            names: independent.join(", "),
        });
    }
    let basis = tangent_basis(&phi, &chosen);
    let kept: Vec<usize> = (0..phi.ncols())
        .filter(|z| chosen.iter().all(|&(_, d)| d != *z))
        .collect();
    let a = (&jacobian * &basis).select_rows(&kept);
    let b = input.select_rows(&kept);
    let eigenvalues = linalg::eigenvalues(a.clone())
        .map_err(SteadyError::Eigenvalues)?
        .iter()
        .copied()
        .collect();
    Ok(LinearSystem {
        state: kept.iter().map(|&z| layout.names[z].clone()).collect(),
        a,
        b,
        eigenvalues,
    })
}

/// [`SteadyError::NotSteady`] unless every rate of `z' = F(z)` is round-off.
pub(super) fn check_steady(
    layout: &Layout,
    rate: &DVector<f64>,
    w: &[f64],
) -> Result<(), SteadyError> {
    let speed = w.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    match largest(rate.as_slice()) {
        Some((worst, residual)) if residual.abs() > 1e-8 * speed * speed => {
            Err(SteadyError::NotSteady {
                kind: if layout.group.is_empty() {
                    "an equilibrium"
                } else {
                    "a relative equilibrium: shape at rest, momentum constant"
                },
                quantity: layout.names[worst].clone(),
                residual,
            })
        }
        Some((_, residual)) if !residual.is_finite() => Err(SteadyError::NonFinite),
        _ => Ok(()),
    }
}

/// The indices in `z` of the entries named.
fn named_entries(layout: &Layout, names: &[&str]) -> Result<Vec<usize>, SteadyError> {
    names
        .iter()
        .map(|name| {
            layout
                .names
                .iter()
                .position(|n| n == name)
                .ok_or_else(|| SteadyError::UnknownName {
                    name: name.to_string(),
                    known: layout.names.join(", "),
                })
        })
        .collect()
}

/// `dz/dy`: the identity on the kept entries, `-Phi_d^-1 Phi_y` on the
/// dependent ones (the pivots' rows and columns).
fn tangent_basis(phi: &DMatrix<f64>, chosen: &[(usize, usize)]) -> DMatrix<f64> {
    let (rows, dependent): (Vec<usize>, Vec<usize>) = chosen.iter().copied().unzip();
    let kept: Vec<usize> = (0..phi.ncols())
        .filter(|z| !dependent.contains(z))
        .collect();
    let phi_rows = phi.select_rows(&rows);
    let phi_dependent = phi_rows.select_columns(&dependent);
    let phi_kept = phi_rows.select_columns(&kept);
    let solved = if dependent.is_empty() {
        DMatrix::zeros(0, kept.len())
    } else {
        phi_dependent
            .lu()
            .solve(&(-phi_kept))
            .unwrap_or_else(|| DMatrix::from_element(dependent.len(), kept.len(), f64::NAN))
    };
    let mut basis = DMatrix::zeros(phi.ncols(), kept.len());
    for (j, &z) in kept.iter().enumerate() {
        basis[(z, j)] = 1.0;
    }
    for (i, &z) in dependent.iter().enumerate() {
        basis.set_row(z, &solved.row(i));
    }
    basis
}

#[cfg(test)]
mod tests {
    use super::LinearSystem;
    use crate::linalg;
    use nalgebra::{DMatrix, Rotation3};

    /// `A = Q block Q^T`, `Q` a rotation that mixes every entry.
    fn system(block: DMatrix<f64>) -> LinearSystem {
        let q = DMatrix::from_iterator(
            3,
            3,
            Rotation3::from_euler_angles(0.3, -0.7, 1.1)
                .matrix()
                .iter()
                .copied(),
        );
        let a = &q * block * q.transpose();
        let mut eigenvalues: Vec<_> = linalg::eigenvalues(a.clone())
            .unwrap()
            .iter()
            .copied()
            .collect();
        eigenvalues.sort_by(|x, y| y.re.total_cmp(&x.re));
        LinearSystem {
            state: vec!["a".into(), "b".into(), "c".into()],
            b: DMatrix::zeros(3, 0),
            a,
            eigenvalues,
        }
    }

    /// A conserved zero beside a centre `+-i w`: neutral, not asymptotically
    /// stable; damped, asymptotically stable, not neutral; with the
    /// centre's frequency small beside the zero, still neutral (the zero
    /// deflated exactly), and its real parts exactly 0 up to round-off.
    #[test]
    fn a_centre_beside_a_conserved_zero_is_neutral() {
        for (w, damping) in [(2.0, 0.0), (2.0, 0.3), (1e-3, 0.0)] {
            let block = DMatrix::from_row_slice(
                3,
                3,
                &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -w * w, -damping],
            );
            let linear = system(block);
            assert_eq!(linear.conserved_zeros(), 1);
            assert_eq!(linear.is_neutral_modulo(1), damping == 0.0, "w = {w}");
            assert_eq!(linear.is_stable_modulo(1), damping > 0.0, "w = {w}");
            let free = linear.free_eigenvalues(1).expect("one null direction");
            assert_eq!(free.len(), 2);
            for e in free {
                assert!((e.norm() - w).abs() < 1e-12 * w.max(1.0) || damping > 0.0);
                assert!((e.re + damping / 2.0).abs() < 1e-14, "{e}");
            }
            assert!(linear.free_eigenvalues(2).is_none());
            let largest = linear.largest_real_part_modulo(1);
            assert!((largest + damping / 2.0).abs() < 1e-14, "{largest}");
        }
    }
}
