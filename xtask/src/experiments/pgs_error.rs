//! PGS error vs iteration count (beyond the paper): the first step of a 10-cube tower and of an
//! off-centre pair solved by PGS with k sweeps, for every model, against the direct solver's
//! exact answer to that model's own problem.
//!
//! Both scenes start at rest with every face exactly touching and every centre of mass over its
//! support, so each model's exact step leaves every cube at rest; PGS's error is the speed it
//! leaves the cubes with — what makes a stack sink and walk when the solve is cut short.
//! Velocities rather than impulses are compared because a face resting on four corners has
//! many exact corner-impulse splits but one exact motion.

use std::time::Instant;

use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
use tatami_lcp::{Problem, direct};
use tatami_world::scene::Scene;
use tatami_world::{ContactModel, ContactProjection, DirectParams, Solver, World, WorldSettings};

use super::chart::{self, Axis, Chart, Series, Stroke};
use super::table::{Table, record};
use super::{Outcome, Progress, scenes, stack_timing};

/// The CSV file.
pub const FILE: &str = "pgs_error.csv";
/// Columns of [`FILE`].
pub const HEADER: [&str; 5] = [
    "model",
    "iterations",
    "linear_error_m_s",
    "angular_error_rad_s",
    "scene",
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

/// One model's first-step problem in one scene, with its exact answer.
struct Case {
    scene: &'static str,
    model: ContactModel,
    problem: Problem<ContactProjection>,
    exact: Problem<ContactProjection>,
    rows: usize,
    direct_ms: f64,
    at_rest: f64,
}

/// The first step of `world` and its exact solution.
fn case(scene: &'static str, model: ContactModel, mut world: World) -> Result<Case, String> {
    let dt = DT;
    let problem = world.prepare_step(dt).map_err(|e| e.to_string())?.clone();
    let mut exact = problem.clone();
    let started = Instant::now();
    direct::solve(&mut exact, &DirectParams::default())
        .map_err(|e| format!("{scene}, {} model, direct solve: {e}", model.name()))?;
    let direct_ms = started.elapsed().as_secs_f64() * 1e3;
    let at_rest = exact
        .bodies
        .iter()
        .map(|b| b.linear_velocity.norm().max(b.angular_velocity.norm()))
        .fold(0.0, f64::max);
    Ok(Case {
        scene,
        model,
        rows: problem.rows.len(),
        problem,
        exact,
        direct_ms,
        at_rest,
    })
}

/// Time step of both scenes (s).
const DT: f64 = 0.01;

/// Runs the comparison, writes the CSV and the chart.
pub fn run(
    iterations: &[usize],
    out: &std::path::Path,
    progress: &Progress,
) -> Result<Outcome, String> {
    let tower = scenes::TOWER.load()?;
    let pair = scenes::OFFSET_PAIR.load()?;
    let pgs_settings = |template: &Scene, model: ContactModel| WorldSettings {
        model,
        solver: Solver::Pgs(PgsParams::default()),
        ..template.settings
    };
    let mut cases = Vec::new();
    for model in ContactModel::ALL {
        let world = stack_timing::tower(&tower, CUBES, pgs_settings(&tower, model))?;
        cases.push(case("tower of 10", model, world)?);
        let mut scene = pair.clone();
        scene.settings = pgs_settings(&pair, model);
        cases.push(case(
            "offset pair",
            model,
            scene.world().map_err(|e| e.to_string())?,
        )?);
    }

    let bar = progress.bar("PGS error", (iterations.len() * cases.len()) as u64);
    let mut table = Table::create(out, FILE, &HEADER)?;
    let mut series = Vec::new();
    let mut at_paper = Vec::new();
    let mut workspace = PgsWorkspace::default();
    for case in &cases {
        let mut points = Vec::new();
        for &k in iterations {
            let mut solved = case.problem.clone();
            let params = PgsParams {
                iterations: k,
                ..PgsParams::default()
            };
            pgs::solve_in_place(&mut solved, &mut workspace, &params).map_err(|e| {
                format!(
                    "{}, {} model, {k} sweeps: {e}",
                    case.scene,
                    case.model.name()
                )
            })?;
            let (linear, angular) = velocity_error(&solved, &case.exact);
            table.record(record![case.model.name(), k, linear, angular, case.scene])?;
            points.push((k as f64, linear));
            if k == pgs::DEFAULT_ITERATIONS {
                at_paper.push((case, linear, angular));
            }
            bar.inc(1);
        }
        series.push(Series {
            name: format!("{}, {}", case.model.name(), case.scene),
            points,
            stroke: if case.scene == "offset pair" {
                Stroke::Dashed
            } else {
                Stroke::Markers
            },
            colour: chart::model_colour(case.model),
        });
    }
    table.finish()?;
    bar.finish_and_clear();
    Chart {
        title: "First step at rest: PGS vs each model's exact answer",
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
         **Tatami.** A tower of {CUBES} cubes from `scenes/{}` and the off-centre pair of \
         `scenes/{}`, at rest and exactly touching; one step of dt = {DT} s. For every model, \
         the direct solver (Lemke) solves that model's own problem exactly; the error of PGS is \
         the largest speed difference from it over the cubes after k sweeps from zero \
         impulses. An error `e` sinks or slides the stack by `e · dt` per step.\n\n\
         | scene | model | rows | exact answer at rest to (m/s) | direct solve (ms) | PGS error after {} sweeps (m/s) | angular (rad/s) |\n\
         |---|---|---:|---:|---:|---:|---:|\n",
        scenes::TOWER.name,
        scenes::OFFSET_PAIR.name,
        pgs::DEFAULT_ITERATIONS,
    );
    for (case, linear, angular) in &at_paper {
        text.push_str(&format!(
            "| {} | {} | {} | {:.1e} | {:.2} | {linear:.2e} | {angular:.2e} |\n",
            case.scene,
            case.model.name(),
            case.rows,
            case.at_rest,
            case.direct_ms,
        ));
    }
    text.push_str("\n![PGS error vs sweeps](pgs_error.png)\n");
    let summary = at_paper
        .iter()
        .filter(|(case, ..)| case.scene == "tower of 10")
        .map(|(case, linear, _)| format!("{} {linear:.1e}", case.model.name()))
        .collect::<Vec<_>>()
        .join(", ");
    Ok(Outcome {
        title: "PGS error vs iterations (2 stacks)",
        summary: if summary.is_empty() {
            "no sweep count of 15 measured".to_owned()
        } else {
            format!("tower error after 15 sweeps (m/s): {summary}")
        },
        report: text,
        files: vec![FILE, "pgs_error.svg", "pgs_error.png"],
    })
}
