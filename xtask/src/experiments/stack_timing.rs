//! Stack timing (paper fig. 4): towers of N cubes of 2 m on a fixed floor, 15 PGS sweeps; the
//! time of the solver call alone per model, rows per step, and whether the tower stands.
//!
//! The solver call is timed by the world (`StepTimings::solve`), so collision and integration
//! are left out as in the paper. The median over the steps after a warm-up of 10% resists the
//! shared machine's noise; the 90th percentile shows the spread. The direct solver runs every
//! model over fewer steps, and stops growing N for a model once a step takes longer than the
//! plan allows.

use std::time::{Duration, Instant};

use tatami_lcp::pgs::{self, PgsWorkspace};
use tatami_lcp::{Problem, direct};

use tatami_world::scene::Scene;
use tatami_world::{
    ContactModel, ContactProjection, DirectParams, PgsParams, Solver, WarmStart, World,
    WorldSettings,
};

use super::chart::{self, Axis, Chart, Series, Stroke};
use super::table::{Table, record};
use super::{Outcome, Progress, scenes};

/// The CSV file and its header.
pub const FILE: &str = "stack_timing.csv";
/// Columns of [`FILE`].
pub const HEADER: [&str; 14] = [
    "model",
    "solver",
    "warm_start",
    "cubes",
    "steps",
    "rows",
    "solver_ms_median",
    "solver_ms_p90",
    "run_solver_ms_median",
    "top_drop_m",
    "top_shift_m",
    "max_penetration_m",
    "stands",
    "failure",
];

/// Sizes and run lengths.
#[derive(Debug, Clone)]
pub struct Plan {
    /// Tower heights, in cubes.
    pub sizes: Vec<usize>,
    /// Steps of each PGS run (10 s at the scene's dt in the full run).
    pub steps: usize,
    /// Steps of each direct run.
    pub direct_steps: usize,
    /// Timed solves of each tower's first step (PGS; the direct solver gets a tenth).
    pub repeats: usize,
    /// The direct solver stops at the first N whose median solve takes longer.
    pub direct_limit: Duration,
}

/// One solver configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Config {
    model: ContactModel,
    direct: bool,
    warm_start: bool,
    /// PGS followed by a shock-propagation pass.
    shock: bool,
}

impl Config {
    fn solver(&self) -> Solver {
        if self.direct {
            Solver::Direct(DirectParams::default())
        } else {
            Solver::Pgs(PgsParams {
                warm_start: if self.warm_start {
                    WarmStart::On
                } else {
                    WarmStart::Off
                },
                ..PgsParams::default()
            })
        }
    }

    /// The tower scene's settings with this configuration's model and solver; the paper's
    /// configurations (PGS from zero impulses, no shock pass) push penetration out as
    /// Springhead does.
    fn settings(&self, scene: &Scene) -> WorldSettings {
        let settings = WorldSettings {
            model: self.model,
            solver: self.solver(),
            shock_propagation: self.shock,
            ..scene.settings
        };
        if self.direct || self.warm_start || self.shock {
            settings
        } else {
            scenes::springhead_penetration(settings)
        }
    }

    fn label(&self) -> String {
        match (self.direct, self.warm_start, self.shock) {
            (true, _, _) => format!("direct ({})", self.model.name()),
            (false, _, true) => format!("{}, shock propagation", self.model.name()),
            (false, false, false) => self.model.name().to_owned(),
            (false, true, false) => format!("{}, warm start", self.model.name()),
        }
    }

    /// The `solver` column of the CSV.
    fn solver_name(&self) -> &'static str {
        match (self.direct, self.shock) {
            (true, _) => "direct",
            (false, true) => "pgs+shock",
            (false, false) => "pgs",
        }
    }
}

/// What one tower run measured.
#[derive(Debug, Clone)]
struct Run {
    config: Config,
    cubes: usize,
    steps: usize,
    rows: usize,
    /// Solver call on the tower's first step, over repeats.
    median_ms: f64,
    p90_ms: f64,
    /// The world's solve stage during the run (the contact set's warm start and keeping of
    /// impulses are timed with the rows, `StepTimings::setup`, not here).
    run_median_ms: f64,
    top_drop: f64,
    top_shift: f64,
    max_penetration: f64,
    stands: bool,
    /// The step error that ended the run early, if one did (the run's figures cover the steps
    /// before it).
    failure: Option<String>,
}

impl Run {
    /// How far the top cube moved (m).
    fn drift(&self) -> f64 {
        self.top_shift.hypot(self.top_drop)
    }
}

