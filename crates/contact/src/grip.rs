//! A grip: the friction of a contact that a body which cannot give way presses in beyond the
//! slop — a kinematic body, driven by position, as a gripper's fingers or a VR hand are.
//!
//! Split impulses put an overlap's push in a position pass that carries no momentum, so the
//! velocity solve sees no normal force where such a body presses: a cube squeezed 1 cm deep
//! between two kinematic fingers fell as if free under every model (rapier3d-f64, whose soft
//! contacts turn the overlap into force, lifted it squeezed by 1 mm). Rigid bodies leave the
//! force of an overlap the driven body will not give up undetermined. The grip takes it as the
//! impulse that would stop the bodies closing by the overlap beyond the slop within one step,
//! `p = (d − slop) / (k dt)` with `k = J M⁻¹ Jᵀ` along the normal at the support's centroid `G`
//! and `d` the mean depth over the support's vertices: as stiff as one step can be, and, like
//! Rapier's and Box2D's soft contacts, in proportion to the mass it holds.
//!
//! What the grip adds is the friction `p` bears, not `p` itself (the position pass still
//! pushes the overlap out, without speed): a block of two friction rows at `G` bounded by
//! `μ p`, and a twist row bounded by `μ r̄ p` where the support has area or length, beside the
//! model's own blocks — by default force and twist on one ball, as the face's
//! ([`crate::FrictionLimit`]). Their friction adds to the model's `μ f3`, and the sum of two
//! discs (or balls of one `r̄`) is the disc (ball) of the summed radius: the contact's friction
//! is bounded by `μ (f3 + p)`.
//!
//! ```
//! use nalgebra::{Point2, Point3, Vector3};
//! use tatami_contact::{Contact, ContactFrame, ContactSettings, Material, grip};
//! use tatami_geometry::ConvexPolygon;
//! use tatami_lcp::{BodyId, Problem, SolverBody};
//!
//! // A 2 kg body pressed 5 mm into a kinematic one (B) over a 10 cm square.
//! let mut held = SolverBody::fixed();
//! held.inv_mass = 0.5;
//! let square = [(-0.05, -0.05), (0.05, -0.05), (0.05, 0.05), (-0.05, 0.05)];
//! let contact = Contact {
//!     body_a: BodyId(0),
//!     body_b: BodyId(1),
//!     centre_a: Point3::new(0.0, 0.0, 0.1),
//!     centre_b: Point3::new(0.0, 0.0, -0.1),
//!     frame: ContactFrame::from_normal(Point3::origin(), Vector3::z())?,
//!     support: ConvexPolygon::from_points(&square.map(|(x, y)| Point2::new(x, y)))?,
//!     depths: vec![0.005; 4],
//!     material: Material::new(0.5, 0.5, 0.0)?,
//!     landing: Vec::new(),
//!     bounce_speed: 0.0,
//! };
//! let mut problem = Problem { bodies: vec![held, SolverBody::fixed()], ..Default::default() };
//! let settings = ContactSettings::default();
//! let dt = 0.01;
//! let excess = grip::excess(&contact, &settings);
//! assert!(grip::build(&contact, excess, dt, &settings, &mut problem, &mut Vec::new()));
//! assert_eq!(problem.rows.len(), 3, "two friction rows and a twist row");
//! // The 3 mm beyond the slop stopped within a step by 2 kg: 0.6 N s, 0.3 N s of friction.
//! let p = (0.005 - settings.slop) * 2.0 / dt;
//! assert!(grip::GripProjection::of(&problem.blocks[0].projection).is_some_and(|g| {
//!     (g.friction - 0.5 * p).abs() < 1e-12
//! }));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use tatami_lcp::{Block, LinearSet, Problem, Projection, Row, RowBound, TwistCoupling};

use crate::jacobian::{Witness, angular_jacobian, block_friction_motion, point_jacobian};
use crate::limit_surface::{LimitSurface, is_coupled};
use crate::{
    Contact, ContactProjection, ContactRows, ContactSettings, FrictionCone, FrictionLimit,
};

/// The projection of a grip's rows: friction `[f1, f2]` within `friction` (the cone's shape
/// from the settings), then, if the block has it, a twist within `±twist`.
#[derive(Debug, Clone, PartialEq)]
pub struct GripProjection {
    /// `p` (N s): the press, the impulse the overlap beyond the slop presses with over the
    /// step, along the normal at the support's centroid.
    pub press: f64,
    /// `μ p` (N s): the most friction impulse the grip bears.
    pub friction: f64,
    /// `μ r̄ p` (N m s): the most twist impulse it bears.
    pub twist: f64,
    /// Box or circular friction bound.
    pub cone: FrictionCone,
    /// Whether the friction force and the twist share one limit surface (with the circle), as
    /// a face's ([`crate::FrictionLimit`]).
    pub friction_limit: FrictionLimit,
}

