//! The canonical form of Meijaard, Papadopoulos, Ruina & Schwab (2007),
//! equation (2.2),
//!
//! ```text
//! M qddot + v C1 qdot + (g K0 + v^2 K2) q = f
//! ```
//!
//! from two linear systems ([`super::LinearSystem`]) of one family of
//! steady motions at the speeds `v1 != v2`, both with the coordinates `q`
//! and their speeds `dot(q)` among the independent entries of the state and
//! one input per coordinate (`f`, a generalized force on it). The rows of
//! `dot(q)` read `qddot = A_q q + A_v qdot + B_v f`: the other independent
//! entries must not enter them (their columns vanish, to
//! [`DECOUPLED`] times the rows' largest entry), else the coordinates do not
//! decouple and there is no canonical form in them. Then
//!
//! ```text
//! M = B_v^-1,   v C1 = -M A_v,   X(v) = g K0 + v^2 K2 = -M A_q,
//! K2 = (X(v1) - X(v2)) / (v1^2 - v2^2),   K0 = (X(v1) - v1^2 K2) / g.
//! ```
//!
//! For the benchmark bicycle: `q = (phi, delta)`, the state
//! `(phi, delta, dot(phi), dot(delta), dot(theta_r))` and the lean and steer
//! torques as inputs.

use super::LinearSystem;
use nalgebra::DMatrix;

/// Below this times the largest entry of the rows of `dot(q)` (at least 1),
/// another entry's column in them counts as zero.
pub const DECOUPLED: f64 = 1e-9;

/// `M`, `C1`, `K0`, `K2`.
#[derive(Clone, Debug, PartialEq)]
pub struct CanonicalForm {
    /// The mass matrix `M`.
    pub m: DMatrix<f64>,
    /// The velocity-proportional damping-like matrix `C1`.
    pub c1: DMatrix<f64>,
    /// The gravity-proportional stiffness `K0`.
    pub k0: DMatrix<f64>,
    /// The velocity-squared stiffness `K2`.
    pub k2: DMatrix<f64>,
}

/// Why the canonical form could not be read off.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CanonicalError {
    /// A coordinate or speed is no independent entry of the state.
    #[error("`{0}` is not an independent entry of the linear system's state")]
    NotInState(String),
    /// The inputs are not one per coordinate, or do not act independently.
    #[error("the inputs' rows B_v are not square and invertible: {rows} x {columns}")]
    Inputs {
        /// The coordinates.
        rows: usize,
        /// The inputs.
        columns: usize,
    },
    /// Another entry of the state enters the rows of the speeds.
    #[error(
        "`{entry}` enters the equation of `{speed}` (coefficient {value:e}): the coordinates do not decouple from the rest of the state"
    )]
    Coupled {
        /// The other entry.
        entry: String,
        /// The speed whose row it enters.
        speed: String,
        /// Its coefficient there.
        value: f64,
    },
    /// The two speeds do not separate `K0` from `K2`.
    #[error("the speeds {0} and {1} must differ in magnitude and be nonzero")]
    Speeds(f64, f64),
}

/// The rows of `dot(q)` of one linear system: `(A_q, A_v, B_v)`.
type Rows = (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>);

fn rows_of(
    linear: &LinearSystem,
    coordinates: &[&str],
    speeds: &[&str],
) -> Result<Rows, CanonicalError> {
    let index = |name: &str| {
        linear
            .state
            .iter()
            .position(|entry| entry == name)
            .ok_or_else(|| CanonicalError::NotInState(name.to_string()))
    };
    let q: Vec<usize> = coordinates
        .iter()
        .map(|c| index(c))
        .collect::<Result<_, _>>()?;
    let v: Vec<usize> = speeds.iter().map(|s| index(s)).collect::<Result<_, _>>()?;
    let speed_rows = linear.a.select_rows(&v);
    let bound = DECOUPLED * speed_rows.amax().max(1.0);
    for (column, entry) in linear.state.iter().enumerate() {
        if q.contains(&column) || v.contains(&column) {
            continue;
        }
        if let Some(row) = (0..v.len()).find(|&row| speed_rows[(row, column)].abs() > bound) {
            return Err(CanonicalError::Coupled {
                entry: entry.clone(),
                speed: speeds[row].to_string(),
                value: speed_rows[(row, column)],
            });
        }
    }
    Ok((
        speed_rows.select_columns(&q),
        speed_rows.select_columns(&v),
        linear.b.select_rows(&v),
    ))
}

impl CanonicalForm {
    /// The canonical form from the linear systems `slow` at speed `v1` and
    /// `fast` at `v2`, `coordinates` and their `speeds` named as in the
    /// state, gravity `g` (see the module documentation).
    ///
    /// # Errors
    /// [`CanonicalError`]: a name not in the state, another entry of the
    /// state in the rows of the speeds, inputs that are not one invertible
    /// force per coordinate, speeds that do not separate `K0` from `K2`.
    pub fn from_linearizations(
        (slow, v1): (&LinearSystem, f64),
        (fast, v2): (&LinearSystem, f64),
        coordinates: &[&str],
        speeds: &[&str],
        g: f64,
    ) -> Result<CanonicalForm, CanonicalError> {
        if v1 == 0.0 || v1 * v1 == v2 * v2 {
            return Err(CanonicalError::Speeds(v1, v2));
        }
        let (a_q1, a_v1, b_v) = rows_of(slow, coordinates, speeds)?;
        let (a_q2, _, _) = rows_of(fast, coordinates, speeds)?;
        let inputs = CanonicalError::Inputs {
            rows: b_v.nrows(),
            columns: b_v.ncols(),
        };
        if !b_v.is_square() {
            return Err(inputs);
        }
        let m = b_v.try_inverse().ok_or(inputs)?;
        let x1 = -(&m * a_q1);
        let x2 = -(&m * a_q2);
        let k2 = (&x1 - x2) / (v1 * v1 - v2 * v2);
        let k0 = (x1 - &k2 * (v1 * v1)) / g;
        let c1 = -(&m * a_v1) / v1;
        Ok(CanonicalForm { m, c1, k0, k2 })
    }
}
