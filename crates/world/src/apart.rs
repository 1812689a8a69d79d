//! Pairs found apart, and how long they stay so: the bound that lets collision skip them.
//!
//! The broad phase's boxes are padded by the margin (and by how far the body may move in the
//! step, [`crate::speculative`]) and cover a turned box's corners, so a resting pile of 1000
//! cubes has some 2,000 pairs a step whose boxes overlap while the bodies are apart, about as
//! many as it has contacts; each used to be tested afresh every step. The
//! separating-axis tests find such a pair apart along a *face* normal of one body, by a
//! separation `s` beyond the margin, and answer "apart" whenever some face normal separates by
//! more than the margin. That face's normal turns with its body, and in the face owner's frame
//! the other body's points move by at most
//!
//! `δ = |Δc_A| + |Δc_B| + θ_other · r_other + θ_owner · (|c_A − c_B| + r_other)`
//!
//! (`c` the centres of mass where the pair was found apart, `θ` each body's turn since, `r` the
//! largest distance of its shape from its centre), so the separation along it is still above
//! `s − δ`. While `s − δ` exceeds the margin the test would answer "apart" again: the pair is
//! skipped, with the same result as testing it.
//!
//! An edge–edge axis turns with both bodies, so the test's axis moves on, but the separation
//! along the axis as it was, fixed in space, drops by no more than each body's points move:
//! `δ = |Δc_A| + θ_A · r_A + |Δc_B| + θ_B · r_B`. While `s − δ` exceeds the margin the shapes
//! are still farther apart than that (no two points are nearer than the separation along any
//! axis), so no contact within the margin exists, and the pair is skipped. A test might still
//! have answered with a contact: along its turned axes the separation can fall short of the
//! distance (two cubes corner to corner are separated along a face normal by 1/√3 of their
//! distance), and such a contact, farther apart than the margin, is what the pair kept apart
//! goes without. On the 1000-shape pile at rest some 56 pairs a step, apart only along
//! an edge–edge axis, had been tested afresh every step.
//!
//! Nothing in the bound needs the axis to be a face normal: any axis fixed in the owner's frame
//! serves, as long as the separation along it is measured against the true shapes. A pair with
//! a ball or a cylinder is decided by parry's GJK, which reports a contact only within the
//! margin (a cylinder against a box or a hull by the polytope's faces first, whose widest
//! separation beyond the margin is a face's gap as above: [`crate::proved_normal`]). When GJK
//! finds none, the face planes of either shape (a polytope's faces, a
//! cylinder's caps) are measured against the other's support function, and where none shows
//! the pair apart, so is GJK's separating direction (or a ball's direction from the other
//! shape's nearest point): each such separation is at most the shapes' distance, so the same
//! bound keeps the pair apart. Two balls keep the gap between them, which follows their
//! centres.

use nalgebra::UnitQuaternion;

use crate::contact_set::Pose;
use crate::speculative::Travel;

/// Relative rounding allowance of the bound, as a fraction of the pair's size (the centres'
/// distance and both reaches): the tests' separations sum a few products of coordinates of that
/// size, each within about 1e-15 of it, so 1e-9 leaves a factor of a million.
const ROUNDING: f64 = 1e-9;

/// What an [`AxisGap`]'s axis is fixed in, which decides how far the bodies' motion can close
/// the gap (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum AxisFrame {
    /// The first body (the first shape given to the test): a face normal of it, or a curved
    /// pair's separating direction taken in it.
    First,
    /// The second body.
    Second,
    /// Space: an edge–edge axis as it was when the pair was found apart.
    Space,
}

impl AxisFrame {
    /// A face normal of the first shape (`true`) or of the second.
    pub(crate) fn of_first(first: bool) -> Self {
        if first { Self::First } else { Self::Second }
    }

    /// The same axis with the shapes given the other way round.
    pub(crate) fn swapped(self) -> Self {
        match self {
            Self::First => Self::Second,
            Self::Second => Self::First,
            Self::Space => Self::Space,
        }
    }
}

/// An axis along which a pair is separated beyond the margin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct AxisGap {
    /// The separation along the axis (m), above the margin.
    pub separation: f64,
    /// What the axis is fixed in.
    pub frame: AxisFrame,
}

