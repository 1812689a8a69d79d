//! The bearing part of a contact: where its two surfaces meet, not where one stands off the
//! other.
//!
//! A face within the feature angle of the contact plane (1° by default) gives the whole face as
//! the support polygon, its depths falling across it: a 2 m cube tilted by 0.8° has one edge on
//! the floor and the other 2.8 cm above it. The face model's block holds the bodies' relative
//! turn while its centre of pressure is in the polygon, so on the whole face it held that tilt
//! for ever, where the vertex and patch models, whose far rows may only close their gaps, let
//! the cube fall flat. The face model builds its block on the part of the polygon within
//! [`bearing_depth`] of its deepest point instead: the strip along the touching edge, which
//! widens as the face closes and is the whole face once it lies flat within that depth. The
//! depths are affine across the overlap of two planar features, so that part is the polygon
//! cut by one line. A face pressed in deeper than the slop all over keeps its whole polygon:
//! the overlap is being pushed out over all of it (500 cubes spawned inside one another, cut
//! to slivers along their deepest edges, still overlapped by 0.53 m after 8 s; on whole faces
//! the last overlap falls below 5 cm by 6.6 s). One pressed in at its deepest point alone is
//! cut: a face landing tilted within the feature angle leaves its low edge beyond the slop,
//! where the position pass, removing a tenth of the depth beyond the slop a step, brings it to
//! the slop from above and never past it, and a whole polygon kept while the deepest point was
//! beyond the slop held such a face at its tilt (a 1 m cube dropped 0.8° off flat stood so,
//! its high edge 12 mm up, for seconds).
//!
//! The depth follows the polygon's size ([`bearing_depth`]): the strip must stay narrow beside
//! the face for the body to tip flat, and under a fixed 0.5 mm a 5 cm cube left tilted by 0.9°
//! on its edge stood so for ever, its strip (3.2 cm) reaching past its centre. The face model
//! then keeps the vertices off the strip from passing its level ([`crate::face`]'s landing
//! blocks): nothing held them, and a small cube tipping flat in one step went through the
//! floor on its other side.

use nalgebra::{Point2, Vector2};
use smallvec::SmallVec;
use tatami_geometry::ConvexPolygon;

use crate::Contact;

/// How far below the deepest point (m) a point of the support polygon still bears, at most: a
/// quarter of the default slop. The face model holds the tilt of a face whose depths differ by
/// less (0.014° across a 2 m face): a 2 m cube left on its edge tilted by 0.3–0.95° came to
/// rest within 0.017° of flat. Measured with the part taken at every depth: 0.1 mm left it
/// within 0.002–0.006°, but a sliver of 10 µm along the deepest edge let a dropped cube rock
/// from edge to edge without end.
pub const BEARING_DEPTH: f64 = 5e-4;

/// Bearing depth per metre of the support polygon's width ([`bearing_depth`]): a face holds a
/// tilt of at most about half a thousandth of a radian (0.03°) across its width, whatever its
/// size. Polygons a metre wide or more keep [`BEARING_DEPTH`]; across smaller ones that depth
/// is a steeper tilt.
pub const BEARING_DEPTH_PER_WIDTH: f64 = 5e-4;

