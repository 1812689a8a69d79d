//! The nearest point of the support polygon (paper §3.2.3), where an escaped ZMP is moved.
//!
//! For `p` outside, the fan search gives its sector `i`; edge `i` is then visible from `p`.
//! 1. If the foot of the perpendicular from `p` falls on edge `i` (eq. 18: both end angles are
//!    acute), the foot is the nearest point — the polygon lies behind that edge's line.
//! 2. Otherwise walk counter-clockwise from the edge's end vertex, edge by edge, stopping at the
//!    first edge whose foot is on it (done) or when the next vertex is no nearer than the last.
//! 3. Likewise clockwise from the edge's start vertex.
//! 4. No foot found: the nearer of the two vertices where the walks stopped.
//!
//! Why the walks stop at the right place: along the chain of edges visible from `p`, the distance
//! seen from `p` is the maximum of `dₖ / cos(φ − φₖ)` over the edges' lines, a convex function of
//! the viewing angle `φ`, so vertex distances fall and then rise along it. The foot is computed by
//! projection onto the edge (`a + t (b − a)`, `t` clamped to `[0, 1]`), which is eq. 19's
//! `p + d n` without the cancellation of subtracting nearly equal distances.

use nalgebra::Point2;

use crate::polygon::{ring_next, ring_previous};
use crate::{ConvexPolygon, PolygonKind, Sector, signed_area};

impl ConvexPolygon {
    /// `p` itself when inside (boundary included); otherwise the nearest point of the polygon.
    ///
    /// ```
    /// use nalgebra::Point2;
    /// use tatami_geometry::ConvexPolygon;
    ///
    /// let triangle = ConvexPolygon::from_points(&[
    ///     Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(0.0, 2.0),
    /// ])?;
    /// assert_eq!(triangle.nearest_point(&Point2::new(2.0, 2.0)), Point2::new(1.0, 1.0));
    /// assert_eq!(triangle.nearest_point(&Point2::new(3.0, -1.0)), Point2::new(2.0, 0.0));
    /// # Ok::<(), tatami_geometry::GeometryError>(())
    /// ```
    pub fn nearest_point(&self, p: &Point2<f64>) -> Point2<f64> {
        let location = self.locate(p);
        self.nearest_point_located(p, location.sector, location.inside)
    }

    /// [`nearest_point`](Self::nearest_point) starting the sector search from `hint`; also returns
    /// the sector `p` was found in, to pass as the hint of the next query.
    pub fn nearest_point_from(&self, p: &Point2<f64>, hint: Sector) -> (Point2<f64>, Sector) {
        if self.kind() != PolygonKind::Polygon {
            // What `locate` and `nearest_point_located` would give, with one projection.
            let nearest = self.nearest_point_degenerate(p);
            let inside = (nearest - p).norm() <= self.tolerance();
            return (if inside { *p } else { nearest }, Sector(0));
        }
        let location = self.locate_from(p, hint);
        (
            self.nearest_point_located(p, location.sector, location.inside),
            location.sector,
        )
    }

    fn nearest_point_located(&self, p: &Point2<f64>, sector: Sector, inside: bool) -> Point2<f64> {
        if inside {
            *p
        } else if self.kind() == PolygonKind::Polygon {
            self.nearest_on_boundary(p, sector.0)
        } else {
            self.nearest_point_degenerate(p)
        }
    }

    /// Nearest point of a point or segment polygon.
    pub(crate) fn nearest_point_degenerate(&self, p: &Point2<f64>) -> Point2<f64> {
        closest_point_on_segment(&self.vertex(0), &self.vertex(1), p)
    }

    /// Steps 1–4 of the module docs for `p` outside, in sector `i`.
    fn nearest_on_boundary(&self, p: &Point2<f64>, i: usize) -> Point2<f64> {
        if let Some(foot) = self.foot_on_edge(i, p) {
            return foot;
        }
        let ccw = match self.walk(p, i + 1, Walk::CounterClockwise) {
            WalkEnd::Foot(foot) => return foot,
            WalkEnd::Vertex(v) => v,
        };
        let cw = match self.walk(p, i, Walk::Clockwise) {
            WalkEnd::Foot(foot) => return foot,
            WalkEnd::Vertex(v) => v,
        };
        if (ccw - p).norm_squared() <= (cw - p).norm_squared() {
            ccw
        } else {
            cw
        }
    }

    /// Walks from vertex `start` while the vertices come nearer to `p`, checking each edge passed
    /// for a foot.
    fn walk(&self, p: &Point2<f64>, start: usize, direction: Walk) -> WalkEnd {
        let n = self.vertices().len();
        let mut at = start % n;
        let mut dist_sq = (self.vertex(at) - p).norm_squared();
        for _ in 0..n {
            let (edge, next) = match direction {
                Walk::CounterClockwise => (at, ring_next(at, n)),
                Walk::Clockwise => (ring_previous(at, n), ring_previous(at, n)),
            };
            if let Some(foot) = self.foot_on_edge(edge, p) {
                return WalkEnd::Foot(foot);
            }
            let next_dist_sq = (self.vertex(next) - p).norm_squared();
            if next_dist_sq >= dist_sq {
                break;
            }
            (at, dist_sq) = (next, next_dist_sq);
        }
        WalkEnd::Vertex(self.vertex(at))
    }

    /// The foot of the perpendicular from `p` on edge `i`, if `p` is outside the edge's line and
    /// the foot falls on the edge (paper eq. 18).
    fn foot_on_edge(&self, i: usize, p: &Point2<f64>) -> Option<Point2<f64>> {
        let (a, b) = (self.vertex(i), self.vertex(i + 1));
        let outside = signed_area(&a, &b, p) < 0.0;
        let ab = b - a;
        let on_edge = ab.dot(&(p - a)) >= 0.0 && (a - b).dot(&(p - b)) >= 0.0;
        (outside && on_edge).then(|| closest_point_on_segment(&a, &b, p))
    }
}

/// The point of segment `a b` nearest to `p` (`a` when the segment has zero length).
///
/// ```
/// use nalgebra::Point2;
/// use tatami_geometry::nearest::closest_point_on_segment;
///
/// let (a, b) = (Point2::new(0.0, 0.0), Point2::new(4.0, 0.0));
/// assert_eq!(closest_point_on_segment(&a, &b, &Point2::new(1.0, 3.0)), Point2::new(1.0, 0.0));
/// assert_eq!(closest_point_on_segment(&a, &b, &Point2::new(9.0, 1.0)), b);
/// ```
pub fn closest_point_on_segment(a: &Point2<f64>, b: &Point2<f64>, p: &Point2<f64>) -> Point2<f64> {
    let ab = b - a;
    let len_sq = ab.norm_squared();
    if len_sq == 0.0 {
        return *a;
    }
    let t = (ab.dot(&(p - a)) / len_sq).clamp(0.0, 1.0);
    a + ab * t
}

/// Direction of a walk round the polygon.
#[derive(Clone, Copy)]
enum Walk {
    CounterClockwise,
    Clockwise,
}

/// Where a walk stopped: on an edge's foot (the answer) or at its nearest vertex.
enum WalkEnd {
    Foot(Point2<f64>),
    Vertex(Point2<f64>),
}
