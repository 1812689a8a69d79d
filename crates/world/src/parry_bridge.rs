//! Everything that touches parry3d: its glam types are converted here (and in [`epa`], which
//! works on its support functions) and nowhere else.
//!
//! Parry supplies the collision shapes, bounding boxes, solid mass properties of hulls, and the
//! contact normal of pairs with a curved shape (its GJK, then [`epa`] where they overlap, or its
//! ball manifolds). The support polygon itself is built by [`crate::support`] from the shapes'
//! full features, because parry's polygonal features hold at most four vertices (a cylinder cap
//! becomes a square).

use std::cell::RefCell;

use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3};
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::query::epa::EPA;
use parry3d_f64::query::gjk::{self, CsoPoint, GJKResult, VoronoiSimplex};
use parry3d_f64::query::{
    self, ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher, ShapeCastOptions,
    ShapeCastStatus, cast_shapes,
};
use parry3d_f64::shape::{Ball, ConvexPolyhedron, Cuboid, Cylinder, SharedShape, SupportMap};

use crate::HullMesh;
use crate::apart::{AxisFrame, AxisGap};
use crate::box_sat;
use crate::proved_normal::{FaceVerdict, PlacedCylinder, Solid, deepest_normal, face_verdict};
use crate::sat::{self, Polytope};
use crate::shape::{MassProperties, Shape};

mod epa;

fn to_glam(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x, v.y, v.z)
}

fn from_glam(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x, v.y, v.z)
}

fn from_glam_turn(q: Rotation) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q.w, q.x, q.y, q.z))
}

/// A body's collision shape placed in the world.
#[derive(Clone)]
pub(crate) struct Collider {
    shape: SharedShape,
    /// Pose of parry's shape in the body frame (parry's cylinders stand along y, ours along z).
    local: Pose,
    /// Whether `local` turns the shape (a cylinder's), fixed with it: a shape that is not turned
    /// is placed at the body's own pose ([`Collider::placed`]). Asked of `local` on every query
    /// instead, collision took 0.9% more instructions while the cube pile lands.
    turned: bool,
    /// A box's or a hull's faces and edges, for [`sat::separating_axis`].
    polytope: Option<Polytope>,
    /// A copy of the shape when it is a box, a ball or a cylinder: its bounding box, reach
    /// and box–box normal are then found from the collider alone, without reading the shape
    /// behind its pointer (for the 1000-cube pile's boxes a cache miss each: the bounding boxes
    /// took 0.12–0.24 ms a step while it settles, 0.03 ms from the copy).
    primitive: Primitive,
    /// A cylinder as a core rounded by [`ROUNDING`] of its size: the shape its contact normal
    /// against a polyhedron or a cylinder is found on (see [`contact_normal`]).
    rounded: Option<SharedShape>,
}

/// Rounding of a cylinder's rims for its contact normal, as a fraction of the smaller of its
/// radius and half-height. The rounded cylinder is the same surface except within this distance
/// of the rims, so a cap or the side touching a face or an edge gives the same normal; and GJK
/// on the core finds the normal of a pair overlapping by less than the rounding — 1 cm and more
/// on the bench's cylinders, five times the default 2 mm slop that resting contacts sink to —
/// without EPA (16% of the mixed pile's samples when every overlapping pair ran it, on a
/// new EPA each time; see [`gjk_then_epa`]).
const ROUNDING: f64 = 0.05;

/// A shape small enough to keep a copy of inline ([`Collider`]'s `primitive`).
#[derive(Clone, Copy)]
enum Primitive {
    Cuboid(Cuboid),
    Ball(Ball),
    Cylinder(Cylinder),
    /// A hull: its points are on the heap either way.
    Other,
}

impl Primitive {
    fn of(shape: &SharedShape) -> Self {
        if let Some(cuboid) = shape.as_cuboid() {
            Self::Cuboid(*cuboid)
        } else if let Some(ball) = shape.as_ball() {
            Self::Ball(*ball)
        } else if let Some(cylinder) = shape.as_cylinder() {
            Self::Cylinder(*cylinder)
        } else {
            Self::Other
        }
    }
}

impl std::fmt::Debug for Collider {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Collider").finish_non_exhaustive()
    }
}

/// Where a collider is: the pose of the shape's frame (the body's origin, not its centre of mass).
pub(crate) fn pose(origin: &Point3<f64>, rotation: &UnitQuaternion<f64>) -> Pose {
    let q = rotation.quaternion();
    Pose::from_parts(
        to_glam(&origin.coords),
        Rotation::from_xyzw(q.i, q.j, q.k, q.w),
    )
}

impl Collider {
    /// The parry shape of a valid `shape`; `None` if parry cannot build it (a flat hull).
    pub(crate) fn new(shape: &Shape) -> Option<Self> {
        let mut local = Pose::IDENTITY;
        let mut rounded = None;
        let shape = match shape {
            Shape::Box { half_extents: h } => SharedShape::cuboid(h.x, h.y, h.z),
            Shape::Sphere { radius } => SharedShape::ball(*radius),
            Shape::Cylinder {
                radius,
                half_height,
            } => {
                local = Pose::from_rotation(Rotation::from_rotation_x(std::f64::consts::FRAC_PI_2));
                let border = ROUNDING * radius.min(*half_height);
                rounded = Some(SharedShape::round_cylinder(
                    half_height - border,
                    radius - border,
                    border,
                ));
                SharedShape::cylinder(*half_height, *radius)
            }
            Shape::Convex { points } => SharedShape::new(hull(points)?),
        };
        let polytope = match shape.as_cuboid() {
            Some(cuboid) => box_polytope(cuboid),
            None => shape.as_convex_polyhedron().and_then(polytope),
        };
        Some(Self {
            primitive: Primitive::of(&shape),
            shape,
            turned: local != Pose::IDENTITY,
            local,
            polytope,
            rounded,
        })
    }

    /// Where parry's shape stands for a body at `pose`: `pose` itself unless the shape is
    /// turned in the body's frame (a cylinder). Composing with the identity gives the same
    /// pose (to the sign of a zero), at the cost of a rotation product on every query.
    fn placed(&self, pose: &Pose) -> Pose {
        if self.turned {
            *pose * self.local
        } else {
            *pose
        }
    }

    /// World bounding box at `pose`, grown by `margin`. A cylinder's is exact in closed form:
    /// along each world axis `eᵢ` it reaches `h |uᵢ| + r √(1 − uᵢ²)` from its centre, for its
    /// axis `u`, where parry's takes six support points (the boxes took 1.3% of the mixed
    /// pile's one-thread profile samples with them, 0.8% now).
    pub(crate) fn aabb(&self, pose: &Pose, margin: f64) -> (Vector3<f64>, Vector3<f64>) {
        let placed = self.placed(pose);
        let grow = Vector3::repeat(margin);
        let aabb = match &self.primitive {
            Primitive::Cylinder(cylinder) => {
                // parry's cylinders stand along y.
                let axis = from_glam(placed.rotation * Vector::Y);
                let reach = axis.map(|u| {
                    cylinder.half_height * u.abs() + cylinder.radius * (1.0 - u * u).max(0.0).sqrt()
                });
                let centre = from_glam(placed.translation);
                return (centre - reach - grow, centre + reach + grow);
            }
            Primitive::Cuboid(cuboid) => cuboid.aabb(&placed),
            Primitive::Ball(ball) => ball.aabb(&placed),
            Primitive::Other => self.shape.compute_aabb(&placed),
        };
        (from_glam(aabb.mins) - grow, from_glam(aabb.maxs) + grow)
    }

    /// How deep this shape at `pose` and `other` at `other_pose` overlap (m, along parry's
    /// least direction out of each other); 0 when apart, or when parry has no query for the
    /// pair.
    pub(crate) fn depth_into(&self, pose: &Pose, other: &Collider, other_pose: &Pose) -> f64 {
        let (placed, other_placed) = (self.placed(pose), other.placed(other_pose));
        match query::contact(&placed, &*self.shape, &other_placed, &*other.shape, 0.0) {
            Ok(Some(contact)) => (-contact.dist).max(0.0),
            Ok(None) | Err(_) => 0.0,
        }
    }

