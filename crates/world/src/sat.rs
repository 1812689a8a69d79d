//! The separating-axis test of two convex polytopes (hulls and boxes): the axis along which they
//! are separated most, or overlap least, among the face normals of each and the cross products of
//! an edge of each. For polytopes this is the exact contact normal, the axis GJK and EPA
//! converge to, without their iterations and allocations (EPA, which parry builds afresh for each
//! call, took a fifth of the profile samples of the 1000-shape pile).
//!
//! Edge pairs are tried only where their arcs on the Gauss map cross (Gregorius, "The
//! Separating Axis Test between Convex Polyhedra", GDC 2013): only those pairs build a face of
//! the Minkowski difference, whose separation is then that of the two edges themselves, without
//! the support functions. An edge pair let through by round-off is within round-off of building
//! one, and so is its separation.

use nalgebra::{UnitQuaternion, Vector3};

use crate::apart::{AxisFrame, AxisGap};

/// A convex polytope in its own frame.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Polytope {
    vertices: Vec<Vector3<f64>>,
    /// Outward unit normal `n` and offset `d` of each face (`n · x = d` on it).
    faces: Vec<(Vector3<f64>, f64)>,
    /// Each edge's two vertices and the outward unit normals `n₁`, `n₂` of its two faces, with
    /// `n₂ × n₁`, the normal of the edge's arc on the Gauss map.
    edges: Vec<Edge>,
    /// The mean of the vertices: a point inside.
    centre: Vector3<f64>,
}

/// An edge of a [`Polytope`].
#[derive(Debug, Clone, PartialEq)]
struct Edge {
    ends: [usize; 2],
    /// The two faces' indices in [`Polytope::faces`].
    faces: [usize; 2],
    normals: [Vector3<f64>; 2],
    arc: Vector3<f64>,
}

impl Polytope {
    /// A polytope from its vertices, its faces (outward unit normal and a vertex index each) and
    /// its edges (two vertex indices and two face indices each); `None` if an index is out of
    /// range or there are no vertices.
    pub(crate) fn new(
        vertices: Vec<Vector3<f64>>,
        faces: &[(Vector3<f64>, usize)],
        edges: &[([usize; 2], [usize; 2])],
    ) -> Option<Self> {
        if vertices.is_empty() {
            return None;
        }
        let faces = faces
            .iter()
            .map(|&(n, v)| Some((n, n.dot(vertices.get(v)?))))
            .collect::<Option<Vec<_>>>()?;
        let edges = edges
            .iter()
            .map(|&(ends, [f, g])| {
                ends.iter().all(|&v| v < vertices.len()).then_some(())?;
                let normals = [faces.get(f)?.0, faces.get(g)?.0];
                Some(Edge {
                    ends,
                    faces: [f, g],
                    normals,
                    arc: normals[1].cross(&normals[0]),
                })
            })
            .collect::<Option<Vec<_>>>()?;
        let centre = vertices.iter().sum::<Vector3<f64>>() / vertices.len() as f64;
        Some(Self {
            vertices,
            faces,
            edges,
            centre,
        })
    }

    /// Outward unit normal `n` and offset `d` of each face (`n · x = d` on it).
    pub(crate) fn faces(&self) -> &[(Vector3<f64>, f64)] {
        &self.faces
    }

