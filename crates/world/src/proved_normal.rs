//! Contact normals of pairs with a cylinder, proved in closed form instead of searched for by
//! GJK and EPA on the cylinder's support function, which took a third of the 1000-shape pile's
//! contact tests while it settled (most of them a cylinder lying or standing on the floor, a
//! box, a hull or another cylinder).
//!
//! The proof is one fact about convex solids: a point inside one is as far from its surface as
//! from the nearest part of it (a face's plane, taken whole, or a cylinder's side, measured
//! from the axis). Let `c` be the point of one solid deepest in along `−u`, inside the other
//! at depth `D` below the nearest part of its surface, whose outward normal is `u`, and let the
//! overlap along `u` be `D`. Any translation that takes the solids apart moves `c` out of the
//! other, by at least `D`: no direction overlaps less, and `u` is the direction EPA converges
//! to ([`deepest_normal`]). Searched from a direction near it, a face's or a cap's normal
//! comes back at once when it is the answer.
//!
//! For a cylinder against a polytope the faces are tried first, as the separating-axis test
//! tries them ([`face_verdict`]): the face along which the cylinder overlaps least gives the
//! normal by the proof above; apart by `s` along it, if the foot of the cylinder's nearest
//! point on the face's plane lies inside the polytope, the two points are `s` apart, no nearer
//! than the separation along any axis, so `s` is the distance and the face normal its
//! direction, what GJK converges to.
//!
//! Otherwise (an edge or a corner against a rim, two rims, or a point near two parts at once)
//! nothing is proved, and the general search decides.

use nalgebra::{UnitQuaternion, Vector3};

use crate::sat::Polytope;

/// Relative slack of the proofs' comparisons, as a fraction of the pair's size: their terms
/// are products of coordinates of that size, each within about 1e-15 of it, so two parts of a
/// surface within 1e-9 of a tie are left to the general search, which may pick either.
const SLACK: f64 = 1e-9;

/// A cylinder placed in another shape's frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlacedCylinder {
    /// Its centre.
    pub centre: Vector3<f64>,
    /// Its turn from its own frame, where it stands along z.
    pub rotation: UnitQuaternion<f64>,
    pub radius: f64,
    pub half_height: f64,
}

impl PlacedCylinder {
    /// A point of the cylinder furthest along `direction`: on a rim, or the centre of the cap
    /// facing it where `direction` is along the axis. Found in the cylinder's own frame, so
    /// the point lies on the rim to rounding for any direction, however near the axis.
    pub(crate) fn support(&self, direction: &Vector3<f64>) -> Vector3<f64> {
        let local = self.rotation.inverse_transform_vector(direction);
        let across = local.x.hypot(local.y);
        let (x, y) = if across > 0.0 {
            (
                local.x * self.radius / across,
                local.y * self.radius / across,
            )
        } else {
            (0.0, 0.0)
        };
        let z = if local.z >= 0.0 {
            self.half_height
        } else {
            -self.half_height
        };
        self.centre + self.rotation * Vector3::new(x, y, z)
    }
}

/// What the faces of a polytope say about a cylinder near it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FaceVerdict {
    /// The contact normal is this face's outward normal (in the polytope's frame).
    Normal(Vector3<f64>),
    /// A face's plane separates the cylinder from the polytope by this much (m), beyond the
    /// prediction.
    Apart(f64),
}

/// The contact normal of `cylinder` (placed in the polytope's frame) against `polytope` when
/// one of the polytope's faces is proved to give it (see the module doc), or that a face
/// separates them by more than `prediction`; `None` when the faces prove neither.
pub(crate) fn face_verdict(
    polytope: &Polytope,
    cylinder: &PlacedCylinder,
    prediction: f64,
) -> Option<FaceVerdict> {
    // The face of largest separation (least overlap), with the cylinder's point furthest in.
    let mut best: Option<(f64, usize, Vector3<f64>)> = None;
    for (k, (n, d)) in polytope.faces().iter().enumerate() {
        let deepest = cylinder.support(&-n);
        let separation = n.dot(&deepest) - d;
        if best.is_none_or(|(s, _, _)| separation > s) {
            best = Some((separation, k, deepest));
        }
    }
    let (separation, k, deepest) = best?;
    if !separation.is_finite() {
        return None;
    }
    if separation > prediction {
        return Some(FaceVerdict::Apart(separation));
    }
    let (normal, _) = polytope.faces()[k];
    let scale = cylinder.radius + cylinder.half_height + cylinder.centre.norm();
    if separation <= 0.0 {
        let owner = Solid::Polytope {
            polytope,
            rotation: UnitQuaternion::identity(),
            translation: Vector3::zeros(),
        };
        let other = Solid::Cylinder(*cylinder);
        return deepest_normal(&owner, &other, &normal, scale).map(FaceVerdict::Normal);
    }
    // Apart, the foot of the deepest point on face `k`'s plane must be inside every other.
    let foot = deepest - normal * separation;
    let slack = SLACK * scale;
    let inside = polytope
        .faces()
        .iter()
        .enumerate()
        .all(|(i, (n, d))| i == k || d - n.dot(&foot) >= slack);
    inside.then_some(FaceVerdict::Normal(normal))
}

