//! Ledge sweep (beyond the paper): a cube on a fixed ledge, overhanging its edge by `d`. Statics
//! says it tips iff its centre of mass is beyond the edge (`d > 0`) and rests otherwise; the face
//! model gets this from the centre-of-pressure clamp alone, the vertex model from its corners.

use tatami_world::ContactModel;

use super::chart::{self, Axis, Chart, Series, Stroke};
use super::table::{Table, record};
use super::{Outcome, Progress, scenes};

/// The CSV file.
pub const FILE: &str = "ledge_sweep.csv";
/// Columns of [`FILE`].
pub const HEADER: [&str; 6] = [
    "model",
    "overhang_m",
    "predicted",
    "turned_rad",
    "tipped",
    "agrees",
];

/// A cube that turned by more than this (rad) at some point of its run has tipped.
const TIPPED: f64 = 0.3;

struct Point {
    model: ContactModel,
    overhang: f64,
    turned: f64,
}

impl Point {
    fn tipped(&self) -> bool {
        self.turned > TIPPED
    }

    fn agrees(&self) -> bool {
        self.tipped() == (self.overhang > 0.0)
    }
}

/// Runs the sweep, writes the CSV and the chart.
pub fn run(
    overhangs: &[f64],
    out: &std::path::Path,
    progress: &Progress,
) -> Result<Outcome, String> {
    let scene = scenes::LEDGE.load()?;
    let [ledge, cube] = scene.bodies.as_slice() else {
        return Err("ledge.json: expected a ledge and a cube".to_owned());
    };
    let tatami_world::Shape::Box { half_extents } = ledge.shape else {
        return Err("ledge.json: the ledge is not a box".to_owned());
    };
    let edge = ledge.position.x + half_extents.x;
    let bar = progress.bar(
        "ledge sweep",
        (overhangs.len() * ContactModel::ALL.len()) as u64,
    );
    let mut points = Vec::new();
    for model in ContactModel::ALL {
        for &overhang in overhangs {
            let mut moved = scene.clone();
            moved.bodies[1].position.x = edge + overhang;
            // The largest turn over the run: a cube that tips falls off the ledge tumbling, and
            // its turn at the end is wherever the tumble leaves it (one at 0.5 m ended at 0.298
            // rad, under the mark, though it had gone over).
            let mut turned = 0.0_f64;
            scenes::run_paper(&moved, model, |_, world| {
                let turn = world.bodies()[1].rotation() * cube.rotation.inverse();
                turned = turned.max(turn.angle());
            })?;
            points.push(Point {
                model,
                overhang,
                turned,
            });
            bar.inc(1);
        }
    }
    bar.finish_and_clear();

    let mut table = Table::create(out, FILE, &HEADER)?;
    for p in &points {
        table.record(record![
            p.model.name(),
            p.overhang,
            if p.overhang > 0.0 { "tips" } else { "rests" },
            p.turned,
            p.tipped(),
            p.agrees(),
        ])?;
    }
    table.finish()?;
    let seconds = scene.steps as f64 * scene.dt;
    Chart {
        title: "Cube over a ledge: largest rotation over the run vs overhang",
        x: Axis {
            label: "centre of mass beyond the edge (m)",
            log: false,
        },
        y: Axis {
            label: "largest rotation over the run (rad)",
            log: false,
        },
        series: ContactModel::ALL
            .iter()
            .map(|&model| Series {
                name: model.name().to_owned(),
                points: points
                    .iter()
                    .filter(|p| p.model == model)
                    .map(|p| (p.overhang, p.turned))
                    .collect(),
                stroke: Stroke::Markers,
                colour: chart::model_colour(model),
            })
            .collect(),
        legend: chart::Legend::UpperLeft,
    }
    .write(out, "ledge_sweep")?;

    let agreeing = points.iter().filter(|p| p.agrees()).count();
    let mut text = format!(
        "**Paper.** Not measured; the ZMP clamp exists so that a face contact tips exactly when \
         the centre of mass leaves the support polygon.\n\n\
         **Tatami.** `scenes/{}` with the cube's centre moved to each overhang, {seconds} s per \
         run; *tipped* means turned by more than {TIPPED} rad at some point of the run. \
         {agreeing} of {} runs agree with statics.\n\n| overhang (m) |",
        scenes::LEDGE.name,
        points.len()
    );
    for model in ContactModel::ALL {
        text.push_str(&format!(" {} turned (rad) |", model.name()));
    }
    text.push_str("\n|---:|");
    text.push_str(&"---:|".repeat(ContactModel::ALL.len()));
    text.push('\n');
    for &overhang in overhangs {
        text.push_str(&format!("| {overhang:+.2} |"));
        for p in points.iter().filter(|p| p.overhang == overhang) {
            let mark = if p.agrees() { "" } else { " **wrong**" };
            text.push_str(&format!(" {:.4}{mark} |", p.turned));
        }
        text.push('\n');
    }
    text.push_str("\n![rotation vs overhang](ledge_sweep.png)\n");
    Ok(Outcome {
        title: "Ledge overhang sweep",
        summary: format!(
            "{agreeing}/{} runs tip iff the centre of mass is past the edge",
            points.len()
        ),
        report: text,
        files: vec![FILE, "ledge_sweep.svg", "ledge_sweep.png"],
    })
}
