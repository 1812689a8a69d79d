//! Collision: broad phase, parry's contact normal, support polygons with their feature ids,
//! written into the persistent [`ContactSet`]. Plain data in, the set out, so it can be run and
//! timed alone; a pair neither of whose bodies moved keeps its contact, one whose bodies barely
//! slid or turned against each other has it carried with them (see [`ContactSet::refresh`],
//! [`crate::carry`]), and a pair found apart along an axis fixed in one body is not tested again
//! while its bodies could not have closed the gap ([`crate::apart`]).

use nalgebra::Vector3;
use tatami_contact::{Contact, Material};
use tatami_lcp::BodyId;

use crate::WorldSettings;
use crate::apart::{Apart, Placement};
use crate::body::Body;
use crate::broad_phase::SweepAndPrune;
use crate::carry::CarryBounds;
use crate::contact_set::{Computed, ContactSet, Recycled};
use crate::parallel;
use crate::parry_bridge::{self, Cast, Collider};
use crate::rows;
use crate::shape::Shape;
use crate::speculative::Travel;
use crate::support::{Feature, FeatureAngle, Outline, Support, VertexIds, support};
use crate::tolerances;

/// Reused buffers of the collision stage.
#[derive(Debug, Default, Clone)]
pub(crate) struct CollisionWorkspace {
    boxes: Vec<(Vector3<f64>, Vector3<f64>)>,
    is_static: Vec<bool>,
    broad_phase: SweepAndPrune,
    pairs: Vec<(usize, usize)>,
    /// Each body's pose, as parry takes it.
    poses: Vec<parry3d_f64::math::Pose>,
    /// Pairs the contact set does not hold yet, each with its contact once computed (or why
    /// not): kept between steps, as a pile's 2,000 new pairs a step take over a megabyte, which
    /// fresh allocations mapped page by page every step (page faults were 0.3% of the step).
    new: Vec<((usize, usize), Found)>,
    /// Contacts the last pass computed (moved or new pairs).
    last_computed: usize,
    features: Features,
    /// Where each body is, for the tests of motion of the pairs held and kept apart.
    pub(crate) placements: Vec<Placement>,
}

impl CollisionWorkspace {
    /// Whether the next pass brings the held pairs up to date on every core.
    pub(crate) fn next_pass_on_every_core(&self) -> bool {
        self.last_computed >= PARALLEL_PASS
    }

    /// The pairs whose boxes, grown by the margin and by how far their points may move in the
    /// step, overlapped in the last pass: every pair that may meet in the step.
    pub(crate) fn pairs(&self) -> &[(usize, usize)] {
        &self.pairs
    }
}

/// Scratch for the touching features of one pair's two bodies.
#[derive(Debug, Default, Clone)]
struct Features {
    a: Feature,
    b: Feature,
}

/// Fewest pairs to compute worth sharing with the thread pool ([`parallel::for_each`]): below
/// this the pairs take less than a helper thread needs to start (a few µs while the pool is
/// busy, far more once it sleeps; the loop ends only when every helper has started), at about
/// 1 µs a box pair.
const PARALLEL_PAIRS: usize = 32;

/// Fewest contacts computed in the last pass for the next to recompute the held pairs on
/// every core beside the broad phase ([`ContactSet::refresh`]): the 1000-cube pile computes
/// 1,500 and more a step; the 210-cube pyramid, a few dozen, would wait longer for a helper to
/// wake than the pairs take.
const PARALLEL_PASS: usize = 256;

/// A bouncing pair's speculative contact takes the normal where its bodies meet
/// ([`meet_within`]) when the two differ by more than about 45 µrad (this, in cosine): a face
/// meeting a face gives the same normal to rounding, and its support is not found again.
const MEETING_NORMAL_COS: f64 = 1.0 - 1e-9;

/// Widest feature angle a pair's turn in a step may grow it to (rad).
const MAX_FEATURE_ANGLE: f64 = 0.35;

/// What collision found of a pair.
#[derive(Debug, Clone)]
#[expect(
    clippy::large_enum_variant,
    reason = "held in a list reused across steps; a box would allocate for every contact"
)]
enum Found {
    /// Its contact.
    Touching(Computed),
    /// Apart along an axis of one body: kept apart, untested, until its bodies could have
    /// closed the gap ([`ContactSet::keep_apart`]).
    Apart(Apart),
    /// No contact, and no axis to keep the pair apart by (or not found yet).
    Nothing,
}

/// A body's collision data, built once when the body is added.
#[derive(Debug, Clone)]
pub(crate) struct BodyGeometry {
    pub collider: Collider,
    pub outline: Outline,
}

