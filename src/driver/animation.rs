//! A run of a model as an animated scene (docs/INTERFACE.md section 10):
//! a mechanism's bodies and the items of the model's `drawing:` section
//! drawn at the recorded configurations, one page written by
//! [`crate::animate::page`].
//!
//! # What is drawn
//!
//! A mechanism (docs/INTERFACE.md section 4) has bodies; the engine's
//! `drawing(q)` gives each body's centre, frame rotation, mass and
//! inertia, and each `no_slip` contact's point, at the model's current
//! parameter values ([`InterpretedModel::drawing`]). The shapes are decided
//! from the bodies and contacts at the run's frames and at the samples of
//! the first frame's configuration with each coordinate in turn moved by
//! one (a metre, a radian: how the mechanism moves, whatever the run
//! does), a contact's offset `P - C` from its body's centre read in the
//! body's axes:
//!
//! - a body with a contact whose offset has the same length `r > 0` at
//!   every sample and a direction that does not keep to one plane through
//!   the centre (the contact wanders over the body's surface: the Chaplygin
//!   ball) is a ball: a [`Shape::Sphere`](crate::animate::Shape::Sphere) of
//!   radius `r` about its centre, on the ground where its contact is;
//! - a body with a contact whose point lies below its centre at the first
//!   frame, the offset of length `r > 0` along world down (gravity, or
//!   `-z` of ground without gravity) seen in a plane through the centre
//!   perpendicular to one of the body's principal axes of inertia, is a
//!   wheel: a [`Shape::Disc`](crate::animate::Shape::Disc) of radius `r` whose axle is that principal
//!   axis (of those, the one with the largest moment: a disc's axle);
//!   with the offset parallel to gravity this is the principal axis
//!   perpendicular to it, the frame's y axis for the benchmark bicycle's
//!   wheels and the rolling disk;
//! - any other body with a positive mass is a [`Shape::Box`](crate::animate::Shape::Box) whose inertia
//!   about its centre is the body's ([`box_size`]), along the frame's axes,
//!   or its principal axes when the inertia is not diagonal;
//! - except where that box is flat or a point (a side comes out below
//!   [`MIN_SIZE`]: a car's chassis declared with the inertia of a plate
//!   about its vertical axis alone, its wheels' masses counted in it), and
//!   the contacts of any bodies that stay at one place in the body's axes
//!   at every sample (its wheels', wherever they are declared) spread over
//!   at least [`MIN_SIZE`] across both of the box's axes nearest
//!   horizontal: then it is the box bounding those contacts across those
//!   two axes, [`MIN_SIZE`] thick along the third at the body's centre. The
//!   mechanism does not say which bodies ride on which, but rigidly
//!   carried contacts are what a chassis's wheels are;
//! - a particle with a positive mass is a [`Shape::Sphere`](crate::animate::Shape::Sphere) of water's
//!   density (at least [`MIN_SIZE`] across);
//! - a body without mass and without a wheel's or a ball's contact is not
//!   drawn (the scene's note lists it).
//!
//! Each item's pose at a frame is its body's centre (moved to the middle of
//! a chassis's box) and frame rotation (a disc's axle being its local y
//! axis, a box's sides along the principal axes), the traces are the
//! contact points, the labels the first three coordinates.
//!
//! A model's `drawing:` section (docs/INTERFACE.md section 10) adds items
//! and traces, placed by `drawing(q)` as well ([`LENGTH_TOLERANCE`] says
//! how rigid a segment is): a shape named like a body replaces the body's
//! automatic shape, a trace named like a contact that contact's trace, and
//! the others follow the bodies and the contacts in the section's order. A
//! model declared by its energy is drawn by its drawing section alone.
//!
//! # The world
//!
//! The page's world has z up and the ground at z = 0. A model whose gravity
//! points along `+z` of ground (the benchmark bicycle's z axis points down)
//! is shown rotated by pi about the ground x axis, `(x, y, z) -> (x, -y,
//! -z)`, and the scene's note says so.
//!
//! # Frames
//!
//! Of the recorded rows every k-th is a frame, k chosen so that frames are
//! about `1 / fps` seconds of simulated time apart ([`frame_rows`]); the
//! last row is always a frame.

mod geometry;
mod items;

pub use geometry::{box_size, quaternion};
pub use items::LENGTH_TOLERANCE;

use crate::animate::{AnimateError, Item, Label, Pose, Scene, Trace};
use crate::runtime::nalgebra::{Matrix3, Vector3};
use crate::runtime::record::Table;
use chaplygin_codegen::interpret::{BodyState, CallError, Drawing, Figure, InterpretedModel};
use geometry::{Look, Run, look_of};

/// The default frames per second of simulated time.
pub const DEFAULT_FPS: f64 = 60.0;

