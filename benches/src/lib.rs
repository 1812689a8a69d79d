//! Inputs shared by the Criterion benchmarks in `benches/benches/`.
//!
//! Each bench target builds its scenes from here so that every benchmark of a concept measures
//! the same input.

use nalgebra::Point2;
use tatami_geometry::ConvexPolygon;

/// A regular `n`-gon of circumradius `radius` centred at the origin, first vertex on `+x`.
pub fn regular_polygon(n: usize, radius: f64) -> ConvexPolygon {
    let points: Vec<_> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            Point2::new(radius * t.cos(), radius * t.sin())
        })
        .collect();
    ConvexPolygon::from_points(&points).expect("a regular polygon has finite vertices")
}

/// `count` query points on a spiral from the centre to twice `radius`: half inside a polygon of
/// that circumradius, half outside, at every angle, so no branch is favoured.
pub fn spiral_queries(count: usize, radius: f64) -> Vec<Point2<f64>> {
    (0..count)
        .map(|k| {
            let s = (k as f64 + 0.5) / count as f64;
            let t = 97.0 * std::f64::consts::TAU * s; // many turns, incommensurate with n
            Point2::new(2.0 * radius * s * t.cos(), 2.0 * radius * s * t.sin())
        })
        .collect()
}
