//! Collision: broad phase, parry's contact normal, support polygons, and the contacts the
//! contact models consume. Plain data in, plain data out, so it can be run and timed alone; the
//! workspace keeps each pair's contact, reused while neither body moves by more than
//! [`REUSE_TOLERANCE`].

use std::collections::HashMap;

use nalgebra::{Point3, UnitQuaternion, Vector3};
use tatami_contact::{Contact, Material};
use tatami_lcp::BodyId;

use crate::body::Body;
use crate::broad_phase::overlapping_pairs;
use crate::parry_bridge::{self, Collider};
use crate::support::{Outline, support};

/// Reused buffers of the collision stage.
#[derive(Debug, Default, Clone)]
pub(crate) struct CollisionWorkspace {
    boxes: Vec<(Vector3<f64>, Vector3<f64>)>,
    is_static: Vec<bool>,
    order: Vec<usize>,
    pairs: Vec<(usize, usize)>,
    feature_a: Vec<Point3<f64>>,
    feature_b: Vec<Point3<f64>>,
    /// Each touching pair's contact with the poses it was computed at, and the settings.
    cache: HashMap<(usize, usize), Cached>,
    cached_with: (f64, f64),
}

/// Largest motion of either body (m; a turn counts as rad × the body's size) since a pair's
/// contact was computed for it to be reused: far below any depth that matters (the slop is
/// 2 mm), and above the round-off by which a resting body drifts.
pub(crate) const REUSE_TOLERANCE: f64 = 1e-9;

/// A contact and where its two bodies were when it was computed.
#[derive(Debug, Clone)]
struct Cached {
    contact: Contact,
    poses: [(Point3<f64>, UnitQuaternion<f64>); 2],
    /// Whether the pair was met by the current call (stale entries are dropped at its end).
    seen: bool,
}

/// Whether `body` is within [`REUSE_TOLERANCE`] of `pose`.
fn still_at(body: &Body, size: f64, pose: &(Point3<f64>, UnitQuaternion<f64>)) -> bool {
    (body.centre - pose.0).norm() <= REUSE_TOLERANCE
        && body.rotation.angle_to(&pose.1) * size.max(1.0) <= REUSE_TOLERANCE
}

/// A body's collision data, built once when the body is added.
#[derive(Debug, Clone)]
pub(crate) struct BodyGeometry {
    pub collider: Collider,
    pub outline: Outline,
}

/// Replaces `contacts` with one contact per touching pair (closer than `margin`).
pub(crate) fn detect(
    bodies: &[Body],
    geometry: &[BodyGeometry],
    margin: f64,
    feature_angle: f64,
    workspace: &mut CollisionWorkspace,
    contacts: &mut Vec<Contact>,
) {
    contacts.clear();
    if workspace.cached_with != (margin, feature_angle) {
        workspace.cache.clear();
        workspace.cached_with = (margin, feature_angle);
    }
    let poses: Vec<_> = bodies
        .iter()
        .map(|b| parry_bridge::pose(&b.position(), &b.rotation))
        .collect();
    workspace.boxes.clear();
    workspace.boxes.extend(
        geometry
            .iter()
            .zip(&poses)
            .map(|(g, pose)| g.collider.aabb(pose, margin)),
    );
    workspace.is_static.clear();
    workspace
        .is_static
        .extend(bodies.iter().map(Body::is_fixed));
    overlapping_pairs(
        &workspace.boxes,
        &workspace.is_static,
        &mut workspace.order,
        &mut workspace.pairs,
    );
    for &(i, j) in &workspace.pairs {
        let (a, b) = (&bodies[i], &bodies[j]);
        // A pair that has not moved since its contact was computed keeps it: the same input
        // gives the same output, and a resting stack's pairs are computed once.
        if let Some(cached) = workspace.cache.get_mut(&(i, j))
            && still_at(a, geometry[i].outline.size(), &cached.poses[0])
            && still_at(b, geometry[j].outline.size(), &cached.poses[1])
        {
            cached.seen = true;
            contacts.push(cached.contact.clone());
            continue;
        }
        let Some(normal) = parry_bridge::contact_normal(
            &geometry[i].collider,
            &poses[i],
            &geometry[j].collider,
            &poses[j],
            margin,
        ) else {
            continue;
        };
        geometry[i].outline.feature(
            &a.position(),
            &a.rotation,
            &-normal,
            feature_angle,
            &mut workspace.feature_a,
        );
        geometry[j].outline.feature(
            &b.position(),
            &b.rotation,
            &normal,
            feature_angle,
            &mut workspace.feature_b,
        );
        let Some(s) = support(&workspace.feature_a, &workspace.feature_b, &normal) else {
            continue;
        };
        let contact = Contact {
            body_a: BodyId(i),
            body_b: BodyId(j),
            centre_a: a.centre,
            centre_b: b.centre,
            frame: s.frame,
            support: s.polygon,
            depths: s.depths,
            material: combine(a, b),
        };
        workspace.cache.insert(
            (i, j),
            Cached {
                contact: contact.clone(),
                poses: [(a.centre, a.rotation), (b.centre, b.rotation)],
                seen: true,
            },
        );
        contacts.push(contact);
    }
    workspace
        .cache
        .retain(|_, cached| std::mem::take(&mut cached.seen));
}

/// The pair's material: the average of the two bodies' coefficients.
fn combine(a: &Body, b: &Body) -> Material {
    Material {
        static_friction: 0.5 * (a.static_friction + b.static_friction),
        kinetic_friction: 0.5 * (a.kinetic_friction + b.kinetic_friction),
        restitution: 0.5 * (a.restitution + b.restitution),
    }
}
