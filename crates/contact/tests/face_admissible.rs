//! `FaceProjection::admissible` against the projection itself: a face wrench is admissible
//! exactly when projecting it changes nothing. PGS keeps a whole-block step only when
//! `admissible` says so, so a wrench it wrongly accepts would leave the face's set, and one it
//! wrongly rejects (the zero wrench of an unloaded face, say) sends the face to the slower
//! row-by-row update for the rest of the solve. Both friction limits: the force and the twist
//! bounded apart, or on one ellipsoid.

use nalgebra::Point2;
use proptest::prelude::*;
use tatami_contact::face::FaceProjection;
use tatami_contact::{FrictionCone, FrictionLimit, TwistCentre};
use tatami_geometry::{ConvexPolygon, Sector};
use tatami_lcp::Projection;

/// A face projection on the polygon of `points` about its centroid.
fn face(
    points: &[(f64, f64)],
    cone: FrictionCone,
    clearance: bool,
    twist_centre: TwistCentre,
    friction_limit: FrictionLimit,
) -> Option<FaceProjection> {
    let points: Vec<Point2<f64>> = points.iter().map(|&(x, y)| Point2::new(x, y)).collect();
    let support = ConvexPolygon::from_points(&points).ok()?;
    if support.area() < 0.05 {
        return None;
    }
    let centre = support.centroid();
    Some(FaceProjection {
        clearance: if clearance {
            support.clearance(&centre)
        } else {
            0.0
        },
        support,
        centre,
        friction: 0.5,
        twist_per_normal: 0.2,
        cone,
        remove_parallel_torque: false,
        twist_centre,
        friction_limit,
        hint: Sector(0),
    })
}

/// A wrench drawn so that every constraint is met or broken with fair odds: an unloaded face
/// (all zero, or zero normal impulse with something else), a pull, or a push whose friction,
/// twist and centre of pressure are scaled around their bounds — the twist about `G`, or
/// about the centre of pressure `(x, y)` (offset by the friction's moment there,
/// `x f2 − y f1`).
fn wrench() -> impl Strategy<Value = [f64; 6]> {
    (
        0..6u8,
        0.01..10.0f64,
        (0.0..1.5f64, -3.2..3.2f64),
        -1.5..1.5f64,
        (-1.5..1.5f64, -1.5..1.5f64),
    )
        .prop_map(|(kind, f3, (slip, heading), twist, (x, y))| match kind {
            0 => [0.0; 6],
            1 => [0.0, 0.0, 0.0, 0.0, 0.0, twist],
            2 => [-f3, 0.0, 0.0, 0.0, 0.0, 0.0],
            _ => {
                let (f1, f2) = (
                    0.5 * f3 * slip * heading.cos(),
                    0.5 * f3 * slip * heading.sin(),
                );
                let moment = if kind == 3 { 0.0 } else { x * f2 - y * f1 };
                [f3, f1, f2, y * f3, -x * f3, moment + 0.2 * f3 * twist]
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 2000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xad1),
        ..ProptestConfig::default()
    })]

    #[test]
    fn admissible_exactly_when_the_projection_changes_nothing(
        points in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 3..9),
        circular in any::<bool>(),
        clearance in any::<bool>(),
        about_pressure in any::<bool>(),
        coupled in any::<bool>(),
        wrench in wrench(),
    ) {
        let cone = if circular { FrictionCone::Circle } else { FrictionCone::Box };
        let twist_centre =
            if about_pressure { TwistCentre::CentreOfPressure } else { TwistCentre::Centroid };
        let limit = if coupled { FrictionLimit::Coupled } else { FrictionLimit::Separate };
        let Some(mut face) = face(&points, cone, clearance, twist_centre, limit) else {
            return Ok(());
        };
        let mut projected = wrench;
        // Row 0 (the normal) changed: every constraint is applied, the centre of pressure too.
        face.project(&mut projected, 0);
        prop_assert_eq!(face.admissible(&wrench), projected == wrench,
            "wrench {:?} projected to {:?}", wrench, projected);
    }
}

/// The zero wrench of an unloaded face is admissible; anything else without a normal impulse
/// is not.
#[test]
fn an_unloaded_face_admits_only_the_zero_wrench() {
    let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut face = face(
        &square,
        FrictionCone::Circle,
        true,
        TwistCentre::CentreOfPressure,
        FrictionLimit::Coupled,
    )
    .expect("a square face");
    assert!(face.admissible(&[0.0; 6]));
    for row in 1..6 {
        let mut wrench = [0.0; 6];
        wrench[row] = 1e-3;
        assert!(!face.admissible(&wrench), "row {row} loaded alone");
    }
}
