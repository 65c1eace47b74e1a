//! The items of a model's `drawing:` section as the page draws them: each
//! shape's dimensions from the first frame (they depend on the parameters
//! only), and its pose at every frame from the values `drawing(q)` gave.
//!
//! A shape oriented by a frame (or a heading) has that frame's axes; a
//! disc given by its axle has its local y axis along the axle and its
//! local z axis as near world up as the axle allows; a segment lies along
//! its local x axis from its first end to its second, centred between
//! them, its local z axis as near up as the segment allows. A segment is
//! rigid: its length at every frame is its first frame's, to a relative
//! [`LENGTH_TOLERANCE`].

use super::geometry::quaternion;
use super::{AnimationError, World};
use crate::animate::{Pose, Shape};
use crate::runtime::nalgebra::{Matrix3, Vector3};
use chaplygin_codegen::interpret::{DrawnItem, Figure, Orientation};

/// How far a segment's length may stray from its first frame's, relative.
pub const LENGTH_TOLERANCE: f64 = 1e-6;

/// How close to zero a direction's length may be before it gives no axis.
const DEGENERATE: f64 = 1e-12;

/// The shape of `item` (its values at the first frame), `None` for a trace.
pub(super) fn shape(item: &DrawnItem<f64>) -> Option<Shape> {
    Some(match item.figure {
        Figure::Box { size, .. } => Shape::Box { size },
        Figure::Sphere { radius, .. } => Shape::Sphere { radius },
        Figure::Disc {
            radius, thickness, ..
        } => Shape::Disc { radius, thickness },
        Figure::Segment { from, to } => Shape::Segment {
            length: (Vector3::from(to) - Vector3::from(from)).norm(),
        },
        Figure::Trace { .. } => return None,
    })
}

/// The pose of `item` at the frame at `time` in the page's world; `shape`
/// is its shape from the first frame.
///
/// # Errors
/// [`AnimationError::Item`] for a disc's axle or a segment of length zero,
/// or a segment whose length changed.
pub(super) fn pose(
    item: &DrawnItem<f64>,
    shape: &Shape,
    world: &World,
    time: f64,
) -> Result<Pose, AnimationError> {
    let refuse = |reason: String| AnimationError::Item {
        item: item.name.clone(),
        time,
        reason,
    };
    let turn = world.turn();
    let (position, axes) = match &item.figure {
        Figure::Box {
            center,
            orientation,
            ..
        }
        | Figure::Sphere {
            center,
            orientation,
            ..
        }
        | Figure::Disc {
            center,
            orientation,
            ..
        } => {
            let axes = match orientation {
                Orientation::Axes(axes) => turn * Matrix3::from_row_slice(axes),
                Orientation::Axle(axle) => along(1, &(turn * Vector3::from(*axle)))
                    .ok_or_else(|| refuse("its axle is zero".into()))?,
            };
            (world.point(*center), axes)
        }
        Figure::Segment { from, to } => {
            let (from, to) = (
                Vector3::from(world.point(*from)),
                Vector3::from(world.point(*to)),
            );
            let length = (to - from).norm();
            if let Shape::Segment { length: first } = *shape
                && (length - first).abs() > LENGTH_TOLERANCE * first
            {
                return Err(refuse(format!(
                    "a segment is rigid, and its length {length} differs from its first \
                     frame's {first}"
                )));
            }
            let axes = along(0, &(to - from)).ok_or_else(|| refuse("its ends coincide".into()))?;
            (((from + to) / 2.0).into(), axes)
        }
        Figure::Trace { point } => (world.point(*point), Matrix3::identity()),
    };
    Ok(Pose {
        position,
        quaternion: quaternion(&axes),
    })
}

/// The right-handed axes whose axis `index` (0 for x, 1 for y) is along
/// `direction` and whose z axis is the nearest to up (world z, or world x
/// for a vertical direction); `None` for a zero direction.
fn along(index: usize, direction: &Vector3<f64>) -> Option<Matrix3<f64>> {
    let axis = direction.try_normalize(DEGENERATE)?;
    let perpendicular = |v: Vector3<f64>| (v - axis * axis.dot(&v)).try_normalize(1e-6);
    let up = perpendicular(Vector3::z()).or_else(|| perpendicular(Vector3::x()))?;
    Some(match index {
        0 => Matrix3::from_columns(&[axis, up.cross(&axis), up]),
        _ => Matrix3::from_columns(&[axis.cross(&up), axis, up]),
    })
}
