//! Animated scenes as one self-contained HTML page drawn in 3D with three.js.
//!
//! A [`Scene`] is plain data: the frames' [`times`](Scene::times), the
//! [`Item`]s (a [`Shape`] and one [`Pose`] per frame), a few
//! [`Label`]s (numbers shown on screen, one per frame) and [`Trace`]s (a
//! point per frame, drawn as a line that grows with time). [`page`] checks
//! it and writes the page, or says what is wrong with it
//! ([`AnimateError`], naming the item and the frame); it never panics.
//! The driver's `animation` module makes the scene of a mechanism's run (its
//! bodies, contacts and coordinates), as `chaplygin simulate --animate`
//! writes it.
//!
//! # The world frame
//!
//! z up, the ground the plane z = 0, metres (docs/INTERFACE.md, section 10).
//! A pose is the position of an item's local frame and its orientation as a
//! unit quaternion `[x, y, z, w]` rotating local to world coordinates. A
//! disc's axle is its local y axis (three.js's cylinder axis), a box's
//! heading its local x axis, a segment lies along its local x axis centred
//! on its position. A model whose own convention differs converts its poses
//! and says so in [`Scene::note`].
//!
//! # The page
//!
//! One file that works offline: three.js 0.187 (with `OrbitControls`, MIT,
//! its licence header kept; remade by `tools/three/bundle.sh`) and the
//! page's script are inlined, the scene is embedded as
//! `<script type="application/json">` (every `<` escaped, so no `</script>`
//! can end it early) with its numbers written so that they parse back to
//! the same doubles, and a Content-Security-Policy forbids every network
//! request. It shows the items moving over a ground grid, with a play/pause
//! button, a time slider, a speed selector, a "follow" checkbox that keeps
//! the camera on the items' centroid (brought within a few times the largest
//! item when checked), orbit, pan and zoom with the mouse,
//! the time and the labels' values, and the note. Keys: space plays or
//! pauses, the left and right arrows step one frame.
//!
//! For tests and users' scripts the page defines, as docs/INTERFACE.md
//! section 10 specifies:
//!
//! ```js
//! window.chaplygin = {
//!   ready,         // a Promise, resolved after the first frame is drawn
//!   duration,      // the last frame's time minus the first's, seconds
//!   times,         // Float64Array of the frames' times
//!   items,         // [{name, shape: "disc"|"box"|"segment"|"sphere",
//!                  //   radius?, thickness?, size?, length?}, ...]
//!   pose(name, t), // {position: [x, y, z], quaternion: [x, y, z, w]}
//!   seek(t), play(), pause(),
//! };
//! ```
//!
//! `pose` returns the embedded numbers themselves at a frame's time, and
//! between frames interpolates: linearly for the position, by spherical
//! linear interpolation (the shorter way, normalized) for the quaternion;
//! before the first frame or after the last it returns that frame's pose.
//! `seek(t)` draws time `t` at once rather than at the next animation
//! frame (headless browsers rarely run those). The canvas keeps its
//! drawing buffer (`preserveDrawingBuffer`), so a script can read its
//! pixels.
//!
//! # Example
//!
//! ```
//! use chaplygin::animate::{page, Item, Pose, Scene, Shape};
//!
//! let times: Vec<f64> = (0..=10).map(|k| f64::from(k) * 0.1).collect();
//! let r = 0.3;
//! let ball = Item {
//!     name: "ball".into(),
//!     shape: Shape::Sphere { radius: r },
//!     poses: times.iter().map(|&t| Pose::at([t, 0.0, r])).collect(),
//! };
//! let scene = Scene { title: "A ball".into(), items: vec![ball], times, ..Scene::default() };
//! let html = page(&scene).unwrap();
//! assert!(html.starts_with("<!DOCTYPE html>"));
//! ```

use std::collections::HashSet;
use std::fmt::Write as _;

/// three.js 0.187 and its `OrbitControls` as one minified IIFE defining the
/// global `THREE`, made by `tools/three/bundle.sh`.
const THREE: &str = include_str!("animate/three.min.js");
/// The page's own script: reads the embedded scene, draws it and defines
/// `window.chaplygin`.
const SCRIPT: &str = include_str!("animate/page.js");
/// The page's style sheet.
const STYLE: &str = include_str!("animate/page.css");
/// The page, its parts as `{{NAME}}` placeholders.
const TEMPLATE: &str = include_str!("animate/page.html");

/// How far a pose's quaternion's norm may be from 1.
pub const QUATERNION_NORM_TOLERANCE: f64 = 1e-6;

