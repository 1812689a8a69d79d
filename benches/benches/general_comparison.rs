//! Tatami's defaults beside Rapier (rapier3d-f64 and rapier3d, f32; their defaults, sleeping
//! off) on general scenes, built for both engines from the same bodies: pyramids of 1 m, 1 kg
//! cubes with bases of 20 and 40 (1 mm gaps), 1000 such cubes dropped from 1 to 20 m with seeded
//! random turns, a pile of 1000 mixed shapes (boxes, spheres, cylinders, hulls), and the tower of
//! 100 cubes of 2 m. μ = 0.5, 600 steps at dt = 1/60.
//!
//! Tatami also runs with sleeping on (islands at rest skip the step; off by default, and off in
//! Rapier here).
//!
//! The engines chosen for a scene are stepped in lockstep, each engine's step k before any
//! engine's step k + 1 (which engine goes first changes every step), so that both engines of a
//! ratio meet the same minutes of this shared, noisy machine: run one after the other, a
//! minute's speed moved one engine's medians by 15–30% and not the other's. Stepped in turn,
//! the engines share the caches too, so each step reads slower than alone (the small scenes'
//! the most: the 210-cube pyramid's by half); compare ratios, not one engine's times across
//! runs with different engines chosen.
//!
//! For each engine: the median whole step, the median of each stage — collision, contact set and
//! rows, solve, and the rest (position correction and integration for Tatami; Rapier's update) —
//! and the quality: for pyramids and the tower the largest displacement of any body, for piles the
//! fastest body and the deepest floor penetration at the end, each the median over the last
//! second's steps of that step's largest (one step's snapshot read a single late topple or
//! impact, and moved by 10× between runs that differed in rounding only); and for every scene
//! when it came to rest: the end of the last step in which a body's centre moved faster than
//! 1 cm/s ("moving" if one still did at the end). A pile's median step falls in its settling, so
//! when each engine's pile came to rest says whether a gap is the engine's cost per step or a
//! longer settling.
//!
//! Run: `cargo bench -p tatami-benches --bench general_comparison` (a few minutes). Arguments
//! after `--` keep only the scenes and engines whose names contain one of them, e.g.
//! `-- pile tatami` for Tatami on both piles (for a profiler). With `--seeds=N` each pile is
//! also dropped from `N − 1` further seeds, and a summary gives each engine's median over the
//! courses and Tatami's ratio to rapier3d-f64 course by course, with when each came to rest:
//! how soon one course settles moves a pile's median as much as the engines do
//! (`-- --seeds=5 dropped`). With `--phases` a second table splits each run into its five
//! two-second phases: the median step of each, and the share of its time in collision, the
//! contact set and rows (a pile falls, lands, settles and rests in turn, and its median step
//! over the run reads only the settling).

use std::cell::RefCell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use nalgebra::{Point3, Quaternion, UnitQuaternion, Vector3};
use tatami_world::dropped::{Random, bin_walls, cubes_to_pour, mixed_shape};
use tatami_world::scene::Scene;
use tatami_world::{BodyDesc, Shape, WorldSettings};

const DT: f64 = 1.0 / 60.0;
const STEPS: usize = 600;
/// The last steps, one second at `DT`, over which the end-of-run quality is taken.
const END_STEPS: usize = 60;
/// A scene is at rest once no dynamic body's centre moves faster than this (m/s), 1 cm/s.
const REST_SPEED: f64 = 0.01;
/// Steps of a phase of `--phases`, two seconds at `DT`.
const PHASE_STEPS: usize = 120;

/// A random orientation (a normalised random quaternion).
fn random_rotation(random: &mut Random) -> UnitQuaternion<f64> {
    let mut component = || random.between(-1.0, 1.0);
    UnitQuaternion::from_quaternion(Quaternion::new(
        component(),
        component(),
        component(),
        component(),
    ))
}

fn floor() -> BodyDesc {
    BodyDesc::fixed(Shape::cuboid([200.0, 200.0, 2.0]))
        .name("floor")
        .position([0.0, 0.0, -1.0])
        .friction(0.5)
}

