//! The expanding polytope algorithm (EPA) on two overlapping convex shapes, stopped at a
//! tolerance relative to their size.
//!
//! GJK ends with a tetrahedron of the shapes' difference (the CSO) around the origin; EPA grows
//! it towards the CSO's boundary until its face nearest the origin lies on that boundary: that
//! face's normal is the direction to part the shapes by least. parry's EPA stops once the
//! support point along the nearest face's normal lies within 100 ε (2.2e-14) of the face,
//! absolutely: reached on flat faces, never on a curved side or rim, on which it runs to its cap
//! of 100 points, each adding faces to search. Here it stops within [`RELATIVE_TOLERANCE`] of
//! the difference's size, which the 1000-shape pile's cylinders meet within 18 points (the
//! median; 25 for nine pairs in ten): its EPA took 1,324 → 764 M instructions over seconds 3–5
//! of the settling (`valgrind --tool=callgrind`, one thread).
//!
//! Each step takes the nearest face, adds the support point along its normal, removes the faces
//! that point sees (found from the nearest one across shared edges, as parry's and Jolt's EPA
//! find them) and closes the hole with a fan of new faces from it over their horizon. Where the
//! horizon is not one loop, or a new face has no normal, the step would not leave a closed
//! convex polytope: `None`, and the caller asks parry's EPA instead, as it does where the
//! tolerance is not met by parry's cap.

use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::gjk::{CsoPoint, VoronoiSimplex};
use parry3d_f64::shape::SupportMap;

/// How near (a share of the CSO's size: its farthest vertex of GJK's tetrahedron from the
/// origin) the support point along the nearest face's normal must come to that face: 0.1 nm
/// for shapes of a metre, so the answer overlaps at most that much more than the least overlap
/// (the polytope lies inside the CSO, its nearest face no farther than the CSO's boundary).
pub(crate) const RELATIVE_TOLERANCE: f64 = 1e-10;

/// How near a face's plane (a share of the CSO's size) a new point counts as seen from it
/// ([`Epa::grow`]): a few thousand times the rounding of a distance, a thousandth of the
/// tolerance.
const FLAT: f64 = 1e-13;

/// Most points a polytope is grown by: parry's cap. On random overlapping pairs of a cylinder
/// with a box, a hull or a cylinder (the tests), the tolerance took 15 points (the median), 36
/// for one pair in ten, and more than this for one in about 500.
const MAX_ITERATIONS: usize = 100;

/// One triangle of the polytope, counter-clockwise seen from outside.
#[derive(Debug, Clone, Copy)]
struct Face {
    vertices: [usize; 3],
    /// The face across each edge, edge `i` running from vertex `i` to the next.
    adjacent: [usize; 3],
    /// Outward unit normal.
    normal: Vector,
    /// The face plane's distance from the origin along `normal`.
    distance: f64,
    /// Still on the polytope (not seen from a point added since).
    alive: bool,
}

/// Buffers kept across calls: a pass over a pile computes many pairs.
#[derive(Debug, Default)]
pub(crate) struct Epa {
    vertices: Vec<CsoPoint>,
    faces: Vec<Face>,
    /// The faces a new point sees.
    seen: Vec<usize>,
    /// The seen faces' edges to faces not seen, each with the face beyond it.
    horizon: Vec<(usize, usize, usize)>,
}

