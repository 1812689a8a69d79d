//! The face model's impulse carried from one step to the next ([`ContactImpulse`]): read back
//! into the same block it is the same impulses; written into the block of a changed contact
//! (turned frame, moved body, the support now a face, a segment or a point) it keeps the whole
//! linear impulse, and the angular impulse up to what the new block cannot carry — nothing
//! for a face, the tilt about a segment's own line, everything but the forces' moment for a
//! point.

use nalgebra::{Point2, Point3, Rotation3, Vector3};
use proptest::prelude::*;
use tatami_contact::{
    Contact, ContactFrame, ContactImpulse, ContactModel, ContactProjection, ContactSettings,
    Material,
};
use tatami_geometry::{ConvexPolygon, PolygonKind};
use tatami_lcp::{BodyId, Problem, SolverBody};

/// A contact over `support` in a frame turned by `turn`, A's centre of mass at `centre_a`.
fn contact(support: ConvexPolygon, turn: Rotation3<f64>, centre_a: Point3<f64>) -> Contact {
    let count = support.vertices().len();
    Contact {
        body_a: BodyId(0),
        body_b: BodyId(1),
        centre_a,
        centre_b: Point3::new(0.2, -0.4, -1.0),
        frame: ContactFrame {
            origin: Point3::new(0.3, -0.2, 0.1),
            tangent1: turn * Vector3::x(),
            tangent2: turn * Vector3::y(),
            normal: turn * Vector3::z(),
        },
        support,
        depths: vec![0.0; count],
        material: Material::new(0.5, 0.5, 0.0).unwrap(),
        landing: Vec::new(),
        bounce_speed: 0.0,
    }
}

/// The face model's rows of `contact`.
fn face_rows(contact: &Contact) -> Problem<ContactProjection> {
    let mut problem = Problem {
        bodies: vec![SolverBody::fixed(); 2],
        ..Default::default()
    };
    ContactModel::Face
        .build(contact, 0.01, &ContactSettings::default(), &mut problem)
        .unwrap();
    problem
}

/// The convex hull of `points`; `None` when it is not of `kind` or is nearly degenerate.
fn support(points: &[(f64, f64)], kind: PolygonKind) -> Option<ConvexPolygon> {
    let points: Vec<Point2<f64>> = points.iter().map(|&(x, y)| Point2::new(x, y)).collect();
    let polygon = ConvexPolygon::from_points(&points).ok()?;
    let big_enough = match kind {
        PolygonKind::Polygon => polygon.area() >= 0.05,
        PolygonKind::Segment => match polygon.vertices() {
            [a, b] => (b - a).norm() >= 0.2,
            _ => false,
        },
        PolygonKind::Point => true,
    };
    (polygon.kind() == kind && big_enough).then_some(polygon)
}

/// A vector of components in `-r..r`.
fn v3(r: f64) -> impl Strategy<Value = Vector3<f64>> {
    [-r..r, -r..r, -r..r].prop_map(Vector3::from)
}

const KINDS: [PolygonKind; 3] = [
    PolygonKind::Polygon,
    PolygonKind::Segment,
    PolygonKind::Point,
];

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xca77),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Any impulses of any face-model block, carried as the impulse on A and written back
    /// into the same block, are the same impulses: the block's force axes and its torque axes
    /// are orthonormal, so nothing is lost or mixed.
    #[test]
    fn a_block_reads_back_its_own_impulses(
        points in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 1..9),
        kind in 0..3usize,
        turn in v3(3.0),
        centre_a in v3(2.0),
        impulses in prop::collection::vec(-1.0..1.0f64, 6),
    ) {
        let Some(support) = support(&points[..points.len().min([9, 2, 1][kind])], KINDS[kind])
        else {
            return Ok(());
        };
        let contact = contact(support, Rotation3::from_scaled_axis(turn), centre_a.into());
        let mut problem = face_rows(&contact);
        for (row, &impulse) in problem.rows.iter_mut().zip(&impulses) {
            row.impulse = impulse;
        }
        let carried = ContactImpulse::of_rows(&problem.rows, contact.centre_a);
        let mut again = face_rows(&contact);
        carried.write_face_rows(&mut again.rows, &contact.centre_a);
        for (k, (was, now)) in problem.rows.iter().zip(&again.rows).enumerate() {
            // Rounding only: a few operations on numbers below 10.
            prop_assert!((was.impulse - now.impulse).abs() < 1e-13, "row {k}: {} vs {}", was.impulse, now.impulse);
        }
    }

    /// A face's impulse written into the block of the same pair a step on — frame turned, A's
    /// centre of mass moved, the support a face, a segment or a point — applies the same
    /// linear impulse, and the same angular impulse but for what the block cannot carry.
    #[test]
    fn a_changed_block_takes_what_it_can_carry(
        points in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 3..9),
        next_points in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 1..9),
        next_kind in 0..3usize,
        turn in v3(3.0),
        next_turn in v3(0.2),
        centre_a in v3(2.0),
        moved in v3(0.1),
        impulses in prop::collection::vec(-1.0..1.0f64, 6),
    ) {
        let Some(face) = support(&points, PolygonKind::Polygon) else {
            return Ok(());
        };
        let next_count = next_points.len().min([9, 2, 1][next_kind]);
        let Some(next_support) = support(&next_points[..next_count], KINDS[next_kind]) else {
            return Ok(());
        };
        let turn = Rotation3::from_scaled_axis(turn);
        let was = contact(face, turn, centre_a.into());
        let mut problem = face_rows(&was);
        for (row, &impulse) in problem.rows.iter_mut().zip(&impulses) {
            row.impulse = impulse;
        }
        let carried = ContactImpulse::of_rows(&problem.rows, was.centre_a);
        let next = contact(
            next_support,
            Rotation3::from_scaled_axis(next_turn) * turn,
            was.centre_a + moved,
        );
        let mut next_problem = face_rows(&next);
        carried.write_face_rows(&mut next_problem.rows, &next.centre_a);
        let applied = ContactImpulse::of_rows(&next_problem.rows, next.centre_a);
        // Rounding only, as above: impulses below 3 and lever arms below 4 m give products
        // below 20, whose last bits are ~4e-15; a dropped or misread row is off by ~0.1.
        prop_assert!((applied.linear - carried.linear).norm() < 1e-13);
        // The carried angular impulse about A's new centre of mass, and what is left of it.
        let angular = carried.angular + (carried.centre_a - next.centre_a).cross(&carried.linear);
        let lost = applied.angular - angular;
        match next.support.kind() {
            PolygonKind::Polygon => prop_assert!(lost.norm() < 1e-13, "lost {lost}"),
            PolygonKind::Segment => {
                let [a, b] = next.support.vertices() else { unreachable!() };
                let along = (next.frame.tangent1 * (b - a).x + next.frame.tangent2 * (b - a).y)
                    .normalize();
                prop_assert!(lost.cross(&along).norm() < 1e-13, "lost {lost}, along {along}");
            }
            // A point carries the moment of its forces only.
            PolygonKind::Point => {
                let p = next.frame.to_world(&next.support.vertices()[0]);
                let moment = (p - next.centre_a).cross(&carried.linear);
                prop_assert!((applied.angular - moment).norm() < 1e-13);
            }
        }
    }
}
