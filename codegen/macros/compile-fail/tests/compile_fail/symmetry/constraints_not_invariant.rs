// Rule: the constraints not invariant under the declared group (a blade fixed in the world frame, `dot(y) = 0`, is not carried along by rotations). Error at `se2`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        constraints: [rail = dot(y)],
        symmetry: se2(x, y, theta),
    }
}

fn main() {}
