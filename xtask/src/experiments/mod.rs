//! `cargo xtask experiments`: the paper's experiments and Tatami's own, as CSV files, charts
//! (SVG and PNG) and `report.md`, which states for each figure what the paper claims and what
//! Tatami measured on this machine.
//!
//! Each experiment starts from a scene file of `scenes/` (compiled in), so any figure can be
//! rerun alone with `cargo xtask simulate`, and returns an [`Outcome`]: the files it wrote, its
//! section of the report and one line of the summary table.

mod chart;
mod edge_toppling;
mod energy;
mod free_rotation;
mod friction_isotropy;
mod holding;
mod ledge;
mod machine;
mod pgs_error;
mod planar_sliding;
mod point_toppling;
mod report;
mod scenes;
mod spin_down;
mod spinning_top;
mod stack_timing;
mod table;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use machine::Machine;

/// Tallest tower the stack-timing experiment accepts.
pub const MAX_TOWER: usize = 1000;

/// Options of `cargo xtask experiments`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Folder for the CSV files, charts and report.md (created if missing).
    #[arg(long, default_value = "target/experiments")]
    out: PathBuf,
    /// Small sizes and short runs: a smoke test of every experiment and every output file.
    #[arg(long)]
    quick: bool,
    /// Tower heights of the stack-timing experiment, comma-separated (1 to 1000 cubes).
    #[arg(long, value_delimiter = ',', value_parser = parse_size)]
    sizes: Option<Vec<usize>>,
}

fn parse_size(text: &str) -> Result<usize, String> {
    let n: usize = text
        .trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a whole number of cubes"))?;
    if (1..=MAX_TOWER).contains(&n) {
        Ok(n)
    } else {
        Err(format!("towers have 1 to {MAX_TOWER} cubes, got {n}"))
    }
}

/// What an experiment produced.
pub struct Outcome {
    /// Section title in the report and name in the summary.
    pub title: &'static str,
    /// One line for the summary table.
    pub summary: String,
    /// The report's section (Markdown).
    pub report: String,
    /// Files written into the output folder.
    pub files: Vec<&'static str>,
}

/// Progress bars on standard error; drawn only when it is a terminal.
pub struct Progress;

impl Progress {
    /// A bar of `len` steps named `name`.
    pub fn bar(&self, name: &str, len: u64) -> ProgressBar {
        let style = ProgressStyle::with_template("{prefix:>16} [{bar:32}] {pos}/{len} {msg}")
            .map(|s| s.progress_chars("=> "))
            .unwrap_or_else(|_| ProgressStyle::default_bar());
        ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr())
            .with_style(style)
            .with_prefix(name.to_owned())
    }
}

/// The sizes of one run of all experiments.
#[derive(Debug, Clone)]
struct Plan {
    quick: bool,
    stack: stack_timing::Plan,
    /// Ledge overhangs (m) of the sweep.
    overhangs: Vec<f64>,
    /// PGS sweep counts compared with the direct solver.
    iterations: Vec<usize>,
    /// Launch angles (°) of the friction-isotropy slides.
    slide_angles: Vec<f64>,
    /// Random dropped scenes of the energy run.
    energy_scenes: u64,
}

impl Plan {
    fn new(args: &Args) -> Self {
        let (sizes, steps, direct_steps, overhangs, iterations) = if args.quick {
            (vec![1, 2, 5], 100, 10, vec![-0.2, 0.2], vec![1, 5, 15, 50])
        } else {
            (
                vec![1, 2, 5, 10, 20, 50, 100],
                1000,
                30,
                vec![
                    -0.9, -0.5, -0.2, -0.1, -0.05, -0.02, 0.02, 0.05, 0.1, 0.2, 0.5, 0.9,
                ],
                vec![
                    1, 2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100, 150, 200, 300, 500, 1000,
                ],
            )
        };
        let slide_angles = if args.quick {
            vec![0.0, 30.0, 45.0]
        } else {
            (0..=12).map(|k| 7.5 * f64::from(k)).collect()
        };
        Self {
            quick: args.quick,
            stack: stack_timing::Plan {
                sizes: args.sizes.clone().unwrap_or(sizes),
                steps,
                direct_steps,
                repeats: if args.quick { 5 } else { 50 },
                direct_limit: Duration::from_millis(200),
            },
            overhangs,
            iterations,
            slide_angles,
            energy_scenes: if args.quick { 20 } else { 2000 },
        }
    }
}

/// Runs every experiment and writes the files, the report and the summary.
pub fn run(args: &Args) -> Result<(), String> {
    let plan = Plan::new(args);
    let out = &args.out;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let machine = Machine::current();
    let progress = Progress;
    let start = Instant::now();
    type Experiment<'a> = Box<dyn Fn() -> Result<Outcome, String> + 'a>;
    let experiments: Vec<Experiment> = vec![
        Box::new(|| stack_timing::run(&plan.stack, out, &progress)),
        Box::new(|| edge_toppling::run(out, &progress)),
        Box::new(|| point_toppling::run(out, &progress)),
        Box::new(|| ledge::run(&plan.overhangs, out, &progress)),
        Box::new(|| spin_down::run(out, &progress)),
        Box::new(|| planar_sliding::run(out, &progress)),
        Box::new(|| pgs_error::run(&plan.iterations, out, &progress)),
        Box::new(|| friction_isotropy::run(&plan.slide_angles, out, &progress)),
        Box::new(|| free_rotation::run(out, &progress)),
        Box::new(|| spinning_top::run(out, &progress)),
        Box::new(|| holding::run(plan.quick, out, &progress)),
        Box::new(|| energy::run(plan.energy_scenes, out, &progress)),
    ];
    let mut outcomes = Vec::new();
    for experiment in &experiments {
        let begun = Instant::now();
        let outcome = experiment()?;
        outcomes.push((outcome, begun.elapsed()));
    }
    let report = report::write(out, &machine, plan.quick, &outcomes)?;
    println!("{:<40} {:>7}  result", "experiment", "time");
    for (outcome, took) in &outcomes {
        println!(
            "{:<40} {:>6.1}s  {}",
            outcome.title,
            took.as_secs_f64(),
            outcome.summary
        );
    }
    println!(
        "{} files and {} in {} ({:.1} s on {machine})",
        outcomes.iter().map(|(o, _)| o.files.len()).sum::<usize>(),
        report.display(),
        out.display(),
        start.elapsed().as_secs_f64(),
    );
    Ok(())
}
