//! Solver-layer benchmarks: PGS throughput on a chain of 6-row blocks, Lemke time against size,
//! and faer against nalgebra for the dense LU that polishes Lemke's answer.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use faer::linalg::solvers::Solve;
use std::hint::black_box;
use tatami_benches::{chain_problem, spd_lcp};
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};

fn pgs_throughput(c: &mut Criterion) {
    let mut group = c.benchmark_group("pgs_chain");
    let params = PgsParams::default();
    for blocks in [1, 10, 100, 1_000, 10_000] {
        let template = chain_problem(blocks);
        group.throughput(Throughput::Elements(
            (template.rows.len() * params.iterations) as u64,
        ));
        let mut workspace = PgsWorkspace::default();
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &blocks, |b, _| {
            b.iter_batched_ref(
                || template.clone(),
                |problem| pgs::solve_in_place(black_box(problem), &mut workspace, &params).unwrap(),
                criterion::BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

fn lemke_size(c: &mut Criterion) {
    let mut group = c.benchmark_group("lemke_spd");
    group.sample_size(10);
    for n in [6, 24, 96, 192] {
        let (a, q) = spd_lcp(n, 7);
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| tatami_lcp::lemke(black_box(&a), black_box(&q), 100 * n).unwrap())
        });
    }
    group.finish();
}

fn dense_lu(c: &mut Criterion) {
    let mut group = c.benchmark_group("lu_solve");
    group.sample_size(10);
    for n in [6, 24, 96, 384, 1536] {
        let (a, q) = spd_lcp(n, 11);
        let a_faer = faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)]);
        let q_faer = faer::Mat::<f64>::from_fn(n, 1, |i, _| q[i]);
        group.bench_with_input(BenchmarkId::new("faer", n), &n, |b, _| {
            b.iter(|| {
                black_box(&a_faer)
                    .partial_piv_lu()
                    .solve(black_box(&q_faer))
            })
        });
        group.bench_with_input(BenchmarkId::new("nalgebra", n), &n, |b, _| {
            b.iter(|| black_box(&a).clone().lu().solve(black_box(&q)))
        });
    }
    group.finish();
}

criterion_group!(benches, pgs_throughput, lemke_size, dense_lu);
criterion_main!(benches);
