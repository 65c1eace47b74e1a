// Rule: a shape is oriented by a known frame (a model declared by its energy has `ground` alone). Error at `heading_frame`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        drawing: [
            sled = box(center = [x, y, 0.05], frame = heading_frame, size = [1, 0.3, 0.02]),
        ],
    }
}

fn main() {}
