// Rule: missing required sections (`coordinates`). Error at the struct name `Sleigh`; x, y, theta must NOT also be reported as unknown names.
chaplygin_macros::model! {
    pub struct Sleigh {
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
