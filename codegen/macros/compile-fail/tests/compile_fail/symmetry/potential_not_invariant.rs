// Rule: the Lagrangian not invariant under the declared group (sleigh on an incline: V depends on x and theta, so SE(2) is not a symmetry; `translation(y)` would be). Error at `se2`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5, slope = 0.1],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: m*9.81*sin(slope)*(x + a*cos(theta)),
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        symmetry: se2(x, y, theta),
    }
}

fn main() {}
