//! Area moments of a support polygon: signed area, centroid and the mean distance `r̄`.
//!
//! Symbols: `S` the polygon, `A` its area, `G` its centroid, `c` any reference point.
//!
//! The torsional-friction bound of the face model is `M = μ f₃ r̄` with
//! `r̄ = (1/A) ∫_S |x − c| dA` (paper eq. 7, uniform pressure). The paper discretises the integral
//! on a grid (eqs. 8–9); here it is exact. Split `S` into the fan triangles `(c, vᵢ, vᵢ₊₁)`, signed
//! so the fan may start outside `S`. In polar coordinates about `c`, a triangle contributes
//! `∫ ρ(θ)³/3 dθ` with `ρ = d / cos(θ − φ)` the distance to the edge's line (`d` its distance from
//! `c`). With `s` the position along the edge measured from the foot of the perpendicular and
//! `r = √(d² + s²)`, `∫ sec³` gives
//!
//! `I = (1/6) [ d (r s) + d³ asinh(s / d) ]` evaluated from `s₁` to `s₂`,
//!
//! written with `asinh` rather than the textbook `ln(s + r)` so that edges seen nearly end-on lose
//! no digits. A boundary-inclusive grid overestimates a unit square's `r̄` by about 40%; the
//! midpoint grid of [`ConvexPolygon::mean_distance_grid`] converges to the exact value.

use nalgebra::Point2;

use crate::{ConvexPolygon, GeometryError, PolygonKind};

/// Samples per axis at most for [`ConvexPolygon::mean_distance_grid`], bounding its memory-free
/// loop to 16.7 million points however fine the requested spacing.
pub const MAX_GRID_SAMPLES_PER_AXIS: usize = 4096;

/// Signed area of the triangle `abc`: positive when `a, b, c` run counter-clockwise (paper eq. 17
/// for three points).
///
/// ```
/// use nalgebra::Point2;
/// use tatami_geometry::signed_area;
///
/// let (a, b, c) = (Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0));
/// assert_eq!(signed_area(&a, &b, &c), 0.5);
/// assert_eq!(signed_area(&a, &c, &b), -0.5);
/// ```
pub fn signed_area(a: &Point2<f64>, b: &Point2<f64>, c: &Point2<f64>) -> f64 {
    0.5 * (b - a).perp(&(c - a))
}

/// Area and centroid of a counter-clockwise ring; a segment's midpoint, a point itself.
///
/// Moments are taken about the first vertex so large coordinates do not swamp small faces.
pub(crate) fn area_and_centroid(vertices: &[Point2<f64>]) -> (f64, Point2<f64>) {
    let origin = vertices[0];
    match vertices.len() {
        1 => (0.0, origin),
        2 => (0.0, nalgebra::center(&vertices[0], &vertices[1])),
        _ => {
            let mut area = 0.0;
            let mut moment = nalgebra::Vector2::zeros();
            for w in vertices[1..].windows(2) {
                let (a, b) = (w[0] - origin, w[1] - origin);
                let twice = a.perp(&b);
                area += 0.5 * twice;
                moment += (a + b) * (twice / 6.0);
            }
            (area, origin + moment / area)
        }
    }
}

impl ConvexPolygon {
    /// Exact mean distance `(1/A) ∫_S |x − c| dA` of the polygon from `c`; for a segment the mean
    /// over its length, for a point the distance. This is `r̄` of the torsional-friction bound.
    ///
    /// ```
    /// use nalgebra::Point2;
    /// use tatami_geometry::ConvexPolygon;
    ///
    /// // A disc of radius R has r̄ = 2R/3; a 4096-gon is within 1e-6 of it.
    /// let n = 4096;
    /// let disc: Vec<_> = (0..n)
    ///     .map(|i| {
    ///         let t = std::f64::consts::TAU * i as f64 / n as f64;
    ///         Point2::new(t.cos(), t.sin())
    ///     })
    ///     .collect();
    /// let disc = ConvexPolygon::from_points(&disc)?;
    /// assert!((disc.mean_distance(&Point2::origin()) - 2.0 / 3.0).abs() < 1e-6);
    /// # Ok::<(), tatami_geometry::GeometryError>(())
    /// ```
    pub fn mean_distance(&self, c: &Point2<f64>) -> f64 {
        match self.kind() {
            PolygonKind::Point => (self.vertex(0) - c).norm(),
            PolygonKind::Segment => segment_mean_distance(&self.vertex(0), &self.vertex(1), c),
            PolygonKind::Polygon => {
                let n = self.vertices().len();
                let integral: f64 = (0..n)
                    .map(|i| {
                        fan_triangle_distance_integral(c, &self.vertex(i), &self.vertex(i + 1))
                    })
                    .sum();
                // The mean lies between the distance to the centroid (Jensen: |x − c| is
                // convex) and the farthest vertex; rounding for a `c` far from a small polygon
                // may leave the sum a few ulps of |c|³ outside.
                let nearest = (self.centroid() - c).norm();
                let farthest = self
                    .vertices()
                    .iter()
                    .map(|v| (v - c).norm())
                    .fold(0.0, f64::max);
                (integral / self.area()).max(nearest).min(farthest)
            }
        }
    }

