//! The heavy symmetric top on a fixed tip (Lagrange's top): the reference a spinning top's
//! nodding and precession are checked against (`tests/spinning_top.rs`, the spinning-top
//! experiment of `cargo xtask experiments`).
//!
//! Let go at rest at a tilt `θ₀` from the vertical, spinning at `ω₃` about its own axis, it
//! keeps `ω₃` and its angular momentum about the vertical, `p_φ = I₁ φ̇ sin²θ + I₃ ω₃ cos θ
//! = I₃ ω₃ cos θ₀`, so its tilt `θ` and heading `φ` follow
//!
//! `φ̇ = I₃ ω₃ (cos θ₀ − cos θ) / (I₁ sin²θ)`,
//! `I₁ θ̈ = I₁ φ̇² sin θ cos θ − I₃ ω₃ φ̇ sin θ + m g l sin θ`
//!
//! (`I₁` about an axis across the top through its tip, `I₃` about its own axis, `l` from the
//! tip to the centre of mass), integrated here by classic RK4. A fast top nods between `θ₀`
//! and a lowest point and precesses at about `m g l / (I₃ ω₃)`.
//!
//! ```
//! use tatami_world::heavy_top::HeavyTop;
//!
//! // A fast top: it nods by a hair and precesses at m g l / (I₃ ω₃) = 0.49 rad/s.
//! let top = HeavyTop { mass: 1.0, gravity: 9.81, arm: 0.1, transverse_moment: 0.02,
//!                      axial_moment: 0.004, spin: 500.0 };
//! let trace = top.trace(0.3, 1e-3, 2000, 10)?;
//! let last = trace.last().unwrap();
//! assert!((last.heading / 2.0 - 0.49).abs() < 0.01);
//! assert!(trace.iter().all(|s| (s.tilt - 0.3).abs() < 0.01));
//! // Upright, it has no heading to precess about: refused, as is any other field out of range.
//! assert!(top.trace(0.0, 1e-3, 2000, 10).is_err());
//! # Ok::<(), tatami_world::heavy_top::HeavyTopError>(())
//! ```

use thiserror::Error;

use crate::scene::MAX_STEPS;

/// A symmetric top on a fixed tip, under gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTop {
    /// Mass (kg).
    pub mass: f64,
    /// Gravity's magnitude (m/s²).
    pub gravity: f64,
    /// Distance from the tip to the centre of mass (m).
    pub arm: f64,
    /// Moment of inertia about an axis across the top through its tip (kg m²).
    pub transverse_moment: f64,
    /// Moment of inertia about the top's own axis (kg m²).
    pub axial_moment: f64,
    /// Spin about its own axis (rad/s), kept.
    pub spin: f64,
}

/// Where a top is: its tilt from the vertical (rad), how fast that changes (rad/s), and its
/// heading about the vertical since it was let go (rad, not wrapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TopState {
    /// Tilt of its axis from the vertical (rad).
    pub tilt: f64,
    /// Rate of the tilt (rad/s).
    pub tilt_rate: f64,
    /// Turn of its axis about the vertical since it was let go (rad).
    pub heading: f64,
}

/// Why a top or its trace was refused.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("heavy top: {field} {reason}")]
pub struct HeavyTopError {
    /// The offending field or argument.
    pub field: &'static str,
    /// What is wrong with it.
    pub reason: String,
}