/// A tower of `cubes` cubes built from the scene's floor (body 0) and first two cubes (their
/// spacing is the tower's pitch).
pub(super) fn tower(
    template: &Scene,
    cubes: usize,
    settings: WorldSettings,
) -> Result<World, String> {
    let [floor, first, second, ..] = template.bodies.as_slice() else {
        return Err(format!(
            "{}: needs a floor and two cubes",
            scenes::TOWER.name
        ));
    };
    let pitch = second.position - first.position;
    let mut scene = template.clone();
    scene.bodies = std::iter::once(floor.clone())
        .chain((0..cubes).map(|k| {
            let mut cube = first.clone();
            cube.name = Some(format!("cube{k}"));
            cube.position += pitch * k as f64;
            cube
        }))
        .collect();
    scene.settings = settings;
    scene.world().map_err(|e| e.to_string())
}

/// Median and 90th percentile (ms) of `samples`.
fn quantiles(mut samples: Vec<Duration>) -> (f64, f64) {
    samples.sort_unstable();
    let at = |q: f64| {
        let i = ((samples.len().max(1) - 1) as f64 * q).round() as usize;
        samples.get(i).map_or(f64::NAN, Duration::as_secs_f64) * 1e3
    };
    (at(0.5), at(0.9))
}

/// Solves copies of each case's problem `repeats` times (plus a fifth as warm-up) and returns
/// the times of the solver calls alone, per case. The cases are interleaved: each round solves
/// every problem once, in turn, so all of them meet the same machine. A shared machine's speed
/// drifts over seconds; timing one configuration after the other put that drift into their
/// ratio (the face/vertex ratio at 100 cubes read anywhere from 0.36 to 0.81 over four runs).
fn time_solves(
    cases: &[(Problem<ContactProjection>, Solver)],
    repeats: usize,
) -> Result<Vec<Vec<Duration>>, String> {
    let mut workspaces = vec![PgsWorkspace::default(); cases.len()];
    let warm_up = repeats.div_ceil(5);
    let mut times = vec![Vec::with_capacity(repeats); cases.len()];
    for i in 0..warm_up + repeats {
        for (((problem, solver), workspace), times) in
            cases.iter().zip(&mut workspaces).zip(&mut times)
        {
            let mut copy = problem.clone();
            let started = Instant::now();
            match solver {
                Solver::Pgs(params) => pgs::solve_in_place(&mut copy, workspace, params).map(drop),
                Solver::Direct(params) => direct::solve(&mut copy, params).map(drop),
            }
            .map_err(|e| e.to_string())?;
            if i >= warm_up {
                times.push(started.elapsed());
            }
        }
    }
    Ok(times)
}

/// Measures `configs` on a tower of `cubes`: their first-step solves timed together (see
/// [`time_solves`]), then a run of `steps` steps each.
fn measure(
    template: &Scene,
    configs: &[Config],
    cubes: usize,
    steps: usize,
    repeats: usize,
) -> Result<Vec<Run>, String> {
    let mut cases = Vec::with_capacity(configs.len());
    for config in configs {
        let mut world = tower(template, cubes, config.settings(template))?;
        let problem = world.prepare_step(template.dt).map_err(|e| e.to_string())?;
        cases.push((problem.clone(), config.solver()));
    }
    let fewest_rows = cases.iter().map(|(p, _)| p.rows.len()).min().unwrap_or(0);
    // Small towers solve in microseconds: enough repeats for ~100k row sweeps keep the clock's
    // resolution and the machine's noise out of the median.
    let repeats = if configs.iter().any(|c| c.direct) {
        repeats
    } else {
        repeats.max(100_000 / fewest_rows.max(1))
    };
    let timed = time_solves(&cases, repeats);
    let mut runs = Vec::with_capacity(configs.len());
    for (k, (config, (problem, _))) in configs.iter().zip(&cases).enumerate() {
        let rows = problem.rows.len();
        let (median_ms, p90_ms) = match &timed {
            Ok(times) => quantiles(times[k].clone()),
            Err(e) => {
                runs.push(Run {
                    config: *config,
                    cubes,
                    steps: 0,
                    rows,
                    median_ms: f64::NAN,
                    p90_ms: f64::NAN,
                    run_median_ms: f64::NAN,
                    top_drop: 0.0,
                    top_shift: 0.0,
                    max_penetration: 0.0,
                    stands: false,
                    failure: Some(format!("first step: {e}")),
                });
                continue;
            }
        };
        runs.push(Run {
            rows,
            median_ms,
            p90_ms,
            ..simulate(template, *config, cubes, steps)?
        });
    }
    Ok(runs)
}

