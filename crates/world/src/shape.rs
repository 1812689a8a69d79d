//! Collision shapes and their solid mass properties.

use nalgebra::{Matrix3, Point3, Vector3};

use crate::WorldError;

/// Lengths a shape may have (m): sizes, radii, heights, hull coordinates. Contact geometry
/// resolves about 1e-9 of a contact's size and keeps depths to the micrometre up to 100 km (a
/// cube fell through a 1e10 m ground, and parry's EPA indexed out of bounds at 1e155 m); below
/// 0.1 mm a body is under the 2 mm slop and the 5 mm contact margin by orders of magnitude.
pub const LENGTHS: std::ops::RangeInclusive<f64> = 1e-4..=1e5;
use crate::parry_bridge;

/// The shape of a body, in its body frame (centred on the body's origin).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A box with the given half edge lengths along the body's axes.
    Box {
        /// Half of each edge length (m).
        half_extents: Vector3<f64>,
    },
    /// A ball.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// A solid cylinder along the body's z axis.
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Half the height (m).
        half_height: f64,
    },
    /// The convex hull of the given points.
    Convex {
        /// Points in the body frame; interior points are allowed and ignored.
        points: Vec<Point3<f64>>,
    },
}

/// A convex hull as a triangle mesh (body frame).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HullMesh {
    /// The hull's vertices.
    pub vertices: Vec<Point3<f64>>,
    /// Each triangle's three indices into `vertices`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// Volume, centre of mass and inertia of a solid shape of unit mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Volume (m³).
    pub volume: f64,
    /// Centre of mass in the body frame.
    pub centre_of_mass: Point3<f64>,
    /// Inertia tensor per unit mass about the centre of mass, body axes (m²).
    pub unit_inertia: Matrix3<f64>,
}

impl Shape {
    /// A box from its full edge lengths.
    pub fn cuboid(size: [f64; 3]) -> Self {
        Self::Box {
            half_extents: Vector3::from(size) / 2.0,
        }
    }

    /// A ball of the given radius.
    pub fn sphere(radius: f64) -> Self {
        Self::Sphere { radius }
    }

    /// A cylinder along z from its radius and full height.
    pub fn cylinder(radius: f64, height: f64) -> Self {
        Self::Cylinder {
            radius,
            half_height: height / 2.0,
        }
    }

    /// The convex hull of `points`.
    pub fn convex(points: Vec<Point3<f64>>) -> Self {
        Self::Convex { points }
    }

    /// The hull of a [`Shape::Convex`] as triangles wound outwards (body frame), for drawing or
    /// export. `None` for the other shapes and for points without volume.
    ///
    /// ```
    /// use nalgebra::Point3;
    /// use tatami_world::Shape;
    /// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let tetrahedron = Shape::convex(corners.iter().map(|&p| Point3::from(p)).collect());
    /// let hull = tetrahedron.hull_mesh().unwrap();
    /// assert_eq!((hull.vertices.len(), hull.triangles.len()), (4, 4));
    /// ```
    pub fn hull_mesh(&self) -> Option<HullMesh> {
        match self {
            Self::Convex { points } => crate::parry_bridge::hull_mesh(points),
            _ => None,
        }
    }

    /// Mass properties of the solid shape, or why the shape is invalid (a length outside
    /// [`LENGTHS`], a hull without volume).
    pub fn mass_properties(&self) -> Result<MassProperties, WorldError> {
        let invalid = |what: &str, value: f64| WorldError::InvalidShape {
            reason: format!(
                "{what} must be from {:e} to {:e} m, got {value}",
                LENGTHS.start(),
                LENGTHS.end()
            ),
        };
        let length = |h: f64| LENGTHS.contains(&(2.0 * h));
        match self {
            Self::Box { half_extents: h } => {
                if let Some(&bad) = h.iter().find(|h| !length(**h)) {
                    return Err(invalid("box size", 2.0 * bad));
                }
                let (x2, y2, z2) = (h.x * h.x, h.y * h.y, h.z * h.z);
                Ok(MassProperties {
                    volume: 8.0 * h.x * h.y * h.z,
                    centre_of_mass: Point3::origin(),
                    unit_inertia: Matrix3::from_diagonal(&Vector3::new(y2 + z2, x2 + z2, x2 + y2))
                        / 3.0,
                })
            }
            Self::Sphere { radius: r } => {
                if !LENGTHS.contains(r) {
                    return Err(invalid("sphere radius", *r));
                }
                Ok(MassProperties {
                    volume: 4.0 / 3.0 * std::f64::consts::PI * r.powi(3),
                    centre_of_mass: Point3::origin(),
                    unit_inertia: Matrix3::identity() * (0.4 * r * r),
                })
            }
            Self::Cylinder {
                radius: r,
                half_height: h,
            } => {
                if !LENGTHS.contains(r) {
                    return Err(invalid("cylinder radius", *r));
                }
                if !length(*h) {
                    return Err(invalid("cylinder height", 2.0 * h));
                }
                let axial = 0.5 * r * r;
                let transverse = (3.0 * r * r + 4.0 * h * h) / 12.0;
                Ok(MassProperties {
                    volume: std::f64::consts::PI * r * r * 2.0 * h,
                    centre_of_mass: Point3::origin(),
                    unit_inertia: Matrix3::from_diagonal(&Vector3::new(
                        transverse, transverse, axial,
                    )),
                })
            }
            Self::Convex { points } => {
                let within = |x: &f64| x.abs() <= *LENGTHS.end();
                if let Some(p) = points.iter().find(|p| !p.iter().all(within)) {
                    return Err(WorldError::InvalidShape {
                        reason: format!(
                            "convex point ({}, {}, {}) must be finite and within {:e} m of the \
                             body's origin",
                            p.x,
                            p.y,
                            p.z,
                            LENGTHS.end()
                        ),
                    });
                }
                parry_bridge::convex_mass_properties(points).ok_or_else(|| {
                    WorldError::InvalidShape {
                        reason: format!(
                            "the hull of {} points has no volume (needs 4 points not on one plane)",
                            points.len()
                        ),
                    }
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn convex_cube_matches_the_box_closed_form() {
        let corners: Vec<_> = (0..8)
            .map(|i| {
                let s = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
                Point3::new(s(1) + 3.0, s(2), s(4))
            })
            .collect();
        let hull = Shape::convex(corners).mass_properties().unwrap();
        let cube = Shape::cuboid([2.0, 2.0, 2.0]).mass_properties().unwrap();
        assert!((hull.volume - cube.volume).abs() < 1e-12);
        assert!((hull.centre_of_mass - Point3::new(3.0, 0.0, 0.0)).norm() < 1e-12);
        assert!((hull.unit_inertia - cube.unit_inertia).norm() < 1e-12);
    }

    #[test]
    fn degenerate_and_non_finite_shapes_are_rejected() {
        assert!(Shape::cuboid([1.0, 0.0, 1.0]).mass_properties().is_err());
        assert!(Shape::sphere(f64::NAN).mass_properties().is_err());
        let flat = vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(1.0, 1.0, 0.0),
        ];
        assert!(Shape::convex(flat).mass_properties().is_err());
    }
}