/// What collision takes of the world's settings.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CollisionSettings {
    /// Bodies closer than this (m) get a contact.
    pub margin: f64,
    /// Faces tilted by less than this (rad) from the contact plane count as flat.
    pub feature_angle: f64,
    /// Whether support vertices are named (for the vertex and patch models' warm start).
    pub ids: VertexIds,
    /// How far a contact is carried with its bodies before it is found afresh; `None` finds
    /// every moved pair's afresh (the named models, see [`crate::carry`]).
    pub carry: Option<CarryBounds>,
    /// How far back (m) a landing point may stand ([`tatami_contact::Contact::landing`]): the
    /// margin.
    pub landing_band: f64,
}

impl CollisionSettings {
    /// What collision takes of the world's `settings`.
    pub(crate) fn of(settings: &WorldSettings) -> Self {
        let ids = VertexIds::for_model(settings.model);
        // Only contacts whose vertices go unnamed (the face model's) are carried: the named
        // models' rows are warm-started vertex by vertex, and carried contacts let the patch
        // model's leaning stack drift 2.6 mm (0.4 mm found afresh; its bound is 1 mm).
        let carry = (ids == VertexIds::Unnamed).then(|| {
            CarryBounds::new(
                settings.contact.slop,
                settings.feature_angle,
                settings.contact_margin,
            )
        });
        Self {
            margin: settings.contact_margin,
            feature_angle: settings.feature_angle,
            ids,
            carry,
            landing_band: settings.contact_margin,
        }
    }
}

/// Brings `set` up to date for a step of `dt`: one contact per pair closer than the margin
/// grown by how far the pair may close in the step ([`crate::speculative`]), ordered from the
/// highest to the lowest along `gravity`, its support vertices named as the settings ask.
/// Returns the pool's helpers kept spinning ([`parallel::Warm`]) when the set holds enough pairs
/// for its rows to be worth building on every core ([`rows::worth_every_core`]), so that the
/// rows stage finds them awake (a helper woken only at the rows took longer to start than the
/// 210-cube pyramid's rows take): from the pass's last loop on every core, or, for a pass on
/// the calling thread alone (a scene at rest), from its start if the set is large
/// ([`rows::worth_waking`]).
pub(crate) fn detect(
    bodies: &[Body],
    geometry: &[BodyGeometry],
    settings: &CollisionSettings,
    gravity: &Vector3<f64>,
    dt: f64,
    workspace: &mut CollisionWorkspace,
    set: &mut ContactSet,
) -> Option<parallel::Warm> {
    let &CollisionSettings {
        margin,
        feature_angle,
        ids,
        carry,
        landing_band,
    } = settings;
    set.begin(margin, feature_angle, ids, carry);
    let base_angle = feature_angle;
    let feature_angle = FeatureAngle::new(feature_angle);
    let plain = Reach::plain(margin, dt, gravity);
    let on_every_core = workspace.next_pass_on_every_core();
    let CollisionWorkspace {
        boxes,
        is_static,
        broad_phase,
        pairs,
        poses,
        new,
        last_computed,
        features,
        placements,
    } = workspace;
    poses.clear();
    poses.extend(
        bodies
            .iter()
            .map(|b| parry_bridge::pose(&b.position(), &b.rotation)),
    );
    let poses = &*poses;
    placements.clear();
    placements.extend(bodies.iter().zip(geometry).map(|(body, g)| {
        let size = g.outline.size();
        let reach = size + body.com_offset().norm();
        Placement {
            pose: (body.centre, body.rotation),
            size,
            reach,
            travel: Travel::of(body, reach, dt),
            round: matches!(body.shape(), Shape::Sphere { .. } | Shape::Cylinder { .. }),
            thickness: body.thickness,
        }
    }));
    let placements = &*placements;
    let find = |features: &mut Features, pair: (usize, usize), recycled: Recycled| {
        let reach = speculative((geometry, placements), pair, plain, base_angle);
        contact_of(
            bodies,
            geometry,
            poses,
            pair,
            (&reach, landing_band),
            reach.angle.as_ref().unwrap_or(&feature_angle),
            ids,
            features,
            recycled,
        )
    };
    let compute = |features: &mut Features, pair: (usize, usize), recycled: Recycled| match find(
        features, pair, recycled,
    ) {
        Found::Touching(computed) => Some(computed),
        Found::Apart(_) | Found::Nothing => None,
    };
    // Stages: the pairs the set holds are brought up to date (recomputed in place where a body
    // moved) while the broad phase finds the overlapping pairs and meets them, on every core
    // when the last pass computed many (`on_every_core`; each contact is a pure function of
    // the two bodies, so the result does not depend on the number of threads); then the new
    // pairs are computed, and join the set in pair order.
    // A large set's rows are built on every core (`crate::rows`): when this pass keeps to the
    // calling thread, the pool's helpers are woken now, so they are awake by then.
    let mut warm = (!on_every_core && rows::worth_waking(set)).then(parallel::Warm::start);
    // A body's box grows by the margin and by how far its points may move in the step.
    let pad = |placed: &Placement| margin + placed.travel.farthest();
    let recomputed = set.refresh(
        on_every_core,
        placements,
        Features::default,
        compute,
        |meeting| {
            boxes.clear();
            boxes.extend(
                (geometry.iter().zip(poses).zip(placements))
                    .map(|((g, pose), placed)| g.collider.aabb(pose, pad(placed))),
            );
            is_static.clear();
            is_static.extend(bodies.iter().map(|b| !b.is_dynamic()));
            broad_phase.overlapping_pairs(boxes, is_static, pairs);
            new.clear();
            new.extend(
                pairs
                    .iter()
                    .filter(|&&pair| !meeting.meet(pair))
                    .map(|&pair| (pair, Found::Nothing)),
            );
        },
    );
    *last_computed = recomputed + new.len();
    let compute_into = |features: &mut Features, (pair, out): &mut ((usize, usize), _)| {
        *out = find(features, *pair, Recycled::default());
    };
    let new_on_every_core = new.len() >= PARALLEL_PAIRS;
    if new_on_every_core {
        drop(warm.take());
        parallel::for_each(new, Features::default, compute_into);
    } else {
        for slot in new.iter_mut() {
            compute_into(features, slot);
        }
    }
    for (pair, found) in new.drain(..) {
        match found {
            Found::Touching(computed) => set.insert(computed),
            Found::Apart(apart) => set.keep_apart(pair, apart),
            Found::Nothing => {}
        }
    }
    // Helpers spinning since the start, or awake from a loop, take the pairs kept apart while
    // this thread orders the set, and are kept spinning after it until the rows.
    let helpers_awake = warm.take().is_some() || on_every_core || new_on_every_core;
    set.end(gravity, helpers_awake);
    (helpers_awake && rows::worth_every_core(set.contacts().len())).then(parallel::Warm::start)
}

