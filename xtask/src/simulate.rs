//! `cargo xtask simulate`: run a scene, write its trajectory, summarise the timing.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::time::{Duration, Instant};

use tatami_world::scene::{MAX_STEPS, Scene};
use tatami_world::{ContactModel, DirectParams, Solver};

use crate::contacts::ContactWriter;
use crate::trajectory::TrajectoryWriter;

/// Options of `cargo xtask simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The scene file (JSON).
    scene: PathBuf,
    #[command(flatten)]
    overrides: Overrides,
    /// Record every K-th step (step 0 and the last step are always recorded).
    #[arg(long, default_value_t = 1)]
    every: usize,
    /// Trajectory file; standard output without it.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also write every recorded step's contact wrenches to this CSV file.
    #[arg(long)]
    contacts: Option<PathBuf>,
}

/// Options that override the scene's values.
#[derive(Debug, clap::Args)]
pub struct Overrides {
    /// Contact model.
    #[arg(long, value_parser = parse_model)]
    model: Option<ContactModel>,
    /// Number of steps.
    #[arg(long)]
    steps: Option<usize>,
    /// Time step (s).
    #[arg(long)]
    dt: Option<f64>,
    /// PGS iterations per step.
    #[arg(long)]
    iterations: Option<usize>,
    /// Solver: pgs or direct.
    #[arg(long, value_parser = ["pgs", "direct"])]
    solver: Option<String>,
}

fn parse_model(name: &str) -> Result<ContactModel, String> {
    ContactModel::from_name(name).ok_or_else(|| {
        let known: Vec<_> = ContactModel::ALL.iter().map(|m| m.name()).collect();
        format!(
            "unknown model `{name}`, expected one of {}",
            known.join(", ")
        )
    })
}

/// Loads the scene at `path` with the command line's `overrides`; with the direct solver, says
/// in one line on standard error which PGS settings it ignores.
pub fn load(path: &std::path::Path, overrides: &Overrides) -> Result<Scene, String> {
    let mut scene = Scene::load(path).map_err(|e| e.to_string())?;
    overrides.apply(&mut scene)?;
    if matches!(scene.settings.solver, Solver::Direct(_)) {
        let mut ignored: Vec<String> = scene
            .pgs_settings
            .iter()
            .map(|s| format!("`{s}`"))
            .collect();
        if overrides.iterations.is_some() {
            ignored.push("--iterations".into());
        }
        if !ignored.is_empty() {
            eprintln!(
                "note: the direct solver ignores the PGS settings {}",
                ignored.join(", ")
            );
        }
    }
    Ok(scene)
}

/// Runs the scene and writes the trajectory.
pub fn run(args: &Args) -> Result<(), String> {
    if args.every == 0 {
        return Err("--every must be ≥ 1".into());
    }
    let scene = load(&args.scene, &args.overrides)?;
    let mut world = scene.world().map_err(|e| e.to_string())?;
    let output: Box<dyn Write> = match &args.out {
        Some(path) => Box::new(BufWriter::new(
            File::create(path).map_err(|e| format!("{}: {e}", path.display()))?,
        )),
        None => Box::new(BufWriter::new(std::io::stdout().lock())),
    };
    let mut writer = TrajectoryWriter::new(output).map_err(|e| e.to_string())?;
    writer.record(0, &world).map_err(|e| e.to_string())?;
    let mut contacts = match &args.contacts {
        Some(path) => Some(
            ContactWriter::new(BufWriter::new(
                File::create(path).map_err(|e| format!("{}: {e}", path.display()))?,
            ))
            .map_err(|e| e.to_string())?,
        ),
        None => None,
    };
    let mut solver_time = Duration::ZERO;
    let start = Instant::now();
    for step in 1..=scene.steps {
        world
            .step(scene.dt)
            .map_err(|e| format!("step {step}: {e}"))?;
        solver_time += world.timings().solve;
        if step % args.every == 0 || step == scene.steps {
            writer.record(step, &world).map_err(|e| e.to_string())?;
            if let Some(contacts) = &mut contacts {
                contacts.record(step, &world).map_err(|e| e.to_string())?;
            }
        }
    }
    let wall = start.elapsed();
    writer.finish().map_err(|e| e.to_string())?;
    if let Some(contacts) = contacts {
        contacts.finish().map_err(|e| e.to_string())?;
    }
    let per_step = |d: Duration| d.as_secs_f64() * 1e3 / scene.steps.max(1) as f64;
    eprintln!(
        "{} steps of {} bodies ({} model): {:.4} ms/step wall, {:.4} ms/step in the solver",
        scene.steps,
        world.bodies().len(),
        world.settings().model.name(),
        per_step(wall),
        per_step(solver_time),
    );
    Ok(())
}

impl Overrides {
    /// Command-line values replace the scene's.
    fn apply(&self, scene: &mut Scene) -> Result<(), String> {
        let args = self;
        if let Some(dt) = args.dt {
            if !(dt.is_finite() && dt > 0.0 && dt <= tatami_world::MAX_TIME_STEP) {
                return Err(format!("--dt must be > 0 and at most 1 s, got {dt}"));
            }
            scene.dt = dt;
        }
        if let Some(steps) = args.steps {
            if !(1..=MAX_STEPS).contains(&steps) {
                return Err(format!("--steps must be 1 to {MAX_STEPS}, got {steps}"));
            }
            scene.steps = steps;
        }
        if let Some(model) = args.model {
            scene.settings.model = model;
        }
        match args.solver.as_deref() {
            Some("direct") => scene.settings.solver = Solver::Direct(DirectParams::default()),
            Some(_) if !matches!(scene.settings.solver, Solver::Pgs(_)) => {
                scene.settings.solver = Solver::default();
            }
            _ => {}
        }
        if let Some(iterations) = args.iterations {
            if iterations == 0 {
                return Err("--iterations must be ≥ 1".into());
            }
            if let Solver::Pgs(params) = &mut scene.settings.solver {
                params.iterations = iterations;
            }
        }
        Ok(())
    }
}
