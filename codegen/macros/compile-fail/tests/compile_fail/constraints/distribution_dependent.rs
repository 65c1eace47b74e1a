// Rule: distribution vectors dependent (`backward` = -1 x `forward`). Error at the vector name `backward`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        distribution: [
            forward = [cos(theta), sin(theta), 0],
            backward = [-cos(theta), -sin(theta), 0],
        ],
    }
}

fn main() {}
