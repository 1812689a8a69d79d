//! Jacobians of point and angular rows between the two bodies of a contact, and the relative
//! motions at a point that their targets are built from.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use tatami_geometry::PolygonKind;
use tatami_lcp::{Jacobian, SolverBody};

use crate::Contact;

/// A's and B's own points where a contact touches at a point `p` of its plane: where the two
/// overlap by `depth` the plane lies midway between their surfaces, and each body's point is
/// on its own surface, half the depth to its side; where they do not, both are `p`. A point
/// row holds A's point against B's: held at the plane instead, a top spinning at 200 rad/s on a
/// tip sunk 2 mm moved the tip at 7 cm/s round the point held, and the tip wandered 5.7 cm in
/// 10 s (5 mm from its own point).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Witness {
    /// A's point.
    pub a: Point3<f64>,
    /// B's point.
    pub b: Point3<f64>,
}

impl Witness {
    /// The points of `contact` at plane point `p`, where it is `depth` deep.
    #[inline]
    pub(crate) fn at(contact: &Contact, p: &Point3<f64>, depth: f64) -> Self {
        // The normal points from B into A: A's surface lies below the plane, B's above it.
        let half = contact.frame.normal * (0.5 * depth.max(0.0));
        Self {
            a: p - half,
            b: p + half,
        }
    }
}

/// The row measuring the velocity of A's point of `witness` relative to B's along `direction`.
#[inline]
pub(crate) fn point_jacobian(
    contact: &Contact,
    witness: &Witness,
    direction: &Vector3<f64>,
) -> Jacobian {
    Jacobian {
        linear_a: *direction,
        angular_a: (witness.a - contact.centre_a).cross(direction),
        linear_b: -direction,
        angular_b: -(witness.b - contact.centre_b).cross(direction),
    }
}

/// How A's point of `witness` moves relative to B's: `(normal speed, slip speed)`, the
/// normal speed negative when closing.
pub(crate) fn point_motion(
    contact: &Contact,
    bodies: &[SolverBody],
    witness: &Witness,
) -> (f64, f64) {
    let (normal_speed, slip) = normal_and_slip(contact, bodies, witness);
    (normal_speed, slip.norm())
}

/// A's velocity relative to B's at `witness`, split into its speed along the normal and its
/// slip.
fn normal_and_slip(
    contact: &Contact,
    bodies: &[SolverBody],
    witness: &Witness,
) -> (f64, Vector3<f64>) {
    let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
    let va = a.linear_velocity + a.angular_velocity.cross(&(witness.a - contact.centre_a));
    let vb = b.linear_velocity + b.angular_velocity.cross(&(witness.b - contact.centre_b));
    let v = va - vb;
    let normal = contact.frame.normal;
    let normal_speed = v.dot(&normal);
    (normal_speed, v - normal * normal_speed)
}

/// [`point_motion`] at `witness` with the velocity the point's friction rows target: `(normal
/// speed, slip speed, target)`. Without a `weld` (a rolling or single-point contact) the target
/// is no slip. With the pair's [`face_weld`], where A's point kept with B's over the last step
/// the target is the weld and the slip is how fast the points parted over that step; elsewhere
/// the target is no slip, the friction opposing the slip itself.
///
/// At the step's start a welded pair's points part at `−weld` (seen from where the bodies now
/// are, each point has swung on round its centre), so `slip + weld` is how fast they parted over
/// the last step: 0 under a weld, `|weld|` on the step before the first. A pair whose points
/// parted by no more than the weld's own drift and `slip_threshold` is welded; slipping (a box
/// sliding off a turntable), the target stays 0, as the kinetic friction's direction wants.
pub(crate) fn friction_motion(
    contact: &Contact,
    bodies: &[SolverBody],
    witness: &Witness,
    weld: Option<&Vector3<f64>>,
    slip_threshold: f64,
) -> (f64, f64, Vector3<f64>) {
    let (normal_speed, slip) = normal_and_slip(contact, bodies, witness);
    match weld {
        Some(weld) if (slip + weld).norm() <= weld.norm() + slip_threshold => {
            (normal_speed, (slip + weld).norm(), *weld)
        }
        _ => (normal_speed, slip.norm(), Vector3::zeros()),
    }
}