    /// Each edge's two vertices and two faces, by index.
    #[cfg(test)]
    pub(crate) fn edges(&self) -> impl Iterator<Item = ([usize; 2], [usize; 2])> + '_ {
        self.edges.iter().map(|e| (e.ends, e.faces))
    }

    /// The least width across the polytope between two parallel planes, one of them a face's:
    /// over its faces, how far the vertices reach back from the face's plane (m).
    pub(crate) fn thickness(&self) -> f64 {
        self.faces
            .iter()
            .map(|(n, d)| d + self.support(&-n))
            .fold(f64::INFINITY, f64::min)
    }

    /// A vertex furthest along `direction` (the first of those that tie).
    pub(crate) fn support_point(&self, direction: &Vector3<f64>) -> Vector3<f64> {
        let mut best = (f64::NEG_INFINITY, self.centre);
        for v in &self.vertices {
            let along = v.dot(direction);
            if along > best.0 {
                best = (along, *v);
            }
        }
        best.1
    }

    /// The largest of `direction · v` over the vertices.
    fn support(&self, direction: &Vector3<f64>) -> f64 {
        self.vertices
            .iter()
            .map(|v| v.dot(direction))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// The axis (unit, in `a`'s frame, pointing out of `a`) along which `b` — placed by `rotation`
/// and `translation` in `a`'s frame — is separated most from `a`, and that separation (negative:
/// the least overlap). An error as soon as some axis separates them by more than `prediction`,
/// with that axis's separation when it is a face normal (see [`crate::apart`]).
pub(crate) fn separating_axis(
    a: &Polytope,
    b: &Polytope,
    rotation: &UnitQuaternion<f64>,
    translation: &Vector3<f64>,
    prediction: f64,
) -> Result<(f64, Vector3<f64>), Option<AxisGap>> {
    let mut best = (f64::NEG_INFINITY, Vector3::z());
    let mut consider = |separation: f64, axis: Vector3<f64>| {
        if separation > best.0 {
            best = (separation, axis);
        }
        separation <= prediction
    };
    // A's faces, then B's (whose outward normals point out of A negated).
    for (n, d) in &a.faces {
        let in_b = rotation.inverse_transform_vector(&-n);
        let separation = -b.support(&in_b) + n.dot(translation) - d;
        if !consider(separation, *n) {
            return Err(Some(AxisGap {
                separation,
                frame: AxisFrame::First,
            }));
        }
    }
    // B's face normals in A's frame, negated: B's side of the difference A − B on the Gauss map.
    let b_normals: Vec<Vector3<f64>> = b.faces.iter().map(|(m, _)| -(rotation * m)).collect();
    for (axis, (_, e)) in b_normals.iter().zip(&b.faces) {
        let separation = -a.support(axis) + axis.dot(translation) - e;
        if !consider(separation, *axis) {
            return Err(Some(AxisGap {
                separation,
                frame: AxisFrame::Second,
            }));
        }
    }
    // Which side of each of A's arcs' planes each of B's normals lies on, `sides[f · E + e]`
    // for B's face `f` and A's edge `e`: every edge pair's first test reads two of these, so
    // each product is formed once per face instead of once per edge pair (a face has about
    // three edges).
    let arcs = a.edges.len();
    let mut sides = Vec::with_capacity(b_normals.len() * arcs);
    for c in &b_normals {
        sides.extend(a.edges.iter().map(|a_edge| c.dot(&a_edge.arc)));
    }
    // Edge pairs building a face of the Minkowski difference.
    for b_edge in &b.edges {
        let ([p, q], [f1, f2]) = (b_edge.ends, b_edge.faces);
        let (p, q) = (
            rotation * b.vertices[p] + translation,
            rotation * b.vertices[q] + translation,
        );
        let (c, d) = (b_normals[f1], b_normals[f2]);
        let d_x_c = d.cross(&c);
        let (c_sides, d_sides) = (
            &sides[f1 * arcs..(f1 + 1) * arcs],
            &sides[f2 * arcs..(f2 + 1) * arcs],
        );
        for ((a_edge, &cba), &dba) in a.edges.iter().zip(c_sides).zip(d_sides) {
            // The arcs cross where B's ends C, D lie on either side of A's arc's plane, A's ends
            // N₁, N₂ on either side of B's, and the arcs on one hemisphere. The first test
            // alone rejects most pairs, so it is made before the others' products.
            if cba * dba >= 0.0 {
                continue;
            }
            let ([r, s], [n1, n2]) = (a_edge.ends, a_edge.normals);
            let (adc, bdc) = (n1.dot(&d_x_c), n2.dot(&d_x_c));
            if !(adc * bdc < 0.0 && cba * bdc > 0.0) {
                continue;
            }
            let (r, s) = (a.vertices[r], a.vertices[s]);
            // Parallel edges (to round-off, whatever the shapes' size) give no axis.
            let (edge_a, edge_b) = (s - r, q - p);
            let cross = edge_a.cross(&edge_b);
            let length = cross.norm();
            if length <= 1e-12 * edge_a.norm() * edge_b.norm() {
                continue;
            }
            let mut axis = cross / length;
            if axis.dot(&(r - a.centre)) < 0.0 {
                axis = -axis;
            }
            // The pair builds a face of the Minkowski difference: its edges are where the two
            // polytopes' extents along the axis end, so the separation is that of the edges.
            let separation = axis.dot(&(p - r));
            if !consider(separation, axis) {
                return Err(Some(AxisGap {
                    separation,
                    frame: AxisFrame::Space,
                }));
            }
        }
    }
    Ok(best)
}