    /// The least width across the shape (m): a polytope's between a face's plane and the
    /// farthest vertex behind it, a ball's diameter, a cylinder's diameter or height.
    pub(crate) fn thickness(&self) -> f64 {
        if let Some(polytope) = &self.polytope {
            return polytope.thickness();
        }
        if let Some(ball) = self.shape.as_ball() {
            return 2.0 * ball.radius;
        }
        self.shape.as_cylinder().map_or(f64::INFINITY, |cylinder| {
            2.0 * cylinder.radius.min(cylinder.half_height)
        })
    }

    /// Whether the contact normal against this shape may come from its rounded core (a
    /// cylinder's, see [`ROUNDING`]), found within more than the prediction of the true shapes:
    /// such a pair's contact is kept only when its true depth is within the prediction.
    pub(crate) fn is_rounded(&self) -> bool {
        self.rounded.is_some()
    }

    /// How far this shape at `pose` reaches along the unit `direction` (world): its support
    /// plane's offset, `max x · direction` over its points. `None` for a shape without a
    /// support function (none of the world's).
    pub(crate) fn reach_along(&self, pose: &Pose, direction: &Vector3<f64>) -> Option<f64> {
        let towards = to_glam(direction);
        let placed = self.placed(pose);
        let point = match &self.primitive {
            Primitive::Cuboid(cuboid) => cuboid.support_point(&placed, towards),
            Primitive::Ball(ball) => ball.support_point(&placed, towards),
            Primitive::Cylinder(cylinder) => cylinder.support_point(&placed, towards),
            Primitive::Other => self.shape.as_support_map()?.support_point(&placed, towards),
        };
        Some(point.dot(towards))
    }

    /// Whether `direction` (in the shape's frame) leans off both a cylinder's axis and its
    /// side's normals, as the normal of its rounded rim does: not for other shapes.
    fn leans(&self, direction: Vector) -> bool {
        // parry's cylinders stand along y; a cap's or the side's normal from GJK is one to
        // rounding, within 1e-6 here.
        let across = direction.x.hypot(direction.z);
        self.rounded.is_some() && direction.y.abs() > 1e-6 && across > 1e-6
    }

    /// The shape as [`deepest_normal`] reads it, its shape's frame placed by `pose`: a box or a
    /// hull, or a cylinder; `None` for a ball.
    fn solid(&self, pose: &Pose) -> Option<Solid<'_>> {
        if let Some(polytope) = &self.polytope {
            return Some(Solid::Polytope {
                polytope,
                rotation: from_glam_turn(pose.rotation),
                translation: from_glam(pose.translation),
            });
        }
        let cylinder = self.shape.as_cylinder()?;
        // The body's frame, where the cylinder stands along z (parry's along y).
        let body = *pose * self.local.inverse();
        Some(Solid::Cylinder(PlacedCylinder {
            centre: from_glam(body.translation),
            rotation: from_glam_turn(body.rotation),
            radius: cylinder.radius,
            half_height: cylinder.half_height,
        }))
    }

    /// The shape whose contact normal stands for this one's: the rounded core of a cylinder
    /// (see [`ROUNDING`]), except against a ball.
    fn normal_shape(&self, against_ball: bool) -> &SharedShape {
        match &self.rounded {
            Some(rounded) if !against_ball => rounded,
            _ => &self.shape,
        }
    }

    /// The face planes `(n, d)` in the shape's frame (outward unit normal, `n · x = d` on the
    /// face) that can show it apart from another shape: a polytope's faces, a cylinder's two
    /// caps (parry's cylinders stand along y), none for a ball.
    fn faces(&self) -> impl Iterator<Item = (Vector3<f64>, f64)> + '_ {
        let polytope = self.polytope.iter().flat_map(|p| p.faces().iter().copied());
        let caps = self
            .shape
            .as_cylinder()
            .into_iter()
            .flat_map(|c| [Vector3::y(), -Vector3::y()].map(|n| (n, c.half_height)));
        polytope.chain(caps)
    }

    /// Vertices of a polyhedral shape's hull in its frame; `None` for a curved shape.
    pub(crate) fn hull_vertices(&self) -> Option<Vec<Vector3<f64>>> {
        if let Some(cuboid) = self.shape.as_cuboid() {
            return Some(corners(cuboid));
        }
        let hull = self.shape.as_convex_polyhedron()?;
        Some(hull.points().iter().map(|p| from_glam(*p)).collect())
    }
}

/// A box's eight corners in its frame, corner `i` on the `+k` side where bit `k` of `i` is set:
/// the numbering [`crate::box_feature`] names a box's feature points by.
fn corners(cuboid: &Cuboid) -> Vec<Vector3<f64>> {
    let h = from_glam(cuboid.half_extents);
    (0..8)
        .map(|i: u8| {
            let s = |bit: u8| if i & bit == 0 { -1.0 } else { 1.0 };
            Vector3::new(s(1) * h.x, s(2) * h.y, s(4) * h.z)
        })
        .collect()
}

/// A box's corners ([`corners`]), six faces and twelve edges as a [`Polytope`], in closed
/// form: parry's hull of the corners of a slab 100 km wide and 2 m thick came out flat, two
/// faces with their offsets swapped, and a cylinder standing on it fell through.
fn box_polytope(cuboid: &Cuboid) -> Option<Polytope> {
    // Face `2k` is the +k side, `2k + 1` the −k side; corner `i` is on the +k side where bit
    // `k` of `i` is set.
    let side = |corner: usize, axis: usize| 2 * axis + usize::from(corner & (1 << axis) == 0);
    let faces: Vec<(Vector3<f64>, usize)> = (0..6)
        .map(|f| {
            let (axis, outward) = (f / 2, f % 2 == 0);
            let normal = Vector3::ith(axis, if outward { 1.0 } else { -1.0 });
            (normal, if outward { 1 << axis } else { 0 })
        })
        .collect();
    let edges: Vec<([usize; 2], [usize; 2])> = (0..3)
        .flat_map(|axis| {
            (0..8)
                .filter(move |corner| corner & (1 << axis) == 0)
                .map(move |corner| {
                    let [j, k] = [(axis + 1) % 3, (axis + 2) % 3];
                    (
                        [corner, corner | 1 << axis],
                        [side(corner, j), side(corner, k)],
                    )
                })
        })
        .collect();
    Polytope::new(corners(cuboid), &faces, &edges)
}

/// A parry polyhedron's vertices, faces and edges as a [`Polytope`].
fn polytope(hull: &ConvexPolyhedron) -> Option<Polytope> {
    let vertices = hull.points().iter().map(|p| from_glam(*p)).collect();
    let adjacent = hull.vertices_adj_to_face();
    let faces = hull
        .faces()
        .iter()
        .map(|f| {
            let first = adjacent.get(f.first_vertex_or_edge as usize)?;
            Some((from_glam(f.normal), *first as usize))
        })
        .collect::<Option<Vec<_>>>()?;
    let edges: Vec<_> = hull
        .edges()
        .iter()
        .map(|e| {
            let [v, w] = e.vertices.map(|v| v as usize);
            let [f, g] = e.faces.map(|f| f as usize);
            ([v, w], [f, g])
        })
        .collect();
    Polytope::new(vertices, &faces, &edges)
}

/// How two colliders cast along their velocities meet within a step ([`meet_within`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Cast {
    /// They do not come within the allowance.
    Miss,
    /// They do; with the unit normal from `b` into `a` where they first do, when the cast
    /// gives one (not for a pair within the allowance from the start, nor one parry cannot
    /// cast).
    Meet(Option<Vector3<f64>>),
}