/// [`friction_motion`] at `witness` for a contact's one friction block (the face and patch
/// models'), with the pair's [`face_weld`].
pub(crate) fn block_friction_motion(
    contact: &Contact,
    bodies: &[SolverBody],
    witness: &Witness,
    dt: f64,
    slip_threshold: f64,
) -> (f64, f64, Vector3<f64>) {
    let weld = face_weld(contact, bodies, dt, slip_threshold);
    friction_motion(contact, bodies, witness, weld.as_ref(), slip_threshold)
}

/// The pair's [`weld_velocity`] where it touches face to face (its support a polygon), for
/// [`friction_motion`]; `None` for an edge or a point, which may roll.
pub(crate) fn face_weld(
    contact: &Contact,
    bodies: &[SolverBody],
    dt: f64,
    slip_threshold: f64,
) -> Option<Vector3<f64>> {
    (contact.support.kind() == PolygonKind::Polygon)
        .then(|| weld_velocity(contact, bodies, dt, slip_threshold))
}

/// The velocity of A relative to B, along the contact plane, that keeps the two bodies'
/// material points together over a step of `dt` while they turn together at `ω`. Semi-implicit
/// Euler moves each body's centre along a straight line while its points swing round it, so
/// where two points' velocities agree A's still drifts from B's by `−½dt² ω×(ω×(c_A − c_B))`
/// a step, the same at every point of the contact: a box sticking to a turntable at 1 rad/s,
/// 1 m out, spiralled outwards at `ω²r dt/2` a step, 8.3 mm/s at 60 Hz. This velocity cancels
/// that drift exactly for bodies turning at a steady `ω`. Zero unless the bodies turn together
/// (their turn against each other moves no point of the support by more than `slip_threshold`
/// a second): a body landing on a face or tipping over it does not keep its points on the
/// other. Only faces take it ([`face_weld`]): a rolling contact runs over its body's surface.
fn weld_velocity(
    contact: &Contact,
    bodies: &[SolverBody],
    dt: f64,
    slip_threshold: f64,
) -> Vector3<f64> {
    let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
    let centre = contact.support.centroid();
    let reach = (contact.support.vertices().iter())
        .map(|v| (v - centre).norm())
        .fold(0.0, f64::max);
    if (a.angular_velocity - b.angular_velocity).norm() * reach > slip_threshold {
        return Vector3::zeros();
    }
    // Their points part by `(I − R)d + (v_A − v_B)dt` over the step (`R` the turn `ω dt`,
    // `d = c_A − c_B`), where their relative velocity is `w = v_A − v_B − ω × d`: none for
    // `w = (R − I)d/dt − ω × d`, which is `½dt ω×(ω×d)` to second order.
    let w = (a.angular_velocity + b.angular_velocity) * 0.5;
    let d = contact.centre_a - contact.centre_b;
    let turned = UnitQuaternion::from_scaled_axis(w * dt) * d;
    let weld = (turned - d) / dt - w.cross(&d);
    let n = contact.frame.normal;
    weld - n * weld.dot(&n)
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

#[cfg(test)]
mod tests {
    use nalgebra::{Matrix3, Point2};
    use tatami_geometry::ConvexPolygon;
    use tatami_lcp::{BodyId, SolverBody};

    use super::*;
    use crate::{ContactFrame, Material};

    /// A 0.4 m square face contact, its frame tilted off the world's axes, between bodies turning
    /// at `w_a` and `w_b`, each moving so that its points at the frame's origin agree.
    fn turning(w_a: Vector3<f64>, w_b: Vector3<f64>) -> (Contact, [SolverBody; 2]) {
        let square = [(-0.2, -0.2), (0.2, -0.2), (0.2, 0.2), (-0.2, 0.2)];
        let frame =
            ContactFrame::from_normal(Point3::new(0.7, -0.4, 0.3), Vector3::new(0.3, -0.2, 1.0))
                .unwrap();
        let contact = Contact {
            body_a: BodyId(0),
            body_b: BodyId(1),
            centre_a: frame.origin + frame.normal * 0.2,
            centre_b: Point3::new(-0.5, 0.8, -0.4),
            frame,
            support: ConvexPolygon::from_points(&square.map(|(x, y)| Point2::new(x, y))).unwrap(),
            depths: vec![0.0; 4],
            material: Material::new(0.5, 0.5, 0.0).unwrap(),
            landing: Vec::new(),
            bounce_speed: 0.0,
        };
        let body = |w: Vector3<f64>, centre: Point3<f64>| SolverBody {
            inv_mass: 1.0,
            inv_inertia_world: Matrix3::identity(),
            linear_velocity: w.cross(&(centre - contact.frame.origin)),
            angular_velocity: w,
        };
        let bodies = [body(w_a, contact.centre_a), body(w_b, contact.centre_b)];
        (contact, bodies)
    }

    /// Two bodies turning together at 2 rad/s about an axis off the world's: moved by
    /// semi-implicit Euler (centres along their velocities, each body turned `ω dt` about its
    /// centre) with the weld added to A's velocity, A's and B's points at every support vertex
    /// end the step together (to 1e-15 m); with the weld left out they part by
    /// `½ω²|d⊥| dt²`-sized amounts. The weld lies in the contact plane.
    #[test]
    fn the_weld_keeps_points_of_bodies_turning_together_together() {
        let w = Vector3::new(0.4, -1.2, 1.5).normalize() * 2.0;
        let (contact, [a, b]) = turning(w, w);
        let dt = 1.0 / 60.0;
        let weld = weld_velocity(&contact, &[a, b], dt, 1e-3);
        assert!(weld.dot(&contact.frame.normal).abs() < 1e-15);
        let turn = UnitQuaternion::from_scaled_axis(w * dt);
        let moved = |centre: Point3<f64>, velocity: Vector3<f64>, p: Point3<f64>| {
            centre + velocity * dt + turn * (p - centre)
        };
        for vertex in contact.support.vertices() {
            let p = contact.frame.to_world(vertex);
            let parted = |weld: Vector3<f64>| {
                let a_point = moved(contact.centre_a, a.linear_velocity + weld, p);
                let b_point = moved(contact.centre_b, b.linear_velocity, p);
                let gap = a_point - b_point;
                (gap - contact.frame.normal * gap.dot(&contact.frame.normal)).norm()
            };
            assert!(parted(weld) < 1e-15, "{}", parted(weld));
            assert!(
                parted(Vector3::zeros()) > 1e-4,
                "{}",
                parted(Vector3::zeros())
            );
        }
    }

    /// A body turning against the other (landing on a face, tipping over it) by more than the
    /// slip threshold at the support's edge gets no weld: its points do not stay on the other's.
    #[test]
    fn bodies_turning_against_each_other_are_not_welded() {
        let w = Vector3::new(0.4, -1.2, 1.5).normalize() * 2.0;
        // 0.01 rad/s against each other moves the square's corners (0.28 m out) by 2.8 mm/s.
        let (contact, bodies) = turning(w + Vector3::new(0.01, 0.0, 0.0), w);
        assert_eq!(
            weld_velocity(&contact, &bodies, 0.01, 1e-3),
            Vector3::zeros()
        );
        let (contact, bodies) = turning(w + Vector3::new(0.001, 0.0, 0.0), w);
        assert_ne!(
            weld_velocity(&contact, &bodies, 0.01, 1e-3),
            Vector3::zeros()
        );
    }
}
