//! Property tests: the fast paths against brute force, over random convex polygons of 1–64
//! vertices at scales from 1e-3 to 1e3, offsets up to 1e6, slivers 1e-6 thin, and input padded
//! with repeated and collinear points.

use nalgebra::{Point2, Rotation2, Vector2};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use tatami_geometry::{ConvexPolygon, PolygonKind, Sector, brute_force, signed_area};

/// A random convex polygon: `n` points on a rotated, squashed circle, plus the raw input with
/// repeats and edge midpoints mixed in.
#[derive(Debug, Clone)]
struct Case {
    points: Vec<Point2<f64>>,
    padded: Vec<Point2<f64>>,
}

fn polygon_case() -> impl Strategy<Value = Case> {
    (
        1usize..=64,
        prop::sample::select(vec![0.0, 1.0, 1e3, 1e6]),
        prop::sample::select(vec![1e-3, 1.0, 1e3]),
        prop::sample::select(vec![1.0, 0.3, 1e-6]),
        0.0..std::f64::consts::TAU,
        any::<u64>(),
    )
        .prop_flat_map(|(n, offset, size, thinness, turn, seed)| {
            (
                prop::collection::vec(0.0..std::f64::consts::TAU, n),
                (-1.0..1.0f64, -1.0..1.0f64),
                Just((offset, size, thinness, turn, seed)),
            )
        })
        .prop_map(|(angles, (ox, oy), (offset, size, thinness, turn, seed))| {
            let rotation = Rotation2::new(turn);
            let centre = Vector2::new(ox, oy) * offset;
            let points: Vec<_> = angles
                .iter()
                .map(|t| {
                    Point2::from(
                        rotation * Vector2::new(size * t.cos(), size * thinness * t.sin()) + centre,
                    )
                })
                .collect();
            let mut padded = points.clone();
            for (k, p) in points.iter().enumerate() {
                let q = points[(k * 7 + 3) % points.len()];
                padded.push(*p); // repeated
                padded.push(nalgebra::center(p, &q)); // inside or on an edge of the hull
            }
            // A deterministic shuffle: the hull must not depend on input order.
            let mut state = seed | 1;
            for i in (1..padded.len()).rev() {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                padded.swap(i, (state % (i as u64 + 1)) as usize);
            }
            Case { points, padded }
        })
}

/// Query points: uniform in a box three times the polygon's, its vertices, points on its edges,
/// and far away.
fn queries(polygon: &ConvexPolygon, unit: &[(f64, f64)]) -> Vec<Point2<f64>> {
    let (lo, hi) = polygon.bounding_box();
    let centre = nalgebra::center(&lo, &hi);
    let half = (hi - lo) * 1.5 + Vector2::repeat(polygon.tolerance());
    let v = polygon.vertices();
    let mut out: Vec<_> = unit
        .iter()
        .map(|&(u, w)| centre + Vector2::new(u * half.x, w * half.y))
        .collect();
    for (k, &(u, _)) in unit.iter().enumerate() {
        let (a, b) = (v[k % v.len()], v[(k + 1) % v.len()]);
        out.push(a);
        out.push(a + (b - a) * (0.5 + 0.5 * u));
        let far = 1e3 * (hi - lo).norm().max(1.0);
        out.push(centre + Vector2::new(u, 1.0 - u.abs()).normalize() * far);
    }
    out
}

