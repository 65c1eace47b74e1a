// Rule: mass matrix not n x n (2 rows for n = 3 coordinates). Error at the mass matrix's outer list `[ ... ]` (starts at its `[`).
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        mass_matrix: [
            [m, 0, -m*a*sin(theta)],
            [0, m, m*a*cos(theta)],
        ],
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
