//! A segment support in the face model (an edge on a face, a cylinder on its side): one 5-row
//! block at the segment's midpoint `G`, rows `(f3, f1, f2, τu, τ3)`, kept physical by
//! [`SegmentProjection`].
//!
//! A line of support resists tilting only about the in-plane axis `u = n × s` across it (`s`
//! along the segment): the centre of pressure may sit anywhere on the segment, `x` from `G`
//! along `s`, so `τu = −x f3` with `|x| ≤ L/2`. About the segment itself the support is a
//! hinge, and the tilt there is zero. The face model's 6-row block carried both tilts about the
//! frame's tangents and projected the centre of pressure back onto the line after every row
//! update: one of the six rows was updated and projected away each sweep, three nearest-point
//! searches ran per update, and a whole-block step never landed on the line, so a segment was
//! always updated row by row. Here every bound is a box on one row (scaled by `f3`) — the
//! twist's centred on the friction force's moment at the centre of pressure, as the face's
//! ([`crate::TwistCentre`]), and by default friction and twist on one ellipsoid as the face's
//! ([`crate::FrictionLimit`]) — a sticking segment is stepped whole like a face, and the
//! admissible set is the same.
//!
//! Across steps the block is carried as the impulse it applied ([`crate::ContactImpulse`]):
//! `u` turns with the segment, so its tilt is read anew on the next step's axes, whether the
//! segment stays one (its ends swapped or clipped by other edges) or becomes a face or a point.

use nalgebra::Vector2;
use tatami_lcp::{LinearSet, Projection, RowBound, TwistCoupling};

use crate::face::{MIN_NORMAL_IMPULSE, twist_interval};
use crate::limit_surface::{LimitSurface, is_coupled};
use crate::{FrictionCone, FrictionLimit, TwistCentre};

/// Rows of a segment block.
pub const ROWS: usize = 5;

/// Row indices within a segment block.
const NORMAL: usize = 0;
const FRICTION_1: usize = 1;
const TILT: usize = 3;
const TWIST: usize = 4;

/// The projection of a segment block onto its admissible wrenches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentProjection {
    /// Force friction coefficient for this step.
    pub friction: f64,
    /// `μ r̄`: the twist bound per unit normal impulse (m).
    pub twist_per_normal: f64,
    /// Half the segment's length: the tilt bound per unit normal impulse (m).
    pub half_length: f64,
    /// The segment's direction `s` in the contact plane (unit, on the tangents `t1`, `t2`):
    /// the centre of pressure is `x s` from `G`, where the friction force acts.
    pub along: Vector2<f64>,
    /// About which point the twist is bounded.
    pub twist_centre: TwistCentre,
    /// Box or circular friction bound.
    pub cone: FrictionCone,
    /// Whether the friction force and the twist share one limit surface (with the circle).
    pub friction_limit: FrictionLimit,
}

impl SegmentProjection {
    /// The middle of the twist's admissible interval `τ3 ∈ c ± μ r̄ f3` for impulses `λ`, as
    /// the face's ([`crate::face::FaceProjection::twist_midpoint`]): about the centre of pressure
    /// `x s` (`x = −τu / f3`), the friction force's moment there, `x (s × f)·n`; about `G`, 0.
    pub fn twist_midpoint(&self, impulses: &[f64]) -> f64 {
        let Some(x) = self.twist_lever(impulses) else {
            return 0.0;
        };
        let (f1, f2) = (impulses[FRICTION_1], impulses[FRICTION_1 + 1]);
        x * (self.along.x * f2 - self.along.y * f1)
    }

    /// `x = −τu / f3`, where along the segment the twist is bounded about: the centre of
    /// pressure; `None` where that is `G` ([`TwistCentre::Centroid`], or no load).
    fn twist_lever(&self, impulses: &[f64]) -> Option<f64> {
        let f3 = impulses[NORMAL];
        if self.twist_centre == TwistCentre::Centroid || f3 <= MIN_NORMAL_IMPULSE {
            return None;
        }
        // A NaN load reads through, to be reported.
        Some(-impulses[TILT] / f3)
    }

    /// The friction force's and the twist's one limit surface under the normal impulse `f3`,
    /// when they share one.
    fn limit_surface(&self, f3: f64) -> Option<LimitSurface> {
        is_coupled(self.friction_limit, self.cone).then_some(LimitSurface {
            force: self.friction * f3,
            twist: self.twist_per_normal * f3,
            friction_row: FRICTION_1,
            twist_row: TWIST,
        })
    }