/// The magnitude that rounding is relative to: the largest coordinate or length in play.
fn scale(polygon: &ConvexPolygon, p: &Point2<f64>) -> f64 {
    let (lo, hi) = polygon.bounding_box();
    p.coords
        .amax()
        .max(lo.coords.amax())
        .max(hi.coords.amax())
        .max((hi - lo).norm())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 512,
        // Degenerate cases are assumed away by a few properties: about one in ten.
        max_global_rejects: 1 << 16,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct("proptest-regressions/properties.txt"))),
        ..ProptestConfig::default()
    })]

    /// The clearance of a point is its distance to the boundary by brute force when inside and
    /// 0 outside, and every point of the disc it spans is inside.
    #[test]
    fn clearance_is_the_distance_to_the_boundary(
        case in polygon_case(),
        unit in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 8),
    ) {
        let polygon = ConvexPolygon::from_points(&case.points).unwrap();
        let mut points = queries(&polygon, &unit);
        points.push(polygon.centroid());
        for p in &points {
            let clearance = polygon.clearance(p);
            let rounding = 1e-9 * scale(&polygon, p);
            if polygon.kind() != PolygonKind::Polygon || !brute_force::contains(&polygon, p) {
                prop_assert!(clearance <= polygon.tolerance(), "outside, clearance {}", clearance);
                continue;
            }
            let boundary = (brute_force::nearest_on_boundary(&polygon, p) - p).norm();
            prop_assert!((clearance - boundary).abs() <= rounding,
                "clearance {} against {} by brute force", clearance, boundary);
            for &(u, w) in &unit {
                let direction = Vector2::new(u, w).try_normalize(0.0).unwrap_or(Vector2::x());
                let q = p + direction * clearance * (1.0 - 1e-12);
                prop_assert!(brute_force::contains(&polygon, &q), "{:?} left the polygon", q);
            }
        }
    }

    #[test]
    fn hull_is_convex_ccw_and_holds_every_input_point(case in polygon_case()) {
        let polygon = ConvexPolygon::from_points(&case.points).unwrap();
        let v = polygon.vertices();
        if v.len() >= 3 {
            for i in 0..v.len() {
                let turn = signed_area(&v[i], &v[(i + 1) % v.len()], &v[(i + 2) % v.len()]);
                prop_assert!(turn > 0.0, "vertex {} does not turn left ({})", i + 1, turn);
            }
            prop_assert!(polygon.area() > 0.0);
        }
        // Simplification keeps every point within the tolerance; the distance here is evaluated
        // along a different rounding than the one that decided, hence the factor 2.
        for p in &case.points {
            let gap = (brute_force::nearest_point(&polygon, p) - p).norm();
            prop_assert!(gap <= 2.0 * polygon.tolerance(), "input point {:?} left out by {}", p, gap);
        }
    }

    #[test]
    fn repeated_and_collinear_points_do_not_change_the_hull(case in polygon_case()) {
        let plain = ConvexPolygon::from_points(&case.points).unwrap();
        let padded = ConvexPolygon::from_points(&case.padded).unwrap();
        // Each hull is within its tolerance of the other's points (up to rounding, factor 2).
        for (a, b) in [(&plain, &padded), (&padded, &plain)] {
            let tol = 2.0 * a.tolerance().max(b.tolerance());
            for v in a.vertices() {
                let gap = (brute_force::nearest_point(b, v) - v).norm();
                prop_assert!(gap <= tol, "vertex {:?} is {} from the other hull", v, gap);
            }
        }
        // Where every vertex stands clear of its neighbours' chord, no vertex may be lost or
        // gained: padding only added repeats and points inside.
        let v = plain.vertices();
        let robust = v.len() >= 3 && (0..v.len()).all(|i| {
            let (a, b, c) = (v[i], v[(i + 1) % v.len()], v[(i + 2) % v.len()]);
            2.0 * signed_area(&a, &b, &c) / (c - a).norm() > 16.0 * plain.tolerance()
        });
        if robust {
            prop_assert_eq!(plain.vertices().len(), padded.vertices().len());
        }
    }

    #[test]
    fn contains_agrees_with_half_planes_away_from_the_boundary(
        case in polygon_case(),
        unit in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 16),
    ) {
        let polygon = ConvexPolygon::from_points(&case.padded).unwrap();
        // Within a few tolerances of the boundary the two tests may round differently; well inside
        // the tolerance (vertices, points on edges) the boundary must count as inside.
        let band = 4.0 * polygon.tolerance();
        for p in queries(&polygon, &unit) {
            let to_boundary = (brute_force::nearest_on_boundary(&polygon, &p) - p).norm();
            if to_boundary > band {
                prop_assert_eq!(polygon.contains(&p), brute_force::contains(&polygon, &p), "at {:?}", p);
            } else if to_boundary <= 0.5 * polygon.tolerance() {
                prop_assert!(polygon.contains(&p), "boundary point {:?} counted outside", p);
            }
        }
    }

    #[test]
    fn nearest_point_matches_brute_force_and_lies_in_the_polygon(
        case in polygon_case(),
        unit in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 16),
    ) {
        let polygon = ConvexPolygon::from_points(&case.padded).unwrap();
        for p in queries(&polygon, &unit) {
            let fast = polygon.nearest_point(&p);
            let brute = brute_force::nearest_point(&polygon, &p);
            // 1e-12 of the magnitudes involved, plus the boundary band in which a point counts as
            // on the polygon (its own nearest point) for one test and just outside for the other.
            let allowed = 1e-12 * scale(&polygon, &p) + polygon.tolerance();
            let (d_fast, d_brute) = ((fast - p).norm(), (brute - p).norm());
            prop_assert!((d_fast - d_brute).abs() <= allowed,
                "at {:?}: fast {} vs brute {} (allowed {})", p, d_fast, d_brute, allowed);
            prop_assert!(polygon.contains(&fast), "nearest point {:?} of {:?} is outside", fast, p);
            prop_assert_eq!(polygon.nearest_point(&fast), fast);
        }
    }

    #[test]
    fn sector_hint_gives_the_same_answer(
        case in polygon_case(),
        unit in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 16),
        hint in 0usize..80,
    ) {
        let polygon = ConvexPolygon::from_points(&case.padded).unwrap();
        let mut sector = Sector(hint);
        for p in queries(&polygon, &unit) {
            let (nearest, found) = polygon.nearest_point_from(&p, sector);
            prop_assert_eq!(nearest, polygon.nearest_point(&p));
            prop_assert_eq!(polygon.locate_from(&p, found), polygon.locate(&p));
            sector = found;
        }
    }

    #[test]
    fn mean_distance_is_invariant_under_rigid_motion(
        case in polygon_case(),
        turn in 0.0..std::f64::consts::TAU,
        shift in (-1e3..1e3f64, -1e3..1e3f64),
        (u, w) in (-1.0..1.0f64, -1.0..1.0f64),
    ) {
        let polygon = ConvexPolygon::from_points(&case.points).unwrap();
        prop_assume!(polygon.kind() == PolygonKind::Polygon);
        let motion = |p: &Point2<f64>| Point2::from(Rotation2::new(turn) * p.coords + Vector2::new(shift.0, shift.1));
        let moved: Vec<_> = polygon.vertices().iter().map(motion).collect();
        let moved = ConvexPolygon::from_points(&moved).unwrap();
        // A sliver as thin as the tolerance may lose a vertex to rounding when moved; r̄ of a
        // different hull is not the claim here.
        prop_assume!(moved.vertices().len() == polygon.vertices().len());
        let (lo, hi) = polygon.bounding_box();
        let c = polygon.centroid() + Vector2::new(u * (hi - lo).x, w * (hi - lo).y);
        let (before, after) = (polygon.mean_distance(&c), moved.mean_distance(&motion(&c)));
        // Moving rounds each vertex by a few ε·scale; for a polygon of width w = 2A/diameter
        // that changes the area, and so r̄, by up to that much relative to w.
        let magnitude = scale(&polygon, &c).max(scale(&moved, &motion(&c)));
        let width = 2.0 * polygon.area() / (hi - lo).norm();
        let allowed = 1e-12 * magnitude + before * 64.0 * f64::EPSILON * magnitude / width;
        prop_assert!((before - after).abs() <= allowed, "{} vs {}", before, after);
    }

    /// The kept mean distance from the centroid is the one computed afresh, to the bit, for
    /// every kind of polygon; a copy made before it was asked for still equals the polygon,
    /// and a copy made after carries the same value.
    #[test]
    fn the_kept_centroid_mean_distance_is_the_computed_one(case in polygon_case()) {
        let polygon = ConvexPolygon::from_points(&case.padded).unwrap();
        let before = polygon.clone();
        let kept = polygon.centroid_mean_distance();
        prop_assert_eq!(kept.to_bits(), polygon.mean_distance(&polygon.centroid()).to_bits());
        prop_assert_eq!(polygon.centroid_mean_distance().to_bits(), kept.to_bits());
        prop_assert!(before == polygon);
        prop_assert_eq!(polygon.clone().centroid_mean_distance().to_bits(), kept.to_bits());
    }

    /// The kept clearance about the centroid is the one computed afresh, to the bit, for every
    /// kind of polygon, in the polygon and in copies made before and after it was asked for.
    #[test]
    fn the_kept_centroid_clearance_is_the_computed_one(case in polygon_case()) {
        let polygon = ConvexPolygon::from_points(&case.padded).unwrap();
        let before = polygon.clone();
        let computed = polygon.clearance(&polygon.centroid());
        let kept = polygon.centroid_clearance();
        prop_assert_eq!(kept.to_bits(), computed.to_bits());
        prop_assert_eq!(polygon.centroid_clearance().to_bits(), kept.to_bits());
        prop_assert_eq!(polygon.clone().centroid_clearance().to_bits(), kept.to_bits());
        prop_assert_eq!(before.centroid_clearance().to_bits(), kept.to_bits());
        prop_assert!(before == polygon);
    }
}