fn unit_cube(position: [f64; 3]) -> BodyDesc {
    BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
        .mass(1.0)
        .friction(0.5)
        .position(position)
}

fn scene(bodies: Vec<BodyDesc>) -> Scene {
    Scene {
        gravity: Vector3::new(0.0, 0.0, -9.81),
        dt: DT,
        steps: STEPS,
        settings: WorldSettings::default(),
        bodies,
        pgs_settings: Vec::new(),
    }
}

/// A two-dimensional pyramid of `base` cubes at the bottom, 1 mm apart.
fn pyramid(base: usize) -> Scene {
    let mut bodies = vec![floor()];
    for row in 0..base {
        let count = base - row;
        for i in 0..count {
            let x = (i as f64 - (count - 1) as f64 / 2.0) * 1.001;
            bodies.push(unit_cube([x, 0.0, 0.5 + row as f64]));
        }
    }
    scene(bodies)
}

/// 1000 bodies dropped from 1 to 20 m, turned at random; `shapes` picks each one's shape.
fn pile(seed: u64, shapes: impl Fn(&mut Random, usize) -> Shape) -> Scene {
    let mut random = Random::new(0x9e37_79b9_7f4a_7c15 ^ seed);
    let mut bodies = vec![floor()];
    for k in 0..1000 {
        let (layer, cell) = (k / 100, k % 100);
        let x = (cell % 10) as f64 * 2.0 - 9.0 + random.between(-0.3, 0.3);
        let y = (cell / 10) as f64 * 2.0 - 9.0 + random.between(-0.3, 0.3);
        let z = 1.0 + layer as f64 * 2.0 + random.between(0.0, 0.5);
        bodies.push(
            BodyDesc::dynamic(shapes(&mut random, k))
                .mass(1.0)
                .friction(0.5)
                .position([x, y, z])
                .rotation(random_rotation(&mut random)),
        );
    }
    scene(bodies)
}

/// 300 cubes of 10 cm (500 kg/m³, μ 0.5) poured in layers, turned at random, into a walled
/// bin 1 m across on the floor: bodies small for the step (Tatami's defaults split it in two).
fn bin() -> Scene {
    let mut bodies = vec![floor()];
    bodies.extend(bin_walls(0.5, 0.05, 2.0));
    bodies.extend(cubes_to_pour(0.1, 0.5, 300, 0.3, 7));
    scene(bodies)
}

fn tower() -> Scene {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/tower_100_60hz.json");
    Scene::load(path).expect("the tower scene loads")
}

/// The height of a body's lowest point.
fn lowest(shape: &Shape, position: &Point3<f64>, rotation: &UnitQuaternion<f64>) -> f64 {
    let axis = |i: usize| rotation * Vector3::ith(i, 1.0);
    position.z
        - match shape {
            Shape::Box { half_extents: h } => (0..3).map(|i| axis(i).z.abs() * h[i]).sum(),
            Shape::Sphere { radius } => *radius,
            Shape::Cylinder {
                radius,
                half_height,
            } => {
                let a = axis(2).z;
                radius * (1.0 - a * a).max(0.0).sqrt() + half_height * a.abs()
            }
            Shape::Convex { points } => points
                .iter()
                .map(|p| -(rotation * p.coords).z)
                .fold(f64::NEG_INFINITY, f64::max),
        }
}

/// Stage times of one step: collision, contact set and rows, solve, the rest.
type Stages = [Duration; 4];

/// What one engine measured on one scene.
struct Measured {
    step: Duration,
    stages: Stages,
    moved: f64,
    fastest: f64,
    penetration: f64,
    /// When the scene came to rest (s): the end of the last step in which a dynamic body's
    /// centre moved faster than [`REST_SPEED`]; `None` if one still did in the last step.
    at_rest_from: Option<f64>,
    phases: Phases,
}

/// Per phase of [`PHASE_STEPS`] steps: the median step, and the share of the phase's time in
/// collision and in the contact set and rows.
type Phases = Vec<(Duration, f64)>;

