//! Settings shared by every contact model: penetration bias, restitution, friction switching.

/// Shape of the friction bound at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionCone {
    /// `|f1| ≤ μ f3` and `|f2| ≤ μ f3` separately (the paper's eq. 4): a pyramid, linear, so the
    /// direct solver handles it exactly.
    #[default]
    Box,
    /// `|(f1, f2)| ≤ μ f3`: isotropic; PGS only.
    Circle,
}

impl FrictionCone {
    /// Bounds the tangential impulse `tangential = [f1, f2]` by `limit` (already `μ` times the
    /// normal impulse): each axis for the box, the magnitude (direction kept) for the circle.
    pub fn clamp(self, tangential: &mut [f64], limit: f64) {
        match self {
            Self::Box => {
                for f in &mut tangential[..2] {
                    *f = f.clamp(-limit, limit);
                }
            }
            Self::Circle => {
                let norm = tangential[0].hypot(tangential[1]);
                if norm > limit {
                    tangential[0] *= limit / norm;
                    tangential[1] *= limit / norm;
                }
            }
        }
    }
}

/// How the face and patch models compute the mean distance `r̄` of the twist bound.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum TwistRadius {
    /// The exact closed form over the support polygon (default).
    #[default]
    Exact,
    /// The paper's grid integral (eq. 9) with the given spacing (m), for reproduction.
    Grid {
        /// Grid spacing (m).
        spacing: f64,
    },
}

/// How contact rows turn depth, approach speed and slip into targets and bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSettings {
    /// Fraction of the depth beyond `slop` removed per step by the normal row's target.
    pub bias_rate: f64,
    /// Penetration left uncorrected, so resting contacts stay touching (m).
    pub slop: f64,
    /// Approach speed above which restitution applies (m/s).
    pub restitution_threshold: f64,
    /// Slip speed above which a contact uses kinetic friction (m/s). For twist the slip speed is
    /// the twist rate times `r̄`.
    pub slip_threshold: f64,
    /// Friction bound at each point.
    pub friction_cone: FrictionCone,
    /// Face model: how `r̄` is computed.
    pub twist_radius: TwistRadius,
    /// Face model: remove the part of the torque parallel to the force before the ZMP step (the
    /// paper's eq. 12 variant).
    pub remove_parallel_torque: bool,
}

impl Default for ContactSettings {
    /// Springhead's bias (rate 0.1 beyond 2 mm), Box2D's 1 m/s restitution threshold, kinetic
    /// friction above 1 mm/s of slip, box friction, exact `r̄`.
    fn default() -> Self {
        Self {
            bias_rate: 0.1,
            slop: 0.002,
            restitution_threshold: 1.0,
            slip_threshold: 1e-3,
            friction_cone: FrictionCone::Box,
            twist_radius: TwistRadius::Exact,
            remove_parallel_torque: false,
        }
    }
}
