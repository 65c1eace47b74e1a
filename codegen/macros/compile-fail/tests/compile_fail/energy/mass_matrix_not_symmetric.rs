// Rule: mass matrix not symmetric (entry (1, 3) is `-m*a*sin(theta)`, entry (3, 1) is `m*a*sin(theta)`). Error at the `-` that starts entry (1, 3).
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        mass_matrix: [
            [m, 0, -m*a*sin(theta)],
            [0, m, m*a*cos(theta)],
            [m*a*sin(theta), m*a*cos(theta), inertia + m*a^2],
        ],
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