    /// [`mean_distance`](Self::mean_distance) from the centroid — the face model's exact `r̄` —
    /// computed when first asked and kept: a contact whose support polygon is unchanged from
    /// one step to the next pays for it once.
    ///
    /// ```
    /// use nalgebra::Point2;
    /// use tatami_geometry::ConvexPolygon;
    /// let square = ConvexPolygon::from_points(&[
    ///     Point2::new(-1.0, -1.0), Point2::new(1.0, -1.0), Point2::new(1.0, 1.0), Point2::new(-1.0, 1.0),
    /// ])?;
    /// // (√2 + asinh 1) / 3 for a square of half-side 1.
    /// let r_bar = (2f64.sqrt() + 1f64.asinh()) / 3.0;
    /// assert!((square.centroid_mean_distance() - r_bar).abs() < 1e-12);
    /// assert_eq!(square.centroid_mean_distance(), square.mean_distance(&square.centroid()));
    /// # Ok::<(), tatami_geometry::GeometryError>(())
    /// ```
    pub fn centroid_mean_distance(&self) -> f64 {
        self.centroid_mean_distance
            .get_or(|| self.mean_distance(&self.centroid()))
    }

    /// The paper's discretised mean distance (eq. 9): the average of `|x − c|` over the centres
    /// of a square grid of the given `spacing` that fall inside the polygon. Kept to reproduce
    /// the paper and to show convergence to [`mean_distance`](Self::mean_distance).
    ///
    /// The grid is aligned with the bounding box and each axis holds at most
    /// [`MAX_GRID_SAMPLES_PER_AXIS`] samples, so a spacing finer than that (or a zero, negative or
    /// NaN one) is raised to it; use [`try_mean_distance_grid`](Self::try_mean_distance_grid) to
    /// have an invalid spacing rejected instead. When no centre falls inside (a sliver, a segment
    /// or a point), the centroid is the one sample.
    pub fn mean_distance_grid(&self, c: &Point2<f64>, spacing: f64) -> f64 {
        let (lo, hi) = self.bounding_box();
        let extent = hi - lo;
        let cells = |len: f64| -> usize {
            let wanted = (len / spacing).ceil();
            // NaN, zero or negative spacing falls through to the finest grid.
            if wanted.is_finite() && wanted >= 1.0 {
                (wanted as usize).min(MAX_GRID_SAMPLES_PER_AXIS)
            } else if wanted.is_finite() {
                1
            } else {
                MAX_GRID_SAMPLES_PER_AXIS
            }
        };
        let (nx, ny) = (cells(extent.x), cells(extent.y));
        let (hx, hy) = (extent.x / nx as f64, extent.y / ny as f64);
        let mut sum = 0.0;
        let mut count = 0usize;
        for i in 0..nx {
            for j in 0..ny {
                let x = Point2::new(lo.x + (i as f64 + 0.5) * hx, lo.y + (j as f64 + 0.5) * hy);
                if self.contains(&x) {
                    sum += (x - c).norm();
                    count += 1;
                }
            }
        }
        if count == 0 {
            (self.centroid() - c).norm()
        } else {
            sum / count as f64
        }
    }

    /// [`mean_distance_grid`](Self::mean_distance_grid) that rejects a spacing that is not finite
    /// and positive instead of raising it to the finest grid.
    pub fn try_mean_distance_grid(
        &self,
        c: &Point2<f64>,
        spacing: f64,
    ) -> Result<f64, GeometryError> {
        if spacing.is_finite() && spacing > 0.0 {
            Ok(self.mean_distance_grid(c, spacing))
        } else {
            Err(GeometryError::InvalidSpacing(spacing))
        }
    }

