// Rule: an input column of B(q) has n entries (`[u = [b_1, ..., b_n]]`); `thrust` has 2, n = 3. Error at the list `[cos(theta), sin(theta)]`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        inputs: [thrust = [cos(theta), sin(theta)]],
    }
}

fn main() {}
