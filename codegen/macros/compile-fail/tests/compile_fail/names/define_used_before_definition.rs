// Rule: defined names are "usable after their definition"; `j` uses `arm2`, defined after it. Error at `arm2` inside the definition of `j`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        define: [j = inertia + m*arm2, arm2 = a^2],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2)
            + m*a*(cos(theta)*dot(y) - sin(theta)*dot(x))*dot(theta) + j/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
