//! How far each body of a contact turns over the step, and how that bends its contact points'
//! paths off the straight lines the rows hold them to.
//!
//! A contact's rows hold the velocities of the two bodies' points at the step's start, as
//! though each point then moved in a straight line; the integrator turns each body about its
//! centre of mass, so a point an arm `r` from it moves by `(R(θ) − I) r` where the rows counted
//! `θ × r`. The rest, `(R(θ) − I − [θ]×) r` (`½ θ × (θ × r)` for a small turn), is the point
//! swinging inwards on its arc. A top spinning at 200 rad/s on its tip swings its tip round the
//! spin axis a fraction of a millimetre off it: the tip sank and wandered by that each step,
//! and the position pass that lifted it back tilted the top, which sank from its 20°–26° nod
//! to 44° over 10 s at 60 Hz (in half-radian substeps; it fell within a second in whole
//! steps). So each point row targets `u · (bend_A − bend_B) / dt` less along its direction
//! `u`: the velocity that leaves the two points where the row asks once the bodies have
//! turned. The top then nods within a degree of the fixed-tip top over 10 s
//! (`tests/spinning_top.rs` of the world crate).
//!
//! The bend is read from the turns the step starts with, so it is taken only where those
//! last the step: at a point that touches and closes slower than [`RESTING_SPEED`] (not at a
//! landing's or an impact's, whose impulses change the turn), held to a quarter of the slop.
//! It is for material points — a polytope's vertices, edges and faces; the caller gives no
//! turn for a ball or a cylinder, whose contact runs over its curved surface as it rolls or
//! wobbles (a rolling ball bent by its turn would be pressed into the floor by `v² dt² / 2r` a
//! step). A face's friction rows take no bend: the weld of two faces turning together
//! already keeps their points together over the step (see the crate doc).

use nalgebra::{UnitQuaternion, Vector3};

use crate::jacobian::Witness;
use crate::{Contact, ContactSettings};

/// Fastest a touching point may close (m/s) and still take its bend: a spun top's tip closes
/// at up to 3 cm/s as the step starts, a box landing flat at 1 m/s or tipping from flat at 1.2
/// rad/s meets the floor in an impact, which the bend, read from the turn before the impact,
/// took 0.06% and 2% off the closed forms.
pub const RESTING_SPEED: f64 = 0.1;

/// How far each body of a contact turns its shape over the step (rad, world axes: the axis
/// times the angle), for
/// [`ContactModel::build_rows_turned`](crate::ContactModel::build_rows_turned).
/// Zero for a fixed body and a ball; a caller may pass zero for a body at rest, whose turn
/// bends nothing, and its rows then cost no more than without turns.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Turns {
    /// Body A's turn.
    pub a: Vector3<f64>,
    /// Body B's turn.
    pub b: Vector3<f64>,
}

impl Turns {
    /// The bend a point row at `witness` takes off its target, `depth` deep (m; a gap when
    /// negative) and closing at `-normal_speed` (m/s) as the step starts: [`Turns::bend`] for
    /// a point that touches and closes slower than [`RESTING_SPEED`], held to a quarter of the
    /// slop in length; none for a point still apart (a landing) or meeting faster (an impact),
    /// whose bodies' turns the step's impulses change: read from the turns the step starts
    /// with, a cube tipping from flat at 1.2 rad/s, which pivots on to its edge at a fifth of
    /// that, took a bend ten times too large.
    #[inline]
    pub(crate) fn bend_at(
        &self,
        contact: &Contact,
        witness: &Witness,
        (depth, normal_speed): (f64, f64),
        settings: &ContactSettings,
    ) -> Vector3<f64> {
        if depth < 0.0 || normal_speed < -RESTING_SPEED || *self == Self::default() {
            return Vector3::zeros();
        }
        let bend = self.bend(contact, witness);
        let (length, limit) = (bend.norm(), 0.25 * settings.slop);
        if length > limit {
            bend * (limit / length)
        } else {
            bend
        }
    }

    /// How far A's point of `witness` moves from B's over the step beyond the straight lines
    /// of their velocities at its start (m).
    #[inline]
    pub(crate) fn bend(&self, contact: &Contact, witness: &Witness) -> Vector3<f64> {
        let swing = |turn: &Vector3<f64>, arm: Vector3<f64>| {
            if *turn == Vector3::zeros() {
                return Vector3::zeros();
            }
            UnitQuaternion::from_scaled_axis(*turn) * arm - arm - turn.cross(&arm)
        };
        swing(&self.a, witness.a - contact.centre_a) - swing(&self.b, witness.b - contact.centre_b)
    }
}

