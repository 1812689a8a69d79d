//! Named degenerate supports: corner contacts (a point), edge contacts (a segment), bad input.

use nalgebra::Point2;
use tatami_geometry::{ConvexPolygon, GeometryError, PolygonKind};

#[test]
fn empty_input_is_an_error() {
    assert_eq!(
        ConvexPolygon::from_points(&[]),
        Err(GeometryError::NoPoints)
    );
}

#[test]
fn non_finite_coordinate_is_an_error_naming_the_point() {
    let err = ConvexPolygon::from_points(&[Point2::new(0.0, 0.0), Point2::new(f64::NAN, 1.0)])
        .unwrap_err();
    assert!(
        matches!(err, GeometryError::NonFinitePoint { index: 1, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("point 1"));
}

#[test]
fn coincident_points_make_a_point() {
    let p = Point2::new(1.0, -2.0);
    let point = ConvexPolygon::from_points(&[p, p, Point2::new(1.0 + 1e-15, -2.0)]).unwrap();
    assert_eq!(point.kind(), PolygonKind::Point);
    assert_eq!(point.centroid(), p);
    assert_eq!(point.area(), 0.0);
    assert!(point.contains(&p));
    assert!(!point.contains(&Point2::new(1.0, -1.9)));
    assert_eq!(point.nearest_point(&Point2::new(5.0, 5.0)), p);
    assert_eq!(point.mean_distance(&Point2::new(4.0, 2.0)), 5.0);
}

#[test]
fn collinear_points_make_a_segment_between_the_extremes() {
    let pts: Vec<_> = [3.0, -1.0, 0.5, 2.0, 3.0]
        .iter()
        .map(|&t| Point2::new(t, 2.0 * t))
        .collect();
    let segment = ConvexPolygon::from_points(&pts).unwrap();
    assert_eq!(segment.kind(), PolygonKind::Segment);
    let v = segment.vertices();
    assert!(v.contains(&Point2::new(-1.0, -2.0)) && v.contains(&Point2::new(3.0, 6.0)));
    assert_eq!(segment.centroid(), Point2::new(1.0, 2.0));
    assert!(segment.contains(&Point2::new(2.0, 4.0)));
    assert!(!segment.contains(&Point2::new(2.0, 4.1)));
    // The foot of the perpendicular from (2, -1) onto the line y = 2x is the origin.
    let foot = segment.nearest_point(&Point2::new(2.0, -1.0));
    assert!((foot - Point2::origin()).norm() < 1e-15);
    // Beyond an end: the end.
    assert_eq!(
        segment.nearest_point(&Point2::new(10.0, 10.0)),
        Point2::new(3.0, 6.0)
    );
}

#[test]
fn segment_mean_distance_from_its_midpoint_is_a_quarter_of_its_length() {
    let segment =
        ConvexPolygon::from_points(&[Point2::new(-2.0, 0.0), Point2::new(2.0, 0.0)]).unwrap();
    assert!((segment.mean_distance(&Point2::origin()) - 1.0).abs() < 1e-15);
    // From a point at height d above the midpoint: (1/L)∫√(d² + s²) ds over [−L/2, L/2]
    // = (1/L)[s r + d² asinh(s/d)] at s = L/2, for L = 4, d = 2.
    let d: f64 = 2.0;
    let expected = (2.0 * 8f64.sqrt() + d * d * (1.0f64).asinh()) / 4.0;
    assert!((segment.mean_distance(&Point2::new(0.0, d)) - expected).abs() < 1e-14);
}

#[test]
fn a_sliver_a_millionth_thin_stays_a_polygon() {
    let sliver = ConvexPolygon::from_points(&[
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.5, 1e-6),
    ])
    .unwrap();
    assert_eq!(sliver.kind(), PolygonKind::Polygon);
    assert!((sliver.area() - 0.5e-6).abs() < 1e-18);
    assert!(sliver.contains(&sliver.centroid()));
    assert!(!sliver.contains(&Point2::new(0.5, 2e-6)));
}

#[test]
fn box_on_box_twisted_45_degrees_keeps_all_eight_corners() {
    // The overlap of two unit squares, one turned by 45°, is a regular octagon.
    let mut pts = Vec::new();
    for k in 0..8 {
        let t = std::f64::consts::FRAC_PI_8 + k as f64 * std::f64::consts::FRAC_PI_4;
        let r = 0.5 / std::f64::consts::FRAC_PI_8.cos();
        pts.push(Point2::new(r * t.cos(), r * t.sin()));
    }
    let octagon = ConvexPolygon::from_points(&pts).unwrap();
    assert_eq!(octagon.vertices().len(), 8);
}

/// Coordinates of 1e200 overflowed the centroid's cubic terms to a NaN centroid; beyond
/// [`MAX_COORDINATE`] a polygon is refused, naming the point, and at the limit it is exact.
#[test]
fn coordinates_beyond_the_limit_are_refused() {
    use tatami_geometry::MAX_COORDINATE;
    let big = 1e200;
    let error = ConvexPolygon::from_points(&[
        Point2::new(0.0, 0.0),
        Point2::new(big, 0.0),
        Point2::new(0.0, big),
    ])
    .unwrap_err();
    assert!(
        matches!(error, GeometryError::OutOfRange { index: 1, .. }),
        "{error}"
    );
    let m = MAX_COORDINATE;
    let square = ConvexPolygon::from_points(&[
        Point2::new(-m, -m),
        Point2::new(m, -m),
        Point2::new(m, m),
        Point2::new(-m, m),
    ])
    .unwrap();
    assert_eq!(square.area(), 4.0 * m * m);
    assert_eq!(square.centroid(), Point2::origin());
    let r = square.mean_distance(&Point2::new(m, m));
    assert!(r.is_finite() && r > m, "{r}");
}

/// A segment whose end is a subnormal 2e-322 off the line through the query point: `d²`
/// underflowed to 0 while `s/d` overflowed to ∞, and `r̄` was NaN (found by fuzzing). The mean
/// distance from one end of a segment of length L is L/2.
#[test]
fn mean_distance_off_a_segment_by_a_subnormal_is_finite() {
    let segment =
        ConvexPolygon::from_points(&[Point2::new(-10.0, 2.37e-322), Point2::new(0.0, 0.0)])
            .unwrap();
    assert_eq!(segment.kind(), PolygonKind::Segment);
    let r = segment.mean_distance(&Point2::origin());
    assert!((r - 5.0).abs() < 1e-12, "{r}");
}

/// A fan triangle from a query point 7.5e-301 off an edge's line: `d³` underflowed to 0 while
/// the logarithm's ratio overflowed, and `r̄` was NaN (found by fuzzing). The triangle is a
/// needle along x (0.34 m high, 1.8e8 m long), so `r̄` is the mean of its triangular width
/// profile, (a + b + m)/3 over its x extent [a, b] and apex m; the part at x < 0 is 1e-8 of it.
#[test]
fn mean_distance_from_a_point_a_subnormal_off_an_edge_is_finite() {
    let polygon = ConvexPolygon::from_points(&[
        Point2::new(-75686.27450980392, 7.540703440909437e-301),
        Point2::new(94712748.91279468, 0.3373464560921645),
        Point2::new(180056458.38101777, -0.0),
    ])
    .unwrap();
    let c = Point2::origin();
    let exact = polygon.mean_distance(&c);
    let profile = (-75686.27450980392 + 180056458.38101777 + 94712748.91279468) / 3.0;
    assert!(
        (exact - profile).abs() < 1e-6 * profile,
        "{exact} vs {profile}"
    );
}

/// A needle 72 km long and 0.9 m wide, seen from its centroid 24 km away: the rays through two
/// vertices are parallel to rounding, and the fan search put the point (0, 0), 0.11 m beyond
/// the vertex (−0.11, 0), inside (found by fuzzing). Location and nearest point now agree with
/// brute force.
#[test]
fn a_point_just_beyond_a_needle_is_outside() {
    let needle = ConvexPolygon::from_points(&[
        Point2::new(-72549.01960784313, 0.4985732814526589),
        Point2::new(-0.1610360875867857, -0.3627450980392157),
        Point2::new(-0.10981918059052415, 0.0),
    ])
    .unwrap();
    let p = Point2::origin();
    assert!(!tatami_geometry::brute_force::contains(&needle, &p));
    assert!(!needle.contains(&p));
    let nearest = needle.nearest_point(&p);
    let reference = tatami_geometry::brute_force::nearest_point(&needle, &p);
    assert!(
        (nearest - reference).norm() < 1e-9,
        "{nearest} vs {reference}"
    );
}
