// Rule: mass matrix not positive definite at the default parameters (parallel-axis sign error: `inertia - m*a^2`, so inertia - 2 m a^2 = -0.4 < 0). Error at the section name `mass_matrix`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        mass_matrix: [
            [m, 0, -m*a*sin(theta)],
            [0, m, m*a*cos(theta)],
            [-m*a*sin(theta), m*a*cos(theta), inertia - m*a^2],
        ],
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
