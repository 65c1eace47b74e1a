//! A frame's state given by how it turns instead of by its coordinates.
//!
//! - `omega(F)=[wx, wy, wz]`: the angular velocity of `F` relative to its
//!   base, in `F`'s axes, sets the velocities of the coordinates that turn
//!   `F` from its base. An `orient` frame's base is its parent, and its
//!   Euler parameters move with `edot = 1/2 e ⊗ (0, omega)` (Nikravesh,
//!   *Computer-Aided Analysis of Mechanical Systems*, 1988, section 6.4). A
//!   `rotate` frame's base is its nearest ancestor that is not a `rotate`
//!   frame whose angle reads coordinates (`ground`, an `orient` frame or a
//!   frame turned by a constant angle). The angles between read exactly
//!   three coordinates, whose rates solve `omega = J(q) rates`; column `i`
//!   of `J` is `vee(R^T dR/dq_i)` of the rotation `R` from the base to `F`,
//!   by central differences of the orientations (to about 1e-10). Where `J`
//!   is singular (Euler angles at gimbal lock) the request is refused.
//! - `angles(F, seq)=[a, b, c]`: an `orient` frame's Euler parameters from
//!   the intrinsic sequence `seq` of three axes, none twice in a row: `F` is
//!   turned by `a` about its parent's axis `seq[0]`, then by `b` about its
//!   own turned axis `seq[1]`, then by `c` about its own axis `seq[2]`, so
//!   `R = R_seq[0](a) R_seq[1](b) R_seq[2](c)` and
//!   `e = q(a) ⊗ q(b) ⊗ q(c)` with `q(t) = (cos t/2, sin t/2 axis)`.

use super::error::InputError;
use crate::runtime::nalgebra::{Matrix3, Vector3};
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};
use chaplygin_codegen::model::{FrameTurn, TurnedBy};

/// What a frame's assignment sets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum FrameSlot {
    /// `omega(F)` of the frame of this index.
    Omega(usize),
    /// `angles(F, seq)` of the frame of this index, the axes of `seq`.
    Angles(usize, [usize; 3]),
}

/// A model's declared frames: their names and how each turns.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frames<'a> {
    pub names: &'a [String],
    pub turns: &'a [FrameTurn],
}

/// The angular velocity asked of a frame, relative to its base in its own
/// axes.
#[derive(Clone, Debug, PartialEq)]
pub struct AngularVelocity {
    /// The flag and the name it was given with, for messages.
    pub given: (String, String),
    /// The frame's index.
    pub frame: usize,
    /// `omega`.
    pub omega: [f64; 3],
}

/// `name` read as `omega(F)` or `angles(F, seq)`; `None` for any other
/// name.
pub(super) fn frame_slot(
    flag: &str,
    name: &str,
    frames: Frames<'_>,
) -> Option<Result<FrameSlot, InputError>> {
    let refused = |reason: String| InputError::FrameState {
        flag: flag.to_string(),
        name: name.to_string(),
        reason,
    };
    if let Some(frame) = inside(name, "omega") {
        return Some(frame_index(flag, name, frame, frames).map(FrameSlot::Omega));
    }
    let (frame, sequence) = inside(name, "angles")?.split_once(',')?;
    let slot = frame_index(flag, name, frame, frames).and_then(|index| {
        let TurnedBy::EulerParameters(_) = frames.turns[index].by else {
            let reason = format!(
                "`{}` is not an `orient` frame: set its angles' coordinates themselves",
                frame.trim()
            );
            return Err(refused(reason));
        };
        let axes = sequence_axes(sequence.trim()).ok_or_else(|| {
            refused(format!(
                "`{}` is no sequence of three axes x, y, z with none twice in a row \
                 (e.g. zxz, zyx, xyz, zyz)",
                sequence.trim()
            ))
        })?;
        Ok(FrameSlot::Angles(index, axes))
    });
    Some(slot)
}

/// `TEXT` of `function(TEXT)`.
fn inside<'a>(name: &'a str, function: &str) -> Option<&'a str> {
    let rest = name.trim().strip_prefix(function)?.trim_start();
    rest.strip_prefix('(')?.strip_suffix(')')
}

/// The index of the frame named `frame`.
fn frame_index(
    flag: &str,
    name: &str,
    frame: &str,
    frames: Frames<'_>,
) -> Result<usize, InputError> {
    let frame = frame.trim();
    (frames.names.iter().position(|f| f == frame)).ok_or_else(|| InputError::UnknownFrame {
        flag: flag.to_string(),
        name: name.to_string(),
        frame: frame.to_string(),
        known: match frames.names.is_empty() {
            true => "none".to_string(),
            false => frames.names.join(", "),
        },
    })
}

/// The axes (0, 1, 2 for x, y, z) of a sequence such as `zxz`.
fn sequence_axes(sequence: &str) -> Option<[usize; 3]> {
    let axes: Vec<usize> = (sequence.chars())
        .map(|axis| "xyz".find(axis))
        .collect::<Option<_>>()?;
    let axes: [usize; 3] = axes.try_into().ok()?;
    (axes[0] != axes[1] && axes[1] != axes[2]).then_some(axes)
}

/// The three entries of `[a, b, c]`, split at the commas outside
/// parentheses.
pub(super) fn components(text: &str) -> Option<[&str; 3]> {
    let list = text.trim().strip_prefix('[')?.strip_suffix(']')?;
    let mut entries = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (at, character) in list.char_indices() {
        match character {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' if depth == 0 => {
                entries.push(list[start..at].trim());
                start = at + 1;
            }
            _ => {}
        }
    }
    entries.push(list[start..].trim());
    entries.try_into().ok()
}

