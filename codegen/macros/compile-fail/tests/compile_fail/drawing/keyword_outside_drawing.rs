// Rule: keyword arguments belong to the drawing section's shapes (`sin(angle = theta)` in a constraint). Error at `angle`.
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(angle = theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