    /// The twist's admissible interval ([`twist_interval`] about [`Self::twist_midpoint`]), as
    /// the projection clamps to it and `admissible` reads it.
    fn twist_bounds(&self, impulses: &[f64]) -> (f64, f64) {
        twist_interval(
            self.twist_midpoint(impulses),
            self.twist_per_normal,
            impulses[NORMAL],
        )
    }
}

impl Projection for SegmentProjection {
    #[inline]
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        impulses[NORMAL] = impulses[NORMAL].max(0.0);
        let f3 = impulses[NORMAL];
        let tilt = self.half_length * f3;
        impulses[TILT] = impulses[TILT].max(-tilt).min(tilt);
        if let Some(surface) = self.limit_surface(f3) {
            surface.clamp(impulses, |λ| self.twist_midpoint(λ));
            return;
        }
        self.cone.clamp(&mut impulses[1..3], self.friction * f3);
        let (low, high) = self.twist_bounds(impulses);
        impulses[TWIST] = impulses[TWIST].max(low).min(high);
    }

    #[inline]
    fn tangent_pair(&self) -> Option<usize> {
        self.cone.tangent_pair(FRICTION_1)
    }

    /// The twist row, coupled to the friction pair by the limit surface, with `p = x s` the
    /// centre of pressure (`G` itself when the twist is bounded there).
    fn twist_coupling(&self, impulses: &[f64]) -> Option<TwistCoupling> {
        let x = self.twist_lever(impulses).unwrap_or(0.0);
        // Per unit normal impulse: `r̄` is the bounds' ratio whatever the load.
        self.limit_surface(1.0)?
            .coupling([x * self.along.x, x * self.along.y])
    }

    /// `f3`; without it the segment carries no friction, tilt or twist.
    #[inline]
    fn leading_normal_rows(&self) -> usize {
        NORMAL + 1
    }

    /// A sticking segment with its centre of pressure inside is solved in one step.
    fn whole_block(&self) -> bool {
        true
    }

    fn admissible(&mut self, impulses: &[f64]) -> bool {
        let f3 = impulses[NORMAL];
        if f3 > MIN_NORMAL_IMPULSE {
            impulses[TILT].abs() <= self.half_length * f3
                && match self.limit_surface(f3) {
                    Some(surface) => surface.contains(impulses, self.twist_midpoint(impulses)),
                    None => {
                        let (low, high) = self.twist_bounds(impulses);
                        self.cone
                            .contains(&impulses[FRICTION_1..FRICTION_1 + 2], self.friction * f3)
                            && (low..=high).contains(&impulses[TWIST])
                    }
                }
        } else {
            // Unloaded (or NaN): only the zero wrench is admissible.
            impulses.iter().all(|&x| x == 0.0)
        }
    }

    /// Only the normal row is a plain bound; the others scale with it (see
    /// [`Projection::linear_set`]).
    fn bound(&self, row: usize) -> Option<RowBound> {
        (row == NORMAL).then_some(RowBound::NonNegative)
    }

    /// The admissible wrenches exactly: `(f3, τu) = Σ βₖ (1, −xₖ)` over the two ends,
    /// `xₖ = ∓L/2`, `βₖ ≥ 0` the normal force at end `k`; friction and twist at `G`, bounded by
    /// `μ f3` and `μ r̄ f3` with `f3 = Σ βₖ` — the face's set for a polygon of two vertices,
    /// its twist bounded about `G` whatever [`TwistCentre`] says, as the face's.
    fn linear_set(&self, rows: usize) -> Option<LinearSet> {
        let mut set = LinearSet::new(rows);
        let ends: Vec<usize> = [self.half_length, -self.half_length]
            .iter()
            .map(|&tilt| set.generator(vec![(NORMAL, 1.0), (TILT, tilt)]))
            .collect();
        let friction: Vec<(usize, f64)> = ends.iter().map(|&e| (e, self.friction)).collect();
        self.cone.add_to(&mut set, FRICTION_1, &friction);
        let twist = ends.iter().map(|&e| (e, self.twist_per_normal)).collect();
        set.symmetric(TWIST, twist);
        Some(set)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn segment(cone: FrictionCone, friction_limit: FrictionLimit) -> SegmentProjection {
        SegmentProjection {
            friction: 0.5,
            twist_per_normal: 0.5 * 0.25,
            half_length: 0.5,
            along: Vector2::new(0.6, 0.8),
            twist_centre: TwistCentre::CentreOfPressure,
            cone,
            friction_limit,
        }
    }

    #[test]
    fn the_centre_of_pressure_stays_on_the_segment() {
        let mut p = segment(FrictionCone::Circle, FrictionLimit::Separate);
        // f3 = 2: tilt within ±1, twist within ±0.25, friction within 1.
        let mut impulses = [2.0, 3.0, 4.0, -5.0, 0.1];
        p.project(&mut impulses, TILT);
        assert_eq!(
            impulses[TILT], -1.0,
            "the centre of pressure at the far end"
        );
        assert!((impulses[1].hypot(impulses[2]) - 1.0).abs() < 1e-12);
        assert_eq!(impulses[TWIST], 0.1);
        assert!(p.admissible(&impulses));
    }

    #[test]
    fn a_pulling_normal_leaves_nothing() {
        let mut p = segment(FrictionCone::Box, FrictionLimit::Coupled);
        let mut impulses = [-1.0, 3.0, -0.4, 0.2, 0.1];
        p.project(&mut impulses, NORMAL);
        assert_eq!(impulses, [0.0; 5]);
        assert!(p.admissible(&impulses));
        assert!(!p.admissible(&[0.0, 0.0, 0.0, 0.1, 0.0]));
    }

    /// `admissible` says yes exactly where `project` changes nothing, on a grid of wrenches in
    /// and out of the set.
    #[test]
    fn admissible_is_where_the_projection_is_the_identity() {
        let kinds = [
            (FrictionCone::Circle, FrictionLimit::Coupled),
            (FrictionCone::Circle, FrictionLimit::Separate),
            (FrictionCone::Box, FrictionLimit::Coupled),
        ];
        for (cone, limit) in kinds {
            let mut p = segment(cone, limit);
            let values = [-1.5, -0.6, -0.2, 0.0, 0.3, 0.9, 2.0];
            for f3 in [0.0, 0.5, 2.0] {
                for f1 in values {
                    for tilt in values {
                        for twist in values {
                            let impulses = [f3, f1, 0.4, tilt, twist * 0.3];
                            let mut projected = impulses;
                            p.project(&mut projected, NORMAL);
                            assert_eq!(
                                p.admissible(&impulses),
                                projected == impulses,
                                "{impulses:?} ({cone:?}, {limit:?})"
                            );
                        }
                    }
                }
            }
        }
    }
    /// The coupled limit surface by hand: `f3 = 2`, `μ = 0.5` (`|f| ≤ 1`), `μ r̄ = 0.125`
    /// (`r̄ = 0.25`), the centre of pressure `x = −τu / f3 = 0.25` along `s = (0.6, 0.8)` and
    /// friction `(0.6, 0)`, whose moment there is `0.25 (0.6 · 0 − 0.8 · 0.6) = −0.12`: the
    /// twist about it may be `±0.25 √(1 − 0.6²) = ±0.2`, so `τ3 ∈ [−0.32, 0.08]` stands; `τ3 =
    /// 0.88` (1.0 about it, `τ′/r̄ = 4`) is scaled onto the ball with the force, by `1/√16.36`.
    #[test]
    fn a_segments_force_and_twist_share_one_ellipsoid() {
        let mut p = segment(FrictionCone::Circle, FrictionLimit::Coupled);
        for (twist, stands) in [
            (-0.33, false),
            (-0.32, true),
            (0.0, true),
            (0.08, true),
            (0.09, false),
        ] {
            assert_eq!(
                p.admissible(&[2.0, 0.6, 0.0, -0.5, twist]),
                stands,
                "{twist}"
            );
        }
        let mut impulses = [2.0, 0.6, 0.0, -0.5, 0.88];
        p.project(&mut impulses, TWIST);
        let shrink = 1.0 / 16.36f64.sqrt();
        let expected = [2.0, 0.6 * shrink, 0.0, -0.5, 0.88 * shrink];
        for (got, want) in impulses.iter().zip(expected) {
            assert!((got - want).abs() < 1e-15, "{impulses:?}");
        }
        assert!(p.admissible(&impulses));
    }
}
