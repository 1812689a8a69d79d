//! Settings shared by every contact model: penetration bias, restitution, friction switching.

use tatami_lcp::{Budget, LinearSet};

/// Shape of the friction bound at a point.
///
/// Decision record: the circle is the default because Coulomb friction is isotropic — a box
/// sliding diagonally must keep its heading and stop at `v²/(2μg)` whatever the orientation of
/// the contact frame's tangents, which are arbitrary. The pyramid bounds each tangent apart, so
/// it lets a diagonal slide up to √2 μ f3 of friction and turns it towards an axis; it stays for
/// reproducing the paper. The direct solver, whose problem must be linear, takes the circle as
/// its inscribed polygon of [`FrictionCone::DIRECT_FACETS`] sides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionCone {
    /// `|f1| ≤ μ f3` and `|f2| ≤ μ f3` separately (the paper's eq. 4): a pyramid aligned with
    /// the tangents, linear, so the direct solver solves it as it is. PGS updates and clamps
    /// each tangent row alone, the projected Gauss–Seidel of that pyramid.
    Box,
    /// `|(f1, f2)| ≤ μ f3`: isotropic Coulomb friction (default). PGS updates the two tangent
    /// rows together and scales them onto the disc (see `tatami_lcp::pgs`).
    #[default]
    Circle,
}

impl FrictionCone {
    /// Sides of the regular polygon inscribed in the circle that the direct solver solves
    /// with: its friction reaches `μ f3` towards each corner and `cos(π/16) μ f3 = 0.981 μ f3`
    /// mid-side, so it bounds friction up to 1.9% short of the circle (a slide's deceleration
    /// is between 0.981 μg and μg, depending on its heading).
    pub const DIRECT_FACETS: usize = 16;

    /// Adds the friction of tangent rows `first`, `first + 1` to `set`, bounded by the normal
    /// impulse that `earn` carries (generator, rate `μ`): the box as two symmetric budgets, the
    /// circle as its inscribed polygon of [`Self::DIRECT_FACETS`] generators spending one.
    pub fn add_to(self, set: &mut LinearSet, first: usize, earn: &[(usize, f64)]) {
        self.add_budgeted(set, first, earn, 0.0);
    }

    /// Adds the friction of tangent rows `first`, `first + 1` to `set`, bounded by the fixed
    /// `limit` (a [`crate::grip`]'s `μ p`), as [`add_to`](Self::add_to) does by a normal impulse.
    pub fn add_limited_to(self, set: &mut LinearSet, first: usize, limit: f64) {
        self.add_budgeted(set, first, &[], limit);
    }

    /// The budgets of [`add_to`](Self::add_to) earning `earn` on top of `constant`.
    fn add_budgeted(self, set: &mut LinearSet, first: usize, earn: &[(usize, f64)], constant: f64) {
        match self {
            Self::Box => {
                for row in [first, first + 1] {
                    set.symmetric(row, earn.to_vec());
                    if let Some(budget) = set.budgets.last_mut() {
                        budget.constant = constant;
                    }
                }
            }
            Self::Circle => {
                let spend = (0..Self::DIRECT_FACETS)
                    .map(|j| {
                        let angle = std::f64::consts::TAU * j as f64 / Self::DIRECT_FACETS as f64;
                        set.generator(vec![(first, angle.cos()), (first + 1, angle.sin())])
                    })
                    .collect();
                set.budgets.push(Budget {
                    spend,
                    earn: earn.to_vec(),
                    constant,
                });
            }
        }
    }

    /// The first tangent row of a block whose tangent rows start at `first`, if PGS must
    /// update the pair together ([`tatami_lcp::Projection::tangent_pair`]): for the circle.
    #[inline]
    pub fn tangent_pair(self, first: usize) -> Option<usize> {
        (self == Self::Circle).then_some(first)
    }

