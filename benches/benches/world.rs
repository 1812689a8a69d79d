//! One world step and the solver call alone, per contact model: towers of 10, 100 and 1000
//! cubes and a planar pyramid with a base of 20 (210 cubes). Then several worlds stepped one
//! after another against all at once on rayon's pool, as simulations run side by side are.
//!
//! Every iteration starts from the same state (a clone of the settled-in world, not timed), so
//! a tower that falls apart during the measurement cannot change what is measured.

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::UnitQuaternion;
use rayon::prelude::*;
use tatami_benches::{pyramid_centres, tatami_cubes, tower_centres};
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
use tatami_world::dropped::Random;
use tatami_world::{BodyDesc, ContactModel, Shape, World, WorldSettings};

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

/// 200 cubes of 1 m dropped in eight layers of 25, turned at random (seeded by `seed`), after
/// 45 steps: landing, with hundreds of fresh pairs a step, so collision and rows run on every
/// core and the position pass beside the velocity solve.
fn landing_pile(seed: u64) -> World {
    let mut random = Random::new(seed);
    let floor = BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).position([0.0, 0.0, -1.0]);
    let mut builder = World::builder().body(floor);
    for k in 0..200 {
        let (layer, cell) = (k / 25, k % 25);
        let x = (cell % 5) as f64 * 2.0 - 4.0 + random.between(-0.3, 0.3);
        let y = (cell / 5) as f64 * 2.0 - 4.0 + random.between(-0.3, 0.3);
        let z = 1.0 + layer as f64 * 2.0;
        let turn = [random.unit(), random.unit(), random.unit()].map(|c| 6.0 * c - 3.0);
        builder = builder.body(
            BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                .mass(1.0)
                .position([x, y, z])
                .rotation(UnitQuaternion::from_scaled_axis(turn.into())),
        );
    }
    let mut world = builder.build().expect("valid cubes on a floor");
    for _ in 0..45 {
        world.step(1.0 / 60.0).expect("a pile steps");
    }
    world
}

/// Four worlds each stepped once (from clones, not timed): one after another, every step using
/// the pool's threads inside it, against all at once on the pool (each step then runs in one of
/// its workers, its own parallel work nested there). On two cores the second can at best take
/// half the time of the first run on one thread (`RAYON_NUM_THREADS=1`).
fn worlds_at_once(c: &mut Criterion) {
    let mut group = c.benchmark_group("worlds_at_once");
    group.sample_size(10);
    let pyramid = settled(&pyramid_centres(20), ContactModel::Face);
    let cases = [
        ("pyramid_20", vec![pyramid; 4], DT),
        (
            "landing_pile_200",
            (0..4).map(landing_pile).collect(),
            1.0 / 60.0,
        ),
    ];
    for (name, worlds, dt) in cases {
        group.throughput(Throughput::Elements(worlds.len() as u64));
        group.bench_with_input(
            BenchmarkId::new("one_after_another", name),
            &worlds,
            |b, w| {
                b.iter_batched_ref(
                    || w.clone(),
                    |worlds| {
                        for world in worlds.iter_mut() {
                            world.step(dt).expect("a scene steps");
                        }
                    },
                    BatchSize::LargeInput,
                )
            },
        );
        group.bench_with_input(BenchmarkId::new("all_at_once", name), &worlds, |b, w| {
            b.iter_batched_ref(
                || w.clone(),
                |worlds| {
                    worlds
                        .par_iter_mut()
                        .for_each(|world| world.step(dt).expect("a scene steps"));
                },
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

criterion_group!(benches, world_step, solver_call, worlds_at_once);
criterion_main!(benches);
