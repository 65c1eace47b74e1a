//! The shapes of bodies and the quaternions of their poses.

use super::MIN_SIZE;
use crate::animate::Shape;
use crate::runtime::nalgebra::{Matrix3, SymmetricEigen, Vector3};
use chaplygin_codegen::interpret::{BodyState, DISC_THICKNESS};

/// How far from perpendicular, or from parallel, two unit vectors may be
/// (the sine or cosine of the angle between them).
const TOLERANCE: f64 = 1e-6;

/// The density of a particle's sphere, kg/m^3 (water's).
const DENSITY: f64 = 1000.0;

/// How a body looks: its shape, and the shape's local axes in the body
/// frame's axes (the columns of `axes`).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Look {
    pub(super) shape: Shape,
    pub(super) axes: Matrix3<f64>,
}

/// The look of a body at its first configuration `state` with the
/// `contacts` points, `down` the world's down in ground axes; `None` for
/// one not drawn (see the module's documentation of `driver::animation`).
pub(super) fn look_of(
    state: &BodyState,
    particle: bool,
    contacts: &[[f64; 3]],
    down: &Vector3<f64>,
) -> Option<Look> {
    if particle {
        return (state.mass > 0.0).then(|| sphere(state.mass));
    }
    let rotation = Matrix3::from_row_slice(&state.rotation);
    let (moments, axes) = principal(&Matrix3::from_row_slice(&state.inertia));
    let to_body = rotation.transpose();
    let down = to_body * down;
    let center = Vector3::from(state.center);
    let wheel = contacts.iter().find_map(|&contact| {
        let offset = to_body * (Vector3::from(contact) - center);
        wheel(&offset, &down, &moments, &axes)
    });
    wheel.or_else(|| {
        (state.mass > 0.0).then(|| Look {
            shape: Shape::Box {
                size: box_size(state.mass, moments.into()),
            },
            axes,
        })
    })
}

/// A sphere of `mass` at [`DENSITY`].
fn sphere(mass: f64) -> Look {
    let radius = (3.0 * mass / (4.0 * std::f64::consts::PI * DENSITY)).cbrt();
    Look {
        shape: Shape::Sphere {
            radius: radius.max(MIN_SIZE / 2.0),
        },
        axes: Matrix3::identity(),
    }
}

/// The principal moments of `inertia` and its principal axes (the columns
/// of a rotation): the frame's own axes when `inertia` is diagonal.
fn principal(inertia: &Matrix3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
    let diagonal = inertia.diagonal();
    if *inertia == Matrix3::from_diagonal(&diagonal) {
        return (diagonal, Matrix3::identity());
    }
    match SymmetricEigen::try_new(*inertia, f64::EPSILON, 1000) {
        Some(eigen) => {
            let mut axes = eigen.eigenvectors;
            if axes.determinant() < 0.0 {
                let flipped = -axes.column(2);
                axes.set_column(2, &flipped);
            }
            (eigen.eigenvalues, axes)
        }
        None => (diagonal, Matrix3::identity()),
    }
}

/// The disc of a wheel whose contact point is at `offset` from its centre
/// (body axes), if it is one: `offset` is perpendicular to a principal axis
/// and points, in the plane perpendicular to it, straight down. Of such
/// axes the one with the largest moment is the axle (on ties y, then x,
/// then z).
fn wheel(
    offset: &Vector3<f64>,
    down: &Vector3<f64>,
    moments: &Vector3<f64>,
    axes: &Matrix3<f64>,
) -> Option<Look> {
    let radius = offset.norm();
    if !(radius > 0.0 && radius.is_finite()) {
        return None;
    }
    let mut order = [1, 0, 2];
    order.sort_by(|&a, &b| moments[b].total_cmp(&moments[a]));
    order.into_iter().find_map(|i| {
        let axle = axes.column(i).into_owned();
        if (axle.dot(offset) / radius).abs() > TOLERANCE {
            return None;
        }
        let below = (down - axle * axle.dot(down)).try_normalize(TOLERANCE)?;
        if (offset / radius - below).norm() > TOLERANCE {
            return None;
        }
        let up = -(offset - axle * axle.dot(offset)).normalize();
        Some(Look {
            shape: Shape::Disc {
                radius,
                thickness: radius * DISC_THICKNESS.0 as f64 / DISC_THICKNESS.1 as f64,
            },
            axes: Matrix3::from_columns(&[axle.cross(&up), axle, up]),
        })
    })
}

/// The edge lengths `[a, b, c]` of the uniform box of `mass` whose moments
/// of inertia about its centre along its edges are `moments`: from
/// `I1 = m (b^2 + c^2) / 12` and its likes, `a = sqrt(6 (I2 + I3 - I1) / m)`
/// and its likes; an edge that comes out below [`MIN_SIZE`] (or not a
/// number or infinite: a massless body, moments that no box has) is
/// [`MIN_SIZE`].
pub fn box_size(mass: f64, moments: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let side = (6.0 * (moments[j] + moments[k] - moments[i]) / mass).sqrt();
        if side.is_finite() && side >= MIN_SIZE {
            side
        } else {
            MIN_SIZE
        }
    })
}

/// The unit quaternion `[x, y, z, w]` of the rotation matrix `m`, `w >= 0`
/// (Shepperd's method: from the largest of the trace and the diagonal, so
/// that no division is by a small number).
pub fn quaternion(m: &Matrix3<f64>) -> [f64; 4] {
    let trace = m.trace();
    let q = if trace > 0.0 {
        let s = 2.0 * (trace + 1.0).sqrt();
        [
            (m[(2, 1)] - m[(1, 2)]) / s,
            (m[(0, 2)] - m[(2, 0)]) / s,
            (m[(1, 0)] - m[(0, 1)]) / s,
            s / 4.0,
        ]
    } else if m[(0, 0)] > m[(1, 1)] && m[(0, 0)] > m[(2, 2)] {
        let s = 2.0 * (1.0 + m[(0, 0)] - m[(1, 1)] - m[(2, 2)]).sqrt();
        [
            s / 4.0,
            (m[(0, 1)] + m[(1, 0)]) / s,
            (m[(0, 2)] + m[(2, 0)]) / s,
            (m[(2, 1)] - m[(1, 2)]) / s,
        ]
    } else if m[(1, 1)] > m[(2, 2)] {
        let s = 2.0 * (1.0 + m[(1, 1)] - m[(0, 0)] - m[(2, 2)]).sqrt();
        [
            (m[(0, 1)] + m[(1, 0)]) / s,
            s / 4.0,
            (m[(1, 2)] + m[(2, 1)]) / s,
            (m[(0, 2)] - m[(2, 0)]) / s,
        ]
    } else {
        let s = 2.0 * (1.0 + m[(2, 2)] - m[(0, 0)] - m[(1, 1)]).sqrt();
        [
            (m[(0, 2)] + m[(2, 0)]) / s,
            (m[(1, 2)] + m[(2, 1)]) / s,
            s / 4.0,
            (m[(1, 0)] - m[(0, 1)]) / s,
        ]
    };
    let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let sign = if q[3] < 0.0 { -1.0 } else { 1.0 };
    q.map(|x| sign * x / norm)
}
