// Rule: `#[deny_holonomic]` forbids integrable constraints: `blade` is (1 + y^2) d(x - a theta). Error at the first constraint's name `blade`.
chaplygin_macros::model! {
    #[deny_holonomic]
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = (1 + y^2)*(dot(x) - a*dot(theta))],
    }
}

fn main() {}
