// Rule: `dot()` of a non-coordinate (`dot(sin(theta))`: dot takes a coordinate's name, not an expression). Error at `sin` inside `dot(sin(theta))`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*dot(sin(theta)))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
