//! Tatami's defaults beside Rapier (rapier3d-f64 and rapier3d, f32; their defaults, sleeping
//! off) on the holding scenes of `scenes/`: an offset pair, a leaning stack, a 1 kg cube under
//! a 1000 kg one, a pyramid of 55 cubes and a tower of 100 cubes of 2 m at 60 Hz. Both engines
//! build each scene from the same parsed file; friction is each body's, combined by average in
//! both. The table gives the median wall time of a whole step and the largest displacement of
//! any body over the scene's window — what `crates/world/tests/holding.rs` asserts for Tatami.
//!
//! Run: `cargo bench -p tatami-benches --bench holding_comparison` (about a minute).

use std::path::Path;
use std::time::{Duration, Instant};

use tatami_benches::RapierF64;
use tatami_world::scene::Scene;

/// A scene file of `scenes/` and the window (s) over which its bodies' motion is measured.
struct Case {
    file: &'static str,
    from: f64,
    to: f64,
}

const CASES: [Case; 5] = [
    Case {
        file: "offset_pair",
        from: 2.0,
        to: 30.0,
    },
    Case {
        file: "leaning_stack",
        from: 2.0,
        to: 30.0,
    },
    Case {
        file: "heavy_on_light",
        from: 0.0,
        to: 10.0,
    },
    Case {
        file: "pyramid_55",
        from: 0.0,
        to: 10.0,
    },
    Case {
        file: "tower_100_60hz",
        from: 0.0,
        to: 10.0,
    },
];

/// What one run measured.
struct Measured {
    step: Duration,
    moved: f64,
}

fn median(mut times: Vec<Duration>) -> Duration {
    times.sort_unstable();
    times.get(times.len() / 2).copied().unwrap_or_default()
}

/// Steps `step` until `case.to`, timing each; returns the median step and the largest
/// displacement of `positions` between `case.from` and `case.to`.
fn measure(
    case: &Case,
    dt: f64,
    mut step: impl FnMut(),
    positions: impl Fn() -> Vec<[f64; 3]>,
) -> Measured {
    let steps = |t: f64| (t / dt).round() as usize;
    let mut times = Vec::with_capacity(steps(case.to));
    let mut settled = positions();
    for k in 0..steps(case.to) {
        if k == steps(case.from) {
            settled = positions();
        }
        let started = Instant::now();
        step();
        times.push(started.elapsed());
    }
    let moved = positions()
        .iter()
        .zip(&settled)
        .map(|(a, b)| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    Measured {
        step: median(times),
        moved,
    }
}

fn tatami(case: &Case, scene: &Scene) -> Result<Measured, String> {
    let world = std::cell::RefCell::new(scene.world().map_err(|e| e.to_string())?);
    let failed = std::cell::Cell::new(None);
    let step = || {
        if let Err(e) = world.borrow_mut().step(scene.dt) {
            failed.set(Some(e.to_string()));
        }
    };
    let positions = || {
        world
            .borrow()
            .bodies()
            .iter()
            .map(|b| b.position().coords.into())
            .collect()
    };
    let measured = measure(case, scene.dt, step, positions);
    match failed.take() {
        Some(e) => Err(e),
        None => Ok(measured),
    }
}

tatami_benches::rapier_scene!(
    /// A scene in rapier3d (f32).
    RapierF32,
    rapier3d,
    f32
);

/// The scene in one of Rapier's two builds.
macro_rules! rapier_run {
    ($name:ident, $scene:ident) => {
        fn $name(case: &Case, scene: &Scene) -> Result<Measured, String> {
            let world = std::cell::RefCell::new($scene::new(scene)?);
            let step = || world.borrow_mut().step();
            let positions = || world.borrow().positions();
            Ok(measure(case, scene.dt, step, positions))
        }
    };
}

/// One engine's run of a case.
type Engine = fn(&Case, &Scene) -> Result<Measured, String>;

rapier_run!(rapier_f64, RapierF64);
rapier_run!(rapier_f32, RapierF32);

fn main() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    println!("| scene | window (s) | engine | step (ms, median) | largest displacement (m) |");
    println!("|---|---|---|---:|---:|");
    for case in &CASES {
        let path = folder.join(format!("{}.json", case.file));
        let scene = match Scene::load(&path) {
            Ok(scene) => scene,
            Err(e) => {
                println!("| {} | | | failed: {e} | |", case.file);
                continue;
            }
        };
        let engines: [(&str, Engine); 3] = [
            ("tatami defaults", tatami),
            ("rapier3d-f64", rapier_f64),
            ("rapier3d (f32)", rapier_f32),
        ];
        for (name, run) in engines {
            match run(case, &scene) {
                Ok(m) => println!(
                    "| {} | {}–{} | {name} | {:.3} | {:.2e} |",
                    case.file,
                    case.from,
                    case.to,
                    m.step.as_secs_f64() * 1e3,
                    m.moved
                ),
                Err(e) => println!("| {} | | {name} | failed: {e} | |", case.file),
            }
        }
    }
}
