//! The support polygon: a convex hull that keeps every corner and degrades to a segment or a point.
//!
//! Contact clipping produces the support polygon's corners in no particular order, with repeats
//! (a corner found from both bodies) and with points on edges. [`ConvexPolygon::from_points`]
//! turns them into a counter-clockwise hull with Andrew's monotone chain, dropping a point when it
//! lies within a *length tolerance* of the hull through its neighbours. The tolerance scales with
//! the input ([`RELATIVE_TOLERANCE`] of the bounding-box diagonal, plus the rounding of the
//! coordinates' magnitude), so a 1 mm face and a 1 km face are treated alike.
//!
//! Degenerate contacts stay meaningful rather than failing: collinear input is a segment (an edge
//! resting on a face), coincident input a point (a corner). Every query of this crate handles all
//! three kinds.

use nalgebra::Point2;
use smallvec::SmallVec;

use crate::GeometryError;
use crate::area::{self, signed_area};
use crate::kept::Kept;
use crate::nearest::closest_point_on_segment;

/// Points closer than this fraction of the input's bounding-box diagonal to the hull through their
/// neighbours are dropped (as repeated or collinear). 1e-9 keeps slivers a millionth of their
/// length thin while absorbing the rounding of contact clipping.
pub const RELATIVE_TOLERANCE: f64 = 1e-9;

/// Bound on rounding relative to the coordinates' magnitude: differences of coordinates near `X`
/// carry an error of a few `ε·X`, so lengths below that cannot be resolved at all.
const ROUNDING_ULPS: f64 = 8.0 * f64::EPSILON;

/// Largest coordinate size a polygon accepts: 1e75. The centroid sums `(xᵢ + xⱼ)·(xᵢ yⱼ − xⱼ yᵢ)`,
/// a cube of coordinates, so 1e75 keeps every term near 1e226 and any sum far from f64's 1.8e308
/// overflow; contact polygons are within 1e5 m of the origin.
pub const MAX_COORDINATE: f64 = 1e75;

/// What a support polygon degenerates to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PolygonKind {
    /// One distinct point: a corner contact.
    Point,
    /// Two distinct points: an edge contact.
    Segment,
    /// Three or more vertices enclosing a positive area: a face contact.
    Polygon,
}

/// A convex polygon in a contact plane, counter-clockwise, without repeated or collinear vertices.
///
/// Area, centroid and the length tolerance are computed once at construction; queries only read,
/// but for the mean distance from the centroid and the clearance about it, computed once when
/// first asked (see [`ConvexPolygon::centroid_mean_distance`],
/// [`ConvexPolygon::centroid_clearance`]).
#[derive(Debug)]
pub struct ConvexPolygon {
    vertices: Vertices,
    area: f64,
    centroid: Point2<f64>,
    tolerance: f64,
    pub(crate) centroid_mean_distance: Kept,
    pub(crate) centroid_clearance: Kept,
}

/// Vertices of a polygon, inline up to [`INLINE_VERTICES`].
type Vertices = SmallVec<[Point2<f64>; INLINE_VERTICES]>;

/// Vertices a polygon holds without a heap allocation: a box's contact has at most 8 (two
/// squares' overlap), and a contact's polygon is built, cloned into its constraint and read by
/// every solver sweep, so inline it costs no allocation and no pointer chase.
const INLINE_VERTICES: usize = 8;

/// A copy of the vertices as one block, and of what has been computed and kept. Smallvec's
/// `clone` pushes the vertices one by one through an iterator; a resting pyramid's row
/// building, which clones every face's polygon into its constraint, took 0.8% fewer
/// instructions this way.
impl Clone for ConvexPolygon {
    fn clone(&self) -> Self {
        Self {
            vertices: Vertices::from_slice(&self.vertices),
            area: self.area,
            centroid: self.centroid,
            tolerance: self.tolerance,
            centroid_mean_distance: self.centroid_mean_distance.clone(),
            centroid_clearance: self.centroid_clearance.clone(),
        }
    }
}

