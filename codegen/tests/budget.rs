//! The derivation budget: the built-in models fit in the default budget with
//! room to spare, the budget never changes what a model compiles to, and a
//! model whose normal form explodes is rejected with one diagnostic stating
//! the budget.

use chaplygin_codegen::sym::{Budget, DEFAULT_DERIVATION_BUDGET};
use chaplygin_codegen::{generate, generate_within};

/// The sleigh with an extra kinetic-energy term whose normal form expands
/// `(sin(x + y) + cos(x - y))^64` (line 15 of the text).
fn exploding_sleigh() -> String {
    crate::support::models::SLEIGH.replace(
        "inertia/2*dot(theta)^2",
        "inertia/2*dot(theta)^2\n        + (sin(x + y) + cos(x - y))^64*dot(theta)^2",
    )
}

#[test]
fn built_in_models_use_under_one_percent_of_the_default_budget() {
    for (name, text) in crate::support::models::built_in() {
        let budget = Budget::default();
        let generated = generate_within(&text, budget.clone());
        assert!(generated.is_ok(), "{name} rejected");
        assert!(budget.used() > 0, "{name} charged nothing");
        assert!(
            budget.used() < DEFAULT_DERIVATION_BUDGET / 100,
            "{name} used {} of {DEFAULT_DERIVATION_BUDGET}",
            budget.used()
        );
    }
}

#[test]
fn a_sufficient_budget_does_not_change_the_generated_code() {
    let (_, snakeboard) = &crate::support::models::built_in()[0];
    let within_default = generate(snakeboard).ok();
    let within_large = generate_within(snakeboard, Budget::new(u64::MAX / 2)).ok();
    assert!(within_default.is_some());
    assert_eq!(within_default, within_large);
}

#[test]
fn an_exploding_normal_form_is_one_diagnostic_stating_the_limit() {
    let limit = 200_000;
    let budget = Budget::new(limit);
    let diagnostics = generate_within(&exploding_sleigh(), budget.clone())
        .expect_err("the budget must stop the expansion");
    assert!(budget.is_exhausted());
    let rendered = diagnostics.render("sleigh.model");
    assert_eq!(diagnostics.len(), 1, "{rendered}");
    assert!(
        rendered.contains(&format!(
            "derivation budget exceeded: the normal form needs more than {limit} polynomial term products"
        )),
        "{rendered}"
    );
}

#[test]
fn a_budget_of_exactly_the_measured_use_suffices_and_one_less_does_not() {
    let (_, sleigh) = &crate::support::models::built_in()[3];
    let measured = Budget::default();
    assert!(generate_within(sleigh, measured.clone()).is_ok());
    assert!(generate_within(sleigh, Budget::new(measured.used())).is_ok());
    assert!(generate_within(sleigh, Budget::new(measured.used() - 1)).is_err());
}