impl Epa {
    /// What parry's `EPA::closest_points` answers, to [`RELATIVE_TOLERANCE`]: from GJK's
    /// `simplex` around the origin, the points of `g1` and `g2` (placed by `pos12`; both in
    /// `g1`'s frame) whose difference is the CSO's boundary point nearest the origin, and the
    /// CSO's outward unit normal there. `None` where the simplex is not a tetrahedron, the
    /// polytope cannot be grown cleanly or the tolerance is not met within
    /// [`MAX_ITERATIONS`] points (the module doc): parry's EPA handles those.
    pub(crate) fn closest_points<G1, G2>(
        &mut self,
        pos12: &Pose,
        g1: &G1,
        g2: &G2,
        simplex: &VoronoiSimplex,
    ) -> Option<(Vector, Vector, Vector)>
    where
        G1: ?Sized + SupportMap,
        G2: ?Sized + SupportMap,
    {
        if simplex.dimension() != 3 {
            return None;
        }
        self.vertices.clear();
        self.faces.clear();
        self.vertices.extend((0..4).map(|i| *simplex.point(i)));
        let size = self
            .vertices
            .iter()
            .map(|v| v.point.length())
            .fold(0.0, f64::max);
        let tolerance = RELATIVE_TOLERANCE * size;
        // The tetrahedron's faces, each with the vertex it leaves out, then which meets which.
        for (face, opposite) in [
            ([0, 1, 2], 3),
            ([0, 3, 1], 2),
            ([0, 2, 3], 1),
            ([1, 3, 2], 0),
        ] {
            let face = self.outward(face, opposite)?;
            self.faces.push(face);
        }
        for f in 0..4 {
            for edge in 0..3 {
                let (from, to) = edge_of(&self.faces[f], edge);
                self.faces[f].adjacent[edge] =
                    (0..4).find(|&g| (0..3).any(|e| edge_of(&self.faces[g], e) == (to, from)))?;
            }
        }
        for _ in 0..MAX_ITERATIONS {
            let nearest = self.nearest()?;
            let face = self.faces[nearest];
            let support = CsoPoint::from_shapes(pos12, g1, g2, face.normal);
            if support.point.dot(face.normal) - face.distance <= tolerance {
                return Some(self.closest_points_on(&face));
            }
            self.grow(support, nearest, FLAT * size)?;
        }
        // Not within the tolerance by the cap (one pair in about 500): parry's EPA, whose
        // polytope grown as far may have come nearer.
        None
    }

    /// Face `vertices` turned to face away from vertex `opposite`, with its normal.
    fn outward(&self, [a, b, c]: [usize; 3], opposite: usize) -> Option<Face> {
        let face = self.face([a, b, c])?;
        let away = face
            .normal
            .dot(self.vertices[opposite].point - self.vertices[a].point)
            < 0.0;
        if away {
            Some(face)
        } else {
            self.face([a, c, b])
        }
    }

    /// Face `vertices` (counter-clockwise seen from outside) with its normal; `None` for a
    /// sliver without one.
    fn face(&self, vertices: [usize; 3]) -> Option<Face> {
        let [a, b, c] = vertices.map(|k| self.vertices[k].point);
        let normal = (b - a).cross(c - a).try_normalize()?;
        let distance = normal.dot(a);
        distance.is_finite().then_some(Face {
            vertices,
            adjacent: [0; 3],
            normal,
            distance,
            alive: true,
        })
    }

    /// The live face nearest the origin, which the origin's projection falls within (every
    /// other face's plane holds it on the inner side).
    fn nearest(&self) -> Option<usize> {
        (0..self.faces.len())
            .filter(|&k| self.faces[k].alive)
            .min_by(|&i, &j| self.faces[i].distance.total_cmp(&self.faces[j].distance))
    }

    /// Adds `point` to the polytope: the faces it sees go, and a fan of faces from it over
    /// their horizon closes the hole. The seen faces are found from `nearest`, which it sees,
    /// across shared edges, so they are one patch; a face it sees within `flat` of its plane
    /// goes too, so that no sliver is left beside the new point. `None` where the patch's
    /// horizon is not one loop.
    fn grow(&mut self, point: CsoPoint, nearest: usize, flat: f64) -> Option<()> {
        let new = self.vertices.len();
        self.vertices.push(point);
        self.seen.clear();
        self.horizon.clear();
        self.faces[nearest].alive = false;
        self.seen.push(nearest);
        let mut next = 0;
        while let Some(&face) = self.seen.get(next) {
            next += 1;
            for edge in 0..3 {
                let beyond = self.faces[face].adjacent[edge];
                let other = &self.faces[beyond];
                // A live face's neighbours are live, or seen from this point.
                if !other.alive {
                    continue;
                }
                let seen = other
                    .normal
                    .dot(point.point - self.vertices[other.vertices[0]].point)
                    > -flat;
                if seen {
                    self.faces[beyond].alive = false;
                    self.seen.push(beyond);
                }
            }
        }
        for &face in &self.seen {
            for edge in 0..3 {
                let beyond = self.faces[face].adjacent[edge];
                if self.faces[beyond].alive {
                    let (from, to) = edge_of(&self.faces[face], edge);
                    self.horizon.push((from, to, beyond));
                }
            }
        }
        // One loop, put in order: no vertex starts two of its edges, and from the first edge,
        // each next one starting where the last ended, the walk comes back to the start only
        // after all of them.
        let n = self.horizon.len();
        for k in 1..n {
            let at = self.horizon[k - 1].1;
            let next = k + self.horizon[k..].iter().position(|e| e.0 == at)?;
            self.horizon.swap(k, next);
        }
        let starts_once =
            (1..n).all(|i| self.horizon[..i].iter().all(|e| e.0 != self.horizon[i].0));
        if n < 3 || !starts_once || self.horizon[n - 1].1 != self.horizon[0].0 {
            return None;
        }
        // The fan: face k over horizon edge k, meeting the faces over the edges before and
        // after it, and the face beyond the edge, which now meets it there.
        let first = self.faces.len();
        for k in 0..n {
            let (from, to, beyond) = self.horizon[k];
            let mut face = self.face([from, to, new])?;
            face.adjacent = [beyond, first + (k + 1) % n, first + (k + n - 1) % n];
            let back = (0..3).find(|&e| edge_of(&self.faces[beyond], e) == (to, from))?;
            self.faces[beyond].adjacent[back] = first + k;
            self.faces.push(face);
        }
        Some(())
    }

