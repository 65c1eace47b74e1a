//! What drawing a model needs (docs/INTERFACE.md sections 4 and 10): a
//! mechanism's bodies and contacts by name and the items of the `drawing:`
//! section ([`Bodies`]), and at a configuration the gravity field, each
//! body's centre, frame rotation, mass and inertia, each contact's point
//! and each item's values ([`Drawing`]), computed by the interpreted
//! function `drawing(q)` at the current parameter values.

use super::{CallError, InterpretedModel};
use crate::emit::DRAWING;
use crate::model::Model;
use crate::model::drawing::DrawnItem;

/// A mechanism's bodies and `no_slip` contacts, in declared order (empty
/// for a model declared by its energy), and the drawing section's items.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bodies {
    /// The bodies and particles.
    pub bodies: Vec<BodyName>,
    /// The contacts, each once whatever its number of directions.
    pub contacts: Vec<ContactName>,
    /// The items of the `drawing:` section, in order: their names and
    /// shapes (without values).
    pub items: Vec<DrawnItem<()>>,
}

impl Bodies {
    /// True when there is nothing to draw: no body and no drawing item.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty() && self.items.is_empty()
    }
}

/// A body's name and kind.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BodyName {
    /// Its declared name.
    pub name: String,
    /// True for a `particle(point, mass)`.
    pub particle: bool,
}

/// A contact's name and body.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ContactName {
    /// Its declared name.
    pub name: String,
    /// Its body's index in [`Bodies::bodies`].
    pub body: usize,
}

/// A mechanism at one configuration, in ground axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    /// The uniform gravity field (zero when not declared).
    pub gravity: [f64; 3],
    /// Each body, in the order of [`Bodies::bodies`].
    pub bodies: Vec<BodyState>,
    /// Each contact's point, in the order of [`Bodies::contacts`].
    pub contacts: Vec<[f64; 3]>,
    /// Each drawing item, in the order of [`Bodies::items`].
    pub items: Vec<DrawnItem<f64>>,
}

/// A body at one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyState {
    /// Its centre `C - origin`.
    pub center: [f64; 3],
    /// Its frame's rotation matrix, row-major: column `j` is the frame's
    /// unit vector `j` (the identity for a particle).
    pub rotation: [f64; 9],
    /// Its mass.
    pub mass: f64,
    /// Its inertia about the centre in its frame's axes, row-major.
    pub inertia: [f64; 9],
}

/// The values of one body in `drawing(q)`: centre, rotation, mass, inertia.
const BODY_VALUES: usize = 3 + 9 + 1 + 9;

/// The bodies and contacts of `model`.
pub(super) fn bodies(model: &Model) -> Bodies {
    let Some(drawing) = model.mechanism.drawing.as_ref() else {
        return Bodies::default();
    };
    Bodies {
        bodies: (drawing.bodies.iter())
            .map(|body| BodyName {
                name: body.name.clone(),
                particle: body.particle,
            })
            .collect(),
        contacts: (drawing.contacts.iter())
            .map(|contact| ContactName {
                name: contact.name.clone(),
                body: contact.body,
            })
            .collect(),
        items: (drawing.items.iter())
            .map(|item| DrawnItem {
                name: item.name.clone(),
                figure: item.figure.map(|_| ()),
            })
            .collect(),
    }
}

/// `N` values of `values` from `start`.
fn array<const N: usize>(values: &[f64], start: usize) -> [f64; N] {
    std::array::from_fn(|i| values[start + i])
}

impl InterpretedModel {
    /// The mechanism's bodies and contacts (none for a model declared by
    /// its energy).
    pub fn bodies(&self) -> &Bodies {
        &self.bodies
    }

    /// The gravity field, the bodies, the contact points and the drawing
    /// items at `q`, at the current parameter values; with nothing to draw,
    /// no gravity either.
    ///
    /// # Errors
    /// [`CallError::ArgumentLength`] when `q` has not n entries.
    pub fn drawing(&self, q: &[f64]) -> Result<Drawing, CallError> {
        if self.bodies.is_empty() {
            return Ok(Drawing {
                gravity: [0.0; 3],
                bodies: Vec::new(),
                contacts: Vec::new(),
                items: Vec::new(),
            });
        }
        let values = self.call(DRAWING, &[q])?;
        let bodies = (0..self.bodies.bodies.len())
            .map(|i| {
                let at = 3 + BODY_VALUES * i;
                BodyState {
                    center: array(&values, at),
                    rotation: array(&values, at + 3),
                    mass: values[at + 12],
                    inertia: array(&values, at + 13),
                }
            })
            .collect();
        let contacts_at = 3 + BODY_VALUES * self.bodies.bodies.len();
        let contacts = (0..self.bodies.contacts.len())
            .map(|i| array(&values, contacts_at + 3 * i))
            .collect();
        let mut rest = values[contacts_at + 3 * self.bodies.contacts.len()..].iter();
        let items = (self.bodies.items.iter())
            .map(|item| DrawnItem {
                name: item.name.clone(),
                figure: item
                    .figure
                    .map(|_| *rest.next().expect("drawing(q)'s layout")),
            })
            .collect();
        Ok(Drawing {
            gravity: array(&values, 0),
            bodies,
            contacts,
            items,
        })
    }
}
