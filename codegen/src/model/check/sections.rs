//! The rules on the sections as a whole: each known, given once, the
//! required ones present, alternatives exclusive, keyword arguments in
//! the drawing section only; and on the attributes.

use super::context::Context;
use super::items::check_no_keywords;
use super::section::{Section, Sections};
use crate::model::Options;
use crate::syntax::{self, ModelSyntax};

/// The sections the model gives, each known and given once, after checking
/// the required ones are there and no two alternatives are both given.
pub(super) fn given_sections<'a>(cx: &mut Context, syntax: &'a ModelSyntax) -> Sections<'a> {
    let mut sections = Sections::default();
    for given in &syntax.sections {
        let Some(section) = check_known_section(cx, given) else {
            continue;
        };
        if section != Section::Drawing {
            check_no_keywords(cx, &given.value);
        }
        if check_section_once(cx, &sections, section, given) {
            sections.insert(section, given);
        }
    }
    check_required_sections(cx, &sections, syntax);
    check_exclusive_sections(cx, &sections, Section::KineticEnergy, Section::MassMatrix);
    check_exclusive_sections(cx, &sections, Section::Constraints, Section::Distribution);
    sections
}

/// A section name is one the language knows.
fn check_known_section(cx: &mut Context, given: &syntax::Section) -> Option<Section> {
    let key = given.key.to_string();
    let section = Section::of_keyword(&key);
    if section.is_none() {
        let keywords: Vec<&str> = Section::ALL.iter().map(|s| s.keyword()).collect();
        cx.diagnostics.error(
            given.key.span(),
            format!(
                "unknown section `{key}`; the sections are {}",
                keywords.join(", ")
            ),
        );
    }
    section
}

/// A section is given at most once.
fn check_section_once(
    cx: &mut Context,
    sections: &Sections,
    section: Section,
    given: &syntax::Section,
) -> bool {
    let fresh = !sections.contains(section);
    if !fresh {
        cx.diagnostics.error(
            given.key.span(),
            format!("section `{}` is given twice", given.key),
        );
    }
    fresh
}

/// `coordinates` and one of `kinetic_energy`/`mass_matrix`/`bodies` are required.
fn check_required_sections(cx: &mut Context, sections: &Sections, syntax: &ModelSyntax) {
    if !sections.contains(Section::Coordinates) {
        cx.diagnostics.error(
            syntax.name.span(),
            "missing section `coordinates`: a model declares its generalized coordinates",
        );
    }
    if ![Section::KineticEnergy, Section::MassMatrix, Section::Bodies]
        .into_iter()
        .any(|section| sections.contains(section))
    {
        cx.diagnostics.error(
            syntax.name.span(),
            "missing section `kinetic_energy` (or `mass_matrix`, or `bodies`): a model \
             declares its kinetic energy",
        );
    }
}

/// Two alternative sections are not both given.
fn check_exclusive_sections(
    cx: &mut Context,
    sections: &Sections,
    first: Section,
    second: Section,
) {
    if let (Some(_), Some(later)) = (sections.get(first), sections.get(second)) {
        cx.diagnostics.error(
            later.key.span(),
            format!(
                "`{}` and `{}` are alternatives: give only one of them",
                first.keyword(),
                second.keyword()
            ),
        );
    }
}

/// Attributes are doc comments or `#[deny_holonomic]`.
pub(super) fn check_attributes(cx: &mut Context, syntax: &ModelSyntax) -> Options {
    let mut options = Options::default();
    for attribute in &syntax.attributes {
        match attribute.name.to_string().as_str() {
            "deny_holonomic" if attribute.tokens.is_empty() => options.deny_holonomic = true,
            name => cx.diagnostics.error(
                attribute.name.span(),
                format!(
                    "unknown attribute `{name}`: a model takes doc comments and \
                     `#[deny_holonomic]`"
                ),
            ),
        }
    }
    options
}
