// Rule: name declared twice / coordinate used as a parameter (`theta` is a coordinate and is declared again as a parameter). Error at `theta` in `theta = 0.0` (the parameters list).
chaplygin_macros::model! {
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5, theta = 0.0],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: 0,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    }
}

fn main() {}
