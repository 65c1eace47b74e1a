// Rule: momentum-basis rows dependent (`forward_again` = m x `forward`; both lie in g(D)). Error at the row name `forward_again`.
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
            forward_again = [m*cos(theta), m*sin(theta), 0],
        ],
    }
}

fn main() {}