/// Polygons are equal when their vertices, area, centroid and tolerance are: whether the mean
/// distance or the clearance has been asked for yet does not matter.
impl PartialEq for ConvexPolygon {
    fn eq(&self, other: &Self) -> bool {
        self.vertices == other.vertices
            && self.area == other.area
            && self.centroid == other.centroid
            && self.tolerance == other.tolerance
    }
}

impl ConvexPolygon {
    /// The convex hull of `points`, counter-clockwise, with repeated and collinear points removed.
    ///
    /// One distinct point gives a [`PolygonKind::Point`], collinear points a
    /// [`PolygonKind::Segment`]. Fails on empty input, a non-finite
    /// coordinate or one beyond [`MAX_COORDINATE`].
    ///
    /// ```
    /// use nalgebra::Point2;
    /// use tatami_geometry::{ConvexPolygon, PolygonKind};
    ///
    /// let edge = ConvexPolygon::from_points(&[
    ///     Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(1.0, 0.0),
    /// ])?;
    /// assert_eq!(edge.kind(), PolygonKind::Segment);
    /// assert_eq!(edge.centroid(), Point2::new(1.0, 0.0));
    /// # Ok::<(), tatami_geometry::GeometryError>(())
    /// ```
    pub fn from_points(points: &[Point2<f64>]) -> Result<Self, GeometryError> {
        if points.is_empty() {
            return Err(GeometryError::NoPoints);
        }
        if let Some((index, p)) = points
            .iter()
            .enumerate()
            .find(|(_, p)| !(p.x.is_finite() && p.y.is_finite()))
        {
            return Err(GeometryError::NonFinitePoint {
                index,
                x: p.x,
                y: p.y,
            });
        }
        if let Some((index, p)) = points
            .iter()
            .enumerate()
            .find(|(_, p)| p.x.abs().max(p.y.abs()) > MAX_COORDINATE)
        {
            return Err(GeometryError::OutOfRange {
                index,
                x: p.x,
                y: p.y,
                max: MAX_COORDINATE,
            });
        }
        let tolerance = length_tolerance(points);
        let vertices = hull(points, tolerance);
        let (area, centroid) = area::area_and_centroid(&vertices);
        Ok(Self {
            vertices,
            area,
            centroid,
            tolerance,
            centroid_mean_distance: Kept::new(),
            centroid_clearance: Kept::new(),
        })
    }

    /// The vertices, counter-clockwise seen from `+z` (the contact normal).
    pub fn vertices(&self) -> &[Point2<f64>] {
        &self.vertices
    }

    /// Enclosed area; zero for a point or a segment.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Area centroid `G`; a segment's midpoint; a point itself. The fan of the sector search and
    /// the face constraint are both centred here.
    pub fn centroid(&self) -> Point2<f64> {
        self.centroid
    }

    /// Whether the polygon is a point, a segment or has area.
    pub fn kind(&self) -> PolygonKind {
        match self.vertices.len() {
            1 => PolygonKind::Point,
            2 => PolygonKind::Segment,
            _ => PolygonKind::Polygon,
        }
    }

    /// Length below which two points are not told apart (and the width of the band in which a
    /// point counts as on the boundary). See [`RELATIVE_TOLERANCE`].
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// Vertex `i` with wrap-around, so edge `i` is `(vertex(i), vertex(i + 1))`.
    pub(crate) fn vertex(&self, i: usize) -> Point2<f64> {
        let n = self.vertices.len();
        // Callers ask for `i + 1` of the last vertex far more often than anything past it: a
        // compare instead of a division in the solver's point location.
        self.vertices[if i < n { i } else { i % n }]
    }
}

