//! Bounces from the surface: a bouncing pair that its contact lands on each other from a gap is
//! bounced on the next step, at the speed it met at.
//!
//! A speculative contact ([`crate::speculative`]) finds a pair up to a step before its bodies
//! meet, and its gap is a target the normal row may close in the step and no more. Bounced from
//! there at once, as Box2D v3 and Rapier do, the bounce would start from the gap, up to a
//! step's approach short of the surface (a ball dropped 1 m with restitution 0.8 at 60 Hz rose
//! 22 mm, 3.4%, too high). So a point still apart is landed on the surface without a bounce
//! ([`ContactSettings::has_landed`]), the pair keeps the speed it met at, and its next step's
//! contact bounces its landed points ([`Contact::bounce_speed`]): the bounce starts at the
//! surface, a step late at most. Before, bouncing pairs kept the plain margin and were met only
//! once they overlapped: a ball or a cube thrown at 60 m/s at a wall 0.2 m thick went through
//! it from 13 of 20 starts, whatever its restitution above 0.
//!
//! Both speeds are those of the integrator, which moves a body by its velocity at the step's
//! end (semi-implicit Euler): that velocity stands for the middle of the step, so under an
//! acceleration `a` along the normal `(v − a dt / 2)² / 2 + a x` is kept exactly in free
//! flight. The speed met at is the one that quantity gives at the surface, and the bounce,
//! from the surface at the step's start, is `e` times it less half a step of `a`: the bounce
//! then scales the quantity by `e²`, and a ball dropped from `h` rises to `e² h` (0.64 m from
//! 1 m with `e` = 0.8 at 60 Hz: 0.6401 m; bounced at `e` times the step's approach plus its
//! gravity, 0.665 m).
//!
//! Every point that bounces leaves at that one speed, and those points need not be the ones
//! that met, nor have met evenly: a tumbling cube meets the floor with a corner and bounces
//! with its face, which that speed lifts through the whole cube's mass. So the bounce is
//! capped by energy: it gives back at most `e²` of what the impact took — the energy the
//! landing step took from the pair, and what stopping the points that bounce still takes
//! (Stronge's energetic restitution, on the pair's coupling of those points' normal
//! velocities; [`Impacts::bounce_speed`]). A ball, met and bounced at one point through its
//! centre, bounces at Newton's speed. Friction is not in that cap; what it adds (a rim's
//! reaction turning spin into lift) is held back after the solve, the bounce held to what its
//! landing took ([`crate::bounce_guard`]). A corner or an edge of two polytopes bounces at the
//! arm it landed with, not the one the landing step turned it to, and without restitution is
//! stopped there ([`bounce_where_landed`]).

use nalgebra::{DMatrix, DVector, Point2, Vector2, Vector3};
use tatami_contact::{Contact, ContactSettings};
use tatami_lcp::{Row, SolverBody};

use crate::body::Body;
use crate::tolerances;

/// How a pair met in a step (its touchdown), handed on to the next step's bounce
/// ([`Impacts::landing`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Touchdown {
    /// The speed met at, at the centroid of the points that met (m/s); 0 for no landing.
    pub speed: f64,
    /// Twice the kinetic energy it takes to stop those points along the normal, each at the
    /// speed it met at (J): `uᵀ A⁺ u`, `u` their speeds and `A` the pair's coupling of their
    /// normal velocities ([`Impacts::coupling`]); the most the landing step's energy drop
    /// counts for in the bounce ([`Impacts::bounce_speed`]).
    pub stopping: f64,
    /// Twice the pair's energy as the integrator keeps it in free flight, when the step it
    /// landed in started (J; [`Impacts::kept_energy`]).
    pub energy: f64,
    /// Where the points that met met, as arms from A's and B's centres of mass when the step
    /// it landed in started (m, world axes): the rest of the impact, and the bounce, act there
    /// ([`bounce_where_landed`]). Kept for a pair that does not bounce too, whose `speed` is 0.
    pub arms: Option<[Vector3<f64>; 2]>,
}

/// A step's bodies, gravity, length and contact settings, which the speeds of its landings
/// and bounces read.
pub(crate) struct Impacts<'a> {
    /// The world's bodies, indexed by the contacts' ids.
    pub bodies: &'a [Body],
    /// Gravity (m/s²), which pulls the dynamic bodies alone.
    pub gravity: &'a Vector3<f64>,
    /// The step (s).
    pub dt: f64,
    /// When a point has landed, and the restitution threshold.
    pub settings: &'a ContactSettings,
}