/// The smallest side of a box and the smallest diameter of a sphere, metres.
pub const MIN_SIZE: f64 = 0.02;

/// How many coordinates the page shows as labels.
const LABELS: usize = 3;

/// Why a run cannot be animated.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AnimationError {
    /// The model has neither bodies nor drawing items.
    #[error(
        "`{model}` has nothing to draw: an animation draws a mechanism's bodies \
         (`bodies:` with `body(...)` or `particle(...)`, docs/INTERFACE.md section 4) \
         and the items of a `drawing:` section (section 10)"
    )]
    NothingToDraw {
        /// The model's name.
        model: String,
    },
    /// The frames per second are not a positive finite number.
    #[error("--fps {fps}: the frames per second must be a positive finite number")]
    Fps {
        /// The value given.
        fps: f64,
    },
    /// The run recorded no row.
    #[error("the run recorded no row: there is nothing to animate")]
    NoRows,
    /// The table's columns are not `t` and the coordinates first.
    #[error(
        "the recorded columns {found:?} do not start with `t` and the coordinates {expected:?}"
    )]
    Columns {
        /// `t` and the coordinates.
        expected: Vec<String>,
        /// The table's columns.
        found: Vec<String>,
    },
    /// A row has not one value per column.
    #[error("row {row} has {found} values for {columns} columns")]
    RowLength {
        /// The row's index.
        row: usize,
        /// Its number of values.
        found: usize,
        /// The number of columns.
        columns: usize,
    },
    /// A body's mass or inertia is not finite.
    #[error("body `{body}`: its mass or inertia is not a finite number")]
    NotFinite {
        /// The body.
        body: String,
    },
    /// A drawing item cannot be placed at a frame.
    #[error("drawing item `{item}` at t = {time}: {reason}")]
    Item {
        /// The item's name.
        item: String,
        /// The frame's time.
        time: f64,
        /// What is wrong: a zero axle, coinciding ends, a segment's length
        /// that changed.
        reason: String,
    },
    /// The engine could not evaluate the drawing.
    #[error("`{model}`: {source}")]
    Call {
        /// The model's name.
        model: String,
        /// What the engine reported.
        source: CallError,
    },
    /// The scene is not one the page accepts.
    #[error(transparent)]
    Page(#[from] AnimateError),
}

/// Checks that `model` (named `label`) has bodies or drawing items to
/// draw, before a run.
///
/// # Errors
/// [`AnimationError::NothingToDraw`].
pub fn check(model: &InterpretedModel, label: &str) -> Result<(), AnimationError> {
    match model.bodies().is_empty() {
        true => Err(AnimationError::NothingToDraw {
            model: label.to_string(),
        }),
        false => Ok(()),
    }
}

/// The page of the run recorded in `table` (`t`, then the coordinates,
/// then anything) of `model`, named `label`, at `fps` frames per second
/// of simulated time.
///
/// # Errors
/// As [`scene`], and a scene the page refuses.
pub fn page(
    model: &InterpretedModel,
    label: &str,
    table: &Table,
    fps: f64,
) -> Result<String, AnimationError> {
    Ok(crate::animate::page(&scene(model, label, table, fps)?)?)
}

/// The scene of the run recorded in `table` (see the [module's
/// documentation](self)).
///
/// # Errors
/// A model with nothing to draw, `fps` not positive, a table without rows,
/// whose columns are not `t` and the coordinates first or with a row of
/// another length, a mass or an inertia not finite, a drawing item that
/// cannot be placed.
pub fn scene(
    model: &InterpretedModel,
    label: &str,
    table: &Table,
    fps: f64,
) -> Result<Scene, AnimationError> {
    check(model, label)?;
    if !(fps.is_finite() && fps > 0.0) {
        return Err(AnimationError::Fps { fps });
    }
    check_columns(model, table)?;
    let times: Vec<f64> = table.rows.iter().map(|row| row[0]).collect();
    let rows = frame_rows(&times, fps);
    let n = model.sizes().n;
    let at = |q: &[f64]| {
        model.drawing(q).map_err(|source| AnimationError::Call {
            model: label.to_string(),
            source,
        })
    };
    let drawings = (rows.iter())
        .map(|&row| at(&table.rows[row][1..=n]))
        .collect::<Result<Vec<Drawing>, _>>()?;
    // A probe where the model is undefined (outside its domain, or not
    // finite) tells nothing and is left out.
    let probes: Vec<Drawing> = (0..n)
        .filter_map(|i| {
            let mut q = table.rows[0][1..=n].to_vec();
            q[i] += 1.0;
            model.drawing(&q).ok().filter(is_finite)
        })
        .collect();
    let world = World::of(&drawings[0]);
    let looks = looks(model, &drawings, &probes, &world)?;
    let times: Vec<f64> = rows.iter().map(|&row| times[row]).collect();
    Ok(Scene {
        title: label.to_string(),
        note: note(model, &looks, &world),
        items: scene_items(model, &looks, &drawings, &world, &times)?,
        labels: labels(model, table, &rows),
        traces: traces(model, &drawings, &world),
        times,
    })
}

