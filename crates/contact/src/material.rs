//! Friction and restitution of a contact pair.

use crate::ContactError;

/// Friction and restitution of a contact, already combined from the two bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Coefficient while the contact sticks (`μs`).
    pub static_friction: f64,
    /// Coefficient while it slides (`μk`).
    pub kinetic_friction: f64,
    /// Ratio of separation to approach speed above the restitution threshold.
    pub restitution: f64,
}

impl Material {
    /// A validated material: friction finite and `≥ 0`, restitution in `[0, 1]`.
    pub fn new(
        static_friction: f64,
        kinetic_friction: f64,
        restitution: f64,
    ) -> Result<Self, ContactError> {
        for (which, value) in [("static", static_friction), ("kinetic", kinetic_friction)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(ContactError::InvalidFriction { which, value });
            }
        }
        if !(restitution.is_finite() && (0.0..=1.0).contains(&restitution)) {
            return Err(ContactError::InvalidRestitution(restitution));
        }
        Ok(Self {
            static_friction,
            kinetic_friction,
            restitution,
        })
    }

    /// The coefficient for a contact slipping at `slip_speed`: kinetic above `threshold`.
    pub fn friction(&self, slip_speed: f64, threshold: f64) -> f64 {
        if slip_speed > threshold {
            self.kinetic_friction
        } else {
            self.static_friction
        }
    }
}
