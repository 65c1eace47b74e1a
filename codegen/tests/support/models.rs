//! Model texts for the tests and fuzz targets: the built-in models, read from
//! the `models` crate's sources, and an N-link snake generated for any N.

/// The `models` crate's sources that declare models with `chaplygin::model!`.
const MACRO_MODELS: &str = include_str!("../../../models/src/lib.rs");

/// The Chaplygin sleigh of the `models` crate's build script.
pub const SLEIGH: &str = include_str!("../../../models/sleigh.model");

/// Every built-in model as `(name, text)`: the bodies of the `chaplygin::model!`
/// invocations of the `models` crate (snakeboard, rolling disk, differential
/// drive) and the sleigh's `.model` file.
pub fn built_in() -> Vec<(String, String)> {
    let mut models: Vec<(String, String)> = macro_bodies(MACRO_MODELS)
        .into_iter()
        .map(|body| (struct_name(&body), body))
        .collect();
    models.push(("Sleigh".to_string(), SLEIGH.to_string()));
    models
}

/// The text between the braces of every `chaplygin::model! { ... }`.
fn macro_bodies(source: &str) -> Vec<String> {
    const OPENING: &str = "chaplygin::model! {";
    let mut bodies = Vec::new();
    let mut rest = source;
    while let Some(start) = rest.find(OPENING) {
        let body = &rest[start + OPENING.len()..];
        let mut depth = 1usize;
        let end = body
            .char_indices()
            .find(|&(_, c)| {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    _ => {}
                }
                depth == 0
            })
            .map_or(body.len(), |(at, _)| at);
        bodies.push(body[..end].to_string());
        rest = &body[end..];
    }
    bodies
}

/// The identifier after `struct` in a model text.
fn struct_name(body: &str) -> String {
    body.split("struct ")
        .nth(1)
        .and_then(|after| after.split_whitespace().next())
        .unwrap_or("Model")
        .to_string()
}

/// An N-link snake: links of length `l` with headings `theta_1 .. theta_N`,
/// the head link's wheel axle midpoint at `(x, y)`, each link's midpoint
/// trailing the previous one by `l` along its heading:
/// `p_i = (x, y) - l * sum_{j<i} (cos theta_j, sin theta_j)`. Each link's
/// wheels do not slip sideways, `-sin(theta_i) xdot_i + cos(theta_i) ydot_i = 0`,
/// and `T = sum_i m/2 |pdot_i|^2 + jl/2 thetadot_i^2`. `n + 2` coordinates,
/// `n` constraints, joint torques on the headings `theta_2 .. theta_N`.
pub fn snake(links: usize) -> String {
    let headings: Vec<String> = (1..=links).map(|i| format!("theta_{i}")).collect();
    let velocity_x = |i: usize| trailing_sum("dot(x)", &headings[..i], "+", "sin");
    let velocity_y = |i: usize| trailing_sum("dot(y)", &headings[..i], "-", "cos");
    let kinetic_energy: Vec<String> = (0..links)
        .map(|i| {
            format!(
                "m/2*(({})^2 + ({})^2) + jl/2*dot({})^2",
                velocity_x(i),
                velocity_y(i),
                headings[i]
            )
        })
        .collect();
    let constraints: Vec<String> = (0..links)
        .map(|i| {
            let heading = &headings[i];
            format!(
                "wheel_{} = -sin({heading})*({}) + cos({heading})*({})",
                i + 1,
                velocity_x(i),
                velocity_y(i)
            )
        })
        .collect();
    let inputs: Vec<String> = headings[1..]
        .iter()
        .map(|heading| format!("u_{heading} = {heading}"))
        .collect();
    format!(
        "pub struct Snake{links} {{\n    coordinates: [x, y, {}],\n    \
         parameters: [m = 1.0, jl = 0.1, l = 0.3],\n    kinetic_energy: {},\n    \
         potential_energy: 0,\n    constraints: [{}],\n    inputs: [{}],\n}}\n",
        headings.join(", "),
        kinetic_energy.join("\n        + "),
        constraints.join(",\n        "),
        inputs.join(", ")
    )
}

/// `start sign l*f(h_1)*dot(h_1) sign ...`: one velocity component of a
/// link's midpoint (`sign` is `+` for x, where `d/dt(-l cos h) = l sin h hdot`).
fn trailing_sum(start: &str, headings: &[String], sign: &str, function: &str) -> String {
    headings.iter().fold(start.to_string(), |sum, heading| {
        format!("{sum} {sign} l*{function}({heading})*dot({heading})")
    })
}
