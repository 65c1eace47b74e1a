// Rule: mass matrix not positive definite (`dot(theta)` never appears, so g is singular: g_theta,theta = 0). Error at the section name `kinetic_energy`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2),
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