/// A convex shape placed in a common frame, as the proof of [`deepest_normal`] reads it: its
/// support points, and for a point inside it the nearest part of its surface.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Solid<'a> {
    /// A box or a hull, turned by `rotation` and moved by `translation` from its own frame.
    Polytope {
        polytope: &'a Polytope,
        rotation: UnitQuaternion<f64>,
        translation: Vector3<f64>,
    },
    Cylinder(PlacedCylinder),
}

/// The part of a solid's surface nearest a point inside it.
#[derive(Debug, Clone, Copy)]
struct Nearest {
    /// Its outward unit normal.
    normal: Vector3<f64>,
    /// How far inside the point is (m, positive inside).
    depth: f64,
    /// How far the next nearest part is.
    next: f64,
}

impl Solid<'_> {
    /// A point of the solid furthest along `direction`.
    fn support(&self, direction: &Vector3<f64>) -> Vector3<f64> {
        match self {
            Self::Polytope {
                polytope,
                rotation,
                translation,
            } => {
                let local = rotation.inverse_transform_vector(direction);
                rotation * polytope.support_point(&local) + translation
            }
            Self::Cylinder(cylinder) => cylinder.support(direction),
        }
    }

    /// The part of the surface nearest `point`, if the point is inside: a face (of a polytope,
    /// or a cylinder's cap) or a cylinder's side, the point's distance from which is from its
    /// axis. For a point inside a convex solid, its distance to the surface is the least of
    /// those distances, each part's own, planes taken whole.
    fn nearest(&self, point: &Vector3<f64>) -> Option<Nearest> {
        let mut nearest = Nearest {
            normal: Vector3::zeros(),
            depth: f64::INFINITY,
            next: f64::INFINITY,
        };
        let mut consider = |normal: Vector3<f64>, depth: f64| {
            if depth < nearest.depth {
                nearest.next = nearest.depth;
                nearest.depth = depth;
                nearest.normal = normal;
            } else if depth < nearest.next {
                nearest.next = depth;
            }
        };
        let rotation = match self {
            Self::Polytope {
                polytope,
                rotation,
                translation,
            } => {
                let local = rotation.inverse_transform_vector(&(point - translation));
                for (n, d) in polytope.faces() {
                    consider(*n, d - n.dot(&local));
                }
                rotation
            }
            Self::Cylinder(cylinder) => {
                let local = cylinder
                    .rotation
                    .inverse_transform_vector(&(point - cylinder.centre));
                consider(Vector3::z(), cylinder.half_height - local.z);
                consider(-Vector3::z(), cylinder.half_height + local.z);
                let from_axis = local.x.hypot(local.y);
                if from_axis > 0.0 {
                    let radial = Vector3::new(local.x, local.y, 0.0) / from_axis;
                    consider(radial, cylinder.radius - from_axis);
                }
                &cylinder.rotation
            }
        };
        nearest.normal = rotation * nearest.normal;
        (nearest.depth > 0.0 && nearest.normal != Vector3::zeros()).then_some(nearest)
    }

    /// How far the solid reaches along the unit `direction`: `max x · direction` over its points.
    fn reach(&self, direction: &Vector3<f64>) -> f64 {
        self.support(direction).dot(direction)
    }
}

/// Most steps of [`deepest_normal`]'s search: a face or a cap is proved in two; a rim on a
/// cylinder's side takes more where the search settles at all (of 900 random overlapping
/// pairs in `parry_bridge`'s tests, 379 proved within two steps, 383 within six, 399 within
/// sixteen), each step a support point and a few planes, far below EPA's cost.
const SEARCH_STEPS: usize = 16;

/// How near (in direction) a step of [`deepest_normal`]'s search must come to the last to end it.
const CONVERGED: f64 = 1e-12;

/// The least-penetration normal of two overlapping solids, out of `owner`, proved from a point
/// of `other` inside `owner`, found from `start` (a direction near it, out of `owner`); `None`
/// where no such point proves one.
///
/// The point of `other` deepest along `−u` lies inside `owner`, at some depth `D` below the
/// nearest part of `owner`'s surface, whose normal is the next `u`; when `u` comes back (to
/// [`CONVERGED`]) and the overlap along it is `D`, it is proved least: any translation that
/// takes `other` out of `owner` takes that point out, which is at least `D` from every part of
/// the surface. A face of a polytope, or a cylinder's cap, comes back at once if it is the
/// answer. A cylinder's side touched by a rim may: each step moves the rim's deepest point,
/// and with it the side's normal there, and the steps often grow instead of shrinking
/// (a search with no proof ends within [`SEARCH_STEPS`], and EPA decides).
pub(crate) fn deepest_normal(
    owner: &Solid<'_>,
    other: &Solid<'_>,
    start: &Vector3<f64>,
    scale: f64,
) -> Option<Vector3<f64>> {
    let slack = SLACK * scale;
    let mut direction = *start;
    for _ in 0..SEARCH_STEPS {
        let deepest = other.support(&-direction);
        let nearest = owner.nearest(&deepest)?;
        if (nearest.normal - direction).norm() <= CONVERGED {
            let overlap = owner.reach(&nearest.normal) - nearest.normal.dot(&deepest);
            let proved =
                (overlap - nearest.depth).abs() <= slack && nearest.next >= nearest.depth + slack;
            return proved.then_some(nearest.normal);
        }
        direction = nearest.normal;
    }
    None
}
