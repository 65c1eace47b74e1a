//! The command line runs a model of any size: the simulation loop and the
//! integrators take the state at the size it has at run time
//! (`chaplygin_runtime::state`), so a model read from text needs no size
//! compiled into the binary. A knife edge and 14 free carts on their own
//! rails (17 coordinates, one constraint) has 34 states in the
//! Lagrange-d'Alembert form and 33 in the reduced form; its motion is known
//! in closed form: at speed `v` and turning rate `w` from the origin the
//! blade runs on the circle `x = (v/w) sin(w t)`, `y = (v/w) (1 - cos(w t))`,
//! `theta = w t`, and each cart moves at its own constant speed. Both
//! forms run in this process, on the model loaded once ([`Model`]), as
//! `chaplygin simulate` runs them.

use crate::support::in_process::Model;
use crate::support::scratch;

const CARTS: usize = 14;
const SPEED: f64 = 1.0;
const TURN: f64 = 0.5;
const T_END: f64 = 1.0;

/// The model's text.
fn knife_and_carts() -> String {
    let carts: Vec<String> = (1..=CARTS).map(|i| format!("z{i}")).collect();
    let kinetic: Vec<String> = carts.iter().map(|z| format!("dot({z})^2")).collect();
    format!(
        "/// A knife edge and {CARTS} free carts on their own rails.\n\
         pub struct KnifeAndCarts {{\n\
             coordinates: [x, y, theta, {}],\n\
             parameters: [m = 1.0, inertia = 0.5],\n\
             kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + inertia/2*dot(theta)^2 + 1/2*({}),\n\
             constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],\n\
         }}\n",
        carts.join(", "),
        kinetic.join(" + ")
    )
}

/// Cart `i`'s speed.
fn cart_speed(i: usize) -> f64 {
    0.1 * i as f64
}

/// The final row of a run of `formulation` with RK4, by column name.
fn final_state(model: &Model, formulation: &str) -> (Vec<String>, Vec<f64>) {
    let initial: Vec<String> = [format!("dot(x)={SPEED}"), format!("dot(theta)={TURN}")]
        .into_iter()
        .chain((1..=CARTS).map(|i| format!("dot(z{i})={}", cart_speed(i))))
        .flat_map(|value| ["--initial".to_string(), value])
        .collect();
    let t_end = T_END.to_string();
    let mut options = vec![
        "--formulation",
        formulation,
        "--integrator",
        "rk4",
        "--t-end",
        &t_end,
        "--dt",
        "0.01",
    ];
    options.extend(initial.iter().map(String::as_str));
    let run = model.finished(&options);
    (run.header, run.rows.last().expect("rows").clone())
}

#[test]
fn a_model_of_more_than_32_states_runs_as_its_closed_form_says() {
    let radius = SPEED / TURN;
    let exact = [
        ("x", radius * (TURN * T_END).sin()),
        ("y", radius * (1.0 - (TURN * T_END).cos())),
        ("theta", TURN * T_END),
    ]
    .into_iter()
    .map(|(name, value)| (name.to_string(), value))
    .chain((1..=CARTS).map(|i| (format!("z{i}"), cart_speed(i) * T_END)))
    .collect::<Vec<_>>();
    let dir = scratch("sizes");
    let file = dir.path().join("knife_and_carts.model");
    std::fs::write(&file, knife_and_carts()).expect("the model file");
    let model = Model::load(file.to_str().expect("a UTF-8 path"), "jit");
    for (formulation, states) in [("lagrange", 2 * (CARTS + 3)), ("reduced", 2 * CARTS + 5)] {
        let (header, last) = final_state(model, formulation);
        let first_output = header
            .iter()
            .position(|name| name == "energy")
            .expect("an energy column");
        assert_eq!(first_output - 1, states, "{formulation}: {header:?}");
        for (name, value) in &exact {
            let column = header.iter().position(|h| h == name).expect("a column");
            let error = (last[column] - value).abs();
            assert!(error < 1e-9, "{formulation}: {name} off by {error:e}");
        }
    }
}
