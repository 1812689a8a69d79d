//! The support polygon of a touching pair: the overlap of the two bodies' touching features on
//! the contact plane, with every vertex kept, and the penetration at each vertex.
//!
//! Each body's feature is the set of its hull vertices within a small angle of the extreme along
//! the contact normal (a face, an edge or a corner; a sphere's is its lowest point; a box's is
//! read off its axes, [`crate::box_feature`]). Both features are projected on the plane, turned
//! into convex polygons, and clipped against each other (Sutherland–Hodgman; a segment is
//! clipped parametrically). A 45°-twisted box on a box therefore gives an octagon, an edge a
//! segment, a corner a point. A feature the shape lists in order around its outline (a box's
//! face, a cylinder's cap, an edge, a corner) is its own polygon; only a hull's points go
//! through the geometry crate's hull. Each feature's height over the plane is its face's own
//! plane when the shape knows the face, the line through an edge's ends, else a least-squares
//! plane through its points. With the box's feature, these took collision on one thread from
//! 3.6–3.9 to 2.9–3.2 ms a step on the 1000-cube pile and from 8.1–9.1 to 5.9–6.6 ms on the
//! 1000 mixed shapes (cylinder caps of 64 points no longer go through a hull and a fit).
//! Under the face model a cylinder resting on one point of its cap's rim also gives the cap
//! vertices beside that point within the margin, with their gaps over the other feature's
//! face, as the contact's landing points ([`Outline::landing`]).
//!
//! Under the vertex and patch models, which carry their rows' impulses from step to step by the
//! vertex they act at, every vertex of the result carries a [`FeatureId`] ([`VertexIds`]; the
//! face model carries its block whole and skips the names, about a tenth of a box pair's
//! contact): which vertex of A's or B's feature it is, or which edge of each crosses there. It
//! is found after clipping, by position, rather than threaded through the hull and clipping
//! code, which reorder, drop and recompute points. A vertex within [`SAME_POINT`] of the
//! polygon's size of a feature point takes that point's id (A's before B's): on two aligned
//! stacked boxes each overlap corner is A's corner, B's corner or a crossing of their edges
//! depending on the sign of a sub-millimetre offset, and a name that flickered with it would
//! throw the corner's warm start away every other step.

use nalgebra::{Matrix3, Point2, Point3, UnitQuaternion, Vector3};
use smallvec::SmallVec;
use std::sync::OnceLock;
use tatami_contact::{BEARING_DEPTH, ContactFrame, ContactModel, Landing};
use tatami_geometry::nearest::closest_point_on_segment;
use tatami_geometry::polygon::ring_next;
use tatami_geometry::{ConvexPolygon, PolygonKind, signed_area};

use crate::box_feature::cuboid_feature;

/// Distance, as a fraction of the support polygon's bounding-box diagonal, within which a
/// support vertex is named after a feature point (see the module doc). At 1% the corners of
/// stacked 2 m boxes keep their names through 2.8 cm of offset, while the crossings of a
/// twisted box (30 cm from any corner for 2 m boxes at 45°) keep theirs.
const SAME_POINT: f64 = 0.01;

/// Points of a touching feature, an outline or an overlap, inline up to 8: a box's feature has
/// at most 4 points and two boxes' overlap at most 8, so a box pair's support polygon is built
/// without a heap allocation (a cylinder cap's 64 spill to the heap).
type Points<T> = SmallVec<[T; 8]>;

/// Squared distance, relative to a point's squared distance from the frame's origin (plus
/// 1 m²), within which a support vertex is a fitted feature's own point: rounding of a clip at
/// that point, far below any distance between two points of a shape.
const SAME_OWN_POINT: f64 = 1e-24;

/// A point of a body's touching feature and which point of the body it is: a hull vertex's
/// index, a cylinder cap's rim point, … — the same from step to step while the body touches
/// with the same feature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FeaturePoint {
    /// World position.
    pub point: Point3<f64>,
    /// Which point of the body.
    pub id: u32,
}

/// A body's touching feature: its points, and what the body's shape says of them. Points that
/// go around the feature in order (a box's face or a cylinder's cap, an edge, a corner) are its
/// outline as they stand, with no hull to build; the outward normal of the face they lie on
/// makes the feature's height over the contact plane that face's plane rather than a fit to
/// its points.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Feature {
    /// The points, each named by which point of the body it is.
    pub points: Vec<FeaturePoint>,
    /// Whether the points go around the feature's outline in order (either way), each once.
    pub ring: bool,
    /// Outward unit normal of the face holding every point, if known.
    pub face_normal: Option<Vector3<f64>>,
    /// For a cylinder's side line, the radius of the side it lies on: the surface falls away
    /// across the line, by `e² / 2r` at `e` from it.
    pub side_radius: Option<f64>,
    /// Points of the body beside the feature where it would land if it turned
    /// ([`Outline::landing`]); empty unless asked for.
    pub landing: Vec<FeaturePoint>,
}

/// Where a support-polygon vertex comes from: a point of A's touching feature, one of B's, or
/// the crossing of an edge of each (an edge named by its first point, counter-clockwise). It
/// stays the same from step to step while the same features touch, so a vertex's impulses can
/// be carried over exactly, as Box2D's and rapier's feature ids do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum FeatureId {
    /// A point of body A's feature.
    A(u32),
    /// A point of body B's feature.
    B(u32),
    /// An edge of A's outline crossing an edge of B's.
    Crossing(u32, u32),
}

/// The feature ids of a support polygon's vertices, inline up to a box contact's 8.
pub(crate) type FeatureIds = SmallVec<[FeatureId; 8]>;

/// What of a body's surface can touch: hull vertices, or a ball.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Outline {
    /// Hull vertices relative to the body's origin (body axes), and the largest distance of one
    /// from the origin.
    Polyhedron {
        /// Vertices in the body frame.
        vertices: Vec<Vector3<f64>>,
        /// Largest vertex distance from the origin, which scales the feature tolerance.
        radius: f64,
        /// A box's half extents: its feature is read off its axes ([`cuboid_feature`]) rather
        /// than searched for among its vertices, which are its corners.
        box_half_extents: Option<Vector3<f64>>,
    },
    /// A ball centred on the body's origin.
    Sphere {
        /// Its radius.
        radius: f64,
    },
    /// A cylinder along the body's z axis; a cap touching flat is a regular
    /// [`CAP_VERTICES`]-gon inscribed in the rim (its `r̄` within 0.1% of the disc's `2R/3`).
    Cylinder {
        /// Radius.
        radius: f64,
        /// Half the height.
        half_height: f64,
    },
}

/// Vertices of the polygon standing in for a cylinder's cap.
pub(crate) const CAP_VERTICES: usize = 64;

/// `(cos t, sin t)` at the cap polygon's vertices, `t = 2π k / CAP_VERTICES`: computed once, not
/// for every cap feature of every contact.
fn cap_directions() -> &'static [(f64, f64); CAP_VERTICES] {
    static DIRECTIONS: OnceLock<[(f64, f64); CAP_VERTICES]> = OnceLock::new();
    DIRECTIONS.get_or_init(|| {
        std::array::from_fn(|k| {
            let t = std::f64::consts::TAU * k as f64 / CAP_VERTICES as f64;
            (t.cos(), t.sin())
        })
    })
}

/// The feature angle with the trigonometry the feature search reads: computed once per
/// collision pass rather than for every feature of every pair (a sine and a tangent were a
/// tenth of a box feature's time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FeatureAngle {
    pub(crate) cos: f64,
    pub(crate) sin: f64,
    tan_squared: f64,
}

impl FeatureAngle {
    /// The feature angle `angle` (rad).
    pub(crate) fn new(angle: f64) -> Self {
        Self {
            cos: angle.cos(),
            sin: angle.sin(),
            tan_squared: angle.tan().powi(2),
        }
    }

    /// Whether a point `rise` above another, by more than `eps`, over a horizontal run whose
    /// square is `run_squared`, lies above it more steeply than the angle: the rule that keeps
    /// the lower point out of a feature. `rise − eps > run · tan(angle)`, squared to keep
    /// square roots out of the feature searches' loops.
    pub(crate) fn is_steeper(&self, rise: f64, run_squared: f64, eps: f64) -> bool {
        let height = rise - eps;
        height > 0.0 && height * height > run_squared * self.tan_squared
    }
}

impl Outline {
    /// The outline of a polyhedron from its hull vertices; a box's (its corners numbered with
    /// bit `k` set on the `+k` side) with its half extents.
    pub(crate) fn polyhedron(
        vertices: Vec<Vector3<f64>>,
        box_half_extents: Option<Vector3<f64>>,
    ) -> Self {
        let radius = vertices.iter().map(|v| v.norm()).fold(0.0, f64::max);
        Self::Polyhedron {
            vertices,
            radius,
            box_half_extents,
        }
    }

    /// Largest distance of the outline from the body's origin (m).
    pub(crate) fn size(&self) -> f64 {
        match self {
            Self::Polyhedron { radius, .. } | Self::Sphere { radius } => *radius,
            Self::Cylinder {
                radius,
                half_height,
            } => radius.hypot(*half_height),
        }
    }