/// An animated scene: frames at increasing times, the items drawn at each,
/// and what the page shows besides.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The page's title.
    pub title: String,
    /// A remark shown under the title, e.g. "the model's z axis points
    /// down; shown with z up".
    pub note: Option<String>,
    /// The items, each with a pose per frame.
    pub items: Vec<Item>,
    /// The frames' times, seconds, increasing; at least one.
    pub times: Vec<f64>,
    /// Numbers shown on screen, a value per frame.
    pub labels: Vec<Label>,
    /// Paths drawn as lines up to the current time, a point per frame.
    pub traces: Vec<Trace>,
}

/// A rigid body of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// Its name, unique among the scene's items: `window.chaplygin.pose`'s
    /// first argument.
    pub name: String,
    /// What it looks like, in its local frame.
    pub shape: Shape,
    /// Its pose at each frame.
    pub poses: Vec<Pose>,
}

/// An item's shape in its local frame, in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A cylinder of the given radius and thickness, its axle the local y
    /// axis, centred on the origin.
    Disc {
        /// The radius.
        radius: f64,
        /// The length along the axle.
        thickness: f64,
    },
    /// A box of the given edge lengths along the local x, y and z axes,
    /// centred on the origin; its heading is the local x axis.
    Box {
        /// The edge lengths along x, y and z.
        size: [f64; 3],
    },
    /// A ball of the given radius centred on the origin.
    Sphere {
        /// The radius.
        radius: f64,
    },
    /// A thin rod of the given length along the local x axis, centred on
    /// the origin.
    Segment {
        /// The length.
        length: f64,
    },
}

impl Shape {
    /// The name `window.chaplygin.items` gives the shape.
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Disc { .. } => "disc",
            Shape::Box { .. } => "box",
            Shape::Sphere { .. } => "sphere",
            Shape::Segment { .. } => "segment",
        }
    }

    /// The shape's dimensions by name, as the page lists them.
    fn dimensions(&self) -> Vec<(&'static str, f64)> {
        match *self {
            Shape::Disc { radius, thickness } => vec![("radius", radius), ("thickness", thickness)],
            Shape::Box { size } => vec![
                ("size[0]", size[0]),
                ("size[1]", size[1]),
                ("size[2]", size[2]),
            ],
            Shape::Sphere { radius } => vec![("radius", radius)],
            Shape::Segment { length } => vec![("length", length)],
        }
    }
}

/// Where an item's local frame is at one frame: its origin in world
/// coordinates and the unit quaternion rotating local coordinates to world
/// ones.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The origin of the item's local frame, metres.
    pub position: [f64; 3],
    /// The orientation as a unit quaternion `[x, y, z, w]`.
    pub quaternion: [f64; 4],
}

impl Pose {
    /// The pose at `position`, not rotated.
    pub fn at(position: [f64; 3]) -> Self {
        Pose {
            position,
            quaternion: [0.0, 0.0, 0.0, 1.0],
        }
    }
}

impl Default for Pose {
    fn default() -> Self {
        Pose::at([0.0; 3])
    }
}

/// A number shown on screen, a value per frame (e.g. a coordinate).
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// What the page writes before the value.
    pub name: String,
    /// The value at each frame.
    pub values: Vec<f64>,
}

/// A path drawn as a line through its points up to the current time (e.g.
/// a wheel's contact point on the ground).
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    /// Its name, unique among the scene's traces.
    pub name: String,
    /// The point at each frame, world coordinates.
    pub points: Vec<[f64; 3]>,
}

/// What is wrong with a [`Scene`] that [`page`] refuses.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AnimateError {
    /// The scene has no frame.
    #[error("the scene has no frame: `times` is empty")]
    NoFrames,
    /// A frame's time is infinite or NaN.
    #[error("frame {frame}: the time {value} is not a finite number")]
    TimeNotFinite {
        /// The frame's index.
        frame: usize,
        /// Its time.
        value: f64,
    },
    /// A frame's time is not after the previous frame's.
    #[error("frame {frame}: the time {value} is not after frame {}'s time {previous}; times must increase", frame - 1)]
    TimesNotIncreasing {
        /// The frame's index.
        frame: usize,
        /// The previous frame's time.
        previous: f64,
        /// The frame's time.
        value: f64,
    },
    /// Two items, two labels or two traces have the same name.
    #[error("two {kind}s are named `{name}`")]
    DuplicateName {
        /// `"item"`, `"label"` or `"trace"`.
        kind: &'static str,
        /// The name.
        name: String,
    },
    /// An item's shape has a dimension that is not a positive finite number.
    #[error("item `{item}`: its {dimension} is {value}, not a positive finite number")]
    BadDimension {
        /// The item's name.
        item: String,
        /// `"radius"`, `"thickness"`, `"size[0]"`, `"size[1]"`, `"size[2]"`
        /// or `"length"`.
        dimension: &'static str,
        /// The dimension's value.
        value: f64,
    },
    /// An item, a label or a trace has not one value per frame.
    #[error("{kind} `{name}` has {found} values for {frames} frames")]
    WrongLength {
        /// `"item"`, `"label"` or `"trace"`.
        kind: &'static str,
        /// Its name.
        name: String,
        /// How many poses, values or points it has.
        found: usize,
        /// How many frames the scene has.
        frames: usize,
    },
    /// A number of an item's pose, a label or a trace is infinite or NaN.
    #[error("{kind} `{name}`, frame {frame}: {what} {value} is not a finite number")]
    NotFinite {
        /// `"item"`, `"label"` or `"trace"`.
        kind: &'static str,
        /// Its name.
        name: String,
        /// The frame's index.
        frame: usize,
        /// Which number: `"position[i]"` or `"quaternion[i]"` of an item,
        /// `"value"` of a label, `"point[i]"` of a trace.
        what: String,
        /// The number.
        value: f64,
    },
    /// A pose's quaternion is not of norm 1 (within
    /// [`QUATERNION_NORM_TOLERANCE`]).
    #[error("item `{item}`, frame {frame}: the quaternion's norm is {norm}, not 1")]
    NotUnitQuaternion {
        /// The item's name.
        item: String,
        /// The frame's index.
        frame: usize,
        /// The quaternion's norm.
        norm: f64,
    },
}

