//! Model texts shared by the crate's tests.

/// The snakeboard of MATH.md 3.1, as docs/INTERFACE.md section 1 declares it.
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

/// The wheeled chain of `links` links (the models crate's `n_link_snake`).
pub(crate) fn chain_of_links(links: usize) -> String {
    let coordinates: Vec<String> = ["x".to_string(), "y".to_string()]
        .into_iter()
        .chain((1..=links).map(|i| format!("theta{i}")))
        .collect();
    let mut velocities = vec!["vx1 = dot(x)".to_string(), "vy1 = dot(y)".to_string()];
    for i in 2..=links {
        let (a, b) = (format!("theta{}", i - 1), format!("theta{i}"));
        velocities.push(format!(
            "vx{i} = vx{} - l/2*(sin({a})*dot({a}) + sin({b})*dot({b}))",
            i - 1
        ));
        velocities.push(format!(
            "vy{i} = vy{} + l/2*(cos({a})*dot({a}) + cos({b})*dot({b}))",
            i - 1
        ));
    }
    let energy: Vec<String> = (1..=links)
        .map(|i| format!("m/2*(vx{i}^2 + vy{i}^2) + j/2*dot(theta{i})^2"))
        .collect();
    let constraints: Vec<String> = (1..=links)
        .map(|i| format!("wheel{i} = -sin(theta{i})*vx{i} + cos(theta{i})*vy{i}"))
        .collect();
    format!(
        "pub struct Chain {{
            coordinates: [{}],
            parameters: [m = 1.0, l = 0.6, j = 0.03],
            define: [{}],
            kinetic_energy: {},
            constraints: [{}],
        }}",
        coordinates.join(", "),
        velocities.join(", "),
        energy.join(" + "),
        constraints.join(", ")
    )
}
