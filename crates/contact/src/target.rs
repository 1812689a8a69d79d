//! The normal row's targets: the velocity the solve drives it to (speculative gap, restitution)
//! and the penetration bias, the separation speed that pushes an overlap out.
//!
//! Beyond a small share the bias is kept apart so that a solver can correct penetration in a
//! pass of its own (split impulses): a bias inside the velocity target leaves its push in the
//! bodies' velocities, and pushes add up along a chain of overlapping bodies — 500 cubes
//! spawned overlapping reached 13.7 m/s with every contact's bias capped at 1 m/s.

use crate::ContactSettings;

/// What a normal row asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NormalTarget {
    /// Target separation speed of the velocity solve (m/s), including the penetration bias up
    /// to `max_velocity_bias`.
    pub velocity: f64,
    /// The rest of the penetration bias, for a position pass (m/s, ≥ 0).
    pub bias: f64,
}

/// Targets of a normal row at a point with `depth` (> 0 overlapping, < 0 apart) approaching at
/// `normal_speed` (< 0 closing) before the step's forces, of a contact whose landed points
/// bounce at `bounce_speed` ([`crate::Contact::bounce_speed`]).
///
/// - a gap: the row may close it in this step but not more (`velocity = depth / dt`, negative);
/// - landed ([`ContactSettings::has_landed`]): bounce at `bounce_speed` if one is handed on
///   (the approach now is what the landing left), else at `−e · normal_speed` when approaching
///   faster than the restitution threshold; a handed-on bounce is given too where the gap
///   closes within the step, for a landing the solve left short (a hull landing on a vertex
///   and spun by it stood 0.6 mm off, then 12 mm, and never bounced);
/// - overlap beyond the slop: a push of `bias_rate · (depth − slop) / dt`, at most
///   `max_depenetration_speed`; up to `max_velocity_bias` of it goes into the velocity target
///   (Baumgarte: it holds resting stacks against the solver's residual), the rest into `bias`.
pub(crate) fn normal_target(
    depth: f64,
    normal_speed: f64,
    bounce_speed: f64,
    restitution: f64,
    dt: f64,
    settings: &ContactSettings,
) -> NormalTarget {
    let push = if depth > settings.slop {
        (settings.bias_rate * (depth - settings.slop) / dt).min(settings.max_depenetration_speed)
    } else {
        0.0
    };
    let held = push.min(settings.max_velocity_bias);
    let gap_or_push = if depth < 0.0 { depth / dt } else { held };
    let approaching = restitution > 0.0 && normal_speed < -settings.restitution_threshold;
    let bounce = if bounce_speed > 0.0 {
        bounce_speed
    } else if approaching {
        -restitution * normal_speed
    } else {
        0.0
    };
    let meets = settings.has_landed(depth) || (bounce_speed > 0.0 && -normal_speed * dt >= -depth);
    let velocity = if bounce > 0.0 && meets {
        gap_or_push.max(bounce)
    } else {
        gap_or_push
    };
    NormalTarget {
        velocity,
        bias: push - held,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_push_goes_to_the_velocity_target_up_to_its_share() {
        let s = ContactSettings {
            max_velocity_bias: 0.2,
            ..ContactSettings::default()
        };
        let none = normal_target(0.001, 0.0, 0.0, 0.0, 0.01, &s);
        assert_eq!((none.velocity, none.bias), (0.0, 0.0));
        // 0.1 · (0.007 − 0.002) / 0.01 = 0.05 m/s, below the velocity solve's share.
        let t = normal_target(0.007, 0.0, 0.0, 0.0, 0.01, &s);
        assert!((t.velocity - 0.05).abs() < 1e-12);
        assert_eq!(t.bias, 0.0);
        // By default the whole push is for the position pass.
        let split = normal_target(0.007, 0.0, 0.0, 0.0, 0.01, &ContactSettings::default());
        assert_eq!(split.velocity, 0.0);
        assert!((split.bias - 0.05).abs() < 1e-12);
    }

    #[test]
    fn a_deep_overlap_is_pushed_out_by_position_no_faster_than_the_cap() {
        let s = ContactSettings::default();
        // 0.1 · (0.5 − 0.002) / 0.01 = 4.98 m/s uncapped: the velocity solve takes its share,
        // the position pass the rest of the capped push.
        let t = normal_target(0.5, 0.0, 0.0, 0.0, 0.01, &s);
        assert_eq!(t.velocity, s.max_velocity_bias);
        assert!((t.velocity + t.bias - s.max_depenetration_speed).abs() < 1e-12);
        // Restitution is not a depenetration and keeps its speed.
        let bounce = normal_target(0.5, -4.0, 0.0, 1.0, 0.01, &s);
        assert!((bounce.velocity - 4.0).abs() < 1e-12);
    }

    #[test]
    fn a_gap_allows_closing_it_within_the_step() {
        let s = ContactSettings::default();
        let t = normal_target(-0.003, -5.0, 0.0, 0.0, 0.01, &s);
        assert!((t.velocity + 0.3).abs() < 1e-12);
        assert_eq!(t.bias, 0.0);
    }

    #[test]
    fn a_gap_lands_without_a_bounce_and_bounces_once_landed() {
        let s = ContactSettings::default();
        // 3 cm apart closing at 5 m/s with e = 0.5: landed on the surface in this step.
        let apart = normal_target(-0.03, -5.0, 0.0, 0.5, 0.01, &s);
        assert!((apart.velocity + 3.0).abs() < 1e-12);
        // A bounce handed on from the landing is not given while still apart beyond the step...
        assert!((normal_target(-0.06, -5.0, 2.5, 0.5, 0.01, &s).velocity + 6.0).abs() < 1e-12);
        // ...and is, where the landing left a gap the step closes.
        assert!((normal_target(-0.03, -5.0, 2.5, 0.5, 0.01, &s).velocity - 2.5).abs() < 1e-12);
        // ...and is given once landed, though the approach is slow now.
        let landed = normal_target(-0.00001, -0.2, 2.5, 0.5, 0.01, &s);
        assert!((landed.velocity - 2.5).abs() < 1e-12);
        // Touching without one, the approach's own.
        assert!((normal_target(0.0, -8.0, 0.0, 0.5, 0.01, &s).velocity - 4.0).abs() < 1e-12);
    }

    #[test]
    fn restitution_applies_only_above_the_threshold() {
        let s = ContactSettings::default();
        assert!((normal_target(0.0, -4.0, 0.0, 0.5, 0.01, &s).velocity - 2.0).abs() < 1e-12);
        assert_eq!(normal_target(0.0, -0.5, 0.0, 0.5, 0.01, &s).velocity, 0.0);
    }
}