    /// Bounds the tangential impulse `tangential = [f1, f2]` by `limit` (already `μ` times the
    /// normal impulse): each axis for the box, the magnitude (direction kept) for the circle.
    #[inline]
    pub fn clamp(self, tangential: &mut [f64], limit: f64) {
        match self {
            Self::Box => {
                for f in &mut tangential[..2] {
                    *f = f.max(-limit).min(limit);
                }
            }
            Self::Circle => {
                // Well inside the disc by the squares, which PGS finds after most of its row
                // updates, the square root is not needed: the rounded root of the squares
                // would be below `limit` (the margin of 4 ulps covers the roundings of both
                // squares and of the root), and nothing changes. Otherwise, the exact test.
                let (f1, f2) = (tangential[0], tangential[1]);
                if f1 * f1 + f2 * f2 < limit * limit * (1.0 - 4.0 * f64::EPSILON) {
                    return;
                }
                let norm = magnitude(f1, f2);
                if norm > limit {
                    tangential[0] *= limit / norm;
                    tangential[1] *= limit / norm;
                }
            }
        }
    }

    /// Whether `tangential = [f1, f2]` is within `limit` already, so that
    /// [`clamp`](Self::clamp) would leave it as it is.
    pub fn contains(self, tangential: &[f64], limit: f64) -> bool {
        match self {
            Self::Box => tangential[..2].iter().all(|f| f.abs() <= limit),
            Self::Circle => magnitude(tangential[0], tangential[1]) <= limit,
        }
    }
}

/// `√(f1² + f2²)` rather than `hypot`, which guards against an overflow that finite impulses
/// below 1e154 N·s cannot reach and costs several times more in PGS's innermost loop; `hypot`
/// takes over past that.
#[inline]
fn magnitude(f1: f64, f2: f64) -> f64 {
    let norm = (f1 * f1 + f2 * f2).sqrt();
    if norm.is_finite() { norm } else { f1.hypot(f2) }
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

/// About which point the face model bounds a face's or a segment's twist by `μ r̄ f3`.
///
/// Decision record: the friction force of a contact acts where its pressure does, and a body
/// held by friction leaves no twist about that point. The paper bounds the twist about the
/// support polygon's centroid `G`, where the block's rows act, so a face loaded off its centre
/// (its centre of pressure at `p`) and pushed along the plane needs the moment `(p − G) × f`
/// of its friction force as twist about `G`: a plank sticking on a 25° ramp over the ramp's
/// corner, bearing on a strip whose centroid is 0.47 m from its centre of mass, needed 0.22
/// `f3` of twist there against a bound of 0.15 `f3` and spun off; the cubes of a settled pile
/// resting across edges of the cubes below crept round and slid off seconds later. Bounded
/// about the centre of pressure, the plank stays, as the vertex and patch models hold it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TwistCentre {
    /// `|τ3 − (p − G) × f| ≤ μ r̄ f3` with `p` the centre of pressure and `f` the friction
    /// force (default). Not a linear set: the direct solver bounds the twist about `G`.
    #[default]
    CentreOfPressure,
    /// `|τ3| ≤ μ r̄ f3` about `G` (the paper's eqs. 10–11): the face model's linear set, which
    /// the direct solver solves.
    Centroid,
}

/// How the face model bounds a face's or a segment's friction force `f` and its twist `τ′`
/// about the centre of pressure, and a grip its own ([`crate::grip`]), with the isotropic
/// [`FrictionCone::Circle`] (the box cone, the paper's, bounds them apart always).
///
/// Decision record: friction acts at every point of a face, and a point slips one way at one
/// speed, so a face that slides and spins shares one budget between the two: the exact bound is
/// the face's *limit surface*, close to the ellipsoid `|f|² + (τ′/r̄)² ≤ (μ f3)²` (Goyal, Ruina
/// and Papadopoulos, 1991; Lynch's planar pushing), whose rim the max-dissipation principle
/// reaches where the sliding velocity at the centre of pressure and `r̄` times the spin point
/// along `(f, τ′/r̄)`. Bounded apart (`|f| ≤ μ f3`, `|τ′| ≤ μ r̄ f3`) a face sliding and spinning
/// gets both bounds at once: a 0.1 m puck on μ 0.3 at 1 m/s spinning at ωR = 2 m/s stopped
/// sliding at 0.34 s and spinning at 0.51 s, where per-point Coulomb friction integrated over
/// its uniformly pressed disc stops both together at 0.648 s. On the ellipsoid the face model
/// stops both together at 0.617 s (60 Hz; the ellipsoid's own equations of motion: 0.613 s),
/// a 0.2 m square plate at 0.683/0.700 s against 0.715 s (`tatami-world`'s
/// `tests/planar_sliding.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionLimit {
    /// One ellipsoidal limit surface over `(f, τ′/r̄)` (default): PGS steps the friction pair
    /// and the twist together along the slip at the centre of pressure
    /// ([`tatami_lcp::Projection::twist_coupling`]). The direct solver's linear set bounds them
    /// apart.
    #[default]
    Coupled,
    /// `|f| ≤ μ f3` and `|τ′| ≤ μ r̄ f3` apart (the paper's eqs. 4, 10–11).
    Separate,
}

