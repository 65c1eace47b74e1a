//! What plans in the reduced and the momentum form share: the
//! transcription's exact derivatives against central differences on the
//! snakeboard.

use super::Form;
use crate::driver::plan::Request;
use crate::driver::plan::catalog_tests::built_in;
use crate::driver::plan::transcription::Transcription;
use crate::driver::plan::transcription::tests::assert_every_scheme_agrees;
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
        let made = |nlp: Transcription| nlp.in_form(form);
        let state = (
            form.state(&model),
            &made as &dyn Fn(Transcription) -> Transcription,
        );
        assert_every_scheme_agrees(&model, (names, costs), state, &format!("{form:?}"));
    }
}