    /// Lower-left and upper-right corners of the axis-aligned bounding box.
    pub fn bounding_box(&self) -> (Point2<f64>, Point2<f64>) {
        let first = self.vertex(0);
        self.vertices()
            .iter()
            .fold((first, first), |(lo, hi), v| (lo.inf(v), hi.sup(v)))
    }
}

/// `∫ |x − c| dA` over the triangle `(c, a, b)`, signed by its orientation (module docs).
fn fan_triangle_distance_integral(c: &Point2<f64>, a: &Point2<f64>, b: &Point2<f64>) -> f64 {
    let edge = b - a;
    let len = edge.norm();
    if len == 0.0 {
        return 0.0;
    }
    let t = edge / len;
    let signed_d = (a - c).perp(&(b - c)) / len;
    let d = signed_d.abs();
    if d == 0.0 {
        return 0.0;
    }
    let (s1, s2) = ((a - c).dot(&t), (b - c).dot(&t));
    // Lengths are bounded far below √f64::MAX, so the plain root (faster than `hypot`) cannot
    // overflow.
    let (r1, r2) = ((s1 * s1 + d * d).sqrt(), (s2 * s2 + d * d).sqrt());
    // The primitive is P(s) = d s r + d³ asinh(s/d), r = √(s² + d²); the integral is
    // (P(s₂) − P(s₁))/6. For a far `c`, P(s₁) and P(s₂) are both of size |c|³ while their
    // difference is |c|²·len, so the differences are rewritten without subtracting: with
    // s₂ − s₁ = len and s₁, s₂ of one sign,
    //   s₂r₂ − s₁r₁ = len (s₁ + s₂)(s₁² + s₂² + d²) / (s₂r₂ + s₁r₁),
    //   asinh(s₂/d) − asinh(s₁/d) = asinh(len (s₁ + s₂) / (s₂r₁ + s₁r₂)).
    let (product, asinh) = if s1 * s2 > 0.0 {
        let sum = s1 + s2;
        (
            len * sum * (s1 * s1 + s2 * s2 + d * d) / (s2 * r2 + s1 * r1),
            (len * sum / (s2 * r1 + s1 * r2)).asinh(),
        )
    } else {
        // s₁ ≤ 0 ≤ s₂: asinh(s₂/d) − asinh(s₁/d) = ln((s₂ + r₂)(r₁ − s₁)/d²), written as
        // ln(1 + x) with x = ((s₂ + r₂)(r₁ − s₁) − d²)/d² expanded into non-negative terms
        // (r₁r₂ − d² = (s₁²s₂² + d²(s₁² + s₂²))/(r₁r₂ + d²)): one logarithm, no cancellation.
        let excess = s2 * r1 - s1 * r2 - s1 * s2
            + (s1 * s1 * s2 * s2 + d * d * (s1 * s1 + s2 * s2)) / (r1 * r2 + d * d);
        (s2 * r2 - s1 * r1, (excess / (d * d)).ln_1p())
    };
    // d³ asinh(…) → 0 as d → 0; below d ≈ 1e-108, d³ is 0 while s/d may overflow to ∞, and
    // 0·∞ would be NaN.
    let cube = d.powi(3);
    let log_term = if cube == 0.0 { 0.0 } else { cube * asinh };
    signed_d.signum() * (d * product + log_term) / 6.0
}

/// Mean of `|x − c|` over the segment `a b`: `(1/L) ∫ √(d² + s²) ds`.
fn segment_mean_distance(a: &Point2<f64>, b: &Point2<f64>, c: &Point2<f64>) -> f64 {
    let edge = b - a;
    let len = edge.norm();
    let t = edge / len;
    let d = (a - c).perp(&t).abs();
    let (s1, s2) = ((a - c).dot(&t), (b - c).dot(&t));
    let primitive = |s: f64| {
        let r = s.hypot(d);
        // d² asinh(s/d) → 0 as d → 0; below d ≈ 1e-162, d² is 0 while s/d may overflow to ∞,
        // and 0·∞ would be NaN.
        if d * d == 0.0 {
            s * r
        } else {
            s * r + d * d * (s / d).asinh()
        }
    };
    (primitive(s2) - primitive(s1)) / (2.0 * len)
}
