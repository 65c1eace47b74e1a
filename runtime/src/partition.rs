//! Charts of D chosen at run time: generalized coordinate partitioning
//! (R. A. Wehage & E. J. Haug, "Generalized coordinate partitioning for
//! dimension reduction in analysis of constrained dynamic systems",
//! J. Mech. Design 104 (1982) 247-255), the guarantee behind the charts
//! derived at build time (docs/guide/simulating.md, "Chart switching").
//!
//! Where the rows of `A(q)` are independent, Gaussian elimination with
//! partial pivoting picks `c` dependent speeds `r` whose minor `A_r` is
//! regular ([`crate::monitor::partial_pivots`]); the other `k` speeds `s`
//! are independent and
//!
//! ```text
//! X(q) = [I; -A_r^-1 A_s]   (rows permuted back),   qdot = X(q) v,   v = qdot_s
//! ```
//!
//! is a basis of D. A run-time chart has the reduced form's state layout
//! `x = (q, v)` (its momenta are the independent speeds, as for the tool's
//! own bases `h = (g X)^T`, MATH.md section 3) and its items are computed
//! from the model's generated `A(q)`, `g(q)`, Lagrange-d'Alembert
//! accelerations and energy:
//!
//! ```text
//! xdot   = (X v, qddot_s(q, X v, u))                       exact
//! H      = T(q, X v) + V(q),   dH/dv = X^T g X v            exact
//! dH/dq  at fixed v                                         central differences
//! Jbar   = [[0, P^T], [-P, Gamma]],   P = gbar X^T,   gbar = (X^T g X)^-1
//! Gamma  = (z w^T - w z^T) / |w|^2,   w = dH/dv,   z = vdot(u = 0) + P dH/dq
//! Bbar   = [0; vdot(e_l) - vdot(0)]   column by input (accelerations are affine in u)
//! ```
//!
//! `Jbar` is skew-symmetric by construction, so the discrete gradient keeps
//! `H` to round-off in a run-time chart too, and `Jbar dH/dx + Bbar u` is
//! the exact flow up to the component of the difference error of `dH/dq`
//! along `w` (`w . z = dH/dt - y . u = 0` for the exact gradient). `Gamma`
//! is not the reduced form's own gyroscopic matrix, which needs the
//! derivatives of `X` and `g`; it is the skew matrix of rank two that
//! completes the exact flow. The Jacobian `d xdot/dx` is taken by central
//! differences (implicit methods use it in Newton's iteration only).
//!
//! A run-time chart is numbered after the model's generated charts by its
//! dependent speeds: chart `charts() + i` has the `i`-th set of `c` of the
//! `n` coordinates in lexicographic order ([`index_of`], [`dependent_of`]).
//! Models with run-time sizes and generated ones (through [`Compiled`]) are
//! read alike ([`Constrained`]); on fixed sizes nothing here allocates.

use crate::arrays::leading;
use crate::linalg::Square;
use crate::monitor::{hadamard_ratio, partial_pivots, signed_pivot_ratio};
use crate::system::LagrangeDalembert;
use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, Dim, OMatrix, OVector};

/// What a run-time chart reads of a model: `n` coordinates, `c`
/// constraint rows, `k = n - c` independent speeds and `p` inputs, as
/// nalgebra dimensions (fixed for generated models, dynamic for models
/// interpreted at run time).
pub trait Constrained {
    /// The coordinates.
    type N: Square;
    /// The constraint rows.
    type C: Square;
    /// The independent speeds, `n - c`.
    type K: Square;
    /// The inputs.
    type P: Dim;
    /// The four dimensions.
    fn dimensions(&self) -> (Self::N, Self::C, Self::K, Self::P);
    /// `A(q)`.
    fn constraint_matrix(&self, q: &[f64]) -> OMatrix<f64, Self::C, Self::N>
    where
        DefaultAllocator: Allocator<Self::C, Self::N>;
    /// `g(q)`.
    fn mass_matrix(&self, q: &[f64]) -> OMatrix<f64, Self::N, Self::N>
    where
        DefaultAllocator: Allocator<Self::N, Self::N>;
    /// The Lagrange-d'Alembert accelerations `qddot(q, qdot, u)`.
    fn acceleration(&self, q: &[f64], qdot: &[f64], u: &[f64]) -> OVector<f64, Self::N>
    where
        DefaultAllocator: Allocator<Self::N>;
    /// The energy `T + V` at `(q, qdot)`.
    fn energy(&self, q: &[f64], qdot: &[f64]) -> f64;
}