/// Checks `scene` and writes its page: one self-contained HTML document
/// (see the [module's documentation](self)).
///
/// # Errors
///
/// [`AnimateError`] for the first thing found wrong: no frame, a time not
/// finite or not increasing, a name used twice among the items (or the
/// labels, or the traces), a shape's dimension not positive, an item, label
/// or trace without exactly one pose, value or point per frame, a number
/// not finite, a quaternion not of norm 1.
pub fn page(scene: &Scene) -> Result<String, AnimateError> {
    validate(scene)?;
    let data = scene_json(scene);
    let note = scene.note.as_deref().unwrap_or("");
    let note_hidden = if scene.note.is_some() { "" } else { " hidden" };
    let title = escape_html(&scene.title);
    let note = escape_html(note);
    let mut html =
        String::with_capacity(THREE.len() + SCRIPT.len() + STYLE.len() + data.len() + 4096);
    let mut rest = TEMPLATE;
    while let Some(start) = rest.find("{{") {
        let end = start
            + rest[start..]
                .find("}}")
                .expect("the template's placeholders are closed");
        html.push_str(&rest[..start]);
        html.push_str(match &rest[start + 2..end] {
            "TITLE" => &title,
            "NOTE" => &note,
            "NOTE_HIDDEN" => note_hidden,
            "STYLE" => STYLE,
            "DATA" => &data,
            "THREE" => THREE,
            "PAGE" => SCRIPT,
            other => unreachable!("the template has no placeholder {other}"),
        });
        rest = &rest[end + 2..];
    }
    html.push_str(rest);
    Ok(html)
}

fn validate(scene: &Scene) -> Result<(), AnimateError> {
    let frames = scene.times.len();
    if frames == 0 {
        return Err(AnimateError::NoFrames);
    }
    for (frame, &value) in scene.times.iter().enumerate() {
        if !value.is_finite() {
            return Err(AnimateError::TimeNotFinite { frame, value });
        }
        if frame > 0 {
            let previous = scene.times[frame - 1];
            if value <= previous {
                return Err(AnimateError::TimesNotIncreasing {
                    frame,
                    previous,
                    value,
                });
            }
        }
    }
    unique("item", scene.items.iter().map(|item| &item.name))?;
    unique("label", scene.labels.iter().map(|label| &label.name))?;
    unique("trace", scene.traces.iter().map(|trace| &trace.name))?;

    for item in &scene.items {
        for (dimension, value) in item.shape.dimensions() {
            if !(value.is_finite() && value > 0.0) {
                return Err(AnimateError::BadDimension {
                    item: item.name.clone(),
                    dimension,
                    value,
                });
            }
        }
        length("item", &item.name, item.poses.len(), frames)?;
        for (frame, pose) in item.poses.iter().enumerate() {
            finite("item", &item.name, frame, "position", &pose.position)?;
            finite("item", &item.name, frame, "quaternion", &pose.quaternion)?;
            let norm = pose.quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
            // finite: its components are
            if (norm - 1.0).abs() > QUATERNION_NORM_TOLERANCE {
                return Err(AnimateError::NotUnitQuaternion {
                    item: item.name.clone(),
                    frame,
                    norm,
                });
            }
        }
    }
    for label in &scene.labels {
        length("label", &label.name, label.values.len(), frames)?;
        for (frame, &value) in label.values.iter().enumerate() {
            if !value.is_finite() {
                let name = label.name.clone();
                return Err(AnimateError::NotFinite {
                    kind: "label",
                    name,
                    frame,
                    what: "value".into(),
                    value,
                });
            }
        }
    }
    for trace in &scene.traces {
        length("trace", &trace.name, trace.points.len(), frames)?;
        for (frame, point) in trace.points.iter().enumerate() {
            finite("trace", &trace.name, frame, "point", point)?;
        }
    }
    Ok(())
}

