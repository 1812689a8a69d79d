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

/// How contact rows turn depth, approach speed and slip into targets and bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSettings {
    /// Fraction of the depth beyond `slop` removed per step by the normal row's target.
    pub bias_rate: f64,
    /// Penetration left uncorrected, so resting contacts stay touching (m).
    pub slop: f64,
    /// Approach speed above which restitution applies (m/s).
    pub restitution_threshold: f64,
    /// Slip speed above which a contact uses kinetic friction (m/s, or rad/s for twist).
    pub slip_threshold: f64,
    /// Friction bound at each point.
    pub friction_cone: FrictionCone,
}

impl Default for ContactSettings {
    /// Springhead's bias (rate 0.1 beyond 2 mm), Box2D's 1 m/s restitution threshold, kinetic
    /// friction above 1 mm/s of slip, box friction.
    fn default() -> Self {
        Self {
            bias_rate: 0.1,
            slop: 0.002,
            restitution_threshold: 1.0,
            slip_threshold: 1e-3,
            friction_cone: FrictionCone::Box,
        }
    }
}
