//! `chaplygin::model!` on a frame turned by Euler parameters: the
//! Chaplygin ball of `models/chaplygin_ball.model` compiles with the unit
//! constraint the tool adds, and its energy is the ball's, computed here
//! from the angular velocity `omega = 2 E(e) edot` in body axes
//! (docs/MATH.md section 5).

chaplygin::model! {
    /// The Chaplygin ball, as in `models/chaplygin_ball.model`.
    pub struct Ball {
        coordinates: [x, y, e0, e1, e2, e3],
        parameters: [m = 1.0, r = 0.5, a = 0.08, b = 0.1, c = 0.12, g = 9.81],
        frames: [ball = orient(ground, e0, e1, e2, e3)],
        points: [
            contact = origin + x*ground.x + y*ground.y,
            center = contact + r*ground.z,
        ],
        bodies: [shell = body(ball, center, m, diag(a, b, c))],
        gravity: -g*ground.z,
        no_slip: [rolling = no_slip(shell, contact, [ground.x, ground.y])],
    }
}

#[test]
fn the_ball_compiles_with_its_unit_constraint_and_its_energy() {
    let ball = Ball::default();
    assert_eq!(Ball::HOLONOMIC, ["ball_unit"]);
    let off_sphere = [0.0, 0.0, 0.5, 0.5, 0.5, 0.1];
    assert!((ball.holonomic_residual(&off_sphere)[0] - (0.76 - 1.0)).abs() < 1e-15);
    // e on the sphere, edot = 1/2 e ⊗ (0, omega) with omega = (1, -2, 0.5)
    let e = [0.5f64, 0.5, 0.5, 0.5];
    let omega = [1.0, -2.0, 0.5];
    let edot = [
        -0.5 * (e[1] * omega[0] + e[2] * omega[1] + e[3] * omega[2]),
        0.5 * (e[0] * omega[0] + e[2] * omega[2] - e[3] * omega[1]),
        0.5 * (e[0] * omega[1] + e[3] * omega[0] - e[1] * omega[2]),
        0.5 * (e[0] * omega[2] + e[1] * omega[1] - e[2] * omega[0]),
    ];
    let (xdot, ydot) = (0.3, -0.4);
    let q = [0.0, 0.0, e[0], e[1], e[2], e[3]];
    let qdot = [xdot, ydot, edot[0], edot[1], edot[2], edot[3]];
    let turning =
        0.5 * (0.08 * omega[0] * omega[0] + 0.1 * omega[1] * omega[1] + 0.12 * omega[2] * omega[2]);
    let expected = turning + 0.5 * (xdot * xdot + ydot * ydot) + 9.81 * 0.5;
    assert!((ball.energy(&q, &qdot) - expected).abs() < 1e-12);
}
