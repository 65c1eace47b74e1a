// Rule: momentum-basis rows not spanning g(D): `spin = [0, 0, 1]` is in D, not in g(D) (A g^-1 h^T != 0 since a != 0; the right row is g (0, 0, 1)). Error at the row name `spin`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        momentum_basis: [
            forward = [cos(theta), sin(theta), 0],
            spin = [0, 0, 1],
        ],
    }
}

fn main() {}
