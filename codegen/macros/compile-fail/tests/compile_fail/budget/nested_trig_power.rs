// Rule: derivation budget (a normal form needing more polynomial term products than the limit): `(1e300*sin(x + y) + cos(x - y))^64` expands past it (a 997-bit coefficient weighs each term product). Error at `m`, the first token of the kinetic energy.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2
            + (1e300*sin(x + y) + cos(x - y))^64*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
