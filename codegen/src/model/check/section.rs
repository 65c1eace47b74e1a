//! The sections of the model language: their keywords, the order the
//! documentation lists them in, which of them declare a mechanism, and the
//! sections a model gives, looked up by kind.

use crate::syntax;

/// A section of the model language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Section {
    Coordinates,
    Parameters,
    Define,
    KineticEnergy,
    MassMatrix,
    PotentialEnergy,
    Constraints,
    Distribution,
    Inputs,
    MomentumBasis,
    Symmetry,
    Frames,
    Points,
    Bodies,
    Gravity,
    NoSlip,
    Holonomic,
    Drawing,
}

impl Section {
    /// Every section, in the order the documentation lists them.
    pub(super) const ALL: [Section; 18] = [
        Section::Coordinates,
        Section::Parameters,
        Section::Define,
        Section::KineticEnergy,
        Section::MassMatrix,
        Section::PotentialEnergy,
        Section::Constraints,
        Section::Distribution,
        Section::Inputs,
        Section::MomentumBasis,
        Section::Symmetry,
        Section::Frames,
        Section::Points,
        Section::Bodies,
        Section::Gravity,
        Section::NoSlip,
        Section::Holonomic,
        Section::Drawing,
    ];

    /// The keyword that opens the section.
    pub(super) fn keyword(self) -> &'static str {
        match self {
            Section::Coordinates => "coordinates",
            Section::Parameters => "parameters",
            Section::Define => "define",
            Section::KineticEnergy => "kinetic_energy",
            Section::MassMatrix => "mass_matrix",
            Section::PotentialEnergy => "potential_energy",
            Section::Constraints => "constraints",
            Section::Distribution => "distribution",
            Section::Inputs => "inputs",
            Section::MomentumBasis => "momentum_basis",
            Section::Symmetry => "symmetry",
            Section::Frames => "frames",
            Section::Points => "points",
            Section::Bodies => "bodies",
            Section::Gravity => "gravity",
            Section::NoSlip => "no_slip",
            Section::Holonomic => "holonomic",
            Section::Drawing => "drawing",
        }
    }

    /// The section a keyword opens, if the language has one.
    pub(super) fn of_keyword(keyword: &str) -> Option<Section> {
        Section::ALL
            .into_iter()
            .find(|section| section.keyword() == keyword)
    }

    /// Where the section stands in [`Section::ALL`].
    pub(super) fn order(self) -> usize {
        self as usize
    }

    /// Whether the section declares part of a mechanism (frames, points,
    /// bodies, gravity, rolling contacts, holonomic constraints).
    pub(super) fn is_mechanism(self) -> bool {
        matches!(
            self,
            Section::Frames
                | Section::Points
                | Section::Bodies
                | Section::Gravity
                | Section::NoSlip
                | Section::Holonomic
        )
    }
}

/// The sections a model gives, each at most once.
#[derive(Default)]
pub(super) struct Sections<'a> {
    given: [Option<&'a syntax::Section>; Section::ALL.len()],
}

impl<'a> Sections<'a> {
    /// The section of this kind, if given.
    pub(super) fn get(&self, section: Section) -> Option<&'a syntax::Section> {
        self.given[section.order()]
    }

    /// Whether a section of this kind is given.
    pub(super) fn contains(&self, section: Section) -> bool {
        self.get(section).is_some()
    }

    /// Records the section given for this kind.
    pub(super) fn insert(&mut self, section: Section, given: &'a syntax::Section) {
        self.given[section.order()] = Some(given);
    }

    /// Whether any mechanism section is given.
    pub(super) fn any_mechanism(&self) -> bool {
        Section::ALL
            .into_iter()
            .any(|section| section.is_mechanism() && self.contains(section))
    }
}
