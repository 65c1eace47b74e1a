// Rule: the momentum equation needs free shape velocities (D + T(orbit) = TQ); `brake` constrains the shape velocity `dot(psi)` on its own. Error at `se2`.
chaplygin_macros::model! {
    pub struct BrakedSleigh {
        coordinates: [x, y, theta, psi],
        parameters: [m = 1.0, inertia = 0.1, j = 0.01],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + inertia/2*dot(theta)^2 + j/2*dot(psi)^2,
        constraints: [
            blade = -sin(theta)*dot(x) + cos(theta)*dot(y),
            brake = dot(psi),
        ],
        symmetry: se2(x, y, theta),
    }
}

fn main() {}