/// A body's pose and speed as an engine reports it.
struct State {
    position: Point3<f64>,
    rotation: UnitQuaternion<f64>,
    speed: f64,
}

/// The median of `values` (none NaN).
fn median<T: PartialOrd + Copy + Default>(mut values: Vec<T>) -> T {
    values.sort_unstable_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    values.get(values.len() / 2).copied().unwrap_or_default()
}

/// One engine's world of a scene, stepped a step at a time: `step` returns the step's stage
/// times, `states` every body's pose and speed in the scene's order.
struct Run {
    step: Box<dyn FnMut() -> Result<Stages, String>>,
    states: Box<dyn Fn() -> Vec<State>>,
}

/// What one engine's run has measured so far.
struct Tally {
    start: Vec<State>,
    moved: f64,
    times: Vec<Duration>,
    stages: [Vec<Duration>; 4],
    fastest: Vec<f64>,
    penetration: Vec<f64>,
    last_moving: usize,
}

impl Tally {
    fn new(start: Vec<State>) -> Self {
        Self {
            start,
            moved: 0.0,
            times: Vec::with_capacity(STEPS),
            stages: Default::default(),
            fastest: Vec::new(),
            penetration: Vec::new(),
            last_moving: 0,
        }
    }

    /// Step `done` (from 1) took `time`, in stages `split`, and left the bodies at `now`.
    fn record(&mut self, scene: &Scene, done: usize, time: Duration, split: Stages, now: &[State]) {
        self.times.push(time);
        for (list, time) in self.stages.iter_mut().zip(split) {
            list.push(time);
        }
        for (a, b) in now.iter().zip(&self.start) {
            self.moved = self.moved.max((a.position - b.position).norm());
        }
        let dynamic = || scene.bodies.iter().zip(now).filter(|(desc, _)| !desc.fixed);
        let fastest_now = dynamic().map(|(_, s)| s.speed).fold(0.0, f64::max);
        if fastest_now > REST_SPEED {
            self.last_moving = done;
        }
        if done > STEPS - END_STEPS {
            self.fastest.push(fastest_now);
            self.penetration.push(
                dynamic()
                    .map(|(desc, s)| -lowest(&desc.shape, &s.position, &s.rotation))
                    .fold(0.0, f64::max),
            );
        }
    }

    fn measured(self, scene: &Scene) -> Measured {
        let phases = (self.times.chunks(PHASE_STEPS))
            .zip(self.stages[0].chunks(PHASE_STEPS))
            .zip(self.stages[1].chunks(PHASE_STEPS))
            .map(|((times, collision), rows)| {
                let total: Duration = times.iter().sum();
                let outside: Duration = collision.iter().chain(rows).sum();
                let share = outside.as_secs_f64() / total.as_secs_f64().max(f64::MIN_POSITIVE);
                (median(times.to_vec()), share)
            })
            .collect();
        Measured {
            phases,
            step: median(self.times),
            stages: self.stages.map(median),
            moved: self.moved,
            fastest: median(self.fastest),
            penetration: median(self.penetration),
            at_rest_from: (self.last_moving < STEPS).then_some(self.last_moving as f64 * scene.dt),
        }
    }
}

/// Steps every run of `scene` 600 times in lockstep — step k of each engine, the first of
/// them taking turns, before step k + 1 of any (why: the module doc) — and measures each. A
/// run that fails is reported and stepped no further.
fn run_together(scene: &Scene, runs: Vec<Result<Run, String>>) -> Vec<Result<Measured, String>> {
    let mut runs: Vec<Result<(Run, Tally), String>> = runs
        .into_iter()
        .map(|run| {
            run.map(|run| {
                let start = (run.states)();
                (run, Tally::new(start))
            })
        })
        .collect();
    let count = runs.len();
    for done in 1..=STEPS {
        for turn in 0..count {
            let slot = &mut runs[(done + turn) % count];
            let Ok((run, tally)) = slot else { continue };
            let started = Instant::now();
            match (run.step)() {
                Ok(split) => {
                    let time = started.elapsed();
                    let now = (run.states)();
                    tally.record(scene, done, time, split, &now);
                }
                Err(e) => *slot = Err(e),
            }
        }
    }
    runs.into_iter()
        .map(|run| run.map(|(_, tally)| tally.measured(scene)))
        .collect()
}

