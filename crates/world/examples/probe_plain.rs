use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::hash::{Hash, Hasher};
use std::time::Instant;
use tatami_world::dropped::{Random, bin_walls, cubes_to_pour, mixed_shape};
use tatami_world::scene::Scene;
use tatami_world::{BodyDesc, Shape, WorldSettings};

fn random_rotation(random: &mut Random) -> UnitQuaternion<f64> {
    let mut c = || random.between(-1.0, 1.0);
    UnitQuaternion::from_quaternion(Quaternion::new(c(), c(), c(), c()))
}

fn pile(seed: u64, mixed: bool) -> Scene {
    let mut random = Random::new(0x9e37_79b9_7f4a_7c15 ^ seed);
    let mut bodies = vec![
        BodyDesc::fixed(Shape::cuboid([200.0, 200.0, 2.0]))
            .name("floor")
            .position([0.0, 0.0, -1.0])
            .friction(0.5),
    ];
    for k in 0..1000 {
        let (layer, cell) = (k / 100, k % 100);
        let x = (cell % 10) as f64 * 2.0 - 9.0 + random.between(-0.3, 0.3);
        let y = (cell / 10) as f64 * 2.0 - 9.0 + random.between(-0.3, 0.3);
        let z = 1.0 + layer as f64 * 2.0 + random.between(0.0, 0.5);
        let shape = if mixed { mixed_shape(&mut random, k) } else { Shape::cuboid([1.0; 3]) };
        bodies.push(
            BodyDesc::dynamic(shape)
                .mass(1.0)
                .friction(0.5)
                .position([x, y, z])
                .rotation(random_rotation(&mut random)),
        );
    }
    if std::env::var("BIN").is_ok() {
        bodies.truncate(1);
        bodies.extend(bin_walls(0.5, 0.05, 2.0));
        bodies.extend(cubes_to_pour(0.1, 0.5, 300, 0.3, 7));
    }
    Scene {
        gravity: Vector3::new(0.0, 0.0, -9.81),
        dt: 1.0 / 60.0,
        steps: 600,
        settings: WorldSettings::default(),
        bodies,
        pgs_settings: Vec::new(),
    }
}

#[inline(never)]
fn measured(world: &mut tatami_world::World, dt: f64) {
    world.step(dt).unwrap();
}

fn main() {
    let env = |k: &str, d: f64| std::env::var(k).ok().and_then(|v| v.parse().ok()).unwrap_or(d);
    let mixed = env("MIXED", 0.0) > 0.0;
    let secs = env("SECS", 10.0);
    let from = env("FROM", 0.0);
    let seed = env("SEED", if mixed { 2.0 } else { 1.0 }) as u64;
    let scene = pile(seed, mixed);
    let mut world = scene.world().unwrap();
    let mut s = WorldSettings::default();
    if env("SLEEP", 0.0) > 0.0 {
        s.sleeping = tatami_world::Sleeping::on();
    }
    if let Ok(t) = std::env::var("TOL") {
        if let tatami_world::Solver::Pgs(p) = &mut s.solver { p.tolerance = t.parse().unwrap(); }
    }
    if let Ok(t) = std::env::var("ITER") {
        if let tatami_world::Solver::Pgs(p) = &mut s.solver { p.iterations = t.parse().unwrap(); }
    }
    world.set_settings(s).unwrap();
    let steps = (secs * 60.0) as usize;
    let first = (from * 60.0) as usize;
    let mut times = vec![];
    let mut stages: Vec<[f64; 5]> = vec![];
    let mut rest = 0.0;
    for k in 0..steps {
        let before: Vec<_> = world.bodies().iter().map(|b| b.position()).collect();
        if k == first { for a in tatami_world::PROBE_T.iter() { a.store(0, std::sync::atomic::Ordering::Relaxed); } }
        if k >= first {
            if let Ok(g) = std::env::var("GAP_MS") { let g: f64 = g.parse().unwrap(); let t = Instant::now(); while t.elapsed().as_secs_f64() * 1e3 < g { std::hint::spin_loop(); } }
            let t = Instant::now();
            measured(&mut world, scene.dt);
            times.push(t.elapsed().as_secs_f64() * 1e3);
            let t = world.timings();
            stages.push([t.collision, t.setup, t.solve, t.correction, t.integrate].map(|d| d.as_secs_f64() * 1e3));
        } else {
            world.step(scene.dt).unwrap();
        }
        let moving = world.bodies().iter().zip(&before).any(|(b, p)| (b.position() - p).norm() / scene.dt > 0.01);
        if moving {
            rest = (k + 1) as f64 * scene.dt;
        }
    }
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for b in world.bodies() {
        for v in b.position().iter().chain(b.rotation().coords.iter()) {
            v.to_bits().hash(&mut h);
        }
    }
    let med = |mut v: Vec<f64>| {
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        if v.is_empty() { 0.0 } else { v[v.len() / 2] }
    };
    let total: f64 = times.iter().sum();
    let n = times.len().max(1) as f64;
    let pt: Vec<String> = tatami_world::PROBE_T.iter().take(3).map(|a| format!("{:.3}", a.load(std::sync::atomic::Ordering::Relaxed) as f64 / 1e6 / n)).collect();
    println!("caller waiting for helpers ms/step: each_beside {} both_ends {} join_beside {}", pt[0], pt[1], pt[2]);
    println!("hash {:016x} at rest {:.2}s", h.finish(), rest);
    println!(
        "step median {:.3} ms total {:.1} ms; coll {:.3} setup {:.3} solve {:.3} corr {:.3} integ {:.3}",
        med(times.clone()),
        total,
        med(stages.iter().map(|s| s[0]).collect()),
        med(stages.iter().map(|s| s[1]).collect()),
        med(stages.iter().map(|s| s[2]).collect()),
        med(stages.iter().map(|s| s[3]).collect()),
        med(stages.iter().map(|s| s[4]).collect()),
    );
}