/// The index after `i` on a ring of `n` vertices (`i < n`), by a compare instead of a division:
/// rings of a few vertices are walked for every contact and in every solver sweep, where an
/// integer division per step cost more than the step.
///
/// ```
/// use tatami_geometry::polygon::{ring_next, ring_previous};
/// assert_eq!((ring_next(2, 4), ring_next(3, 4)), (3, 0));
/// assert_eq!((ring_previous(0, 4), ring_previous(3, 4)), (3, 2));
/// ```
pub fn ring_next(i: usize, n: usize) -> usize {
    if i + 1 == n { 0 } else { i + 1 }
}

/// The index before `i` on a ring of `n` vertices (`i < n`); see [`ring_next`].
pub fn ring_previous(i: usize, n: usize) -> usize {
    if i == 0 { n - 1 } else { i - 1 }
}

/// The scale-aware length tolerance of a point set: [`RELATIVE_TOLERANCE`] of its bounding-box
/// diagonal plus the rounding of its largest coordinate.
fn length_tolerance(points: &[Point2<f64>]) -> f64 {
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let magnitude = lo.coords.abs().sup(&hi.coords.abs()).max();
    RELATIVE_TOLERANCE * (hi - lo).norm() + ROUNDING_ULPS * magnitude
}

/// The exact hull, then [`simplify`]: every input point ends within `tolerance` of the result.
fn hull(points: &[Point2<f64>], tolerance: f64) -> Vertices {
    simplify(monotone_chain(points), tolerance)
}

/// Inputs of at most this many points are sorted in a buffer on the stack: a box face or a
/// clipped overlap has 4 to 8, and a hull is built three times for every contact every step.
const SORTED_ON_STACK: usize = 16;

/// Andrew's monotone chain keeping strict left turns only, as the floating-point sign says.
fn monotone_chain(points: &[Point2<f64>]) -> Vertices {
    let mut on_stack = [Point2::origin(); SORTED_ON_STACK];
    let mut on_heap = Vec::new();
    let sorted: &mut [Point2<f64>] = if points.len() <= SORTED_ON_STACK {
        let buffer = &mut on_stack[..points.len()];
        buffer.copy_from_slice(points);
        buffer
    } else {
        on_heap.extend_from_slice(points);
        &mut on_heap
    };
    let before = |a: &Point2<f64>, b: &Point2<f64>| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y));
    if sorted.len() <= SORTED_ON_STACK {
        // Insertion sort: stable, as `sort_by`, so the same order, without its set-up.
        for k in 1..sorted.len() {
            let mut j = k;
            while j > 0 && before(&sorted[j - 1], &sorted[j]).is_gt() {
                sorted.swap(j - 1, j);
                j -= 1;
            }
        }
    } else {
        sorted.sort_by(before);
    }
    // Repeated points dropped, in place (what `Vec::dedup` does).
    let mut unique = 0;
    for k in 0..sorted.len() {
        if unique == 0 || sorted[k] != sorted[unique - 1] {
            sorted[unique] = sorted[k];
            unique += 1;
        }
    }
    let sorted = &sorted[..unique];

    // The chain is built in a buffer on the stack too, then copied out once: `Vertices`' pushes
    // and pops check where its storage is on every call, and were half of a box face's chain
    // time. Each point is pushed at most twice (once a pass), so twice the input bounds it.
    let mut chain_on_stack = [Point2::origin(); 2 * SORTED_ON_STACK];
    let mut chain_on_heap = Vec::new();
    let chain: &mut [Point2<f64>] = if sorted.len() <= SORTED_ON_STACK {
        &mut chain_on_stack
    } else {
        chain_on_heap.resize(2 * sorted.len(), Point2::origin());
        &mut chain_on_heap
    };
    let mut len = 0;
    let mut push = |len: &mut usize, floor: usize, p: Point2<f64>| {
        while *len >= floor + 2 && signed_area(&chain[*len - 2], &chain[*len - 1], &p) <= 0.0 {
            *len -= 1;
        }
        chain[*len] = p;
        *len += 1;
    };
    for &p in sorted {
        push(&mut len, 0, p);
    }
    // The upper hull runs back from the lower hull's last point, which stays in place.
    let upper_floor = len - 1;
    for &p in sorted.iter().rev().skip(1) {
        push(&mut len, upper_floor, p);
    }
    if len > 1 {
        len -= 1; // the upper hull ends where the lower began
    }
    Vertices::from_slice(&chain[..len])
}