fn tatami(scene: &Scene) -> Result<Run, String> {
    run_tatami(scene, scene.settings)
}

/// Tatami's defaults with sleeping on (the `--` filter `sleeping` picks it alone).
fn tatami_sleeping(scene: &Scene) -> Result<Run, String> {
    let settings = WorldSettings {
        sleeping: tatami_world::Sleeping::on(),
        ..scene.settings
    };
    run_tatami(scene, settings)
}

fn run_tatami(scene: &Scene, settings: WorldSettings) -> Result<Run, String> {
    let mut world = scene.world().map_err(|e| e.to_string())?;
    world.set_settings(settings).map_err(|e| e.to_string())?;
    let world = Rc::new(RefCell::new(world));
    let dt = scene.dt;
    let stepped = Rc::clone(&world);
    let step = move || {
        let mut world = stepped.borrow_mut();
        world.step(dt).map_err(|e| e.to_string())?;
        let t = world.timings();
        Ok([t.collision, t.setup, t.solve, t.correction + t.integrate])
    };
    let states = move || {
        world
            .borrow()
            .bodies()
            .iter()
            .map(|b| State {
                position: b.position(),
                rotation: b.rotation(),
                speed: b.linear_velocity().norm(),
            })
            .collect()
    };
    Ok(Run {
        step: Box::new(step),
        states: Box::new(states),
    })
}

/// The scene in one of Rapier's two builds (the crates differ only in `Real`).
macro_rules! rapier_scene {
    ($name:ident, $rapier:ident, $real:ty) => {
        fn $name(scene: &Scene) -> Result<Run, String> {
            use $rapier::prelude::*;
            let v = |x: f64, y: f64, z: f64| Vector::new(x as $real, y as $real, z as $real);
            let mut bodies = RigidBodySet::new();
            let mut colliders = ColliderSet::new();
            let mut handles = Vec::new();
            for desc in &scene.bodies {
                let volume = desc
                    .shape
                    .mass_properties()
                    .map_err(|e| e.to_string())?
                    .volume;
                let density = match desc.mass {
                    tatami_world::MassSpec::Mass(m) => m / volume,
                    tatami_world::MassSpec::Density(rho) => rho,
                };
                let collider = match &desc.shape {
                    tatami_world::Shape::Box { half_extents: h } => {
                        ColliderBuilder::cuboid(h.x as $real, h.y as $real, h.z as $real)
                    }
                    tatami_world::Shape::Sphere { radius } => {
                        ColliderBuilder::ball(*radius as $real)
                    }
                    // Rapier's cylinders run along y, Tatami's along z.
                    tatami_world::Shape::Cylinder {
                        radius,
                        half_height,
                    } => ColliderBuilder::cylinder(*half_height as $real, *radius as $real)
                        .rotation(v(std::f64::consts::FRAC_PI_2, 0.0, 0.0)),
                    tatami_world::Shape::Convex { points } => {
                        let points: Vec<_> = points.iter().map(|p| v(p.x, p.y, p.z)).collect();
                        ColliderBuilder::convex_hull(&points).ok_or("no hull")?
                    }
                };
                let body = if desc.fixed {
                    RigidBodyBuilder::fixed()
                } else {
                    RigidBodyBuilder::dynamic().can_sleep(false)
                };
                let (p, turn) = (desc.position, desc.rotation.scaled_axis());
                let handle = bodies.insert(
                    body.translation(v(p.x, p.y, p.z))
                        .rotation(v(turn.x, turn.y, turn.z)),
                );
                colliders.insert_with_parent(
                    collider
                        .density(density as $real)
                        .friction(desc.static_friction as $real),
                    handle,
                    &mut bodies,
                );
                handles.push(handle);
            }
            let parameters = IntegrationParameters {
                dt: scene.dt as $real,
                ..IntegrationParameters::default()
            };
            let g = scene.gravity;
            let gravity = v(g.x, g.y, g.z);
            let mut pipeline = PhysicsPipeline::new();
            pipeline.counters.enable();
            let world = Rc::new(RefCell::new((
                bodies,
                colliders,
                pipeline,
                IslandManager::new(),
                BroadPhaseBvh::new(),
                NarrowPhase::new(),
                ImpulseJointSet::new(),
                MultibodyJointSet::new(),
                CCDSolver::new(),
                SoftBodySet::new(),
            )));
            let stepped = Rc::clone(&world);
            let step = move || {
                let w = &mut *stepped.borrow_mut();
                w.2.step(
                    gravity,
                    &parameters,
                    &mut w.3,
                    &mut w.4,
                    &mut w.5,
                    &mut w.0,
                    &mut w.1,
                    &mut w.6,
                    &mut w.7,
                    &mut w.9,
                    &mut w.8,
                    &(),
                    &(),
                );
                let c = &w.2.counters;
                let ms = |t: f64| Duration::from_secs_f64(t / 1e3);
                let collision = c.stages.collision_detection_time.time_ms();
                let rows = c.stages.island_construction_time.time_ms()
                    + c.solver.velocity_assembly_time.time_ms();
                let solve =
                    c.stages.solver_time.time_ms() - c.solver.velocity_assembly_time.time_ms();
                let rest = c.step_time_ms() - collision - rows - solve;
                Ok([
                    ms(collision),
                    ms(rows),
                    ms(solve.max(0.0)),
                    ms(rest.max(0.0)),
                ])
            };
            let states = move || {
                let w = world.borrow();
                handles
                    .iter()
                    .map(|&h| {
                        let body = &w.0[h];
                        let (t, q, s) = (body.translation(), body.rotation(), body.linvel());
                        State {
                            position: ::nalgebra::Point3::new(t.x as f64, t.y as f64, t.z as f64),
                            rotation: ::nalgebra::UnitQuaternion::new_normalize(
                                ::nalgebra::Quaternion::new(
                                    q.w as f64, q.x as f64, q.y as f64, q.z as f64,
                                ),
                            ),
                            speed: ::nalgebra::Vector3::new(s.x as f64, s.y as f64, s.z as f64)
                                .norm(),
                        }
                    })
                    .collect()
            };
            Ok(Run {
                step: Box::new(step),
                states: Box::new(states),
            })
        }
    };
}

