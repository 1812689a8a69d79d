//! Collision: broad phase, parry's contact normal, support polygons with their feature ids,
//! written into the persistent [`ContactSet`]. Plain data in, the set out, so it can be run and
//! timed alone; a pair neither of whose bodies moved keeps its contact (see
//! [`ContactSet::keep`]).

use nalgebra::Vector3;
use tatami_contact::{Contact, Material};
use tatami_lcp::BodyId;

use crate::body::Body;
use crate::broad_phase::overlapping_pairs;
use crate::contact_set::ContactSet;
use crate::parry_bridge::{self, Collider};
use crate::support::{FeaturePoint, Outline, support};

/// Reused buffers of the collision stage.
#[derive(Debug, Default, Clone)]
pub(crate) struct CollisionWorkspace {
    boxes: Vec<(Vector3<f64>, Vector3<f64>)>,
    is_static: Vec<bool>,
    order: Vec<usize>,
    pairs: Vec<(usize, usize)>,
    feature_a: Vec<FeaturePoint>,
    feature_b: Vec<FeaturePoint>,
}

/// A body's collision data, built once when the body is added.
#[derive(Debug, Clone)]
pub(crate) struct BodyGeometry {
    pub collider: Collider,
    pub outline: Outline,
}

/// Brings `set` up to date: one contact per pair closer than `margin`, ordered from the highest
/// to the lowest along `gravity`.
pub(crate) fn detect(
    bodies: &[Body],
    geometry: &[BodyGeometry],
    margin: f64,
    feature_angle: f64,
    gravity: &Vector3<f64>,
    workspace: &mut CollisionWorkspace,
    set: &mut ContactSet,
) {
    set.begin(margin, feature_angle);
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
        .extend(bodies.iter().map(|b| !b.is_dynamic()));
    overlapping_pairs(
        &workspace.boxes,
        &workspace.is_static,
        &mut workspace.order,
        &mut workspace.pairs,
    );
    for &(i, j) in &workspace.pairs {
        let (a, b) = (&bodies[i], &bodies[j]);
        let now = [(a.centre, a.rotation), (b.centre, b.rotation)];
        let sizes = [geometry[i].outline.size(), geometry[j].outline.size()];
        if set.keep((i, j), [&now[0], &now[1]], sizes) {
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
        set.update(contact, s.features, now);
    }
    set.end(gravity);
}

/// The pair's material: the average of the two bodies' coefficients.
fn combine(a: &Body, b: &Body) -> Material {
    // Halves first: the sum of two coefficients of 1e308 overflows to ∞.
    let average = |x: f64, y: f64| 0.5 * x + 0.5 * y;
    Material {
        static_friction: average(a.static_friction, b.static_friction),
        kinetic_friction: average(a.kinetic_friction, b.kinetic_friction),
        restitution: average(a.restitution, b.restitution),
    }
}
