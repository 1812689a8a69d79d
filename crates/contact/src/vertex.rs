//! The vertex model (the paper's baseline, Springhead's `PHContactPoint`): one point constraint
//! per support-polygon vertex, no torque rows. Each vertex is its own 3-row block
//! (normal, t1, t2), so a Gauss–Seidel sweep costs O(rows).

use nalgebra::{Point2, Vector3};
use tatami_lcp::{Block, Problem, Row};

use crate::jacobian::{face_weld, friction_motion, point_jacobian};
use crate::target::normal_target;
use crate::{Contact, ContactProjection, ContactSettings, PointFriction};

/// Rows per support vertex.
pub const ROWS_PER_VERTEX: usize = 3;

/// Appends one block per support vertex and each row's penetration bias to `biases`. The
/// contact must be validated.
pub(crate) fn build(
    contact: &Contact,
    dt: f64,
    settings: &ContactSettings,
    problem: &mut Problem<ContactProjection>,
    biases: &mut Vec<f64>,
) {
    let weld = face_weld(contact, &problem.bodies, dt, settings.slip_threshold);
    for (vertex, &depth) in contact.support.vertices().iter().zip(&contact.depths) {
        let at = (vertex, depth, contact.bounce_speed);
        build_point(contact, at, weld.as_ref(), dt, settings, problem, biases);
    }
}

/// Appends the 3-row block of one point of `contact`'s plane, `vertex` in its frame, at `depth`,
/// whose normal row bounces at `bounce_speed` once it meets the other body
/// ([`Contact::bounce_speed`]: the contact's for a point of its support, 0 for the face model's
/// landing blocks, which catch a turn and bounce on their own approach alone). A point of a
/// face resting on a face, given the pair's `weld`, has its friction rows keep the two bodies'
/// material points together over the step while they stick ([`friction_motion`]).
pub(crate) fn build_point(
    contact: &Contact,
    (vertex, depth, bounce_speed): (&Point2<f64>, f64, f64),
    weld: Option<&Vector3<f64>>,
    dt: f64,
    settings: &ContactSettings,
    problem: &mut Problem<ContactProjection>,
    biases: &mut Vec<f64>,
) {
    let frame = &contact.frame;
    let p = frame.to_world(vertex);
    let (normal_speed, slip, weld) =
        friction_motion(contact, &problem.bodies, &p, weld, settings.slip_threshold);
    let start = problem.rows.len();
    let target = normal_target(
        depth,
        normal_speed,
        bounce_speed,
        contact.material.restitution,
        dt,
        settings,
    );
    for (direction, target) in [
        (frame.normal, target.velocity),
        (frame.tangent1, weld.dot(&frame.tangent1)),
        (frame.tangent2, weld.dot(&frame.tangent2)),
    ] {
        problem.rows.push(Row {
            jacobian: point_jacobian(contact, &p, &direction),
            target,
            impulse: 0.0,
        });
    }
    biases.extend([target.bias, 0.0, 0.0]);
    problem.blocks.push(Block {
        body_a: contact.body_a,
        body_b: contact.body_b,
        rows: start..start + ROWS_PER_VERTEX,
        projection: ContactProjection::Point(PointFriction {
            coefficient: contact.material.friction(slip, settings.slip_threshold),
            cone: settings.friction_cone,
        }),
    });
}
