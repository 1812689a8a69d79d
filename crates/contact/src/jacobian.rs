//! Jacobians of point and angular rows between the two bodies of a contact.

use nalgebra::{Point3, Vector3};
use tatami_lcp::{Jacobian, SolverBody};

use crate::Contact;

/// The row measuring the velocity of A relative to B at world point `p` along `direction`.
pub(crate) fn point_jacobian(
    contact: &Contact,
    p: &Point3<f64>,
    direction: &Vector3<f64>,
) -> Jacobian {
    Jacobian {
        linear_a: *direction,
        angular_a: (p - contact.centre_a).cross(direction),
        linear_b: -direction,
        angular_b: -(p - contact.centre_b).cross(direction),
    }
}

/// How A's material point at `p` moves relative to B's: `(normal speed, slip speed)`, the
/// normal speed negative when closing.
pub(crate) fn point_motion(
    contact: &Contact,
    bodies: &[SolverBody],
    p: &Point3<f64>,
) -> (f64, f64) {
    let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
    let va = a.linear_velocity + a.angular_velocity.cross(&(p - contact.centre_a));
    let vb = b.linear_velocity + b.angular_velocity.cross(&(p - contact.centre_b));
    let v = va - vb;
    let normal = contact.frame.normal;
    let normal_speed = v.dot(&normal);
    (normal_speed, (v - normal * normal_speed).norm())
}

/// Rate (rad/s) at which A twists relative to B about the contact normal.
pub(crate) fn twist_rate(contact: &Contact, bodies: &[SolverBody]) -> f64 {
    let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
    (a.angular_velocity - b.angular_velocity)
        .dot(&contact.frame.normal)
        .abs()
}

/// The row measuring the angular velocity of A relative to B about `axis`.
pub(crate) fn angular_jacobian(axis: &Vector3<f64>) -> Jacobian {
    Jacobian {
        angular_a: *axis,
        angular_b: -axis,
        ..Jacobian::default()
    }
}