    /// The points of the two shapes whose difference is the origin's projection on `face`, and
    /// the face's normal.
    fn closest_points_on(&self, face: &Face) -> (Vector, Vector, Vector) {
        let [a, b, c] = face.vertices.map(|k| self.vertices[k]);
        let at = face.normal * face.distance;
        let [u, v, w] = barycentric(at, [a.point, b.point, c.point], face.normal);
        (
            a.orig1 * u + b.orig1 * v + c.orig1 * w,
            a.orig2 * u + b.orig2 * v + c.orig2 * w,
            face.normal,
        )
    }
}

/// Edge `edge` of `face`: from its vertex `edge` to the next, counter-clockwise.
fn edge_of(face: &Face, edge: usize) -> (usize, usize) {
    (face.vertices[edge], face.vertices[(edge + 1) % 3])
}

/// The barycentric coordinates of `p` (in the triangle's plane) in triangle `[a, b, c]` of
/// unit normal `normal`: the areas of the triangles `p` makes with each edge, over the whole's.
fn barycentric(p: Vector, [a, b, c]: [Vector; 3], normal: Vector) -> [f64; 3] {
    let area = |x: Vector, y: Vector, z: Vector| normal.dot((y - x).cross(z - x));
    let whole = area(a, b, c);
    let (u, v) = (area(p, b, c) / whole, area(a, p, c) / whole);
    [u, v, 1.0 - u - v]
}

#[cfg(test)]
mod tests {
    use nalgebra::{Point3, UnitQuaternion};
    use parry3d_f64::query::epa::EPA;
    use parry3d_f64::query::gjk::{self, GJKResult};
    use parry3d_f64::shape::{ConvexPolyhedron, Cuboid, Cylinder};

    use super::*;
    use crate::parry_bridge::pose;
    use crate::parry_bridge::tests::uniform_from;

    /// GJK's simplex around the origin for `g1` and `g2` placed by `pos12`, if they overlap.
    fn overlapping<G1, G2>(pos12: &Pose, g1: &G1, g2: &G2) -> Option<VoronoiSimplex>
    where
        G1: ?Sized + SupportMap,
        G2: ?Sized + SupportMap,
    {
        let mut simplex = VoronoiSimplex::new();
        let start = pos12.translation.try_normalize().unwrap_or(Vector::X);
        simplex.reset(CsoPoint::from_shapes(pos12, g1, g2, start));
        let found = gjk::closest_points(pos12, g1, g2, 0.0, true, &mut simplex);
        (found == GJKResult::Intersection).then_some(simplex)
    }

    /// How far the two shapes overlap along the unit `normal`: the CSO's reach along it.
    fn overlap_along<G1, G2>(pos12: &Pose, g1: &G1, g2: &G2, normal: Vector) -> f64
    where
        G1: ?Sized + SupportMap,
        G2: ?Sized + SupportMap,
    {
        CsoPoint::from_shapes(pos12, g1, g2, normal)
            .point
            .dot(normal)
    }

