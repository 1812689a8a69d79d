//! A support's friction force and twist on one limit surface ([`FrictionLimit::Coupled`]): the
//! ball `|(f1, f2, τ′/r̄)| ≤ μ f3`, with `τ′ = τ3 − m` the twist about the centre of pressure
//! (`m = (p × f)·n`, the friction force's moment there about the rows' point) — the
//! ellipsoidal limit surface of planar sliding. Every point of a face slips one way, so a
//! support that slides and spins at once shares one friction budget between the two; see
//! [`FrictionLimit`] for what bounding them apart did. The face and the segment blocks share
//! it: their rows `f3, f1, f2` lead, their twist rows differ.

use tatami_lcp::TwistCoupling;

use crate::{FrictionCone, FrictionLimit};

/// Row indices shared by the blocks that use it.
const NORMAL: usize = 0;
const FRICTION_1: usize = 1;

/// One block's limit surface: `μ`, `μ r̄` and where its twist row is.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LimitSurface {
    /// `μ`, the force's bound per unit normal impulse.
    pub friction: f64,
    /// `μ r̄`, the twist's bound per unit normal impulse (m).
    pub twist_per_normal: f64,
    /// The twist row within the block.
    pub twist: usize,
}

impl LimitSurface {
    /// `|f|² + (τ′/r̄)²` against `(μ f3)²`, the bound widened by 4 ulps so that a wrench just
    /// scaled onto the ball counts as on it despite the scaling's roundings; `midpoint` is `m`.
    /// `None` where the twist has no room (no load, no friction or `r̄ = 0`): the bound is then
    /// the disc alone and `τ′ = 0`.
    fn measure(&self, impulses: &[f64], midpoint: f64) -> Option<(f64, f64)> {
        let f3 = impulses[NORMAL];
        let (force_limit, twist_limit) = (self.friction * f3, self.twist_per_normal * f3);
        if !(force_limit > 0.0 && twist_limit > 0.0) {
            return None;
        }
        let (f1, f2) = (impulses[FRICTION_1], impulses[FRICTION_1 + 1]);
        let about = (impulses[self.twist] - midpoint) * force_limit / twist_limit;
        Some((
            f1 * f1 + f2 * f2 + about * about,
            force_limit * force_limit * (1.0 + 4.0 * f64::EPSILON),
        ))
    }

    /// Whether `impulses` are on or in the ball already, so that [`Self::clamp`] would leave
    /// them as they are; `midpoint` is `m`.
    pub fn contains(&self, impulses: &[f64], midpoint: f64) -> bool {
        match self.measure(impulses, midpoint) {
            Some((squared, limit)) => squared <= limit,
            None => {
                FrictionCone::Circle.contains(
                    &impulses[FRICTION_1..FRICTION_1 + 2],
                    self.friction * impulses[NORMAL],
                ) && impulses[self.twist] == midpoint
            }
        }
    }

    /// Scales the friction force and the twist about the centre of pressure back onto the ball
    /// (direction kept: radial in `(f, τ′/r̄)`). `τ3 = τ′ + m` is linear in `(f, τ′)` for a fixed
    /// centre of pressure, so the three rows scale alike. `midpoint` reads `m` of impulses.
    pub fn clamp(&self, impulses: &mut [f64], midpoint: impl Fn(&[f64]) -> f64) {
        let f3 = impulses[NORMAL];
        match self.measure(impulses, midpoint(impulses)) {
            Some((squared, limit)) => {
                if squared > limit {
                    let shrink = self.friction * f3 / squared.sqrt();
                    for row in [FRICTION_1, FRICTION_1 + 1, self.twist] {
                        impulses[row] *= shrink;
                    }
                }
            }
            None => {
                FrictionCone::Circle.clamp(
                    &mut impulses[FRICTION_1..FRICTION_1 + 2],
                    self.friction * f3,
                );
                impulses[self.twist] = midpoint(impulses);
            }
        }
    }

    /// The twist row's coupling to the friction pair for PGS's 3-D step, `centre` the centre
    /// of pressure relative to the rows' point; `None` where the twist has no room.
    pub fn coupling(&self, centre: [f64; 2]) -> Option<TwistCoupling> {
        (self.friction > 0.0 && self.twist_per_normal > 0.0).then(|| TwistCoupling {
            row: self.twist,
            radius: self.twist_per_normal / self.friction,
            centre,
        })
    }
}

/// Whether a block with `cone` bounds its force and twist on one limit surface under `limit`:
/// with the isotropic cone only (the box is the paper's, bounds apart throughout).
pub(crate) fn is_coupled(limit: FrictionLimit, cone: FrictionCone) -> bool {
    limit == FrictionLimit::Coupled && cone == FrictionCone::Circle
}
