//! Energy (beyond the paper): random scenes of boxes, spheres, cylinders and hulls dropped or
//! placed on a floor, none overlapping at the start (`tatami_world::dropped`), each run for its
//! 500 steps with the default settings. Nothing in the engine may make a scene's total energy
//! exceed its start: the bound is 0.1%. The tests run 200 of these scenes; this runs more.

use tatami_world::dropped::dropped_scene;

use super::table::{Table, record};
use super::{Outcome, Progress, scenes};

/// The CSV file.
pub const FILE: &str = "energy.csv";
/// Columns of [`FILE`].
pub const HEADER: [&str; 5] = [
    "scene",
    "bodies",
    "initial_energy_j",
    "largest_gain",
    "final_ratio",
];

/// Largest allowed gain, as a fraction of the initial energy.
const BOUND: f64 = 1e-3;

/// One scene's run.
struct Run {
    seed: u64,
    bodies: usize,
    initial: f64,
    largest_gain: f64,
    final_ratio: f64,
}

/// Runs scenes `0..count`, writes the CSV.
pub fn run(count: u64, out: &std::path::Path, progress: &Progress) -> Result<Outcome, String> {
    let bar = progress.bar("energy", count);
    let mut runs = Vec::new();
    for seed in 0..count {
        let scene = dropped_scene(seed);
        let mut world = scene.world().map_err(|e| format!("scene {seed}: {e}"))?;
        let initial = world.total_energy();
        let mut largest_gain: f64 = 0.0;
        for _ in 0..scene.steps {
            scenes::step(&mut world, scene.dt).map_err(|e| format!("scene {seed}: {e}"))?;
            largest_gain = largest_gain.max((world.total_energy() - initial) / initial.abs());
        }
        runs.push(Run {
            seed,
            bodies: scene.bodies.len() - 1,
            initial,
            largest_gain,
            final_ratio: world.total_energy() / initial,
        });
        bar.inc(1);
    }
    bar.finish_and_clear();

    let mut table = Table::create(out, FILE, &HEADER)?;
    for r in &runs {
        table.record(record![
            r.seed as usize,
            r.bodies,
            r.initial,
            r.largest_gain,
            r.final_ratio
        ])?;
    }
    table.finish()?;

    let worst = runs
        .iter()
        .max_by(|a, b| a.largest_gain.total_cmp(&b.largest_gain))
        .ok_or("no scenes were run")?;
    let over = runs.iter().filter(|r| r.largest_gain > BOUND).count();
    let lowest = runs
        .iter()
        .map(|r| r.final_ratio)
        .fold(f64::INFINITY, f64::min);
    let text = format!(
        "**Paper.** Not covered.\n\n\
         **Tatami.** {count} random scenes of 1 to 6 boxes, spheres, cylinders and hulls \
         (densities 200–3000 kg/m³, friction 0.1–1), apart at the start, half dropped from up \
         to 2 m and half placed within 1 cm of the floor, 500 steps of 0.01 s with the default \
         settings. Largest gain over its start of any scene at any step: {:.2e} of the initial \
         energy (scene {}; bound {BOUND:.0e}); {over} scenes over the bound. Energy is lost to \
         friction, to the landing and to semi-implicit Euler's free fall (½g²dt² per unit mass a \
         step): the lowest final ratio is {lowest:.3}.\n",
        worst.largest_gain, worst.seed,
    );
    Ok(Outcome {
        title: "Energy of random dropped scenes",
        summary: format!(
            "largest gain {:.1e} of the initial energy over {count} scenes (bound 1e-3); {over} over",
            worst.largest_gain
        ),
        report: text,
        files: vec![FILE],
    })
}
