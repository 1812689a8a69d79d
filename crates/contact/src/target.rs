//! The normal row's target velocity: penetration bias, speculative gap, restitution.

use crate::ContactSettings;

/// Target separation speed of a normal row at a point with `depth` (> 0 overlapping, < 0 apart)
/// approaching at `normal_speed` (< 0 closing) before the step's forces.
///
/// - overlap beyond the slop: push apart at `bias_rate · (depth − slop) / dt`, at most
///   `max_depenetration_speed`;
/// - a gap: the row may close it in this step but not more (`depth / dt`, negative);
/// - closing faster than the restitution threshold: bounce at `−e · normal_speed` if larger.
pub(crate) fn normal_target(
    depth: f64,
    normal_speed: f64,
    restitution: f64,
    dt: f64,
    settings: &ContactSettings,
) -> f64 {
    let bias = if depth > settings.slop {
        (settings.bias_rate * (depth - settings.slop) / dt).min(settings.max_depenetration_speed)
    } else if depth < 0.0 {
        depth / dt
    } else {
        0.0
    };
    if restitution > 0.0 && normal_speed < -settings.restitution_threshold {
        bias.max(-restitution * normal_speed)
    } else {
        bias
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bias_starts_beyond_the_slop_and_scales_with_the_rate() {
        let s = ContactSettings::default();
        assert_eq!(normal_target(0.001, 0.0, 0.0, 0.01, &s), 0.0);
        // 0.1 · (0.012 − 0.002) / 0.01 = 0.1 m/s.
        assert!((normal_target(0.012, 0.0, 0.0, 0.01, &s) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn a_deep_overlap_separates_no_faster_than_the_cap() {
        let s = ContactSettings::default();
        // 0.1 · (0.5 − 0.002) / 0.01 = 4.98 m/s uncapped.
        assert_eq!(
            normal_target(0.5, 0.0, 0.0, 0.01, &s),
            s.max_depenetration_speed
        );
        // Restitution is not a depenetration and keeps its speed.
        assert!((normal_target(0.5, -4.0, 1.0, 0.01, &s) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn a_gap_allows_closing_it_within_the_step() {
        let s = ContactSettings::default();
        assert!((normal_target(-0.003, -5.0, 0.0, 0.01, &s) + 0.3).abs() < 1e-12);
    }

    #[test]
    fn restitution_applies_only_above_the_threshold() {
        let s = ContactSettings::default();
        assert!((normal_target(0.0, -4.0, 0.5, 0.01, &s) - 2.0).abs() < 1e-12);
        assert_eq!(normal_target(0.0, -0.5, 0.5, 0.01, &s), 0.0);
    }
}
