//! Sections: known, given once, the required ones present, alternatives
//! exclusive; attributes.

use super::*;

impl Checker {
    pub(super) fn sections<'a>(&mut self, syntax: &'a ModelSyntax) -> Sections<'a> {
        let mut sections: Sections<'a> = HashMap::new();
        for section in &syntax.sections {
            let key = section.key.to_string();
            if !self.rule_known_section(section) || !self.rule_section_once(&sections, section) {
                continue;
            }
            sections.insert(key, section);
        }
        self.rule_required_sections(&sections, syntax);
        self.rule_exclusive_sections(&sections, "kinetic_energy", "mass_matrix");
        self.rule_exclusive_sections(&sections, "constraints", "distribution");
        sections
    }

    /// A section name is one the language knows.
    pub(super) fn rule_known_section(&mut self, section: &Section) -> bool {
        let key = section.key.to_string();
        let known = SECTIONS.contains(&key.as_str());
        if !known {
            self.diagnostics.error(
                section.key.span(),
                format!(
                    "unknown section `{key}`; the sections are {}",
                    SECTIONS.join(", ")
                ),
            );
        }
        known
    }

    /// A section is given at most once.
    pub(super) fn rule_section_once(&mut self, sections: &Sections, section: &Section) -> bool {
        let key = section.key.to_string();
        let fresh = !sections.contains_key(&key);
        if !fresh {
            self.diagnostics.error(
                section.key.span(),
                format!("section `{key}` is given twice"),
            );
        }
        fresh
    }

    /// `coordinates` and one of `kinetic_energy`/`mass_matrix` are required.
    pub(super) fn rule_required_sections(&mut self, sections: &Sections, syntax: &ModelSyntax) {
        if !sections.contains_key("coordinates") {
            self.diagnostics.error(
                syntax.name.span(),
                "missing section `coordinates`: a model declares its generalized coordinates",
            );
        }
        if !["kinetic_energy", "mass_matrix", "bodies"]
            .iter()
            .any(|key| sections.contains_key(*key))
        {
            self.diagnostics.error(
                syntax.name.span(),
                "missing section `kinetic_energy` (or `mass_matrix`, or `bodies`): a model \
                 declares its kinetic energy",
            );
        }
    }

    /// Two alternative sections are not both given.
    pub(super) fn rule_exclusive_sections(
        &mut self,
        sections: &Sections,
        first: &str,
        second: &str,
    ) {
        if let (Some(_), Some(later)) = (sections.get(first), sections.get(second)) {
            self.diagnostics.error(
                later.key.span(),
                format!("`{first}` and `{second}` are alternatives: give only one of them"),
            );
        }
    }

    // ----- attributes ----------------------------------------------------

    /// Attributes are doc comments or `#[deny_holonomic]`.
    pub(super) fn options(&mut self, syntax: &ModelSyntax) -> Options {
        let mut options = Options::default();
        for attribute in &syntax.attributes {
            match attribute.name.to_string().as_str() {
                "deny_holonomic" if attribute.tokens.is_empty() => options.deny_holonomic = true,
                name => self.diagnostics.error(
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
}
