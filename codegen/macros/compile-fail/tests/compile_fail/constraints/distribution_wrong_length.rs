// Rule: a distribution vector has n entries (`[name = [v_1, ..., v_n]]`); `spin` has 2, n = 3. Error at the list `[0, 1]`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        distribution: [
            forward = [cos(theta), sin(theta), 0],
            spin = [0, 1],
        ],
    }
}

fn main() {}