/// Removes near-repeated and near-collinear vertices of an exact hull `ring`, smallest deviation
/// first. A vertex goes only if every vertex of the *original* ring between its neighbours lies
/// within `tolerance` of the chord joining them, so removals never compound: the result is within
/// `tolerance` of every input point. A ring whose every vertex is within `tolerance` of one of
/// them becomes that point.
///
/// Decision record: tolerant turn tests inside the monotone chain were rejected because a point
/// dropped against one chord can end several tolerances outside the next.
fn simplify(ring: Vertices, tolerance: f64) -> Vertices {
    let n = ring.len();
    if n <= 1 {
        return ring;
    }
    // Largest distance of the original vertices strictly between `a` and `c` (cyclically) from
    // the segment `a c`.
    let deviation = |a: usize, c: usize| -> f64 {
        let (pa, pc) = (ring[a], ring[c]);
        (1..(c + n - a) % n)
            .map(|k| {
                let p = ring[(a + k) % n];
                (closest_point_on_segment(&pa, &pc, &p) - p).norm()
            })
            .fold(0.0, f64::max)
    };
    let cost_of = |i: usize| deviation(ring_previous(i, n), ring_next(i, n));
    // Most rings have nothing to remove (a box face, a clipped overlap): return them as they
    // are, without the bookkeeping below. A vertex's cost is then its own distance from its
    // neighbours' chord, found without `deviation`'s index divisions (which were most of a box
    // face's hull time). A vertex farther than twice the tolerance from the chord's line, by
    // the cross product, is farther than the tolerance from the chord, found without a
    // division or a square root: the factor of two covers the cross product's rounding, a few
    // ulps of the points' spread (under the tolerance's 1e-9 of it) and of their coordinates
    // (under its 8 ulps).
    let bent = |i: usize| {
        let before = ring[ring_previous(i, n)];
        let after = ring[ring_next(i, n)];
        let (p, chord) = (ring[i], after - before);
        let cross = chord.perp(&(p - before));
        cross * cross > 4.0 * tolerance * tolerance * chord.norm_squared()
            || (closest_point_on_segment(&before, &after, &p) - p).norm() > tolerance
    };
    if n > 2 && (0..n).all(bent) {
        return ring;
    }
    // Inline for the rings of a contact (a box pair's are at most 8): rings with a vertex to
    // drop are common on a pile of cubes, and heap buffers here took a seventh of its hulls'
    // time.
    let mut kept: SmallVec<[usize; SORTED_ON_STACK]> = (0..n).collect();
    let mut cost: SmallVec<[f64; SORTED_ON_STACK]> = (0..n).map(cost_of).collect();
    while kept.len() > 2 {
        let (slot, &worst) = cost
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(y.1))
            .expect("more than two vertices are kept");
        if worst > tolerance {
            break;
        }
        kept.remove(slot);
        cost.remove(slot);
        let k = kept.len();
        for s in [(slot + k - 1) % k, slot % k] {
            cost[s] = if k <= 2 {
                0.0 // a segment's ends are judged below
            } else {
                deviation(kept[(s + k - 1) % k], kept[(s + 1) % k])
            };
        }
    }
    if kept.len() == 2 {
        let within_of = |end: usize| ring.iter().all(|p| (p - ring[end]).norm() <= tolerance);
        if let Some(&end) = kept.iter().find(|&&end| within_of(end)) {
            kept.clear();
            kept.push(end);
        }
    }
    kept.into_iter().map(|i| ring[i]).collect()
}
