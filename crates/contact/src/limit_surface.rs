//! A contact's friction force and twist on one limit surface ([`FrictionLimit::Coupled`]): the
//! ball `|(f1, f2, τ′/r̄)| ≤ F`, `F` the force's bound (`μ f3`, or a grip's `μ p`) and `r̄ F` the
//! twist's, with `τ′ = τ3 − m` the twist about the centre of pressure (`m = (p × f)·n`, the
//! friction force's moment there about the rows' point) — the ellipsoidal limit surface of
//! planar sliding. Every point of a face slips one way, so a support that slides and spins at
//! once shares one friction budget between the two; see [`FrictionLimit`] for what bounding
//! them apart did. Faces, segments and grips share it; their rows differ.

use tatami_lcp::TwistCoupling;

use crate::{FrictionCone, FrictionLimit};

/// One block's limit surface: its bounds and where its rows are.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LimitSurface {
    /// `F`: the friction force's bound (N s).
    pub force: f64,
    /// `r̄ F`: the twist's bound (N m s).
    pub twist: f64,
    /// The first of the block's two friction rows.
    pub friction_row: usize,
    /// The block's twist row.
    pub twist_row: usize,
}

impl LimitSurface {
    /// `|f|² + (τ′/r̄)²` against `F²`, the bound widened by 4 ulps so that a wrench just scaled
    /// onto the ball counts as on it despite the scaling's roundings; `midpoint` is `m`.
    /// `None` where the twist has no room (no load, no friction or `r̄ = 0`): the bound is then
    /// the disc alone and `τ′ = 0`.
    fn measure(&self, impulses: &[f64], midpoint: f64) -> Option<(f64, f64)> {
        if !(self.force > 0.0 && self.twist > 0.0) {
            return None;
        }
        let (f1, f2) = (impulses[self.friction_row], impulses[self.friction_row + 1]);
        let about = (impulses[self.twist_row] - midpoint) * self.force / self.twist;
        Some((
            f1 * f1 + f2 * f2 + about * about,
            self.force * self.force * (1.0 + 4.0 * f64::EPSILON),
        ))
    }

    /// Whether `impulses` are on or in the ball already, so that [`Self::clamp`] would leave
    /// them as they are; `midpoint` is `m`.
    pub fn contains(&self, impulses: &[f64], midpoint: f64) -> bool {
        match self.measure(impulses, midpoint) {
            Some((squared, limit)) => squared <= limit,
            None => {
                let pair = self.friction_row..self.friction_row + 2;
                FrictionCone::Circle.contains(&impulses[pair], self.force)
                    && impulses[self.twist_row] == midpoint
            }
        }
    }

    /// Scales the friction force and the twist about the centre of pressure back onto the ball
    /// (direction kept: radial in `(f, τ′/r̄)`). `τ3 = τ′ + m` is linear in `(f, τ′)` for a fixed
    /// centre of pressure, so the three rows scale alike. `midpoint` reads `m` of impulses.
    pub fn clamp(&self, impulses: &mut [f64], midpoint: impl Fn(&[f64]) -> f64) {
        match self.measure(impulses, midpoint(impulses)) {
            Some((squared, limit)) => {
                if squared > limit {
                    let shrink = self.force / squared.sqrt();
                    let pair = self.friction_row;
                    for row in [pair, pair + 1, self.twist_row] {
                        impulses[row] *= shrink;
                    }
                }
            }
            None => {
                let pair = self.friction_row..self.friction_row + 2;
                FrictionCone::Circle.clamp(&mut impulses[pair], self.force);
                impulses[self.twist_row] = midpoint(impulses);
            }
        }
    }

    /// The twist row's coupling to the friction pair for PGS's 3-D step, `centre` the centre
    /// of pressure relative to the rows' point; `None` where the twist has no room.
    pub fn coupling(&self, centre: [f64; 2]) -> Option<TwistCoupling> {
        (self.force > 0.0 && self.twist > 0.0).then(|| TwistCoupling {
            row: self.twist_row,
            radius: self.twist / self.force,
            centre,
        })
    }
}

/// Whether a block with `cone` bounds its force and twist on one limit surface under `limit`:
/// with the isotropic cone only (the box is the paper's, bounds apart throughout).
pub(crate) fn is_coupled(limit: FrictionLimit, cone: FrictionCone) -> bool {
    limit == FrictionLimit::Coupled && cone == FrictionCone::Circle
}
