//! Tatami beside Rapier (rapier3d-f64 and rapier3d, f32) on the same tower: N cubes of 2 m and
//! 1 kg on a fixed floor, friction 0.5 (both engines' default), sleeping off, Rapier's default
//! solver settings and Tatami's settings as named. For dt = 1/60 s and 0.01 s and N = 10, 100,
//! 200, 1000, each engine simulates 10 s; the table gives the median wall time of a whole step,
//! the top cube's drop after 10 s and the largest penetration at the end.
//!
//! Run: `cargo bench -p tatami-benches --bench tower_comparison` (a few minutes). Arguments
//! choose tower heights: `… -- 10 100`. The figures are printed as a Markdown table.

use std::time::{Duration, Instant};

use tatami_benches::{CUBE_SIDE, tatami_cubes, tower_centres};
use tatami_world::{ContactModel, PgsParams, Solver, WarmStart, WorldSettings};

/// Simulated time of every run (s).
const SECONDS: f64 = 10.0;

/// What one run measured.
struct Measured {
    step: Duration,
    top_drop: f64,
    penetration: f64,
}

fn median(mut times: Vec<Duration>) -> Duration {
    times.sort_unstable();
    times.get(times.len() / 2).copied().unwrap_or_default()
}

fn steps(dt: f64) -> usize {
    (SECONDS / dt).round() as usize
}

fn tatami(n: usize, dt: f64, settings: WorldSettings) -> Result<Measured, String> {
    let mut world = tatami_cubes(&tower_centres(n), settings);
    let top = world.bodies().len() - 1;
    let z0 = world.bodies()[top].position().z;
    let mut times = Vec::with_capacity(steps(dt));
    for k in 0..steps(dt) {
        let started = Instant::now();
        world.step(dt).map_err(|e| format!("step {}: {e}", k + 1))?;
        times.push(started.elapsed());
    }
    let penetration = world
        .contacts()
        .flat_map(|c| c.depths.iter().copied())
        .fold(0.0, f64::max);
    Ok(Measured {
        step: median(times),
        top_drop: z0 - world.bodies()[top].position().z,
        penetration,
    })
}

/// The same tower in one of Rapier's two builds (the crates differ only in `Real`).
macro_rules! rapier_tower {
    ($name:ident, $rapier:ident, $real:ty) => {
        fn $name(n: usize, dt: f64) -> Measured {
            use $rapier::prelude::*;
            let mut bodies = RigidBodySet::new();
            let mut colliders = ColliderSet::new();
            let floor =
                bodies.insert(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 0.0, -1.0)));
            colliders.insert_with_parent(
                ColliderBuilder::cuboid(200.0, 200.0, 1.0),
                floor,
                &mut bodies,
            );
            let half = (CUBE_SIDE / 2.0) as $real;
            let volume = (CUBE_SIDE * CUBE_SIDE * CUBE_SIDE) as $real;
            let mut top = floor;
            for [x, y, z] in tower_centres(n) {
                let centre = Vector::new(x as $real, y as $real, z as $real);
                top = bodies.insert(
                    RigidBodyBuilder::dynamic()
                        .translation(centre)
                        .can_sleep(false),
                );
                colliders.insert_with_parent(
                    ColliderBuilder::cuboid(half, half, half).density(1.0 / volume),
                    top,
                    &mut bodies,
                );
            }
            let z0 = bodies[top].translation().z as f64;
            let parameters = IntegrationParameters {
                dt: dt as $real,
                ..IntegrationParameters::default()
            };
            let mut pipeline = PhysicsPipeline::new();
            let mut islands = IslandManager::new();
            let mut broad_phase = BroadPhaseBvh::new();
            let mut narrow_phase = NarrowPhase::new();
            let mut impulse_joints = ImpulseJointSet::new();
            let mut multibody_joints = MultibodyJointSet::new();
            let mut soft_bodies = SoftBodySet::new();
            let mut ccd = CCDSolver::new();
            let gravity = Vector::new(0.0, 0.0, -9.8);
            let mut times = Vec::with_capacity(steps(dt));
            for _ in 0..steps(dt) {
                let started = Instant::now();
                pipeline.step(
                    gravity,
                    &parameters,
                    &mut islands,
                    &mut broad_phase,
                    &mut narrow_phase,
                    &mut bodies,
                    &mut colliders,
                    &mut impulse_joints,
                    &mut multibody_joints,
                    &mut soft_bodies,
                    &mut ccd,
                    &(),
                    &(),
                );
                times.push(started.elapsed());
            }
            let penetration = narrow_phase
                .contact_pairs()
                .flat_map(|pair| pair.manifolds().iter())
                .flat_map(|manifold| manifold.points.iter())
                .map(|point| -(point.dist as f64))
                .fold(0.0, f64::max);
            Measured {
                step: median(times),
                top_drop: z0 - bodies[top].translation().z as f64,
                penetration,
            }
        }
    };
}

rapier_tower!(rapier_f64, rapier3d_f64, f64);
rapier_tower!(rapier_f32, rapier3d, f32);

/// Tatami's configurations: its defaults, the face model, and what it takes to stand.
fn tatami_configs() -> Vec<(&'static str, WorldSettings)> {
    let face = |iterations: usize, warm_start: WarmStart| WorldSettings {
        model: ContactModel::Face,
        solver: Solver::Pgs(PgsParams {
            iterations,
            warm_start,
            ..PgsParams::default()
        }),
        ..WorldSettings::default()
    };
    let shocked = |iterations: usize| WorldSettings {
        shock_propagation: true,
        ..face(iterations, WarmStart::Off)
    };
    vec![
        ("tatami defaults", WorldSettings::default()),
        ("tatami face, 15 sweeps", face(15, WarmStart::Off)),
        (
            "tatami face, 15 sweeps, warm start",
            face(15, WarmStart::On),
        ),
        (
            "tatami face, 60 sweeps, warm start",
            face(60, WarmStart::On),
        ),
        ("tatami face, 15 sweeps, shock propagation", shocked(15)),
        ("tatami face, 4 sweeps, shock propagation", shocked(4)),
    ]
}

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![10, 100, 200, 1000]
    } else {
        sizes
    };
    println!(
        "| dt (s) | cubes | engine | step (ms, median) | top drop after 10 s (m) | largest penetration (mm) |"
    );
    println!("|---:|---:|---|---:|---:|---:|");
    let row = |dt: f64, n: usize, name: &str, m: &Measured| {
        println!(
            "| {dt:.4} | {n} | {name} | {:.3} | {:.4} | {:.2} |",
            m.step.as_secs_f64() * 1e3,
            m.top_drop,
            m.penetration * 1e3
        );
    };
    for dt in [1.0 / 60.0, 0.01] {
        for &n in &sizes {
            row(dt, n, "rapier3d-f64", &rapier_f64(n, dt));
            row(dt, n, "rapier3d (f32)", &rapier_f32(n, dt));
            for (name, settings) in tatami_configs() {
                match tatami(n, dt, settings) {
                    Ok(m) => row(dt, n, name, &m),
                    Err(e) => println!("| {dt:.4} | {n} | {name} | failed: {e} | | |"),
                }
            }
        }
    }
}
