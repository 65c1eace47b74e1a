// Rule: mass matrix not n x n (row 2 has 2 entries, n = 3). Error at the row `[0, m]`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        mass_matrix: [
            [m, 0, -m*a*sin(theta)],
            [0, m],
            [-m*a*sin(theta), m*a*cos(theta), inertia + m*a^2],
        ],
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