/// Fraction of the depth beyond the slop that the normal row's penetration bias removes per
/// step. Default 0.1 (Springhead's).
pub const DEFAULT_BIAS_RATE: f64 = 0.1;

/// Penetration left uncorrected (m). Default 2 mm (Springhead's), so resting contacts stay
/// touching.
pub const DEFAULT_SLOP: f64 = 0.002;

/// Fastest separation (m/s) the penetration bias may ask for at one contact. Default 1 m/s,
/// within the 1–3 m/s of Box2D's contact push speed: bodies created overlapping separate over a
/// few steps instead of being pushed at `bias_rate · depth / dt` (0.1 · 0.5 m / 0.01 s = 5 m/s for
/// two coincident unit cubes). Restitution is not capped.
pub const DEFAULT_MAX_DEPENETRATION_SPEED: f64 = 1.0;

/// The part of the penetration push (m/s) the velocity solve takes at one contact; the rest
/// goes to a position pass that moves the bodies without giving them speed (split impulses).
///
/// Default 0: the whole push moves positions only, which adds no energy. Measured on a tower of
/// 100 cubes of 2 m (face model, 15 sweeps, warm start, 10 s): with 0.2 m/s in the velocity solve
/// the tower bounced, up to 18 m/s; with 0 its speeds decay (0.3 m/s at 10 s). Without warm
/// starting the opposite holds — a velocity bias (Baumgarte) is what keeps the solver's
/// residual from sinking tall stacks step after step: with 15 cold sweeps the face model's tower
/// stands to 50 cubes with the whole push in the velocity and to 10 with none, so set it to
/// `max_depenetration_speed` when solving cold, as the paper's experiments do.
pub const DEFAULT_MAX_VELOCITY_BIAS: f64 = 0.0;

/// How contact rows turn depth, approach speed and slip into targets and bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSettings {
    /// Fraction of the depth beyond `slop` removed per step by the normal row's target; see
    /// [`DEFAULT_BIAS_RATE`].
    pub bias_rate: f64,
    /// Penetration left uncorrected (m); see [`DEFAULT_SLOP`].
    pub slop: f64,
    /// Cap on the penetration bias's separation speed (m/s); see
    /// [`DEFAULT_MAX_DEPENETRATION_SPEED`].
    pub max_depenetration_speed: f64,
    /// The part of the push the velocity solve takes (m/s); see [`DEFAULT_MAX_VELOCITY_BIAS`].
    pub max_velocity_bias: f64,
    /// Approach speed above which restitution applies (m/s).
    pub restitution_threshold: f64,
    /// Slip speed above which a contact uses kinetic friction (m/s). For twist the slip speed is
    /// the twist rate times `r̄`.
    pub slip_threshold: f64,
    /// Friction bound at each point; isotropic by default ([`FrictionCone`]).
    pub friction_cone: FrictionCone,
    /// Face model: how `r̄` is computed.
    pub twist_radius: TwistRadius,
    /// Face model: about which point the twist is bounded ([`TwistCentre`]).
    pub twist_centre: TwistCentre,
    /// Face model: remove the part of the torque parallel to the force before the ZMP step (the
    /// paper's eq. 12 variant).
    pub remove_parallel_torque: bool,
    /// Face model: a face's or a segment's friction force and twist bounded together or apart
    /// ([`FrictionLimit`]).
    pub friction_limit: FrictionLimit,
}

