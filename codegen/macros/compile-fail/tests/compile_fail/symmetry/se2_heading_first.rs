// Rule: the Lagrangian/constraints not invariant under the declared group, an se2 factor with its coordinates out of order (`se2(theta, x, y)`): the message names the order under which they are, `se2(x, y, theta)`. Error at `se2`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        symmetry: se2(theta, x, y),
    }
}

fn main() {}
