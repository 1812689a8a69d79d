//! Fan-sector search (O(log n)) against the brute-force O(n) queries, at n = 4, 8, 64, 1024.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use tatami_benches::{regular_polygon, spiral_queries};
use tatami_geometry::brute_force;

const SIZES: [usize; 4] = [4, 8, 64, 1024];
const QUERIES: usize = 256;

fn contains(c: &mut Criterion) {
    let mut group = c.benchmark_group("contains");
    group.throughput(Throughput::Elements(QUERIES as u64));
    for n in SIZES {
        let polygon = regular_polygon(n, 1.0);
        let queries = spiral_queries(QUERIES, 1.0);
        group.bench_with_input(BenchmarkId::new("fan_search", n), &n, |b, _| {
            b.iter(|| {
                queries
                    .iter()
                    .filter(|p| polygon.contains(black_box(p)))
                    .count()
            })
        });
        group.bench_with_input(BenchmarkId::new("brute_force", n), &n, |b, _| {
            b.iter(|| {
                queries
                    .iter()
                    .filter(|p| brute_force::contains(&polygon, black_box(p)))
                    .count()
            })
        });
    }
    group.finish();
}

fn nearest_point(c: &mut Criterion) {
    let mut group = c.benchmark_group("nearest_point");
    group.throughput(Throughput::Elements(QUERIES as u64));
    for n in SIZES {
        let polygon = regular_polygon(n, 1.0);
        let queries = spiral_queries(QUERIES, 1.0);
        group.bench_with_input(BenchmarkId::new("fan_search", n), &n, |b, _| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|p| polygon.nearest_point(black_box(p)).x)
                    .sum::<f64>()
            })
        });
        group.bench_with_input(BenchmarkId::new("brute_force", n), &n, |b, _| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|p| brute_force::nearest_point(&polygon, black_box(p)).x)
                    .sum::<f64>()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, contains, nearest_point);
criterion_main!(benches);