fn unique<'a>(
    kind: &'static str,
    names: impl Iterator<Item = &'a String>,
) -> Result<(), AnimateError> {
    let mut seen = HashSet::new();
    for name in names {
        if !seen.insert(name) {
            return Err(AnimateError::DuplicateName {
                kind,
                name: name.clone(),
            });
        }
    }
    Ok(())
}

fn length(kind: &'static str, name: &str, found: usize, frames: usize) -> Result<(), AnimateError> {
    if found == frames {
        Ok(())
    } else {
        Err(AnimateError::WrongLength {
            kind,
            name: name.to_owned(),
            found,
            frames,
        })
    }
}

fn finite(
    kind: &'static str,
    name: &str,
    frame: usize,
    what: &str,
    values: &[f64],
) -> Result<(), AnimateError> {
    match values.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(i) => Err(AnimateError::NotFinite {
            kind,
            name: name.to_owned(),
            frame,
            what: format!("{what}[{i}]"),
            value: values[i],
        }),
    }
}

/// The scene as the page reads it (`src/animate/page.js`):
/// `{"title", "note", "times", "items": [{"name", "shape", dimensions...,
/// "position": [x0, y0, z0, x1, ...], "quaternion": [x0, y0, z0, w0, x1,
/// ...]}], "labels": [{"name", "values"}], "traces": [{"name", "points":
/// [x0, y0, z0, ...]}]}`, keys in that order, arrays flat. Numbers are
/// written so that they parse back to the same doubles and `<` only ever
/// appears escaped, inside strings.
fn scene_json(scene: &Scene) -> String {
    let mut out = String::new();
    out.push_str("{\"title\":");
    string(&mut out, &scene.title);
    out.push_str(",\"note\":");
    match &scene.note {
        Some(note) => string(&mut out, note),
        None => out.push_str("null"),
    }
    out.push_str(",\"times\":");
    numbers(&mut out, scene.times.iter().copied());
    out.push_str(",\"items\":[");
    for (i, item) in scene.items.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str("{\"name\":");
        string(&mut out, &item.name);
        out.push_str(",\"shape\":");
        string(&mut out, item.shape.kind());
        match item.shape {
            Shape::Disc { radius, thickness } => {
                out.push_str(",\"radius\":");
                number(&mut out, radius);
                out.push_str(",\"thickness\":");
                number(&mut out, thickness);
            }
            Shape::Box { size } => {
                out.push_str(",\"size\":");
                numbers(&mut out, size.into_iter());
            }
            Shape::Sphere { radius } => {
                out.push_str(",\"radius\":");
                number(&mut out, radius);
            }
            Shape::Segment { length } => {
                out.push_str(",\"length\":");
                number(&mut out, length);
            }
        }
        out.push_str(",\"position\":");
        numbers(&mut out, item.poses.iter().flat_map(|pose| pose.position));
        out.push_str(",\"quaternion\":");
        numbers(&mut out, item.poses.iter().flat_map(|pose| pose.quaternion));
        out.push('}');
    }
    out.push_str("],\"labels\":[");
    for (i, label) in scene.labels.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str("{\"name\":");
        string(&mut out, &label.name);
        out.push_str(",\"values\":");
        numbers(&mut out, label.values.iter().copied());
        out.push('}');
    }
    out.push_str("],\"traces\":[");
    for (i, trace) in scene.traces.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str("{\"name\":");
        string(&mut out, &trace.name);
        out.push_str(",\"points\":");
        numbers(&mut out, trace.points.iter().flatten().copied());
        out.push('}');
    }
    out.push_str("]}");
    out
}

/// A finite double as the shorter of Rust's two shortest round-trip forms,
/// plain (`0.001`) and exponent (`1e-3`); both are JSON numbers.
fn number(out: &mut String, x: f64) {
    debug_assert!(x.is_finite());
    let plain = format!("{x}");
    let exponent = format!("{x:e}");
    out.push_str(if exponent.len() < plain.len() {
        &exponent
    } else {
        &plain
    });
}

fn numbers(out: &mut String, xs: impl Iterator<Item = f64>) {
    out.push('[');
    for (i, x) in xs.enumerate() {
        if i > 0 {
            out.push(',');
        }
        number(out, x);
    }
    out.push(']');
}

/// A JSON string; `<` is escaped too, so that the text can sit inside a
/// `<script>` element.
fn string(out: &mut String, text: &str) {
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '<' | '\u{2028}' | '\u{2029}' | '\0'..='\u{1f}' => {
                write!(out, "\\u{:04x}", u32::from(c)).expect("writing to a String");
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn escape_html(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests;