/// Whether `a` and `b`, from `pose_a` and `pose_b` and moving on at the linear velocities
/// `velocity_a` and `velocity_b`, come within `allowance` of each other within `dt`, and their
/// normal there: parry's linear shape cast. The allowance stands for what the bodies' turns
/// may add; a pair parry cannot cast counts as meeting.
pub(crate) fn meet_within(
    (a, pose_a, velocity_a): (&Collider, &Pose, &Vector3<f64>),
    (b, pose_b, velocity_b): (&Collider, &Pose, &Vector3<f64>),
    allowance: f64,
    dt: f64,
) -> Cast {
    let options = ShapeCastOptions {
        max_time_of_impact: dt,
        target_distance: allowance,
        stop_at_penetration: true,
        compute_impact_geometry_on_penetration: false,
    };
    let pose_b = b.placed(pose_b);
    let hit = cast_shapes(
        &a.placed(pose_a),
        to_glam(velocity_a),
        &*a.shape,
        &pose_b,
        to_glam(velocity_b),
        &*b.shape,
        options,
    );
    match hit {
        Ok(None) => Cast::Miss,
        Ok(Some(hit)) if hit.status == ShapeCastStatus::Converged => {
            // B's outward normal, in its shape's frame: from B into A.
            let normal = from_glam(pose_b.rotation * hit.normal2);
            let length = normal.norm();
            Cast::Meet((length.is_finite() && length > 0.0).then(|| normal / length))
        }
        Ok(Some(_)) | Err(_) => Cast::Meet(None),
    }
}

/// The unit contact normal between two colliders, pointing from `b` into `a`, when they are
/// closer than `prediction`: by the separating-axis test for two boxes (parry's) or two
/// polytopes ([`sat`]), else from parry's GJK (and [`epa`]) on a cylinder's rounded core (see
/// [`ROUNDING`]) — or its contact manifold when one is a ball, whose exact projection is
/// already cheap.
///
/// An error otherwise, with what showed the pair apart when something did — a face normal of
/// either, a cylinder's cap, an edge–edge axis of two polytopes, a curved pair's separating
/// direction, or two balls' gap ([`AxisGap::frame`] says whose, `First` meaning `a`'s) — for
/// [`crate::apart`].
///
/// `hint`, the pair's normal at its last contact, is where GJK starts its search: a direction
/// near the answer saves it iterations (it still converges to the same closest points, from
/// anywhere). On the 1000-shape pile, where most pairs GJK decides are recomputed contacts
/// whose normal has turned a little since, it took 8% off the collision stage.
pub(crate) fn contact_normal(
    a: &Collider,
    pose_a: &Pose,
    b: &Collider,
    pose_b: &Pose,
    prediction: f64,
    hint: Option<&Vector3<f64>>,
) -> Result<Vector3<f64>, Option<AxisGap>> {
    let (pose_a, pose_b) = (a.placed(pose_a), b.placed(pose_b));
    let pos_ba = pose_b.inverse() * pose_a;
    // The tests below take `b` first.
    let of_a = |gap: Option<AxisGap>| {
        gap.map(|g| AxisGap {
            frame: g.frame.swapped(),
            ..g
        })
    };
    if let (Primitive::Cuboid(box_b), Primitive::Cuboid(box_a)) = (&b.primitive, &a.primitive) {
        return box_sat::cuboid_normal(box_b, box_a, &pos_ba, prediction)
            .map(|local| from_glam(pose_b.rotation * local).normalize())
            .map_err(of_a);
    }
    if let (Some(polytope_b), Some(polytope_a)) = (&b.polytope, &a.polytope) {
        let rotation = from_glam_turn(pos_ba.rotation);
        let translation = from_glam(pos_ba.translation);
        let (_, local) =
            sat::separating_axis(polytope_b, polytope_a, &rotation, &translation, prediction)
                .map_err(of_a)?;
        return Ok(from_glam(pose_b.rotation * to_glam(&local)).normalize());
    }
    if let Some(verdict) = cylinder_on_face(a, &pose_a, b, &pose_b, prediction) {
        return verdict;
    }
    let balls = a.shape.as_ball().is_some() || b.shape.as_ball().is_some();
    let (shape_a, shape_b) = (a.normal_shape(balls), b.normal_shape(balls));
    let local_normal = if let (false, Some((core_b, radius_b)), Some((core_a, radius_a))) = (
        balls,
        shape_b.as_polygonal_feature_map(),
        shape_a.as_polygonal_feature_map(),
    ) {
        // What parry's manifold for two such shapes takes its normal from, without the
        // features and clipping it would add (a sixth of the manifold's time) and its buffers.
        // A cylinder's rim stands (√2 − 1) times the rounding out of its rounded core, so two
        // rims crossing can overlap while the rounded shapes are apart by up to that much of
        // each: the cores are searched within the prediction plus √2 times their roundings,
        // and the contact keeps to the prediction on the true shapes ([`Collider::is_rounded`]).
        match gjk_then_epa(
            &pos_ba,
            core_b,
            core_a,
            prediction + std::f64::consts::SQRT_2 * (radius_b + radius_a),
            // GJK's directions are in `b`'s frame, pointing out of `b`, as the normal does.
            hint.map(|n| pose_b.rotation.inverse() * to_glam(n)),
        ) {
            // Near a rim the rounded shape's normal is not the true shapes' ([`sharp_normal`]).
            GJKResult::ClosestPoints(_, _, normal)
                if b.leans(normal) || a.leans(pos_ba.rotation.inverse() * normal) =>
            {
                deepest_of(a, b, &pos_ba, normal)
                    .or_else(|| sharp_normal(a, b, &pos_ba, prediction, normal))
                    .unwrap_or(normal)
            }
            GJKResult::ClosestPoints(_, _, normal) => normal,
            // The cores are apart along `dir` (out of `b`) by more than the search's reach,
            // so the true shapes by more than the prediction.
            GJKResult::NoIntersection(dir) => {
                let axis = pose_b.rotation * -dir;
                return Err(curved_gap(a, &pose_a, b, &pose_b, prediction, || {
                    Some(axis)
                }));
            }
            _ => return Err(curved_gap(a, &pose_a, b, &pose_b, prediction, || None)),
        }
    } else {
        let mut manifolds: Vec<ContactManifold<(), ()>> = Vec::new();
        DefaultQueryDispatcher
            .contact_manifolds(
                &pos_ba,
                &**shape_b,
                &**shape_a,
                prediction,
                &mut manifolds,
                &mut None,
            )
            .map_err(|_| None)?;
        let Some(manifold) = manifolds.iter().find(|m| !m.points.is_empty()) else {
            let axis = || ball_axis(a, &pose_a, b, &pose_b);
            return Err(curved_gap(a, &pose_a, b, &pose_b, prediction, axis));
        };
        manifold.local_n1
    };
    let normal = from_glam(pose_b.rotation * local_normal);
    let length = normal.norm();
    (length.is_finite() && length > 0.0)
        .then(|| normal / length)
        .ok_or(None)
}

/// The least-penetration normal (out of `b`, in its shape's frame) of `a` (placed there by
/// `pos_ba`) overlapping `b`, proved from a point of either inside the other
/// ([`deepest_normal`]), searched from `start`: what EPA converges to, without it. `None` where
/// no point proves it.
fn deepest_of(a: &Collider, b: &Collider, pos_ba: &Pose, start: Vector) -> Option<Vector> {
    let (solid_a, solid_b) = (a.solid(pos_ba)?, b.solid(&Pose::IDENTITY)?);
    let scale = 1.0 + pos_ba.translation.length();
    let start = from_glam(start);
    deepest_normal(&solid_b, &solid_a, &start, scale)
        .or_else(|| deepest_normal(&solid_a, &solid_b, &-start, scale).map(|n| -n))
        .map(|n| to_glam(&n))
}