impl GripProjection {
    /// The grip's projection, if `projection` is one.
    pub fn of(projection: &ContactProjection) -> Option<&GripProjection> {
        match projection {
            ContactProjection::Grip(grip) => Some(grip),
            _ => None,
        }
    }
}

/// The twist row's index in a grip's block, when it has one.
const TWIST: usize = 2;

impl GripProjection {
    /// The friction force's and the twist's one limit surface, when they share one and the
    /// block of `rows` rows has a twist row. About the support's centroid, where the grip's
    /// rows act: the press has no centre of its own.
    fn limit_surface(&self, rows: usize) -> Option<LimitSurface> {
        (is_coupled(self.friction_limit, self.cone) && rows > TWIST).then_some(LimitSurface {
            force: self.friction,
            twist: self.twist,
            friction_row: 0,
            twist_row: TWIST,
        })
    }
}

impl Projection for GripProjection {
    #[inline]
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        if let Some(surface) = self.limit_surface(impulses.len()) {
            surface.clamp(impulses, |_| 0.0);
            return;
        }
        self.cone.clamp(&mut impulses[..2], self.friction);
        if let Some(twist) = impulses.get_mut(TWIST) {
            *twist = twist.max(-self.twist).min(self.twist);
        }
    }

    #[inline]
    fn tangent_pair(&self) -> Option<usize> {
        self.cone.tangent_pair(0)
    }

    fn twist_coupling(&self, impulses: &[f64]) -> Option<TwistCoupling> {
        self.limit_surface(impulses.len())?.coupling([0.0, 0.0])
    }

    /// Fixed bounds, a product of row bounds but for the circular cone.
    fn bound(&self, row: usize) -> Option<RowBound> {
        match (row, self.cone) {
            (0 | 1, FrictionCone::Box) => Some(RowBound::Box {
                lo: -self.friction,
                hi: self.friction,
            }),
            (TWIST, _) => Some(RowBound::Box {
                lo: -self.twist,
                hi: self.twist,
            }),
            _ => None,
        }
    }

    /// The cone within `μ p` ([`FrictionCone::add_limited_to`]) and the twist within `μ r̄ p`.
    fn linear_set(&self, rows: usize) -> Option<LinearSet> {
        let mut set = LinearSet::new(rows);
        self.cone.add_limited_to(&mut set, 0, self.friction);
        if rows > TWIST {
            set.symmetric(TWIST, Vec::new());
            set.budgets.last_mut()?.constant = self.twist;
        }
        Some(set)
    }
}

/// How far `contact` is pressed in beyond the slop: the mean over its support's vertices of
/// `max(d − slop, 0)` (m); 0 without vertices.
pub fn excess(contact: &Contact, settings: &ContactSettings) -> f64 {
    let depths = &contact.depths;
    if depths.is_empty() {
        return 0.0;
    }
    depths
        .iter()
        .map(|d| (d - settings.slop).max(0.0))
        .sum::<f64>()
        / depths.len() as f64
}

/// Appends `contact`'s grip for a press `excess` beyond the slop (m; [`excess`], or the
/// caller's share of a press several contacts bear) to `problem`, with its rows' biases (none:
/// a grip pushes nothing) to `biases`; returns whether it did (not for no excess or no mass to
/// hold). The caller decides which contacts a body presses that cannot give way.
pub fn build(
    contact: &Contact,
    excess: f64,
    dt: f64,
    settings: &ContactSettings,
    problem: &mut Problem<ContactProjection>,
    biases: &mut Vec<f64>,
) -> bool {
    build_rows(
        contact,
        excess,
        dt,
        settings,
        &mut ContactRows::of(problem, biases),
    )
}

