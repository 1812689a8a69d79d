//! Which contacts a kinematic body presses in beyond the slop, and by how much: what their
//! grips bear ([`tatami_contact::grip`]).
//!
//! A body driven by position, which no impulse moves, presses what it overlaps with whatever
//! force that takes: a gripper's finger, a VR hand. It presses the body against whatever
//! cannot give way either, another finger or a fixed wall or floor, and those contacts grip
//! too. Between other bodies an overlap is an error the position pass undoes, not a press,
//! and gets no grip: a body wedged between fixed bodies alone is left to the position pass.
//!
//! A body squeezed between such bodies cannot leave the overlap, only move it. The position
//! pass, pushing it out from both sides at once, ended each step with the push of the contact
//! it updated last, and shifted the body towards the other finger until the last contact was
//! within the slop: a cube squeezed by 1 cm a side went 8 mm off centre, its other finger
//! holding the whole overlap, and under the vertex and patch models, whose corners took up
//! the unbalanced pushes, it crept down the fingers at 6 and 20 mm/s. So a contact pressed
//! beyond the slop while another pushes its body the other way, also beyond it, is
//! *squeezed*: the position pass leaves it be (its pushes are zero), and the cube stays where
//! the fingers hold it, to 2–5 µm under every model, or where a finger holds it against a
//! wall. And a contact's press is the mean of its own excess and those of the body's pressed
//! contacts that push it the other way, so the sides of one squeeze grip alike however the
//! overlap is shared between them.

use nalgebra::Vector3;
use tatami_contact::{Contact, ContactSettings, grip};

use crate::Body;

/// A contact of a dynamic body with one that cannot give way: the dynamic body, the direction
/// the contact pushes it, the contact's own excess beyond the slop, whether the other body is
/// kinematic (driven), and the contact's index in the contact set.
#[derive(Debug, Clone, Copy)]
struct Pressed {
    body: usize,
    push: Vector3<f64>,
    excess: f64,
    driven: bool,
    contact: usize,
}

impl Pressed {
    /// Whether a kinematic body presses its body in beyond the slop here.
    fn presses(&self) -> bool {
        self.driven && self.excess > 0.0
    }
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
    /// Finds, among `contacts` (the contact set's, in its order), those of awake dynamic bodies
    /// that a kinematic body presses in beyond the slop with bodies that cannot give way
    /// (kinematic or fixed), and each one's share of its body's squeeze.
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
        // Most worlds have no kinematic body, and a pile's thousands of contacts need no look.
        if !bodies.iter().any(Body::is_kinematic) {
            return;
        }
        for (index, contact) in contacts.enumerate() {
            let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
            let awake = |body: &Body| body.is_dynamic() && !body.asleep;
            // Body A is pushed along the normal, B against it.
            let (body, push, by) = match (awake(a), awake(b)) {
                (true, false) if !b.is_dynamic() => (contact.body_a.0, contact.frame.normal, b),
                (false, true) if !a.is_dynamic() => (contact.body_b.0, -contact.frame.normal, a),
                _ => continue,
            };
            self.pressed.push(Pressed {
                body,
                push,
                excess: grip::excess(contact, settings),
                driven: by.is_kinematic(),
                contact: index,
            });
        }
        // Most steps of most worlds: no kinematic body presses anything.
        if !self.pressed.iter().any(Pressed::presses) {
            return;
        }
        self.pressed.sort_by_key(|p| p.body);
        let against = |own: &Pressed, other: &Pressed| other.push.dot(&own.push) < 0.0;
        for run in self.pressed.chunk_by(|p, q| p.body == q.body) {
            // Only a body a kinematic body presses in beyond the slop.
            if !run.iter().any(Pressed::presses) {
                continue;
            }
            for own in run {
                // Its contacts with kinematic bodies, and those with fixed bodies that a
                // kinematic body presses it into: a body wedged between fixed ones is left to
                // the position pass, and the floor under a body a paddle pushes along is not
                // pressed by the paddle.
                let pressed = own.driven
                    || run
                        .iter()
                        .any(|other| other.presses() && against(own, other));
                if !pressed {
                    continue;
                }
                let (sum, count) = run
                    .iter()
                    .filter(|other| other.contact == own.contact || against(own, other))
                    .fold((0.0, 0.0), |(sum, count), other| {
                        (sum + other.excess, count + 1.0)
                    });
                self.shares[own.contact] = sum / count;
                self.squeezed[own.contact] = own.excess > 0.0
                    && run
                        .iter()
                        .any(|other| against(own, other) && other.excess > 0.0);
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
