//! A contact carried with its bodies. While two bodies slide and turn against each other by
//! less than the [`CarryBounds`] since their contact was computed, the contact moves with them
//! and only its depths are measured again, instead of being found afresh: late in a settling
//! pile most bodies creep by tens of micrometres a step, past the reuse tolerance of
//! [`crate::contact_set`], while their contacts barely change (rapier keeps its contact points
//! the same way, up to 1 mm of slip and 1° of turn).
//!
//! The support polygon moves with body B: its vertices stay the points of B they were, and
//! each depth changes by how far the point of A that was there has moved along the normal,
//! away (shallower) or in (deeper). The slip and turn are summed over the steps the contact is
//! carried, so it is never further than the bounds from the contact computed at its poses.
//!
//! A ball's or a cylinder's contact at a point or along its side is not carried
//! ([`crate::contact_set`]): it runs over the curved surface as the body rolls, and moved with
//! the body its normal tilted with the turn and pushed the body on.

use nalgebra::Point2;
use tatami_contact::Contact;

use crate::contact_set::Pose;
use crate::support::{CAP_VERTICES, LANDING_POINTS_PER_SIDE};

/// Most slip of the bodies' surfaces against each other across a carried contact, as a
/// fraction of the slop: 0.1 mm at the default 2 mm, far below the depths the solver tells
/// apart. Measured on the piles (`benches/HISTORY.md`): 0.5 mm (and 0.3°) let the cube pile's
/// last cubes creep on.
const SLIP_PER_SLOP: f64 = 0.05;

/// Most turn of the bodies against each other, as a fraction of the feature angle (0.1° at the
/// default 1°), which decides whether a tilted face is kept whole.
const TURN_PER_FEATURE_ANGLE: f64 = 0.1;

/// How far contacts are carried, from the world's settings: with a slop or a feature angle of
/// zero only a pair that neither slid nor turned (moved only along the normal, where the
/// carried contact is exact) is carried.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CarryBounds {
    /// Most slip (m) since the contact was computed.
    pub slip: f64,
    /// Most turn (rad) since the contact was computed.
    pub turn: f64,
    /// A contact open wider than this everywhere (m) is found afresh: collision would find
    /// the pair apart.
    margin: f64,
}

impl CarryBounds {
    pub(crate) fn new(slop: f64, feature_angle: f64, margin: f64) -> Self {
        Self {
            slip: SLIP_PER_SLOP * slop,
            turn: TURN_PER_FEATURE_ANGLE * feature_angle,
            margin,
        }
    }
}

/// How far a carried contact has moved from the one computed: summed slip and turn.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Drift {
    slip: f64,
    turn: f64,
}

