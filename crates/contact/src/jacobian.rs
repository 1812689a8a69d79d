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

/// Velocity of A's material point at `p` relative to B's.
pub(crate) fn relative_velocity(
    contact: &Contact,
    bodies: &[SolverBody],
    p: &Point3<f64>,
) -> Vector3<f64> {
    let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
    let va = a.linear_velocity + a.angular_velocity.cross(&(p - contact.centre_a));
    let vb = b.linear_velocity + b.angular_velocity.cross(&(p - contact.centre_b));
    va - vb
}

/// The row measuring the angular velocity of A relative to B about `axis`.
pub(crate) fn angular_jacobian(axis: &Vector3<f64>) -> Jacobian {
    Jacobian {
        angular_a: *axis,
        angular_b: -axis,
        ..Jacobian::default()
    }
}
