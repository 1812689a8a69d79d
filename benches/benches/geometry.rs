//! Fan-sector search (O(log n)) against the brute-force O(n) queries, at n = 4, 8, 64, 1024.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Point2;
use std::hint::black_box;
use tatami_benches::{regular_polygon, spiral_queries};
use tatami_geometry::{ConvexPolygon, brute_force};

const SIZES: [usize; 4] = [4, 8, 64, 1024];
const QUERIES: usize = 256;

/// A query reduced to a number, so both forms do the same work on their answer.
type Query = fn(&ConvexPolygon, &Point2<f64>) -> f64;

/// Benchmarks `fan_search` and `brute_force` forms of one query over the spiral queries.
fn compare(c: &mut Criterion, name: &str, fan_search: Query, brute: Query) {
    let mut group = c.benchmark_group(name);
    group.throughput(Throughput::Elements(QUERIES as u64));
    let queries = spiral_queries(QUERIES, 1.0);
    for n in SIZES {
        let polygon = regular_polygon(n, 1.0);
        for (label, query) in [("fan_search", fan_search), ("brute_force", brute)] {
            group.bench_with_input(BenchmarkId::new(label, n), &n, |b, _| {
                b.iter(|| {
                    queries
                        .iter()
                        .map(|p| query(&polygon, black_box(p)))
                        .sum::<f64>()
                })
            });
        }
    }
    group.finish();
}

fn contains(c: &mut Criterion) {
    compare(
        c,
        "contains",
        |polygon, p| f64::from(u8::from(polygon.contains(p))),
        |polygon, p| f64::from(u8::from(brute_force::contains(polygon, p))),
    );
}

fn nearest_point(c: &mut Criterion) {
    compare(
        c,
        "nearest_point",
        |polygon, p| polygon.nearest_point(p).x,
        |polygon, p| brute_force::nearest_point(polygon, p).x,
    );
}

criterion_group!(benches, contains, nearest_point);
criterion_main!(benches);