/// How far from each other a pair's contact is looked for in a pass ([`speculative`]).
#[derive(Debug, Clone, Copy)]
struct Reach {
    /// The pair's margin (m): the settings', held to its thinner body's thickness
    /// ([`tolerances::pair_margin`]).
    margin: f64,
    /// How far the pair may close in the step (m): a contact is looked for within the margin
    /// grown by this, and one found only beyond the margin stands if the bodies meet within
    /// the step.
    closing: f64,
    /// How far the bodies' turns in the step may move their points (m), together.
    turns: f64,
    /// The step (s).
    dt: f64,
    /// How fast gravity may close a gap on a fixed body (m/s², its magnitude).
    gravity: f64,
    /// The pair's feature angle, grown by its turn in the step, when it turns.
    angle: Option<FeatureAngle>,
}

impl Reach {
    /// The reach of a pair that neither closes nor turns in a step of `dt` under `gravity`:
    /// the margin alone.
    fn plain(margin: f64, dt: f64, gravity: &Vector3<f64>) -> Self {
        Self {
            margin,
            closing: 0.0,
            turns: 0.0,
            dt,
            gravity: gravity.norm(),
            angle: None,
        }
    }
}

/// Pair `(i, j)`'s reach: the pass's `plain` one (no closing, no angle of its own), its margin
/// and the feature angle `angle` grown by how far its bodies may close and turn against each
/// other in the step ([`crate::speculative`]), the margin first held to its thinner body's
/// thickness ([`tolerances::pair_margin`]). A pair with a cylinder keeps its feature angle: a
/// rolling cylinder turns by `v dt / r` a step, and its side line grown by that took in points
/// beside it, which braked a cylinder rolling down a ramp (2.96 m/s against the closed form's
/// 3.38). A bouncing pair lands first and bounces on the next step ([`crate::impact`]).
fn speculative(
    (geometry, placements): (&[BodyGeometry], &[Placement]),
    (i, j): (usize, usize),
    plain: Reach,
    angle: f64,
) -> Reach {
    let (a, b) = (&placements[i].travel, &placements[j].travel);
    let turning = a.turning(b);
    let rounded = geometry[i].collider.is_rounded() || geometry[j].collider.is_rounded();
    let thickness = [placements[i].thickness, placements[j].thickness];
    Reach {
        margin: tolerances::pair_margin(plain.margin, thickness),
        closing: a.closing(b),
        turns: a.turn + b.turn,
        // A turn under a tenth of the angle would change little, and costs the trigonometry.
        angle: (!rounded && turning > 0.1 * angle)
            .then(|| FeatureAngle::new((angle + turning).min(MAX_FEATURE_ANGLE))),
        ..plain
    }
}

