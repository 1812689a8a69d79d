//! Putting back a pair of free bodies that their step drove into each other (time of impact).
//!
//! Contacts are linearised at the step's start: a contact's rows hold its touching features
//! apart, and its landing points the corners an impact's turn swings onto a face it touches
//! ([`crate::speculative`]). Two bodies that meet corner to corner or edge to edge have no such
//! face: the impulse at the one touching point spins them, and within the same step other
//! corners and edges swing into each other. Two 0.3 m cubes thrown at each other at 5 m/s
//! each, turned at random, ended the step they met in up to 11.5 cm deep in each other (7 of
//! 100 starts more than a third of the cube, and they lay so for eight steps while the
//! position pass pushed them out; 14 of 100 at 10 m/s, 72 at 20 m/s).
//!
//! So after the solve, each pair of dynamic bodies that may meet in the step (the broad phase's
//! pairs), that may close on each other past the contact margin at the solved velocities, and
//! that is apart when the step starts, is tested at the poses the step moves it to. If the step
//! leaves the two deeper in each other than the slop and the margin, both are put back along
//! their own motion to where they stood the slop deep, found by bisection, as Box2D's
//! time-of-impact pass puts a fast body back: velocities as solved, the rest of the step's
//! travel dropped. Next step finds them touching at the features that met and solves that
//! contact. Now the cubes end the step they meet in within the slop and the
//! margin from every start (`tests/speculative.rs`), and a third of the cube deep at any time
//! from 0, 2 and 4 of 100 starts at 5, 10 and 20 m/s each.
//!
//! Only a pair whose bodies touch no other body (fixed ones aside) is put back, and only if
//! that drives neither deeper into a third body than the step without it would: a third
//! body's step is not put back with them. On piles of 1000 dropped cubes (12 seeds) the steps
//! with a contact over 10 cm deep were 15.9 a pile before, 20.2 without the third-body check,
//! 11.6 with it (one seed without either check: 36 against 16). Nor is a body a kinematic one
//! touches: the kinematic body goes on, and the depth test at the step's end does not see it
//! pass through what it pushed (a row of cubes pushed by a fast paddle, put back where they
//! met each other). A pair already touching when
//! the step starts is left to its contact: put back too, a pair its contact could not hold
//! stood still step after step while gravity sped it up. Except once: the step after a pair
//! was put back where it met, its contact is the single point of a corner on an edge, and the
//! turn its impulse gives the two bodies swings other corners into each other within the step
//! (the cubes above sank a third of their size into each other from 2 and 3 of 100 starts at
//! 10 and 20 m/s each, 18 at 30 m/s); put back once more, none did at 10 and 20 m/s, 8 at
//! 30 m/s (now 3 and 12 of 100 at 20 and 30 m/s, none at 5 and 10 m/s: cubes meeting as they
//! slide and spin keep more of their spin since a face's friction force and twist share one
//! limit surface, and edges meeting beyond an end touch where they come nearest; see
//! `CHANGES.md`). More than once, the cubes at 30 m/s got no better (7 of 100 with up to five
//! put-backs), and kept being put back, a pair standing still. A body in several such pairs is
//! put back to the earliest of their times.

use nalgebra::{Point3, Quaternion, UnitQuaternion};
use tatami_contact::Contact;
use tatami_lcp::SolverBody;

use crate::apart::Placement;
use crate::body::{Body, Motion};
use crate::collision::BodyGeometry;
use crate::parry_bridge;
use crate::speculative::Travel;

/// Halvings of the step that find where a pair stood at the depth it may keep: the motion's
/// 1/256th, 1.3 mm of a pair closing at 20 m/s at 60 Hz.
const BISECTIONS: usize = 8;