/// The allocations a run-time chart makes (on the stack for fixed sizes).
pub trait Allocations<N: Dim, C: Dim, K: Dim, P: Dim>:
    Allocator<N>
    + Allocator<C>
    + Allocator<K>
    + Allocator<P>
    + Allocator<N, N>
    + Allocator<C, N>
    + Allocator<N, C>
    + Allocator<C, C>
    + Allocator<C, K>
    + Allocator<N, K>
    + Allocator<K, N>
    + Allocator<K, K>
{
}

impl<N: Dim, C: Dim, K: Dim, P: Dim, T> Allocations<N, C, K, P> for T where
    T: Allocator<N>
        + Allocator<C>
        + Allocator<K>
        + Allocator<P>
        + Allocator<N, N>
        + Allocator<C, N>
        + Allocator<N, C>
        + Allocator<C, C>
        + Allocator<C, K>
        + Allocator<N, K>
        + Allocator<K, N>
        + Allocator<K, K>
{
}

/// A generated model read as [`Constrained`]: `N` coordinates, `C` rows,
/// `K = N - C`, `P` inputs.
pub struct Compiled<'a, M, const N: usize, const C: usize, const K: usize, const P: usize>(
    pub &'a M,
);

impl<M, const N: usize, const C: usize, const K: usize, const P: usize> Constrained
    for Compiled<'_, M, N, C, K, P>
where
    M: crate::linearize::Linearization<N, C, P>,
    Const<N>: Square,
    Const<C>: Square,
    Const<K>: Square,
{
    type N = Const<N>;
    type C = Const<C>;
    type K = Const<K>;
    type P = Const<P>;

    fn dimensions(&self) -> (Const<N>, Const<C>, Const<K>, Const<P>) {
        const { assert!(K + C == N, "K = N - C") };
        (Const, Const, Const, Const)
    }

    fn constraint_matrix(&self, q: &[f64]) -> OMatrix<f64, Const<C>, Const<N>> {
        crate::arrays::matrix_from_rows(&self.0.constraint_matrix(&leading(q)))
    }

    fn mass_matrix(&self, q: &[f64]) -> OMatrix<f64, Const<N>, Const<N>> {
        crate::arrays::matrix_from_rows(&self.0.mass_matrix(&leading(q)))
    }

    fn acceleration(&self, q: &[f64], qdot: &[f64], u: &[f64]) -> OVector<f64, Const<N>> {
        self.0
            .acceleration(&leading(q), &leading(qdot), &leading(u))
            .0
            .into()
    }

    fn energy(&self, q: &[f64], qdot: &[f64]) -> f64 {
        LagrangeDalembert::energy(self.0, &leading(q), &leading(qdot))
    }
}

/// `C(n, k)`, saturating at `usize::MAX`.
fn binomial(n: usize, k: usize) -> usize {
    if k > n {
        return 0;
    }
    let k = k.min(n - k);
    let mut value: u128 = 1;
    for i in 0..k {
        value = value * (n - i) as u128 / (i + 1) as u128;
        if value > usize::MAX as u128 {
            return usize::MAX;
        }
    }
    value as usize
}

/// The position of the increasing index set `dependent` among the
/// `c`-element subsets of `0..n` in lexicographic order.
///
/// ```
/// use chaplygin_runtime::partition::{dependent_of, index_of};
/// assert_eq!(index_of(4, &[0, 1]), 0);
/// assert_eq!(index_of(4, &[2, 3]), 5);
/// let mut dependent = [0; 2];
/// assert!(dependent_of(4, 5, &mut dependent));
/// assert_eq!(dependent, [2, 3]);
/// assert!(!dependent_of(4, 6, &mut dependent));
/// ```
pub fn index_of(n: usize, dependent: &[usize]) -> usize {
    let c = dependent.len();
    let mut index = 0;
    let mut next = 0;
    for (i, &chosen) in dependent.iter().enumerate() {
        for skipped in next..chosen {
            index += binomial(n - skipped - 1, c - i - 1);
        }
        next = chosen + 1;
    }
    index
}

/// The set at `index` of [`index_of`], written into `dependent` (`c`
/// entries); `false` when there are not that many sets.
pub fn dependent_of(n: usize, mut index: usize, dependent: &mut [usize]) -> bool {
    let c = dependent.len();
    let mut next = 0;
    for (i, slot) in dependent.iter_mut().enumerate() {
        loop {
            if next >= n {
                return false;
            }
            let with_next = binomial(n - next - 1, c - i - 1);
            if index < with_next {
                *slot = next;
                next += 1;
                break;
            }
            index -= with_next;
            next += 1;
        }
    }
    index == 0
}

