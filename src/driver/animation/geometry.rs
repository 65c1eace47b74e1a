//! The shapes of bodies, decided from their contacts' offsets over a run's
//! samples (the module's documentation of `driver::animation` says which
//! shape a body gets), and the quaternions of their poses.

use super::MIN_SIZE;
use crate::animate::Shape;
use crate::runtime::nalgebra::{Matrix3, SymmetricEigen, Vector3};
use chaplygin_codegen::interpret::{BodyState, DISC_THICKNESS, Drawing};

/// How far from perpendicular, or from parallel, two unit vectors may be
/// (the sine or cosine of the angle between them); how far, relative, a
/// length may change and still be the same.
const TOLERANCE: f64 = 1e-6;

/// The density of a particle's sphere, kg/m^3 (water's).
const DENSITY: f64 = 1000.0;

/// How a body looks: its shape, the shape's local axes in the body frame's
/// axes (the columns of `axes`), and the shape's centre from the body's,
/// in the body frame's axes.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Look {
    pub(super) shape: Shape,
    pub(super) axes: Matrix3<f64>,
    pub(super) center: Vector3<f64>,
}

impl Look {
    /// `shape` along `axes`, centred on the body's centre.
    fn centred(shape: Shape, axes: Matrix3<f64>) -> Look {
        Look {
            shape,
            axes,
            center: Vector3::zeros(),
        }
    }
}

/// A body over the run: body `body` of the mechanism drawn at `samples`
/// (the run's frames, the first one first, and the first frame's
/// configuration with each coordinate in turn moved by one), the indices of
/// its contacts, and the world's `down` in ground axes.
pub(super) struct Run<'a> {
    pub(super) samples: &'a [&'a Drawing],
    pub(super) body: usize,
    pub(super) contacts: Vec<usize>,
    pub(super) down: Vector3<f64>,
}

impl Run<'_> {
    /// The body at the first frame.
    fn first(&self) -> &BodyState {
        &self.samples[0].bodies[self.body]
    }

    /// Contact `contact`'s offset `P - C` from the body's centre, in the
    /// body's axes, at every sample: by the frame's rotation divided by
    /// the cube root of its determinant (Euler parameters moved off their
    /// unit sphere scale it).
    fn offsets(&self, contact: usize) -> Vec<Vector3<f64>> {
        (self.samples.iter())
            .map(|drawing| {
                let state = &drawing.bodies[self.body];
                let rotation = Matrix3::from_row_slice(&state.rotation);
                let rotation = rotation / rotation.determinant().cbrt();
                let offset = Vector3::from(drawing.contacts[contact]) - Vector3::from(state.center);
                rotation.transpose() * offset
            })
            .collect()
    }
}

/// The look of the body of `run`, a particle if `particle`; `None` for one
/// not drawn (see the module's documentation of `driver::animation`).
pub(super) fn look_of(run: &Run, particle: bool) -> Option<Look> {
    let state = run.first();
    if particle {
        return (state.mass > 0.0).then(|| sphere(state.mass));
    }
    let (moments, axes) = principal(&Matrix3::from_row_slice(&state.inertia));
    let rotation = Matrix3::from_row_slice(&state.rotation);
    let down = rotation.transpose() * run.down;
    let ball = run.contacts.iter().find_map(|&c| ball(&run.offsets(c)));
    let wheel =
        || (run.contacts.iter()).find_map(|&c| wheel(&run.offsets(c)[0], &down, &moments, &axes));
    ball.or_else(wheel)
        .or_else(|| (state.mass > 0.0).then(|| body_box(run, &moments, &axes, &down)))
}

/// The box of a body of positive mass with the principal `moments` along
/// `axes`, `down` the world's down in its axes: the box of its inertia,
/// or where that box is flat or a point (a side came out below
/// [`MIN_SIZE`]), the [`chassis`] if there is one.
fn body_box(run: &Run, moments: &Vector3<f64>, axes: &Matrix3<f64>, down: &Vector3<f64>) -> Look {
    let sides = box_sides(run.first().mass, (*moments).into());
    let size = at_least_min(sides);
    let inertia = Look::centred(Shape::Box { size }, *axes);
    match size == sides {
        true => inertia,
        false => chassis(run, axes, down).unwrap_or(inertia),
    }
}

