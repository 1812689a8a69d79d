//! The support-polygon entry points: hull, area, centroid, fan-sector search, nearest point
//! and mean distance, on points from anywhere in f64.

use nalgebra::Point2;
use tatami_geometry::{ConvexPolygon, MAX_COORDINATE, brute_force};

use crate::bytes::Bytes;

/// Builds a polygon of up to 12 points and queries it at a point.
pub fn geometry(data: &[u8]) {
    let mut bytes = Bytes::new(data);
    let count = bytes.below(13);
    let points: Vec<_> = (0..count)
        .map(|_| Point2::new(bytes.number(), bytes.number()))
        .collect();
    let Ok(polygon) = ConvexPolygon::from_points(&points) else {
        return;
    };
    let finite = |p: &Point2<f64>| p.x.is_finite() && p.y.is_finite();
    assert!(polygon.vertices().iter().all(finite));
    assert!(polygon.area().is_finite() && polygon.area() >= 0.0);
    assert!(finite(&polygon.centroid()), "{points:?}");

    let query = Point2::new(bytes.number(), bytes.number());
    let inside = polygon.contains(&query);
    if !(finite(&query) && query.x.abs() <= MAX_COORDINATE && query.y.abs() <= MAX_COORDINATE) {
        return;
    }
    let nearest = polygon.nearest_point(&query);
    assert!(finite(&nearest), "{points:?} {query}");
    if inside {
        assert_eq!(nearest, query, "a point inside is its own nearest point");
    }
    // The fan search's nearest point is in the polygon and no farther than brute force's, to
    // the polygon's tolerance (on a nearly straight edge seen from afar, points 1e-3 apart are
    // at distances equal to rounding, so the points themselves are not compared).
    let reference = brute_force::nearest_point(&polygon, &query);
    let slack = 10.0 * polygon.tolerance() + 1e-9 * (query - reference).norm();
    assert!(
        (query - nearest).norm() <= (query - reference).norm() + slack,
        "{points:?} {query}: {nearest} farther than {reference}"
    );
    let back = brute_force::nearest_point(&polygon, &nearest);
    assert!(
        (back - nearest).norm() <= slack,
        "{points:?} {query}: {nearest} is outside"
    );
    let r = polygon.mean_distance(&query);
    assert!(r.is_finite() && r >= 0.0, "{points:?} {query}: r̄ = {r}");
    // The grid form is capped in samples; keep it to spacings the fuzzer can afford.
    let (low, high) = polygon.bounding_box();
    let extent = (high - low).amax();
    let spacing = bytes.number();
    if spacing.is_nan() || spacing >= extent / 64.0 {
        let _ = polygon.try_mean_distance_grid(&query, spacing);
    }
}
