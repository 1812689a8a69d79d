//! Which contacts a kinematic body presses in beyond the slop, and by how much: what their
//! grips bear ([`tatami_contact::grip`]).
//!
//! A body driven by position, which no impulse moves, presses what it overlaps with whatever
//! force that takes: a gripper's finger, a VR hand. Between other bodies an overlap is an error
//! the position pass undoes, not a press, and gets no grip.
//!
//! A body squeezed between such bodies cannot leave the overlap, only move it. The position
//! pass, pushing it out from both sides at once, ended each step with the push of the contact
//! it updated last, and shifted the body towards the other finger until the last contact was
//! within the slop: a cube squeezed by 1 cm a side went 8 mm off centre, its other finger
//! holding the whole overlap, and under the vertex and patch models, whose corners took up
//! the unbalanced pushes, it crept down the fingers at 6 and 20 mm/s. So a contact pressed
//! beyond the slop while another pushes its body the other way, also beyond it, is
//! *squeezed*: the position pass leaves it be (its pushes are zero), and the cube stays where
//! the fingers hold it, to 2–4 µm under every model. And a contact's press is the mean of its
//! own excess and those of the body's pressed contacts that push it the other way, so the
//! sides of one squeeze grip alike however the overlap is shared between them.

use nalgebra::Vector3;
use tatami_contact::{Contact, ContactSettings, grip};

use crate::Body;

/// One contact a kinematic body presses: the dynamic body it presses, the direction it pushes
/// that body, the contact's own excess beyond the slop, and its index in the contact set.
#[derive(Debug, Clone, Copy)]
struct Pressed {
    body: usize,
    push: Vector3<f64>,
    excess: f64,
    contact: usize,
}

/// The presses of one step, reused across steps.
#[derive(Debug, Clone, Default)]
pub(crate) struct Presses {
    pressed: Vec<Pressed>,
    /// Per contact of the set, the press its grip bears (m beyond the slop); 0 for none.
    shares: Vec<f64>,
    /// Per contact of the set, whether it and another pushing its body the other way are both
    /// pressed in beyond the slop.
    squeezed: Vec<bool>,
}

impl Presses {
    /// Finds the pressed contacts among `contacts` (the contact set's, in its order) between a
    /// kinematic body and an awake dynamic one, and each one's share of its body's squeeze.
    pub(crate) fn find<'a>(
        &mut self,
        bodies: &[Body],
        contacts: impl ExactSizeIterator<Item = &'a Contact>,
        settings: &ContactSettings,
    ) {
        self.shares.clear();
        self.shares.resize(contacts.len(), 0.0);
        self.squeezed.clear();
        self.squeezed.resize(contacts.len(), false);
        self.pressed.clear();
        for (index, contact) in contacts.enumerate() {
            let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
            // Body A is pushed along the normal, B against it.
            let (body, push) = match (a.is_kinematic(), b.is_kinematic()) {
                (false, true) if a.is_dynamic() && !a.asleep => {
                    (contact.body_a.0, contact.frame.normal)
                }
                (true, false) if b.is_dynamic() && !b.asleep => {
                    (contact.body_b.0, -contact.frame.normal)
                }
                _ => continue,
            };
            self.pressed.push(Pressed {
                body,
                push,
                excess: grip::excess(contact, settings),
                contact: index,
            });
        }
        self.pressed.sort_by_key(|p| p.body);
        for run in self.pressed.chunk_by(|p, q| p.body == q.body) {
            for own in run {
                let (sum, count) = run
                    .iter()
                    .filter(|other| other.contact == own.contact || other.push.dot(&own.push) < 0.0)
                    .fold((0.0, 0.0), |(sum, count), other| {
                        (sum + other.excess, count + 1.0)
                    });
                self.shares[own.contact] = sum / count;
                self.squeezed[own.contact] = own.excess > 0.0
                    && run
                        .iter()
                        .any(|other| other.push.dot(&own.push) < 0.0 && other.excess > 0.0);
            }
        }
    }

    /// The press the grip of the contact at `index` bears (m beyond the slop), if a kinematic
    /// body presses it.
    pub(crate) fn share(&self, index: usize) -> f64 {
        self.shares.get(index).copied().unwrap_or(0.0)
    }

    /// Whether the contact at `index` squeezes its body against another pressed contact: the
    /// position pass, which could only shift the body between them, leaves it be.
    pub(crate) fn squeezed(&self, index: usize) -> bool {
        self.squeezed.get(index).copied().unwrap_or(false)
    }
}