/// How a pair may move in a step, for a speculative contact: each body at its velocity, or
/// stopped along the contact normal. A dynamic body may be stopped within the step by its
/// other contacts, and the other then closes on it at its own speed: a box falling onto the
/// floor with a box falling just above it, at the same speed and so not closing on it, was
/// stopped by the floor, and the upper box came down 16 mm in that step with no contact between
/// them (9 mm into the lower box, three 0.3 m boxes dropped 3 cm onto each other at 60 Hz).
/// Only the normal part of its velocity is stopped: a ball rolling on past where another falls
/// keeps out of its way, and gets no contact from where it is now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Motion {
    a_moves: bool,
    b_moves: bool,
}

impl Motion {
    /// Both bodies at their velocities, then each dynamic one stopped ([`Travel::held`]).
    fn of_pair(a: &Body, b: &Body) -> impl Iterator<Item = Self> {
        let both = Self {
            a_moves: true,
            b_moves: true,
        };
        let a_stopped = a.is_dynamic().then_some(Self {
            a_moves: false,
            ..both
        });
        let b_stopped = b.is_dynamic().then_some(Self {
            b_moves: false,
            ..both
        });
        [Some(both), a_stopped, b_stopped].into_iter().flatten()
    }

    /// `velocity`, or its part across `normal` when the body is stopped along it.
    fn along(moves: bool, velocity: Vector3<f64>, normal: &Vector3<f64>) -> Vector3<f64> {
        if moves {
            velocity
        } else {
            velocity - normal * velocity.dot(normal)
        }
    }
}

/// Whether a point of support `s` between bodies `a` and `b` closes its gap within the step
/// of `reach` as the bodies move under `motion`, the relative velocity gravity may add
/// included (when it pulls one of the bodies moving along the normal and not the other).
fn closes_in_step(a: &Body, b: &Body, s: &Support, reach: &Reach, motion: Motion) -> bool {
    let (dt, n) = (reach.dt, &s.frame.normal);
    let falls = |moves: bool, body: &Body| moves && body.is_dynamic();
    let pulled = if falls(motion.a_moves, a) != falls(motion.b_moves, b) {
        reach.gravity * dt
    } else {
        0.0
    };
    s.polygon
        .vertices()
        .iter()
        .zip(&s.depths)
        .any(|(vertex, &depth)| {
            let p = s.frame.to_world(vertex);
            let relative = Motion::along(motion.a_moves, a.velocity_at(&p), n)
                - Motion::along(motion.b_moves, b.velocity_at(&p), n);
            // `n` points from B into A: A closes on B against it.
            let closing = -relative.dot(n) + pulled;
            closing * dt >= -depth
        })
}

/// Whether bodies `a` and `b`, from their colliders' poses and moving on at their centres'
/// velocities under `motion` (stopped along `normal`), touch within the step, the most their
/// turns may move their points ([`Reach::turns`]) allowed for, and their normal where they
/// first do.
fn meet_within(
    (a, collider_a, pose_a): (&Body, &Collider, &parry3d_f64::math::Pose),
    (b, collider_b, pose_b): (&Body, &Collider, &parry3d_f64::math::Pose),
    (reach, motion, normal): (&Reach, Motion, &Vector3<f64>),
) -> Cast {
    let velocity_a = Motion::along(motion.a_moves, a.linear_velocity(), normal);
    let velocity_b = Motion::along(motion.b_moves, b.linear_velocity(), normal);
    parry_bridge::meet_within(
        (collider_a, pose_a, &velocity_a),
        (collider_b, pose_b, &velocity_b),
        reach.turns,
        reach.dt,
    )
}

