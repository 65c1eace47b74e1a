//! A model whose constraint is integrable only with an integrating factor
//! compiles, and its REPORT says it is holonomic (Frobenius), while Moore's
//! exactness test alone would call the row nonholonomic.

chaplygin::model! {
    /// A point in space kept on the surface `x y + z = const`, written with
    /// the integrating factor `1 + x^2`.
    pub struct Surface {
        coordinates: [x, y, z],
        parameters: [m = 1.0],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2),
        constraints: [level = (1 + x^2)*(y*dot(x) + x*dot(y) + dot(z))],
    }
}

#[test]
fn an_integrable_constraint_compiles_and_is_reported_holonomic() {
    let report = Surface::REPORT;
    assert!(report.contains("classification: holonomic"), "{report}");
    assert!(report.contains("growth vector (2)"), "{report}");
    assert!(report.contains("level not exact"), "{report}");
    // a velocity tangent to the surface (d(x y + z) = 0) satisfies the constraint
    let surface = Surface::default();
    let q = [0.3, -0.4, 0.2];
    let qdot = [0.5, 0.1, -(-0.4 * 0.5 + 0.3 * 0.1)];
    assert!(surface.constraint_residual(&q, &qdot)[0].abs() < 1e-15);
}
