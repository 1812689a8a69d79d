//! Point location by the paper's fan-sector binary search (§3.2.2.1).
//!
//! Rays from the centroid `G` through the vertices `q₀ … qₙ₋₁` cut the plane into `n` sectors;
//! sector `i` lies between the rays through `qᵢ` and `qᵢ₊₁`. Since `G` is strictly inside a convex
//! polygon, the rays' angles about `G`, measured counter-clockwise from `q₀`, increase with `i`, so
//! a binary search on signed areas finds the sector of a point `p` in O(log n). `p` is inside
//! exactly when it is not to the right of the sector's edge: `area(qᵢ, qᵢ₊₁, p) ≥ 0` (the
//! boundary counts, within the polygon's [tolerance](crate::ConvexPolygon::tolerance)).
//!
//! The paper's printed pseudo-code has unbalanced braces; this is the search it intends, written
//! as "last vertex whose angle does not exceed `p`'s". Angles are never computed: the comparison
//! uses which half-plane of the ray `G q₀` a direction falls in, then one signed area.

use nalgebra::{Point2, Vector2};

use crate::polygon::{ring_next, ring_previous};
use crate::{ConvexPolygon, PolygonKind, signed_area};

/// A sector of the fan about the centroid: sector `i` lies between the rays through vertices `i`
/// and `i + 1`, and its outer side is edge `i`. Keep the one a query returns to start the next
/// query near a point that moves a little (as a solver's sweeps do).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Sector(pub usize);

/// Where a point lies relative to the polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    /// The fan sector holding the point (always `Sector(0)` for a point or a segment).
    pub sector: Sector,
    /// Inside or on the boundary.
    pub inside: bool,
}

impl ConvexPolygon {
    /// Whether `p` lies inside or on the boundary (within [`tolerance`](Self::tolerance)), by the
    /// fan-sector binary search: O(log n).
    pub fn contains(&self, p: &Point2<f64>) -> bool {
        self.locate(p).inside
    }

    /// The radius of the largest disc about `p` that lies in the polygon: the distance from `p`
    /// to the nearest edge's line, 0 when `p` is outside or on the boundary and for a point or
    /// segment polygon. O(n); computed once, it lets a point that moves less than this be known
    /// inside without a search (the face model checks its centre of pressure this way).
    ///
    /// ```
    /// use nalgebra::Point2;
    /// use tatami_geometry::ConvexPolygon;
    ///
    /// let square = ConvexPolygon::from_points(&[
    ///     Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(2.0, 2.0), Point2::new(0.0, 2.0),
    /// ])?;
    /// assert_eq!(square.clearance(&Point2::new(1.0, 1.0)), 1.0);
    /// assert_eq!(square.clearance(&Point2::new(1.5, 1.0)), 0.5);
    /// assert_eq!(square.clearance(&Point2::new(3.0, 1.0)), 0.0);
    /// # Ok::<(), tatami_geometry::GeometryError>(())
    /// ```
    pub fn clearance(&self, p: &Point2<f64>) -> f64 {
        if self.kind() != PolygonKind::Polygon {
            return 0.0;
        }
        (0..self.vertices().len())
            .map(|i| {
                let (a, b) = (self.vertex(i), self.vertex(i + 1));
                2.0 * signed_area(&a, &b, p) / (b - a).norm()
            })
            .fold(f64::INFINITY, f64::min)
            .max(0.0)
    }

    /// [`clearance`](Self::clearance) about the centroid, computed when first asked and kept:
    /// the face model reads it for every face contact every step, and a contact whose support
    /// polygon is unchanged keeps it.
    ///
    /// ```
    /// use nalgebra::Point2;
    /// use tatami_geometry::ConvexPolygon;
    ///
    /// let rectangle = ConvexPolygon::from_points(&[
    ///     Point2::new(0.0, 0.0), Point2::new(4.0, 0.0), Point2::new(4.0, 2.0), Point2::new(0.0, 2.0),
    /// ])?;
    /// assert_eq!(rectangle.centroid_clearance(), 1.0);
    /// assert_eq!(rectangle.centroid_clearance(), rectangle.clearance(&rectangle.centroid()));
    /// # Ok::<(), tatami_geometry::GeometryError>(())
    /// ```
    pub fn centroid_clearance(&self) -> f64 {
        self.centroid_clearance
            .get_or(|| self.clearance(&self.centroid()))
    }

    /// The sector of `p` and whether it is inside.
    pub fn locate(&self, p: &Point2<f64>) -> Location {
        match self.kind() {
            PolygonKind::Polygon => self.locate_in_sector(p, self.sector_of(p)),
            _ => self.locate_degenerate(p),
        }
    }

