//! PGS ends a block's update once its normal rows leave it unloaded
//! ([`Projection::leading_normal_rows`]): the answer must be the same, bit for bit, as updating
//! every row (to the sign of a zero), on random chains of boxes whose contacts part, close and
//! slide.

use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
use tatami_lcp::{Block, BodyId, Jacobian, Problem, Projection, Row, RowBound, SolverBody};

/// A point contact's friction cone with box bounds, `|fₜ| ≤ μ fₙ`: normal row first. `promise`
/// says whether it reports its normal row, which lets PGS skip the friction rows while it is
/// unloaded.
#[derive(Debug, Clone, Copy)]
struct Cone {
    mu: f64,
    promise: bool,
}

impl Projection for Cone {
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        impulses[0] = impulses[0].max(0.0);
        let limit = self.mu * impulses[0];
        for f in &mut impulses[1..] {
            *f = f.max(-limit).min(limit);
        }
    }

    fn leading_normal_rows(&self) -> usize {
        usize::from(self.promise)
    }

    fn bound(&self, row: usize) -> Option<RowBound> {
        Some(if row == 0 {
            RowBound::NonNegative
        } else {
            RowBound::Friction {
                normal: 0,
                coefficient: self.mu,
            }
        })
    }
}

/// One contact of the chain: the lever arms from both bodies' centres, the normal's tilt, the
/// target speed of the normal row (positive: the contact is parting) and μ.
#[derive(Debug, Clone)]
struct Contact {
    arm_a: [f64; 3],
    arm_b: [f64; 3],
    tilt: [f64; 2],
    target: f64,
    mu: f64,
}

fn contact() -> impl Strategy<Value = Contact> {
    (
        prop::array::uniform3(-1.0..1.0f64),
        prop::array::uniform3(-1.0..1.0f64),
        prop::array::uniform2(-0.3..0.3f64),
        -1.0..1.0f64,
        0.0..1.0f64,
    )
        .prop_map(|(arm_a, arm_b, tilt, target, mu)| Contact {
            arm_a,
            arm_b,
            tilt,
            target,
            mu,
        })
}

/// A chain of bodies on a fixed body 0 (body `k` on body `k − 1`), with random velocities and
/// masses; one 3-row block per contact.
fn chain(
    contacts: &[Contact],
    velocities: &[[f64; 3]],
    masses: &[f64],
    promise: bool,
) -> Problem<Cone> {
    let mut problem = Problem {
        bodies: vec![SolverBody::fixed()],
        ..Problem::default()
    };
    for (v, &m) in velocities.iter().zip(masses) {
        problem.bodies.push(SolverBody {
            inv_mass: 1.0 / m,
            inv_inertia_world: Matrix3::identity() * 6.0 / m,
            linear_velocity: Vector3::from(*v),
            angular_velocity: Vector3::from(*v).yzx() * 0.5,
        });
    }
    for (k, c) in contacts.iter().enumerate() {
        let normal = Vector3::new(c.tilt[0], c.tilt[1], 1.0).normalize();
        let tangent1 = normal.cross(&Vector3::y()).normalize();
        let tangent2 = normal.cross(&tangent1);
        let (arm_a, arm_b) = (Vector3::from(c.arm_a), Vector3::from(c.arm_b));
        let start = problem.rows.len();
        for (direction, target) in [(normal, c.target), (tangent1, 0.0), (tangent2, 0.0)] {
            problem.rows.push(Row {
                jacobian: Jacobian {
                    linear_a: direction,
                    angular_a: arm_a.cross(&direction),
                    linear_b: -direction,
                    angular_b: -arm_b.cross(&direction),
                },
                target,
                impulse: 0.0,
            });
        }
        problem.blocks.push(Block {
            body_a: BodyId(k + 1),
            body_b: BodyId(k),
            rows: start..start + 3,
            projection: Cone { mu: c.mu, promise },
        });
    }
    problem
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/unloaded_blocks.txt",
        ))),
        ..ProptestConfig::default()
    })]

    #[test]
    fn skipping_unloaded_rows_changes_nothing(
        (contacts, velocities, masses) in (1usize..12).prop_flat_map(|n| (
            prop::collection::vec(contact(), n),
            prop::collection::vec(prop::array::uniform3(-2.0..2.0f64), n),
            prop::collection::vec(0.1..10.0f64, n),
        )),
        sweeps in 1usize..20,
    ) {
        let params = PgsParams { iterations: sweeps, ..PgsParams::default() };
        let mut every_row = chain(&contacts, &velocities, &masses, false);
        let mut skipping = chain(&contacts, &velocities, &masses, true);
        pgs::solve_in_place(&mut every_row, &mut PgsWorkspace::default(), &params).unwrap();
        pgs::solve_in_place(&mut skipping, &mut PgsWorkspace::default(), &params).unwrap();
        // Some contacts must have parted for the test to mean anything; most draws have one.
        let unloaded = every_row.rows.iter().step_by(3).filter(|r| r.impulse == 0.0).count();
        prop_assume!(unloaded > 0);
        for (a, b) in every_row.rows.iter().zip(&skipping.rows) {
            prop_assert_eq!(a.impulse, b.impulse);
        }
        for (a, b) in every_row.bodies.iter().zip(&skipping.bodies) {
            prop_assert_eq!(a.linear_velocity, b.linear_velocity);
            prop_assert_eq!(a.angular_velocity, b.angular_velocity);
        }
    }
}
