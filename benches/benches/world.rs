//! One world step and the solver call alone, per contact model: towers of 10, 100 and 1000
//! cubes and a planar pyramid with a base of 20 (210 cubes).
//!
//! Every iteration starts from the same state (a clone of the settled-in world, not timed), so
//! a tower that falls apart during the measurement cannot change what is measured.

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use tatami_benches::{pyramid_centres, tatami_cubes, tower_centres};
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
use tatami_world::{ContactModel, World, WorldSettings};

const DT: f64 = 0.01;

/// The world under `model` with Tatami's default solver (15 PGS sweeps, warm-started), after
/// one step so contacts exist.
fn settled(centres: &[[f64; 3]], model: ContactModel) -> World {
    let settings = WorldSettings {
        model,
        ..WorldSettings::default()
    };
    let mut world = tatami_cubes(centres, settings);
    world.step(DT).expect("a tower steps");
    world
}

fn scenes() -> Vec<(String, Vec<[f64; 3]>)> {
    let mut scenes: Vec<(String, Vec<[f64; 3]>)> = [10, 100, 1000]
        .iter()
        .map(|&n| (format!("tower_{n}"), tower_centres(n)))
        .collect();
    scenes.push(("pyramid_20".to_owned(), pyramid_centres(20)));
    scenes
}

fn world_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("world_step");
    group.sample_size(10);
    for (name, centres) in scenes() {
        group.throughput(Throughput::Elements(centres.len() as u64));
        for model in ContactModel::ALL {
            let world = settled(&centres, model);
            group.bench_with_input(BenchmarkId::new(model.name(), &name), &world, |b, w| {
                b.iter_batched_ref(
                    || w.clone(),
                    |w| w.step(DT).expect("a tower steps"),
                    BatchSize::LargeInput,
                )
            });
        }
    }
    group.finish();
}

fn solver_call(c: &mut Criterion) {
    let mut group = c.benchmark_group("solver_call");
    group.sample_size(20);
    for (name, centres) in scenes() {
        for model in ContactModel::ALL {
            let mut world = settled(&centres, model);
            let problem = world.prepare_step(DT).expect("a tower steps").clone();
            let params = PgsParams::default();
            let mut workspace = PgsWorkspace::default();
            group.throughput(Throughput::Elements(
                (problem.rows.len() * params.iterations) as u64,
            ));
            group.bench_with_input(BenchmarkId::new(model.name(), &name), &problem, |b, p| {
                b.iter_batched_ref(
                    || p.clone(),
                    |p| pgs::solve_in_place(p, &mut workspace, &params),
                    BatchSize::LargeInput,
                )
            });
        }
    }
    group.finish();
}

criterion_group!(benches, world_step, solver_call);
criterion_main!(benches);