impl Impacts<'_> {
    /// The contact settings of `contact`'s pair, its slop held to its bodies' thickness
    /// ([`crate::tolerances`]), as its rows get them.
    fn settings_of(&self, contact: &Contact) -> ContactSettings {
        tolerances::pair_settings(self.settings, self.bodies, contact)
    }

    /// The acceleration (m/s²) with which gravity closes `contact`'s bodies along its normal
    /// (negative if it parts them).
    fn closing_pull(&self, contact: &Contact) -> f64 {
        let pulled = |body: &Body| {
            if body.is_dynamic() {
                *self.gravity
            } else {
                Vector3::zeros()
            }
        };
        let (a, b) = (
            &self.bodies[contact.body_a.0],
            &self.bodies[contact.body_b.0],
        );
        // The normal points from B into A: A closes on B against it.
        -(pulled(a) - pulled(b)).dot(&contact.frame.normal)
    }

    /// How `contact`'s bodies land on each other in this step, to bounce on the next (see the
    /// module doc for the integrator's speed): the speed of its points still apart that close
    /// their gaps in the step, taken at their centroid with their mean gap, the energy it takes
    /// to stop them ([`Touchdown::stopping`]) and the pair's energy as the step starts — or
    /// `met`, the last contact's landing, when faster and no point has landed yet (a landing
    /// the solve left short of the surface lands again, the speed kept). None for a pair that
    /// does not bounce, whose points apart do not close their gaps in the step, or that
    /// bounces in this step at `bounce_speed` ([`Impacts::bounce_speed`]; the contact models
    /// bounce its landed and closing points both). Read off the contact instead, the bounce
    /// was the last step's, or none for a contact found afresh: a pair bounced, handed its
    /// landing on again, and bounced a second time on the next step (two cubes with
    /// restitution 0.9 thrown at each other parted with up to 1.44 times their energy).
    ///
    /// Without restitution only where it met ([`Touchdown::arms`], its speed 0): the rest of
    /// the stop acts there ([`bounce_where_landed`]). Its pairs are most of a scene's, so a
    /// pair kept `still` in the collision pass (its bodies have not moved by the reuse
    /// tolerance since its contact was found: it meets at no speed that would tell), and one
    /// whose points cannot close their gaps in the step ([`Impacts::may_close`]), are passed
    /// over first.
    pub(crate) fn landing(
        &self,
        contact: &Contact,
        met: Touchdown,
        bounce_speed: f64,
        still: bool,
    ) -> Touchdown {
        if bounce_speed > 0.0 {
            return Touchdown::default();
        }
        let inelastic = contact.material.restitution == 0.0;
        if inelastic && still {
            return Touchdown::default();
        }
        let (pull, dt) = (self.closing_pull(contact), self.dt);
        let settings = self.settings_of(contact);
        if inelastic && !self.may_close(contact, pull) {
            return Touchdown::default();
        }
        // The speed a point at `gap` approaching at `approach` meets the other body at.
        let met_at = |approach: f64, gap: f64| {
            let middle = (approach + 0.5 * pull * dt).max(0.0);
            (middle * middle + 2.0 * pull * gap).max(0.0).sqrt()
        };
        // The points that close their gaps in the step meet as one: with the fastest of them
        // standing for the whole landing, every point of a face landing tilted and turning
        // bounced at its fastest corner's speed, and a cube dropped turned at random with
        // restitution 0.9 came up with up to 1.27 times the energy it was dropped with.
        let closing: Vec<(Point2<f64>, f64, f64)> = points(contact)
            .filter(|&(_, &depth)| !settings.has_landed(depth))
            .map(|(point, &depth)| (*point, -depth, self.approach(contact, point)))
            .filter(|&(_, gap, approach)| (approach + pull * dt) * dt >= gap)
            .collect();
        if closing.is_empty() {
            return Touchdown::default();
        }
        let count = closing.len() as f64;
        let centroid =
            Point2::from(closing.iter().map(|(p, ..)| p.coords).sum::<Vector2<f64>>() / count);
        let gap = closing.iter().map(|(_, gap, _)| gap).sum::<f64>() / count;
        let speed = met_at(self.approach(contact, &centroid), gap);
        let arms = Some(self.arms_at_impact(contact, &centroid, gap, speed));
        if inelastic {
            // Nothing to bounce: only where the impact ends.
            return Touchdown {
                arms,
                ..Touchdown::default()
            };
        }
        let at: Vec<Point2<f64>> = closing.iter().map(|(p, ..)| *p).collect();
        let speeds = DVector::from_iterator(
            closing.len(),
            closing
                .iter()
                .map(|&(_, gap, approach)| met_at(approach, gap)),
        );
        let here = Touchdown {
            speed,
            stopping: self.stopping(contact, &at, &speeds),
            energy: self.kept_energy(contact),
            arms,
        };
        let landed = contact.depths.iter().any(|&d| settings.has_landed(d));
        if landed || speed >= met.speed {
            here
        } else {
            met
        }
    }

    /// The arms from `contact`'s bodies' centres of mass to `point` (plane coordinates, `gap`
    /// apart, met at `speed`) when they meet there within the step: each arm as the step
    /// starts, turned with its body until then (to first order), the time taken at the mean of
    /// the approach now and `speed`.
    fn arms_at_impact(
        &self,
        contact: &Contact,
        point: &Point2<f64>,
        gap: f64,
        speed: f64,
    ) -> [Vector3<f64>; 2] {
        let closing = 0.5 * (self.approach(contact, point) + speed);
        let until = if closing > 0.0 {
            (gap / closing).clamp(0.0, self.dt)
        } else {
            0.0
        };
        let p = contact.frame.to_world(point);
        [
            (contact.body_a, contact.centre_a),
            (contact.body_b, contact.centre_b),
        ]
        .map(|(id, centre)| {
            let arm = p - centre;
            arm + self.bodies[id.0].angular_velocity().cross(&arm) * until
        })
    }

    /// The speed `contact`'s landed points bounce at in this step ([`Contact::bounce_speed`]),
    /// its bodies having met as `met` ([`Impacts::landing`]) in the step before: restitution
    /// times the speed met at, less half a step of gravity's pull along the normal (module
    /// doc), when it is faster than the restitution threshold; else 0.
    ///
    /// The points that bounce all leave at that one speed, which gives back more than `e²` of
    /// the energy the impact took where they are heavier along the normal than the points that
    /// met (a corner met the floor, its edge or face bounces), or where the points met unevenly
    /// (a body turning as it lands): bounced at Newton's speed, a tumbling cube with
    /// restitution 0.9 rose up to 1.43 (vertex model) and 2.61 (face model) times its height,
    /// frictionless. So the speed is at most the one that gives the points that bounce `e²` of
    /// the energy the impact took: what the landing step took from the pair (the drop of the
    /// energy the integrator keeps in free flight, [`Impacts::kept_energy`]), and what stopping
    /// the points that bounce still takes now (a face slapping down after its corner landed):
    /// `e √(D / 1ᵀ A⁺ 1)` with `D` that energy, twice over, and `A` the points' coupling
    /// ([`Impacts::coupling`]). The landing step's drop is counted at most as what stopping the
    /// points that met would take ([`Touchdown::stopping`]): a body touching others as well
    /// loses energy to them. Never faster than Newton's; a ball, met and bounced at one point
    /// through its centre, bounces at Newton's speed.
    ///
    /// The points that bounce are the support's, landed or closing their gap in the step: the
    /// rows at the contact's landing points bounce on their own approach alone. Counted among
    /// them, a fast-spinning rim's far landing points credited the bounce with stopping their
    /// approach, which no row did, and a frictionless cylinder with restitution 0.95 rose to
    /// 1.10 times its drop's energy.
    pub(crate) fn bounce_speed(&self, contact: &Contact, met: Touchdown) -> f64 {
        if met.speed <= self.settings.restitution_threshold {
            return 0.0;
        }
        let settings = self.settings_of(contact);
        let (pull, dt) = (self.closing_pull(contact), self.dt);
        let bouncing: Vec<Point2<f64>> = support_points(contact)
            .filter(|&(point, &depth)| {
                settings.has_landed(depth) || self.approach(contact, point) * dt >= -depth
            })
            .map(|(point, _)| *point)
            .collect();
        let newton = contact.material.restitution * met.speed;
        // Twice the energy a bounce at unit speed gives the points that bounce.
        let unit = self.stopping(contact, &bouncing, &DVector::repeat(bouncing.len(), 1.0));
        let speed = if unit > 0.0 {
            // Their approach now, as the speed met at reads it (at the surface, module doc).
            let at_surface =
                |p: &Point2<f64>| (self.approach(contact, p) + 0.5 * pull * dt).max(0.0);
            let approaching =
                DVector::from_iterator(bouncing.len(), bouncing.iter().map(at_surface));
            let still = self.stopping(contact, &bouncing, &approaching);
            let landing = 2.0 * self.landing_took(contact, met);
            newton.min(contact.material.restitution * ((landing + still) / unit).sqrt())
        } else {
            newton
        };
        (speed - 0.5 * pull * dt).max(0.0)
    }

    /// The energy (J) the landing `met` took from `contact`'s bodies: the drop of the energy the
    /// integrator keeps in free flight since the landing step started, counted at most as what
    /// stopping the points that met would take ([`Touchdown::stopping`]; a body touching others
    /// as well loses energy to them). The bounce gives back at most `e²` of it
    /// ([`Impacts::bounce_speed`]), and no more than all of it ([`crate::bounce_guard`]).
    pub(crate) fn landing_took(&self, contact: &Contact, met: Touchdown) -> f64 {
        0.5 * (met.energy - self.kept_energy(contact)).clamp(0.0, met.stopping)
    }

    /// Twice the energy of `contact`'s dynamic bodies as semi-implicit Euler keeps it in free
    /// flight (J): kinetic at `v + g dt / 2`, the velocity at the step's end (the velocity `v`
    /// that moved a body stands for the step's middle, module doc), and potential.
    ///
    /// Against a kinematic body, in the frame moving with it: an impact on a body no impulse
    /// moves takes energy that depends on the frame it is counted in, and the impact is the
    /// kinematic body's. Counted at rest, a ball met by a paddle moving up at 1 m/s took less
    /// energy than it lost in the paddle's frame, and the cap sent it back at 0.71 of its
    /// approach instead of the 0.8 of its restitution (a paddle moving down: no change).
    fn kept_energy(&self, contact: &Contact) -> f64 {
        let g = self.gravity;
        let (a, b) = (
            &self.bodies[contact.body_a.0],
            &self.bodies[contact.body_b.0],
        );
        let frame = match (a.is_kinematic(), b.is_kinematic()) {
            (true, false) => Some(a),
            (false, true) => Some(b),
            _ => None,
        };
        [a, b]
            .into_iter()
            .filter(|body| body.is_dynamic())
            .map(|body| {
                let (v, centre) = match frame {
                    Some(frame) => (
                        body.linear_velocity() - frame.linear_velocity(),
                        body.centre - frame.centre.coords,
                    ),
                    None => (body.linear_velocity(), body.centre),
                };
                let at_end = v + g * (self.dt / 2.0);
                let kinetic = 2.0
                    * body.kinetic_energy_at(&body.inertia_world(), &v, &body.angular_velocity());
                kinetic + body.mass() * (at_end.norm_squared() - v.norm_squared())
                    - 2.0 * body.mass() * g.dot(&centre.coords)
            })
            .sum()
    }

    /// Whether any of `contact`'s points still apart may close its gap in the step under the
    /// bodies' closing `pull`: the approach at the frame's origin and the bodies' relative
    /// spin times the farthest such point's reach bound every point's approach (the relative
    /// velocity is affine over the plane). Pairs at rest or parting, most of a pile's or a
    /// pyramid's, are passed over without the approach of each point.
    fn may_close(&self, contact: &Contact, pull: f64) -> bool {
        let (a, b) = (
            &self.bodies[contact.body_a.0],
            &self.bodies[contact.body_b.0],
        );
        // Plain loops over the two lists: read for every pair on every step.
        let settings = self.settings_of(contact);
        let (mut reach_squared, mut gap) = (0.0_f64, f64::INFINITY);
        let mut take = |point: &Point2<f64>, depth: f64| {
            if !settings.has_landed(depth) {
                reach_squared = reach_squared.max(point.coords.norm_squared());
                gap = gap.min(-depth);
            }
        };
        for (point, &depth) in contact.support.vertices().iter().zip(&contact.depths) {
            take(point, depth);
        }
        for landing in &contact.landing {
            take(&landing.point, landing.depth);
        }
        if gap == f64::INFINITY {
            return false;
        }
        let spin = (a.angular_velocity() - b.angular_velocity()).norm();
        let reach = reach_squared.sqrt();
        let fastest = self.approach(contact, &Point2::origin()) + spin * reach;
        // A hair over, so rounding never hides a point that closes to the last bit.
        (fastest + pull * self.dt) * self.dt * (1.0 + 1e-9) + 1e-12 >= gap
    }

    /// How fast `contact`'s bodies close on each other along its normal at `point` (m/s).
    fn approach(&self, contact: &Contact, point: &Point2<f64>) -> f64 {
        let (a, b) = (
            &self.bodies[contact.body_a.0],
            &self.bodies[contact.body_b.0],
        );
        let p = contact.frame.to_world(point);
        -(a.velocity_at(&p) - b.velocity_at(&p)).dot(&contact.frame.normal)
    }

    /// The pair's coupling of its normal velocities at `points`: entry `(i, j)` is how fast a
    /// unit impulse along the normal at point `j` (on A, its reaction on B) closes or opens the
    /// pair at point `i` (1/kg). Symmetric, positive semidefinite, of rank 3 at most: a rigid
    /// pair's normal velocities over a plane are affine.
    fn coupling(&self, contact: &Contact, points: &[Point2<f64>]) -> DMatrix<f64> {
        let n = &contact.frame.normal;
        let world: Vec<_> = points.iter().map(|p| contact.frame.to_world(p)).collect();
        // Each body's inverse mass and world inertia (zero for a body no impulse moves) and
        // its moments at the points: entry `(i, j)` sums `1/m + mᵢᵀ I⁻¹ mⱼ` over the two.
        let [a, b] = [contact.body_a, contact.body_b].map(|id| {
            let body = &self.bodies[id.0];
            let moments: Vec<_> = world.iter().map(|p| body.normal_moment(p, n)).collect();
            (body.solver_body(), moments)
        });
        DMatrix::from_fn(points.len(), points.len(), |i, j| {
            [&a, &b]
                .iter()
                .map(|(body, m)| body.inv_mass + m[i].dot(&(body.inv_inertia_world * m[j])))
                .sum()
        })
    }

    /// Twice the kinetic energy the least impulses along the normal at `points` take to change
    /// the pair's normal velocities there by `speeds` (J): `uᵀ A⁺ u` with `A` the
    /// [`Impacts::coupling`], its pseudo-inverse for points of which some are redundant (four
    /// corners of a face, three of them enough to hold it). 0 where the pair cannot be moved.
    fn stopping(&self, contact: &Contact, points: &[Point2<f64>], speeds: &DVector<f64>) -> f64 {
        let coupling = self.coupling(contact, points);
        let largest = coupling.diagonal().iter().fold(0.0, |m: f64, &x| m.max(x));
        if largest <= 0.0 {
            return 0.0;
        }
        // `uᵀ A⁺ u` over `A`'s eigenpairs; eigenvalues below this share of the largest
        // coupling are the redundant points' (zero to rounding). An SVD's pseudo-inverse read
        // 1.6% low for a cube's face met with its back corners' landing points on the same
        // spots of the plane.
        let eigen = coupling.symmetric_eigen();
        eigen
            .eigenvalues
            .iter()
            .zip(eigen.eigenvectors.column_iter())
            .filter(|&(&value, _)| value > largest * 1e-9)
            .map(|(value, vector)| vector.dot(speeds).powi(2) / value)
            .sum()
    }
}

