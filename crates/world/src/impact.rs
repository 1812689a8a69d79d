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

use nalgebra::{Point2, Vector2, Vector3};
use tatami_contact::{Contact, ContactSettings};

use crate::body::Body;

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

    /// How fast `contact`'s bodies land on each other in this step, to bounce on the next (m/s;
    /// see the module doc for the integrator's speed): the speed of its points still apart
    /// that close their gaps in the step, taken at their centroid with their mean gap — or
    /// `met_at`, the speed the pair's last contact met at, when faster and no point has landed
    /// yet (a landing the solve left short of the surface lands again, the speed kept). 0 for a
    /// pair that does not bounce, whose points apart do not close their gaps in the step, or
    /// that bounces in this step at `bounce_speed` ([`Impacts::bounce_speed`]; the contact
    /// models bounce its landed and closing points both). Read off the contact instead, the
    /// bounce was the last step's, or none for a contact found afresh: a pair bounced, handed
    /// its landing on again, and bounced a second time on the next step (two cubes with
    /// restitution 0.9 thrown at each other parted with up to 1.44 times their energy).
    pub(crate) fn landing_speed(&self, contact: &Contact, met_at: f64, bounce_speed: f64) -> f64 {
        if contact.material.restitution == 0.0 {
            return 0.0;
        }
        let (a, b) = (
            &self.bodies[contact.body_a.0],
            &self.bodies[contact.body_b.0],
        );
        let (pull, dt, settings) = (self.closing_pull(contact), self.dt, self.settings);
        let frame = &contact.frame;
        let support = contact.support.vertices().iter().zip(&contact.depths);
        let landing = contact.landing.iter().map(|l| (&l.point, &l.depth));
        let closing = |&(point, &depth): &(&Point2<f64>, &f64)| {
            if settings.has_landed(depth) {
                return false;
            }
            let p = frame.to_world(point);
            let approach = -(a.velocity_at(&p) - b.velocity_at(&p)).dot(&frame.normal);
            (approach + pull * dt) * dt >= -depth
        };
        // The points that close their gaps in the step meet as one: with the fastest of them
        // standing for the whole landing, every point of a face landing tilted and turning
        // bounced at its fastest corner's speed, and a cube dropped turned at random with
        // restitution 0.9 came up with up to 1.27 times the energy it was dropped with.
        let (sum, gaps, count) = support.chain(landing).filter(closing).fold(
            (Vector2::zeros(), 0.0, 0.0),
            |(sum, gaps, count), (point, &depth)| (sum + point.coords, gaps - depth, count + 1.0),
        );
        let landed = contact.depths.iter().any(|&d| settings.has_landed(d));
        if count == 0.0 || bounce_speed > 0.0 {
            return 0.0;
        }
        let p = frame.to_world(&Point2::from(sum / count));
        let approach = -(a.velocity_at(&p) - b.velocity_at(&p)).dot(&frame.normal);
        let (gap, middle) = (gaps / count, (approach + 0.5 * pull * dt).max(0.0));
        let speed = (middle * middle + 2.0 * pull * gap).max(0.0).sqrt();
        if landed { speed } else { speed.max(met_at) }
    }

    /// The speed `contact`'s landed points bounce at in this step ([`Contact::bounce_speed`]),
    /// its bodies having met at `met_at` ([`Impacts::landing_speed`]) in the step before:
    /// restitution times that, less half a step of gravity's pull along the normal (module
    /// doc), when it is faster than the restitution threshold; else 0.
    pub(crate) fn bounce_speed(&self, contact: &Contact, met_at: f64) -> f64 {
        if met_at <= self.settings.restitution_threshold {
            return 0.0;
        }
        let pull = self.closing_pull(contact);
        (contact.material.restitution * met_at - 0.5 * pull * self.dt).max(0.0)
    }
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

    /// [`Impacts::landing_speed`] over a step of [`DT`] with the default settings.
    fn landing(contact: &Contact, met_at: f64, bodies: &[Body], gravity: Vector3<f64>) -> f64 {
        let settings = ContactSettings::default();
        let impacts = Impacts {
            bodies,
            gravity: &gravity,
            dt: DT,
            settings: &settings,
        };
        impacts.landing_speed(contact, met_at, contact.bounce_speed)
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
        let bounce = impacts.bounce_speed(&contact, 4.0);
        assert!(
            (bounce - (0.5 * 4.0 - 0.5 * a * DT)).abs() < 1e-12,
            "{bounce}"
        );
        let slow = settings.restitution_threshold;
        assert_eq!(impacts.bounce_speed(&contact, slow), 0.0);
    }
}