impl HeavyTop {
    /// The top let go at rest at `tilt` (rad, strictly between 0 and π: upright or hanging it
    /// has no heading to precess about), sampled every `dt` (s) for `steps` samples after the
    /// first (1 to [`MAX_STEPS`]), `substeps` RK4 steps between samples (1 to 10 000): `steps + 1`
    /// states from the start. A mass, gravity, arm or moment that is not finite and positive, a
    /// spin that is not finite, or an argument out of range is an error naming it.
    pub fn trace(
        &self,
        tilt: f64,
        dt: f64,
        steps: usize,
        substeps: usize,
    ) -> Result<Vec<TopState>, HeavyTopError> {
        self.check(tilt, dt, steps, substeps)?;
        let spin_momentum = self.axial_moment * self.spin;
        let (i1, weight) = (self.transverse_moment, self.mass * self.gravity * self.arm);
        let rates = |[theta, theta_rate, _]: [f64; 3]| {
            let (sin, cos) = theta.sin_cos();
            let heading_rate = spin_momentum * (tilt.cos() - cos) / (i1 * sin * sin);
            let theta_accel = (i1 * heading_rate * heading_rate * sin * cos
                - spin_momentum * heading_rate * sin
                + weight * sin)
                / i1;
            [theta_rate, theta_accel, heading_rate]
        };
        let along = |s: [f64; 3], k: [f64; 3], h: f64| std::array::from_fn(|i| s[i] + h * k[i]);
        let h = dt / substeps as f64;
        let mut state = [tilt, 0.0, 0.0];
        let sample = |s: [f64; 3]| TopState {
            tilt: s[0],
            tilt_rate: s[1],
            heading: s[2],
        };
        let mut trace = Vec::with_capacity(steps + 1);
        trace.push(sample(state));
        for _ in 0..steps {
            for _ in 0..substeps {
                let k1 = rates(state);
                let k2 = rates(along(state, k1, h / 2.0));
                let k3 = rates(along(state, k2, h / 2.0));
                let k4 = rates(along(state, k3, h));
                state = std::array::from_fn(|i| {
                    state[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
                });
            }
            trace.push(sample(state));
        }
        Ok(trace)
    }

    /// [`HeavyTop::trace`]'s checks of the top and of its arguments.
    fn check(
        &self,
        tilt: f64,
        dt: f64,
        steps: usize,
        substeps: usize,
    ) -> Result<(), HeavyTopError> {
        let refuse = |field, reason: &str| {
            Err(HeavyTopError {
                field,
                reason: reason.to_owned(),
            })
        };
        let positive = [
            ("mass", self.mass),
            ("gravity", self.gravity),
            ("arm", self.arm),
            ("transverse_moment", self.transverse_moment),
            ("axial_moment", self.axial_moment),
            ("dt", dt),
        ];
        for (field, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return refuse(field, &format!("must be finite and > 0, got {value}"));
            }
        }
        if !self.spin.is_finite() {
            return refuse("spin", &format!("must be finite, got {}", self.spin));
        }
        if !(tilt > 0.0 && tilt < std::f64::consts::PI) {
            return refuse("tilt", &format!("must be between 0 and π rad, got {tilt}"));
        }
        if !(1..=MAX_STEPS).contains(&steps) {
            return refuse("steps", &format!("must be 1 to {MAX_STEPS}, got {steps}"));
        }
        if !(1..=10_000).contains(&substeps) {
            return refuse("substeps", &format!("must be 1 to 10000, got {substeps}"));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each field and argument out of range is refused by name, never traced into NaN.
    #[test]
    fn bad_input_is_refused_by_name() {
        let top = HeavyTop {
            mass: 1.0,
            gravity: 9.81,
            arm: 0.1,
            transverse_moment: 0.02,
            axial_moment: 0.004,
            spin: 100.0,
        };
        let field = |top: HeavyTop, (tilt, dt, steps, substeps): (f64, f64, usize, usize)| {
            top.trace(tilt, dt, steps, substeps).unwrap_err().field
        };
        let fine = (0.3, 1e-3, 10, 10);
        assert_eq!(field(HeavyTop { mass: 0.0, ..top }, fine), "mass");
        assert_eq!(
            field(
                HeavyTop {
                    gravity: f64::NAN,
                    ..top
                },
                fine
            ),
            "gravity"
        );
        assert_eq!(field(HeavyTop { arm: -0.1, ..top }, fine), "arm");
        let flat = HeavyTop {
            transverse_moment: f64::INFINITY,
            ..top
        };
        assert_eq!(field(flat, fine), "transverse_moment");
        assert_eq!(
            field(
                HeavyTop {
                    axial_moment: 0.0,
                    ..top
                },
                fine
            ),
            "axial_moment"
        );
        assert_eq!(
            field(
                HeavyTop {
                    spin: f64::NAN,
                    ..top
                },
                fine
            ),
            "spin"
        );
        for tilt in [0.0, std::f64::consts::PI, f64::NAN] {
            assert_eq!(field(top, (tilt, 1e-3, 10, 10)), "tilt");
        }
        assert_eq!(field(top, (0.3, 0.0, 10, 10)), "dt");
        assert_eq!(field(top, (0.3, 1e-3, 0, 10)), "steps");
        assert_eq!(field(top, (0.3, 1e-3, MAX_STEPS + 1, 10)), "steps");
        assert_eq!(field(top, (0.3, 1e-3, 10, 0)), "substeps");
        assert_eq!(top.trace(0.3, 1e-3, 10, 10).map(|t| t.len()), Ok(11));
    }

    /// Energy `½ I₁ (θ̇² + φ̇² sin²θ) + m g l cos θ` (the spin's part kept) stays within 1e-9
    /// of its start over 10 s of a nodding top, and the tilt's turning points agree with the
    /// roots of the energy equation: the lowest point `θ₁` has `θ̇ = 0`, so
    /// `½ I₁ φ̇(θ₁)² sin²θ₁ = m g l (cos θ₀ − cos θ₁)`.
    #[test]
    fn the_top_keeps_its_energy_and_turns_where_the_energy_says() {
        let top = HeavyTop {
            mass: 1.0,
            gravity: 9.81,
            arm: 0.15,
            transverse_moment: 0.0255,
            axial_moment: 0.003,
            spin: 200.0,
        };
        let tilt = 20f64.to_radians();
        let trace = top.trace(tilt, 1e-3, 10_000, 20).unwrap();
        let heading_rate = |theta: f64| {
            top.axial_moment * top.spin * (tilt.cos() - theta.cos())
                / (top.transverse_moment * theta.sin().powi(2))
        };
        let energy = |s: &TopState| {
            let swing = s.tilt_rate.powi(2) + (heading_rate(s.tilt) * s.tilt.sin()).powi(2);
            0.5 * top.transverse_moment * swing + top.mass * top.gravity * top.arm * s.tilt.cos()
        };
        let start = energy(&trace[0]);
        for s in &trace {
            assert!((energy(s) - start).abs() < 1e-9 * start, "{s:?}");
        }
        let lowest = trace.iter().map(|s| s.tilt).fold(0.0, f64::max);
        let kinetic = 0.5 * top.transverse_moment * (heading_rate(lowest) * lowest.sin()).powi(2);
        let fall = top.mass * top.gravity * top.arm * (tilt.cos() - lowest.cos());
        assert!(
            (kinetic - fall).abs() < 1e-6 * fall,
            "{kinetic} against {fall}"
        );
        assert!(lowest > tilt + 0.05, "it nods: {lowest}");
    }
}
