//! The vertex model (the paper's baseline, Springhead's `PHContactPoint`): one point constraint
//! per support-polygon vertex, no torque rows. Each vertex is its own 3-row block
//! (normal, t1, t2), so a Gauss–Seidel sweep costs O(rows).
//!
//! A contact's landing points ([`Contact::landing`]: a cylinder's rim beside the one rim point
//! it rests on, a turning polyhedron's vertices beside its touching one) get such blocks too,
//! as under the face model ([`crate::face`]): each may come down to the support's deepest
//! level within the step and no further. Without them a cylinder landing on one rim point, or
//! dropped tilted onto another's cap, turned about that point and sank the rim beside it: a
//! stack of three 3 cm cylinders dropped 3 mm at 60 Hz went through the floor.

use nalgebra::{Point2, Vector3};
use tatami_lcp::{Block, Row};

use crate::jacobian::{Witness, face_weld, friction_motion, point_jacobian};
use crate::target::normal_target;
use crate::turns::{bent, friction_bend};
use crate::{Contact, ContactProjection, ContactRows, ContactSettings, PointFriction, Turns};

/// Rows per support vertex.
pub const ROWS_PER_VERTEX: usize = 3;

/// Appends one block per support vertex, then one per landing point ([`build_landing`]), and
/// each row's penetration bias to `out`. The contact must be validated.
pub(crate) fn build(
    contact: &Contact,
    (dt, turns): (f64, &Turns),
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) {
    build_support(contact, (dt, turns), settings, out);
    let landing = contact.landing.iter().map(|l| (&l.point, &l.depth));
    build_landing(contact, landing, (dt, turns), settings, out);
}

/// Appends one block per support vertex and each row's penetration bias to `out` (the face
/// model's block for a point support too).
pub(crate) fn build_support(
    contact: &Contact,
    (dt, turns): (f64, &Turns),
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) {
    let weld = face_weld(contact, out.bodies, dt, settings.slip_threshold);
    for (vertex, &depth) in contact.support.vertices().iter().zip(&contact.depths) {
        let at = (vertex, depth, contact.bounce_speed);
        build_point(contact, at, weld.as_ref(), (dt, turns), settings, out);
    }
}

/// Appends a 3-row block for each of `points` (plane coordinates and depth, a gap when
/// negative), whose normal row lets the point come down to `contact`'s deepest level in this
/// step and no further; it bounces on its own approach alone. The landing points of every
/// model, and the face model's tipping vertices.
pub(crate) fn build_landing<'a>(
    contact: &Contact,
    points: impl Iterator<Item = (&'a Point2<f64>, &'a f64)>,
    (dt, turns): (f64, &Turns),
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) {
    let deepest = landing_level(contact.depth());
    for (point, &depth) in points {
        let gap = (depth - deepest).min(0.0);
        build_point(contact, (point, gap, 0.0), None, (dt, turns), settings, out);
    }
}

/// The level (depth, m) a landing block's point may come down to within the step: the support's
/// `level` where the bodies overlap there, the other body's surface where they are still
/// apart. A speculative contact's support has a gap too, which its own rows may close in the
/// step: measured from the support's level instead, the gap of a cube's far corners 0.5 m
/// behind a face 0.7 m from a wall was 0.5 m, and a cube thrown face first at the wall at
/// 60 m/s (1 m a step) was held to 30 m/s by them, stopped 0.19 m short and sent spinning.
pub(crate) fn landing_level(level: f64) -> f64 {
    level.max(0.0)
}

/// Appends the 3-row block of one point of `contact`'s plane, `vertex` in its frame, at `depth`,
/// whose normal row bounces at `bounce_speed` once it meets the other body
/// ([`Contact::bounce_speed`]: the contact's for a point of its support, 0 for the landing
/// blocks, which catch a turn and bounce on their own approach alone). A point of a
/// face resting on a face, given the pair's `weld`, has its friction rows keep the two bodies'
/// material points together over the step while they stick ([`friction_motion`]); without
/// one, they and the normal row take off the points' bend over the step, the bodies turning
/// by `turns` ([`crate::turns`]).
pub(crate) fn build_point(
    contact: &Contact,
    (vertex, depth, bounce_speed): (&Point2<f64>, f64, f64),
    weld: Option<&Vector3<f64>>,
    (dt, turns): (f64, &Turns),
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) {
    let frame = &contact.frame;
    let witness = Witness::at(contact, &frame.to_world(vertex), depth);
    let (normal_speed, slip, weld_target) =
        friction_motion(contact, out.bodies, &witness, weld, settings.slip_threshold);
    let bend = turns.bend_at(contact, &witness, (depth, normal_speed), settings);
    let friction_bend = friction_bend(weld.is_some(), bend);
    let start = out.rows.len();
    let target = normal_target(
        depth,
        normal_speed,
        bounce_speed,
        contact.material.restitution,
        dt,
        settings,
    );
    for (direction, target, bend) in [
        (frame.normal, target.velocity, &bend),
        (
            frame.tangent1,
            weld_target.dot(&frame.tangent1),
            &friction_bend,
        ),
        (
            frame.tangent2,
            weld_target.dot(&frame.tangent2),
            &friction_bend,
        ),
    ] {
        out.rows.push(Row {
            jacobian: point_jacobian(contact, &witness, &direction),
            target: bent(target, &direction, bend, dt),
            impulse: 0.0,
        });
    }
    out.biases.extend([target.bias, 0.0, 0.0]);
    out.blocks.push(Block {
        body_a: contact.body_a,
        body_b: contact.body_b,
        rows: start..start + ROWS_PER_VERTEX,
        projection: ContactProjection::Point(PointFriction {
            coefficient: contact.material.friction(slip, settings.slip_threshold),
            cone: settings.friction_cone,
        }),
    });
}