    /// World points of the feature furthest along `direction` (unit): the vertices no other
    /// vertex lies above more steeply than `angle`, so faces tilted by less than `angle` count as
    /// flat whatever the body's size.
    pub(crate) fn feature(
        &self,
        origin: &Point3<f64>,
        rotation: &UnitQuaternion<f64>,
        direction: &Vector3<f64>,
        angle: &FeatureAngle,
        feature: &mut Feature,
    ) {
        feature.side_radius = None;
        if let Self::Polyhedron {
            box_half_extents: Some(h),
            ..
        } = self
            && cuboid_feature(h, origin, rotation, direction, angle, feature)
        {
            return;
        }
        feature.face_normal = None;
        // A sphere's point, a cylinder's cap, side line or rim point, and any one or two points
        // of a hull go around their outline in order.
        feature.ring = true;
        let out = &mut feature.points;
        out.clear();
        let rim_points = CAP_VERTICES as u32;
        match self {
            Self::Sphere { radius } => out.push(FeaturePoint {
                point: origin + direction * *radius,
                id: 0,
            }),
            Self::Cylinder {
                radius,
                half_height,
            } => {
                let d = rotation.inverse_transform_vector(direction);
                let cap = half_height.copysign(d.z);
                let radial = Vector3::new(d.x, d.y, 0.0);
                let rim = radial.try_normalize(1e-12).map(|u| u * *radius);
                // Ids: the rim points of the bottom cap, of the top cap, then the two ends of the
                // side line, then the single rim point of either cap.
                let top = u32::from(cap > 0.0);
                let place = |(v, id): (Vector3<f64>, u32)| FeaturePoint {
                    point: origin + rotation * v,
                    id,
                };
                if d.z.abs() >= angle.cos || rim.is_none() {
                    feature.face_normal = Some(rotation * Vector3::z() * cap.signum());
                    out.extend((0..CAP_VERTICES).map(|k| {
                        let (id, v) = cap_vertex(*radius, cap, k);
                        place((v, id))
                    }));
                } else {
                    let rim = rim.unwrap_or_default();
                    if d.z.abs() <= angle.sin {
                        // Lying on its side: the line along the axis.
                        feature.side_radius = Some(*radius);
                        out.extend(
                            [
                                (rim - Vector3::z() * *half_height, 2 * rim_points),
                                (rim + Vector3::z() * *half_height, 2 * rim_points + 1),
                            ]
                            .map(place),
                        );
                    } else {
                        out.push(place((rim + Vector3::z() * cap, 2 * rim_points + 2 + top)));
                    }
                }
            }
            Self::Polyhedron {
                vertices, radius, ..
            } => {
                let local = rotation.inverse_transform_vector(direction);
                let extreme = vertices
                    .iter()
                    .map(|v| v.dot(&local))
                    .fold(f64::NEG_INFINITY, f64::max);
                // Candidates: every vertex within `2 radius · sin(angle) + eps` of the extreme.
                // The rule below keeps no vertex lower than that: one the extreme is not above
                // more steeply than the angle lies at most `|E − v| · sin(angle) + eps` below
                // it, and no two vertices are more than `2 radius` apart. (A band of `radius ·
                // sin(angle)` dropped a cube's far face edge from a tilt of 0.87° under a 1°
                // angle, and a longer face's earlier still.)
                let eps = 1e-9 * radius;
                let tolerance = 2.0 * radius * angle.sin + eps;
                out.extend(
                    (0u32..)
                        .zip(vertices)
                        .filter(|(_, v)| v.dot(&local) >= extreme - tolerance)
                        .map(|(id, v)| FeaturePoint {
                            point: origin + rotation * v,
                            id,
                        }),
                );
                keep_within_angle(out, direction, angle, eps);
                feature.ring = out.len() <= 2;
            }
        }
    }
}

/// Most landing points on either side of a cylinder's rim point ([`Outline::landing`]),
/// spread evenly over the arc of the rim within the band, the farthest always among them.
/// Between two of them the rim sags below their chord by about a 36th of the band (0.14 mm
/// under the default 5 mm margin) whatever the tilt, since the band sets the arc; a nearly
/// flat cap would otherwise take every vertex of a long arc (11 a side at 1.4°, a landing
/// block each). Two a side let a cylinder wobbling at 3° go 3.1 mm into the floor
/// (`face_model.rs`), past the slop.
pub(crate) const LANDING_POINTS_PER_SIDE: usize = 3;

impl Outline {
    /// Writes into `feature.landing` points beside its touching feature along the unit
    /// `direction` (as [`Outline::feature`] found it) that stand back from it by at most `band`
    /// (m) along that direction: for a cylinder touching with one point of its cap's rim, cap
    /// polygon vertices within `band` of that point on either side, where the rim lands as the
    /// cylinder wobbles ([`tatami_contact::Contact::landing`]; [`LANDING_POINTS_PER_SIDE`] of
    /// them a side at most), and the far end of the side line through it, where the other rim
    /// lands as a cylinder nearly on its side rocks. A polyhedron's faces, edges and corners
    /// land on points of its feature as it turns slowly; its vertices within `turn_band` (the
    /// pair's closing in the step, [`crate::speculative`], or 0) are its landing points,
    /// nearest first, at most [`LANDING_POINTS_PER_SIDE`] twice: a cube hitting the floor on a
    /// corner at 13.8 m/s left it spinning at 7.5 rad/s, and the next corner swung down 93 mm
    /// into the floor in that step, outside the feature and any feature angle.
    pub(crate) fn landing(
        &self,
        origin: &Point3<f64>,
        rotation: &UnitQuaternion<f64>,
        direction: &Vector3<f64>,
        (band, turn_band): (f64, f64),
        feature: &mut Feature,
    ) {
        feature.landing.clear();
        let (radius, half_height) = match self {
            Self::Cylinder {
                radius,
                half_height,
            } => (radius, half_height),
            Self::Polyhedron {
                vertices, radius, ..
            } => {
                let vertices = (0u32..).zip(vertices.iter().copied());
                turning_landing(
                    vertices,
                    *radius,
                    (origin, rotation),
                    direction,
                    turn_band,
                    feature,
                );
                return;
            }
            Self::Sphere { .. } => return,
        };
        // A fast cylinder's rims, where its turn may swing them down; not beside a side line,
        // which rolls: the rims' points ahead of it sink at the rolling speed without coming
        // down, and their landing blocks, linear over the step, braked a cylinder rolling down
        // a ramp (2.96 m/s against the closed form's 3.38).
        let turning = |feature: &mut Feature| {
            if turn_band > 0.0 && feature.side_radius.is_none() {
                let rims = turning_rims(*radius, *half_height);
                let size = radius.max(*half_height);
                let pose = (origin, rotation);
                turning_landing(rims, size, pose, direction, turn_band, feature);
            }
        };
        // The rim point alone is the feature exactly when it is neither a cap nor a side line.
        let (&[rim], None) = (&feature.points[..], feature.face_normal) else {
            turning(feature);
            return;
        };
        if band > 0.0 {
            rim_landing(
                *radius,
                *half_height,
                (origin, rotation),
                direction,
                band,
                rim,
                feature,
            );
        }
        turning(feature);
    }
}

/// [`Outline::landing`] of a cylinder of `radius` and `half_height` (its origin at `origin`
/// turned by `rotation`) touching along the unit `direction` with the one point `rim` of a
/// cap's rim: cap polygon vertices standing back from it by at most `band` on either side,
/// [`LANDING_POINTS_PER_SIDE`] a side at most, spread evenly over the arc, the farthest always
/// among them; then the far end of the side line through it, on the other cap's rim, if it
/// stands back by at most `band`.
fn rim_landing(
    radius: f64,
    half_height: f64,
    (origin, rotation): (&Point3<f64>, &UnitQuaternion<f64>),
    direction: &Vector3<f64>,
    band: f64,
    rim: FeaturePoint,
    feature: &mut Feature,
) {
    let d = rotation.inverse_transform_vector(direction);
    let cap = half_height.copysign(d.z);
    let lowest = rotation.inverse_transform_vector(&(rim.point - origin));
    let extreme = lowest.dot(&d);
    let vertex = |k: usize| cap_vertex(radius, cap, k).1;
    // The first cap vertex counter-clockwise from the rim point (at or past its angle).
    let spacing = std::f64::consts::TAU / CAP_VERTICES as f64;
    let first =
        (lowest.y.atan2(lowest.x).rem_euclid(std::f64::consts::TAU) / spacing).ceil() as usize;
    // A cap vertex on the rim point itself would be a second contact at the same place.
    let apart_squared = (1e-6 * radius).powi(2);
    let half = CAP_VERTICES / 2;
    // Counter-clockwise from `first`, then clockwise from the vertex before it.
    for counter_clockwise in [true, false] {
        let side = |i: usize| match counter_clockwise {
            true => first + i,
            false => first + 2 * CAP_VERTICES - 1 - i,
        };
        // The side's vertices within the band, nearest first: an arc of the rim.
        let (mut arc, mut len) = ([0; CAP_VERTICES / 2], 0);
        for k in (0..half).map(side) {
            if extreme - vertex(k).dot(&d) > band {
                break;
            }
            if (vertex(k) - lowest).norm_squared() > apart_squared {
                arc[len] = k;
                len += 1;
            }
        }
        let arc = &arc[..len];
        let picks = LANDING_POINTS_PER_SIDE.min(arc.len());
        feature.landing.extend((1..=picks).map(|j| {
            let (id, v) = cap_vertex(radius, cap, arc[(arc.len() * j).div_ceil(picks) - 1]);
            FeaturePoint {
                point: origin + rotation * v,
                id,
            }
        }));
    }
    // The far end of the side line through the rim point, on the other cap's rim, where a
    // cylinder nearly on its side lands as it rocks from one rim to the other: no point of
    // the rim point's own cap is near it.
    let far = Vector3::new(lowest.x, lowest.y, -cap);
    if extreme - far.dot(&d) <= band {
        // Named as that end of the side line ([`Outline::feature`]'s ids).
        feature.landing.push(FeaturePoint {
            point: origin + rotation * far,
            id: 2 * CAP_VERTICES as u32 + u32::from(cap < 0.0),
        });
    }
}