/// A cylinder against a box or a hull (placed by the poses of their shapes' frames) when a face
/// of the polytope is proved to give their normal, or to hold them apart beyond `prediction`
/// ([`crate::proved_normal`]): [`contact_normal`]'s answer, from `b` into `a`. `None` for any
/// other pair, and where the faces prove neither.
fn cylinder_on_face(
    a: &Collider,
    pose_a: &Pose,
    b: &Collider,
    pose_b: &Pose,
    prediction: f64,
) -> Option<Result<Vector3<f64>, Option<AxisGap>>> {
    let (polytope_is_a, polytope, polytope_pose, cylinder, cylinder_pose) =
        match (&a.polytope, &b.polytope) {
            (Some(polytope), _) => (true, polytope, pose_a, b, pose_b),
            (_, Some(polytope)) => (false, polytope, pose_b, a, pose_a),
            _ => return None,
        };
    // The cylinder in the polytope's frame.
    let Some(Solid::Cylinder(placed)) = cylinder.solid(&(polytope_pose.inverse() * *cylinder_pose))
    else {
        return None;
    };
    Some(match face_verdict(polytope, &placed, prediction)? {
        FaceVerdict::Normal(outward) => {
            let normal = from_glam(polytope_pose.rotation * to_glam(&outward));
            Ok(if polytope_is_a { -normal } else { normal })
        }
        FaceVerdict::Apart(separation) => Err(Some(AxisGap {
            separation,
            frame: AxisFrame::of_first(polytope_is_a),
        })),
    })
}

/// Least distance or overlap (m) of the true shapes at which [`sharp_normal`] gives their
/// normal: nearer, their closest points (or EPA's deepest ones) are too near each other to give
/// it to rounding.
const SHARP_GAP: f64 = 1e-6;

/// The normal (out of `b`, in its frame) of the true shapes of `a` and `b` (placed by `pos_ba`)
/// within `prediction` of each other or overlapping, by GJK on them from `start`, and EPA
/// when they overlap; `None` when they are farther apart, touch within [`SHARP_GAP`], or a
/// shape has no support function.
///
/// Within the rounding of a cylinder's rim the rounded cylinder's surface turns from the cap to
/// the side, so against an edge, a corner or another rim its normal leans off the true one
/// ([`Collider::leans`]): by up to 18° among random pairs within the margin, whose contact then
/// read up to 4.9 mm closer than the shapes were, and overlapping ones up to 3.6 mm deeper
/// (`collision::tests`). There the true shapes' normal is sought; a cap or a side touching
/// flat keeps the rounded shape's, which is the true one and which EPA's, on a flat cap, is off
/// by more.
fn sharp_normal(
    a: &Collider,
    b: &Collider,
    pos_ba: &Pose,
    prediction: f64,
    start: Vector,
) -> Option<Vector> {
    let (shape_b, shape_a) = (b.shape.as_support_map()?, a.shape.as_support_map()?);
    match gjk_then_epa(pos_ba, shape_b, shape_a, prediction, Some(start)) {
        GJKResult::ClosestPoints(on_b, on_a, normal)
            if (on_a - on_b).dot(normal).abs() > SHARP_GAP =>
        {
            Some(normal)
        }
        _ => None,
    }
}

/// Parry's `contact_support_map_support_map_with_params`, step for step up to its EPA, with
/// this thread's EPA buffers: parry builds a new EPA, and allocates its buffers, for every pair
/// whose shapes overlap (the pile's threads then also waited on the allocator's lock). Its GJK
/// searches from `start` (in `pos12`'s first frame), or from the centres' offset. Where the
/// shapes overlap, [`epa::Epa`] finds the way out to a tolerance relative to their size, and
/// parry's EPA where that cannot ([`epa::Epa::closest_points`]).
fn gjk_then_epa<G1, G2>(
    pos12: &Pose,
    g1: &G1,
    g2: &G2,
    prediction: f64,
    start: Option<Vector>,
) -> GJKResult
where
    G1: ?Sized + SupportMap,
    G2: ?Sized + SupportMap,
{
    thread_local! {
        static EPA_BUFFERS: RefCell<(epa::Epa, EPA)> = RefCell::new(Default::default());
    }
    let dir = start
        .or_else(|| pos12.translation.try_normalize())
        .unwrap_or(Vector::X);
    let mut simplex = VoronoiSimplex::new();
    simplex.reset(CsoPoint::from_shapes(pos12, g1, g2, dir));
    let found = gjk::closest_points(pos12, g1, g2, prediction, true, &mut simplex);
    if found != GJKResult::Intersection {
        return found;
    }
    // The origin is inside the shapes' difference: EPA finds the way out.
    EPA_BUFFERS
        .with_borrow_mut(|(relative, parrys)| {
            (relative.closest_points(pos12, g1, g2, &simplex))
                .or_else(|| parrys.closest_points(pos12, g1, g2, &simplex))
        })
        .map_or(
            GJKResult::NoIntersection(Vector::X),
            |(on_1, on_2, normal)| GJKResult::ClosestPoints(on_1, on_2, normal),
        )
}