/// Runs `config`'s tower for `steps` steps; the first step's figures (rows, solve times) are
/// left for the caller.
fn simulate(template: &Scene, config: Config, cubes: usize, steps: usize) -> Result<Run, String> {
    let mut world = tower(template, cubes, config.settings(template))?;
    let top = world.bodies().len() - 1;
    let start = world.bodies()[top].position();
    let pitch = if cubes > 1 {
        (world.bodies()[2].position() - world.bodies()[1].position()).norm()
    } else {
        start.z * 2.0
    };
    let warm_up = steps / 10;
    let mut in_run = Vec::with_capacity(steps);
    let mut max_penetration = 0.0_f64;
    let mut failure = None;
    for step in 0..steps {
        if let Err(e) = scenes::step(&mut world, template.dt) {
            failure = Some(e);
            break;
        }
        if step >= warm_up {
            in_run.push(world.timings().solve);
        }
        for contact in world.contacts() {
            max_penetration = contact
                .depths
                .iter()
                .fold(max_penetration, |m, &d| m.max(d));
        }
    }
    let moved = world.bodies()[top].position() - start;
    let top_drop = -moved.z;
    Ok(Run {
        config,
        cubes,
        steps: world.steps(),
        rows: 0,
        median_ms: f64::NAN,
        p90_ms: f64::NAN,
        run_median_ms: quantiles(in_run).0,
        top_drop,
        top_shift: moved.xy().norm(),
        max_penetration,
        stands: failure.is_none() && top_drop < 0.5 * pitch,
        failure,
    })
}

/// Runs every configuration on every size, writes the CSV and the chart.
pub fn run(plan: &Plan, out: &std::path::Path, progress: &Progress) -> Result<Outcome, String> {
    let template = scenes::TOWER.load()?;
    let mut configs: Vec<Config> = Vec::new();
    for warm_start in [false, true] {
        for model in ContactModel::ALL {
            configs.push(Config {
                model,
                direct: false,
                warm_start,
                shock: false,
            });
        }
    }
    let shock = Config {
        model: ContactModel::Face,
        direct: false,
        warm_start: false,
        shock: true,
    };
    configs.push(shock);
    let directs = ContactModel::ALL.map(|model| Config {
        model,
        direct: true,
        warm_start: false,
        shock: false,
    });
    let bar = progress.bar(
        "stack timing",
        (plan.sizes.len() * (configs.len() + directs.len())) as u64,
    );
    let mut runs = Vec::new();
    for &cubes in &plan.sizes {
        bar.set_message(format!("PGS × {cubes}"));
        for run in measure(&template, &configs, cubes, plan.steps, plan.repeats)? {
            if let Some(failure) = &run.failure {
                return Err(format!(
                    "{} tower of {cubes}: {failure}",
                    run.config.label()
                ));
            }
            runs.push(run);
            bar.inc(1);
        }
    }
    // Per model, the first height at which the direct solver was too slow or failed.
    let mut direct_stopped = Vec::new();
    for direct in directs {
        let mut stopped = None;
        for &cubes in &plan.sizes {
            bar.set_message(format!("{} × {cubes}", direct.label()));
            if stopped.is_none() {
                let measured = measure(
                    &template,
                    &[direct],
                    cubes,
                    plan.direct_steps,
                    plan.repeats.div_ceil(10),
                )?;
                for run in measured {
                    let too_slow = run.median_ms > plan.direct_limit.as_secs_f64() * 1e3;
                    if too_slow || run.median_ms.is_nan() {
                        stopped = Some(cubes);
                    }
                    runs.push(run);
                }
            }
            bar.inc(1);
        }
        if let Some(cubes) = stopped {
            direct_stopped.push((direct.model, cubes));
        }
    }
    bar.finish_and_clear();

    let mut table = Table::create(out, FILE, &HEADER)?;
    for r in &runs {
        table.record(record![
            r.config.model.name(),
            r.config.solver_name(),
            if r.config.warm_start { "on" } else { "off" },
            r.cubes,
            r.steps,
            r.rows,
            r.median_ms,
            r.p90_ms,
            r.run_median_ms,
            r.top_drop,
            r.top_shift,
            r.max_penetration,
            r.stands,
            r.failure.as_deref().unwrap_or(""),
        ])?;
    }
    table.finish()?;

    let series = configs
        .iter()
        .filter(|c| !c.warm_start)
        .chain(&directs)
        .map(|c| Series {
            name: c.label(),
            points: runs
                .iter()
                .filter(|r| r.config == *c)
                .map(|r| (r.cubes as f64, r.median_ms))
                .collect(),
            stroke: if c.direct || c.shock {
                Stroke::Dashed
            } else {
                Stroke::Markers
            },
            colour: chart::model_colour(c.model),
        })
        .collect();
    Chart {
        title: "Solver time per step vs tower height (15 PGS sweeps)",
        x: Axis {
            label: "cubes in the tower",
            log: true,
        },
        y: Axis {
            label: "solver time per step (ms, median)",
            log: true,
        },
        series,
        legend: chart::Legend::UpperLeft,
    }
    .write(out, "stack_timing")?;

    Ok(report(plan, &runs, &direct_stopped))
}