/// The run-time chart partial pivoting picks at `q`, by its index of
/// [`index_of`]; `None` without constraint rows or where the rows are
/// dependent.
pub fn pivoted<M: Constrained>(model: &M, q: &[f64]) -> Option<usize>
where
    DefaultAllocator: Allocations<M::N, M::C, M::K, M::P>,
{
    let (n, c, _, _) = model.dimensions();
    if c.value() == 0 {
        return None;
    }
    let mut pivots = OVector::<usize, M::C>::from_element_generic(c, Const::<1>, 0);
    if !partial_pivots(&model.constraint_matrix(q), pivots.as_mut_slice()) {
        return None;
    }
    pivots.as_mut_slice().sort_unstable();
    Some(index_of(n.value(), pivots.as_slice()))
}

/// A run-time chart of a model: its dependent and independent speeds.
pub struct RuntimeChart<'a, M: Constrained>
where
    DefaultAllocator: Allocations<M::N, M::C, M::K, M::P>,
{
    model: &'a M,
    dependent: OVector<usize, M::C>,
    independent: OVector<usize, M::K>,
}

/// The state `(q, v)` of a run-time chart, split.
struct State<N: Dim, K: Dim>
where
    DefaultAllocator: Allocator<N> + Allocator<K>,
{
    q: OVector<f64, N>,
    v: OVector<f64, K>,
}