/// The Euler parameters of the intrinsic angle sequence `axes`, `angles`.
pub(super) fn euler_parameters(axes: [usize; 3], angles: [f64; 3]) -> [f64; 4] {
    axes.iter()
        .zip(angles)
        .fold([1.0, 0.0, 0.0, 0.0], |e, (&axis, angle)| {
            let mut turn = [(angle / 2.0).cos(), 0.0, 0.0, 0.0];
            turn[1 + axis] = (angle / 2.0).sin();
            product(e, turn)
        })
}

/// The quaternion product `p ⊗ q`.
fn product(p: [f64; 4], q: [f64; 4]) -> [f64; 4] {
    [
        p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
        p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
        p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
        p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0],
    ]
}

/// Each `orient` frame none of whose Euler parameters is given starts
/// unturned: `e = (1, 0, 0, 0)`.
pub(super) fn unturned_where_unset(turns: &[FrameTurn], q: &mut [Option<f64>]) {
    for turn in turns {
        if let TurnedBy::EulerParameters(indices) = turn.by
            && indices.iter().all(|&i| q[i].is_none())
        {
            for (&i, value) in indices.iter().zip([1.0, 0.0, 0.0, 0.0]) {
                q[i] = Some(value);
            }
        }
    }
}

/// The velocities of the coordinates that turn the frame of `asked` from
/// its base with the angular velocity asked, at `q`: `(index, rate)` each.
///
/// # Errors
/// A `rotate` chain that does not read three coordinates, or whose rates
/// do not give every angular velocity at `q`.
pub(super) fn coordinate_rates(
    model: &InterpretedModel,
    q: &[f64],
    asked: &AngularVelocity,
) -> Result<Vec<(usize, f64)>, InputError> {
    let turns = model.turns();
    if let TurnedBy::EulerParameters(indices) = turns[asked.frame].by {
        let e = indices.map(|i| q[i]);
        let [wx, wy, wz] = asked.omega;
        let rates = product(e, [0.0, wx, wy, wz]).map(|entry| entry / 2.0);
        return Ok(indices.into_iter().zip(rates).collect());
    }
    let names = &model.names().frames;
    let refused = |reason: String| InputError::FrameState {
        flag: asked.given.0.clone(),
        name: asked.given.1.clone(),
        reason,
    };
    let (base, coordinates) = rotation_chain(names, turns, asked.frame);
    let base_name = base.map_or("ground", |b| names[b].as_str());
    let coordinate_names: Vec<&str> = (coordinates.iter())
        .map(|&i| model.names().coordinates[i].as_str())
        .collect();
    let [first, second, third] = coordinates[..] else {
        return Err(refused(format!(
            "the rotations from `{base_name}` to `{}` read {} coordinates ({}), and omega \
             sets the rates of three",
            names[asked.frame],
            coordinates.len(),
            coordinate_names.join(", ")
        )));
    };
    let jacobian = rate_jacobian(model, q, (base, asked.frame), [first, second, third]);
    let singular = jacobian.singular_values();
    let rates = (singular.min() > 1e-8 * singular.max())
        .then(|| jacobian.lu().solve(&Vector3::from(asked.omega)))
        .flatten();
    let rates = rates.ok_or_else(|| {
        refused(format!(
            "the rates of {} do not turn `{}` about every axis here (a singular orientation \
             of these angles): use an `orient` frame",
            coordinate_names.join(", "),
            names[asked.frame]
        ))
    })?;
    Ok(coordinates.into_iter().zip(rates.iter().copied()).collect())
}

/// The base of the `rotate` frame `frame` (`None` for `ground`) and the
/// coordinates the angles between read, each once.
fn rotation_chain(
    names: &[String],
    turns: &[FrameTurn],
    frame: usize,
) -> (Option<usize>, Vec<usize>) {
    let mut coordinates: Vec<usize> = Vec::new();
    let mut current = Some(frame);
    while let Some(index) = current {
        let TurnedBy::Angle(reads) = &turns[index].by else {
            break;
        };
        if reads.is_empty() {
            break;
        }
        for &read in reads {
            if !coordinates.contains(&read) {
                coordinates.push(read);
            }
        }
        current = names.iter().position(|n| *n == turns[index].parent);
        if current.is_none() {
            return (None, coordinates);
        }
    }
    (current, coordinates)
}

/// `J`: column `i` is `vee(R^T dR/dq_i)` of the rotation `R` from `base`
/// to `frame` (both indices of frames, `None` for `ground`).
fn rate_jacobian(
    model: &InterpretedModel,
    q: &[f64],
    (base, frame): (Option<usize>, usize),
    coordinates: [usize; 3],
) -> Matrix3<f64> {
    let relative = |q: &[f64]| {
        let orientations = evaluated(model.call("orientations", &[q]));
        let rotation =
            |index: usize| Matrix3::from_row_slice(&orientations[9 * index..9 * index + 9]);
        let base = base.map_or_else(Matrix3::identity, rotation);
        base.transpose() * rotation(frame)
    };
    let at = relative(q);
    let columns = coordinates.map(|i| {
        let step = 1e-5 * q[i].abs().max(1.0);
        let (mut ahead, mut behind) = (q.to_vec(), q.to_vec());
        ahead[i] += step;
        behind[i] -= step;
        let rate = (relative(&ahead) - relative(&behind)) / (2.0 * step);
        let turning = at.transpose() * rate;
        Vector3::new(
            (turning[(2, 1)] - turning[(1, 2)]) / 2.0,
            (turning[(0, 2)] - turning[(2, 0)]) / 2.0,
            (turning[(1, 0)] - turning[(0, 1)]) / 2.0,
        )
    });
    Matrix3::from_columns(&columns)
}