fn find(runs: &[Run], model: ContactModel, warm_start: bool, cubes: usize) -> Option<&Run> {
    runs.iter().find(|r| {
        !r.config.direct
            && !r.config.shock
            && r.config.model == model
            && r.config.warm_start == warm_start
            && r.cubes == cubes
    })
}

/// Where Tatami agrees with the paper and where it goes further or disagrees, from the data.
fn verdict(plan: &Plan, runs: &[Run]) -> String {
    let ratios: Vec<f64> = plan
        .sizes
        .iter()
        .filter_map(|&n| {
            let v = find(runs, ContactModel::Vertex, false, n)?;
            let f = find(runs, ContactModel::Face, false, n)?;
            Some(f.median_ms / v.median_ms)
        })
        .collect();
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &r| {
            (lo.min(r), hi.max(r))
        });
    // The tallest tower up to which every run of the model stands.
    let stands_to = |model: ContactModel| {
        plan.sizes
            .iter()
            .take_while(|&&n| find(runs, model, false, n).is_some_and(|r| r.stands))
            .last()
            .map_or("none".to_owned(), |n| format!("{n} cubes"))
    };
    let mut text = String::from("\n**Agreement.** ");
    if ratios.is_empty() {
        return text + "No tower was measured.\n";
    }
    text.push_str(&format!(
        "The face model's solver call takes {lo:.2}–{hi:.2}× the vertex model's time over \
         these towers: the paper's claim holds, by the row count (6 rows per face contact \
         against 12). ",
    ));
    text.push_str(&format!(
        "The paper says nothing of stability; with its settings (15 sweeps, no warm start) \
         the towers stand up to: vertex {}, patch {}, face {}. Fifteen sweeps from zero \
         impulses cannot carry a tall tower's weight (section 6 measures the error), so the \
         per-vertex towers creep and fall; one wrench per face removes the corner-to-corner \
         rocking and the face model's towers stand far taller, but not indefinitely.",
        stands_to(ContactModel::Vertex),
        stands_to(ContactModel::Patch),
        stands_to(ContactModel::Face),
    ));
    let shocked: Vec<&Run> = runs.iter().filter(|r| r.config.shock).collect();
    if let Some(tallest) = shocked.iter().filter(|r| r.stands).max_by_key(|r| r.cubes) {
        let worst = shocked.iter().map(|r| r.drift()).fold(0.0, f64::max);
        text.push_str(&format!(
            " Beyond the paper: a shock-propagation pass after the sweeps lets the face \
             model's towers stand up to {} cubes (every size tried: {}), the top cube \
             moving at most {worst:.1e} m in the run.",
            tallest.cubes,
            if shocked.iter().all(|r| r.stands) {
                "all stand"
            } else {
                "not all stand"
            },
        ));
    }
    if runs.iter().any(|r| r.config.direct && r.failure.is_some()) {
        text.push_str(
            " The direct solver (Lemke) is exact when it succeeds but failed on towers \
             (ray termination on the degenerate four-corner contacts; see its table), so here \
             it is a reference for single steps, not a simulator.",
        );
    }
    text.push('\n');
    text
}

