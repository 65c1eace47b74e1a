//! Frames and points: orientations, angular velocities and positions.
//!
//! A frame `f = rotate(p, axis, angle)` is turned from its parent by
//! `angle` about the parent's `axis`: its rotation matrix in ground axes is
//! `R_f = R_p R_axis(angle)` with the elementary right-handed rotations
//!
//! ```text
//! R_x(a) = [[1, 0, 0], [0, c, -s], [0, s, c]]
//! R_y(a) = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
//! R_z(a) = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
//! ```
//!
//! and its angular velocity in ground axes `omega_f = omega_p + (d angle/dt) R_p e_axis`
//! (angular velocities of a chain of rotations add; e.g. Greenwood,
//! *Advanced Dynamics*, 2003, section 2.3). The columns of `R_f` are the unit
//! vectors `f.x`, `f.y`, `f.z`. `ground` has `R = I`, `omega = 0`; `origin`
//! is at zero.
//!
//! A frame `f = orient(p, e0, e1, e2, e3)` is turned by the Euler parameters
//! `e` (the quaternion `e0 + e1 i + e2 j + e3 k`): `R_f = R_p R(e)` with
//!
//! ```text
//! R(e) = [[e0²+e1²-e2²-e3², 2(e1e2-e0e3),    2(e1e3+e0e2)],
//!         [2(e1e2+e0e3),    e0²-e1²+e2²-e3², 2(e2e3-e0e1)],
//!         [2(e1e3-e0e2),    2(e2e3+e0e1),    e0²-e1²-e2²+e3²]]  = G(e) E(e)^T
//! E(e) = [[-e1, e0, e3, -e2], [-e2, -e3, e0, e1], [-e3, e2, -e1, e0]]
//! G(e) = [[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]]
//! ```
//!
//! and the angular velocity relative to `p` is `2 G(e) edot` in `p`'s axes
//! and `2 E(e) edot` in `f`'s own (Nikravesh, *Computer-Aided Analysis of
//! Mechanical Systems*, 1988, sections 6.3-6.4). On the unit sphere
//! `|e| = 1` these equal the skew parts of `Rdot R^T` and `R^T Rdot`; off
//! it `R(e)` is `|e|^2` times a rotation, and the rates stay the linear forms
//! above. `E e = G e = 0`, so they ignore the rate along `e` whatever its
//! size: the tool keeps `|e| = 1`, and the equations of motion on it only
//! read the energies and rows there (docs/MATH.md section 5). The frame's
//! own-axes rate is kept as `2 E(e) edot` (plus the parent's turned by
//! `R(e)^T`) instead of `R_f^T omega_f`, which is the same on the sphere at a
//! third of the polynomial degree.

use super::vector::{self, Vector};
use crate::sym::{Context, ExprId, Function, Rational, SymError, SymbolId};

/// A frame's orientation and angular velocity, both in ground axes.
#[derive(Clone, Debug)]
pub(in crate::model) struct FrameState {
    /// `R`, row-major: column `j` is the frame's unit vector `j`.
    pub(in crate::model) rotation: [ExprId; 9],
    /// `omega`.
    pub(in crate::model) angular_velocity: Vector,
    /// `omega` in the frame's own axes where it is kept as derived (an
    /// `orient` frame's); `None` for `R^T omega`.
    pub(in crate::model) own_angular_velocity: Option<Vector>,
}

impl FrameState {
    /// The unit vector along axis `axis` (0, 1, 2 for x, y, z).
    pub(in crate::model) fn axis(&self, axis: usize) -> Vector {
        [0, 1, 2].map(|row| self.rotation[3 * row + axis])
    }

    /// `R^T a`: a ground-axes vector in this frame's axes.
    pub(in crate::model) fn to_frame_axes(&self, cx: &mut Context, a: &Vector) -> Vector {
        [0, 1, 2].map(|axis| {
            let column = self.axis(axis);
            vector::inner(cx, &column, a)
        })
    }

    /// `omega` in the frame's own axes.
    pub(in crate::model) fn own_axes_angular_velocity(&self, cx: &mut Context) -> Vector {
        match self.own_angular_velocity {
            Some(own) => own,
            None => self.to_frame_axes(cx, &self.angular_velocity),
        }
    }
}

/// The frames and points declared so far, `ground` and `origin` first.
#[derive(Debug)]
pub(in crate::model) struct Space {
    frames: Vec<(String, FrameState)>,
    points: Vec<(String, Vector)>,
    /// Frames, points and bodies whose declarations failed: their uses are
    /// not reported again.
    broken: Vec<String>,
}

/// The name of the inertial frame.
pub(in crate::model) const GROUND: &str = "ground";
/// The name of the inertial frame's origin.
pub(in crate::model) const ORIGIN: &str = "origin";