/// Where a body is, as the tests of motion read it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Placement {
    /// Centre of mass and orientation.
    pub pose: Pose,
    /// The outline's size: a turn counts as rad × this in the contact-reuse test.
    pub size: f64,
    /// Largest distance of the body's shape from its centre of mass.
    pub reach: f64,
    /// How far its points may move in the coming step: a pair's margin grows by their
    /// closing ([`crate::speculative`]).
    pub travel: Travel,
    /// A ball or a cylinder, whose contacts on its curved surface run over it as it rolls.
    pub round: bool,
    /// The body's least width (its [`crate::Body`]'s thickness), which holds its pairs' margin
    /// ([`crate::tolerances::pair_margin`]).
    pub thickness: f64,
}

/// A pair found apart along an axis, with the poses it was found at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Apart {
    pub gap: AxisGap,
    pub poses: [Pose; 2],
}

impl Apart {
    /// Whether the pair's bodies, now at `a` and `b`, cannot have closed the gap to `margin`:
    /// the separating-axis test would find them apart again (see the module doc). `false` on
    /// any non-finite input.
    pub(crate) fn still_apart(&self, a: &Placement, b: &Placement, margin: f64) -> bool {
        let [(was_a, turned_a), (was_b, turned_b)] = &self.poses;
        let moved = (a.pose.0 - was_a).norm() + (b.pose.0 - was_b).norm();
        let (turn_a, turn_b) = (
            turn_bound(&a.pose.1, turned_a),
            turn_bound(&b.pose.1, turned_b),
        );
        let distance = (was_b - was_a).norm();
        let closed = moved
            + match self.gap.frame {
                AxisFrame::First => turn_b * b.reach + turn_a * (distance + b.reach),
                AxisFrame::Second => turn_a * a.reach + turn_b * (distance + a.reach),
                AxisFrame::Space => turn_a * a.reach + turn_b * b.reach,
            };
        let rounding = ROUNDING * (distance + a.reach + b.reach);
        closed + rounding < self.gap.separation - margin
    }
}

