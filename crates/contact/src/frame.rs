//! The contact frame: an origin on the contact plane and the orthonormal axes `t1, t2, n`.

use nalgebra::{Point2, Point3, Vector3};

use crate::ContactError;

/// Origin and axes of a contact: `n` points from body B into body A; `(t1, t2, n)` is
/// right-handed, so polygons counter-clockwise in `(t1, t2)` are counter-clockwise seen from `+n`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFrame {
    /// A point of the contact plane; support polygons are expressed relative to it.
    pub origin: Point3<f64>,
    /// First tangent.
    pub tangent1: Vector3<f64>,
    /// Second tangent, `n × t1`.
    pub tangent2: Vector3<f64>,
    /// Unit normal, from B into A.
    pub normal: Vector3<f64>,
}

impl ContactFrame {
    /// A frame with the given normal (normalised here) and tangents chosen from it alone, so the
    /// same normal always gives the same tangents.
    pub fn from_normal(origin: Point3<f64>, normal: Vector3<f64>) -> Result<Self, ContactError> {
        let length = normal.norm();
        if !(length.is_finite() && length > 0.0) {
            return Err(ContactError::InvalidNormal(normal.x, normal.y, normal.z));
        }
        if !origin.iter().all(|x| x.is_finite()) {
            return Err(ContactError::NonFinite { what: "origin" });
        }
        let n = normal / length;
        // Cross with the world axis least aligned with n: well conditioned for every normal.
        let axis = if n.x.abs() < 0.57 {
            Vector3::x()
        } else if n.y.abs() < 0.57 {
            Vector3::y()
        } else {
            Vector3::z()
        };
        let tangent2 = n.cross(&axis).normalize();
        let tangent1 = tangent2.cross(&n);
        Ok(Self {
            origin,
            tangent1,
            tangent2,
            normal: n,
        })
    }

    /// The world point of plane coordinates `p`.
    pub fn to_world(&self, p: &Point2<f64>) -> Point3<f64> {
        self.origin + self.tangent1 * p.x + self.tangent2 * p.y
    }

    /// Plane coordinates of the world point `p` projected along the normal.
    pub fn to_plane(&self, p: &Point3<f64>) -> Point2<f64> {
        let d = p - self.origin;
        Point2::new(d.dot(&self.tangent1), d.dot(&self.tangent2))
    }
}
