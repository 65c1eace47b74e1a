//! A test model whose dense, coupled metric makes the run-time solve the
//! cheaper strategy for `acceleration`, so the numeric path is exercised in a
//! crate that depends only on `chaplygin`.

chaplygin::model! {
    /// The Chaplygin sleigh towing a point mass `mp` on a rod of length `l`
    /// hinged at the blade, at angle `alpha` to the body, held by a spring `k`;
    /// the input `steer` is a torque on the hinge.
    pub struct Towed {
        coordinates: [x, y, theta, alpha],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5, mp = 0.3, l = 0.7, k = 2.0],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2
            + mp/2*((dot(x) - l*sin(theta + alpha)*(dot(theta) + dot(alpha)))^2
            + (dot(y) + l*cos(theta + alpha)*(dot(theta) + dot(alpha)))^2),
        potential_energy: k/2*alpha^2,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        inputs: [steer = alpha],
    }
}