/// Moves the normal row of a support that landed (its first row: a point's, or the face
/// model's block at the support's centroid) to where its landing `landed` met, at the arms the
/// bodies had there ([`Touchdown::arms`]), when it is the same point turned with the bodies
/// since — its arm differs from the landing's by no more than a step's turn, of at most
/// [`MAX_LANDING_TURN`] — and, once that point closes to within the slop of the surface in the
/// step (at the velocities in `solved`, before the step's forces), stops it there: at the
/// contact's bounce, or at rest without restitution. Only the arms of dynamic bodies of two
/// polytopes are moved. `bodies` are the world's, `rows` the contact's from its first.
///
/// An impact that lands a corner or an edge is split over two steps: the landing step stops
/// it at the surface, which sets the body turning, and the rest of the stop and the bounce act
/// on the next, where the arm has turned with the body. A 0.3 m cube thrown corner first at 3
/// m/s at a floor, 5° off corner-down, left up to 25% (restitution 0.5) and 33% (1) too fast
/// in spin and 13% too slow upwards, the earlier in a step its corner landed, and thrown edge
/// first with 6–23% too much angular momentum; acting at the landing's arm, the two parts add
/// up to the single-point impact's closed form: to rounding for a cube that was not spinning,
/// within 6e-6 for a box of other proportions (whose inertia turns with it in the landing
/// step), within 1% for a cube tumbling at 1 rad/s (its arm turned to the impact to first
/// order). Without restitution the same: the cube moved on up to 17% too fast in spin and at
/// up to twice the closed form's speed down (its corner left short of the surface and stopped
/// a step later still), and now moves on as the inelastic impact's closed form. The contact's
/// depth is not that point's: the landing step's turn lifts a corner off the surface (a cube
/// 10° off corner-down, landed from 4.9 mm, stood 1.8 mm off and never bounced, its first
/// impact left to a second one), so the stop is given within the slop. Curved shapes keep
/// their arm: the point of a ball or a rim that touches is not the material point that met.
pub(crate) fn bounce_where_landed(
    contact: &Contact,
    landed: Touchdown,
    (bodies, solved): (&[Body], &[SolverBody]),
    rows: &mut [Row],
    (settings, dt): (&ContactSettings, f64),
) {
    let polytope = |id: tatami_lcp::BodyId| {
        matches!(
            bodies[id.0].shape(),
            crate::Shape::Box { .. } | crate::Shape::Convex { .. }
        )
    };
    let Some(arms) = landed.arms else {
        return;
    };
    if !(polytope(contact.body_a) && polytope(contact.body_b)) {
        return;
    }
    let Some(row) = rows.first_mut() else {
        return;
    };
    let depth = contact.depth();
    let j = &mut row.jacobian;
    let sides = [
        (contact.body_a, arms[0], j.linear_a, j.angular_a),
        (contact.body_b, arms[1], j.linear_b, j.angular_b),
    ];
    // The row's point is the landing's, turned since, on every dynamic body.
    let moved = sides.map(|(id, arm, linear, angular)| {
        let dynamic = bodies[id.0].is_dynamic();
        let at_landing = arm.cross(&linear);
        let turn = solved[id.0].angular_velocity.norm() * dt;
        let same = turn <= MAX_LANDING_TURN
            && (at_landing - angular).norm() <= (turn + 1e-9) * arm.norm() + 1e-12;
        (dynamic, same, at_landing)
    });
    if moved.iter().any(|&(dynamic, same, _)| dynamic && !same) {
        return;
    }
    if moved[0].0 {
        j.angular_a = moved[0].2;
    }
    if moved[1].0 {
        j.angular_b = moved[1].2;
    }
    let normal_speed = j.velocity(&solved[contact.body_a.0], &solved[contact.body_b.0]);
    if settings.has_landed(depth) || -normal_speed * dt >= -depth - settings.slop {
        row.target = row.target.max(contact.bounce_speed);
    }
}