/// The contact of pair `(i, j)` at the bodies' current poses, with its feature ids (if `ids`
/// asks) and the poses it was computed at; or, when the bodies are farther apart than `reach`
/// lets them be, the axis that shows it if one does. The contact's depths go into `recycled.depths`
/// (see [`support`]), and its normal is searched for from `recycled.normal`. Its landing
/// points are those standing back by at most `landing_band` (m; 0 for none).
#[expect(
    clippy::too_many_arguments,
    reason = "the pass's read-only inputs, the thread's scratch and what the old contact left"
)]
fn contact_of(
    bodies: &[Body],
    geometry: &[BodyGeometry],
    poses: &[parry3d_f64::math::Pose],
    (i, j): (usize, usize),
    (reach, landing_band): (&Reach, f64),
    feature_angle: &FeatureAngle,
    ids: VertexIds,
    features: &mut Features,
    Recycled {
        depths,
        normal: hint,
        keep_normal,
    }: Recycled,
) -> Found {
    let (a, b) = (&bodies[i], &bodies[j]);
    let found_at = [(a.centre, a.rotation), (b.centre, b.rotation)];
    let margin = reach.margin + reach.closing;
    let normal = match parry_bridge::contact_normal(
        &geometry[i].collider,
        &poses[i],
        &geometry[j].collider,
        &poses[j],
        margin,
        hint.as_ref(),
    ) {
        Ok(normal) => normal,
        Err(Some(gap)) => {
            return Found::Apart(Apart {
                gap,
                poses: found_at,
            });
        }
        Err(None) => return Found::Nothing,
    };
    // A landing to be bounced is bounced along the normal it landed on, the impact's: two
    // balls sliding past each other as they land turn their normal by the step's sliding.
    let normal = match (keep_normal, hint) {
        (true, Some(landed_on)) => landed_on,
        _ => normal,
    };
    // Under the face model, which reads landing points, a polyhedron's vertices that the
    // pair's closing in the step, or the turn an impact turns it into, may bring down.
    let turn_band = if landing_band > 0.0 && reach.closing > reach.margin {
        reach.margin + reach.closing
    } else {
        0.0
    };
    // The touching features along `normal` (from B into A), their landing points, and the
    // support they make.
    let support_with =
        |normal: &Vector3<f64>, features: &mut Features, depths: Vec<f64>, turn_band: f64| {
            for (k, outward, feature) in
                [(i, -normal, &mut features.a), (j, *normal, &mut features.b)]
            {
                let (outline, body) = (&geometry[k].outline, &bodies[k]);
                let (origin, rotation) = (body.position(), body.rotation);
                outline.feature(&origin, &rotation, &outward, feature_angle, feature);
                let bands = (landing_band, turn_band);
                outline.landing(&origin, &rotation, &outward, bands, feature);
            }
            let mut s = support(&features.a, &features.b, normal, depths, ids)?;
            // No point of B stands out along the normal beyond B's support plane, nor of A
            // below A's: a depth past their overlap is a feature's plane taken past its points
            // (a hull's faces within the feature angle, fitted as one plane).
            let (b_top, a_bottom) = (
                geometry[j].collider.reach_along(&poses[j], normal),
                geometry[i].collider.reach_along(&poses[i], &-normal),
            );
            if let (Some(b_top), Some(a_bottom)) = (b_top, a_bottom) {
                // Past it by more than the offsets' rounding: a face resting flat, its depths
                // that overlap to rounding, keeps them as they are.
                let deepest = b_top + a_bottom;
                let past = deepest + 1e-9 * (1.0 + b_top.abs() + a_bottom.abs());
                for depth in s.depths.iter_mut().filter(|d| **d > past) {
                    *depth = deepest;
                }
            }
            Some(s)
        };
    let support_along = |normal: &Vector3<f64>, features: &mut Features, depths: Vec<f64>| {
        support_with(normal, features, depths, turn_band)
    };
    let Some(mut s) = support_along(&normal, features, depths) else {
        return Found::Nothing;
    };
    // A pair in deeper than its margin has vertices inside the other body besides its touching
    // feature: those standing back from the feature by less than its depth are landing points
    // too, or the body turns about its feature further in.
    let deepest = s.depths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if landing_band > 0.0 && deepest > reach.margin.max(turn_band) {
        let depths = std::mem::take(&mut s.depths);
        match support_with(&normal, features, depths, deepest) {
            Some(deep) => s = deep,
            None => return Found::Nothing,
        }
    }
    // A normal found on a cylinder's rounded core reaches past the margin of the true shapes.
    let rounded = geometry[i].collider.is_rounded() || geometry[j].collider.is_rounded();
    if rounded && s.depths.iter().all(|&d| d < -margin) {
        return Found::Nothing;
    }
    // Found beyond the margin, the contact is speculative. It stands only if a support point
    // closes its gap in the step at the bodies' velocities (the step's gravity added), else
    // its rows could do nothing; and only if the bodies meet within the step, else the contact
    // plane of features that pass each other by would stop them (a ball at 10 m/s passing
    // 1 cm over a box's edge left it at 8.2 m/s, turned 7°). A bouncing pair's normal is then
    // the one where they meet, which its bounce keeps ([`crate::impact`]): the normal between
    // the poses the step starts at is not the impact's (two balls 30° off centre at 10 m/s
    // left 2.9% off the closed form's velocities). Other pairs keep theirs: on a pile of
    // mixed shapes that normal left a contact 12 mm deep for seconds (not chased).
    let speculative = s.depths.iter().all(|&d| d < -reach.margin);
    if speculative {
        // The first way the pair may move in which it closes and meets, or a miss.
        let cast = Motion::of_pair(a, b)
            .filter(|&motion| closes_in_step(a, b, &s, reach, motion))
            .map(|motion| {
                meet_within(
                    (a, &geometry[i].collider, &poses[i]),
                    (b, &geometry[j].collider, &poses[j]),
                    (reach, motion, &s.frame.normal),
                )
            })
            .find(|cast| *cast != Cast::Miss);
        let Some(cast) = cast else {
            return Found::Nothing;
        };
        let bouncing = a.restitution > 0.0 || b.restitution > 0.0;
        match cast {
            Cast::Miss => return Found::Nothing,
            Cast::Meet(Some(at_impact))
                if bouncing && at_impact.dot(&normal) < MEETING_NORMAL_COS =>
            {
                let depths = std::mem::take(&mut s.depths);
                match support_along(&at_impact, features, depths) {
                    Some(met) => s = met,
                    None => return Found::Nothing,
                }
            }
            Cast::Meet(_) => {}
        }
    }
    // The polygon's mean distance from its centroid (`r̄`, exact area moments with a logarithm
    // an edge), which the face model's rows read for every face contact, is found here on
    // every core and kept in the polygon, instead of in the rows' serial stage (a fifth of it
    // on the 1000-cube pile: 0.65–0.76 → 0.52–0.54 ms on one thread); the other models do not
    // read it.
    s.polygon.centroid_mean_distance();
    let contact = Contact {
        body_a: BodyId(i),
        body_b: BodyId(j),
        centre_a: a.centre,
        centre_b: b.centre,
        frame: s.frame,
        support: s.polygon,
        depths: s.depths,
        material: combine(a, b),
        landing: s.landing,
        // Handed on from the pair's last contact by the contact set ([`crate::impact`]).
        bounce_speed: 0.0,
    };
    Found::Touching((contact, s.features, found_at))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dropped::{Random, mixed_shape};
    use crate::{BodyDesc, Shape, World};
    use nalgebra::UnitQuaternion;
    use std::collections::HashSet;

    /// `count` shapes of [`mixed_shape`] (the `kind(k)`-th of its cycle for the `k`-th body),
    /// turned at random and stacked 0.4 m apart over a 3 m square of an 8 m floor.
    fn dropped_heap(seed: u64, count: usize, kind: impl Fn(usize) -> usize) -> World {
        let mut random = Random::new(seed);
        let mut builder = World::builder()
            .body(BodyDesc::fixed(Shape::cuboid([8.0, 8.0, 1.0])).position([0.0, 0.0, -0.5]));
        for k in 0..count {
            let position = [
                random.between(-1.5, 1.5),
                random.between(-1.5, 1.5),
                0.5 + 0.4 * k as f64,
            ];
            let turn = UnitQuaternion::from_euler_angles(
                random.between(0.0, 3.0),
                random.between(0.0, 3.0),
                random.between(0.0, 3.0),
            );
            let shape = mixed_shape(&mut random, kind(k));
            builder = builder.body(BodyDesc::dynamic(shape).position(position).rotation(turn));
        }
        builder.build().expect("a valid scene")
    }

    /// Where the world's bodies' collision shapes are.
    fn poses_of(world: &World) -> Vec<parry3d_f64::math::Pose> {
        let pose = |b: &Body| parry_bridge::pose(&b.position(), &b.rotation);
        world.bodies.iter().map(pose).collect()
    }

    /// 48 mixed shapes (boxes, balls, cylinders, hulls) dropped in a heap: after every step's
    /// collision pass, every pair that a fresh test finds touching is in the contact set — the
    /// pairs kept apart without a test (see [`crate::apart`]) hide none — while the set keeps
    /// many pairs apart (about 24 a step).
    #[test]
    fn no_touching_pair_is_kept_apart() {
        let mut world = dropped_heap(11, 48, |k| k);
        let margin = world.settings.contact_margin;
        let angle = FeatureAngle::new(world.settings.feature_angle);
        let mut kept_apart = 0;
        for step in 0..300 {
            let dt = 1.0 / 60.0;
            let plain = Reach::plain(margin, dt, &world.gravity);
            world.prepare_step(dt).expect("collision");
            kept_apart += world.contact_set.kept_apart();
            let held: HashSet<(usize, usize)> =
                world.contacts().map(|c| (c.body_a.0, c.body_b.0)).collect();
            let poses = poses_of(&world);
            let mut features = Features::default();
            for i in 0..world.bodies.len() {
                for j in i + 1..world.bodies.len() {
                    if !world.bodies[i].is_dynamic() && !world.bodies[j].is_dynamic() {
                        continue;
                    }
                    let reach = speculative(
                        (&world.geometry, &world.collision_workspace.placements),
                        (i, j),
                        plain,
                        world.settings.feature_angle,
                    );
                    let found = contact_of(
                        &world.bodies,
                        &world.geometry,
                        &poses,
                        (i, j),
                        (&reach, CollisionSettings::of(&world.settings).landing_band),
                        reach.angle.as_ref().unwrap_or(&angle),
                        VertexIds::for_model(world.settings.model),
                        &mut features,
                        Recycled::default(),
                    );
                    assert!(
                        !matches!(found, Found::Touching(_)) || held.contains(&(i, j)),
                        "step {step}: pair ({i}, {j}) touches but is not in the set"
                    );
                }
            }
            world.step(dt).expect("a step");
        }
        // About 24 a step; half as many without the balls and cylinders kept apart.
        assert!(kept_apart >= 4_000, "{kept_apart} pairs kept apart in all");
    }

    /// Contacts carried with their bodies ([`crate::carry`]) against contacts found afresh at
    /// the same poses, every step of a heap of 40 boxes, balls and hulls turned at random,
    /// dropped onto a floor and settling: the normals within twice the carried turn's bound
    /// (an edge–edge normal turns with both edges), except a point contact's (two edges
    /// crossing nearly parallel have a normal, their cross product, that a turn of under 0.1°
    /// moved by 8° at the same 0.35 mm depth), the deepest depths within twice the slip
    /// bound (a carried depth is off by the slip times the slope of the surfaces where they
    /// touch; at a point two edges cross, and their crossing runs along them as they turn: a
    /// hull creeping past a box's edge 0.6–0.9 mm away was carried to within 0.15 mm of the gap
    /// found afresh, for a slip bound of 0.1 mm; a face's vertex clipped by the other face's
    /// edge runs along that edge likewise), and a pair found apart afresh held only
    /// while open nearly the margin. Cylinders are left out: their contact normal comes from a
    /// rounded core, which finds two rims crossing apart while the cylinders still overlap by
    /// a few millimetres, so a fresh contact is no reference there.
    #[test]
    fn carried_contacts_stay_near_the_contacts_found_afresh() {
        // `mixed_shape` cycles box, ball, cylinder, hull: no cylinder.
        let mut world = dropped_heap(12, 40, |k| [0, 1, 3][k % 3]);
        let margin = world.settings.contact_margin;
        let angle = FeatureAngle::new(world.settings.feature_angle);
        let bounds = CarryBounds::new(
            world.settings.contact.slop,
            world.settings.feature_angle,
            margin,
        );
        let (mut compared, mut moved) = (0, 0);
        for step in 0..400 {
            let dt = 1.0 / 60.0;
            let plain = Reach::plain(margin, dt, &world.gravity);
            world.prepare_step(dt).expect("collision");
            let poses = poses_of(&world);
            let mut features = Features::default();
            for held in world.contacts() {
                let pair = (held.body_a.0, held.body_b.0);
                let reach = speculative(
                    (&world.geometry, &world.collision_workspace.placements),
                    pair,
                    plain,
                    world.settings.feature_angle,
                );
                let found = contact_of(
                    &world.bodies,
                    &world.geometry,
                    &poses,
                    pair,
                    (&reach, CollisionSettings::of(&world.settings).landing_band),
                    reach.angle.as_ref().unwrap_or(&angle),
                    VertexIds::for_model(world.settings.model),
                    &mut features,
                    Recycled::default(),
                );
                let Found::Touching((fresh, _, _)) = found else {
                    assert!(
                        held.depth() <= -(reach.margin + reach.closing) + bounds.slip,
                        "step {step}: pair {pair:?} found apart, held at depth {}",
                        held.depth()
                    );
                    continue;
                };
                compared += 1;
                moved += usize::from(fresh != *held);
                let turn = fresh.frame.normal.angle(&held.frame.normal);
                let point = held.depths.len() == 1 || fresh.depths.len() == 1;
                assert!(
                    point || turn <= 2.0 * bounds.turn,
                    "step {step}: pair {pair:?} turned {turn}"
                );
                let depth = (fresh.depth() - held.depth()).abs();
                // Twice the slip: a support clipped where one face's edge crosses the other
                // face has a vertex that runs along that edge as the bodies slide, not with
                // them (two hulls face to face, their depths 1.1–1.9 mm across a tilt: the
                // deepest vertex carried 0.135 mm deeper than the one found afresh).
                let slip = 2.0 * bounds.slip;
                assert!(
                    depth <= slip,
                    "step {step}: pair {pair:?} depth off by {depth}"
                );
            }
            world.step(dt).expect("a step");
        }
        // About 44 contacts a step, half of them held by their bodies' motion (carried, or kept
        // while the bodies moved under 10 µm) rather than found again.
        assert!(
            compared >= 10_000 && moved >= compared / 4,
            "{moved} of {compared} moved"
        );
    }

    /// Two of [`mixed_shape`]'s bodies turned at random, the second placed along a random
    /// direction from the first.
    struct RandomPair {
        kinds: [usize; 2],
        shapes: [Shape; 2],
        turns: [UnitQuaternion<f64>; 2],
        towards: Vector3<f64>,
    }

    impl RandomPair {
        /// Kinds `kinds` of [`mixed_shape`] (a box, a ball, a cylinder, a hull).
        fn new(random: &mut Random, kinds: [usize; 2]) -> Self {
            let shapes = kinds.map(|k| mixed_shape(random, k));
            let mut c = || random.between(-1.0, 1.0);
            let turns = [(); 2].map(|()| {
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(c(), c(), c(), c()))
            });
            let towards = Vector3::new(c(), c(), c()).normalize();
            Self {
                kinds,
                shapes,
                turns,
                towards,
            }
        }

        /// The pair without gravity, the second body `offset` from the first.
        fn world(&self, offset: f64) -> World {
            World::builder()
                .gravity([0.0; 3])
                .body(BodyDesc::dynamic(self.shapes[0].clone()).rotation(self.turns[0]))
                .body(
                    BodyDesc::dynamic(self.shapes[1].clone())
                        .rotation(self.turns[1])
                        .position((self.towards * offset).into()),
                )
                .build()
                .expect("a valid scene")
        }

        /// The pair placed where `measure` (growing with the offset, from overlap to apart)
        /// reads `target`, by bisection, with what it reads there and the contact's deepest
        /// depth after a collision pass.
        fn placed_at(&self, measure: impl Fn(&World) -> f64, target: f64) -> (f64, f64) {
            let (mut near, mut far) = (0.0, 4.0);
            for _ in 0..60 {
                let offset = 0.5 * (near + far);
                if measure(&self.world(offset)) < target {
                    near = offset;
                } else {
                    far = offset;
                }
            }
            let mut world = self.world(far);
            let measured = measure(&world);
            world.prepare_step(1.0 / 60.0).expect("collision");
            let contact = world
                .contacts()
                .next()
                .unwrap_or_else(|| panic!("kinds {:?}, {measured} m: no contact", self.kinds));
            let deepest = contact
                .depths
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max);
            (measured, deepest)
        }
    }

    /// The two colliders of a [`RandomPair`]'s world at their poses.
    fn colliders(world: &World) -> ([&Collider; 2], Vec<parry3d_f64::math::Pose>) {
        ([0, 1].map(|k| &world.geometry[k].collider), poses_of(world))
    }

    /// Every pair of boxes, balls, cylinders and 10-point hulls (each order), turned at random
    /// and placed 0.1 to 4 mm apart (within the 5 mm margin) along a random direction, has a
    /// contact whose deepest point reads their distance (parry's, on the true shapes): within
    /// 10 µm for a pair with a ball or a cylinder (GJK's normal of shapes apart, and the planes
    /// and lines of caps, sides and faces, exact to rounding), and never more than 0.25 mm
    /// closer for two polytopes (their best separating axis reads less than their distance
    /// where they come nearest corner to corner or corner to edge: up to 0.23 mm here).
    /// Before, near a rim the rounded cylinder's normal leaned off the true one by up to 18°,
    /// and hulls' faces within the feature angle were fitted as one plane past their points:
    /// contacts read up to 4.9 mm closer than the shapes were, in beyond the slop where a box
    /// stood 1.9 mm from a cylinder's rim.
    #[test]
    fn pairs_apart_within_the_margin_read_their_gap() {
        use crate::parry_bridge::tests::sharp_distance;
        let mut random = Random::new(5);
        for case in 0..800 {
            let pair = RandomPair::new(&mut random, [case % 4, case / 4 % 4]);
            let gap = random.between(1e-4, 4e-3);
            let distance = |world: &World| {
                let ([a, b], poses) = colliders(world);
                sharp_distance(a, &poses[0], b, &poses[1])
            };
            let (apart, deepest) = pair.placed_at(distance, gap);
            let closer = deepest + apart;
            let curved = pair.kinds.iter().any(|&k| k == 1 || k == 2);
            let nearer = if curved { 1e-5 } else { 2.5e-4 };
            assert!(
                closer <= nearer && closer >= -1e-5,
                "case {case}, kinds {:?}: {apart} m apart, the contact reads {deepest} m deep",
                pair.kinds
            );
        }
    }

    /// The same pairs overlapping by 0.1 to 3 mm (parry's depth, on the true shapes, along
    /// their least way out of each other), resting contacts' depths: the contact's deepest
    /// point reads the overlap within 10 µm, every pair (GJK and EPA on the true shapes near
    /// a cylinder's rim read it to 2 µm). On the rounded cylinder's normal, leaning off the
    /// true one near a rim, 28 of 1,250 pairs of a cylinder and a box, a cylinder or a hull
    /// read up to 3.6 mm deeper than they were.
    #[test]
    fn overlapping_pairs_read_their_depth() {
        let mut random = Random::new(7);
        for case in 0..800 {
            let pair = RandomPair::new(&mut random, [case % 4, case / 4 % 4]);
            let overlap = random.between(1e-4, 3e-3);
            // Less the depth, so that the measure grows with the offset.
            let shallower = |world: &World| {
                let ([a, b], poses) = colliders(world);
                -a.depth_into(&poses[0], b, &poses[1])
            };
            let (less, deepest) = pair.placed_at(shallower, -overlap);
            assert!(
                (deepest + less).abs() < 1e-5,
                "case {case}, kinds {:?}: {} m in, the contact reads {deepest} m deep",
                pair.kinds,
                -less
            );
        }
    }
}