    /// Two boxes overlapping by 0.1 m along z and by more across: the least overlap is along z,
    /// to the tolerance, and the points found are 0.1 m apart along it.
    #[test]
    fn boxes_part_along_their_least_overlap() {
        let (g1, g2) = (
            Cuboid::new(Vector::splat(1.0)),
            Cuboid::new(Vector::splat(1.0)),
        );
        let pos12 = pose(&Point3::new(0.3, 0.2, 1.9), &UnitQuaternion::identity());
        let simplex = overlapping(&pos12, &g1, &g2).expect("they overlap");
        let (on1, on2, normal) = Epa::default()
            .closest_points(&pos12, &g1, &g2, &simplex)
            .expect("a tetrahedron");
        assert!((normal - Vector::Z).length() < 1e-9, "{normal}");
        assert!(((on1 - on2).dot(normal) - 0.1).abs() < 1e-9, "{on1} {on2}");
    }

    /// Random overlapping pairs of a cylinder with a box, a 10-point hull or another cylinder,
    /// turned at random: the direction found overlaps no more than parry's EPA's, to the
    /// tolerance. The CSO reaches at least as far as the polytope along any direction, and the
    /// answer's face is within the tolerance of the CSO, so no direction overlaps less than it
    /// does by more than that; its points' difference lies along its normal.
    #[test]
    fn curved_pairs_overlap_least_along_the_answer() {
        let mut uniform = uniform_from(2024);
        let mut between = |lo: f64, hi: f64| lo + (hi - lo) * uniform();
        let (mut ours, mut parrys) = (Epa::default(), EPA::new());
        let mut compared = 0;
        for case in 0..600 {
            let g1 = Cylinder::new(between(0.2, 0.5), between(0.25, 0.5));
            let hull = |between: &mut dyn FnMut(f64, f64) -> f64| {
                let points: Vec<Vector> = (0..10)
                    .map(|_| {
                        Vector::new(between(-0.5, 0.5), between(-0.5, 0.5), between(-0.5, 0.5))
                    })
                    .collect();
                ConvexPolyhedron::from_convex_hull(&points).expect("ten random points")
            };
            let offset = Point3::new(between(-0.7, 0.7), between(-0.7, 0.7), between(-0.7, 0.7));
            let turn = UnitQuaternion::from_euler_angles(
                between(-3.0, 3.0),
                between(-3.0, 3.0),
                between(-3.0, 3.0),
            );
            let pos12 = pose(&offset, &turn);
            let check = |g2: &dyn SupportMap, ours: &mut Epa, parrys: &mut EPA| -> bool {
                let Some(simplex) = overlapping(&pos12, &g1, g2) else {
                    return false;
                };
                let Some((on1, on2, normal)) = ours.closest_points(&pos12, &g1, g2, &simplex)
                else {
                    return false;
                };
                let (_, _, theirs) = parrys
                    .closest_points(&pos12, &g1, g2, &simplex)
                    .expect("parry's EPA on a tetrahedron");
                let size = (0..4)
                    .map(|i| simplex.point(i).point.length())
                    .fold(0.0, f64::max);
                let depth = overlap_along(&pos12, &g1, g2, normal);
                let best = overlap_along(&pos12, &g1, g2, theirs);
                // The tolerance, and rounding of a few ε of the size.
                assert!(
                    depth <= best + RELATIVE_TOLERANCE * size + 1e-13 * size,
                    "case {case}: {depth} against parry's {best}"
                );
                let along = on1 - on2;
                assert!(
                    (along - normal * along.dot(normal)).length() <= 1e-9 * size,
                    "case {case}: {along} off {normal}"
                );
                true
            };
            let found = match case % 3 {
                0 => {
                    let half = Vector::new(between(0.2, 0.5), between(0.2, 0.5), between(0.2, 0.5));
                    check(&Cuboid::new(half), &mut ours, &mut parrys)
                }
                1 => check(&hull(&mut between), &mut ours, &mut parrys),
                _ => {
                    let other = Cylinder::new(between(0.2, 0.5), between(0.25, 0.5));
                    check(&other, &mut ours, &mut parrys)
                }
            };
            compared += usize::from(found);
        }
        // Most pairs overlap, and most of those take the relative tolerance's answer.
        assert!(compared > 300, "{compared} of 600");
    }
}