/// How far below its deepest point (m) a point of `support` still bears: [`BEARING_DEPTH`], or
/// [`BEARING_DEPTH_PER_WIDTH`] times the polygon's width if less. The width is twice the
/// largest distance of a vertex from the vertices' mean (the diagonal of a rectangle, the
/// length of a segment, 0 for a point), the same however the polygon is turned.
///
/// ```
/// use nalgebra::Point2;
/// use tatami_contact::{BEARING_DEPTH, bearing_depth};
/// use tatami_geometry::ConvexPolygon;
///
/// let square = |side: f64| {
///     let h = side / 2.0;
///     ConvexPolygon::from_points(&[(-h, -h), (h, -h), (h, h), (-h, h)].map(|(x, y)| Point2::new(x, y)))
/// };
/// assert_eq!(bearing_depth(&square(2.0)?), BEARING_DEPTH);
/// // A 5 cm face: 5e-4 of its 7.1 cm diagonal, 35 µm.
/// assert!((bearing_depth(&square(0.05)?) - 0.05 * 2f64.sqrt() * 5e-4).abs() < 1e-15);
/// # Ok::<(), tatami_geometry::GeometryError>(())
/// ```
pub fn bearing_depth(support: &ConvexPolygon) -> f64 {
    let vertices = support.vertices();
    let mean = vertices.iter().map(|v| v.coords).sum::<Vector2<f64>>() / vertices.len() as f64;
    let farthest = vertices
        .iter()
        .map(|v| (v.coords - mean).norm_squared())
        .fold(0.0, f64::max);
    BEARING_DEPTH.min(BEARING_DEPTH_PER_WIDTH * 2.0 * farthest.sqrt())
}

