//! The N-link wheeled snake, a family of models of any size written out in
//! the model language.
//!
//! N identical links (length `l`, mass `m`, inertia `j` about the centre)
//! are joined end to end by revolute joints. The coordinates are the centre
//! `(x, y)` of link 1 and the absolute headings `theta1..thetaN` (n = N + 2).
//! Consecutive centres are a joint apart:
//!
//! ```text
//! c_1 = (x, y),   c_{i+1} = c_i + (l/2) (cos th_i + cos th_{i+1}, sin th_i + sin th_{i+1})
//! ```
//!
//! so their velocities are `v_1 = (xdot, ydot)` and
//! `v_{i+1} = v_i + (l/2) (-sin th_i thdot_i - sin th_{i+1} thdot_{i+1}, cos th_i thdot_i + cos th_{i+1} thdot_{i+1})`,
//! and `T = sum_i m/2 |v_i|^2 + j/2 thdot_i^2`, `V = 0`. Each centre
//! carries a wheel pair that cannot slip sideways: N constraints
//! `-sin(th_i) v_i,x + cos(th_i) v_i,y = 0`, leaving k = 2 degrees of freedom
//! in velocity. The inputs are the N - 1 joint torques: `tau_i` on joint `i`
//! acts as `-tau_i` on `theta_i` and `+tau_i` on `theta_{i+1}`.
//!
//! One link is the Chaplygin sleigh with its blade under the centre of mass.
//! The defaults are uniform rods: `m = 1`, `l = 0.6`, `j = m l^2 / 12 = 0.03`.
//! The constraint rows become dependent where the wheel axles meet in one
//! point (for three links: equal joint angles, the links on one circle);
//! the straight snake, where the model is checked, is regular.

/// The model text of the N-link wheeled snake with `links` links (the
/// module documentation states its mechanics); the struct is named
/// `Snake{links}`. With no links the kinetic energy is zero and the
/// compiler rejects the model (its kinetic energy is not quadratic in the velocities).
pub fn n_link_snake(links: usize) -> String {
    let coordinates: Vec<String> = ["x".to_string(), "y".to_string()]
        .into_iter()
        .chain((1..=links).map(|i| format!("theta{i}")))
        .collect();
    format!(
        "/// Wheeled snake of {links} links: link 1's centre (x, y), absolute headings.\n\
         pub struct Snake{links} {{\n\
         \x20   coordinates: [{}],\n\
         \x20   parameters: [m = 1.0, l = 0.6, j = 0.03],\n\
         \x20   define: [\n{}    ],\n\
         \x20   kinetic_energy: {},\n\
         \x20   potential_energy: 0,\n\
         \x20   constraints: [\n{}    ],\n\
         \x20   inputs: [\n{}    ],\n\
         }}\n",
        coordinates.join(", "),
        lines((1..=links).map(centre_velocity)),
        kinetic_energy(links),
        lines(
            (1..=links)
                .map(|i| { format!("wheel{i} = -sin(theta{i})*vx{i} + cos(theta{i})*vy{i}") })
        ),
        lines((1..links).map(|joint| joint_torque(joint, links))),
    )
}

/// One indented, comma-terminated line per item.
fn lines(items: impl Iterator<Item = String>) -> String {
    items.map(|item| format!("        {item},\n")).collect()
}

/// `vx{i}, vy{i}`: the velocity of link i's centre, from link i - 1's.
fn centre_velocity(i: usize) -> String {
    if i == 1 {
        return "vx1 = dot(x),\n        vy1 = dot(y)".to_string();
    }
    let (a, b, previous) = (format!("theta{}", i - 1), format!("theta{i}"), i - 1);
    format!(
        "vx{i} = vx{previous} - l/2*(sin({a})*dot({a}) + sin({b})*dot({b})),\n        \
         vy{i} = vy{previous} + l/2*(cos({a})*dot({a}) + cos({b})*dot({b}))"
    )
}

/// `sum_i m/2 (vx_i^2 + vy_i^2) + j/2 thdot_i^2`, or `0` without links.
fn kinetic_energy(links: usize) -> String {
    if links == 0 {
        return "0".to_string();
    }
    let translation: Vec<String> = (1..=links).map(|i| format!("vx{i}^2 + vy{i}^2")).collect();
    let rotation: Vec<String> = (1..=links).map(|i| format!("dot(theta{i})^2")).collect();
    format!(
        "m/2*({}) + j/2*({})",
        translation.join(" + "),
        rotation.join(" + ")
    )
}

/// `joint{joint} = [0, 0, ..., -1, 1, ...]`: the torque between links
/// `joint` and `joint + 1`, as a column of B.
fn joint_torque(joint: usize, links: usize) -> String {
    let column: Vec<&str> = (0..links + 2)
        .map(|row| {
            if row == joint + 1 {
                "-1"
            } else if row == joint + 2 {
                "1"
            } else {
                "0"
            }
        })
        .collect();
    format!("joint{joint} = [{}]", column.join(", "))
}