impl<'a, M: Constrained> RuntimeChart<'a, M>
where
    DefaultAllocator: Allocations<M::N, M::C, M::K, M::P>,
{
    /// The chart at `index` ([`index_of`]); `None` past the last one.
    pub fn new(model: &'a M, index: usize) -> Option<Self> {
        let (n, c, k, _) = model.dimensions();
        let mut dependent = OVector::<usize, M::C>::from_element_generic(c, Const::<1>, 0);
        if !dependent_of(n.value(), index, dependent.as_mut_slice()) {
            return None;
        }
        let mut independent = OVector::<usize, M::K>::from_element_generic(k, Const::<1>, 0);
        let free = (0..n.value()).filter(|j| !dependent.as_slice().contains(j));
        for (slot, j) in independent.iter_mut().zip(free) {
            *slot = j;
        }
        Some(Self {
            model,
            dependent,
            independent,
        })
    }

    /// The dependent speeds.
    pub fn dependent(&self) -> &[usize] {
        self.dependent.as_slice()
    }

    fn split(&self, x: &[f64]) -> State<M::N, M::K> {
        let (n, _, k, _) = self.model.dimensions();
        State {
            q: OVector::from_fn_generic(n, Const::<1>, |i, _| x[i]),
            v: OVector::from_fn_generic(k, Const::<1>, |i, _| x[n.value() + i]),
        }
    }

    /// `X(q)`, `n x k` (NaN where the minor `A_r` is singular).
    fn basis(&self, q: &[f64]) -> OMatrix<f64, M::N, M::K> {
        let (n, c, k, _) = self.model.dimensions();
        let a = self.model.constraint_matrix(q);
        let columns = |indices: &[usize]| {
            OMatrix::<f64, M::C, M::C>::from_fn_generic(c, c, |i, j| a[(i, indices[j])])
        };
        let minor = columns(self.dependent.as_slice());
        let free =
            OMatrix::<f64, M::C, M::K>::from_fn_generic(c, k, |i, j| a[(i, self.independent[j])]);
        let solved = minor
            .lu()
            .solve(&free)
            .unwrap_or_else(|| OMatrix::from_element_generic(c, k, f64::NAN));
        let mut x = OMatrix::<f64, M::N, M::K>::zeros_generic(n, k);
        for (j, &i) in self.independent.iter().enumerate() {
            x[(i, j)] = 1.0;
        }
        for (row, &i) in self.dependent.iter().enumerate() {
            for j in 0..k.value() {
                x[(i, j)] = -solved[(row, j)];
            }
        }
        x
    }

    /// `qdot = X(q) v`, into `qdot`.
    pub fn velocities(&self, q: &[f64], v: &[f64], qdot: &mut [f64]) {
        let (_, _, k, _) = self.model.dimensions();
        let v = OVector::<f64, M::K>::from_fn_generic(k, Const::<1>, |i, _| v[i]);
        qdot.copy_from_slice((self.basis(q) * v).as_slice());
    }

    /// The chart's momenta of an allowed velocity: its independent speeds.
    pub fn momenta(&self, qdot: &[f64], v: &mut [f64]) {
        for (slot, &j) in v.iter_mut().zip(self.independent.iter()) {
            *slot = qdot[j];
        }
    }

    /// `(qdot, vdot)` at the state and the inputs `u`.
    fn flow(
        &self,
        state: &State<M::N, M::K>,
        u: &[f64],
    ) -> (OVector<f64, M::N>, OVector<f64, M::K>) {
        let qdot = self.basis(state.q.as_slice()) * &state.v;
        let qddot = self
            .model
            .acceleration(state.q.as_slice(), qdot.as_slice(), u);
        let (_, _, k, _) = self.model.dimensions();
        let vdot = OVector::from_fn_generic(k, Const::<1>, |i, _| qddot[self.independent[i]]);
        (qdot, vdot)
    }

    fn unforced(&self, state: &State<M::N, M::K>) -> OVector<f64, M::K> {
        let (_, _, _, p) = self.model.dimensions();
        let zero = OVector::<f64, M::P>::zeros_generic(p, Const::<1>);
        self.flow(state, zero.as_slice()).1
    }

    /// `xdot` at `x` and `u`, into `xdot`.
    pub fn rhs(&self, x: &[f64], u: &[f64], xdot: &mut [f64]) {
        let (qdot, vdot) = self.flow(&self.split(x), u);
        let n = qdot.len();
        xdot[..n].copy_from_slice(qdot.as_slice());
        xdot[n..].copy_from_slice(vdot.as_slice());
    }

    /// `d xdot/dx` by central differences, row-major into `jacobian`.
    pub fn rhs_jacobian(&self, x: &[f64], u: &[f64], jacobian: &mut [f64]) {
        let s = x.len();
        let base = self.split(x);
        for j in 0..s {
            let step = f64::EPSILON.cbrt() * x[j].abs().max(1.0);
            let shifted = |by: f64| {
                let mut state = State {
                    q: base.q.clone(),
                    v: base.v.clone(),
                };
                let n = state.q.len();
                match j < n {
                    true => state.q[j] += by,
                    false => state.v[j - n] += by,
                }
                self.flow(&state, u)
            };
            let ((q_plus, v_plus), (q_minus, v_minus)) = (shifted(step), shifted(-step));
            let n = q_plus.len();
            for i in 0..s {
                let difference = match i < n {
                    true => q_plus[i] - q_minus[i],
                    false => v_plus[i - n] - v_minus[i - n],
                };
                jacobian[i * s + j] = difference / (2.0 * step);
            }
        }
    }

    /// `H(q, v) = T(q, X v) + V(q)`.
    pub fn hamiltonian(&self, x: &[f64]) -> f64 {
        let state = self.split(x);
        self.energy(&state)
    }

    fn energy(&self, state: &State<M::N, M::K>) -> f64 {
        let qdot = self.basis(state.q.as_slice()) * &state.v;
        self.model.energy(state.q.as_slice(), qdot.as_slice())
    }

    /// `(dH/dq, dH/dv, P)` at the state: `dH/dq` by central differences,
    /// `dH/dv = X^T g X v`, `P = (X^T g X)^-1 X^T`.
    #[allow(clippy::type_complexity)]
    fn gradient_parts(
        &self,
        state: &State<M::N, M::K>,
    ) -> (
        OVector<f64, M::N>,
        OVector<f64, M::K>,
        OMatrix<f64, M::K, M::N>,
    ) {
        let mut by_q = state.q.clone();
        for j in 0..state.q.len() {
            let step = f64::EPSILON.cbrt() * state.q[j].abs().max(1.0);
            let at = |by: f64| {
                let mut q = state.q.clone();
                q[j] += by;
                self.energy(&State {
                    q,
                    v: state.v.clone(),
                })
            };
            by_q[j] = (at(step) - at(-step)) / (2.0 * step);
        }
        let x = self.basis(state.q.as_slice());
        let g = self.model.mass_matrix(state.q.as_slice());
        let metric_inverse = x.transpose() * &g * &x;
        let by_v = &metric_inverse * &state.v;
        let (_, _, k, _) = self.model.dimensions();
        let projection = metric_inverse
            .lu()
            .solve(&x.transpose())
            .unwrap_or_else(|| {
                OMatrix::from_element_generic(k, state.q.shape_generic().0, f64::NAN)
            });
        (by_q, by_v, projection)
    }

    /// `dH/dx`, into `gradient`.
    pub fn hamiltonian_gradient(&self, x: &[f64], gradient: &mut [f64]) {
        let (by_q, by_v, _) = self.gradient_parts(&self.split(x));
        let n = by_q.len();
        gradient[..n].copy_from_slice(by_q.as_slice());
        gradient[n..].copy_from_slice(by_v.as_slice());
    }

    /// `Jbar(x)` (see the module documentation), row-major into `structure`.
    pub fn structure_matrix(&self, x: &[f64], structure: &mut [f64]) {
        let state = self.split(x);
        let (by_q, w, projection) = self.gradient_parts(&state);
        let z = self.unforced(&state) + &projection * &by_q;
        let (n, s) = (by_q.len(), x.len());
        structure.fill(0.0);
        for a in 0..w.len() {
            for j in 0..n {
                structure[j * s + n + a] = projection[(a, j)];
                structure[(n + a) * s + j] = -projection[(a, j)];
            }
        }
        let squared = w.norm_squared();
        if squared > 0.0 {
            for a in 0..w.len() {
                for b in 0..w.len() {
                    structure[(n + a) * s + n + b] = (z[a] * w[b] - w[a] * z[b]) / squared;
                }
            }
        }
    }

    /// `Bbar(x)`, row-major into `input_matrix` (`s x p`).
    pub fn input_matrix(&self, x: &[f64], input_matrix: &mut [f64]) {
        let state = self.split(x);
        let (_, _, _, p) = self.model.dimensions();
        let unforced = self.unforced(&state);
        let n = state.q.len();
        let p = p.value();
        input_matrix.fill(0.0);
        let mut unit = OVector::<f64, M::P>::zeros_generic(self.model.dimensions().3, Const::<1>);
        for l in 0..p {
            unit.fill(0.0);
            unit[l] = 1.0;
            let (_, forced) = self.flow(&state, unit.as_slice());
            for (a, (f, u)) in forced.iter().zip(unforced.iter()).enumerate() {
                input_matrix[(n + a) * p + l] = f - u;
            }
        }
    }

    /// How well the chart fits at `q`: its pivot ratio.
    pub fn fit(&self, q: &[f64]) -> f64 {
        signed_pivot_ratio(&self.model.constraint_matrix(q), self.dependent.as_slice()).abs()
    }

    /// `det[A; X^T]` over its rows' norms ([`crate::monitor`]).
    pub fn regularity(&self, q: &[f64]) -> f64 {
        let (n, c, _, _) = self.model.dimensions();
        let (a, x) = (self.model.constraint_matrix(q), self.basis(q));
        let rows = OMatrix::<f64, M::N, M::N>::from_fn_generic(n, n, |i, j| match i < c.value() {
            true => a[(i, j)],
            false => x[(j, i - c.value())],
        });
        hadamard_ratio(rows)
    }

    /// The largest `|A(q) X(q) v|`.
    pub fn constraint_violation(&self, x: &[f64]) -> f64 {
        let state = self.split(x);
        let q = state.q.as_slice();
        let residual = self.model.constraint_matrix(q) * (self.basis(q) * &state.v);
        residual.amax()
    }
}

/// `f` applied to the run-time chart `index` of the generated model
/// `model`; `None` past the last chart.
pub fn with_chart<M, const N: usize, const C: usize, const K: usize, const P: usize, T>(
    model: &M,
    index: usize,
    f: impl FnOnce(&RuntimeChart<'_, Compiled<'_, M, N, C, K, P>>) -> T,
) -> Option<T>
where
    M: crate::linearize::Linearization<N, C, P>,
    Const<N>: Square,
    Const<C>: Square,
    Const<K>: Square,
{
    let compiled = Compiled(model);
    RuntimeChart::new(&compiled, index).map(|chart| f(&chart))
}

/// An array of `L` entries written by `fill` (NaN where it writes none).
pub fn vector<const L: usize>(fill: impl FnOnce(&mut [f64])) -> [f64; L] {
    let mut out = [f64::NAN; L];
    fill(&mut out);
    out
}

/// An `R x L` row-major matrix written by `fill` (NaN where it writes none).
pub fn matrix<const R: usize, const L: usize>(fill: impl FnOnce(&mut [f64])) -> [[f64; L]; R] {
    let mut out = [[f64::NAN; L]; R];
    fill(out.as_flattened_mut());
    out
}
