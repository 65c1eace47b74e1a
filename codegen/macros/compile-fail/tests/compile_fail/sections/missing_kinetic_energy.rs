// Rule: missing required sections (neither `kinetic_energy` nor `mass_matrix`). Error at the struct name `Sleigh`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