/// `contact` on the part of its support polygon whose depth is within `within` (m) of its
/// deepest vertex's, the depths of the new vertices interpolated along the cut edges; `None`
/// when every vertex is within it (the contact bears on all of its polygon). The contact's
/// depths must have been checked ([`Contact::validate_depths`]).
pub(crate) fn bearing_part(contact: &Contact, within: f64) -> Option<Contact> {
    let cut = contact.depth() - within;
    let depths = &contact.depths;
    if depths.iter().all(|&d| d >= cut) {
        return None;
    }
    let vertices = contact.support.vertices();
    let n = vertices.len();
    // A cut keeps at most all the vertices and adds two: inline for a box's contact (at most 8).
    let (mut points, mut point_depths) = (
        SmallVec::<[Point2<f64>; 10]>::new(),
        SmallVec::<[f64; 10]>::new(),
    );
    for i in 0..n {
        let (p, q) = (vertices[i], vertices[(i + 1) % n]);
        let (dp, dq) = (depths[i], depths[(i + 1) % n]);
        if dp >= cut {
            points.push(p);
            point_depths.push(dp);
        }
        if (dp >= cut) != (dq >= cut) {
            let t = (dp - cut) / (dp - dq);
            points.push(p + (q - p) * t);
            point_depths.push(cut);
        }
    }
    let support = ConvexPolygon::from_points(&points).ok()?;
    // The hull keeps some of the points as they are: each takes its own depth.
    let depths = support
        .vertices()
        .iter()
        .map(|v| points.iter().position(|p| p == v).map(|k| point_depths[k]))
        .collect::<Option<Vec<f64>>>()?;
    Some(Contact {
        support,
        depths,
        body_a: contact.body_a,
        body_b: contact.body_b,
        centre_a: contact.centre_a,
        centre_b: contact.centre_b,
        frame: contact.frame,
        material: contact.material,
        // The face model reads them off the whole contact.
        landing: Vec::new(),
        bounce_speed: contact.bounce_speed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ContactFrame, Material};
    use nalgebra::{Point3, Vector3};
    use proptest::prelude::*;
    use tatami_geometry::PolygonKind;
    use tatami_lcp::BodyId;

    fn contact(vertices: &[Point2<f64>], depths: Vec<f64>) -> Contact {
        Contact {
            body_a: BodyId(0),
            body_b: BodyId(1),
            centre_a: Point3::new(0.0, 0.0, 1.0),
            centre_b: Point3::new(0.0, 0.0, -1.0),
            frame: ContactFrame::from_normal(Point3::origin(), Vector3::z()).unwrap(),
            support: ConvexPolygon::from_points(vertices).unwrap(),
            depths,
            material: Material::new(0.5, 0.5, 0.0).unwrap(),
            landing: Vec::new(),
            bounce_speed: 0.0,
        }
    }

    /// A 2 m square resting on its edge x = −1, its edge x = 1 lifted 2 cm: within 2 mm of the
    /// touching edge is the strip −1 ≤ x ≤ −0.8 (area 0.4); pressed in by 3 mm at x = −1 and
    /// 1.5 mm at x = 1, all of it is within 2 mm of the deepest; still 5 mm above the floor at
    /// x = −1 and 25 mm at x = 1, the nearest strip, of the same area.
    #[test]
    fn a_square_on_its_edge_bears_on_the_strip_along_it() {
        let square =
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
        let on_edge = contact(&square, vec![0.0, -0.02, -0.02, 0.0]);
        let bearing = bearing_part(&on_edge, 0.002).expect("the far edge stands off");
        assert_eq!(bearing.support.kind(), PolygonKind::Polygon);
        assert!((bearing.support.area() - 0.4).abs() < 1e-12);
        assert!(bearing.depths.iter().all(|&d| d >= -0.002 - 1e-15));
        let pressed = contact(&square, vec![0.003, 0.0015, 0.0015, 0.003]);
        assert!(bearing_part(&pressed, 0.002).is_none());
        let above = contact(&square, vec![-0.005, -0.025, -0.025, -0.005]);
        let nearest = bearing_part(&above, 0.002).expect("the far edge is farther");
        assert!((nearest.support.area() - 0.4).abs() < 1e-12);
    }

    /// Against brute force: a regular polygon turned anywhere, its depths an affine function
    /// `d(x) = c + g · x` (a face tilted against the other, touching, pressed in or apart). The
    /// bearing part is the set `d ≥ max d − within`: every one of its vertices is in
    /// the polygon and on the right side (within rounding, 1e-9 of the polygon's 1 m size and
    /// of the depths' 0.1 m range), the deepest vertex is one of them, the depths carried are
    /// `d` at each vertex, and a grid point of the polygon is inside the part exactly when it
    /// is on the right side (away from the cut by 1e-6, beyond rounding).
    #[test]
    fn the_bearing_part_is_where_the_depth_is_within_reach_of_the_deepest() {
        proptest!(ProptestConfig::with_cases(256), |(
            sides in 3usize..9,
            turn in 0.0..6.3f64,
            (c, gx, gy) in (-0.01..0.01f64, -0.05..0.05f64, -0.05..0.05f64),
            within in 0.0..0.002f64,
        )| {
            let ring: Vec<Point2<f64>> = (0..sides)
                .map(|k| {
                    let t = turn + std::f64::consts::TAU * k as f64 / sides as f64;
                    Point2::new(t.cos(), t.sin())
                })
                .collect();
            let depth = |p: &Point2<f64>| c + gx * p.x + gy * p.y;
            let whole = contact(&ring, Vec::new());
            let depths = whole.support.vertices().iter().map(depth).collect();
            let whole = Contact { depths, ..whole };
            let deepest = whole.depth();
            let cut = deepest - within;
            let Some(part) = bearing_part(&whole, within) else {
                prop_assert!(whole.depths.iter().all(|&d| d >= cut));
                return Ok(());
            };
            prop_assert!(whole.depths.iter().any(|&d| d < cut));
            prop_assert_eq!(part.depths.len(), part.support.vertices().len());
            for (v, &d) in part.support.vertices().iter().zip(&part.depths) {
                prop_assert!((d - depth(v)).abs() < 1e-9);
                prop_assert!(d >= cut - 1e-9);
                prop_assert!((whole.support.nearest_point(v) - v).norm() < 1e-9);
            }
            prop_assert!((part.depth() - deepest).abs() < 1e-12);
            for i in -20..=20 {
                for j in -20..=20 {
                    let p = Point2::new(f64::from(i) / 20.0, f64::from(j) / 20.0);
                    if !whole.support.contains(&p) || (depth(&p) - cut).abs() < 1e-6 {
                        continue;
                    }
                    prop_assert_eq!(part.support.contains(&p), depth(&p) > cut, "{:?}", p);
                }
            }
        });
    }
}
