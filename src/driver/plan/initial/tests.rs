//! The first node's rows against central differences: their values,
//! Jacobian and Hessians, in a plan's Lagrangian.

use super::{Held, declared};
use crate::driver::plan::Scheme;
use crate::driver::plan::form::Form;
use crate::driver::plan::nlp::Nlp;
use crate::driver::plan::transcription::Transcription;
use crate::driver::plan::transcription::tests::{assert_every_scheme_agrees, three_nodes};
use chaplygin_codegen::interpret::InterpretedModel;

/// A knife edge held to a trough that tilts with its heading: a
/// configuration constraint beside a velocity constraint, both reading
/// every coordinate.
const BLADE_IN_TROUGH: &str = "pub struct BladeInTrough {
    coordinates: [x, y, theta],
    parameters: [m = 1.0, j = 0.5, a = 0.3],
    kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + j/2*dot(theta)^2,
    holonomic: [trough = y - a*x^2 - a*sin(theta)],
    constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    inputs: [push = x, turn = theta],
}";

/// The blade's plan on 3 nodes at a point with every variable nonzero,
/// holding the start to both constraints in the Lagrange form and to the
/// configuration constraint in the reduced one: the exact Jacobian,
/// gradient and Hessian of the Lagrangian agree with central
/// differences, for every scheme with a fixed and a free duration. The
/// rows are named in messages by their family and declared name.
#[test]
fn the_start_rows_derivatives_agree_with_central_differences() {
    let model = InterpretedModel::from_source(BLADE_IN_TROUGH).expect("the model derives");
    assert_eq!(declared(&model), [Held::Configuration, Held::Velocity]);
    let names = (&["x", "y", "theta"][..], &["push", "turn"][..]);
    let costs = ("push^2 + x*dot(theta)^2 + t*turn", "x^2*dot(y) + t*theta");
    let (nlp, z) = three_nodes(
        model.clone(),
        names,
        costs,
        (2 * 3 + 2, None),
        (Scheme::Midpoint, false),
    );
    let nlp = nlp.holding_start(declared(&model));
    let described: Vec<String> = (12..15).map(|row| nlp.describe_row(&z, row)).collect();
    assert_eq!(
        described,
        [
            "the start's configuration constraint `trough`",
            "the start's velocity constraint `blade`",
            "the start's velocity constraint `trough`",
        ]
    );
    let forms = [
        (Form::Lagrange, declared(&model)),
        (Form::Reduced, vec![Held::Configuration]),
    ];
    for (form, held) in forms {
        let made = |nlp: Transcription| nlp.in_form(form).holding_start(held.clone());
        let state = (
            form.state(&model),
            &made as &dyn Fn(Transcription) -> Transcription,
        );
        assert_every_scheme_agrees(&model, (names, costs), state, &format!("{form:?}"));
    }
}
