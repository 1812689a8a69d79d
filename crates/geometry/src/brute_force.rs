//! Obvious O(n) reference versions of the polygon queries, for property tests and benchmarks.
//!
//! They share nothing with the fast paths but the polygon's vertices and tolerance.

use nalgebra::Point2;

use crate::nearest::closest_point_on_segment;
use crate::{ConvexPolygon, PolygonKind, signed_area};

/// Inside or on the boundary: not farther than the tolerance outside any edge's line (a point or
/// segment polygon: within the tolerance of it).
pub fn contains(polygon: &ConvexPolygon, p: &Point2<f64>) -> bool {
    if polygon.kind() != PolygonKind::Polygon {
        return (nearest_on_boundary(polygon, p) - p).norm() <= polygon.tolerance();
    }
    edges(polygon)
        .all(|(a, b)| 2.0 * signed_area(&a, &b, p) / (b - a).norm() >= -polygon.tolerance())
}

/// `p` when [`contains`] says so, otherwise the nearest point over every edge segment.
pub fn nearest_point(polygon: &ConvexPolygon, p: &Point2<f64>) -> Point2<f64> {
    if contains(polygon, p) {
        *p
    } else {
        nearest_on_boundary(polygon, p)
    }
}

/// The nearest point of the boundary: the minimum over every edge segment.
pub fn nearest_on_boundary(polygon: &ConvexPolygon, p: &Point2<f64>) -> Point2<f64> {
    edges(polygon)
        .map(|(a, b)| closest_point_on_segment(&a, &b, p))
        .min_by(|x, y| (x - p).norm_squared().total_cmp(&(y - p).norm_squared()))
        .unwrap_or(polygon.vertices()[0])
}

fn edges(polygon: &ConvexPolygon) -> impl Iterator<Item = (Point2<f64>, Point2<f64>)> + '_ {
    let v = polygon.vertices();
    (0..v.len()).map(move |i| (v[i], v[(i + 1) % v.len()]))
}
