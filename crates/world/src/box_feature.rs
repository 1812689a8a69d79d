//! A box's touching feature from its topology: the corners [`Outline::feature`] keeps of a
//! polyhedron's, without searching them.
//!
//! The general search dots every hull vertex with the direction, then tests every pair of the
//! candidates for one lying above the other more steeply than the feature angle. A box's
//! corners are the extreme corner `E` and its flips across one, two or three axes: flipping
//! axis `k` lowers a corner by `2 hₖ |dₖ|` (`d` the direction in the box's axes) over a
//! horizontal run of `2 hₖ √(1 − dₖ²)`. So the same rule reads off the axes directly: axis `k`
//! is *flat* when its flip is a candidate and not too steep; no flat axis gives the corner, one
//! the edge `E, E_k`, two the face `E, E_i, E_ij, E_j` (its far corner `E_ij` judged against
//! `E` along the diagonal, as the search judges it). The face comes with its outward normal,
//! so [`crate::support`] places its plane exactly instead of fitting one; the corners keep
//! their hull-vertex numbers (bit `k` set when the corner is on the `+k` side), so named
//! support vertices are the same as from the search. A direction within the feature angle of
//! three axes at once (a feature angle near 45°) is left to the search.
//!
//! [`Outline::feature`]: crate::support::Outline::feature

use nalgebra::{Point3, UnitQuaternion, Vector3};

use crate::support::{Feature, FeatureAngle, FeaturePoint};

