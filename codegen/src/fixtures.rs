//! Model texts shared by the crate's tests.

/// The snakeboard of MATH.md 3.1, as INTERFACE.md section 1 declares it.
pub(crate) const SNAKEBOARD: &str = r#"
/// Snakeboard with J = Jt + m r^2 (Duindam & Stramigioli 2004).
pub struct Snakeboard {
    coordinates: [x, y, theta, psi, phi],
    parameters: [m = 1.0, r = 0.5, jt = 0.3, jw = 0.05],
    define: [j = jt + m*r^2],
    kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + j/2*dot(theta)^2
        + jt*dot(theta)*dot(psi) + jt/2*dot(psi)^2 + jw/2*dot(phi)^2,
    potential_energy: 0,
    constraints: [
        front = -sin(theta + phi)*dot(x) + cos(theta + phi)*dot(y) + r*cos(phi)*dot(theta),
        back  = -sin(theta - phi)*dot(x) + cos(theta - phi)*dot(y) - r*cos(phi)*dot(theta),
    ],
    inputs: [u_torso = psi, u_wheels = phi],
    momentum_basis: [
        group  = [cos(phi)*cos(theta), cos(phi)*sin(theta), r*sin(phi), 0, 0],
        torso  = [0, 0, 1, 1, 0],
        wheels = [0, 0, 0, 0, 1],
    ],
    symmetry: se2(x, y, theta),
}
"#;
