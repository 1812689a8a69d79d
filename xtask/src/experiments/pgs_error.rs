//! PGS error vs iteration count (beyond the paper): the first step of a 10-cube tower solved by
//! PGS with k sweeps, against the direct solver's exact answer.
//!
//! The tower starts at rest with every face exactly touching, so the exact step leaves every
//! cube at rest: the direct solver (vertex model) must give zero velocities, and PGS's error is
//! the speed it leaves the cubes with — what makes a tower sink and walk when the solve is cut
//! short. Velocities rather than impulses are compared because a face resting on four corners
//! has many exact corner-impulse splits but one exact motion.

use std::time::Instant;

use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
use tatami_lcp::{Problem, direct};
use tatami_world::{ContactModel, DirectParams, Solver, WorldSettings};

use super::chart::{self, Axis, Chart, Series, Stroke};
use super::table::{Table, record};
use super::{Outcome, Progress, scenes, stack_timing};

/// The CSV file.
pub const FILE: &str = "pgs_error.csv";
/// Columns of [`FILE`].
pub const HEADER: [&str; 4] = [
    "model",
    "iterations",
    "linear_error_m_s",
    "angular_error_rad_s",
];

/// Cubes in the tower.
const CUBES: usize = 10;

/// Largest linear and angular velocity differences over the bodies of two solved problems.
fn velocity_error<P, Q>(a: &Problem<P>, b: &Problem<Q>) -> (f64, f64) {
    a.bodies
        .iter()
        .zip(&b.bodies)
        .fold((0.0_f64, 0.0_f64), |(lin, ang), (x, y)| {
            (
                lin.max((x.linear_velocity - y.linear_velocity).norm()),
                ang.max((x.angular_velocity - y.angular_velocity).norm()),
            )
        })
}

/// Runs the comparison, writes the CSV and the chart.
pub fn run(
    iterations: &[usize],
    out: &std::path::Path,
    progress: &Progress,
) -> Result<Outcome, String> {
    let template = scenes::TOWER.load()?;
    let dt = template.dt;
    let settings = |model: ContactModel, solver: Solver| WorldSettings {
        model,
        solver,
        ..template.settings
    };
    let direct_solver = Solver::Direct(DirectParams::default());
    let mut reference_world = stack_timing::tower(
        &template,
        CUBES,
        settings(ContactModel::Vertex, direct_solver),
    )?;
    let mut reference = reference_world
        .prepare_step(dt)
        .map_err(|e| e.to_string())?
        .clone();
    let started = Instant::now();
    direct::solve(&mut reference, &DirectParams::default())
        .map_err(|e| format!("direct solve: {e}"))?;
    let direct_ms = started.elapsed().as_secs_f64() * 1e3;
    let at_rest = reference
        .bodies
        .iter()
        .map(|b| b.linear_velocity.norm().max(b.angular_velocity.norm()))
        .fold(0.0, f64::max);

    let bar = progress.bar(
        "PGS error",
        (iterations.len() * ContactModel::ALL.len()) as u64,
    );
    let mut table = Table::create(out, FILE, &HEADER)?;
    let mut series = Vec::new();
    let mut at_paper = Vec::new();
    let mut workspace = PgsWorkspace::default();
    for model in ContactModel::ALL {
        let pgs_solver = Solver::Pgs(PgsParams::default());
        let mut world = stack_timing::tower(&template, CUBES, settings(model, pgs_solver))?;
        let problem = world.prepare_step(dt).map_err(|e| e.to_string())?.clone();
        let mut points = Vec::new();
        for &k in iterations {
            let mut solved = problem.clone();
            let params = PgsParams {
                iterations: k,
                ..PgsParams::default()
            };
            pgs::solve_in_place(&mut solved, &mut workspace, &params)
                .map_err(|e| format!("{} model, {k} sweeps: {e}", model.name()))?;
            let (linear, angular) = velocity_error(&solved, &reference);
            table.record(record![model.name(), k, linear, angular])?;
            points.push((k as f64, linear));
            if k == pgs::DEFAULT_ITERATIONS {
                at_paper.push((model, linear, angular));
            }
            bar.inc(1);
        }
        series.push(Series {
            name: model.name().to_owned(),
            points,
            stroke: Stroke::Markers,
            colour: chart::model_colour(model),
        });
    }
    table.finish()?;
    bar.finish_and_clear();
    Chart {
        title: "First step of a 10-cube tower: PGS vs the direct solver",
        x: Axis {
            label: "PGS sweeps",
            log: true,
        },
        y: Axis {
            label: "largest velocity error (m/s)",
            log: true,
        },
        series,
        legend: chart::Legend::LowerLeft,
    }
    .write(out, "pgs_error")?;

    let mut text = format!(
        "**Paper.** PGS with 15 iterations is the method; the direct (\"analytical\") solver is \
         not compared per iteration.\n\n\
         **Tatami.** A tower of {CUBES} cubes from `scenes/{}`, at rest and exactly touching; \
         one step of dt = {dt} s. The direct solver (Lemke, vertex model, {} rows) leaves every \
         cube at rest to {at_rest:.1e} m/s and took {direct_ms:.2} ms; the error of PGS is the \
         largest speed difference from it over the cubes after k sweeps from zero impulses. \
         An error `e` sinks or slides the tower by `e · dt` per step.\n\n\
         | model | error after {} sweeps (m/s) | angular (rad/s) |\n|---|---:|---:|\n",
        scenes::TOWER.name,
        reference.rows.len(),
        pgs::DEFAULT_ITERATIONS,
    );
    for (model, linear, angular) in &at_paper {
        text.push_str(&format!(
            "| {} | {linear:.2e} | {angular:.2e} |\n",
            model.name()
        ));
    }
    text.push_str("\n![PGS error vs sweeps](pgs_error.png)\n");
    let summary = at_paper
        .iter()
        .map(|(m, linear, _)| format!("{} {linear:.1e}", m.name()))
        .collect::<Vec<_>>()
        .join(", ");
    Ok(Outcome {
        title: "PGS error vs iterations (10-cube tower)",
        summary: if summary.is_empty() {
            format!("direct solve {direct_ms:.2} ms")
        } else {
            format!("error after 15 sweeps (m/s): {summary}")
        },
        report: text,
        files: vec![FILE, "pgs_error.svg", "pgs_error.png"],
    })
}
