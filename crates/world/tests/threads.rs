//! A step gives the same bits on one thread as on two: collision pairs are computed on every
//! core, each as a function of its two bodies alone, and written into the contact set in pair
//! order; the pairs' rows are built on every core, the helpers' share apart and then joined in
//! the set's order, while a helper makes the warm start's guess for new pairs; the position
//! pass, on its own copy of the problem, runs beside the velocity solve, computes the shock
//! passes' held responses for both, and its helper then takes a share of the bodies' motions.
//! So do a world stepped from the program's own thread, the pool's helpers spinning on between
//! its steps, and worlds stepped at once, each inside one of the pool's workers.

use nalgebra::{UnitQuaternion, Vector3};
use tatami_world::dropped::{Random, mixed_shape};
use tatami_world::{BodyDesc, Shape, World};

/// 256 bodies of every shape (box, sphere, cylinder, hull), turned at random, dropped in four
/// layers onto a floor: hundreds of fresh pairs a step once they land, far above the count at
/// which collision goes parallel, over 256 touching pairs, where their rows go parallel too,
/// over 1,024 rows once they land, where the position pass goes beside the velocity solve, and
/// 256 bodies besides the floor, whose motions are then shared with the pass's helper.
fn pile() -> World {
    let mut random = Random::new(7);
    let mut builder = World::builder().body(
        BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0]))
            .name("floor")
            .position([0.0, 0.0, -1.0]),
    );
    for k in 0..256 {
        let shape = mixed_shape(&mut random, k);
        let (layer, cell) = (k / 64, k % 64);
        let turn = Vector3::new(random.unit(), random.unit(), random.unit()) * 3.0;
        builder = builder.body(
            BodyDesc::dynamic(shape)
                .position([
                    (cell % 8) as f64 * 1.1 - 3.85,
                    (cell / 8) as f64 * 1.1 - 3.85,
                    0.6 + layer as f64 * 1.2,
                ])
                .rotation(UnitQuaternion::from_scaled_axis(turn)),
        );
    }
    builder.build().unwrap()
}

/// A pool of `threads` threads.
fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// The pile after `steps` steps.
fn stepped(steps: usize) -> World {
    let mut world = pile();
    for _ in 0..steps {
        world.step(1.0 / 60.0).unwrap();
    }
    world
}

/// Every body's pose and velocity as bits.
fn bits(world: &World) -> Vec<[u64; 13]> {
    world
        .bodies()
        .iter()
        .map(|b| {
            let (p, q) = (b.position(), b.rotation());
            let (v, w) = (b.linear_velocity(), b.angular_velocity());
            [
                p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z,
            ]
            .map(f64::to_bits)
        })
        .collect()
}

/// Every body's pose and velocity as bits, after `steps` steps in a pool of `threads` threads,
/// and the number of touching pairs at the end.
fn run(threads: usize, steps: usize) -> (Vec<[u64; 13]>, usize) {
    pool(threads).install(|| {
        let world = stepped(steps);
        (bits(&world), world.contacts().len())
    })
}

/// 120 steps (2 s: the pile lands and settles) on one thread and on two: identical bits.
#[test]
fn one_and_two_threads_give_the_same_bits() {
    let (one, touching) = run(1, 120);
    let (two, _) = run(2, 120);
    let differ = one.iter().zip(&two).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{differ} of {} bodies differ", one.len());
    // The run exercised the parallel paths: every body rests on the floor or another body, and
    // there are enough pairs for their rows to be built on every core.
    assert!(touching >= 256, "only {touching} touching pairs");
}

/// Stepped from the program's own thread, as most programs step a world, on rayon's global
/// pool (a thread per core), whose helpers spin on between two steps for the next collision
/// pass. The bits of one thread (on a machine of one core the pool has no helpers, and this
/// checks the run against itself).
#[test]
fn stepped_from_the_programs_own_thread_with_helpers_kept_warm_gives_the_bits_of_one_thread() {
    let (one, _) = run(1, 120);
    let world = stepped(120);
    let differ = one
        .iter()
        .zip(bits(&world))
        .filter(|(a, b)| **a != *b)
        .count();
    assert_eq!(differ, 0, "{differ} of {} bodies differ", one.len());
}

/// Several worlds stepped at once on a pool of two threads (many simulations run side by side,
/// as when training a controller): each step then runs inside one of the pool's workers, its
/// parallel loops, the helpers kept spinning between two of them and the position pass beside
/// the velocity solve nested in the pool the other worlds' steps keep busy. Each world ends
/// with the bits of one world stepped on one thread.
#[test]
fn worlds_stepped_at_once_on_the_pool_give_the_bits_of_one_thread() {
    use rayon::prelude::*;
    let (one, touching) = run(1, 120);
    assert!(touching >= 256, "only {touching} touching pairs");
    let worlds: Vec<World> =
        pool(2).install(|| (0..3).into_par_iter().map(|_| stepped(120)).collect());
    for (k, world) in worlds.iter().enumerate() {
        let differ = one
            .iter()
            .zip(bits(world))
            .filter(|(a, b)| **a != *b)
            .count();
        assert_eq!(
            differ,
            0,
            "world {k}: {differ} of {} bodies differ",
            one.len()
        );
    }
}
