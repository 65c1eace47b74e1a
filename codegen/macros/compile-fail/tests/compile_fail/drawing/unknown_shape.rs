// Rule: an item is one of box, sphere, disc, segment, trace (`cube`). Error at `cube`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        drawing: [
            sled = cube(center = [x, y, 0.05], size = [1, 0.3, 0.02]),
        ],
    }
}

fn main() {}