/// Scratch reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct RewindWorkspace {
    /// Each body's entry in the step's motions, if it moves.
    motion_of: Vec<Option<usize>>,
    /// Each body's share of its motion it keeps (1: all of it).
    kept: Vec<f64>,
    /// How many bodies other than fixed ones each body has a contact with (`u32::MAX` once one
    /// of them is kinematic: a body a kinematic one pushes is never put back).
    neighbours: Vec<u32>,
    /// How far each body's points may move in the step at its solved velocities.
    travels: Vec<Travel>,
    /// The pairs put back, the share of the step each keeps, and whether it was apart at the
    /// step's start.
    rewinds: Vec<([usize; 2], f64, bool)>,
    /// Bodies whose rewind would drive them or a third body deeper into each other.
    cancelled: Vec<bool>,
    /// The pairs put back from apart in the last step, sorted: each may be put back once more,
    /// touching.
    met: Vec<[usize; 2]>,
}

/// What a pair's test reads of the step.
pub(crate) struct StepMotion<'a> {
    pub bodies: &'a [Body],
    pub geometry: &'a [BodyGeometry],
    /// Where each body was at the step's start, with how far its shape reaches.
    pub placements: &'a [Placement],
    /// The solved velocities, by body.
    pub solved: &'a [SolverBody],
    pub dt: f64,
    /// The contact margin and slop (m).
    pub margin: f64,
    pub slop: f64,
}

impl RewindWorkspace {
    /// Puts back, in `motions` (each moving body's index and its end-of-step state, the bodies
    /// at the step's start), the bodies of each of the broad phase's `pairs` that the step
    /// drives into each other from apart, or from touching the step after they were put back
    /// from apart (module doc); `contacts` are the step's.
    pub(crate) fn rewind<'c>(
        &mut self,
        step: &StepMotion,
        pairs: &[(usize, usize)],
        contacts: impl Iterator<Item = &'c Contact>,
        motions: &mut [(usize, Motion)],
    ) {
        let bodies = step.bodies;
        self.motion_of.clear();
        self.motion_of.resize(bodies.len(), None);
        for (m, (index, _)) in motions.iter().enumerate() {
            self.motion_of[*index] = Some(m);
        }
        self.kept.clear();
        self.kept.resize(bodies.len(), 1.0);
        self.rewinds.clear();
        self.neighbours.clear();
        self.neighbours.resize(bodies.len(), 0);
        for contact in contacts {
            let (a, b) = (contact.body_a.0, contact.body_b.0);
            if !bodies[a].is_fixed() && !bodies[b].is_fixed() {
                for (k, other) in [(a, b), (b, a)] {
                    // A kinematic body's step is never put back: a body it pushes, put back
                    // where it met a third, would be passed through (1 cm cubes 3 mm apart
                    // pushed by a paddle at 5 m/s: two of four behind it after one step).
                    self.neighbours[k] = if bodies[other].is_kinematic() {
                        u32::MAX
                    } else {
                        self.neighbours[k].saturating_add(1)
                    };
                }
            }
        }
        let reach = |k: usize| step.placements[k].reach;
        self.travels.clear();
        self.travels
            .extend(step.solved.iter().enumerate().map(|(k, v)| {
                Travel::moving(&v.linear_velocity, &v.angular_velocity, reach(k), step.dt)
            }));
        for &(a, b) in pairs {
            let pair = [a, b];
            // Cheapest tests first: most pairs of a pile touch a third body.
            let alone = pair.iter().all(|&k| self.neighbours[k] <= 1);
            if !alone {
                continue;
            }
            let ends = pair.map(|k| self.motion_of[k].map(|m| motions[m].1.centre));
            let [Some(end_a), Some(end_b)] = ends else {
                continue;
            };
            let dynamic = bodies[a].is_dynamic() && bodies[b].is_dynamic();
            if !dynamic || self.travels[a].closing(&self.travels[b]) <= step.margin {
                continue;
            }
            // Where the step ends them, their bounding spheres apart: most fast pairs end so.
            if (end_a - end_b).norm() > reach(a) + reach(b) {
                continue;
            }
            let depth = |s: f64| step.depth(pair, [s, s], &self.motion_of, motions);
            // At the step's end first: most of the rest end it no deeper than the slop.
            if depth(1.0) <= step.slop + step.margin {
                continue;
            }
            // Apart at the step's start, or touching since it was put back where it met.
            let apart = depth(0.0) <= 0.0;
            if !apart && self.met.binary_search(&pair).is_err() {
                continue;
            }
            let (mut kept, mut overshot) = (0.0, 1.0);
            for _ in 0..BISECTIONS {
                let s = 0.5 * (kept + overshot);
                if depth(s) <= step.slop {
                    kept = s;
                } else {
                    overshot = s;
                }
            }
            self.rewinds.push((pair, kept, apart));
        }
        self.met.clear();
        if self.rewinds.is_empty() {
            return;
        }
        // A rewind stands only if it drives neither body deeper into a third than the step
        // without it would: the third body's step is not put back with them.
        for &(pair, kept, _) in &self.rewinds {
            for k in pair {
                self.kept[k] = self.kept[k].min(kept);
            }
        }
        self.cancelled.clear();
        self.cancelled.resize(bodies.len(), false);
        for &(a, b) in pairs {
            let kept = [self.kept[a], self.kept[b]];
            if kept == [1.0, 1.0] {
                continue;
            }
            let depth = |shares: [f64; 2]| step.depth([a, b], shares, &self.motion_of, motions);
            if depth(kept) > depth([1.0, 1.0]) + step.slop {
                self.cancelled[a] = true;
                self.cancelled[b] = true;
            }
        }
        self.kept.fill(1.0);
        for &(pair, kept, apart) in &self.rewinds {
            if !pair.iter().any(|&k| self.cancelled[k]) {
                for k in pair {
                    self.kept[k] = self.kept[k].min(kept);
                }
                if apart {
                    self.met.push(pair);
                }
            }
        }
        self.met.sort_unstable();
        for (index, motion) in motions.iter_mut() {
            let kept = self.kept[*index];
            if kept < 1.0 {
                (motion.centre, motion.rotation) = between(&bodies[*index], motion, kept);
            }
        }
    }
}

