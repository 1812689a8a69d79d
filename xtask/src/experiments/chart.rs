//! Line charts of the experiments, drawn twice by `plotters`: SVG (for the web and for diffs)
//! and PNG (for viewers without SVG).
//!
//! Logarithmic axes are drawn as linear axes over `log10` of the data with tick labels mapped
//! back, which keeps one drawing routine for every chart. The font is embedded (Ubuntu Light,
//! from `epaint_default_fonts`), so no system font library is needed.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

/// Where the legend goes.
pub use plotters::chart::SeriesLabelPosition as Legend;

/// Pixel size of every chart.
const SIZE: (u32, u32) = (960, 600);

/// One axis: label and scale.
#[derive(Debug, Clone, Copy)]
pub struct Axis<'a> {
    /// Quantity and unit, e.g. "time (s)".
    pub label: &'a str,
    /// Logarithmic (base 10) scale; non-positive values are left out.
    pub log: bool,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stroke {
    /// A solid line.
    Line,
    /// A dashed line, for closed forms and references.
    Dashed,
    /// Markers joined by a thin line, for sparse sweeps.
    Markers,
}

/// One named line of a chart.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// Points `(x, y)` in data units.
    pub points: Vec<(f64, f64)>,
    /// Line style.
    pub stroke: Stroke,
    /// Colour.
    pub colour: RGBColor,
}

/// A chart: title, axes and series.
#[derive(Debug, Clone)]
pub struct Chart<'a> {
    /// Title drawn on top.
    pub title: &'a str,
    /// Horizontal axis.
    pub x: Axis<'a>,
    /// Vertical axis.
    pub y: Axis<'a>,
    /// Lines, drawn in order.
    pub series: Vec<Series>,
    /// Corner of the legend, where it hides no data.
    pub legend: Legend,
}

/// The colour of a contact model's lines, the same in every chart.
pub fn model_colour(model: tatami_world::ContactModel) -> RGBColor {
    match model {
        tatami_world::ContactModel::Vertex => RGBColor(214, 39, 40),
        tatami_world::ContactModel::Patch => RGBColor(31, 119, 180),
        tatami_world::ContactModel::Face => RGBColor(44, 160, 44),
    }
}

/// The axes of an angular-speed-per-step chart: steps (labelled `step_label`) and |ω|.
pub fn angular_speed_axes(step_label: &str) -> (Axis<'_>, Axis<'static>) {
    (
        Axis {
            label: step_label,
            log: false,
        },
        Axis {
            label: "|ω| (rad/s)",
            log: false,
        },
    )
}

/// A contact model's angular speed per step, as a solid line in the model's colour.
pub fn speed_per_step(model: tatami_world::ContactModel, omega: &[f64]) -> Series {
    Series {
        name: model.name().to_owned(),
        points: omega
            .iter()
            .enumerate()
            .map(|(n, &w)| (n as f64, w))
            .collect(),
        stroke: Stroke::Line,
        colour: model_colour(model),
    }
}

/// Colour of closed forms and references.
pub const REFERENCE: RGBColor = RGBColor(0, 0, 0);

impl Chart<'_> {
    /// Writes `dir/stem.svg` and `dir/stem.png`.
    pub fn write(&self, dir: &Path, stem: &str) -> Result<(), String> {
        register_embedded_font()?;
        let svg = dir.join(format!("{stem}.svg"));
        self.draw(SVGBackend::new(&svg, SIZE).into_drawing_area())
            .map_err(|e| format!("{}: {e}", svg.display()))?;
        let png = dir.join(format!("{stem}.png"));
        self.draw(BitMapBackend::new(&png, SIZE).into_drawing_area())
            .map_err(|e| format!("{}: {e}", png.display()))
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String>
    where
        DB::ErrorType: 'static,
    {
        let failed = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(failed)?;
        let scale = |axis: Axis, v: f64| {
            if axis.log {
                (v > 0.0).then(|| v.log10())
            } else {
                Some(v)
            }
        };
        let series: Vec<(&Series, Vec<(f64, f64)>)> = self
            .series
            .iter()
            .map(|s| {
                let points = s
                    .points
                    .iter()
                    .filter_map(|&(x, y)| Some((scale(self.x, x)?, scale(self.y, y)?)))
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
                    .collect();
                (s, points)
            })
            .collect();
        let (x_range, y_range) = ranges(series.iter().flat_map(|(_, p)| p.iter().copied()));
        let mut chart = ChartBuilder::on(&root)
            .caption(self.title, ("sans-serif", 26))
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(x_range, y_range)
            .map_err(failed)?;
        let tick = |axis: Axis| {
            move |v: &f64| {
                if axis.log {
                    log_tick_label(*v)
                } else {
                    tick_label(*v)
                }
            }
        };
        let (x_tick, y_tick) = (tick(self.x), tick(self.y));
        chart
            .configure_mesh()
            .x_desc(self.x.label)
            .y_desc(self.y.label)
            .x_label_formatter(&x_tick)
            .y_label_formatter(&y_tick)
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 18))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(failed)?;
        for (s, points) in series {
            let colour = s.colour;
            let style = colour.stroke_width(2);
            let drawn = match s.stroke {
                Stroke::Line => chart.draw_series(LineSeries::new(points, style)),
                Stroke::Dashed => chart.draw_series(DashedLineSeries::new(points, 8, 6, style)),
                Stroke::Markers => {
                    chart
                        .draw_series(LineSeries::new(points.clone(), colour.stroke_width(1)))
                        .map_err(failed)?;
                    chart.draw_series(PointSeries::of_element(
                        points,
                        4,
                        colour.filled(),
                        &|c, size, style| Circle::new(c, size, style),
                    ))
                }
            }
            .map_err(failed)?;
            drawn
                .label(s.name.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], style));
        }
        chart
            .configure_series_labels()
            .position(self.legend.clone())
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()
            .map_err(failed)?;
        root.present().map_err(failed)
    }
}

