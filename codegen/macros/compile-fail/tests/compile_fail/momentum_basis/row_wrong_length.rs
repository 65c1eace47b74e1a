// Rule: a momentum-basis row has n entries (`[name = [h_1, ..., h_n]]`); `forward` has 2, n = 3. Error at the list `[cos(theta), sin(theta)]`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        momentum_basis: [
            forward = [cos(theta), sin(theta)],
            spin = [-m*a*sin(theta), m*a*cos(theta), inertia + m*a^2],
        ],
    }
}

fn main() {}