/// A sphere of `mass` at [`DENSITY`].
fn sphere(mass: f64) -> Look {
    let radius = (3.0 * mass / (4.0 * std::f64::consts::PI * DENSITY)).cbrt();
    Look::centred(
        Shape::Sphere {
            radius: radius.max(MIN_SIZE / 2.0),
        },
        Matrix3::identity(),
    )
}

/// The sphere of a ball whose contact is at `offsets` from its centre
/// (body axes, a sample each), if it is one: their lengths agree to a
/// relative [`TOLERANCE`], and their directions keep off every plane
/// through the centre (the least eigenvalue of their mean `u u^T` is over
/// [`TOLERANCE`]). A wheel's offsets keep to the plane perpendicular to
/// its axle.
fn ball(offsets: &[Vector3<f64>]) -> Option<Look> {
    let radius = offsets[0].norm();
    let steady =
        (offsets.iter()).all(|offset| (offset.norm() - radius).abs() <= TOLERANCE * radius);
    if !(steady && radius > 0.0 && radius.is_finite()) {
        return None;
    }
    let spread = (offsets.iter()).fold(Matrix3::zeros(), |sum, offset| {
        sum + offset * offset.transpose()
    }) / (offsets.len() as f64 * radius * radius);
    let least = SymmetricEigen::new(spread).eigenvalues.min();
    (least > TOLERANCE).then(|| Look::centred(Shape::Sphere { radius }, Matrix3::identity()))
}

/// The box of a chassis along `axes` (body axes, `down` the world's down in
/// them): the rectangle bounding the contacts that stay where they are in
/// the body's axes at every sample (to a relative [`TOLERANCE`]), across the
/// two of `axes` nearest horizontal, [`MIN_SIZE`] thick along the third,
/// at the body's centre's height along it; `None` when the rectangle is
/// narrower than [`MIN_SIZE`] either way.
fn chassis(run: &Run, axes: &Matrix3<f64>, down: &Vector3<f64>) -> Option<Look> {
    let carried: Vec<Vector3<f64>> = (0..run.samples[0].contacts.len())
        .filter_map(|c| {
            let offsets = run.offsets(c);
            let first = offsets[0];
            (offsets.iter())
                .all(|offset| (offset - first).norm() <= TOLERANCE * first.norm())
                .then(|| axes.transpose() * first)
        })
        .collect();
    let vertical = (axes.transpose() * down).iamax();
    let mut size = [MIN_SIZE; 3];
    let mut center = Vector3::zeros();
    for k in (0..3).filter(|&k| k != vertical) {
        let low = carried.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let high = carried
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max);
        if high - low < MIN_SIZE {
            return None;
        }
        size[k] = high - low;
        center[k] = (low + high) / 2.0;
    }
    Some(Look {
        shape: Shape::Box { size },
        axes: *axes,
        center: axes * center,
    })
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
        Some(Look::centred(
            Shape::Disc {
                radius,
                thickness: radius * DISC_THICKNESS.0 as f64 / DISC_THICKNESS.1 as f64,
            },
            Matrix3::from_columns(&[axle.cross(&up), axle, up]),
        ))
    })
}

/// The edge lengths `[a, b, c]` of the uniform box of `mass` whose moments
/// of inertia about its centre along its edges are `moments`: from
/// `I1 = m (b^2 + c^2) / 12` and its likes, `a = sqrt(6 (I2 + I3 - I1) / m)`
/// and its likes; an edge that comes out below [`MIN_SIZE`] (or not a
/// number or infinite: a massless body, moments that no box has) is
/// [`MIN_SIZE`].
pub fn box_size(mass: f64, moments: [f64; 3]) -> [f64; 3] {
    at_least_min(box_sides(mass, moments))
}

/// The edge lengths of [`box_size`] as they come out, below [`MIN_SIZE`],
/// not a number or infinite as may be.
fn box_sides(mass: f64, moments: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        (6.0 * (moments[j] + moments[k] - moments[i]) / mass).sqrt()
    })
}

/// `sides` with each one that is below [`MIN_SIZE`], not a number or
/// infinite made [`MIN_SIZE`].
fn at_least_min(sides: [f64; 3]) -> [f64; 3] {
    sides.map(|side| {
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