/// Data ranges with a 5% margin; a flat or empty range is widened so the chart still draws.
fn ranges(
    points: impl Iterator<Item = (f64, f64)>,
) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
    let mut lo = (f64::INFINITY, f64::INFINITY);
    let mut hi = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    for (x, y) in points {
        lo = (lo.0.min(x), lo.1.min(y));
        hi = (hi.0.max(x), hi.1.max(y));
    }
    let widen = |lo: f64, hi: f64| {
        if !(lo.is_finite() && hi.is_finite()) {
            return 0.0..1.0;
        }
        let margin = if hi > lo {
            0.05 * (hi - lo)
        } else {
            0.5 * lo.abs().max(1.0)
        };
        lo - margin..hi + margin
    };
    (widen(lo.0, hi.0), widen(lo.1, hi.1))
}

/// Tick labels: plain decimals in a readable range, powers of ten elsewhere. A tick within
/// 1e-12 of zero is zero: the tick positions carry round-off (a zero tick came out as −2e-16),
/// and no chart plots quantities that small on a linear axis.
fn tick_label(v: f64) -> String {
    let magnitude = v.abs();
    if magnitude < 1e-12 {
        "0".to_owned()
    } else if !(1e-3..1e5).contains(&magnitude) {
        format!("{v:.0e}")
    } else {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    }
}

/// Label of a tick at `exponent` on a logarithmic axis: the value when it is 1, 2 or 5 times
/// a power of ten (to 2%), else nothing, so the labels read 1, 2, 5, 10, 20 …
fn log_tick_label(exponent: f64) -> String {
    let value = 10f64.powf(exponent);
    let power = 10f64.powf(exponent.floor());
    let mantissa = value / power;
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .find(|&&m| (mantissa - m).abs() < 0.02 * m)
        .map_or_else(String::new, |&m| tick_label(m * power))
}

/// Registers the embedded font as "sans-serif" once per process.
fn register_embedded_font() -> Result<(), String> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        )
        .is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err("the embedded chart font could not be read".to_owned())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_read_as_the_values() {
        for v in [0.0, 1.0, 0.25, 12.5, 100.0, 1e-6, 3e7, -2.0] {
            let label = tick_label(v);
            let back: f64 = label.parse().unwrap();
            assert!((back - v).abs() <= 1e-3 * v.abs(), "{v} → {label}");
        }
    }

    #[test]
    fn log_ticks_label_only_one_two_five() {
        assert_eq!(log_tick_label(0.0), "1");
        assert_eq!(log_tick_label(2f64.log10()), "2");
        assert_eq!(log_tick_label(1.0 + 5f64.log10()), "50");
        assert_eq!(log_tick_label(-3.0), "0.001");
        assert_eq!(log_tick_label(0.2), "", "10^0.2 = 1.58 is not labelled");
    }

    #[test]
    fn ranges_include_every_point_and_survive_flat_data() {
        let (x, y) = ranges([(1.0, 5.0), (3.0, 5.0)].into_iter());
        assert!(x.start < 1.0 && x.end > 3.0);
        assert!(y.start < 5.0 && y.end > 5.0, "a flat series gets a height");
        let (x, _) = ranges(std::iter::empty());
        assert!(x.start < x.end);
    }
}
