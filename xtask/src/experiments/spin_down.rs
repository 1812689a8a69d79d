//! Spin-down (beyond the paper): a cube and a standing cylinder spinning flat on the floor slow
//! down under torsional friction. Under uniform pressure the friction torque is `μ N r̄`, `r̄` the
//! face's mean distance from its centre, so the deceleration is constant:
//! cube `6 μ g r̄ / a²` with `r̄ = a (√2 + ln(1 + √2)) / 6`; disc `4 μ g / (3 R)`.
//!
//! The measured deceleration is a least-squares slope of `ω_z(t)` between 90% and 10% of the
//! initial rate, away from the start and the stop.

use tatami_world::scene::Scene;
use tatami_world::{ContactModel, Shape};

use super::chart::{self, Axis, Chart, Series, Stroke};
use super::scenes::SceneFile;
use super::table::{Table, record};
use super::{Outcome, Progress, scenes};

/// The fitted rates.
pub const FILE: &str = "spin_down.csv";
/// Columns of [`FILE`].
pub const HEADER: [&str; 5] = [
    "shape",
    "model",
    "closed_form_rad_s2",
    "measured_rad_s2",
    "ratio",
];
/// The traces.
pub const TRACE_FILE: &str = "spin_down_trace.csv";
/// Columns of [`TRACE_FILE`].
pub const TRACE_HEADER: [&str; 5] = ["shape", "model", "step", "time", "omega_z_rad_s"];

/// The closed-form deceleration (rad/s²) of the scene's body 1 spinning flat on body 0.
fn closed_form(scene: &Scene) -> Result<f64, String> {
    let [ground, body] = scene.bodies.as_slice() else {
        return Err("spin scenes have a ground and one body".to_owned());
    };
    let mu = scenes::kinetic_friction(ground, body);
    let g = scene.gravity.norm();
    match &body.shape {
        shape @ Shape::Box { .. } => {
            let a = scenes::cube_side(shape).ok_or("the spinning box is not a cube")?;
            let r_bar = a * (2f64.sqrt() + (1.0 + 2f64.sqrt()).ln()) / 6.0;
            Ok(6.0 * mu * g * r_bar / (a * a))
        }
        Shape::Cylinder { radius, .. } => Ok(4.0 * mu * g / (3.0 * radius)),
        _ => Err("spin scenes spin a cube or a cylinder".to_owned()),
    }
}

/// Least-squares deceleration over the samples between 90% and 10% of `omega0`.
fn fitted_rate(times: &[f64], omega: &[f64], omega0: f64) -> Option<f64> {
    let samples: Vec<(f64, f64)> = times
        .iter()
        .zip(omega)
        .filter(|&(_, &w)| w < 0.9 * omega0 && w > 0.1 * omega0)
        .map(|(&t, &w)| (t, w))
        .collect();
    if samples.len() < 3 {
        return None;
    }
    let n = samples.len() as f64;
    let (mt, mw) = samples
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, w)| (a + t / n, b + w / n));
    let (cov, var) = samples.iter().fold((0.0, 0.0), |(c, v), (t, w)| {
        (c + (t - mt) * (w - mw), v + (t - mt) * (t - mt))
    });
    Some(-cov / var)
}

struct Spin {
    shape: &'static str,
    model: ContactModel,
    omega: Vec<f64>,
    rate: Option<f64>,
    expected: f64,
    dt: f64,
}