/// Every [`TURNING_RIM_STRIDE`]-th vertex of either cap polygon of a cylinder of `radius` and
/// `half_height`, with its id (as [`Outline::feature`] names cap vertices): where a fast
/// cylinder's turn may swing its rims onto the other body ([`Outline::landing`]).
fn turning_rims(radius: f64, half_height: f64) -> impl Iterator<Item = (u32, Vector3<f64>)> {
    [-half_height, half_height]
        .into_iter()
        .flat_map(move |cap| {
            (0..CAP_VERTICES)
                .step_by(TURNING_RIM_STRIDE)
                .map(move |k| cap_vertex(radius, cap, k))
        })
}

/// Vertex `k` (taken modulo [`CAP_VERTICES`]) of the polygon inscribed in the rim of the cap at
/// height `cap` (body frame; the top cap when above 0) of a cylinder of `radius`, with its id
/// as [`Outline::feature`] names cap vertices: the bottom cap's first, then the top's.
fn cap_vertex(radius: f64, cap: f64, k: usize) -> (u32, Vector3<f64>) {
    let k = k % CAP_VERTICES;
    let (cos, sin) = cap_directions()[k];
    let id = k as u32 + u32::from(cap > 0.0) * CAP_VERTICES as u32;
    (id, Vector3::new(radius * cos, radius * sin, cap))
}

/// Cap vertices between two of a cylinder's turning landing points ([`turning_rims`]): eight
/// a rim, 45° apart. The nearest cap vertices stand back from a rim point by micrometres and
/// would take every landing point beside it, where the turn swings the rim's far side.
const TURNING_RIM_STRIDE: usize = CAP_VERTICES / 8;

/// [`Outline::landing`] of a polyhedron's `vertices` (body frame, with their ids) or a fast
/// cylinder's [`turning_rims`], its size `radius`, its origin at `origin` turned by `rotation`:
/// the vertices that stand back from its touching feature by at most `band` (m) along the unit
/// `direction`, nearest first (ties in vertex order), at most [`LANDING_POINTS_PER_SIDE`]
/// twice. Kept in a fixed array while they are found: collision allocates nothing per pair
/// here.
fn turning_landing(
    vertices: impl Iterator<Item = (u32, Vector3<f64>)>,
    radius: f64,
    (origin, rotation): (&Point3<f64>, &UnitQuaternion<f64>),
    direction: &Vector3<f64>,
    band: f64,
    feature: &mut Feature,
) {
    if band <= 0.0 {
        return;
    }
    let local = rotation.inverse_transform_vector(direction);
    let extreme = (feature.points.iter())
        .map(|p| {
            rotation
                .inverse_transform_vector(&(p.point - origin))
                .dot(&local)
        })
        .fold(f64::NEG_INFINITY, f64::max);
    let eps = 1e-9 * radius;
    // The nearest so far, by how far each stands back, in order.
    let mut nearest = [(0.0, 0u32, Vector3::zeros()); 2 * LANDING_POINTS_PER_SIDE];
    let mut len = 0;
    for (id, v) in vertices {
        let back = extreme - v.dot(&local);
        let taken = |p: &FeaturePoint| p.id == id;
        if back <= eps
            || back > band
            || feature.points.iter().any(taken)
            || feature.landing.iter().any(taken)
        {
            continue;
        }
        // After every one standing back as little or less.
        let at = nearest[..len].partition_point(|&(b, _, _)| b <= back);
        if at < nearest.len() {
            len = (len + 1).min(nearest.len());
            nearest.copy_within(at..len - 1, at + 1);
            nearest[at] = (back, id, v);
        }
    }
    feature
        .landing
        .extend(nearest[..len].iter().map(|&(_, id, v)| FeaturePoint {
            point: origin + rotation * v,
            id,
        }));
}

/// Drops from `points` every point that another lies above more steeply than the feature
/// `angle` along the unit `direction` ([`FeatureAngle::is_steeper`]): what is left is the face,
/// edge or corner tilted by less than that angle from the plane normal to `direction`. Unlike a
/// height threshold this does not depend on the body's size: the far bottom corners of a wide,
/// thin slab are within any fixed height of its top face, but every one lies straight below a
/// top corner.
///
/// "Steeply above" is transitive (the slopes add along a chain, the horizontal offsets obey the
/// triangle inequality), so a point dominated by a dropped point is also dominated by a kept
/// one, and the points can be compacted in place while being checked.
fn keep_within_angle(
    points: &mut Vec<FeaturePoint>,
    direction: &Vector3<f64>,
    angle: &FeatureAngle,
    eps: f64,
) {
    let mut kept = 0;
    for i in 0..points.len() {
        let v = points[i];
        let above = |u: &FeaturePoint| {
            let offset = u.point - v.point;
            let rise = offset.dot(direction);
            angle.is_steeper(rise, offset.norm_squared() - rise.powi(2), eps)
        };
        let dominated = points[..kept].iter().chain(&points[i + 1..]).any(above);
        if !dominated {
            points[kept] = v;
            kept += 1;
        }
    }
    points.truncate(kept);
}

/// Whether [`support`] names each vertex of the polygon by its [`FeatureId`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum VertexIds {
    /// Each vertex named (the default: the whole answer).
    #[default]
    Named,
    /// No names: finding them costs a tenth of a box pair's contact (a search of both
    /// features' points and edges for every vertex, and of each feature's points for every
    /// outline vertex), and the face model needs none.
    Unnamed,
}

impl VertexIds {
    /// What `model` needs: the vertex and patch models carry their rows' impulses from step to
    /// step by the vertex they act at; the face model carries its block whole
    /// ([`tatami_contact::ContactImpulse`]).
    pub(crate) fn for_model(model: ContactModel) -> Self {
        match model {
            ContactModel::Vertex | ContactModel::Patch => Self::Named,
            ContactModel::Face => Self::Unnamed,
        }
    }
}

/// A support polygon with its frame, per-vertex depths and per-vertex feature ids (none when
/// not asked for).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Support {
    pub frame: ContactFrame,
    pub polygon: ConvexPolygon,
    pub depths: Vec<f64>,
    pub features: FeatureIds,
    /// Each feature's landing points over the other's outline, with their depths.
    pub landing: Vec<Landing>,
}

/// The support polygon of A's `feature_a` resting on B's `feature_b`, with `normal` (unit) from B
/// into A, its depths written into `depths` (cleared first: the buffer of the contact it
/// replaces, so that a moved pair's contact is recomputed without an allocation), and each
/// vertex's feature id if `ids` asks for them. `None` only if a feature is empty or not finite.
pub(crate) fn support(
    feature_a: &Feature,
    feature_b: &Feature,
    normal: &Vector3<f64>,
    mut depths: Vec<f64>,
    ids: VertexIds,
) -> Option<Support> {
    let (a0, b0) = (feature_a.points.first()?, feature_b.points.first()?);
    let frame = ContactFrame::from_normal(nalgebra::center(&a0.point, &b0.point), *normal).ok()?;
    let surface_a = Surface::fit(&frame, feature_a, ids, Side::A)?;
    let surface_b = Surface::fit(&frame, feature_b, ids, Side::B)?;
    let mut points = match (feature_a.side_radius, feature_b.side_radius) {
        (Some(ra), Some(rb))
            if (surface_a.kind, surface_b.kind) == (PolygonKind::Segment, PolygonKind::Segment) =>
        {
            side_lines_overlap(&surface_a.outline, &surface_b.outline, ra, rb)
        }
        _ => overlap(&surface_a, &surface_b),
    };
    if points.is_empty() {
        // Touching only at the boundary within rounding, or just missing each other (edges
        // crossing a hair beyond an end, as a normal found to within GJK's accuracy leaves
        // them): where they come nearest.
        points.push(nearest_of_a(&surface_a.outline, &surface_b.outline)?);
    }
    let polygon = ConvexPolygon::from_points(&points).ok()?;
    depths.clear();
    depths.extend(
        polygon
            .vertices()
            .iter()
            .map(|p| surface_b.height(p) - surface_a.height(p)),
    );
    let features = match ids {
        VertexIds::Named => {
            let (lo, hi) = polygon.bounding_box();
            let tolerance = polygon.tolerance().max(SAME_POINT * (hi - lo).norm());
            polygon
                .vertices()
                .iter()
                .map(|p| identify(p, &surface_a, &surface_b, tolerance))
                .collect()
        }
        VertexIds::Unnamed => FeatureIds::new(),
    };
    let mut landing = Vec::new();
    for (feature, other, sign) in [(feature_a, &surface_b, 1.0), (feature_b, &surface_a, -1.0)] {
        if other.kind != PolygonKind::Polygon {
            continue;
        }
        landing.extend(feature.landing.iter().filter_map(|f| {
            let point = frame.to_plane(&f.point);
            let height = (f.point - frame.origin).dot(&frame.normal);
            // Depth as for the support's vertices: B's height less A's.
            let depth = sign * (other.height(&point) - height);
            other.covers(&point).then_some(Landing { point, depth })
        }));
    }
    Some(Support {
        frame,
        polygon,
        depths,
        features,
        landing,
    })
}