impl Default for ContactSettings {
    /// Springhead's bias (rate 0.1 beyond 2 mm) capped at 1 m/s, all of it for a position pass,
    /// Box2D's 1 m/s restitution threshold, kinetic friction above 1 mm/s of slip, isotropic
    /// friction, exact `r̄`, the twist bounded about the centre of pressure and together with
    /// the friction force.
    fn default() -> Self {
        Self {
            bias_rate: DEFAULT_BIAS_RATE,
            slop: DEFAULT_SLOP,
            max_depenetration_speed: DEFAULT_MAX_DEPENETRATION_SPEED,
            max_velocity_bias: DEFAULT_MAX_VELOCITY_BIAS,
            restitution_threshold: 1.0,
            slip_threshold: 1e-3,
            friction_cone: FrictionCone::Circle,
            twist_radius: TwistRadius::Exact,
            twist_centre: TwistCentre::CentreOfPressure,
            remove_parallel_torque: false,
            friction_limit: FrictionLimit::Coupled,
        }
    }
}

/// The share of the slop within which a gap counts as closed for a bounce
/// ([`ContactSettings::has_landed`]): 0.1 mm by default, far under the slop, and over the few
/// micrometres by which a landing's solve may leave the bodies apart (its rows stop within
/// 0.1 mm/s, 2 µm a step at 60 Hz).
const LANDED_SHARE_OF_SLOP: f64 = 0.05;

impl ContactSettings {
    /// Whether a point of a contact at `depth` (> 0 overlapping, < 0 apart) has landed: only
    /// then does it bounce. A point still apart is landed on the surface first, its gap a
    /// target it may close in the step and no more, and bounced on the next step at
    /// [`Contact::bounce_speed`](crate::Contact::bounce_speed): bounced off the gap, a ball
    /// dropped 1 m with restitution 0.8 at 60 Hz rose 22 mm too high, up to a step's approach
    /// above the floor, and at 1 kHz one bounced 1.1 mm above the floor without touching it.
    ///
    /// ```
    /// use tatami_contact::ContactSettings;
    ///
    /// let settings = ContactSettings::default();
    /// assert!(settings.has_landed(0.001));
    /// assert!(settings.has_landed(-0.00005));
    /// assert!(!settings.has_landed(-0.001));
    /// ```
    pub fn has_landed(&self, depth: f64) -> bool {
        depth >= -LANDED_SHARE_OF_SLOP * self.slop
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// The circle's clamp as the square root alone decides it, the oracle of the shortcut.
    fn clamped_by_root(mut tangential: [f64; 2], limit: f64) -> [f64; 2] {
        let norm = magnitude(tangential[0], tangential[1]);
        if norm > limit {
            tangential[0] *= limit / norm;
            tangential[1] *= limit / norm;
        }
        tangential
    }

    proptest! {
        /// The shortcut inside the disc changes no bit: tangential impulses within a few ulps of
        /// the limit on either side (where the squares and the root round differently), far
        /// inside and outside, over magnitudes from 1e-150 to 1e150.
        #[test]
        fn the_circle_clamps_as_its_square_root_decides(
            angle in 0.0..std::f64::consts::TAU,
            exponent in -150i32..150,
            ulps in -16i64..16,
            scale in prop_oneof![Just(1.0), 0.0..2.0],
        ) {
            let limit = 10f64.powi(exponent);
            let norm = f64::from_bits((limit * scale).to_bits().saturating_add_signed(ulps));
            let tangential = [norm * angle.cos(), norm * angle.sin()];
            let mut clamped = tangential;
            FrictionCone::Circle.clamp(&mut clamped, limit);
            let expected = clamped_by_root(tangential, limit);
            prop_assert_eq!(clamped.map(f64::to_bits), expected.map(f64::to_bits));
        }
    }

    #[test]
    fn non_finite_and_zero_limits_take_the_exact_path() {
        for (tangential, limit) in [
            ([3.0, 4.0], 0.0),
            ([0.0, 0.0], 0.0),
            ([1e200, 1e200], 1.0),
            ([3.0, 4.0], f64::INFINITY),
            ([3.0, 4.0], f64::NAN),
        ] {
            let mut clamped = tangential;
            FrictionCone::Circle.clamp(&mut clamped, limit);
            let expected = clamped_by_root(tangential, limit);
            assert_eq!(
                clamped.map(f64::to_bits),
                expected.map(f64::to_bits),
                "{tangential:?} within {limit}"
            );
        }
    }
}