rapier_scene!(rapier_f64, rapier3d_f64, f64);
rapier_scene!(rapier_f32, rapier3d, f32);

/// One engine's world of a scene, set up to be stepped.
type Engine = fn(&Scene) -> Result<Run, String>;

/// The piles' names, which their further courses under `--seeds=N` extend with their seeds.
const CUBE_PILE: &str = "1000 cubes dropped";
const MIXED_PILE: &str = "1000 mixed shapes dropped";

/// Under `--seeds=N`, the cube pile's `k`-th further course (`k` from 1) is dropped from seed
/// `CUBE_SEEDS + k`: 3, 4, … (its own is seed 1).
const CUBE_SEEDS: u64 = 2;
/// Under `--seeds=N`, the mixed pile's `k`-th further course is dropped from seed
/// `MIXED_SEEDS + k`: 103, 104, … (its own is seed 2).
const MIXED_SEEDS: u64 = 102;

/// `--seeds=N` among the arguments: how many courses each pile is run on (1 without it).
fn seeds(arguments: &[String]) -> Result<u64, String> {
    match arguments.iter().find_map(|a| a.strip_prefix("--seeds=")) {
        None => Ok(1),
        Some(n) => match n.parse::<u64>() {
            Ok(n) if (1..=100).contains(&n) => Ok(n),
            _ => Err(format!(
                "--seeds must be a whole number from 1 to 100, got {n:?}"
            )),
        },
    }
}