/// The indices of the rows at `times` that are frames: every k-th, k the
/// whole number of rows nearest to `1 / fps` seconds at the rows' mean
/// spacing (at least 1), and the last row; a last row at the time of the
/// frame before it replaces that frame.
pub fn frame_rows(times: &[f64], fps: f64) -> Vec<usize> {
    let Some(last) = times.len().checked_sub(1) else {
        return Vec::new();
    };
    let spacing = (times[last] - times[0]) / last.max(1) as f64;
    let k = ((1.0 / fps) / spacing).round();
    let k = if k.is_finite() && k >= 1.0 {
        k as usize
    } else {
        1
    };
    let mut rows: Vec<usize> = (0..=last).step_by(k).collect();
    if rows.last() != Some(&last) {
        if rows.len() > 1 && rows.last().is_some_and(|&row| times[row] >= times[last]) {
            rows.pop();
        }
        rows.push(last);
    }
    rows
}

fn check_columns(model: &InterpretedModel, table: &Table) -> Result<(), AnimationError> {
    let expected: Vec<String> = std::iter::once("t".to_string())
        .chain(model.names().coordinates.iter().cloned())
        .collect();
    if !table.columns.starts_with(&expected) {
        return Err(AnimationError::Columns {
            expected,
            found: table.columns.clone(),
        });
    }
    if table.rows.is_empty() {
        return Err(AnimationError::NoRows);
    }
    let columns = table.columns.len();
    match (table.rows.iter()).position(|row| row.len() != columns) {
        Some(row) => Err(AnimationError::RowLength {
            row,
            found: table.rows[row].len(),
            columns,
        }),
        None => Ok(()),
    }
}

/// The page's world seen from the model's ground: down, and whether the
/// model is turned by pi about x to show its `+z` gravity as down.
struct World {
    /// The unit vector down in the model's ground axes.
    down: Vector3<f64>,
    /// Gravity along `+z`: `(x, y, z) -> (x, -y, -z)`.
    flipped: bool,
}

impl World {
    /// The world of the gravity field `drawing.gravity`; without gravity,
    /// down is `-z`.
    fn of(drawing: &Drawing) -> World {
        let gravity = Vector3::from(drawing.gravity);
        let down = gravity.try_normalize(0.0).unwrap_or_else(|| -Vector3::z());
        World {
            down,
            flipped: gravity.z > 0.0,
        }
    }

    /// The conversion from the model's ground axes to the page's.
    fn turn(&self) -> Matrix3<f64> {
        match self.flipped {
            true => Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0)),
            false => Matrix3::identity(),
        }
    }

    /// A point of the model in the page's world.
    fn point(&self, p: [f64; 3]) -> [f64; 3] {
        (self.turn() * Vector3::from(p)).into()
    }
}

/// Whether every body's centre and rotation and every contact is finite.
fn is_finite(drawing: &Drawing) -> bool {
    let bodies = (drawing.bodies.iter()).flat_map(|body| body.center.iter().chain(&body.rotation));
    let contacts = drawing.contacts.iter().flatten();
    bodies.chain(contacts).all(|x| x.is_finite())
}

/// Each body's look over the frames `drawings` and the first frame's
/// `probes` (each coordinate in turn moved by one), `None` for a body not
/// drawn.
fn looks(
    model: &InterpretedModel,
    drawings: &[Drawing],
    probes: &[Drawing],
    world: &World,
) -> Result<Vec<Option<Look>>, AnimationError> {
    let bodies = model.bodies();
    let samples: Vec<&Drawing> = drawings.iter().chain(probes).collect();
    (bodies.bodies.iter().enumerate())
        .map(|(i, body)| {
            let state = &drawings[0].bodies[i];
            if !(state.mass.is_finite() && state.inertia.iter().all(|x| x.is_finite())) {
                return Err(AnimationError::NotFinite {
                    body: body.name.clone(),
                });
            }
            let run = Run {
                samples: &samples,
                body: i,
                contacts: (bodies.contacts.iter().enumerate())
                    .filter(|(_, contact)| contact.body == i)
                    .map(|(c, _)| c)
                    .collect(),
                down: world.down,
            };
            Ok(look_of(&run, body.particle))
        })
        .collect()
}

