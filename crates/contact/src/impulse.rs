//! What a contact's rows did to body A over a solve, as one linear impulse and one angular
//! impulse about A's centre of mass: the face model's impulses carried from one step to the
//! next.
//!
//! The face model's block is forces at one point along orthonormal axes `(n, t1, t2)`, then
//! torques about orthonormal axes (none for a point, `(u, n)` for a segment, `(t1, t2, n)` for a
//! face). So the impulse on A fixes every row of the next step's block, whatever its support
//! became: a segment whose ends are clipped by other edges, or that turns into a face or a
//! point, starts from the torque it carried, moved to its new point and read on its new axes.
//! Named per row instead (by the feature id of the segment's first end), a 1000-cube pile
//! restarted the tilt and twist of about 30 segments a step from zero, and never came to rest
//! (`CHANGES.md`).

use nalgebra::{Point3, Vector3};
use tatami_lcp::Row;

/// The impulse a contact's rows applied to body A: `linear`, and `angular` about `centre_a`,
/// A's centre of mass when the rows were built (B got the opposite).
///
/// ```
/// use nalgebra::{Point2, Point3, Vector3};
/// use tatami_contact::{Contact, ContactFrame, ContactImpulse, ContactModel, ContactSettings, Material};
/// use tatami_geometry::ConvexPolygon;
/// use tatami_lcp::{BodyId, Problem, SolverBody};
///
/// let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let mut contact = Contact {
///     body_a: BodyId(0),
///     body_b: BodyId(1),
///     centre_a: Point3::new(0.0, 0.0, 1.0),
///     centre_b: Point3::new(0.0, 0.0, -1.0),
///     frame: ContactFrame::from_normal(Point3::origin(), Vector3::z())?,
///     support: ConvexPolygon::from_points(&square)?,
///     depths: vec![0.0; 4],
///     material: Material::new(0.5, 0.5, 0.0)?,
///     landing: Vec::new(),
///     bounce_speed: 0.0,
/// };
/// let build = |contact: &Contact| -> Result<Problem<_>, tatami_contact::ContactError> {
///     let mut problem = Problem { bodies: vec![SolverBody::fixed(); 2], ..Default::default() };
///     ContactModel::Face.build(contact, 0.01, &ContactSettings::default(), &mut problem)?;
///     Ok(problem)
/// };
/// // The face carries weight with its centre of pressure off centre.
/// let mut face = build(&contact)?;
/// face.rows[0].impulse = 0.1; // f3
/// face.rows[4].impulse = 0.02; // τ2: the centre of pressure 0.2 m along −t1
/// let carried = ContactImpulse::of_rows(&face.rows, contact.centre_a);
/// // Next step the support is a segment across the face's centre, along t1.
/// let segment = [(-1.0, 0.0), (1.0, 0.0)].map(|(x, y)| Point2::new(x, y));
/// contact.support = ConvexPolygon::from_points(&segment)?;
/// contact.depths = vec![0.0; 2];
/// let mut next = build(&contact)?;
/// carried.write_face_rows(&mut next.rows, &contact.centre_a);
/// // Rows f3, f1, f2, τu, τ3 with u = n × (±t1) = ±t2: the same weight and tilt.
/// assert!((next.rows[0].impulse - 0.1).abs() < 1e-15);
/// assert!((next.rows[3].impulse.abs() - 0.02).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactImpulse {
    /// Linear impulse on A (N s).
    pub linear: Vector3<f64>,
    /// Angular impulse on A about `centre_a` (N m s).
    pub angular: Vector3<f64>,
    /// The point `angular` is about (world).
    pub centre_a: Point3<f64>,
}

impl ContactImpulse {
    /// The impulse that `rows` (of any model), with their solved impulses, apply to body A
    /// whose centre of mass the rows were built about is `centre_a`.
    pub fn of_rows(rows: &[Row], centre_a: Point3<f64>) -> Self {
        let (mut linear, mut angular) = (Vector3::zeros(), Vector3::zeros());
        for row in rows {
            linear += row.jacobian.linear_a * row.impulse;
            angular += row.jacobian.angular_a * row.impulse;
        }
        Self {
            linear,
            angular,
            centre_a,
        }
    }

    /// Sets the impulses of one face-model block's `rows`, built with A's centre of mass at
    /// `centre_a`, to this impulse's components on them: each force row takes the linear
    /// impulse along its axis, each torque row the rest of the angular impulse about the
    /// block's point along its axis. Exact where the block can carry the impulse; what it
    /// cannot (a torque on a point, a tilt about a segment's own line) is left out.
    pub fn write_face_rows(&self, rows: &mut [Row], centre_a: &Point3<f64>) {
        let mut angular = self.angular + (self.centre_a - centre_a).cross(&self.linear);
        let is_force = |row: &Row| row.jacobian.linear_a != Vector3::zeros();
        for row in rows.iter_mut().filter(|row| is_force(row)) {
            row.impulse = self.linear.dot(&row.jacobian.linear_a);
            angular -= row.jacobian.angular_a * row.impulse;
        }
        for row in rows.iter_mut().filter(|row| !is_force(row)) {
            row.impulse = angular.dot(&row.jacobian.angular_a);
        }
    }
}