/// Where support vertex `p` comes from: the nearest point of A's outline or else of B's within
/// `tolerance`, else the crossing of the edges of each that pass nearest to it.
fn identify(p: &Point2<f64>, a: &Surface, b: &Surface, tolerance: f64) -> FeatureId {
    // Points farther than twice the tolerance by their squared distance are passed over without
    // a square root (the factor covers its rounding): they could not be within it.
    let within = 4.0 * tolerance * tolerance;
    let at_point = |s: &Surface| {
        s.outline
            .iter()
            .zip(&s.ids)
            .filter(|(v, _)| (*v - p).norm_squared() <= within)
            .map(|(v, &id)| ((v - p).norm(), id))
            .filter(|&(distance, _)| distance <= tolerance)
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .map(|(_, id)| id)
    };
    if let Some(id) = at_point(a) {
        FeatureId::A(id)
    } else if let Some(id) = at_point(b) {
        FeatureId::B(id)
    } else {
        FeatureId::Crossing(a.edge_nearest(p), b.edge_nearest(p))
    }
}

/// A feature seen from the contact plane: its outline (counter-clockwise, without repeated or
/// collinear vertices) with the id of each outline vertex (when named, [`VertexIds`]), and its
/// height above the plane as an affine function `h = c₀ + c₁ x + c₂ y`: a face's own plane
/// when the shape says which face it is, linear along an edge, else least squares over its
/// points, moved towards the other body until none of them lies past it. A hull's feature can
/// be two faces meeting at a fold within the feature angle; the least-squares plane runs
/// between them and would hide the fold's depth (a hull of the mixed pile rested with its
/// fold 5.7 mm into the floor, its contact reading 1.5 mm, under the slop). A support vertex
/// at one of the feature's own points reads that point's height; the plane, moved, serves the
/// vertices where edges cross, at most the fold's deeper. Moved alone, it read every vertex
/// but one too deep by up to the fold: a hull on the floor whose feature held a point 6.6 mm
/// up read 4.4 mm where its lowest point was 1.0 mm in, and was pushed out until it floated
/// 0.9 mm above the floor. Where the feature's deepest point is not an outline vertex (a
/// shallow point under a face, inside the outline), the own heights would miss it — a hull
/// whose bottom had a point 6 mm under its corners sank it all into the floor, its contact
/// reading 0 — so every vertex reads the moved plane, which passes through that point.
struct Surface {
    outline: Points<Point2<f64>>,
    kind: PolygonKind,
    ids: Points<u32>,
    coefficients: Vector3<f64>,
    /// A fitted feature's outline vertices' own heights, `None` for a vertex that is not one of
    /// its points (empty for a face's own plane or an edge, whose heights are exact): a support
    /// vertex at one reads it, not the plane's.
    own_heights: Points<Option<f64>>,
}

/// Which body of the pair a feature is of: A's faces B against the normal, B's faces A along it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    A,
    B,
}

impl Surface {
    fn fit(frame: &ContactFrame, feature: &Feature, names: VertexIds, side: Side) -> Option<Self> {
        let points = &feature.points;
        let on_plane =
            || -> Points<Point2<f64>> { points.iter().map(|f| frame.to_plane(&f.point)).collect() };
        // A ring's points on the plane are its outline as they stand. `plane`, the points in
        // the feature's order, is kept apart only where the outline is their hull; the one
        // branch below that reads a ring's in that order projects them again rather than every
        // face copying them.
        let mut outline = on_plane();
        let ring = feature.ring.then(|| ring_kind(&outline)).flatten();
        let (kind, ids, hull, plane) = match ring {
            Some((kind, reversed)) => {
                let mut ids: Points<u32> = match names {
                    VertexIds::Named => points.iter().map(|f| f.id).collect(),
                    VertexIds::Unnamed => Points::new(),
                };
                if reversed {
                    outline.reverse();
                    ids.reverse();
                }
                (kind, ids, None, None)
            }
            None => {
                let hull = ConvexPolygon::from_points(&outline).ok()?;
                let plane = std::mem::replace(&mut outline, Points::from_slice(hull.vertices()));
                // The hull's vertices are copies of its input points.
                let ids = match names {
                    VertexIds::Named => hull
                        .vertices()
                        .iter()
                        .map(|v| {
                            plane
                                .iter()
                                .position(|p| p == v)
                                .map_or(0, |k| points[k].id)
                        })
                        .collect(),
                    VertexIds::Unnamed => Points::new(),
                };
                (hull.kind(), ids, Some(hull), Some(plane))
            }
        };
        let height = |f: &FeaturePoint| (f.point - frame.origin).dot(&frame.normal);
        let mut own_heights = Points::new();
        let coefficients = match (kind, feature.face_normal, &points[..]) {
            (PolygonKind::Point, ..) => {
                let mean_height = points.iter().map(height).sum::<f64>() / points.len() as f64;
                Vector3::new(mean_height, 0.0, 0.0)
            }
            // A face's own plane, through any of its points: `(P − p₀)·m = 0` at
            // `P = origin + x t₁ + y t₂ + h n`. A face within the feature angle across each of
            // its axes has `|n·m| ≥ √cos(2·angle)`, 0.9997 at 1°; a face steeper than 60°
            // (feature angles past 30°) is fitted instead.
            (_, Some(m), [p0, ..]) if frame.normal.dot(&m).abs() >= 0.5 => {
                let nm = frame.normal.dot(&m);
                Vector3::new(
                    (p0.point - frame.origin).dot(&m),
                    -frame.tangent1.dot(&m),
                    -frame.tangent2.dot(&m),
                ) / nm
            }
            // An edge: the height runs linearly between its ends (the least-squares fit's
            // answer, without its normal equations).
            (PolygonKind::Segment, None, [p0, p1]) => {
                // A ring of two points is never reversed: its outline is its points in order.
                let (q0, q1) = match &plane {
                    Some(plane) => (plane[0], plane[1]),
                    None => (outline[0], outline[1]),
                };
                let along = q1 - q0;
                let slope = along * ((height(p1) - height(p0)) / along.norm_squared());
                Vector3::new(height(p0) - slope.dot(&q0.coords), slope.x, slope.y)
            }
            _ => {
                let plane = plane.unwrap_or_else(on_plane);
                // Heights grow towards A: A's points past the plane lie below it, B's above.
                let towards_other = match side {
                    Side::A => -1.0,
                    Side::B => 1.0,
                };
                // The outline's vertices are copies of the points: each keeps its own height,
                // unless the feature's deepest point is not one of them (a shallow point inside
                // the outline, or on an edge between two of its vertices): the outline's own
                // heights would miss it, and the plane, moved onto it, reads it instead.
                let deepest = (0..points.len()).max_by(|&i, &j| {
                    let depth = |k: usize| towards_other * height(&points[k]);
                    depth(i).total_cmp(&depth(j))
                })?;
                if outline.contains(&plane[deepest]) {
                    own_heights = outline
                        .iter()
                        .map(|v| {
                            plane
                                .iter()
                                .position(|q| q == v)
                                .map(|k| height(&points[k]))
                        })
                        .collect();
                }
                let hull = hull.or_else(|| ConvexPolygon::from_points(&plane).ok())?;
                let mut fit = least_squares_plane(&hull, &plane, points.iter().map(height))?;
                let past = plane
                    .iter()
                    .zip(points)
                    .map(|(q, f)| {
                        towards_other * (height(f) - fit.dot(&Vector3::new(1.0, q.x, q.y)))
                    })
                    .fold(0.0, f64::max);
                fit.x += towards_other * past;
                fit
            }
        };
        Some(Self {
            outline,
            kind,
            ids,
            coefficients,
            own_heights,
        })
    }

    fn height(&self, p: &Point2<f64>) -> f64 {
        // A vertex where an edge was clipped at one of the points is that point to rounding.
        let own = (self.outline.iter().zip(&self.own_heights)).find_map(|(v, &h)| {
            let close = (v - p).norm_squared() <= SAME_OWN_POINT * (1.0 + v.coords.norm_squared());
            h.filter(|_| close)
        });
        own.unwrap_or_else(|| self.coefficients.dot(&Vector3::new(1.0, p.x, p.y)))
    }

    /// Whether `p` is within the outline (counter-clockwise, convex) or on it.
    fn covers(&self, p: &Point2<f64>) -> bool {
        let v = &self.outline;
        (0..v.len()).all(|k| signed_area(&v[k], &v[ring_next(k, v.len())], p) >= 0.0)
    }