impl StepMotion<'_> {
    /// How deep `pair`'s shapes overlap (m; 0 apart) with each body at its share of its
    /// step's motion in `shares` (a body without a motion where it is).
    fn depth(
        &self,
        pair: [usize; 2],
        shares: [f64; 2],
        motion_of: &[Option<usize>],
        motions: &[(usize, Motion)],
    ) -> f64 {
        let [pose_a, pose_b] = [0, 1].map(|side| {
            let (k, body) = (pair[side], &self.bodies[pair[side]]);
            let (centre, rotation) = match motion_of[k] {
                Some(m) => between(body, &motions[m].1, shares[side]),
                None => (body.centre, body.rotation),
            };
            parry_bridge::pose(&(centre - rotation * body.com_offset()), &rotation)
        });
        let (a, b) = (
            &self.geometry[pair[0]].collider,
            &self.geometry[pair[1]].collider,
        );
        a.depth_into(&pose_a, b, &pose_b)
    }
}

/// `body`'s centre and rotation at the share `s` of its step to `motion`.
fn between(body: &Body, motion: &Motion, s: f64) -> (Point3<f64>, UnitQuaternion<f64>) {
    let centre = body.centre + (motion.centre - body.centre) * s;
    // Normalised linear interpolation, the short way round: a step's turn is small, and a
    // rotation off unit length by rounding turns the carried contacts' normals off unit length.
    let (from, to) = (body.rotation.coords, motion.rotation.coords);
    let to = if from.dot(&to) < 0.0 { -to } else { to };
    let rotation = UnitQuaternion::new_normalize(Quaternion::from(from.lerp(&to, s)));
    (centre, rotation)
}