/// Widest turn (rad) of a body in a step for [`bounce_where_landed`] to tell the point that
/// landed from its neighbours: a turn of `θ` may move a point by `θ` times its arm, and past a
/// quarter of it, a cube's arm to its corner (0.87 of its edge) grows as far as the corner's
/// distance to the middle of an edge. Two 0.3 m cubes thrown at each other at 20 m/s, spun at
/// 1.3 rad a step by the corners they met with, had a face's row moved to a corner's arm and
/// sank 17 cm into each other.
const MAX_LANDING_TURN: f64 = 0.25;

/// `contact`'s support points and landing points, each with its depth.
fn points(contact: &Contact) -> impl Iterator<Item = (&Point2<f64>, &f64)> {
    support_points(contact).chain(contact.landing.iter().map(|l| (&l.point, &l.depth)))
}

/// `contact`'s support points, each with its depth: those whose rows bounce at the speed
/// handed on ([`Contact::bounce_speed`]; a landing point's row bounces on its own approach).
fn support_points(contact: &Contact) -> impl Iterator<Item = (&Point2<f64>, &f64)> {
    contact.support.vertices().iter().zip(&contact.depths)
}

#[cfg(test)]
mod tests {
    use nalgebra::{Point2, Point3};
    use tatami_contact::{ContactFrame, Material};
    use tatami_geometry::ConvexPolygon;
    use tatami_lcp::BodyId;

