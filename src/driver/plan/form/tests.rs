//! What plans in the reduced and the momentum form share: the
//! transcription's exact derivatives against central differences on the
//! snakeboard.

use super::Form;
use crate::driver::plan::catalog_tests::built_in;
use crate::driver::plan::transcription::tests::{
    assert_derivatives_agree, assert_hessian_agrees, three_nodes,
};
use crate::driver::plan::{Request, Scheme};
use crate::driver::simulate::FormulationChoice;

/// `request` in the formulation `choice`.
pub(super) fn in_formulation(mut request: Request, choice: FormulationChoice) -> Request {
    request.formulation = choice;
    request
}

/// The snakeboard's plan in each form on 3 nodes at a point with every
/// variable nonzero, its running cost reading the time, coordinates,
/// velocities and inputs, its final cost the time and the velocities: the
/// exact Jacobian, gradient and Hessian of the Lagrangian, for every
/// scheme with a fixed and a free duration.
#[test]
fn the_derivatives_agree_with_central_differences_in_the_reduced_and_momentum_forms() {
    let names = (
        &["x", "y", "theta", "psi", "phi"][..],
        &["u_torso", "u_wheels"][..],
    );
    let costs = (
        "u_torso^2 + x*dot(theta)^2 + sin(phi)*u_wheels + t*dot(x) + dot(psi)*dot(y)",
        "x^2*dot(y) + t^2*dot(phi)",
    );
    let model = built_in("snakeboard").model;
    for form in [Form::Reduced, Form::Momentum] {
        let width = form.state(&model) + model.sizes().p;
        for (scheme, free_duration) in Scheme::ALL.iter().flat_map(|&s| [(s, false), (s, true)]) {
            let (nlp, z) = three_nodes(
                model.clone(),
                names,
                costs,
                (width, None),
                (scheme, free_duration),
            );
            let nlp = nlp.in_form(form);
            let label = format!("{form:?} {scheme:?} free {free_duration}");
            assert_derivatives_agree(&nlp, &z, &label);
            assert_hessian_agrees(&nlp, &z, &label);
        }
    }
}