    /// [`locate`](Self::locate), trying sector `hint` first: O(1) when `p` is still in it.
    pub fn locate_from(&self, p: &Point2<f64>, hint: Sector) -> Location {
        match self.kind() {
            PolygonKind::Polygon => {
                let sector = if hint.0 < self.vertices().len() && self.sector_holds(hint, p) {
                    hint
                } else {
                    self.sector_of(p)
                };
                self.locate_in_sector(p, sector)
            }
            _ => self.locate_degenerate(p),
        }
    }

    /// The binary search: the last vertex `i` whose angle about `G` (from `q₀`) is at most `p`'s.
    fn sector_of(&self, p: &Point2<f64>) -> Sector {
        let angle = FanAngle::new(self);
        let (mut lo, mut hi) = (0, self.vertices().len());
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if angle.precedes(&p.coords, &self.vertex(mid).coords) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Sector(lo)
    }

    /// `p` lies between the rays through vertices `i` and `i + 1`.
    fn sector_holds(&self, Sector(i): Sector, p: &Point2<f64>) -> bool {
        let angle = FanAngle::new(self);
        let after_start = !angle.precedes(&p.coords, &self.vertex(i).coords);
        let before_end =
            i + 1 == self.vertices().len() || angle.precedes(&p.coords, &self.vertex(i + 1).coords);
        after_start && before_end
    }

    /// Tests `p` against the sector's edge and its two neighbours. In exact arithmetic the
    /// sector's own edge decides; in floating point, when `p` lies within rounding of the ray
    /// through a vertex whose neighbouring rays are nearly parallel (a needle-thin polygon seen
    /// from its far-away centroid), the search may return the sector next to the right one, so
    /// the neighbours' edges are checked too (found by fuzzing: a point 0.11 m outside a needle
    /// was reported inside). A point outside gets the sector of the edge it is farthest beyond.
    fn locate_in_sector(&self, p: &Point2<f64>, sector: Sector) -> Location {
        let n = self.vertices().len();
        let neighbours = [ring_previous(sector.0, n), sector.0, ring_next(sector.0, n)];
        // Strictly inside all three edges' lines: inside, without the distances' square roots
        // (what the test below concludes too, every distance being positive).
        if neighbours
            .iter()
            .all(|&i| signed_area(&self.vertex(i), &self.vertex(i + 1), p) > 0.0)
        {
            return Location {
                sector,
                inside: true,
            };
        }
        // Signed distance of p from edge i, positive inside.
        let distance = |i: usize| {
            let (a, b) = (self.vertex(i), self.vertex(i + 1));
            2.0 * signed_area(&a, &b, p) / (b - a).norm()
        };
        let (worst, outside) = neighbours.into_iter().map(|i| (i, distance(i))).fold(
            (sector.0, f64::INFINITY),
            |best, (i, d)| {
                if d < best.1 || d.is_nan() {
                    (i, d)
                } else {
                    best
                }
            },
        );
        if outside >= -self.tolerance() {
            Location {
                sector,
                inside: true,
            }
        } else {
            Location {
                sector: Sector(worst),
                inside: false,
            }
        }
    }

    fn locate_degenerate(&self, p: &Point2<f64>) -> Location {
        let nearest = self.nearest_point_degenerate(p);
        Location {
            sector: Sector(0),
            inside: (nearest - p).norm() <= self.tolerance(),
        }
    }
}

/// Compares angles about the centroid `G`, measured counter-clockwise from the ray `G q₀`, without
/// computing them: first by half-plane of that ray, then by one signed area.
struct FanAngle {
    centroid: Vector2<f64>,
    start: Vector2<f64>,
}

impl FanAngle {
    fn new(polygon: &ConvexPolygon) -> Self {
        let centroid = polygon.centroid().coords;
        Self {
            centroid,
            start: polygon.vertex(0).coords - centroid,
        }
    }

    /// 0 for directions in `[0, π)` from the start ray, 1 for `[π, 2π)`.
    fn half(&self, v: &Vector2<f64>) -> u8 {
        let cross = self.start.perp(v);
        u8::from(!(cross > 0.0 || (cross == 0.0 && self.start.dot(v) > 0.0)))
    }

    /// The angle of `a` is strictly smaller than that of `b`.
    fn precedes(&self, a: &Vector2<f64>, b: &Vector2<f64>) -> bool {
        let (a, b) = (a - self.centroid, b - self.centroid);
        let (half_a, half_b) = (self.half(&a), self.half(&b));
        half_a < half_b || (half_a == half_b && a.perp(&b) > 0.0)
    }
}