impl Space {
    /// `ground` and `origin` alone.
    pub(in crate::model) fn new(cx: &mut Context) -> Space {
        let (zero, one) = (cx.integer(0), cx.integer(1));
        let rotation = [one, zero, zero, zero, one, zero, zero, zero, one];
        let ground = FrameState {
            rotation,
            angular_velocity: vector::zero(cx),
            own_angular_velocity: None,
        };
        Space {
            frames: vec![(GROUND.to_string(), ground)],
            points: vec![(ORIGIN.to_string(), vector::zero(cx))],
            broken: Vec::new(),
        }
    }

    /// A frame by name.
    pub(in crate::model) fn frame(&self, name: &str) -> Option<&FrameState> {
        self.frames.iter().find(|(n, _)| n == name).map(|(_, f)| f)
    }

    /// A point's position by name.
    pub(in crate::model) fn point(&self, name: &str) -> Option<&Vector> {
        self.points.iter().find(|(n, _)| n == name).map(|(_, p)| p)
    }

    /// Records a frame.
    pub(in crate::model) fn add_frame(&mut self, name: &str, frame: FrameState) {
        self.frames.push((name.to_string(), frame));
    }

    /// Records a point.
    pub(in crate::model) fn add_point(&mut self, name: &str, position: Vector) {
        self.points.push((name.to_string(), position));
    }

    /// Records a declaration that failed.
    pub(in crate::model) fn mark_broken(&mut self, name: &str) {
        self.broken.push(name.to_string());
    }

    /// True when `name` was declared but its declaration failed.
    pub(in crate::model) fn is_broken(&self, name: &str) -> bool {
        self.broken.iter().any(|b| b == name)
    }

    /// The declared frames (without `ground`), in resolution order.
    pub(in crate::model) fn declared_frames(&self) -> &[(String, FrameState)] {
        &self.frames[1..]
    }

    /// The declared points (without `origin`), in order.
    pub(in crate::model) fn declared_points(&self) -> &[(String, Vector)] {
        &self.points[1..]
    }
}

/// The frame turned from `parent` by `angle` about the parent's `axis`.
pub(in crate::model) fn rotated(
    cx: &mut Context,
    parent: &FrameState,
    axis: usize,
    angle: ExprId,
    coordinates: &[SymbolId],
) -> Result<FrameState, SymError> {
    let elementary = elementary_rotation(cx, axis, angle)?;
    let rotation = product(cx, &parent.rotation, &elementary);
    let rate = time_derivative(cx, angle, coordinates)?;
    let turn = vector::scale(cx, rate, &parent.axis(axis));
    Ok(FrameState {
        rotation,
        angular_velocity: vector::add(cx, &parent.angular_velocity, &turn),
        own_angular_velocity: None,
    })
}

/// The frame turned from `parent` by the Euler parameters `e` (see the
/// module documentation).
pub(in crate::model) fn oriented(
    cx: &mut Context,
    parent: &FrameState,
    e: [SymbolId; 4],
) -> FrameState {
    let e_values = e.map(|entry| cx.symbol(entry));
    let rates = e.map(|entry| {
        let velocity = cx.velocity_of(entry);
        cx.symbol(velocity)
    });
    let relative = euler_parameter_rotation(cx, &e_values);
    let [e0, e1, e2, e3] = e_values;
    let [m1, m2, m3] = [e1, e2, e3].map(|entry| cx.neg(entry));
    let in_parent_axes = twice_rows(
        cx,
        [[m1, e0, m3, e2], [m2, e3, e0, m1], [m3, m2, e1, e0]],
        &rates,
    );
    let in_own_axes = twice_rows(
        cx,
        [[m1, e0, e3, m2], [m2, m3, e0, e1], [m3, e2, m1, e0]],
        &rates,
    );
    let turn = times_vector(cx, &parent.rotation, &in_parent_axes);
    let parent_own = parent.own_axes_angular_velocity(cx);
    let carried = transpose_times_vector(cx, &relative, &parent_own);
    FrameState {
        rotation: product(cx, &parent.rotation, &relative),
        angular_velocity: vector::add(cx, &parent.angular_velocity, &turn),
        own_angular_velocity: Some(vector::add(cx, &carried, &in_own_axes)),
    }
}

