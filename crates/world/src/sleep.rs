//! Islands and sleeping, as in Box2D, Jolt and Rapier: bodies at rest stop costing anything
//! until something disturbs them.
//!
//! An island is a set of dynamic bodies joined by contacts (fixed and kinematic bodies do not
//! join islands: a floor does not tie everything on it together). Each step, after collision,
//! an island with any body awake — or touching a moving kinematic body — is woken whole, so a
//! body that lands on a sleeping pile wakes the pile. Contacts whose bodies sleep get no rows,
//! sleeping bodies get no gravity and are not integrated, and their contacts are kept as they
//! are (they do not move). After the step, a dynamic body slower than the thresholds accrues
//! rest time; an island all of whose bodies have rested for [`Sleeping::time`] falls asleep,
//! its velocities set to zero. Every control call on a body wakes it, and with it its island.
//!
//! Off by default ([`Sleeping::default`]), so the defaults simulate every body every step.

use crate::Body;
use crate::body::BodyKind;
use crate::tolerances;
use tatami_contact::{Contact, ContactSettings};
use tatami_lcp::DisjointSets;

/// When bodies fall asleep. The thresholds are Box2D's (its `b2_linearSleepTolerance`-like 5 cm/s
/// and 2°/s for half a second).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sleeping {
    /// Whether bodies may fall asleep at all. Off by default.
    pub enabled: bool,
    /// Speed of the centre of mass (m/s) below which a body counts as at rest.
    pub linear_speed: f64,
    /// Angular speed (rad/s) below which a body counts as at rest.
    pub angular_speed: f64,
    /// How long (s) every body of an island must have been at rest for it to sleep.
    pub time: f64,
}

impl Default for Sleeping {
    fn default() -> Self {
        Self {
            enabled: false,
            linear_speed: 0.05,
            angular_speed: 2f64.to_radians(),
            time: 0.5,
        }
    }
}

impl Sleeping {
    /// The default thresholds, switched on.
    pub fn on() -> Self {
        Self {
            enabled: true,
            ..Self::default()
        }
    }
}

/// How much deeper than the slop (m) a contact may be for its island to fall asleep. The
/// position pass brings a contact pressed in back to the slop a tenth of the excess a step,
/// from above; an island asleep is not pushed at all, so one put to sleep deep in stays so.
pub const SLEEP_DEPTH_TOLERANCE: f64 = 0.0005;

/// The islands of one step: a union–find over the bodies, reused across steps.
#[derive(Debug, Clone, Default)]
pub(crate) struct Islands {
    /// The dynamic bodies, joined through their contacts.
    sets: DisjointSets,
    /// Per island root: whether it must be awake this step.
    awake: Vec<bool>,
    /// Per island root: whether a moving kinematic body touches it (it may not fall asleep).
    pushed: Vec<bool>,
    /// Per island root: the shortest rest time of its bodies.
    rested: Vec<f64>,
}

impl Islands {
    /// Joins the dynamic bodies that touch, then wakes every island with a body awake or a
    /// contact with a moving kinematic body.
    pub(crate) fn wake<'a>(
        &mut self,
        bodies: &mut [Body],
        contacts: impl Iterator<Item = &'a Contact> + Clone,
    ) {
        self.join(bodies, contacts.clone());
        self.awake.clear();
        self.awake.resize(bodies.len(), false);
        self.pushed.clear();
        self.pushed.resize(bodies.len(), false);
        for (k, body) in bodies.iter().enumerate() {
            if body.is_dynamic() && !body.asleep {
                let root = self.sets.root(k);
                self.awake[root] = true;
            }
        }
        for contact in contacts {
            let (a, b) = (contact.body_a.0, contact.body_b.0);
            for (mover, other) in [(a, b), (b, a)] {
                if bodies[mover].kind() == BodyKind::Kinematic
                    && bodies[mover].moves()
                    && bodies[other].is_dynamic()
                {
                    let root = self.sets.root(other);
                    self.awake[root] = true;
                    self.pushed[root] = true;
                }
            }
        }
        for (k, body) in bodies.iter_mut().enumerate() {
            let root = self.sets.root(k);
            if body.asleep && self.awake[root] {
                body.wake();
            }
        }
    }

    /// Advances each awake dynamic body's rest time by `dt` (or resets it) and puts to sleep
    /// every island whose bodies have all rested for `settings.time`, unless one of its
    /// `contacts` is deeper than its pair's slop ([`crate::tolerances`] of `contact_settings`) +
    /// [`SLEEP_DEPTH_TOLERANCE`]. Uses the islands of the last [`wake`](Self::wake).
    pub(crate) fn fall_asleep<'a>(
        &mut self,
        bodies: &mut [Body],
        contacts: impl Iterator<Item = &'a Contact>,
        settings: &Sleeping,
        contact_settings: &ContactSettings,
        dt: f64,
    ) {
        self.rested.clear();
        self.rested.resize(bodies.len(), f64::INFINITY);
        // A body pressed in stays awake, so the position pass goes on pushing it out: the
        // island's shortest rest time is held at zero.
        let pressed_in = |c: &Contact, bodies: &[Body]| {
            let slop = tolerances::pair_settings(contact_settings, bodies, c).slop;
            c.depth() > slop + SLEEP_DEPTH_TOLERANCE
        };
        for contact in contacts.filter(|c| pressed_in(c, bodies)) {
            for body in [contact.body_a.0, contact.body_b.0] {
                if bodies[body].is_dynamic() {
                    let root = self.sets.root(body);
                    self.rested[root] = 0.0;
                }
            }
        }
        for (k, body) in bodies.iter_mut().enumerate() {
            if !body.is_dynamic() || body.asleep {
                continue;
            }
            let resting = body.linear_velocity.norm() < settings.linear_speed
                && body.angular_velocity.norm() < settings.angular_speed;
            body.rest_time = if resting { body.rest_time + dt } else { 0.0 };
            let root = self.sets.root(k);
            self.rested[root] = self.rested[root].min(body.rest_time);
        }
        for (k, body) in bodies.iter_mut().enumerate() {
            let root = self.sets.root(k);
            if body.is_dynamic()
                && !body.asleep
                && !self.pushed[root]
                && self.rested[root] >= settings.time
            {
                body.sleep();
            }
        }
    }

    /// Islands do not depend on contact order: a set's root is its smallest body index.
    fn join<'a>(&mut self, bodies: &[Body], contacts: impl Iterator<Item = &'a Contact>) {
        let pairs = contacts.map(|contact| (contact.body_a.0, contact.body_b.0));
        join_dynamic(&mut self.sets, bodies, pairs);
    }
}

/// Sets `sets` to `bodies`' islands through `pairs` (body indices): each pair of dynamic
/// bodies joined, fixed and kinematic ones left alone.
pub(crate) fn join_dynamic(
    sets: &mut DisjointSets,
    bodies: &[Body],
    pairs: impl Iterator<Item = (usize, usize)>,
) {
    sets.reset(bodies.len());
    for (a, b) in pairs {
        if bodies[a].is_dynamic() && bodies[b].is_dynamic() {
            sets.join(a, b);
        }
    }
}
