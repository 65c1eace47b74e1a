//! What a model's `drawing:` section declares (docs/INTERFACE.md section
//! 10): named shapes placed by expressions of the configuration, and paths
//! traced on the ground.
//!
//! Each [`DrawnItem`] holds its values as `T`: expressions ([`ExprId`](crate::sym::ExprId)) in
//! the checked model, `()` where only the layout matters, numbers (`f64`)
//! once the interpreted `drawing(q)` has computed them at a configuration.
//! [`Figure::map`] rebuilds an item with other values in the one order
//! [`Figure::values`] lists them, the order `drawing(q)` writes them in.
//! Positions and directions are in ground axes; sizes depend on the
//! parameters only.

/// A disc's thickness over its radius where the model does not give it
/// (and for a mechanism's wheels), as `(numerator, denominator)`.
pub const DISC_THICKNESS: (i64, i64) = (1, 5);

/// A named entry of the drawing section.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnItem<T> {
    /// Its name, unique in the section: a declared body's replaces that
    /// body's automatic shape.
    pub name: String,
    /// What it draws.
    pub figure: Figure<T>,
}

/// A shape and where it is, or a path.
#[derive(Clone, Debug, PartialEq)]
pub enum Figure<T> {
    /// `box(center = P, size = [a, b, c], ...)`: edges `a`, `b`, `c` along
    /// its local x (its heading), y and z axes.
    Box {
        /// Its centre.
        center: [T; 3],
        /// Its local axes.
        orientation: Orientation<T>,
        /// Its edge lengths.
        size: [T; 3],
    },
    /// `sphere(center = P, radius = r, ...)`.
    Sphere {
        /// Its centre.
        center: [T; 3],
        /// Its local axes (the page marks its turning about local y).
        orientation: Orientation<T>,
        /// Its radius.
        radius: T,
    },
    /// `disc(center = P, radius = r, ...)`: its axle the local y axis.
    Disc {
        /// Its centre.
        center: [T; 3],
        /// Its local axes, or its axle alone.
        orientation: Orientation<T>,
        /// Its radius.
        radius: T,
        /// Its length along the axle (a fifth of the radius unless given).
        thickness: T,
    },
    /// `segment(A, B)`: a rod from `A` to `B`.
    Segment {
        /// Its first end.
        from: [T; 3],
        /// Its second end.
        to: [T; 3],
    },
    /// `trace(P)`: the path of a point, drawn up to the current time.
    Trace {
        /// The point.
        point: [T; 3],
    },
}

/// How a shape's local axes lie in ground axes.
#[derive(Clone, Debug, PartialEq)]
pub enum Orientation<T> {
    /// A rotation matrix, row-major: column `j` is the local unit vector
    /// `j` (from `frame = F`, `heading = angle`, or ground's axes).
    Axes([T; 9]),
    /// A disc's axle alone, not necessarily of unit length (`axle = v`):
    /// the disc's turning about it is not drawn.
    Axle([T; 3]),
}

impl<T> Orientation<T> {
    fn map<'a, U>(&'a self, f: &mut impl FnMut(&'a T) -> U) -> Orientation<U> {
        match self {
            Orientation::Axes(axes) => Orientation::Axes(axes.each_ref().map(f)),
            Orientation::Axle(axle) => Orientation::Axle(axle.each_ref().map(f)),
        }
    }
}

impl<T> Figure<T> {
    /// The keyword of the shape in the drawing section: `"box"`,
    /// `"sphere"`, `"disc"`, `"segment"` or `"trace"`.
    pub fn kind(&self) -> &'static str {
        match self {
            Figure::Box { .. } => "box",
            Figure::Sphere { .. } => "sphere",
            Figure::Disc { .. } => "disc",
            Figure::Segment { .. } => "segment",
            Figure::Trace { .. } => "trace",
        }
    }

    /// The same figure with each value `v` replaced by `f(v)`, called in the
    /// order of [`Figure::values`]: the centre (or the ends, or the point),
    /// the orientation, then the sizes.
    pub fn map<'a, U>(&'a self, mut f: impl FnMut(&'a T) -> U) -> Figure<U> {
        let mut point = |p: &'a [T; 3]| p.each_ref().map(&mut f);
        match self {
            Figure::Box {
                center,
                orientation,
                size,
            } => {
                let center = point(center);
                let orientation = orientation.map(&mut f);
                Figure::Box {
                    center,
                    orientation,
                    size: size.each_ref().map(&mut f),
                }
            }
            Figure::Sphere {
                center,
                orientation,
                radius,
            } => {
                let center = point(center);
                let orientation = orientation.map(&mut f);
                Figure::Sphere {
                    center,
                    orientation,
                    radius: f(radius),
                }
            }
            Figure::Disc {
                center,
                orientation,
                radius,
                thickness,
            } => {
                let center = point(center);
                let orientation = orientation.map(&mut f);
                let radius = f(radius);
                Figure::Disc {
                    center,
                    orientation,
                    radius,
                    thickness: f(thickness),
                }
            }
            Figure::Segment { from, to } => {
                let from = point(from);
                Figure::Segment {
                    from,
                    to: point(to),
                }
            }
            Figure::Trace { point: p } => Figure::Trace { point: point(p) },
        }
    }

    /// The values in order (what `drawing(q)` writes for this item).
    pub fn values(&self) -> Vec<&T> {
        let mut values = Vec::new();
        self.map(|value| values.push(value));
        values
    }
}