fn report(plan: &Plan, runs: &[Run], direct_stopped: &[(ContactModel, usize)]) -> Outcome {
    let mut text = String::new();
    text.push_str(
        "**Paper (fig. 4).** Towers of 2 m boxes, 15 iterations, time of the LCP call: the \
         face-contact constraint is faster than one constraint per vertex, increasingly so \
         with the number of boxes (Springhead, Intel i5-8250U).\n\n",
    );
    text.push_str(&format!(
        "**Tatami.** The solver call alone, timed on each tower's first step (median of at \
         least {} solves after a warm-up, the models' solves interleaved so that all meet the \
         same machine; dt = 0.01 s), then a run of {} steps with that solver to see \
         whether the tower stands: a tower *stands* when its top cube has lost less than half \
         a cube of height; *drift* is how far the top cube moved. No warm start (the paper's \
         setting) unless noted.\n\n",
        plan.repeats, plan.steps
    ));
    text.push_str("| cubes | vertex rows | vertex ms | patch ms | face ms | face / vertex | stands (v / p / f) | top drift v / p / f (m) |\n");
    text.push_str("|---:|---:|---:|---:|---:|---:|:---:|---:|\n");
    let mut largest_ratio = None;
    for &cubes in &plan.sizes {
        let [v, p, f] = ContactModel::ALL.map(|m| find(runs, m, false, cubes));
        let (Some(v), Some(p), Some(f)) = (v, p, f) else {
            continue;
        };
        let ratio = f.median_ms / v.median_ms;
        largest_ratio = Some((cubes, ratio));
        let yes = |r: &Run| if r.stands { "yes" } else { "**no**" };
        text.push_str(&format!(
            "| {cubes} | {} | {:.4} | {:.4} | {:.4} | {ratio:.2} | {} / {} / {} | {:.3} / {:.3} / {:.3} |\n",
            v.rows,
            v.median_ms,
            p.median_ms,
            f.median_ms,
            yes(v),
            yes(p),
            yes(f),
            v.drift(),
            p.drift(),
            f.drift(),
        ));
    }
    text.push_str(
        "\nWith warm starting (impulses carried over from the previous step), solver time \
         as measured during the run (median over its steps after a 10% warm-up; the contact \
         set's warm start and keeping of impulses, timed with the rows, left out):\n\n",
    );
    text.push_str("| cubes | vertex ms in the run | patch ms | face ms | top drift v / p / f (m) | largest penetration v / p / f (mm) |\n");
    text.push_str("|---:|---:|---:|---:|---:|---:|\n");
    for &cubes in &plan.sizes {
        let [v, p, f] = ContactModel::ALL.map(|m| find(runs, m, true, cubes));
        let (Some(v), Some(p), Some(f)) = (v, p, f) else {
            continue;
        };
        text.push_str(&format!(
            "| {cubes} | {:.4} | {:.4} | {:.4} | {:.3} / {:.3} / {:.3} | {:.2} / {:.2} / {:.2} |\n",
            v.run_median_ms,
            p.run_median_ms,
            f.run_median_ms,
            v.drift(),
            p.drift(),
            f.drift(),
            v.max_penetration * 1e3,
            p.max_penetration * 1e3,
            f.max_penetration * 1e3,
        ));
    }
    text.push_str(
        "\nThe face model with a shock-propagation pass after the 15 sweeps (no warm start; \
         each contact, from the ground up, sets the upper body to rest on the lower one):\n\n\
         | cubes | solver ms in the run (pass included) | top drift (m) | largest penetration (mm) | stands |\n\
         |---:|---:|---:|---:|:---:|\n",
    );
    for r in runs.iter().filter(|r| r.config.shock) {
        text.push_str(&format!(
            "| {} | {:.4} | {:.2e} | {:.3} | {} |\n",
            r.cubes,
            r.run_median_ms,
            r.drift(),
            r.max_penetration * 1e3,
            if r.stands { "yes" } else { "**no**" },
        ));
    }
    text.push_str(
        "\nThe direct solver (Lemke, exact to round-off; the circular friction cone as its \
         inscribed 16-gon), per model:\n\n",
    );
    text.push_str("| model | cubes | rows | steps run | ms per solve (median) | stands | failure |\n|---|---:|---:|---:|---:|:---:|---|\n");
    for r in runs.iter().filter(|r| r.config.direct) {
        text.push_str(&format!(
            "| {} | {} | {} | {} | {:.3} | {} | {} |\n",
            r.config.model.name(),
            r.cubes,
            r.rows,
            r.steps,
            r.median_ms,
            if r.stands { "yes" } else { "no" },
            r.failure.as_deref().unwrap_or("—"),
        ));
    }
    for (model, cubes) in direct_stopped {
        text.push_str(&format!(
            "\nThe direct solver ({} model) was not run beyond {cubes} cubes: its median solve \
             passed {:.0} ms or failed there.\n",
            model.name(),
            plan.direct_limit.as_secs_f64() * 1e3
        ));
    }
    text.push_str(&verdict(plan, runs));
    text.push_str("\n![solver time vs tower height](stack_timing.png)\n");
    let summary = match largest_ratio {
        Some((cubes, ratio)) => format!("face solver time = {ratio:.2}× vertex at {cubes} cubes"),
        None => "no tower measured".to_owned(),
    };
    Outcome {
        title: "Stack timing (paper fig. 4)",
        summary,
        report: text,
        files: vec![FILE, "stack_timing.svg", "stack_timing.png"],
    }
}
