//! Holding (beyond the paper): the holding scenes of `scenes/` — an offset pair, a leaning
//! stack, a 1 kg cube under a 1000 kg one, a pyramid of 55 cubes, a tower of 100 cubes of 2 m at
//! 60 Hz — under each contact model with the default solver settings (warm start, the
//! penetration push in a position pass). The drift is the largest displacement of any body from
//! where it started. Rapier's figures on the same files are in `benches/README.md`
//! (`holding_comparison`), which keeps Rapier out of this tool's build.

use tatami_world::ContactModel;

use super::chart::{self, Axis, Chart, Legend, Series, Stroke};
use super::scenes::{self, SceneFile};
use super::table::{Table, record};
use super::{Outcome, Progress};

/// The CSV file.
pub const FILE: &str = "holding.csv";
/// Columns of [`FILE`].
pub const HEADER: [&str; 5] = ["scene", "model", "step", "time", "drift_m"];

/// Drift below which a scene is drawn at this floor on the logarithmic axis (m).
const FLOOR: f64 = 1e-9;

/// A holding scene, what the default model must meet (drift in m, measured from `from` s to
/// the end, as `crates/world/tests/holding.rs` does) and its chart.
struct Case {
    file: SceneFile,
    bound: f64,
    from: f64,
    chart: &'static str,
    files: [&'static str; 2],
}

/// The scenes.
const CASES: [Case; 5] = [
    Case {
        file: scenes::OFFSET_PAIR,
        from: 2.0,
        bound: 1e-3,
        chart: "holding_offset_pair",
        files: ["holding_offset_pair.svg", "holding_offset_pair.png"],
    },
    Case {
        file: scenes::LEANING_STACK,
        from: 2.0,
        bound: 1e-3,
        chart: "holding_leaning_stack",
        files: ["holding_leaning_stack.svg", "holding_leaning_stack.png"],
    },
    Case {
        file: scenes::HEAVY_ON_LIGHT,
        from: 0.0,
        bound: 1e-2,
        chart: "holding_heavy_on_light",
        files: ["holding_heavy_on_light.svg", "holding_heavy_on_light.png"],
    },
    Case {
        file: scenes::PYRAMID_55,
        from: 0.0,
        bound: 1e-2,
        chart: "holding_pyramid_55",
        files: ["holding_pyramid_55.svg", "holding_pyramid_55.png"],
    },
    Case {
        file: scenes::TOWER_100_60HZ,
        from: 0.0,
        bound: 1e-2,
        chart: "holding_tower_100_60hz",
        files: ["holding_tower_100_60hz.svg", "holding_tower_100_60hz.png"],
    },
];

/// One run: the drift from the start after every step (step 0 first), and over the case's
/// window.
struct Trace {
    scene: &'static str,
    model: ContactModel,
    dt: f64,
    drift: Vec<f64>,
    window_drift: f64,
}

/// The largest displacement of `world`'s bodies from `positions`.
fn largest_move(world: &tatami_world::World, positions: &[nalgebra::Point3<f64>]) -> f64 {
    world
        .bodies()
        .iter()
        .zip(positions)
        .map(|(b, p)| (b.position() - p).norm())
        .fold(0.0, f64::max)
}

/// Runs `case`'s scene under `model` for `steps` (the scene's own when `None`).
fn trace(case: &Case, model: ContactModel, steps: Option<usize>) -> Result<Trace, String> {
    let mut scene = case.file.load()?;
    scene.settings.model = model;
    let mut world = scene.world().map_err(|e| e.to_string())?;
    let positions =
        |w: &tatami_world::World| -> Vec<_> { w.bodies().iter().map(|b| b.position()).collect() };
    let start = positions(&world);
    let from = (case.from / scene.dt).round() as usize;
    let mut settled = start.clone();
    let mut drift = vec![0.0];
    for n in 1..=steps.unwrap_or(scene.steps) {
        scenes::step(&mut world, scene.dt)?;
        drift.push(largest_move(&world, &start));
        if n == from {
            settled = positions(&world);
        }
    }
    Ok(Trace {
        scene: case.file.name.trim_end_matches(".json"),
        model,
        dt: scene.dt,
        drift,
        window_drift: largest_move(&world, &settled),
    })
}

/// Runs every scene under every model, writes the CSV and one chart per scene.
pub fn run(quick: bool, out: &std::path::Path, progress: &Progress) -> Result<Outcome, String> {
    let bar = progress.bar("holding", (CASES.len() * ContactModel::ALL.len()) as u64);
    let mut traces = Vec::new();
    for case in &CASES {
        for model in ContactModel::ALL {
            traces.push(trace(case, model, quick.then_some(100))?);
            bar.inc(1);
        }
    }
    bar.finish_and_clear();

    let mut table = Table::create(out, FILE, &HEADER)?;
    for t in &traces {
        for (n, &d) in t.drift.iter().enumerate() {
            table.record(record![t.scene, t.model.name(), n, n as f64 * t.dt, d])?;
        }
    }
    table.finish()?;

    let mut files = vec![FILE];
    for case in &CASES {
        let (name, bound) = (case.file.name.trim_end_matches(".json"), &case.bound);
        let mine: Vec<&Trace> = traces.iter().filter(|t| t.scene == name).collect();
        let mut series: Vec<Series> = mine
            .iter()
            .map(|t| Series {
                name: t.model.name().to_owned(),
                points: t
                    .drift
                    .iter()
                    .enumerate()
                    .step_by(10)
                    .map(|(n, &d)| (n as f64 * t.dt, d.max(FLOOR)))
                    .collect(),
                stroke: Stroke::Line,
                colour: chart::model_colour(t.model),
            })
            .collect();
        let end = mine
            .iter()
            .map(|t| t.dt * (t.drift.len() - 1) as f64)
            .fold(0.0, f64::max);
        series.push(Series {
            name: format!("bound on the drift from {} s on: {bound} m", case.from),
            points: vec![(0.0, *bound), (end, *bound)],
            stroke: Stroke::Dashed,
            colour: chart::REFERENCE,
        });
        Chart {
            title: &format!("Holding: {name}"),
            x: Axis {
                label: "time (s)",
                log: false,
            },
            y: Axis {
                label: "largest drift from the start (m)",
                log: true,
            },
            series,
            legend: Legend::LowerRight,
        }
        .write(out, case.chart)?;
        files.extend(case.files);
    }
    Ok(report(&traces, files))
}

fn report(traces: &[Trace], files: Vec<&'static str>) -> Outcome {
    let mut text = String::from(
        "**Paper.** The face contact holds where per-vertex contacts rock and walk; shown on \
         symmetric towers only.\n\n\
         **Tatami.** The holding scenes with the default settings (up to 15 PGS sweeps \
         warm-started by contact feature, the energy-guarded shock pass, the penetration push in \
         a position pass), under each model. Drift = \
         the largest displacement of any body over the window the tests use (from 2 s on for the \
         pair and the leaning stack, which settle first; from the start for the others), then \
         from the start over the whole run, as charted.\n\n\
         | scene | window (s) | required (default model) | vertex | patch | face | face, whole run |\n\
         |---|---|---:|---:|---:|---:|---:|\n",
    );
    let mut held = 0;
    for case in &CASES {
        let (name, bound) = (case.file.name.trim_end_matches(".json"), &case.bound);
        let of = |model: ContactModel| traces.iter().find(|t| t.scene == name && t.model == model);
        let window = |model| of(model).map_or(f64::NAN, |t| t.window_drift);
        let whole = of(ContactModel::Face)
            .and_then(|t| t.drift.last().copied())
            .unwrap_or(f64::NAN);
        if window(ContactModel::Face) <= *bound {
            held += 1;
        }
        text.push_str(&format!(
            "| {name} | {}– | {bound} m | {:.2e} | {:.2e} | {:.2e} | {whole:.2e} |\n",
            case.from,
            window(ContactModel::Vertex),
            window(ContactModel::Patch),
            window(ContactModel::Face),
        ));
    }
    text.push_str(
        "\nUnder the face model neither cube of the 1000:1 stack moves: the shock pass sets the \
         heavy cube at rest on the light one, which rests on the floor. The tower of 100 at 60 Hz \
         stands under every model: all its contacts are new on the first step, and each starts \
         from the weight it carries (estimated from the top down), so the first solve already \
         holds the stack; from zero impulses, 15 sweeps carry the floor's reaction up only about \
         15 levels.\n",
    );
    for file in &files[1..] {
        if file.ends_with(".png") {
            text.push_str(&format!("\n![{file}]({file})\n"));
        }
    }
    Outcome {
        title: "Holding (default settings)",
        summary: format!(
            "face model within the bound on {held} of {} holding scenes",
            CASES.len()
        ),
        report: text,
        files,
    }
}