/// Moves `contact`, placed for its bodies at `was`, with them to `now`, adding to `drift`;
/// `false`, leaving both as they were, when the drift would pass the `bounds`, a depth would
/// change sign (the polygon's shape may then change), or the contact would open wider than the
/// margin everywhere.
pub(crate) fn carry(
    contact: &mut Contact,
    drift: &mut Drift,
    was: &[Pose; 2],
    now: &[Pose; 2],
    bounds: &CarryBounds,
) -> bool {
    let ([(ca, qa), (cb, qb)], [(na, ra), (nb, rb)]) = (was, now);
    let turn = (qa.inverse() * qb).angle_to(&(ra.inverse() * rb));
    if drift.turn + turn > bounds.turn {
        return false;
    }
    // As matrices: each moves every vertex, at half a quaternion's cost a vector.
    let (move_a, move_b) = (
        (ra * qa.inverse()).to_rotation_matrix(),
        (rb * qb.inverse()).to_rotation_matrix(),
    );
    let frame = contact.frame;
    let normal = move_b * frame.normal;
    let mut slip: f64 = 0.0;
    // A support polygon has at most a cylinder cap's vertices; one with more is found afresh.
    let mut depths = [0.0; CAP_VERTICES];
    let vertices = contact.support.vertices();
    let n = vertices.len();
    if n > depths.len() {
        return false;
    }
    // How far the points of A and B at `v` (plane coordinates) moved apart: along the normal,
    // and across it.
    let apart_at = |v: &Point2<f64>| {
        let p = frame.to_world(v);
        let of_a = move_a * (p - ca) + na.coords;
        let of_b = move_b * (p - cb) + nb.coords;
        let apart = of_a - of_b;
        let along = apart.dot(&normal);
        (along, (apart - normal * along).norm())
    };
    for ((v, &depth), new) in vertices.iter().zip(&contact.depths).zip(&mut depths) {
        let (along, across) = apart_at(v);
        slip = slip.max(across);
        *new = depth - along;
        if (*new > 0.0) != (depth > 0.0) {
            return false;
        }
    }
    // Landing points (at most a few each side of a rim point) move the same way, and stay gaps.
    let mut landing = [0.0; 2 * LANDING_POINTS_PER_SIDE];
    if contact.landing.len() > landing.len() {
        return false;
    }
    for (point, new) in contact.landing.iter().zip(&mut landing) {
        *new = point.depth - apart_at(&point.point).0;
        if *new > 0.0 {
            return false;
        }
    }
    let deepest = depths[..n]
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    if drift.slip + slip > bounds.slip || deepest < -bounds.margin {
        return false;
    }
    drift.slip += slip;
    drift.turn += turn;
    contact.frame.origin = nb + move_b * (frame.origin - cb);
    contact.frame.tangent1 = move_b * frame.tangent1;
    contact.frame.tangent2 = move_b * frame.tangent2;
    contact.frame.normal = normal;
    contact.depths.copy_from_slice(&depths[..n]);
    for (point, &depth) in contact.landing.iter_mut().zip(&landing) {
        point.depth = depth;
    }
    contact.centre_a = *na;
    contact.centre_b = *nb;
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point2, Point3, UnitQuaternion, Vector3};
    use tatami_contact::{ContactFrame, Material};
    use tatami_geometry::ConvexPolygon;
    use tatami_lcp::BodyId;

    /// The default slop and feature angle (0.1 mm and 0.1° of slip and turn) and a 1 cm
    /// margin.
    fn bounds() -> CarryBounds {
        CarryBounds::new(0.002, 1f64.to_radians(), 0.01)
    }

    /// A 1 m face of A (centre 0.5 m up) on B (centre 0.5 m down), pressed in 1 mm at two
    /// corners and 0.5 mm at the others, its normal turned off the axes.
    fn resting() -> (Contact, [Pose; 2]) {
        let turn = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.7);
        let normal = turn * Vector3::z();
        let was = [
            (Point3::from(turn * Vector3::new(0.0, 0.0, 0.5)), turn),
            (Point3::from(turn * Vector3::new(0.0, 0.0, -0.5)), turn),
        ];
        let square = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)];
        let contact = Contact {
            body_a: BodyId(0),
            body_b: BodyId(1),
            centre_a: was[0].0,
            centre_b: was[1].0,
            frame: ContactFrame::from_normal(Point3::origin(), normal).unwrap(),
            support: ConvexPolygon::from_points(&square.map(|(x, y)| Point2::new(x, y))).unwrap(),
            depths: vec![1e-3, 1e-3, 5e-4, 5e-4],
            material: Material::new(0.5, 0.5, 0.0).unwrap(),
            landing: Vec::new(),
            bounce_speed: 0.0,
        };
        (contact, was)
    }

    /// Both bodies moved and turned together: the same depths at the same points of B, the
    /// frame moved with them.
    #[test]
    fn a_contact_moved_with_both_bodies_keeps_its_depths() {
        let (mut contact, was) = resting();
        let (shift, spin) = (
            Vector3::new(0.3, -1.2, 0.05),
            UnitQuaternion::from_euler_angles(0.4, 0.1, -0.9),
        );
        let moved = |(c, q): Pose| (Point3::from(spin * c.coords + shift), spin * q);
        let now = [moved(was[0]), moved(was[1])];
        let before = contact.clone();
        assert!(carry(
            &mut contact,
            &mut Drift::default(),
            &was,
            &now,
            &bounds(),
        ));
        for (d, e) in contact.depths.iter().zip(&before.depths) {
            assert!((d - e).abs() < 1e-12, "{d} against {e}");
        }
        let point = |c: &Contact, v: &Point2<f64>| c.frame.to_world(v);
        for v in before.support.vertices() {
            let expected = spin * point(&before, v).coords + shift;
            assert!((point(&contact, v).coords - expected).norm() < 1e-12);
        }
        assert!((contact.frame.normal - spin * before.frame.normal).norm() < 1e-12);
        assert_eq!(contact.centre_a, now[0].0);
    }

    /// A lifted along the normal by 0.3 mm: every depth 0.3 mm less; by 0.7 mm the 0.5 mm
    /// corners would open, so the contact is left to be found afresh; slid 0.2 mm across it,
    /// past the slip bound, likewise; tilted by 0.2°, past the turn bound, likewise; lifted
    /// wider than the margin, likewise.
    #[test]
    fn a_lift_changes_the_depths_and_a_slide_or_a_turn_past_the_bounds_is_refused() {
        let (contact, was) = resting();
        let n = contact.frame.normal;
        let t = contact.frame.tangent1;
        let with_a = |c: Point3<f64>, q: UnitQuaternion<f64>| [(c, q), was[1]];
        let mut lifted = contact.clone();
        let now = with_a(was[0].0 + n * 3e-4, was[0].1);
        assert!(carry(
            &mut lifted,
            &mut Drift::default(),
            &was,
            &now,
            &bounds(),
        ));
        for (d, e) in lifted.depths.iter().zip(&contact.depths) {
            assert!((d - (e - 3e-4)).abs() < 1e-12, "{d} against {e} − 0.3 mm");
        }
        let tilt =
            UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(t), 0.2f64.to_radians());
        for now in [
            with_a(was[0].0 + n * 7e-4, was[0].1),
            with_a(was[0].0 + t * 2e-4, was[0].1),
            with_a(was[0].0, tilt * was[0].1),
        ] {
            let (mut moved, mut drift) = (contact.clone(), Drift::default());
            assert!(!carry(&mut moved, &mut drift, &was, &now, &bounds()));
            assert_eq!((moved, drift), (contact.clone(), Drift::default()));
        }
        // Standing 1–2 mm off (a speculative contact): lifted by 5 mm it is carried; by 1 cm
        // it opens wider than the 1 cm margin everywhere and is refused.
        let off = Contact {
            depths: vec![-1e-3, -1e-3, -2e-3, -2e-3],
            ..contact.clone()
        };
        let lift = |by: f64| with_a(was[0].0 + n * by, was[0].1);
        assert!(carry(
            &mut off.clone(),
            &mut Drift::default(),
            &was,
            &lift(5e-3),
            &bounds(),
        ));
        assert!(!carry(
            &mut off.clone(),
            &mut Drift::default(),
            &was,
            &lift(1e-2),
            &bounds(),
        ));
        // Slid 0.06 mm twice: the second passes the bound on the sum.
        let mut drift = Drift::default();
        let mut slid = contact.clone();
        let first = with_a(was[0].0 + t * 6e-5, was[0].1);
        assert!(carry(&mut slid, &mut drift, &was, &first, &bounds()));
        let second = with_a(was[0].0 + t * 1.2e-4, was[0].1);
        assert!(!carry(&mut slid, &mut drift, &first, &second, &bounds()));
    }

    /// Landing points move as the vertices do: A lifted 0.3 mm along the normal leaves each
    /// landing gap 0.3 mm wider; A pushed 0.6 mm in would close the 0.5 mm gap (the support
    /// vertices stay pressed in), and the contact is left to be found afresh.
    #[test]
    fn landing_gaps_move_with_the_bodies_and_do_not_close() {
        let (mut contact, was) = resting();
        contact.landing = [(0.8, 0.1, -5e-4), (-0.2, 0.9, -2e-3)]
            .map(|(x, y, depth)| tatami_contact::Landing {
                point: Point2::new(x, y),
                depth,
            })
            .to_vec();
        let n = contact.frame.normal;
        let with_a = |by: f64| [(was[0].0 + n * by, was[0].1), was[1]];
        let mut lifted = contact.clone();
        assert!(carry(
            &mut lifted,
            &mut Drift::default(),
            &was,
            &with_a(3e-4),
            &bounds(),
        ));
        for (l, m) in lifted.landing.iter().zip(&contact.landing) {
            assert_eq!(l.point, m.point);
            assert!((l.depth - (m.depth - 3e-4)).abs() < 1e-12);
        }
        let mut pressed = contact.clone();
        assert!(!carry(
            &mut pressed,
            &mut Drift::default(),
            &was,
            &with_a(-6e-4),
            &bounds(),
        ));
        assert_eq!(pressed, contact);
    }
}