/// `R(e)`, row-major (see the module documentation).
fn euler_parameter_rotation(cx: &mut Context, e: &[ExprId; 4]) -> [ExprId; 9] {
    let two = cx.integer(2);
    let square = |cx: &mut Context, i: usize| cx.mul2(e[i], e[i]);
    let squares: [ExprId; 4] = std::array::from_fn(|i| square(cx, i));
    let diagonal = |cx: &mut Context, plus: usize| {
        let signed: Vec<ExprId> = (1..4)
            .map(|i| match i == plus {
                true => squares[i],
                false => cx.neg(squares[i]),
            })
            .collect();
        let rest = cx.add(&signed);
        cx.add2(squares[0], rest)
    };
    let twice = |cx: &mut Context, (a, b): (usize, usize), (c, d): (usize, usize), sign: i64| {
        let first = cx.mul2(e[a], e[b]);
        let second = cx.mul2(e[c], e[d]);
        let second = match sign {
            1 => second,
            _ => cx.neg(second),
        };
        let sum = cx.add2(first, second);
        cx.mul2(two, sum)
    };
    [
        diagonal(cx, 1),
        twice(cx, (1, 2), (0, 3), -1),
        twice(cx, (1, 3), (0, 2), 1),
        twice(cx, (1, 2), (0, 3), 1),
        diagonal(cx, 2),
        twice(cx, (2, 3), (0, 1), -1),
        twice(cx, (1, 3), (0, 2), -1),
        twice(cx, (2, 3), (0, 1), 1),
        diagonal(cx, 3),
    ]
}

/// `2 M edot` of the 3 x 4 matrix `M` given by rows.
fn twice_rows(cx: &mut Context, rows: [[ExprId; 4]; 3], rates: &[ExprId; 4]) -> Vector {
    let two = cx.integer(2);
    rows.map(|row| {
        let products: Vec<ExprId> = row
            .iter()
            .zip(rates)
            .map(|(&m, &r)| cx.mul2(m, r))
            .collect();
        let sum = cx.add(&products);
        cx.mul2(two, sum)
    })
}

/// The product `a b` of two 3 x 3 matrices, row-major.
fn product(cx: &mut Context, a: &[ExprId; 9], b: &[ExprId; 9]) -> [ExprId; 9] {
    std::array::from_fn(|entry| {
        let (row, column) = (entry / 3, entry % 3);
        let products: Vec<ExprId> = (0..3)
            .map(|k| cx.mul2(a[3 * row + k], b[3 * k + column]))
            .collect();
        cx.add(&products)
    })
}

/// `m v` of a 3 x 3 matrix, row-major.
fn times_vector(cx: &mut Context, m: &[ExprId; 9], v: &Vector) -> Vector {
    [0, 1, 2].map(|row| {
        let entries = [0, 1, 2].map(|k| m[3 * row + k]);
        vector::inner(cx, &entries, v)
    })
}

/// `m^T v` of a 3 x 3 matrix, row-major.
fn transpose_times_vector(cx: &mut Context, m: &[ExprId; 9], v: &Vector) -> Vector {
    [0, 1, 2].map(|column| {
        let entries = [0, 1, 2].map(|k| m[3 * k + column]);
        vector::inner(cx, &entries, v)
    })
}

/// `R_axis(angle)`, row-major.
fn elementary_rotation(
    cx: &mut Context,
    axis: usize,
    angle: ExprId,
) -> Result<[ExprId; 9], SymError> {
    let (zero, one) = (cx.integer(0), cx.integer(1));
    let c = cx.apply(Function::Cos, angle)?;
    let s = cx.apply(Function::Sin, angle)?;
    let minus_s = cx.neg(s);
    Ok(match axis {
        0 => [one, zero, zero, zero, c, minus_s, zero, s, c],
        1 => [c, zero, s, zero, one, zero, minus_s, zero, c],
        _ => [c, minus_s, zero, s, c, zero, zero, zero, one],
    })
}

/// `d e / dt = sum_i (d e / d q_i) qdot_i` of an expression of the
/// configuration, differentiated on its DAG: the partials share the
/// expression's own sub-expressions instead of expanding them.
pub(in crate::model) fn time_derivative(
    cx: &mut Context,
    expression: ExprId,
    coordinates: &[SymbolId],
) -> Result<ExprId, SymError> {
    let zero = cx.integer(0);
    let mut terms = Vec::with_capacity(coordinates.len());
    for &coordinate in coordinates {
        let partial = cx.derivative(expression, coordinate);
        if partial == zero {
            continue;
        }
        let velocity = cx.velocity_of(coordinate);
        let velocity = cx.symbol(velocity);
        terms.push(cx.mul2(partial, velocity));
    }
    Ok(cx.add(&terms))
}

/// The velocity `d p / dt` of a position.
pub(in crate::model) fn velocity(
    cx: &mut Context,
    position: &Vector,
    coordinates: &[SymbolId],
) -> Result<Vector, SymError> {
    let mut components = *position;
    for component in &mut components {
        *component = time_derivative(cx, *component, coordinates)?;
    }
    Ok(components)
}

/// One half, for the energies.
pub(in crate::model) fn half(cx: &mut Context) -> ExprId {
    cx.number(Rational::HALF)
}