fn main() {
    // Cargo passes `--bench` to a bench without a harness; `--seeds=N` is read apart; the rest
    // are filters.
    let arguments: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    let courses = match seeds(&arguments) {
        Ok(n) => n,
        Err(reason) => {
            eprintln!("general_comparison: {reason}");
            std::process::exit(2);
        }
    };
    let by_phase = arguments.iter().any(|a| a == "--phases");
    let filters: Vec<&String> = arguments
        .iter()
        .filter(|a| !a.starts_with("--seeds=") && *a != "--phases")
        .collect();
    let cubes = |_: &mut Random, _: usize| Shape::cuboid([1.0; 3]);
    let mut scenes: Vec<(String, Scene)> = vec![
        ("pyramid, base 20 (210 cubes)".into(), pyramid(20)),
        ("pyramid, base 40 (820 cubes)".into(), pyramid(40)),
        (CUBE_PILE.into(), pile(1, cubes)),
        (MIXED_PILE.into(), pile(2, mixed_shape)),
        ("tower of 100 cubes of 2 m".into(), tower()),
        ("bin of 300 cubes of 10 cm".into(), bin()),
    ];
    for k in 1..courses {
        let (cube_seed, mixed_seed) = (CUBE_SEEDS + k, MIXED_SEEDS + k);
        scenes.push((
            format!("{CUBE_PILE}, seed {cube_seed}"),
            pile(cube_seed, cubes),
        ));
        scenes.push((
            format!("{MIXED_PILE}, seed {mixed_seed}"),
            pile(mixed_seed, mixed_shape),
        ));
    }
    let engines: [(&str, Engine); 4] = [
        ("tatami defaults", tatami),
        ("tatami, sleeping on", tatami_sleeping),
        ("rapier3d-f64", rapier_f64),
        ("rapier3d (f32)", rapier_f32),
    ];
    let wanted = |name: &str, all: &[&str]| {
        let named: Vec<_> = filters
            .iter()
            .filter(|f| all.iter().any(|n| n.contains(f.as_str())))
            .collect();
        named.is_empty() || named.iter().any(|f| name.contains(f.as_str()))
    };
    let scene_names: Vec<&str> = scenes.iter().map(|(n, _)| n.as_str()).collect();
    let engine_names: Vec<&str> = engines.iter().map(|(n, _)| *n).collect();
    println!(
        "| scene | engine | step (ms) | collision | contact set and rows | solve | rest | \
         largest displacement (m) | fastest at the end (m/s) | deepest penetration (m) | \
         at rest from (s) |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    // Each pile's median step per engine and course, and when it came to rest, for the summary
    // over courses.
    let mut piles: Vec<Course> = Vec::new();
    // Each run's phases, for `--phases`.
    let mut phases: Vec<(String, &str, Phases)> = Vec::new();
    for (name, scene) in scenes.iter().filter(|(n, _)| wanted(n, &scene_names)) {
        let chosen: Vec<(&str, Engine)> = engines
            .into_iter()
            .filter(|(n, _)| wanted(n, &engine_names))
            .collect();
        let runs = chosen.iter().map(|(_, build)| build(scene)).collect();
        for ((engine, _), measured) in chosen.iter().zip(run_together(scene, runs)) {
            match measured {
                Ok(m) => {
                    println!(
                        "| {name} | {engine} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.4} | {} |",
                        ms(m.step),
                        ms(m.stages[0]),
                        ms(m.stages[1]),
                        ms(m.stages[2]),
                        ms(m.stages[3]),
                        m.moved,
                        m.fastest,
                        m.penetration,
                        rest_time(m.at_rest_from),
                    );
                    phases.push((name.clone(), engine, m.phases));
                    if let Some(pile) = [CUBE_PILE, MIXED_PILE]
                        .into_iter()
                        .find(|pile| name.starts_with(pile))
                    {
                        piles.push(Course {
                            pile,
                            engine,
                            step: ms(m.step),
                            at_rest_from: m.at_rest_from,
                        });
                    }
                }
                Err(e) => println!("| {name} | {engine} | failed: {e} | | | | | | | | |"),
            }
        }
    }
    if courses > 1 {
        print_over_courses(&piles);
    }
    if by_phase {
        print_phases(&phases);
    }
}

/// Under `--phases`: each run's median step per two-second phase, with the share of the
/// phase's time in collision and in the contact set and rows.
fn print_phases(runs: &[(String, &str, Phases)]) {
    let seconds = PHASE_STEPS as f64 * DT;
    let count = STEPS / PHASE_STEPS;
    let heads: Vec<String> = (0..count)
        .map(|k| {
            format!(
                "{:.0}–{:.0} s",
                k as f64 * seconds,
                (k + 1) as f64 * seconds
            )
        })
        .collect();
    println!();
    println!(
        "Median step (ms) per phase, and the share of its time in collision, contact set and rows:"
    );
    println!();
    println!("| scene | engine | {} |", heads.join(" | "));
    println!("|---|---|{}", "---:|".repeat(count));
    for (name, engine, phases) in runs {
        let cells: Vec<String> = phases
            .iter()
            .map(|(step, share)| format!("{:.2} ({:.0}%)", step.as_secs_f64() * 1e3, share * 100.0))
            .collect();
        println!("| {name} | {engine} | {} |", cells.join(" | "));
    }
}

/// One engine's run of one course of a pile, for the summary over courses.
struct Course<'a> {
    pile: &'a str,
    engine: &'a str,
    /// The median step (ms).
    step: f64,
    /// See [`Measured::at_rest_from`].
    at_rest_from: Option<f64>,
}