/// Two colliders that parry's GJK or manifold found apart, one of them curved, placed by the
/// poses of their shapes' frames: the axis that separates them most, if by more than
/// `prediction`, among the face planes of either (a polytope's faces, a cylinder's caps) and,
/// if those do not, the direction from `a` towards `b` that `axis` gives (GJK's separating
/// direction, or a ball's from the other shape's nearest point); for two balls, the gap
/// between them (the bound of [`crate::apart`] holds for it too, as their distance follows
/// their centres).
///
/// Each separation is measured with the shapes' exact support functions, so it is at most
/// their distance, and parry reports a contact only closer than `prediction`: its GJK distance
/// is never below the true one, and a cylinder's rounded core lies inside the cylinder. Any
/// axis fixed in one body's frame serves the bound ([`crate::apart`]); `a`'s holds `axis`.
/// Without it, a cylinder beside a cylinder or a ball, whose side no face plane shows apart,
/// was tested afresh every step: 270 such pairs a step as the mixed pile settles, more than
/// its recomputed contacts.
fn curved_gap(
    a: &Collider,
    pose_a: &Pose,
    b: &Collider,
    pose_b: &Pose,
    prediction: f64,
    axis: impl FnOnce() -> Option<Vector>,
) -> Option<AxisGap> {
    if let (Some(ball_a), Some(ball_b)) = (a.shape.as_ball(), b.shape.as_ball()) {
        let gap =
            (pose_a.translation - pose_b.translation).length() - ball_a.radius - ball_b.radius;
        return (gap > prediction).then_some(AxisGap {
            separation: gap,
            frame: AxisFrame::First,
        });
    }
    // The separation of `other` beyond `owner`'s plane `(n, d)`, `n` in `owner`'s frame.
    let beyond = |owner_pose: &Pose, other: &Collider, other_pose: &Pose, (n, d): (Vector, f64)| {
        let normal = owner_pose.rotation * n;
        let support = other.shape.as_support_map()?;
        let towards = other_pose.rotation.inverse() * -normal;
        let point = other_pose.transform_point(support.local_support_point(towards));
        Some(normal.dot(point - owner_pose.translation) - d)
    };
    let separations = |owner: &Collider, owner_pose: &Pose, other: &Collider, other_pose: &Pose| {
        owner
            .faces()
            .filter_map(|(n, d)| beyond(owner_pose, other, other_pose, (to_glam(&n), d)))
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let (of_a, of_b) = (
        separations(a, pose_a, b, pose_b),
        separations(b, pose_b, a, pose_a),
    );
    let (mut separation, mut on_first) = if of_a >= of_b {
        (of_a, true)
    } else {
        (of_b, false)
    };
    if separation <= prediction
        && let Some(axis) = axis().and_then(Vector::try_normalize)
        && let Some(support_a) = a.shape.as_support_map()
    {
        // `a`'s plane through its furthest point along the axis.
        let local = pose_a.rotation.inverse() * axis;
        let offset = support_a.local_support_point(local).dot(local);
        let along = beyond(pose_a, b, pose_b, (local, offset)).unwrap_or(f64::NEG_INFINITY);
        if along > separation {
            (separation, on_first) = (along, true);
        }
    }
    (separation > prediction).then_some(AxisGap {
        separation,
        frame: AxisFrame::of_first(on_first),
    })
}

/// The direction from `a` towards `b` where one of them is a ball: from the other shape's point
/// nearest the ball's centre to the centre, or back; `None` if the centre is inside the other
/// shape.
fn ball_axis(a: &Collider, pose_a: &Pose, b: &Collider, pose_b: &Pose) -> Option<Vector> {
    let (ball_is_b, other, other_pose, centre) = if b.shape.as_ball().is_some() {
        (true, a, pose_a, pose_b.translation)
    } else if a.shape.as_ball().is_some() {
        (false, b, pose_b, pose_a.translation)
    } else {
        return None;
    };
    let nearest = other.shape.project_point(other_pose, centre, true);
    if nearest.is_inside {
        return None;
    }
    let outward = centre - nearest.point;
    Some(if ball_is_b { outward } else { -outward })
}

fn glam_points(points: &[Point3<f64>]) -> Vec<Vector> {
    points.iter().map(|p| to_glam(&p.coords)).collect()
}

/// The convex hull of `points` as a collider (see [`hull_mesh`]).
pub(crate) fn hull(points: &[Point3<f64>]) -> Option<ConvexPolyhedron> {
    let mesh = hull_mesh(points)?;
    ConvexPolyhedron::from_convex_mesh(
        mesh.vertices.iter().map(|p| to_glam(&p.coords)).collect(),
        &mesh.triangles,
    )
}

/// The convex hull of `points`, its triangles wound outwards, checked: every point on the inner
/// side of every face.
///
/// parry's hull of exactly four points is sometimes flat (two triangles) or turned inside out —
/// about 1 in 400 random tetrahedra — so a tetrahedron is built from its four faces directly,
/// wound outwards. A hull that fails the check is `None` rather than a wrong collider.
pub(crate) fn hull_mesh(points: &[Point3<f64>]) -> Option<HullMesh> {
    let (vertices, triangles) = match points {
        [a, b, c, d] => {
            // Wind the faces outwards: (b − a) × (c − a) points away from d when the signed
            // volume is negative.
            let volume = (b - a).cross(&(c - a)).dot(&(d - a));
            let faces = if volume < 0.0 {
                [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]
            } else {
                [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
            };
            (glam_points(points), faces.to_vec())
        }
        _ => parry3d_f64::transformation::try_convex_hull(&glam_points(points)).ok()?,
    };
    let extent = points
        .iter()
        .flat_map(|p| p.iter().map(|x| x.abs()))
        .fold(0.0, f64::max);
    // Round-off of a plane test on coordinates of size `extent`.
    let tolerance = 1e-9 * extent;
    let corner = |i: u32| from_glam(vertices[i as usize]);
    let inside = triangles.len() >= 4
        && triangles.iter().all(|&[i, j, k]| {
            let normal = (corner(j) - corner(i)).cross(&(corner(k) - corner(i)));
            let length = normal.norm();
            length > 0.0
                && points
                    .iter()
                    .all(|p| normal.dot(&(p.coords - corner(i))) <= tolerance * length)
        });
    inside.then(|| {
        let vertices = vertices.iter().map(|v| from_glam(*v).into()).collect();
        HullMesh {
            vertices,
            triangles,
        }
    })
}

/// Volume, centroid and unit-mass inertia of the hull of `points`; `None` without volume.
pub(crate) fn convex_mass_properties(points: &[Point3<f64>]) -> Option<MassProperties> {
    let hull = hull(points)?;
    let unit_density = parry3d_f64::shape::Shape::mass_properties(&hull, 1.0);
    let volume = unit_density.mass();
    if !(volume.is_finite() && volume > 0.0) {
        return None;
    }
    let inertia = unit_density.reconstruct_inertia_matrix();
    let columns = [inertia.x_axis, inertia.y_axis, inertia.z_axis].map(from_glam);
    Some(MassProperties {
        volume,
        centre_of_mass: from_glam(unit_density.local_com).into(),
        unit_inertia: Matrix3::from_columns(&columns) / volume,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The distance between two colliders' true shapes, by parry's own query (0 when they
    /// overlap): a reference independent of the contact normal's tests.
    pub(crate) fn sharp_distance(a: &Collider, pose_a: &Pose, b: &Collider, pose_b: &Pose) -> f64 {
        let (sharp_a, sharp_b) = (*pose_a * a.local, *pose_b * b.local);
        parry3d_f64::query::distance(&sharp_a, &*a.shape, &sharp_b, &*b.shape)
            .expect("convex shapes")
            .distance
    }

    /// How far a collider's true shape, its body placed by `p`, reaches along the unit `d`.
    fn support(c: &Collider, p: &Pose, d: Vector) -> f64 {
        c.reach_along(p, &from_glam(d)).expect("convex")
    }

    /// A deterministic uniform generator on [0, 1) (a 64-bit LCG's top 53 bits).
    pub(crate) fn uniform_from(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Random tetrahedra of sizes 1 cm to 10 m: the hull's volume is the determinant's, where
    /// parry's own hull lost about one in 400 (flat, volume ~1e-17) and wound others inwards.
    #[test]
    fn every_tetrahedron_has_its_volume_and_outward_faces() {
        let mut uniform = uniform_from(12345);
        for i in 0..4000 {
            let scale = [0.01, 0.1, 1.0, 10.0][i % 4];
            let p: Vec<Point3<f64>> = (0..4)
                .map(|_| Point3::new(uniform(), uniform(), uniform()) * scale)
                .collect();
            let want = (p[1] - p[0])
                .cross(&(p[2] - p[0]))
                .dot(&(p[3] - p[0]))
                .abs()
                / 6.0;
            if want < 1e-6 * scale.powi(3) {
                continue; // nearly flat: no volume to compare
            }
            let got = convex_mass_properties(&p)
                .expect("a tetrahedron has a hull")
                .volume;
            assert!((got - want).abs() <= 1e-9 * want, "{p:?}: {got} vs {want}");
        }
    }

    /// A turn by Euler angles drawn in ±3 rad.
    fn random_turn(between: &mut dyn FnMut(f64, f64) -> f64) -> UnitQuaternion<f64> {
        UnitQuaternion::from_euler_angles(
            between(-3.0, 3.0),
            between(-3.0, 3.0),
            between(-3.0, 3.0),
        )
    }

    /// A cylinder of radius 0.25–0.5 m and half-height 0.2–0.5 m, and by `case` a box, a
    /// 10-point hull or another such cylinder.
    fn a_cylinder_and_another(
        case: usize,
        between: &mut dyn FnMut(f64, f64) -> f64,
    ) -> (Shape, Shape) {
        let cylinder = |between: &mut dyn FnMut(f64, f64) -> f64| Shape::Cylinder {
            radius: between(0.25, 0.5),
            half_height: between(0.2, 0.5),
        };
        let first = cylinder(between);
        let other = match case % 3 {
            0 => Shape::cuboid([between(0.4, 1.0), between(0.4, 1.0), between(0.4, 1.0)]),
            1 => Shape::Convex {
                points: (0..10)
                    .map(|_| {
                        Point3::new(between(-0.5, 0.5), between(-0.5, 0.5), between(-0.5, 0.5))
                    })
                    .collect(),
            },
            _ => cylinder(between),
        };
        (first, other)
    }

    /// The separating-axis normal of two hulls, or of a hull and a box, against parry's GJK and
    /// EPA (`query::contact`, the path the hulls took before): on overlapping pairs the least
    /// overlap is the same, and it is the overlap along the returned axis; on pairs apart, the
    /// test's separation is a lower bound of the distance (it equals it when the closest features
    /// are a face or two edges).
    #[test]
    fn polytope_normals_agree_with_gjk_and_epa() {
        let mut unit = uniform_from(2024);
        let mut uniform = || unit() * 2.0 - 1.0;
        let mut compared = 0;
        for case in 0..1500 {
            let mut shape = |k: usize| -> Shape {
                if k.is_multiple_of(3) {
                    Shape::cuboid([1.0 + uniform().abs(), 0.5 + uniform().abs(), 0.7])
                } else {
                    let points = (0..4 + case % 9)
                        .map(|_| Point3::new(uniform(), uniform(), uniform() * 0.6))
                        .collect();
                    Shape::Convex { points }
                }
            };
            let (shape_a, shape_b) = (shape(case), shape(case / 3 + 1));
            let (Some(a), Some(b)) = (Collider::new(&shape_a), Collider::new(&shape_b)) else {
                continue;
            };
            let turn = |x: f64, y: f64, z: f64| {
                UnitQuaternion::from_euler_angles(x * 3.0, y * 3.0, z * 3.0)
            };
            let pose_a = pose(&Point3::origin(), &turn(uniform(), uniform(), uniform()));
            let centre_b = Point3::new(uniform(), uniform(), uniform()) * 1.5;
            let pose_b = pose(&centre_b, &turn(uniform(), uniform(), uniform()));
            let (Some(polytope_a), Some(polytope_b)) = (&a.polytope, &b.polytope) else {
                panic!("boxes and hulls have polytopes");
            };
            let pos_ab = pose_a.inverse() * pose_b;
            let rotation = from_glam_turn(pos_ab.rotation);
            let translation = from_glam(pos_ab.translation);
            let (separation, axis) = sat::separating_axis(
                polytope_a,
                polytope_b,
                &rotation,
                &translation,
                f64::INFINITY,
            )
            .expect("no prediction limit");
            let Ok(Some(contact)) =
                parry3d_f64::query::contact(&pose_a, &*a.shape, &pose_b, &*b.shape, 10.0)
            else {
                continue;
            };
            // EPA stops within about 1e-6 of the least overlap on shapes of size 1.
            let tolerance = 1e-5;
            if contact.dist < -1e-3 {
                assert!(
                    (separation - contact.dist).abs() <= tolerance,
                    "case {case}: separating axis {separation} against EPA {}",
                    contact.dist
                );
                compared += 1;
            } else if contact.dist > 1e-3 {
                assert!(
                    separation > 0.0 && separation <= contact.dist + tolerance,
                    "case {case}"
                );
            }
            // The axis (in a's frame) separates by what the test reports, by support functions.
            let world_axis = pose_a.rotation * to_glam(&axis);
            let measured = -support(&b, &pose_b, -world_axis) - support(&a, &pose_a, world_axis);
            assert!(
                (measured - separation).abs() <= 1e-9,
                "case {case}: {measured} vs {separation}"
            );
        }
        assert!(compared > 200, "only {compared} overlapping pairs compared");
    }

    /// A cylinder's normal, found on its rounded core, against parry's GJK and EPA on the sharp
    /// shapes, for random cylinders overlapping random boxes, hulls and cylinders at random
    /// turns. The overlap of the sharp shapes along the returned normal is at least EPA's least
    /// overlap, and at most `(√2 − 1) δ` more, where `δ` is the rounding: the rounded cylinder
    /// lies inside the sharp one, so its least overlap is no larger, and its support function
    /// `(r − δ)|n_r| + (h − δ)|n_z| + δ` falls short of the sharp `r|n_r| + h|n_z|` by
    /// `δ(|n_r| + |n_z| − 1) ≤ (√2 − 1) δ` in any direction. The same holds wherever GJK starts
    /// its search: with no hint, the normal found a little turned (as a recomputed contact's
    /// last normal is), reversed, and a random direction.
    #[test]
    fn cylinder_normals_overlap_least_up_to_the_rounding() {
        let mut unit = uniform_from(77);
        let mut between = |lo: f64, hi: f64| lo + (hi - lo) * unit();
        let mut compared = 0;
        for case in 0..1200 {
            let (shape_a, shape_b) = a_cylinder_and_another(case, &mut between);
            let rounding = [&shape_a, &shape_b]
                .iter()
                .filter_map(|s| match s {
                    Shape::Cylinder {
                        radius,
                        half_height,
                    } => Some(ROUNDING * radius.min(*half_height)),
                    _ => None,
                })
                .sum::<f64>();
            let (Some(a), Some(b)) = (Collider::new(&shape_a), Collider::new(&shape_b)) else {
                continue;
            };
            let (turn_a, turn_b) = (random_turn(&mut between), random_turn(&mut between));
            let pose_a = pose(&Point3::origin(), &turn_a);
            let centre_b = Point3::new(between(-1.0, 1.0), between(-1.0, 1.0), between(-1.0, 1.0));
            let pose_b = pose(&centre_b, &turn_b);
            let Ok(unhinted) = contact_normal(&a, &pose_a, &b, &pose_b, 0.0, None) else {
                continue;
            };
            let turned = UnitQuaternion::from_euler_angles(
                between(-0.1, 0.1),
                between(-0.1, 0.1),
                between(-0.1, 0.1),
            ) * unhinted;
            let random = Vector3::new(between(-1.0, 1.0), between(-1.0, 1.0), between(-1.0, 1.0));
            let (sharp_a, sharp_b) = (pose_a * a.local, pose_b * b.local);
            let Ok(Some(contact)) =
                parry3d_f64::query::contact(&sharp_a, &*a.shape, &sharp_b, &*b.shape, 0.0)
            else {
                continue;
            };
            if contact.dist > -1e-3 {
                continue;
            }
            // EPA stops within about 1e-6 of the least overlap on shapes of size 1.
            let tolerance = 1e-5;
            let least = -contact.dist;
            let most = least + (2f64.sqrt() - 1.0) * rounding;
            for hint in [None, Some(turned), Some(-unhinted), Some(random)] {
                let normal = contact_normal(&a, &pose_a, &b, &pose_b, 0.0, hint.as_ref())
                    .expect("touching, as found without a hint");
                let n = to_glam(&normal);
                let overlap = support(&b, &pose_b, n) + support(&a, &pose_a, -n);
                assert!(
                    overlap >= least - tolerance && overlap <= most + tolerance,
                    "case {case}, hint {hint:?}: overlap {overlap} along the normal, EPA's \
                     least {least}, most allowed {most}"
                );
            }
            compared += 1;
        }
        assert!(compared > 200, "only {compared} overlapping pairs compared");
    }

    /// A cylinder turned at random and set against a random face of a box or a 10-point hull,
    /// from 2 cm into it to 3 cm off it along the face's normal, anywhere over the polytope:
    /// where the polytope's faces prove the normal ([`cylinder_on_face`]), the true shapes'
    /// least overlap, by parry's GJK and EPA (`query::contact`), is the overlap along it, and
    /// for a pair apart parry's distance is the separation along it; where a face holds them
    /// apart beyond the prediction, parry finds them farther apart than that. The proof is not
    /// vacuous: it holds for a good share of the pairs, and no proof is claimed for a pair
    /// whose least overlap lies along another direction.
    #[test]
    fn cylinder_faces_prove_the_normal_parry_finds() {
        let mut unit = uniform_from(909);
        let mut between = |lo: f64, hi: f64| lo + (hi - lo) * unit();
        let prediction = 0.02;
        let (mut proved, mut overlapping, mut apart, mut tried) = (0, 0, 0, 0);
        for case in 0..3000 {
            let (cylinder_shape, polytope_shape) = a_cylinder_and_another(case % 2, &mut between);
            let (Some(cylinder), Some(polytope)) = (
                Collider::new(&cylinder_shape),
                Collider::new(&polytope_shape),
            ) else {
                continue;
            };
            let faces = polytope.polytope.as_ref().expect("a box or a hull").faces();
            let (normal, offset) = faces[case % faces.len()];
            let (turn_p, turn_c) = (random_turn(&mut between), random_turn(&mut between));
            // In the polytope's frame: the cylinder's lowest point along the face's inward
            // normal put `gap` off the face's plane.
            let gap = between(-0.02, 0.03);
            let start = Vector3::new(between(-0.5, 0.5), between(-0.5, 0.5), between(-0.5, 0.5));
            let placed = |centre: Vector3<f64>| PlacedCylinder {
                centre,
                rotation: turn_c,
                radius: cylinder.shape.as_cylinder().expect("a cylinder").radius,
                half_height: cylinder
                    .shape
                    .as_cylinder()
                    .expect("a cylinder")
                    .half_height,
            };
            let lowest = placed(start).support(&-normal);
            let centre = start + normal * (gap - (normal.dot(&lowest) - offset));
            let pose_p = pose(&Point3::origin(), &turn_p);
            let pose_c = pose(&Point3::from(turn_p * centre), &(turn_p * turn_c));
            // Either may be the first of the pair.
            let (a, pose_a, b, pose_b) = if case % 4 < 2 {
                (&cylinder, pose_c, &polytope, pose_p)
            } else {
                (&polytope, pose_p, &cylinder, pose_c)
            };
            tried += 1;
            let Some(verdict) =
                cylinder_on_face(a, &(pose_a * a.local), b, &(pose_b * b.local), prediction)
            else {
                continue;
            };
            let (sharp_a, sharp_b) = (pose_a * a.local, pose_b * b.local);
            let reference =
                parry3d_f64::query::contact(&sharp_a, &*a.shape, &sharp_b, &*b.shape, 1.0)
                    .expect("convex shapes");
            match verdict {
                Ok(n) => {
                    // From b into a: b reaches up along it, a down against it.
                    let n = to_glam(&n);
                    let along = -support(b, &pose_b, n) - support(a, &pose_a, -n);
                    let contact = reference.expect("within the prediction of each other");
                    // EPA and GJK stop within about 1e-6 of the least overlap or the distance
                    // on shapes of size 1.
                    assert!(
                        (along - contact.dist).abs() <= 1e-5,
                        "case {case}: {along} along the face's normal, parry {}",
                        contact.dist
                    );
                    proved += 1;
                    if along < 0.0 {
                        overlapping += 1;
                    }
                }
                Err(gap) => {
                    let gap = gap.expect("a face's separation");
                    assert!(gap.separation > prediction, "case {case}");
                    let distance = sharp_distance(a, &pose_a, b, &pose_b);
                    assert!(
                        distance >= gap.separation - 1e-9,
                        "case {case}: {distance} vs {gap:?}"
                    );
                    apart += 1;
                }
            }
        }
        assert!(
            proved > tried / 6 && overlapping > tried / 10 && apart > tried / 20,
            "{proved} proved ({overlapping} overlapping), {apart} apart of {tried}"
        );
    }

    /// `a` at the origin turned by `turn_a`, and `b` turned by `turn_b` moved in along
    /// `direction` until the true shapes overlap by `overlap` (parry's GJK and EPA on them,
    /// bisected): their poses and EPA's contact, `None` where EPA does not settle within 0.5–4
    /// mm.
    fn pressed_together(
        (a, turn_a): (&Collider, UnitQuaternion<f64>),
        (b, turn_b): (&Collider, UnitQuaternion<f64>),
        direction: Vector3<f64>,
        overlap: f64,
    ) -> Option<(Pose, Pose, parry3d_f64::query::Contact)> {
        let pose_a = pose(&Point3::origin(), &turn_a);
        let pose_at = |s: f64| pose(&Point3::from(direction * s), &turn_b);
        let contact = |s: f64| {
            let (sharp_a, sharp_b) = (pose_a * a.local, pose_at(s) * b.local);
            parry3d_f64::query::contact(&sharp_a, &*a.shape, &sharp_b, &*b.shape, 10.0)
                .ok()
                .flatten()
        };
        let signed_distance = |s: f64| contact(s).map_or(f64::INFINITY, |c| c.dist);
        let (mut near, mut far) = (0.0, 4.0);
        for _ in 0..60 {
            let mid = 0.5 * (near + far);
            if signed_distance(mid) < -overlap {
                near = mid;
            } else {
                far = mid;
            }
        }
        let found = contact(near)?;
        (-4e-3..=-5e-4)
            .contains(&found.dist)
            .then_some((pose_a, pose_at(near), found))
    }

    /// A cylinder and a box, a hull or another cylinder, turned at random and moved towards
    /// each other along a random direction until the true shapes overlap by 0.5–4 mm (parry's
    /// GJK and EPA on them, bisected): a contact normal is found for every pair, rims crossing
    /// included, where the rounded cores stand up to `(√2 − 1)` of each rounding further apart
    /// than the cylinders. Without that allowance 319 of the 600 pairs were lost (148 of the
    /// 200 cylinder pairs): a cylinder turned at random meets things with its rim first.
    #[test]
    fn overlapping_cylinders_are_always_found_touching() {
        let mut unit = uniform_from(4242);
        let mut between = |lo: f64, hi: f64| lo + (hi - lo) * unit();
        let mut found = 0;
        for case in 0..600 {
            let (shape_a, shape_b) = a_cylinder_and_another(case, &mut between);
            let (Some(a), Some(b)) = (Collider::new(&shape_a), Collider::new(&shape_b)) else {
                continue;
            };
            let (turn_a, turn_b) = (random_turn(&mut between), random_turn(&mut between));
            let direction =
                Vector3::new(between(-1.0, 1.0), between(-1.0, 1.0), between(-1.0, 1.0))
                    .normalize();
            let overlap = between(5e-4, 4e-3);
            let Some((pose_a, pose_b, contact)) =
                pressed_together((&a, turn_a), (&b, turn_b), direction, overlap)
            else {
                continue; // EPA did not settle on this pair
            };
            assert!(
                contact_normal(&a, &pose_a, &b, &pose_b, 0.0, None).is_ok(),
                "case {case}: overlapping by {} mm, found apart",
                -contact.dist * 1e3
            );
            found += 1;
        }
        assert!(found > 400, "only {found} overlapping pairs");
    }

    /// Pairs pressed together as above, and a cylinder standing on another's cap, on a box
    /// and on a hull's face, tilted onto its rim: where a point of either shape inside the
    /// other proves the least-penetration normal ([`deepest_of`], searched from EPA's normal
    /// turned by up to 0.1 rad, as the rounded cores' normal is off the true one), the overlap
    /// along it is EPA's least overlap. It proves a share of the random pairs (a face or a cap
    /// against a rim or a corner) and every one standing on a flat face.
    #[test]
    fn deepest_points_prove_the_least_overlap() {
        let mut unit = uniform_from(616);
        let mut between = |lo: f64, hi: f64| lo + (hi - lo) * unit();
        let (mut tried, mut proved) = (0, 0);
        for case in 0..900 {
            let (shape_a, shape_b) = a_cylinder_and_another(case, &mut between);
            let (Some(a), Some(b)) = (Collider::new(&shape_a), Collider::new(&shape_b)) else {
                continue;
            };
            // Every third pair stands `a` on `b` from above, tilted by up to 0.3 rad; the others
            // meet from anywhere.
            let standing = case % 3 == 0;
            let turn_a = if standing {
                UnitQuaternion::from_euler_angles(between(-0.3, 0.3), between(-0.3, 0.3), 0.0)
            } else {
                random_turn(&mut between)
            };
            let turn_b = if standing {
                UnitQuaternion::identity()
            } else {
                random_turn(&mut between)
            };
            let direction = if standing {
                -Vector3::z()
            } else {
                Vector3::new(between(-1.0, 1.0), between(-1.0, 1.0), between(-1.0, 1.0)).normalize()
            };
            let Some((pose_a, pose_b, contact)) =
                pressed_together((&a, turn_a), (&b, turn_b), direction, between(5e-4, 4e-3))
            else {
                continue;
            };
            tried += 1;
            let (sharp_a, sharp_b) = (pose_a * a.local, pose_b * b.local);
            let pos_ba = sharp_b.inverse() * sharp_a;
            let nudge = Rotation::from_scaled_axis(Vector::new(
                between(-0.06, 0.06),
                between(-0.06, 0.06),
                between(-0.06, 0.06),
            ));
            let start = nudge * (sharp_b.rotation.inverse() * contact.normal2);
            let Some(local) = deepest_of(&a, &b, &pos_ba, start) else {
                continue;
            };
            let n = sharp_b.rotation * local;
            let overlap = support(&b, &pose_b, n) + support(&a, &pose_a, -n);
            // EPA stops within about 1e-6 of the least overlap on shapes of size 1.
            assert!(
                (overlap + contact.dist).abs() <= 1e-5,
                "case {case}: overlap {overlap} along the proved normal, EPA's {}",
                -contact.dist
            );
            proved += 1;
        }
        // 399 of the 900 when this was written (379 within two steps of the search).
        assert!(
            proved > tried / 3,
            "proved {proved} of {tried} overlapping pairs"
        );
    }

    /// Shapes whose faces do not show them apart, turned off the axes, 3 cm apart with a margin
    /// of 5 mm: two cylinders side by side, two crossed, a ball beside a cylinder's side, a
    /// ball by a box's edge. Each used to be tested afresh every step; now each is found apart,
    /// along GJK's separating direction or from the ball's nearest point, by never more than
    /// its distance. The ball's axis is exact; GJK's stops as soon as it shows the cores apart
    /// by the margin and their roundings, and is within 0.1 mm of the nearest points' here.
    #[test]
    fn curved_sides_are_found_apart_by_their_distance() {
        let turn = UnitQuaternion::from_euler_angles(0.3, -0.5, 0.8);
        let cylinder = Collider::new(&Shape::cylinder(0.4, 1.0)).expect("a cylinder");
        let ball = Collider::new(&Shape::sphere(0.3)).expect("a ball");
        let cube = Collider::new(&Shape::cuboid([1.0, 1.0, 1.0])).expect("a box");
        let gap = 0.03;
        let straight = UnitQuaternion::identity();
        let crossed = UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
        // By the box's edge along z, the ball's centre `gap` beyond contact, diagonally.
        let edge = (0.5 + (0.3 + gap) / 2f64.sqrt()) * Vector3::new(1.0, 1.0, 0.0);
        let cases = [
            (
                &cylinder,
                &cylinder,
                Vector3::x() * (0.8 + gap),
                straight,
                1e-4,
            ),
            (
                &cylinder,
                &cylinder,
                Vector3::x() * (0.8 + gap),
                crossed,
                1e-4,
            ),
            (
                &cylinder,
                &ball,
                Vector3::y() * (0.7 + gap),
                straight,
                1e-12,
            ),
            (&cube, &ball, edge, straight, 1e-12),
        ];
        let centre = Point3::new(1.0, -2.0, 0.5);
        for (case, (first, second, offset, relative, short)) in cases.into_iter().enumerate() {
            // The second shape placed in the turned frame of the first.
            let pose_a = pose(&centre, &turn);
            let pose_b = pose(&(centre + turn * offset), &(turn * relative));
            // The placement, checked by parry's distance (GJK, within about 1e-8 here).
            let distance = sharp_distance(first, &pose_a, second, &pose_b);
            assert!(
                (distance - gap).abs() < 1e-6,
                "case {case}: {distance} m apart"
            );
            let Err(Some(found)) = contact_normal(first, &pose_a, second, &pose_b, 0.005, None)
            else {
                panic!("case {case}: not kept apart");
            };
            // Support functions measure it: above the gap by round-off at most.
            assert!(
                found.separation <= gap + 1e-12 && found.separation >= gap - short,
                "case {case}: separation {} against a gap of {gap}",
                found.separation
            );
        }
    }

    /// A box's polytope, from a 1 cm cube to a 100 km slab 2 m thick (whose hull by parry came
    /// out flat): six faces, each holding four corners on its plane and every corner on or
    /// behind it; twelve edges, each joining two corners on both of its faces; and its least
    /// width the box's least side.
    #[test]
    fn a_box_polytope_has_its_faces_and_edges_at_any_proportions() {
        for size in [
            [0.01, 0.01, 0.01],
            [1.0, 2.0, 3.0],
            [100_000.0, 100_000.0, 2.0],
        ] {
            let collider = Collider::new(&Shape::cuboid(size)).expect("a box");
            let polytope = collider.polytope.as_ref().expect("a polytope");
            let corners = collider.hull_vertices().expect("corners");
            let tolerance = 1e-12 * size.iter().sum::<f64>();
            assert_eq!(polytope.faces().len(), 6);
            for (n, d) in polytope.faces() {
                let on = corners.iter().filter(|c| (n.dot(c) - d).abs() <= tolerance);
                assert_eq!(on.count(), 4, "{size:?}: face {n}");
                assert!(corners.iter().all(|c| n.dot(c) <= d + tolerance));
            }
            assert_eq!(polytope.edges().count(), 12);
            for ([v, w], [f, g]) in polytope.edges() {
                for face in [f, g] {
                    let (n, d) = polytope.faces()[face];
                    for corner in [v, w] {
                        assert!((n.dot(&corners[corner]) - d).abs() <= tolerance);
                    }
                }
            }
            let least = size.iter().copied().fold(f64::INFINITY, f64::min);
            assert!(
                (polytope.thickness() - least).abs() <= tolerance,
                "{size:?}"
            );
        }
    }

    /// A cylinder's closed-form box against parry's from six support points, for random
    /// cylinders turned at random (axes along a world axis included): the same to round-off
    /// of the coordinates (1e-12 m at sizes of 1–10 m).
    #[test]
    fn a_cylinder_box_is_the_support_points_box() {
        let mut unit = uniform_from(17);
        let mut between = |lo: f64, hi: f64| lo + (hi - lo) * unit();
        for case in 0..500 {
            let shape = Shape::cylinder(between(0.1, 3.0), between(0.1, 6.0));
            let collider = Collider::new(&shape).expect("a cylinder");
            let turn = match case % 4 {
                0 => UnitQuaternion::identity(),
                1 => UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0),
                _ => random_turn(&mut between),
            };
            let centre = Point3::new(between(-5.0, 5.0), between(-5.0, 5.0), between(-5.0, 5.0));
            let at = pose(&centre, &turn);
            let (mins, maxs) = collider.aabb(&at, 0.01);
            let reference = collider.shape.compute_aabb(&(at * collider.local));
            let grow = Vector3::repeat(0.01);
            let (ref_mins, ref_maxs) = (
                from_glam(reference.mins) - grow,
                from_glam(reference.maxs) + grow,
            );
            assert!(
                (mins - ref_mins).amax() <= 1e-12 && (maxs - ref_maxs).amax() <= 1e-12,
                "case {case}: {mins:?}–{maxs:?} against {ref_mins:?}–{ref_maxs:?}"
            );
        }
    }

    /// A cylinder standing on its cap and one lying on its side, on a box turned off the axes,
    /// sunk 3 mm into it (past the default slop): the box's face normal to round-off, as the
    /// sharp cylinder gives.
    #[test]
    fn a_cylinder_on_a_face_touches_along_the_face_normal() {
        let tilt = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.7);
        let face_normal = tilt * Vector3::z();
        let slab = Collider::new(&Shape::cuboid([4.0, 4.0, 1.0])).expect("a box");
        let slab_pose = pose(&Point3::origin(), &tilt);
        let (radius, half_height) = (0.4, 0.3);
        let cylinder = Collider::new(&Shape::Cylinder {
            radius,
            half_height,
        })
        .expect("a cylinder");
        let standing = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.4);
        let lying = UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 1.1);
        for (turn, height) in [(standing, half_height), (lying, radius)] {
            let centre = Point3::from(tilt * Vector3::new(0.3, -0.2, 0.5 + height - 0.003));
            let normal = contact_normal(
                &cylinder,
                &pose(&centre, &(tilt * turn)),
                &slab,
                &slab_pose,
                0.0,
                None,
            )
            .expect("touching");
            assert!(
                (normal - face_normal).norm() <= 1e-9,
                "{normal} against {face_normal}"
            );
        }
    }

    /// A hull resting face down on another, turned 30° about the normal and offset, gives the
    /// face normal whatever the size: 1 mm and 1 km cubes given as hulls, overlapping by 1% of
    /// their size.
    #[test]
    fn stacked_hulls_touch_along_the_face_normal_at_any_size() {
        for size in [1e-3, 1.0, 1e3] {
            let corners = (0..8)
                .map(|i: u8| {
                    let s = |bit: u8| if i & bit == 0 { -0.5 } else { 0.5 };
                    Point3::new(s(1), s(2), s(4)) * size
                })
                .collect();
            let cube = Collider::new(&Shape::Convex { points: corners }).expect("a cube");
            let lower = pose(&Point3::origin(), &UnitQuaternion::identity());
            let upper = pose(
                &(Point3::new(0.2, 0.1, 0.99) * size),
                &UnitQuaternion::from_euler_angles(0.0, 0.0, std::f64::consts::FRAC_PI_6),
            );
            let normal = contact_normal(&cube, &upper, &cube, &lower, 0.0, None).expect("touching");
            assert!(
                (normal - Vector3::z()).norm() <= 1e-9,
                "size {size}: {normal}"
            );
        }
    }
}