/// Runs both scenes under each model, writes the CSVs and one chart per shape.
pub fn run(out: &std::path::Path, progress: &Progress) -> Result<Outcome, String> {
    let files: [(&str, SceneFile); 2] = [
        ("cube", scenes::CUBE_SPIN),
        ("cylinder", scenes::CYLINDER_SPIN),
    ];
    let bar = progress.bar("spin-down", (files.len() * ContactModel::ALL.len()) as u64);
    let mut spins = Vec::new();
    for (shape, file) in &files {
        let scene = file.load()?;
        let expected = closed_form(&scene).map_err(|e| format!("scenes/{}: {e}", file.name))?;
        let omega0 = scene.bodies[1].angular_velocity.z;
        let times: Vec<f64> = (0..=scene.steps).map(|n| n as f64 * scene.dt).collect();
        for model in ContactModel::ALL {
            let mut omega = vec![omega0];
            scenes::run_paper(&scene, model, |_, w| {
                omega.push(w.bodies()[1].angular_velocity().z);
            })?;
            spins.push(Spin {
                shape,
                model,
                rate: fitted_rate(&times, &omega, omega0),
                omega,
                expected,
                dt: scene.dt,
            });
            bar.inc(1);
        }
        let chart_spins: Vec<&Spin> = spins.iter().filter(|s| s.shape == *shape).collect();
        let mut series: Vec<Series> = chart_spins
            .iter()
            .map(|s| Series {
                name: s.model.name().to_owned(),
                points: times.iter().copied().zip(s.omega.iter().copied()).collect(),
                stroke: Stroke::Line,
                colour: chart::model_colour(s.model),
            })
            .collect();
        series.push(Series {
            name: "closed form (uniform pressure)".to_owned(),
            points: times
                .iter()
                .map(|&t| (t, (omega0 - expected * t).max(0.0)))
                .collect(),
            stroke: Stroke::Dashed,
            colour: chart::REFERENCE,
        });
        Chart {
            title: &format!("Spin-down of a {shape} on the floor"),
            x: Axis {
                label: "time (s)",
                log: false,
            },
            y: Axis {
                label: "ω_z (rad/s)",
                log: false,
            },
            series,
            legend: chart::Legend::UpperRight,
        }
        .write(out, &format!("spin_down_{shape}"))?;
    }
    bar.finish_and_clear();

    let mut table = Table::create(out, FILE, &HEADER)?;
    let mut trace = Table::create(out, TRACE_FILE, &TRACE_HEADER)?;
    for s in &spins {
        table.record(record![
            s.shape,
            s.model.name(),
            s.expected,
            s.rate,
            s.rate.map(|r| r / s.expected),
        ])?;
        for (n, &w) in s.omega.iter().enumerate() {
            trace.record(record![s.shape, s.model.name(), n, n as f64 * s.dt, w])?;
        }
    }
    table.finish()?;
    trace.finish()?;

    let mut text = String::from(
        "**Paper.** Twist is bounded by `μ f₃ r̄` with `r̄` from a grid integral (eqs. 7–11); \
         no spin-down is measured. Tatami computes `r̄` exactly.\n\n\
         **Tatami.** `scenes/cube_spin.json` (2 m cube) and `scenes/cylinder_spin.json` \
         (R = 1 m), 5 rad/s, μ = 0.5.\n\n\
         | shape | model | closed form (rad/s²) | measured (rad/s²) | measured / closed form |\n\
         |---|---|---:|---:|---:|\n",
    );
    for s in &spins {
        text.push_str(&format!(
            "| {} | {} | {:.3} | {} | {} |\n",
            s.shape,
            s.model.name(),
            s.expected,
            s.rate.map_or("—".to_owned(), |r| format!("{r:.3}")),
            s.rate
                .map_or("—".to_owned(), |r| format!("{:.3}", r / s.expected)),
        ));
    }
    text.push_str(
        "\nThe vertex and patch models concentrate the pressure at the corners (the cylinder's \
         at its 64-gon's vertices), the farthest points from the centre, so their friction \
         torque is larger than uniform pressure gives.\n\n\
         ![cube spin-down](spin_down_cube.png)\n\n![cylinder spin-down](spin_down_cylinder.png)\n",
    );
    let face_error = spins
        .iter()
        .filter(|s| s.model == ContactModel::Face)
        .map(|s| {
            s.rate
                .map_or(f64::INFINITY, |r| (r / s.expected - 1.0).abs())
        })
        .fold(0.0, f64::max);
    Ok(Outcome {
        title: "Spin-down under torsional friction",
        summary: format!(
            "face model within {:.1}% of the closed forms (cube, cylinder)",
            face_error * 100.0
        ),
        report: text,
        files: vec![
            FILE,
            TRACE_FILE,
            "spin_down_cube.svg",
            "spin_down_cube.png",
            "spin_down_cylinder.svg",
            "spin_down_cylinder.png",
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fit_recovers_a_constant_deceleration_and_ignores_the_stop() {
        let times: Vec<f64> = (0..300).map(|n| n as f64 * 0.01).collect();
        let omega: Vec<f64> = times.iter().map(|t| (5.0 - 3.0 * t).max(0.0)).collect();
        let rate = fitted_rate(&times, &omega, 5.0).unwrap();
        assert!((rate - 3.0).abs() < 1e-9, "{rate}");
        assert_eq!(fitted_rate(&times[..2], &omega[..2], 5.0), None);
    }

    #[test]
    fn the_closed_forms_are_the_textbook_ones() {
        let cube = scenes::CUBE_SPIN.load().unwrap();
        // 6 μ g r̄ / a² with r̄ = 0.3826 a, a = 2, μ = 0.5.
        let expected = 6.0 * 0.5 * 9.8 * 0.382_597_858 / 2.0;
        assert!((closed_form(&cube).unwrap() - expected).abs() < 1e-6);
        let cylinder = scenes::CYLINDER_SPIN.load().unwrap();
        assert!((closed_form(&cylinder).unwrap() - 4.0 * 0.5 * 9.8 / 3.0).abs() < 1e-12);
    }
}