    use super::*;
    use crate::{BodyDesc, Shape, World};

    const DT: f64 = 0.01;

    /// The speed of [`Impacts::landing`] over a step of [`DT`] with the default settings,
    /// the last landing met at `met_at`.
    fn landing(contact: &Contact, met_at: f64, bodies: &[Body], gravity: Vector3<f64>) -> f64 {
        let settings = ContactSettings::default();
        let impacts = Impacts {
            bodies,
            gravity: &gravity,
            dt: DT,
            settings: &settings,
        };
        let met = Touchdown {
            speed: met_at,
            stopping: bodies[1].mass() * met_at * met_at,
            ..Touchdown::default()
        };
        impacts
            .landing(contact, met, contact.bounce_speed, false)
            .speed
    }

    /// A ball falling at `speed` onto a fixed floor, its contact at `depth` along a normal
    /// turned off the axes, with restitution 0.5.
    fn ball_over_floor(speed: f64, depth: f64) -> (Vec<Body>, Contact) {
        let down = nalgebra::Unit::new_normalize(Vector3::new(0.3, -0.2, -1.0));
        let world = World::builder()
            .body(BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 1.0])))
            .body(
                BodyDesc::dynamic(Shape::sphere(0.5))
                    .position([0.0, 0.0, 2.0])
                    .velocity((down.into_inner() * speed).into())
                    .restitution(0.5),
            )
            .build()
            .expect("a valid scene");
        let contact = Contact {
            body_a: BodyId(1),
            body_b: BodyId(0),
            centre_a: Point3::new(0.0, 0.0, 2.0),
            centre_b: Point3::origin(),
            frame: ContactFrame::from_normal(Point3::new(0.0, 0.0, 1.5), -down.into_inner())
                .expect("a frame"),
            support: ConvexPolygon::from_points(&[Point2::origin()]).expect("a point"),
            depths: vec![depth],
            material: Material::new(0.5, 0.5, 0.5).expect("a material"),
            landing: Vec::new(),
            bounce_speed: 0.0,
        };
        (world.bodies().to_vec(), contact)
    }

    /// [`Impacts::may_close`] bounds every point's approach: over random pairs of a box moving
    /// and spinning above a floor or another moving box, under gravity or not, with points at
    /// random gaps around a turned frame, whenever some point still apart closes its gap in the
    /// step by its own approach (the test [`Impacts::landing`] makes), the bound says it may.
    #[test]
    fn the_bound_on_closing_never_passes_over_a_point_that_closes() {
        use proptest::prelude::*;
        let vector = || prop::array::uniform3(-3.0..3.0f64);
        proptest!(ProptestConfig::with_cases(512), |(
            (velocity, spin, other_velocity, other_spin) in (vector(), vector(), vector(), vector()),
            moving_floor in any::<bool>(),
            under_gravity in any::<bool>(),
            normal in vector(),
            spots in prop::collection::vec(((-0.6..0.6f64, -0.6..0.6f64), -0.05..0.002f64), 1..8),
        )| {
            let normal = Vector3::from(normal);
            prop_assume!(normal.norm() > 0.1);
            let floor = if moving_floor {
                BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                    .velocity(other_velocity)
                    .angular_velocity(other_spin)
            } else {
                BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 1.0]))
            };
            let world = World::builder()
                .body(floor.position([0.1, -0.2, 0.0]))
                .body(
                    BodyDesc::dynamic(Shape::cuboid([0.6, 0.4, 0.8]))
                        .position([0.0, 0.0, 1.0])
                        .velocity(velocity)
                        .angular_velocity(spin),
                )
                .build()
                .expect("a valid scene");
            let bodies = world.bodies();
            let (plane, depths): (Vec<Point2<f64>>, Vec<f64>) =
                spots.iter().map(|&((x, y), depth)| (Point2::new(x, y), depth)).unzip();
            let Ok(support) = ConvexPolygon::from_points(&plane) else {
                return Ok(());
            };
            let depths: Vec<f64> = (0..support.vertices().len()).map(|k| depths[k % depths.len()]).collect();
            let contact = Contact {
                body_a: BodyId(1),
                body_b: BodyId(0),
                centre_a: bodies[1].centre_of_mass(),
                centre_b: bodies[0].centre_of_mass(),
                frame: ContactFrame::from_normal(Point3::new(0.05, 0.02, 0.55), normal)
                    .expect("a frame"),
                support,
                depths,
                material: Material::new(0.5, 0.5, 0.0).expect("a material"),
                landing: vec![tatami_contact::Landing { point: Point2::new(0.3, -0.7), depth: -0.01 }],
                bounce_speed: 0.0,
            };
            let gravity = if under_gravity { Vector3::new(0.0, 0.0, -9.81) } else { Vector3::zeros() };
            let settings = ContactSettings::default();
            let impacts = Impacts { bodies, gravity: &gravity, dt: DT, settings: &settings };
            let pull = impacts.closing_pull(&contact);
            let closes = points(&contact).any(|(point, &depth)| {
                !settings.has_landed(depth)
                    && (impacts.approach(&contact, point) + pull * DT) * DT >= -depth
            });
            prop_assert!(!closes || impacts.may_close(&contact, pull));
        });
    }

    /// Without gravity the speed met at is the approach; with it, the integrator's: from the
    /// kept quantity `(v − a dt/2)²/2 + a x` at the gap and at the surface.
    #[test]
    fn a_gap_closed_in_the_step_is_met_at_the_integrators_speed() {
        let (bodies, contact) = ball_over_floor(5.0, -0.03);
        let none = landing(&contact, 0.0, &bodies, Vector3::zeros());
        assert!((none - 5.0).abs() < 1e-12, "{none}");
        let gravity = Vector3::new(0.0, 0.0, -9.81);
        let a = -gravity.dot(&contact.frame.normal);
        let kept = 0.5 * (5.0 + 0.5 * a * DT).powi(2) + a * 0.03;
        let speed = landing(&contact, 0.0, &bodies, gravity);
        assert!((0.5 * speed * speed - kept).abs() < 1e-12, "{speed}");
        // 6 cm away it does not close in the step (about 5.1 m/s · 0.01 s = 5.1 cm).
        let (bodies, far) = ball_over_floor(5.0, -0.06);
        assert_eq!(landing(&far, 0.0, &bodies, gravity), 0.0);
    }

    #[test]
    fn a_landing_left_short_keeps_the_speed_it_met_at_and_a_landed_one_does_not() {
        let gravity = Vector3::zeros();
        // Left 1 mm short at 0.2 m/s, having met at 5 m/s: lands again, still at 5 m/s.
        let (bodies, short) = ball_over_floor(0.2, -0.001);
        let speed = landing(&short, 5.0, &bodies, gravity);
        assert!((speed - 5.0).abs() < 1e-12);
        // Landed: it bounces in this step; nothing is kept for the next.
        let (bodies, landed) = ball_over_floor(0.2, 0.0);
        assert_eq!(landing(&landed, 5.0, &bodies, gravity), 0.0);
    }

    #[test]
    fn a_pair_that_does_not_bounce_keeps_nothing() {
        let (bodies, mut contact) = ball_over_floor(5.0, -0.03);
        contact.material = Material::new(0.5, 0.5, 0.0).expect("a material");
        let speed = landing(&contact, 0.0, &bodies, Vector3::zeros());
        assert_eq!(speed, 0.0);
    }

    /// `e` times the speed met at, less half a step of gravity's pull; nothing under the
    /// restitution threshold.
    #[test]
    fn the_bounce_is_restitution_times_the_speed_met_at_less_half_a_step_of_pull() {
        let settings = ContactSettings::default();
        let (bodies, contact) = ball_over_floor(0.0, 0.0);
        let gravity = Vector3::new(0.0, 0.0, -9.81);
        let a = -gravity.dot(&contact.frame.normal);
        let impacts = Impacts {
            bodies: &bodies,
            gravity: &gravity,
            dt: DT,
            settings: &settings,
        };
        // A ball met along its normal: stopping it takes its kinetic energy along the normal,
        // and its landing took that.
        let met = |speed: f64| Touchdown {
            speed,
            stopping: bodies[1].mass() * speed * speed,
            arms: None,
            energy: impacts.kept_energy(&contact) + bodies[1].mass() * speed * speed,
        };
        let bounce = impacts.bounce_speed(&contact, met(4.0));
        assert!(
            (bounce - (0.5 * 4.0 - 0.5 * a * DT)).abs() < 1e-12,
            "{bounce}"
        );
        let slow = settings.restitution_threshold;
        assert_eq!(impacts.bounce_speed(&contact, met(slow)), 0.0);
    }

    /// A 0.3 m, 1 kg cube resting flat on a fixed floor, its four corners landed, with
    /// restitution 1: lifted evenly at its four corners, it moves as 1 kg (`1ᵀ A⁺ 1` = 1 kg:
    /// the closed form, not the code's). Met at 3 m/s at one corner alone (the coupling there
    /// `1/m + (r × n)ᵀ I⁻¹ (r × n)` = 1 + 0.15² · 2 / (0.3² / 6) = 4 per kg, so stopping it
    /// takes `v² / 4` = 2.25 J, twice over), its landing having taken that, its face bounces at
    /// half Newton's speed, giving it back. A landing that took less (1 J, twice over) gives
    /// back less (1 m/s); one that took more (a body touching others too) counts as stopping the
    /// corner; and where stopping took more than a bounce at Newton's speed gives back,
    /// Newton's speed, not more.
    #[test]
    fn a_face_bounces_with_the_energy_its_corner_met_with() {
        let world = World::builder()
            .gravity([0.0; 3])
            .body(BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 1.0])))
            .body(
                BodyDesc::dynamic(Shape::cuboid([0.3; 3]))
                    .mass(1.0)
                    .position([0.0, 0.0, 0.65])
                    .restitution(1.0),
            )
            .build()
            .expect("a valid scene");
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(x, y)| Point2::new(0.15 * x, 0.15 * y));
        let contact = Contact {
            body_a: BodyId(1),
            body_b: BodyId(0),
            centre_a: Point3::new(0.0, 0.0, 0.65),
            centre_b: Point3::origin(),
            frame: ContactFrame::from_normal(Point3::new(0.0, 0.0, 0.5), Vector3::z())
                .expect("a frame"),
            support: ConvexPolygon::from_points(&corners).expect("a square"),
            depths: vec![0.0; 4],
            material: Material::new(0.5, 0.5, 1.0).expect("a material"),
            landing: Vec::new(),
            bounce_speed: 0.0,
        };
        let settings = ContactSettings::default();
        let bodies = world.bodies();
        let impacts = Impacts {
            bodies,
            gravity: &Vector3::zeros(),
            dt: DT,
            settings: &settings,
        };
        // The corner's arm (0.15, 0.15, −0.15) crossed with z has length 0.15 √2; the cube's
        // inertia is m s² / 6 about every axis.
        let corner = 1.0 + 0.15f64.powi(2) * 2.0 / (0.09 / 6.0);
        assert!((corner - 4.0).abs() < 1e-12);
        // At rest without gravity, the pair keeps no energy now: the landing took `energy`.
        let met = |stopping, energy| Touchdown {
            speed: 3.0,
            stopping,
            energy,
            arms: None,
        };
        let stop_corner = 9.0 / corner;
        let bounce = impacts.bounce_speed(&contact, met(stop_corner, stop_corner));
        assert!((bounce - 1.5).abs() < 1e-9, "{bounce}");
        let bounce = impacts.bounce_speed(&contact, met(stop_corner, 1.0));
        assert!((bounce - 1.0).abs() < 1e-9, "{bounce}");
        let bounce = impacts.bounce_speed(&contact, met(stop_corner, 10.0));
        assert!((bounce - 1.5).abs() < 1e-9, "{bounce}");
        let bounce = impacts.bounce_speed(&contact, met(18.0, 18.0));
        assert!((bounce - 3.0).abs() < 1e-12, "{bounce}");
    }
}
