//! One contact between two bodies, as every contact model sees it.

use nalgebra::{Point2, Point3};
use tatami_geometry::ConvexPolygon;
use tatami_lcp::BodyId;

use crate::{ContactError, ContactFrame, Material};

/// Two touching bodies and the geometry of their contact.
///
/// The support polygon lives in the frame's plane coordinates `(t1, t2)` relative to
/// `frame.origin`; `depths[i]` is the penetration at its vertex `i` along `n` (positive when the
/// bodies overlap there, negative for a gap the contact may close within the step).
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    /// The body pushed along `+n`.
    pub body_a: BodyId,
    /// The body pushed along `−n`.
    pub body_b: BodyId,
    /// Centre of mass of A (world).
    pub centre_a: Point3<f64>,
    /// Centre of mass of B (world).
    pub centre_b: Point3<f64>,
    /// Origin and axes.
    pub frame: ContactFrame,
    /// Every vertex of the overlap of the two touching features, counter-clockwise from `+n`.
    pub support: ConvexPolygon,
    /// Penetration at each support vertex.
    pub depths: Vec<f64>,
    /// Combined friction and restitution.
    pub material: Material,
    /// Points of either body standing off the support polygon within the contact margin, where
    /// the touching feature would land if the body turned (usually none). A cylinder resting on
    /// the lowest point of its cap's rim touches at that point alone, yet as it wobbles the
    /// lowest point runs round the rim; held at one point,
    /// the rim beside it went 1 cm into the floor. A polyhedron closing on the other body
    /// faster than the margin a step has its vertices within that closing distance here too,
    /// where the turn an impact gives it would swing them down. Every model gives each a
    /// block that lets it come down to the support's deepest level within the step and no
    /// further.
    pub landing: Vec<Landing>,
    /// The separation speed (m/s, ≥ 0) the contact's landed points bounce at in this step: a
    /// bouncing pair is landed on the surface from a gap first, without a bounce, and bounced on
    /// the next step at restitution times the speed it met at, so the bounce starts from the
    /// surface, not from the gap (see
    /// [`ContactSettings::has_landed`](crate::ContactSettings::has_landed)); 0 when no landing
    /// is to be bounced. Set by the world; 0 for a contact built by hand.
    pub bounce_speed: f64,
}

/// A point of a contact's plane where a body stands off the other ([`Contact::landing`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Landing {
    /// Where, in the frame's plane coordinates (as the support polygon's vertices).
    pub point: Point2<f64>,
    /// Penetration there along `n`: negative, a gap.
    pub depth: f64,
}

impl Contact {
    /// The largest penetration over the support polygon.
    pub fn depth(&self) -> f64 {
        self.depths
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Checks that there is one finite depth per support vertex, that the landing points are
    /// finite, and that the bounce speed is finite and ≥ 0.
    pub(crate) fn validate_depths(&self) -> Result<(), ContactError> {
        let vertices = self.support.vertices().len();
        if self.depths.len() != vertices {
            return Err(ContactError::DepthCount {
                depths: self.depths.len(),
                vertices,
            });
        }
        if !self.depths.iter().all(|d| d.is_finite()) {
            return Err(ContactError::NonFinite { what: "depth" });
        }
        let landing = |l: &Landing| l.point.iter().chain([&l.depth]).all(|x| x.is_finite());
        if !self.landing.iter().all(landing) {
            return Err(ContactError::NonFinite {
                what: "landing point",
            });
        }
        if !(self.bounce_speed.is_finite() && self.bounce_speed >= 0.0) {
            return Err(ContactError::InvalidBounceSpeed(self.bounce_speed));
        }
        Ok(())
    }

    /// Checks that the contact is well formed for a problem with `bodies` bodies.
    pub fn validate(&self, bodies: usize) -> Result<(), ContactError> {
        for body in [self.body_a, self.body_b] {
            if body.0 >= bodies {
                return Err(ContactError::UnknownBody {
                    body: body.0,
                    bodies,
                });
            }
        }
        // The fields are public: a material built by hand gets the checks of `Material::new`.
        let m = &self.material;
        Material::new(m.static_friction, m.kinetic_friction, m.restitution)?;
        self.validate_depths()?;
        // One array, not a chain of the two points' iterators, which took a third of these
        // checks' instructions (3.6% of a resting pyramid's row building).
        let (a, b) = (&self.centre_a, &self.centre_b);
        if ![a.x, a.y, a.z, b.x, b.y, b.z].iter().all(|x| x.is_finite()) {
            return Err(ContactError::NonFinite { what: "centre" });
        }
        // Re-validates the frame (a hand-built frame may bypass `from_normal`).
        let n = self.frame.normal;
        let unit = (n.norm() - 1.0).abs() < 1e-9;
        if !unit {
            return Err(ContactError::InvalidNormal(n.x, n.y, n.z));
        }
        if !self.frame.origin.iter().all(|x| x.is_finite()) {
            return Err(ContactError::NonFinite { what: "origin" });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Point2, Vector3};

    use super::*;

    /// A `Material` built by hand with NaN or negative friction made `f64::clamp` panic in the
    /// friction projection; `validate` now refuses it.
    #[test]
    fn a_hand_built_material_is_checked() {
        let contact = |static_friction: f64| Contact {
            body_a: BodyId(0),
            body_b: BodyId(1),
            centre_a: Point3::new(0.0, 0.0, 1.0),
            centre_b: Point3::new(0.0, 0.0, -1.0),
            frame: ContactFrame::from_normal(Point3::origin(), Vector3::z()).unwrap(),
            support: ConvexPolygon::from_points(&[Point2::origin()]).unwrap(),
            depths: vec![0.0],
            material: Material {
                static_friction,
                kinetic_friction: 0.5,
                restitution: 0.0,
            },
            landing: Vec::new(),
            bounce_speed: 0.0,
        };
        assert!(contact(0.5).validate(2).is_ok());
        for bad in [f64::NAN, -0.1, f64::INFINITY] {
            assert!(matches!(
                contact(bad).validate(2),
                Err(ContactError::InvalidFriction { .. })
            ));
        }
        // A bounce speed is a separation speed: negative or not finite, it is refused.
        let bouncing = |bounce_speed: f64| Contact {
            bounce_speed,
            ..contact(0.5)
        };
        assert!(bouncing(2.5).validate(2).is_ok());
        for bad in [f64::NAN, -1.0, f64::INFINITY] {
            assert!(matches!(
                bouncing(bad).validate(2),
                Err(ContactError::InvalidBounceSpeed(_))
            ));
        }
    }
}