/// As [`build`], appending to `out`.
pub fn build_rows(
    contact: &Contact,
    excess: f64,
    dt: f64,
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) -> bool {
    let frame = &contact.frame;
    // The points the model's friction rows hold, beside which this grip acts.
    let witness = Witness::at(
        contact,
        &frame.to_world(&contact.support.centroid()),
        contact.depth(),
    );
    let (a, b) = (&out.bodies[contact.body_a.0], &out.bodies[contact.body_b.0]);
    let inverse_mass = point_jacobian(contact, &witness, &frame.normal).inverse_mass(a, b);
    // A NaN depth or mass is not `> 0` and adds no grip.
    if !(excess > 0.0 && inverse_mass > 0.0 && dt > 0.0) {
        return false;
    }
    let press = excess / (inverse_mass * dt);
    // As the model's own friction rows: on a face, the relative velocity that keeps the two
    // bodies' points together over the step while they turn together (a hand turning what
    // it holds), else no slip.
    let (_, slip, weld) =
        block_friction_motion(contact, out.bodies, &witness, dt, settings.slip_threshold);
    let mu = contact.material.friction(slip, settings.slip_threshold);
    let twist_radius = contact.support.centroid_mean_distance();
    let start = out.rows.len();
    let mut directions = vec![
        (
            point_jacobian(contact, &witness, &frame.tangent1),
            weld.dot(&frame.tangent1),
        ),
        (
            point_jacobian(contact, &witness, &frame.tangent2),
            weld.dot(&frame.tangent2),
        ),
    ];
    if twist_radius > 0.0 {
        directions.push((angular_jacobian(&frame.normal), 0.0));
    }
    let rows = directions.len();
    out.rows
        .extend(directions.into_iter().map(|(jacobian, target)| Row {
            jacobian,
            target,
            impulse: 0.0,
        }));
    out.biases.extend(std::iter::repeat_n(0.0, rows));
    out.blocks.push(Block {
        body_a: contact.body_a,
        body_b: contact.body_b,
        rows: start..start + rows,
        projection: ContactProjection::Grip(GripProjection {
            press,
            friction: mu * press,
            twist: mu * twist_radius * press,
            cone: settings.friction_cone,
            friction_limit: settings.friction_limit,
        }),
    });
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With the bounds apart, the direct solver's set and the PGS projection bound the same
    /// impulses: every corner of the set (one generator spending its whole budget, for each
    /// cone) is left alone by the projection, and the projection of impulses far outside lands
    /// on the bounds.
    #[test]
    fn the_linear_set_and_the_projection_bound_alike() {
        for cone in [FrictionCone::Box, FrictionCone::Circle] {
            let mut grip = GripProjection {
                press: 0.6,
                friction: 0.3,
                twist: 0.02,
                cone,
                friction_limit: FrictionLimit::Separate,
            };
            let set = grip.linear_set(3).expect("a grip has a linear set");
            for budget in &set.budgets {
                for &generator in &budget.spend {
                    let mut corner = set.offset.clone();
                    for &(row, coefficient) in &set.generators[generator] {
                        corner[row] += coefficient * budget.constant;
                    }
                    let mut projected = corner.clone();
                    grip.project(&mut projected, 0);
                    for (p, c) in projected.iter().zip(&corner) {
                        assert!(
                            (p - c).abs() < 1e-15,
                            "{cone:?}: {corner:?} → {projected:?}"
                        );
                    }
                }
            }
            let mut far = [3.0, -4.0, -1.0];
            grip.project(&mut far, 0);
            let friction = match cone {
                FrictionCone::Box => far[0].abs().max(far[1].abs()),
                FrictionCone::Circle => far[0].hypot(far[1]),
            };
            assert!(
                (friction - 0.3).abs() < 1e-15,
                "{cone:?}: friction {friction}"
            );
            assert_eq!(far[2], -0.02, "{cone:?}: the twist at its bound");
        }
    }

    /// With the force and the twist on one ball (the default), impulses far outside are scaled
    /// onto it along their own direction in `(f1, f2, τ/r̄)`, `r̄ = 0.02 / 0.3`; inside, left
    /// alone; without a twist row, the disc.
    #[test]
    fn a_coupled_grip_scales_force_and_twist_together() {
        let mut grip = GripProjection {
            press: 0.6,
            friction: 0.3,
            twist: 0.02,
            cone: FrictionCone::Circle,
            friction_limit: FrictionLimit::Coupled,
        };
        let r_bar = 0.02 / 0.3;
        let ball = |x: &[f64; 3]| (x[0].powi(2) + x[1].powi(2) + (x[2] / r_bar).powi(2)).sqrt();
        let far = [3.0, -4.0, -1.0];
        let mut projected = far;
        grip.project(&mut projected, 0);
        assert!((ball(&projected) - 0.3).abs() < 1e-15, "{projected:?}");
        for k in 0..3 {
            assert!((projected[k] / far[k] - 0.3 / ball(&far)).abs() < 1e-15);
        }
        let inside = [0.1, 0.1, 0.01];
        let mut kept = inside;
        grip.project(&mut kept, 0);
        assert_eq!(kept, inside);
        let mut pair = [3.0, -4.0];
        grip.project(&mut pair, 0);
        assert!((pair[0].hypot(pair[1]) - 0.3).abs() < 1e-15);
        assert_eq!(grip.twist_coupling(&pair), None);
        assert!(grip.twist_coupling(&far).is_some());
    }
}
