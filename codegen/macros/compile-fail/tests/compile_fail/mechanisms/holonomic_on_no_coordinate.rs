// Rule: a holonomic constraint that reads no coordinate (`fixed = l - 1`, on a parameter alone): its row df/dq is zero and constrains nothing. Error at its name `fixed`.
chaplygin_macros::model! {
    pub struct Bead {
        coordinates: [x, y],
        parameters: [m = 1.0, l = 1.0],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2),
        holonomic: [fixed = l - 1],
    }
}

fn main() {}
