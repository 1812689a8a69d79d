//! Holding (beyond the paper): the holding scenes of `scenes/` — an offset pair, a leaning
//! stack, a 1 kg cube under a 1000 kg one, a pyramid of 55 cubes, a tower of 100 cubes of 2 m at
//! 60 Hz — under each contact model with the default solver settings (warm start, the
//! penetration push in a position pass). The drift is the largest displacement of any body from
//! where it started. rapier3d-f64 runs the same files beside them (its defaults, sleeping off;
//! [`tatami_benches::RapierF64`], which the `holding_comparison` bench times too).

use nalgebra::Point3;
use plotters::style::RGBColor;
use tatami_benches::RapierF64;
use tatami_world::ContactModel;

use super::chart::{self, Axis, Chart, Legend, Series, Stroke};
use super::scenes::{self, SceneFile};
use super::table::{Table, record};
use super::{Outcome, Progress};

/// The CSV file.
pub const FILE: &str = "holding.csv";
/// Columns of [`FILE`]; `model` names the contact model, or `rapier3d-f64` for Rapier's run.
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

/// Who ran a trace: Tatami under a contact model, or rapier3d-f64 on the same file.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Engine {
    Tatami(ContactModel),
    Rapier,
}

impl Engine {
    fn name(self) -> &'static str {
        match self {
            Self::Tatami(model) => model.name(),
            Self::Rapier => "rapier3d-f64",
        }
    }

    fn colour(self) -> RGBColor {
        match self {
            Self::Tatami(model) => chart::model_colour(model),
            Self::Rapier => RGBColor(127, 127, 127),
        }
    }
}

/// One run: the drift from the start after every step (step 0 first), and over the case's
/// window.
struct Trace {
    scene: &'static str,
    engine: Engine,
    dt: f64,
    drift: Vec<f64>,
    /// Where the window began (s): the case's `from`, or half the run when the run is shorter
    /// (`--quick`).
    window_from: f64,
    window_drift: f64,
}

/// The largest distance between matching points of `now` and `then`.
fn largest_move(now: &[Point3<f64>], then: &[Point3<f64>]) -> f64 {
    now.iter()
        .zip(then)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
}

/// Steps `world` `steps` times at `dt`, recording the drift of its `positions` from the start
/// after every step and over `case`'s window.
fn record_drift<W>(
    case: &Case,
    engine: Engine,
    (dt, steps): (f64, usize),
    world: &mut W,
    step: impl Fn(&mut W) -> Result<(), String>,
    positions: impl Fn(&W) -> Vec<Point3<f64>>,
) -> Result<Trace, String> {
    let start = positions(world);
    let from = ((case.from / dt).round() as usize).min(steps / 2);
    let mut settled = start.clone();
    let mut drift = vec![0.0];
    for n in 1..=steps {
        step(world)?;
        let now = positions(world);
        drift.push(largest_move(&now, &start));
        if n == from {
            settled = now;
        }
    }
    Ok(Trace {
        scene: case.file.name.trim_end_matches(".json"),
        engine,
        dt,
        drift,
        window_from: from as f64 * dt,
        window_drift: largest_move(&positions(world), &settled),
    })
}

/// Runs `case`'s scene in `engine` for `steps` (the scene's own when `None`).
fn trace(case: &Case, engine: Engine, steps: Option<usize>) -> Result<Trace, String> {
    let mut scene = case.file.load()?;
    let run = (scene.dt, steps.unwrap_or(scene.steps));
    match engine {
        Engine::Tatami(model) => {
            scene.settings.model = model;
            let mut world = scene.world().map_err(|e| e.to_string())?;
            record_drift(
                case,
                engine,
                run,
                &mut world,
                |w| scenes::step(w, scene.dt),
                |w| w.bodies().iter().map(|b| b.position()).collect(),
            )
        }
        Engine::Rapier => {
            let mut world = RapierF64::new(&scene)?;
            record_drift(
                case,
                engine,
                run,
                &mut world,
                |w| {
                    w.step();
                    Ok(())
                },
                |w| w.positions().into_iter().map(Point3::from).collect(),
            )
        }
    }
}

/// Runs every scene under every model, writes the CSV and one chart per scene.
pub fn run(quick: bool, out: &std::path::Path, progress: &Progress) -> Result<Outcome, String> {
    let engines: Vec<Engine> = ContactModel::ALL
        .into_iter()
        .map(Engine::Tatami)
        .chain([Engine::Rapier])
        .collect();
    let bar = progress.bar("holding", (CASES.len() * engines.len()) as u64);
    let mut traces = Vec::new();
    for case in &CASES {
        for &engine in &engines {
            traces.push(trace(case, engine, quick.then_some(100))?);
            bar.inc(1);
        }
    }
    bar.finish_and_clear();

    let mut table = Table::create(out, FILE, &HEADER)?;
    for t in &traces {
        for (n, &d) in t.drift.iter().enumerate() {
            table.record(record![t.scene, t.engine.name(), n, n as f64 * t.dt, d])?;
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
                name: t.engine.name().to_owned(),
                points: t
                    .drift
                    .iter()
                    .enumerate()
                    .step_by(10)
                    .map(|(n, &d)| (n as f64 * t.dt, d.max(FLOOR)))
                    .collect(),
                stroke: Stroke::Line,
                colour: t.engine.colour(),
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
         **Tatami.** The holding scenes with the default settings (up to 12 PGS sweeps \
         warm-started from the last step's impulses, the energy-guarded shock pass, the penetration push in \
         a position pass), under each model, and rapier3d-f64 (its defaults, sleeping off) on the \
         same files. Drift = \
         the largest displacement of any body over the window the tests use (from 2 s on for the \
         pair and the leaning stack, where the tests allow a first settling; from the start for \
         the others; from \
         half the run when the run is shorter, as with `--quick`), then from the start over the \
         whole run, as charted.\n\n\
         | scene | window (s) | required (default model) | vertex | patch | face | face, whole run | rapier3d-f64 |\n\
         |---|---|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut held = 0;
    for case in &CASES {
        let (name, bound) = (case.file.name.trim_end_matches(".json"), &case.bound);
        let of = |engine: Engine| {
            traces
                .iter()
                .find(|t| t.scene == name && t.engine == engine)
        };
        let window = |engine| of(engine).map_or(f64::NAN, |t| t.window_drift);
        let face = Engine::Tatami(ContactModel::Face);
        let from = of(face).map_or(case.from, |t| t.window_from);
        let whole = of(face)
            .and_then(|t| t.drift.last().copied())
            .unwrap_or(f64::NAN);
        if window(face) <= *bound {
            held += 1;
        }
        text.push_str(&format!(
            "| {name} | {from}– | {bound} m | {:.2e} | {:.2e} | {:.2e} | {whole:.2e} | {:.2e} |\n",
            window(Engine::Tatami(ContactModel::Vertex)),
            window(Engine::Tatami(ContactModel::Patch)),
            window(face),
            window(Engine::Rapier),
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