/// The feature of the box of `half_extents`, centred at `origin` and turned by `rotation`,
/// furthest along the unit `direction`, as the general search finds it among the box's
/// corners; written into `out`. `false` (and `out` untouched) when three axes are flat, which
/// the search settles.
pub(crate) fn cuboid_feature(
    half_extents: &Vector3<f64>,
    origin: &Point3<f64>,
    rotation: &UnitQuaternion<f64>,
    direction: &Vector3<f64>,
    angle: &FeatureAngle,
    out: &mut Feature,
) -> bool {
    let h = half_extents;
    let radius = h.norm();
    let local = rotation.inverse_transform_vector(direction);
    // The search's thresholds: candidates within `2 radius · sin(angle) + eps` below the
    // extreme; a candidate dropped when another is above it by more than `eps` and more
    // steeply than the angle ([`FeatureAngle::is_steeper`]).
    let eps = 1e-9 * radius;
    let band = 2.0 * radius * angle.sin + eps;
    let steep = |drop: f64, run_squared: f64| angle.is_steeper(drop, run_squared, eps);
    // How far a flip of each axis lowers the corner, and whether that axis is flat.
    let drops = Vector3::from_fn(|k, _| 2.0 * h[k] * local[k].abs());
    let flat: [bool; 3] = std::array::from_fn(|k| {
        let run_squared = 4.0 * h[k] * h[k] - drops[k] * drops[k];
        drops[k] <= band && !steep(drops[k], run_squared)
    });
    let (i, j) = match flat {
        [true, true, true] => return false,
        [true, true, false] => (Some(0), Some(1)),
        [true, false, true] => (Some(0), Some(2)),
        [false, true, true] => (Some(1), Some(2)),
        _ => (flat.iter().position(|&f| f), None),
    };
    let matrix = rotation.to_rotation_matrix();
    let axes = matrix.matrix();
    // The extreme corner: on the side of each axis the direction points to.
    let signs = local.map(|x| if x >= 0.0 { 1.0 } else { -1.0 });
    let extreme_id = (0..3).fold(0u32, |id, k| id | (u32::from(signs[k] > 0.0) << k));
    let extreme = origin + axes * signs.component_mul(h);
    // A flip of axis `k` moves the corner by `∓2 hₖ` along the box's `k` axis.
    let flip = |k: usize| axes.column(k) * (-2.0 * signs[k] * h[k]);
    out.points.clear();
    out.face_normal = None;
    out.ring = true;
    out.points.push(FeaturePoint {
        point: extreme,
        id: extreme_id,
    });
    match (i, j) {
        (None, _) => {}
        (Some(k), None) => out.points.push(FeaturePoint {
            point: extreme + flip(k),
            id: extreme_id ^ (1 << k),
        }),
        (Some(i), Some(j)) => {
            let drop = drops[i] + drops[j];
            let run_squared = 4.0 * (h[i] * h[i] + h[j] * h[j]) - drop * drop;
            let far = drop <= band && !steep(drop, run_squared);
            let (corner_i, corner_j) = (extreme + flip(i), extreme + flip(j));
            out.points.push(FeaturePoint {
                point: corner_i,
                id: extreme_id ^ (1 << i),
            });
            if far {
                out.points.push(FeaturePoint {
                    point: corner_i + flip(j),
                    id: extreme_id ^ (1 << i) ^ (1 << j),
                });
            }
            out.points.push(FeaturePoint {
                point: corner_j,
                id: extreme_id ^ (1 << j),
            });
            // The face across the third axis, outward on the direction's side.
            let k = 3 - i - j;
            out.face_normal = Some(axes.column(k) * signs[k]);
        }
    }
    // The search lists the corners by number; starting the ring at the lowest keeps the first
    // point, where the contact frame's origin is taken from, the search's.
    if let Some(lowest) = (0..out.points.len()).min_by_key(|&k| out.points[k].id) {
        out.points.rotate_left(lowest);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Shape;
    use crate::parry_bridge::Collider;
    use crate::support::Outline;
    use proptest::prelude::*;

    /// A box's corners as the world lists them for its outline.
    fn corners(h: &Vector3<f64>) -> Vec<Vector3<f64>> {
        let shape = Shape::cuboid([2.0 * h.x, 2.0 * h.y, 2.0 * h.z]);
        Collider::new(&shape)
            .and_then(|collider| collider.hull_vertices())
            .expect("a box has corners")
    }

    /// Against the general search over the box's corners: the same corners (by number, and in
    /// place within rounding), whether the direction is near an axis (a face, up to its far
    /// corner dropped along the diagonal), near an edge's normal or near neither. Directions are
    /// drawn within twice the feature angle of a face normal, where the three cases meet, on
    /// boxes of mixed proportions turned anywhere. A face's points lie on the plane of its
    /// normal within rounding.
    #[test]
    fn a_box_feature_is_the_searched_one() {
        proptest!(ProptestConfig::with_cases(512), |(
            h in (0.05..3.0f64, 0.05..3.0f64, 0.05..3.0f64),
            turn in (-3.2..3.2f64, -1.6..1.6f64, -3.2..3.2f64),
            axis in 0usize..3,
            positive in any::<bool>(),
            tilt in (-2.0..2.0f64, -2.0..2.0f64),
            degrees in 0.2..30.0f64,
        )| {
            let h = Vector3::new(h.0, h.1, h.2);
            let rotation = UnitQuaternion::from_euler_angles(turn.0, turn.1, turn.2);
            let angle = FeatureAngle::new(degrees.to_radians());
            let mut local = Vector3::zeros();
            local[axis] = if positive { 1.0 } else { -1.0 };
            local[(axis + 1) % 3] = tilt.0 * angle.sin;
            local[(axis + 2) % 3] = tilt.1 * angle.sin;
            let direction = rotation * local.normalize();
            let origin = Point3::new(1.0, -2.0, 0.5);
            let mut read = Feature::default();
            prop_assume!(cuboid_feature(&h, &origin, &rotation, &direction, &angle, &mut read));
            let mut searched = Feature::default();
            Outline::polyhedron(corners(&h), None)
                .feature(&origin, &rotation, &direction, &angle, &mut searched);
            let numbers = |f: &Feature| {
                let mut ids: Vec<u32> = f.points.iter().map(|p| p.id).collect();
                ids.sort_unstable();
                ids
            };
            prop_assert_eq!(numbers(&read), numbers(&searched));
            prop_assert_eq!(read.points[0].id, searched.points[0].id, "the first point");
            for p in &read.points {
                let q = searched.points.iter().find(|q| q.id == p.id).expect("same numbers");
                prop_assert!((p.point - q.point).norm() < 1e-12 * (1.0 + h.norm()));
            }
            prop_assert_eq!(read.face_normal.is_some(), read.points.len() >= 3);
            if let Some(m) = read.face_normal {
                // Each of the face's two flips within the angle: `m·d ≥ √(1 − 2 sin² angle)`.
                let least = (1.0 - 2.0 * angle.sin * angle.sin).sqrt();
                prop_assert!(m.dot(&direction) > least - 1e-12);
                let p0 = read.points[0].point;
                for p in &read.points {
                    prop_assert!((p.point - p0).dot(&m).abs() < 1e-12 * (1.0 + h.norm()));
                }
            }
        });
    }
}
