// Rule: exactly one of `kinetic_energy` and `mass_matrix` (both given, and they agree). Error at the section name `mass_matrix` (the second one written).
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        mass_matrix: [
            [m, 0, -m*a*sin(theta)],
            [0, m, m*a*cos(theta)],
            [-m*a*sin(theta), m*a*cos(theta), inertia + m*a^2],
        ],
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