/// An upper bound of the angle (rad) between two orientations, without an arc cosine: the
/// relative rotation's quaternion has vector part `sin(θ/2)` long, and `θ ≤ π sin(θ/2)` for
/// `θ` in `[0, π]`. The vector part is formed directly, so it keeps its relative precision
/// for small turns, where `1 − cos` would not.
fn turn_bound(now: &UnitQuaternion<f64>, was: &UnitQuaternion<f64>) -> f64 {
    std::f64::consts::PI * (was.inverse() * now).imag().norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parry_bridge::tests::{sharp_distance, uniform_from};
    use crate::parry_bridge::{Collider, contact_normal, pose};
    use crate::shape::Shape;
    use nalgebra::{Point3, Unit, Vector3};

    fn direction(uniform: &mut impl FnMut() -> f64) -> Unit<Vector3<f64>> {
        Unit::new_normalize(Vector3::new(
            uniform() - 0.5,
            uniform() - 0.5,
            uniform() - 0.5,
        ))
    }

    /// A turn by up to `most` rad about a random axis.
    fn turn(uniform: &mut impl FnMut() -> f64, most: f64) -> UnitQuaternion<f64> {
        UnitQuaternion::from_axis_angle(&direction(uniform), most * uniform())
    }

    /// Shape `kind` (a box; an octahedron stretched along each axis, eight faces none of them
    /// a box's; a ball; a cylinder) of 0.1–2 m times `scale`, with the largest distance of a
    /// point of it from its origin.
    fn shape(uniform: &mut impl FnMut() -> f64, kind: usize, scale: f64) -> (Shape, f64) {
        let size = scale * (0.1 + 1.9 * uniform());
        let mut side = || size * (0.3 + 0.7 * uniform());
        let (x, y, z) = (side(), side(), side());
        match kind {
            0 => (
                Shape::cuboid([2.0 * x, 2.0 * y, 2.0 * z]),
                Vector3::new(x, y, z).norm(),
            ),
            1 => {
                let points = vec![
                    Point3::new(x, 0.0, 0.0),
                    Point3::new(-x, 0.0, 0.0),
                    Point3::new(0.0, y, 0.0),
                    Point3::new(0.0, -y, 0.0),
                    Point3::new(0.0, 0.0, z),
                    Point3::new(0.0, 0.0, -z),
                ];
                (Shape::Convex { points }, x.max(y).max(z))
            }
            2 => (Shape::sphere(x), x),
            _ => (Shape::cylinder(x, 2.0 * y), x.hypot(y)),
        }
    }

    /// Pairs of boxes, hulls, balls and cylinders, turned at random and found apart along an
    /// axis (or, for two balls, by their gap), then each body moved by up to half the gap and
    /// turned by up to 0.1 rad (or not): every pair the bound keeps apart is farther apart than
    /// the margin (parry's distance query), a pair without a cylinder is found apart again by
    /// the same tests (guaranteed along a face normal; along an edge–edge axis, fixed in space,
    /// only the distance is, and the 21 such pairs kept here are found apart again too), and
    /// the bound keeps a good share of them (it is not vacuous). A pair
    /// with a cylinder may not be: its normal is searched on rounded cores within more than
    /// the margin, and the contact found there is dropped later, by its depths
    /// ([`Collider::is_rounded`]).
    #[test]
    fn a_pair_the_bound_keeps_apart_is_found_apart() {
        let mut uniform = uniform_from(31);
        let margin = 0.02;
        let (mut found, mut kept, mut kept_along_edges) = (0, 0, 0);
        for case in 0..40_000 {
            // A third of the first bodies are ten times larger: which body's face it is matters.
            let scale = if case % 3 == 2 { 10.0 } else { 1.0 };
            let (shape_a, reach_a) = shape(&mut uniform, case % 4, scale);
            let (shape_b, reach_b) = shape(&mut uniform, case / 4 % 4, 1.0);
            let (Some(a), Some(b)) = (Collider::new(&shape_a), Collider::new(&shape_b)) else {
                continue;
            };
            let (turn_a, turn_b) = (turn(&mut uniform, 3.0), turn(&mut uniform, 3.0));
            let centre_a = Point3::origin();
            let centre_b = Point3::from(
                direction(&mut uniform).into_inner()
                    * (reach_a + reach_b)
                    * (0.5 + 0.7 * uniform()),
            );
            let Err(Some(gap)) = contact_normal(
                &a,
                &pose(&centre_a, &turn_a),
                &b,
                &pose(&centre_b, &turn_b),
                margin,
                None,
            ) else {
                continue;
            };
            found += 1;
            let apart = Apart {
                gap,
                poses: [(centre_a, turn_a), (centre_b, turn_b)],
            };
            let mut moved = |centre: Point3<f64>, turned: UnitQuaternion<f64>, reach: f64| {
                let shift = direction(&mut uniform).into_inner() * gap.separation * 0.5 * uniform();
                // A third of the bodies only move, so that each term of the bound is needed.
                let most = if uniform() < 1.0 / 3.0 { 0.0 } else { 0.1 };
                Placement {
                    pose: (centre + shift, turn(&mut uniform, most) * turned),
                    size: reach,
                    reach,
                    travel: Travel::default(),
                    round: false,
                    thickness: f64::INFINITY,
                }
            };
            let (now_a, now_b) = (
                moved(centre_a, turn_a, reach_a),
                moved(centre_b, turn_b, reach_b),
            );
            if apart.still_apart(&now_a, &now_b, margin) {
                kept += 1;
                if gap.frame == AxisFrame::Space {
                    kept_along_edges += 1;
                }
                let (pose_a, pose_b) = (
                    pose(&now_a.pose.0, &now_a.pose.1),
                    pose(&now_b.pose.0, &now_b.pose.1),
                );
                let distance = sharp_distance(&a, &pose_a, &b, &pose_b);
                assert!(
                    distance > margin,
                    "case {case}: kept apart {distance} m apart"
                );
                if !(a.is_rounded() || b.is_rounded()) {
                    let normal = contact_normal(&a, &pose_a, &b, &pose_b, margin, None);
                    assert!(normal.is_err(), "case {case}: kept apart, but touching");
                }
            }
        }
        assert!(found > 10_000, "only {found} pairs found apart");
        assert!(kept > found / 10, "the bound kept {kept} of {found} apart");
        assert!(
            kept_along_edges > 10,
            "{kept_along_edges} kept along edge axes"
        );
    }

    /// A cube hovering 10 cm above a 20 m slab, turned 45° about two axes: the slab's face
    /// shows them apart, whichever is given first, as a box and as a hull. Turning the cube
    /// by 0.05 rad about its centre cannot close the gap (its corners move by under 5 cm), and
    /// the bound says so, as it can only when the face is known to be the slab's: were it the
    /// cube's, the slab's far corners would swing past it.
    #[test]
    fn a_turning_cube_above_a_slab_stays_apart() {
        let corners = |half: Vector3<f64>| {
            (0..8)
                .map(|i: u8| {
                    let s = |bit: u8| if i & bit == 0 { -1.0 } else { 1.0 };
                    Point3::new(s(1) * half.x, s(2) * half.y, s(4) * half.z)
                })
                .collect()
        };
        let (slab_half, cube_half) = (Vector3::new(10.0, 10.0, 0.5), Vector3::repeat(0.5));
        let tilt = UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_4, 0.6, 0.0);
        // How far the tilted cube reaches below its centre.
        let lowest: f64 = (0..3)
            .map(|i| cube_half[i] * (tilt * Vector3::ith(i, 1.0)).z.abs())
            .sum();
        let slab_at = (Point3::new(0.0, 0.0, -0.5), UnitQuaternion::identity());
        let cube_at = (Point3::new(1.0, 2.0, lowest + 0.1), tilt);
        let margin = 0.01;
        let placed = |(centre, turn): Pose, reach: f64| Placement {
            pose: (centre, turn),
            size: reach,
            reach,
            travel: Travel::default(),
            round: false,
            thickness: f64::INFINITY,
        };
        let turned = (
            cube_at.0,
            UnitQuaternion::from_euler_angles(0.05, 0.0, 0.0) * cube_at.1,
        );
        for shapes in [
            (
                Shape::cuboid([20.0, 20.0, 1.0]),
                Shape::cuboid([1.0, 1.0, 1.0]),
            ),
            (
                Shape::Convex {
                    points: corners(slab_half),
                },
                Shape::Convex {
                    points: corners(cube_half),
                },
            ),
        ] {
            let (slab, cube) = (
                Collider::new(&shapes.0).expect("a slab"),
                Collider::new(&shapes.1).expect("a cube"),
            );
            let slab_now = (&slab, slab_at, slab_at, slab_half.norm());
            let cube_now = (&cube, cube_at, turned, cube_half.norm());
            // The slab first, then the cube first.
            for (slab_first, [first, second]) in
                [(true, [slab_now, cube_now]), (false, [cube_now, slab_now])]
            {
                let Err(Some(gap)) = contact_normal(
                    first.0,
                    &pose(&first.1.0, &first.1.1),
                    second.0,
                    &pose(&second.1.0, &second.1.1),
                    margin,
                    None,
                ) else {
                    panic!("apart along a face normal");
                };
                assert_eq!(
                    gap.frame,
                    AxisFrame::of_first(slab_first),
                    "the slab's face"
                );
                assert!((gap.separation - 0.1).abs() < 1e-9, "{}", gap.separation);
                let apart = Apart {
                    gap,
                    poses: [first.1, second.1],
                };
                assert!(apart.still_apart(
                    &placed(first.2, first.3),
                    &placed(second.2, second.3),
                    margin
                ));
            }
        }
    }

    /// The turn bound is above the exact angle, and within π/2 of it (`θ ≤ π sin(θ/2)`).
    #[test]
    fn the_turn_bound_is_above_the_angle() {
        let mut uniform = uniform_from(5);
        for _ in 0..10_000 {
            let was = turn(&mut uniform, 3.0);
            let angle = std::f64::consts::PI * uniform().powi(4);
            let now = UnitQuaternion::from_axis_angle(&direction(&mut uniform), angle) * was;
            let bound = turn_bound(&now, &was);
            let exact = now.angle_to(&was);
            assert!(bound >= exact * (1.0 - 1e-12), "{bound} below {exact}");
            assert!(bound <= exact * std::f64::consts::FRAC_PI_2 + 1e-12);
        }
    }
}