/// When a run came to rest, for the table: seconds, or "moving" if it had not by the end.
fn rest_time(at_rest_from: Option<f64>) -> String {
    at_rest_from.map_or_else(|| "moving".to_owned(), |t| format!("{t:.1}"))
}

/// When a run came to rest, in words: "at rest from 8.4 s", or "still moving".
fn settled(at_rest_from: Option<f64>) -> String {
    at_rest_from.map_or_else(
        || "still moving".to_owned(),
        |t| format!("at rest from {t:.1} s"),
    )
}

/// Under `--seeds=N`: each pile's median step per engine over its courses (the median of the
/// courses' medians, the upper middle one for an even count, with their range), and each
/// course's ratio of Tatami's defaults to rapier3d-f64 with when each engine's course came to
/// rest: one course's median reads how soon that course settles as much as the engine.
fn print_over_courses(piles: &[Course<'_>]) {
    let courses_of = |pile: &str, engine: &str| -> Vec<&Course<'_>> {
        piles
            .iter()
            .filter(|c| (c.pile, c.engine) == (pile, engine))
            .collect()
    };
    println!();
    println!("| pile | engine | courses | median step (ms) | range (ms) |");
    println!("|---|---|---:|---:|---|");
    let mut seen: Vec<(&str, &str)> = Vec::new();
    for course in piles {
        let (pile, engine) = (course.pile, course.engine);
        if seen.contains(&(pile, engine)) {
            continue;
        }
        seen.push((pile, engine));
        let steps: Vec<f64> = courses_of(pile, engine).iter().map(|c| c.step).collect();
        let least = steps.iter().copied().fold(f64::INFINITY, f64::min);
        let most = steps.iter().copied().fold(0.0, f64::max);
        let count = steps.len();
        println!(
            "| {pile} | {engine} | {count} | {:.3} | {least:.3}–{most:.3} |",
            median(steps)
        );
    }
    for pile in [CUBE_PILE, MIXED_PILE] {
        let (tatami, rapier) = (
            courses_of(pile, "tatami defaults"),
            courses_of(pile, "rapier3d-f64"),
        );
        if tatami.is_empty() || tatami.len() != rapier.len() {
            continue;
        }
        let ratios: Vec<String> = tatami
            .iter()
            .zip(&rapier)
            .map(|(t, r)| {
                format!(
                    "{:.2}× (Tatami {}, Rapier {})",
                    t.step / r.step,
                    settled(t.at_rest_from),
                    settled(r.at_rest_from)
                )
            })
            .collect();
        println!(
            "\n{pile}: Tatami's defaults against rapier3d-f64, course by course: {}",
            ratios.join(", ")
        );
    }
}