/// The bend a contact's friction rows take at a point whose normal row takes `bend`: none
/// where a weld holds them (a face on a face, `welded`), whose target already keeps two faces
/// turning together together over the step ([`crate::jacobian`]'s weld), else the point's.
#[inline]
pub(crate) fn friction_bend(welded: bool, bend: Vector3<f64>) -> Vector3<f64> {
    if welded { Vector3::zeros() } else { bend }
}

/// A point row's `target` along `direction` with the row's points' `bend` over a step of `dt`
/// taken off (see the module doc).
#[inline]
pub(crate) fn bent(target: f64, direction: &Vector3<f64>, bend: &Vector3<f64>, dt: f64) -> f64 {
    target - direction.dot(bend) / dt
}

#[cfg(test)]
mod tests {
    use nalgebra::{Point2, Point3};
    use tatami_geometry::ConvexPolygon;
    use tatami_lcp::{BodyId, Problem, SolverBody};

    use super::*;
    use crate::{ContactError, ContactFrame, ContactModel, ContactRows, Material};

    /// A turn that is not finite is refused by name under every model, with nothing built.
    #[test]
    fn a_turn_that_is_not_finite_is_an_error() {
        let contact = contact();
        for model in ContactModel::ALL {
            for bad in [f64::NAN, f64::INFINITY] {
                let turns = Turns {
                    a: Vector3::zeros(),
                    b: Vector3::new(0.0, bad, 0.0),
                };
                let mut problem = Problem {
                    bodies: vec![SolverBody::fixed(); 2],
                    ..Default::default()
                };
                let mut biases = Vec::new();
                let mut out = ContactRows::of(&mut problem, &mut biases);
                let settings = ContactSettings::default();
                let built =
                    model.build_rows_turned(&contact, None, 0.01, &turns, &settings, &mut out);
                assert_eq!(built, Err(ContactError::NonFinite { what: "turn" }));
                assert!(problem.rows.is_empty());
            }
        }
    }

    /// A point contact off the world's axes between bodies whose centres lie off its normal.
    fn contact() -> Contact {
        Contact {
            body_a: BodyId(0),
            body_b: BodyId(1),
            centre_a: Point3::new(0.3, -0.2, 0.9),
            centre_b: Point3::new(-1.0, 0.5, -2.0),
            frame: ContactFrame::from_normal(
                Point3::new(0.1, 0.2, 0.0),
                Vector3::new(0.2, -0.1, 1.0),
            )
            .unwrap(),
            support: ConvexPolygon::from_points(&[Point2::origin()]).unwrap(),
            depths: vec![0.002],
            material: Material::new(0.5, 0.5, 0.0).unwrap(),
            landing: Vec::new(),
            bounce_speed: 0.0,
        }
    }

    /// Each body turned whole about its centre by its turn: A's point ends where its start,
    /// moved by `θ × r`, and the bend put it (to 1e-15 m), against B's likewise; a turn of 2
    /// mrad bends by `½ θ × (θ × r)` but for the third order's `θ/3` of it; no turn, no bend.
    #[test]
    fn the_bend_is_what_the_turn_adds_to_the_straight_line() {
        let contact = contact();
        let witness = Witness::at(&contact, &contact.frame.origin, 0.002);
        let turns = Turns {
            a: Vector3::new(0.9, -1.4, 0.6),
            b: Vector3::new(-0.2, 0.1, 0.3),
        };
        let end = |turn: &Vector3<f64>, centre: Point3<f64>, point: Point3<f64>| {
            centre + UnitQuaternion::from_scaled_axis(*turn) * (point - centre)
        };
        let straight = |turn: &Vector3<f64>, centre: Point3<f64>, point: Point3<f64>| {
            point + turn.cross(&(point - centre))
        };
        let moved = (end(&turns.a, contact.centre_a, witness.a)
            - straight(&turns.a, contact.centre_a, witness.a))
            - (end(&turns.b, contact.centre_b, witness.b)
                - straight(&turns.b, contact.centre_b, witness.b));
        assert!((turns.bend(&contact, &witness) - moved).norm() < 1e-15);
        let small = Turns {
            a: turns.a * 1e-3,
            b: turns.b * 1e-3,
        };
        let half = |turn: &Vector3<f64>, arm: Vector3<f64>| turn.cross(&turn.cross(&arm)) * 0.5;
        let second_order = half(&small.a, witness.a - contact.centre_a)
            - half(&small.b, witness.b - contact.centre_b);
        let error = (small.bend(&contact, &witness) - second_order).norm();
        assert!(
            error < 1e-3 * second_order.norm(),
            "{error} of {second_order}"
        );
        let none = Turns::default().bend(&contact, &witness);
        assert_eq!(none, Vector3::zeros());
    }
}