    /// The id of the first point of the outline edge nearest to `p` (counter-clockwise).
    fn edge_nearest(&self, p: &Point2<f64>) -> u32 {
        let v = &self.outline;
        (0..v.len())
            .map(|k| {
                let q = closest_point_on_segment(&v[k], &v[ring_next(k, v.len())], p);
                ((q - p).norm_squared(), self.ids[k])
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or(0, |(_, id)| id)
    }
}

/// What the points of a ring (around a feature's outline in order, either way) enclose, and
/// whether they go clockwise; `None` when they do not clearly enclose it (a sliver of a face
/// seen edge-on, an edge seen end-on), which the hull settles. Projected within the feature
/// angle of their own plane, a box's face or a cylinder's cap keeps its shape: no vertex comes
/// near its neighbours' chord.
fn ring_kind(ring: &[Point2<f64>]) -> Option<(PolygonKind, bool)> {
    // Clear: an edge longer than 1e-6 of the points' reach from the origin (the features'
    // middle), an area more than 1e-6 of the points' bounding box squared.
    let reach = ring.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
    match ring {
        [_] => Some((PolygonKind::Point, false)),
        [p, q] => ((q - p).norm() > 1e-6 * reach).then_some((PolygonKind::Segment, false)),
        _ => {
            let twice_area: f64 = (0..ring.len())
                .map(|k| ring[k].coords.perp(&ring[ring_next(k, ring.len())].coords))
                .sum();
            let (lo, hi) = ring
                .iter()
                .fold((ring[0], ring[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
            (twice_area.abs() > 1e-6 * (hi - lo).norm_squared())
                .then_some((PolygonKind::Polygon, twice_area < 0.0))
        }
    }
}

/// The plane `h = c₀ + c₁ x + c₂ y` fitting `heights` at the points `plane` (whose hull is
/// `outline`, a segment or a polygon) by least squares, in coordinates centred on the
/// outline's centroid; along a segment only the slope along it is determined, so the normal
/// matrix gets a tiny ridge.
fn least_squares_plane(
    outline: &ConvexPolygon,
    plane: &[Point2<f64>],
    heights: impl Iterator<Item = f64>,
) -> Option<Vector3<f64>> {
    let c = outline.centroid();
    let mut normal_matrix = Matrix3::zeros();
    let mut rhs = Vector3::zeros();
    for (p, h) in plane.iter().zip(heights) {
        let row = Vector3::new(1.0, p.x - c.x, p.y - c.y);
        normal_matrix += row * row.transpose();
        rhs += row * h;
    }
    let ridge = 1e-12 * normal_matrix.trace();
    // Symmetric positive definite with the ridge: Cholesky is the cheap exact solve.
    let solved = (normal_matrix + Matrix3::identity() * ridge)
        .cholesky()?
        .solve(&rhs);
    Some(Vector3::new(
        solved.x - solved.y * c.x - solved.z * c.y,
        solved.y,
        solved.z,
    ))
}

/// The point of outline `a` nearest to outline `b` (each a point, a segment or a convex
/// polygon, its vertices in any order): two convex sets come nearest at a vertex of one, so
/// the nearest of `a`'s points to `b`'s vertices, and of `a`'s vertices to `b`. `None` for an
/// outline without a hull (no finite points).
fn nearest_of_a(a: &[Point2<f64>], b: &[Point2<f64>]) -> Option<Point2<f64>> {
    let (hull_a, hull_b) = (
        ConvexPolygon::from_points(a).ok()?,
        ConvexPolygon::from_points(b).ok()?,
    );
    let towards_b = hull_b
        .vertices()
        .iter()
        .map(|v| (hull_a.nearest_point(v), *v));
    let towards_a = hull_a
        .vertices()
        .iter()
        .map(|u| (*u, hull_b.nearest_point(u)));
    towards_b
        .chain(towards_a)
        .min_by(|x, y| {
            (x.0 - x.1)
                .norm_squared()
                .total_cmp(&(y.0 - y.1).norm_squared())
        })
        .map(|(on_a, _)| on_a)
}

/// The overlap of two features' outlines (points, segments or polygons), as unordered points.
fn overlap(a: &Surface, b: &Surface) -> Points<Point2<f64>> {
    let (a_points, b_points) = (&a.outline[..], &b.outline[..]);
    match (a.kind, b.kind) {
        (PolygonKind::Point, _) => Points::from_slice(a_points),
        (_, PolygonKind::Point) => Points::from_slice(b_points),
        (PolygonKind::Polygon, PolygonKind::Polygon) => clip_polygon(a_points, b_points),
        (PolygonKind::Segment, PolygonKind::Polygon) => clip_segment(a_points, b_points),
        (PolygonKind::Polygon, PolygonKind::Segment) => clip_segment(b_points, a_points),
        (PolygonKind::Segment, PolygonKind::Segment) => segment_overlap(a_points, b_points),
    }
}

/// Sutherland–Hodgman: `subject` clipped by each edge of the counter-clockwise `clip`.
fn clip_polygon(subject: &[Point2<f64>], clip: &[Point2<f64>]) -> Points<Point2<f64>> {
    let mut current = Points::from_slice(subject);
    let mut next = Points::with_capacity(subject.len() + clip.len());
    for (i, c0) in clip.iter().enumerate() {
        let c1 = &clip[ring_next(i, clip.len())];
        next.clear();
        for (j, p) in current.iter().enumerate() {
            let q = &current[ring_next(j, current.len())];
            let (sp, sq) = (signed_area(c0, c1, p), signed_area(c0, c1, q));
            if sp >= 0.0 {
                next.push(*p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                next.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        std::mem::swap(&mut current, &mut next);
        if current.is_empty() {
            break;
        }
    }
    current
}

/// The part of segment `s` inside the counter-clockwise polygon `clip` (Cyrus–Beck).
fn clip_segment(s: &[Point2<f64>], clip: &[Point2<f64>]) -> Points<Point2<f64>> {
    let (p, q) = (s[0], s[1]);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (i, c0) in clip.iter().enumerate() {
        let c1 = &clip[ring_next(i, clip.len())];
        let (sp, sq) = (signed_area(c0, c1, &p), signed_area(c0, c1, &q));
        if sp < 0.0 && sq < 0.0 {
            return Points::new();
        }
        if sp < 0.0 {
            t0 = t0.max(sp / (sp - sq));
        } else if sq < 0.0 {
            t1 = t1.min(sp / (sp - sq));
        }
    }
    if t0 > t1 {
        return Points::new();
    }
    Points::from_slice(&[p + (q - p) * t0, p + (q - p) * t1])
}

/// Two cylinders' side lines `a` and `b` (radii `ra`, `rb`): where the sides meet within
/// [`BEARING_DEPTH`]. Lines (nearly) parallel overlap along their common part, as edges do
/// ([`segment_overlap`]); lines crossing at `α` do not meet at their crossing point alone, as
/// straight edges would: off it along the bisector by `s`, each side falls away from the
/// other by `(s sin(α/2))² / 2r`, so they stay within that depth for
/// `|s| ≤ √(depth / (sin²(α/2) (1/2ra + 1/2rb)))`, the whole overlap of two long cylinders
/// crossing at a few degrees. Held at their crossing point alone, two lying cylinders crossing
/// at 3.5° in a pile rocked about it, ends dipping in, 5–8 mm deep for seconds.
fn side_lines_overlap(
    a: &[Point2<f64>],
    b: &[Point2<f64>],
    ra: f64,
    rb: f64,
) -> Points<Point2<f64>> {
    let crossing = segment_overlap(a, b);
    let (Some(da), Some(db), &[c]) = (
        (a[1] - a[0]).try_normalize(0.0),
        (b[1] - b[0]).try_normalize(0.0),
        crossing.as_slice(),
    ) else {
        return crossing;
    };
    let db = if da.dot(&db) < 0.0 { -db } else { db };
    let Some(m) = (da + db).try_normalize(0.0) else {
        return crossing;
    };
    let half_sin_squared = (1.0 - da.dot(&db)) / 2.0;
    let reach = (BEARING_DEPTH / (half_sin_squared * (0.5 / ra + 0.5 / rb))).sqrt();
    // Along the bisector, within reach and over both segments.
    let (mut lo, mut hi) = (-reach, reach);
    for (start, end, d) in [(a[0], a[1], da), (b[0], b[1], db)] {
        let along = m.dot(&d);
        let (t0, t1) = ((start - c).dot(&d), (end - c).dot(&d));
        let (t0, t1) = (t0.min(t1), t0.max(t1));
        lo = lo.max(t0 / along);
        hi = hi.min(t1 / along);
    }
    if lo >= hi {
        return crossing;
    }
    Points::from_slice(&[c + m * lo, c + m * hi])
}

/// Two segments: their common part when (nearly) parallel, else their crossing point.
fn segment_overlap(a: &[Point2<f64>], b: &[Point2<f64>]) -> Points<Point2<f64>> {
    let (a0, a1) = (a[0], a[1]);
    let (b0, b1) = (b[0], b[1]);
    let (da, db) = (a1 - a0, b1 - b0);
    let cross = da.perp(&db);
    // Parallel within about a degree: the edges lie along each other.
    if cross.abs() <= 0.02 * da.norm() * db.norm() {
        let length2 = da.norm_squared();
        let (mut u0, mut u1) = ((b0 - a0).dot(&da) / length2, (b1 - a0).dot(&da) / length2);
        if u0 > u1 {
            std::mem::swap(&mut u0, &mut u1);
        }
        let (lo, hi) = (u0.max(0.0), u1.min(1.0));
        if lo > hi {
            return Points::new();
        }
        return Points::from_slice(&[a0 + da * lo, a0 + da * hi]);
    }
    let t = (b0 - a0).perp(&db) / cross;
    let u = (b0 - a0).perp(&da) / cross;
    if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u) {
        Points::from_slice(&[a0 + da * t])
    } else {
        Points::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDesc, Shape};
    use nalgebra::Vector2;

    /// Feature points numbered in order.
    fn numbered(points: Vec<Point3<f64>>) -> Vec<FeaturePoint> {
        (0u32..)
            .zip(points)
            .map(|(id, point)| FeaturePoint { point, id })
            .collect()
    }

    /// The named support polygon of A's points resting on B's, the normal along z.
    fn named_on_z(a: &[FeaturePoint], b: &[FeaturePoint]) -> Support {
        support(
            &fitted(a),
            &fitted(b),
            &Vector3::z(),
            Vec::new(),
            VertexIds::Named,
        )
        .unwrap()
    }

    /// A feature whose heights are fitted, as a hull's.
    fn fitted(points: &[FeaturePoint]) -> Feature {
        Feature {
            points: points.to_vec(),
            ring: false,
            face_normal: None,
            side_radius: None,
            landing: Vec::new(),
        }
    }

    fn square(half: f64, angle: f64, z: f64) -> Vec<FeaturePoint> {
        let r = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle);
        numbered(
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .map(|&(x, y)| Point3::from(r * Vector3::new(x * half, y * half, z)))
                .collect(),
        )
    }

    #[test]
    fn twisted_squares_overlap_in_a_regular_octagon() {
        let a = square(1.0, std::f64::consts::FRAC_PI_4, 0.0);
        let b = square(1.0, 0.0, 0.0);
        let s = named_on_z(&a, &b);
        assert_eq!(s.polygon.vertices().len(), 8);
        // Regular octagon with inradius 1: area 8 tan(π/8).
        let expected = 8.0 * (std::f64::consts::PI / 8.0).tan();
        assert!((s.polygon.area() - expected).abs() < 1e-12);
        assert!(s.depths.iter().all(|d| d.abs() < 1e-12));
        // A recycled buffer (a replaced contact's depths) is cleared before it is filled.
        let recycled = support(
            &fitted(&a),
            &fitted(&b),
            &Vector3::z(),
            vec![7.0; 12],
            VertexIds::Named,
        )
        .unwrap();
        assert_eq!(recycled.depths, s.depths);
    }

    #[test]
    fn depth_follows_a_tilted_face() {
        // A's face dips 1 cm below B's top at x = +1 and sits 1 cm above at x = −1.
        let a: Vec<_> = square(1.0, 0.0, 0.0)
            .into_iter()
            .map(|f| FeaturePoint {
                point: Point3::new(f.point.x, f.point.y, -0.01 * f.point.x),
                ..f
            })
            .collect();
        let b = square(2.0, 0.0, 0.0);
        let s = named_on_z(&a, &b);
        for (v, d) in s.polygon.vertices().iter().zip(&s.depths) {
            let world = s.frame.to_world(v);
            assert!(
                (d - 0.01 * world.x).abs() < 1e-9,
                "depth {d} at x = {}",
                world.x
            );
        }
    }

    #[test]
    fn an_edge_across_a_face_gives_the_clipped_segment() {
        let a = numbered(vec![
            Point3::new(-3.0, 0.5, 0.0),
            Point3::new(3.0, 0.5, 0.0),
        ]);
        let b = square(1.0, 0.0, 0.0);
        let s = named_on_z(&a, &b);
        assert_eq!(s.polygon.kind(), PolygonKind::Segment);
        let ends: Vec<_> = s
            .polygon
            .vertices()
            .iter()
            .map(|v| s.frame.to_world(v))
            .collect();
        let xs = {
            let mut xs: Vec<f64> = ends.iter().map(|p| p.x).collect();
            xs.sort_by(f64::total_cmp);
            xs
        };
        assert!((xs[0] + 1.0).abs() < 1e-12 && (xs[1] - 1.0).abs() < 1e-12);
    }

    /// Two cylinders' side lines crossing at `α` meet along the bisector within the closed
    /// form's reach `√(δ / (sin²(α/2) (1/2ra + 1/2rb)))` of their crossing, δ the bearing
    /// depth, clipped to where both lines run: at 30° a short segment centred on the
    /// crossing, at 3.5° the part of the bisector over both lines (each 0.9 m long, so about
    /// their whole length), turned anywhere in the plane. Straight edges crossing at 3.5° meet
    /// at their crossing point alone, and nearly parallel side lines along their common part.
    #[test]
    fn crossing_side_lines_meet_along_the_bisector_within_the_bearing_depth() {
        let (ra, rb) = (0.4, 0.3);
        for turn in [0.0, 0.7, 2.9] {
            let line = |angle: f64, half: f64, shift: Vector2<f64>| {
                let d = Vector2::new((turn + angle).cos(), (turn + angle).sin()) * half;
                [Point2::from(shift - d), Point2::from(shift + d)]
            };
            let c = Point2::new(0.3, -0.2);
            for degrees in [30.0_f64, 3.5] {
                let alpha = degrees.to_radians();
                let (a, b) = (line(0.0, 0.45, c.coords), line(alpha, 0.45, c.coords));
                let points = side_lines_overlap(&a, &b, ra, rb);
                assert_eq!(points.len(), 2, "{degrees}°");
                let reach =
                    (BEARING_DEPTH / ((alpha / 2.0).sin().powi(2) * (0.5 / ra + 0.5 / rb))).sqrt();
                // Over both lines: a point at `r` along the bisector projects `r cos(α/2)` along
                // each from the crossing, which each line's 0.45 m bounds.
                let expected = reach.min(0.45 / (alpha / 2.0).cos());
                let bisector = Vector2::new((turn + alpha / 2.0).cos(), (turn + alpha / 2.0).sin());
                for p in &points {
                    let r = p - c;
                    assert!(
                        r.perp(&bisector).abs() < 1e-12,
                        "{degrees}°: off the bisector"
                    );
                    assert!(
                        (r.norm() - expected).abs() < 1e-12,
                        "{degrees}°: {}",
                        r.norm()
                    );
                }
                if degrees == 30.0 {
                    assert!(expected < 0.1, "a short segment: {expected}");
                }
                // Straight edges meet at the crossing only.
                assert_eq!(segment_overlap(&a, &b).len(), 1);
            }
            // Parallel within the edges' tolerance: the common part, as for edges.
            let (a, b) = (line(0.0, 0.45, c.coords), line(0.005, 0.3, c.coords));
            assert_eq!(side_lines_overlap(&a, &b, ra, rb), segment_overlap(&a, &b));
        }
    }

    /// Two edges whose outlines just miss each other — B's crosses the line of A's a hair
    /// beyond A's end — touch at A's end, as they do when the crossing falls a hair short of
    /// it: the contact does not jump as the crossing passes the end. Turned anywhere in the
    /// plane, at 2° to 90° between the edges, each rising or falling along itself, B up to 5 mm
    /// below A at the crossing. (The normal of a lying cylinder's side against a hull's edge,
    /// found by GJK to within 1e-4 rad, moved such a crossing past the end, and the contact
    /// went from 3 to 5.3 mm apart, beyond the margin, and was dropped: the point taken was
    /// A's nearest to B's middle.)
    #[test]
    fn edges_missing_each_other_by_a_hair_touch_at_the_end() {
        use proptest::prelude::*;
        proptest!(ProptestConfig::with_cases(256), |(
            turn in -3.2..3.2f64,
            degrees in 2.0..90.0f64,
            (slope_a, slope_b) in (-0.2..0.2f64, -0.2..0.2f64),
            gap in 0.0..0.005f64,
        )| {
            let twist = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn);
            let a = numbered(vec![
                Point3::from(twist * Vector3::new(-1.0, 0.0, gap - slope_a)),
                Point3::from(twist * Vector3::new(1.0, 0.0, gap + slope_a)),
            ]);
            let end = twist * Vector3::new(1.0, 0.0, 0.0);
            let alpha = degrees.to_radians();
            let along = twist * Vector3::new(alpha.cos(), alpha.sin(), slope_b);
            let touching = [-1e-7, 1e-7].map(|beyond| {
                // B crosses A's line `beyond` past A's end, `gap` below A there (to first order).
                let crossing = Point3::from(end * (1.0 + beyond)) + Vector3::z() * slope_a;
                let b = numbered(vec![crossing - along, crossing + along * 0.5]);
                let s = named_on_z(&a, &b);
                let at = s.frame.to_world(&s.polygon.vertices()[0]);
                (s.polygon.kind(), at, s.depths[0])
            });
            for (kind, at, depth) in touching {
                prop_assert_eq!(kind, PolygonKind::Point);
                // Within 1e-7 of the end, B's edge is within 1e-7 × its slope of `gap` below A.
                prop_assert!((at.xy() - Point2::from(end.xy())).norm() < 1e-6, "at {}", at);
                prop_assert!((depth + gap).abs() < 1e-6, "{} for a gap of {}", depth, gap);
            }
        });
    }

    #[test]
    fn crossing_edges_meet_in_a_point() {
        let a = numbered(vec![
            Point3::new(-1.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
        ]);
        let b = numbered(vec![
            Point3::new(0.25, -1.0, 0.0),
            Point3::new(0.25, 1.0, 0.0),
        ]);
        let s = named_on_z(&a, &b);
        assert_eq!(s.polygon.kind(), PolygonKind::Point);
        assert!(
            (s.frame.to_world(&s.polygon.vertices()[0]) - Point3::new(0.25, 0.0, 0.0)).norm()
                < 1e-12
        );
    }

    #[test]
    fn feature_ids_name_the_corners_and_crossings_and_survive_a_small_motion() {
        // A small square on a large one: its four corners, all of A.
        let small = square(0.5, 0.3, 0.0);
        let s = named_on_z(&small, &square(2.0, 0.0, 0.0));
        let mut ids = s.features.clone();
        ids.sort();
        assert_eq!(ids[..], (0..4).map(FeatureId::A).collect::<Vec<_>>());
        // Twisted equal squares: eight crossings, each a different pair of edges.
        let a = square(1.0, std::f64::consts::FRAC_PI_4, 0.0);
        let b = square(1.0, 0.0, 0.0);
        let s = named_on_z(&a, &b);
        let mut crossings = s.features.clone();
        crossings.sort();
        crossings.dedup();
        assert_eq!(crossings.len(), 8);
        assert!(
            crossings
                .iter()
                .all(|f| matches!(f, FeatureId::Crossing(..)))
        );
        // Moved by 1 mm, the same vertices keep the same ids.
        let moved: Vec<_> = a
            .iter()
            .map(|f| FeaturePoint {
                point: f.point + Vector3::new(1e-3, -2e-3, 0.0),
                ..*f
            })
            .collect();
        let after = named_on_z(&moved, &b);
        for (v, id) in after.polygon.vertices().iter().zip(&after.features) {
            let before = s.features[s
                .polygon
                .vertices()
                .iter()
                .enumerate()
                .min_by(|x, y| (x.1 - v).norm().total_cmp(&(y.1 - v).norm()))
                .unwrap()
                .0];
            assert_eq!(*id, before);
        }
    }

    /// A face placed by its normal and an edge placed by its ends give the heights that the
    /// least-squares fit of their points gives (the fit is exact for both): faces tilted up to
    /// 1° and edges tilted up to 30°, turned anywhere about the normal, at heights up to 1 m
    /// and 10 m off the frame's origin. Tolerance: the fit's ridge (1e-12 of its normal
    /// matrix's trace, `n + Σ|p − c|²`) biases its answer by up to about `1e-12 (1 + r²/ρ²)`
    /// relative, `r` the points' reach from their centroid (up to 3 m) and `ρ` the spread it is
    /// divided by (down to 0.1 m along a short edge): 1e-9 of the heights and offsets.
    #[test]
    fn known_faces_and_edges_are_placed_as_the_fit_places_them() {
        use proptest::prelude::*;
        proptest!(ProptestConfig::with_cases(256), |(
            half in 0.1..2.0f64,
            turn in -3.2..3.2f64,
            (tilt_axis, tilt) in (-3.2..3.2f64, -1.0..1.0f64),
            edge_slope in -0.5..0.5f64,
            (x, y, z) in (-10.0..10.0f64, -10.0..10.0f64, -1.0..1.0f64),
        )| {
            let frame = ContactFrame::from_normal(Point3::new(x, y, z), Vector3::z()).unwrap();
            let twist = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn);
            let axis = Vector3::new(tilt_axis.cos(), tilt_axis.sin(), 0.0);
            let lean = UnitQuaternion::from_scaled_axis(axis * tilt.to_radians());
            let centre = Point3::new(0.3, -0.2, 0.01);
            let face: Vec<_> = square(half, 0.0, 0.0)
                .into_iter()
                .map(|f| FeaturePoint { point: centre + lean * (twist * f.point.coords), ..f })
                .collect();
            // Around the face either way: the ring is the hull, counter-clockwise.
            let mut backwards = face.clone();
            backwards.reverse();
            let by_fit = Surface::fit(&frame, &fitted(&face), VertexIds::Named, Side::A).unwrap();
            let scale = 1e-9 * (1.0 + x.abs() + y.abs() + z.abs());
            for points in [face.clone(), backwards] {
                let placed = Feature {
                    points,
                    ring: true,
                    face_normal: Some(lean * Vector3::z()),
                    side_radius: None,
                    landing: Vec::new(),
                };
                let by_plane = Surface::fit(&frame, &placed, VertexIds::Named, Side::A).unwrap();
                prop_assert_eq!(by_plane.kind, PolygonKind::Polygon);
                let start = by_plane.ids.iter().position(|&id| id == by_fit.ids[0]).unwrap();
                for k in 0..4 {
                    prop_assert_eq!(by_plane.ids[(start + k) % 4], by_fit.ids[k]);
                    prop_assert_eq!(by_plane.outline[(start + k) % 4], by_fit.outline[k]);
                }
                for p in by_fit.outline.iter().chain([&Point2::new(0.1, 0.7)]) {
                    prop_assert!((by_plane.height(p) - by_fit.height(p)).abs() < scale);
                }
            }
            let ends = [Point3::new(-half, 0.2, 0.0), Point3::new(half, 0.2, 2.0 * half * edge_slope)];
            let edge: Vec<_> = numbered(ends.map(|p| centre + twist * p.coords).to_vec());
            let by_line =
                Surface::fit(&frame, &fitted(&edge), VertexIds::Unnamed, Side::A).unwrap();
            let plane: Vec<_> = edge.iter().map(|f| frame.to_plane(&f.point)).collect();
            let heights = edge.iter().map(|f| (f.point - frame.origin).dot(&frame.normal));
            let hull = ConvexPolygon::from_points(&plane).unwrap();
            let fit = least_squares_plane(&hull, &plane, heights).unwrap();
            for p in plane.iter().chain([&nalgebra::center(&plane[0], &plane[1])]) {
                let least = fit.dot(&Vector3::new(1.0, p.x, p.y));
                prop_assert!((by_line.height(p) - least).abs() < scale);
            }
        });
    }

    /// A hull whose bottom is two faces meeting at a fold, each tilted 0.49° (within the 1°
    /// feature angle), sunk 3 mm at the fold into a tilted slab, and turned about the normal:
    /// the contact is as deep as the fold, whichever body is A, and each corner reads its own
    /// depth. The least-squares plane through the four bottom corners runs halfway up the
    /// fold's 6 mm and read about 0 mm, so the fold rested in the slab, under the slop; moved
    /// down to the fold, it read the raised corners 3 mm deep, 6 mm below where they are.
    #[test]
    fn a_folded_bottom_is_as_deep_as_its_fold() {
        let (fold, sunk) = (0.006, 0.003);
        // Two bottom corners on the fold's line (z = 0), two raised; a flat top.
        let mut points: Vec<Point3<f64>> = [(-0.5, -0.5, 0.0), (0.5, -0.5, fold), (0.5, 0.5, 0.0)]
            .into_iter()
            .chain([(-0.5, 0.5, fold)])
            .map(|(x, y, z)| Point3::new(x, y, z))
            .collect();
        points.extend(
            [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
                .map(|(x, y)| Point3::new(x, y, 0.5)),
        );
        let tilt = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.0);
        for turn in [0.0, 0.7, 2.0] {
            let hull_at = tilt * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn);
            let hull_origin = Point3::from(tilt * Vector3::new(0.2, -0.1, -sunk));
            let slab = || {
                BodyDesc::fixed(Shape::cuboid([6.0, 6.0, 1.0]))
                    .position((tilt * Vector3::new(0.0, 0.0, -0.5)).into())
                    .rotation(tilt)
            };
            let hull = || {
                BodyDesc::dynamic(Shape::convex(points.clone()))
                    .position(hull_origin.coords.into())
                    .rotation(hull_at)
            };
            for (name, first, second) in [
                ("slab first", slab(), hull()),
                ("hull first", hull(), slab()),
            ] {
                let mut world = crate::World::builder()
                    .body(first)
                    .body(second)
                    .build()
                    .unwrap();
                world.prepare_step(0.01).unwrap();
                let contact = world.contacts().next().expect("touching");
                assert!(
                    (contact.depth() - sunk).abs() < 1e-9,
                    "turn {turn}, {name}: {} mm deep, the fold {} mm",
                    contact.depth() * 1e3,
                    sunk * 1e3
                );
                // Each corner at its own depth: the two on the fold's line, the raised two.
                let mut depths = contact.depths.clone();
                depths.sort_by(f64::total_cmp);
                let expected = [sunk - fold, sunk - fold, sunk, sunk];
                assert!(
                    depths.len() == 4
                        && depths
                            .iter()
                            .zip(expected)
                            .all(|(d, e)| (d - e).abs() < 1e-9),
                    "turn {turn}, {name}: depths {depths:?}"
                );
            }
        }
    }

    /// A face tilted from the contact plane by just less than the feature angle is kept whole,
    /// and by just more is cut to its lowest edge: the angle alone decides, not the body's
    /// proportions. For a cube, a 3 m × 0.2 m slab and a thin plate, read off the box's axes and
    /// searched among the same corners as a hull, the bottom face tilted about either of its
    /// edge directions, either way, then turned about the normal. (The search's candidate band
    /// used to drop a cube's far face edge from 0.87° under a 1° angle.)
    #[test]
    fn a_face_is_kept_whole_up_to_the_feature_angle() {
        let degree = 1f64.to_radians();
        let angle = FeatureAngle::new(degree);
        for h in [
            Vector3::new(0.5, 0.5, 0.5),
            Vector3::new(1.5, 0.1, 0.5),
            Vector3::new(0.02, 2.0, 0.3),
        ] {
            let corners: Vec<_> = (0..8)
                .map(|k| {
                    let side = |bit: usize| if k & (1 << bit) == 0 { -1.0 } else { 1.0 };
                    Vector3::new(side(0) * h.x, side(1) * h.y, side(2) * h.z)
                })
                .collect();
            let outlines = [
                ("box", Outline::polyhedron(corners.clone(), Some(h))),
                ("hull", Outline::polyhedron(corners, None)),
            ];
            let tilts = [
                (Vector3::x(), 0.3),
                (Vector3::y(), 2.1),
                (-Vector3::x(), -1.2),
                (-Vector3::y(), 4.0),
            ];
            for (edge, turn) in tilts {
                // 2% either side of the angle: far beyond rounding and the 1e-9 m tolerance.
                for (tilt, whole) in [(0.98, true), (1.02, false)] {
                    let rotation = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn)
                        * UnitQuaternion::from_scaled_axis(edge * tilt * degree);
                    for (name, outline) in &outlines {
                        let mut feature = Feature::default();
                        let origin = Point3::new(1.0, -2.0, 0.5);
                        outline.feature(&origin, &rotation, &-Vector3::z(), &angle, &mut feature);
                        let expected = if whole { 4 } else { 2 };
                        assert_eq!(
                            feature.points.len(),
                            expected,
                            "{name} {h:?} tilted {tilt}° about {edge:?}"
                        );
                    }
                }
            }
        }
    }

    /// Where the landing tests place a body: off the world's origin.
    fn landing_origin() -> Point3<f64> {
        Point3::new(0.3, -0.2, 1.0)
    }

    /// `outline`'s feature along −z (feature angle 1°) at [`landing_origin`] turned by
    /// `rotation`, with its landing points within `band`.
    fn landing_down(outline: &Outline, rotation: &UnitQuaternion<f64>, band: f64) -> Feature {
        let (origin, down) = (landing_origin(), -Vector3::z());
        let mut feature = Feature::default();
        let angle = FeatureAngle::new(1f64.to_radians());
        outline.feature(&origin, rotation, &down, &angle, &mut feature);
        outline.landing(&origin, rotation, &down, (band, 0.0), &mut feature);
        feature
    }

    /// A cylinder touching with one point of its cap's rim (tilted past the feature angle,
    /// about an axis off the body's axes) lands on cap vertices within the band of that point,
    /// found here by brute force over the cap: on each side of the rim point, at most
    /// [`LANDING_POINTS_PER_SIDE`] of them, the farthest within the band always among them,
    /// and no run of the arc between two (or the rim point and the first) longer than its
    /// share (`⌈m / 3⌉` of the side's `m` vertices). The arc's size follows the closed form
    /// `R (1 − cos φ) sin θ ≤ band`. A cap lying flat, a side line and a box have none.
    #[test]
    fn a_cylinder_on_its_rim_lands_on_the_cap_vertices_within_the_band() {
        let (radius, half_height, band) = (0.4, 0.45, 0.005);
        let cylinder = Outline::Cylinder {
            radius,
            half_height,
        };
        let (origin, down) = (landing_origin(), -Vector3::z());
        let landing_of = |outline: &Outline, rotation: &UnitQuaternion<f64>| {
            landing_down(outline, rotation, band)
        };
        let axis = Vector3::new(1.0, 2.0, 0.0).normalize();
        let spacing = std::f64::consts::TAU / CAP_VERTICES as f64;
        for tilt in [1.4f64, 3.0, 10.0, 30.0, 60.0] {
            let rotation = UnitQuaternion::from_axis_angle(
                &nalgebra::Unit::new_normalize(axis),
                tilt.to_radians(),
            ) * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3);
            let feature = landing_of(&cylinder, &rotation);
            let [rim] = feature.points[..] else {
                panic!("{tilt}°: one rim point, got {}", feature.points.len());
            };
            // Angle round the cap from the rim point (body axes), signed by side.
            let local = |p: &Point3<f64>| rotation.inverse_transform_vector(&(p - origin));
            let rim_angle = local(&rim.point).y.atan2(local(&rim.point).x);
            let around = |p: &Point3<f64>| {
                let t = local(p).y.atan2(local(p).x) - rim_angle;
                (t + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
            };
            let rise = |v: &Point3<f64>| (v - rim.point).dot(&-down);
            let vertices: Vec<_> = cap_directions()
                .iter()
                .map(|(cos, sin)| {
                    origin + rotation * Vector3::new(radius * cos, radius * sin, -half_height)
                })
                .filter(|v| rise(v) <= band && (v - rim.point).norm() > 1e-9)
                .collect();
            let arc = (1.0 - band / (radius * tilt.to_radians().sin())).acos();
            for sign in [1.0, -1.0] {
                let case = format!("{tilt}°, side {sign}");
                let mut side: Vec<f64> = vertices
                    .iter()
                    .map(&around)
                    .filter(|t| t * sign > 0.0)
                    .map(f64::abs)
                    .collect();
                side.sort_by(f64::total_cmp);
                let m = side.len();
                let closed_form =
                    (arc / spacing).floor() as usize..=(arc / spacing).ceil() as usize;
                assert!(closed_form.contains(&m), "{case}: {m} in the band");
                let mut picked: Vec<f64> = feature
                    .landing
                    .iter()
                    .map(|l| around(&l.point))
                    .filter(|t| t * sign > 0.0)
                    .map(f64::abs)
                    .collect();
                picked.sort_by(f64::total_cmp);
                assert_eq!(picked.len(), m.min(LANDING_POINTS_PER_SIDE), "{case}");
                for t in &picked {
                    assert!(
                        side.iter().any(|s| (s - t).abs() < 1e-9),
                        "{case}: {t} not in the band"
                    );
                }
                if let (Some(last), Some(far)) = (picked.last(), side.last()) {
                    assert!(
                        (last - far).abs() < 1e-9,
                        "{case}: the farthest is left out"
                    );
                }
                let share = m.div_ceil(LANDING_POINTS_PER_SIDE) as f64 * spacing;
                let mut from = 0.0;
                for t in &picked {
                    assert!(
                        t - from <= share + spacing + 1e-9,
                        "{case}: a run of {} rad",
                        t - from
                    );
                    from = *t;
                }
            }
        }
        // Flat within the feature angle: the cap is the feature, nothing to land on.
        let flat = UnitQuaternion::from_axis_angle(
            &nalgebra::Unit::new_normalize(axis),
            0.5f64.to_radians(),
        );
        assert!(landing_of(&cylinder, &flat).landing.is_empty());
        // On its side: the side line.
        let side = UnitQuaternion::from_axis_angle(
            &nalgebra::Unit::new_normalize(axis),
            90f64.to_radians(),
        );
        let feature = landing_of(&cylinder, &side);
        assert_eq!(feature.points.len(), 2);
        assert!(feature.landing.is_empty());
        // A box on a corner: its corner is all it has.
        let h = Vector3::new(0.5, 0.5, 0.5);
        let cube = Outline::polyhedron(
            (0..8)
                .map(|k| {
                    h.component_mul(&Vector3::new(
                        if k & 1 == 0 { -1.0 } else { 1.0 },
                        if k & 2 == 0 { -1.0 } else { 1.0 },
                        if k & 4 == 0 { -1.0 } else { 1.0 },
                    ))
                })
                .collect(),
            Some(h),
        );
        let corner = UnitQuaternion::from_euler_angles(0.6, 0.5, 0.2);
        assert!(landing_of(&cube, &corner).landing.is_empty());
    }

    /// A cylinder tilted `θ` from upright, touching with one point of its cap's rim, also
    /// lands on the far end of the side line through that point, on the other cap's rim, 2h
    /// along its axis: exactly when that end stands back by no more than the band, `2h cos θ
    /// ≤ band` (a 1 cm cylinder from 60° on under a 5 mm band), named as the side line's end
    /// there. Off the body's axes, on either cap.
    #[test]
    fn a_cylinder_on_its_rim_nearly_on_its_side_lands_on_the_far_end_of_its_side_line() {
        let (radius, half_height, band) = (0.005, 0.005, 0.005);
        let cylinder = Outline::Cylinder {
            radius,
            half_height,
        };
        let (origin, down) = (landing_origin(), -Vector3::z());
        let axis = nalgebra::Unit::new_normalize(Vector3::new(1.0, 2.0, 0.0));
        for upside_down in [false, true] {
            for tilt in [30f64, 55.0, 61.0, 75.0, 88.0] {
                let tilt = if upside_down { 180.0 - tilt } else { tilt };
                let rotation = UnitQuaternion::from_axis_angle(&axis, tilt.to_radians())
                    * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3);
                let feature = landing_down(&cylinder, &rotation, band);
                let [rim] = feature.points[..] else {
                    panic!("{tilt}°: one rim point, got {}", feature.points.len());
                };
                let along_axis = rotation * Vector3::z();
                let far = feature
                    .landing
                    .iter()
                    .find(|l| ((l.point - rim.point).cross(&along_axis)).norm() < 1e-12);
                let stands_back = 2.0 * half_height * tilt.to_radians().cos().abs();
                let case = format!("{tilt}°");
                assert_eq!(far.is_some(), stands_back <= band, "{case}");
                if let Some(far) = far {
                    assert!(((far.point - rim.point).norm() - 2.0 * half_height).abs() < 1e-12);
                    assert!(((far.point - rim.point).dot(&-down) - stands_back).abs() < 1e-12);
                    // The side line's ends are named 2 n (bottom cap) and 2 n + 1 (top).
                    let bottom = rotation.inverse_transform_vector(&(far.point - origin)).z < 0.0;
                    let id = 2 * CAP_VERTICES as u32 + u32::from(!bottom);
                    assert_eq!(far.id, id, "{case}");
                }
            }
        }
    }
}