/// The drawn bodies with their poses at every frame, each replaced by the
/// drawing item of its name if there is one, then the other drawing items.
fn scene_items(
    model: &InterpretedModel,
    looks: &[Option<Look>],
    drawings: &[Drawing],
    world: &World,
    times: &[f64],
) -> Result<Vec<Item>, AnimationError> {
    let bodies = &model.bodies().bodies;
    let mut scene_items = Vec::new();
    for (i, (body, look)) in bodies.iter().zip(looks).enumerate() {
        if let Some(replacing) = drawn_item(model, &body.name) {
            scene_items.extend(drawing_item(replacing, drawings, world, times)?);
        } else if let Some(look) = look {
            scene_items.push(Item {
                name: body.name.clone(),
                shape: look.shape,
                poses: (drawings.iter())
                    .map(|drawing| pose(&drawing.bodies[i], look, world))
                    .collect(),
            });
        }
    }
    for (i, item) in model.bodies().items.iter().enumerate() {
        if !bodies.iter().any(|body| body.name == item.name) {
            scene_items.extend(drawing_item(i, drawings, world, times)?);
        }
    }
    Ok(scene_items)
}

/// The index of the drawing item (not a trace) named `name`.
fn drawn_item(model: &InterpretedModel, name: &str) -> Option<usize> {
    (model.bodies().items.iter())
        .position(|item| item.name == name && !matches!(item.figure, Figure::Trace { .. }))
}

/// The drawing item `i` with its poses at every frame; `None` for a trace.
fn drawing_item(
    i: usize,
    drawings: &[Drawing],
    world: &World,
    times: &[f64],
) -> Result<Option<Item>, AnimationError> {
    let first = &drawings[0].items[i];
    let Some(shape) = items::shape(first) else {
        return Ok(None);
    };
    let poses = (drawings.iter().zip(times))
        .map(|(drawing, &time)| items::pose(&drawing.items[i], &shape, world, time))
        .collect::<Result<_, _>>()?;
    Ok(Some(Item {
        name: first.name.clone(),
        shape,
        poses,
    }))
}

/// A body's pose in the page's world: its centre moved by its look's, and
/// its frame rotation composed with its look's axes.
fn pose(state: &BodyState, look: &Look, world: &World) -> Pose {
    let rotation = Matrix3::from_row_slice(&state.rotation);
    let center = Vector3::from(state.center) + rotation * look.center;
    Pose {
        position: world.point(center.into()),
        quaternion: quaternion(&(world.turn() * rotation * look.axes)),
    }
}

/// The contacts' traces, each replaced by the drawing's trace of its name
/// if there is one, then the drawing's other traces.
fn traces(model: &InterpretedModel, drawings: &[Drawing], world: &World) -> Vec<Trace> {
    let bodies = model.bodies();
    let mut drawn: Vec<Trace> = (bodies.items.iter().enumerate())
        .filter(|(_, item)| matches!(item.figure, Figure::Trace { .. }))
        .map(|(i, item)| Trace {
            name: item.name.clone(),
            points: (drawings.iter())
                .filter_map(|drawing| match drawing.items[i].figure {
                    Figure::Trace { point } => Some(world.point(point)),
                    _ => None,
                })
                .collect(),
        })
        .collect();
    let mut traces: Vec<Trace> = (bodies.contacts.iter().enumerate())
        .map(
            |(i, contact)| match drawn.iter().position(|t| t.name == contact.name) {
                Some(replacing) => drawn.remove(replacing),
                None => Trace {
                    name: contact.name.clone(),
                    points: (drawings.iter())
                        .map(|drawing| world.point(drawing.contacts[i]))
                        .collect(),
                },
            },
        )
        .collect();
    traces.append(&mut drawn);
    traces
}

fn labels(model: &InterpretedModel, table: &Table, rows: &[usize]) -> Vec<Label> {
    (model.names().coordinates.iter().take(LABELS).enumerate())
        .map(|(i, name)| Label {
            name: name.clone(),
            values: rows.iter().map(|&row| table.rows[row][1 + i]).collect(),
        })
        .collect()
}

/// The note: the world's turn, and the bodies not drawn.
fn note(model: &InterpretedModel, looks: &[Option<Look>], world: &World) -> Option<String> {
    let mut parts = Vec::new();
    if world.flipped {
        parts.push(
            "the model's gravity points along its +z axis: shown rotated by pi about x, \
             (x, y, z) -> (x, -y, -z), so that z is up"
                .to_string(),
        );
    }
    let hidden: Vec<&str> = (model.bodies().bodies.iter().zip(looks))
        .filter(|(body, look)| look.is_none() && drawn_item(model, &body.name).is_none())
        .map(|(body, _)| body.name.as_str())
        .collect();
    if !hidden.is_empty() {
        parts.push(format!("not drawn (no mass): {}", hidden.join(", ")));
    }
    (!parts.is_empty()).then(|| parts.join("; "))
}

#[cfg(test)]
mod tests;
