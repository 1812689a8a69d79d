//! A friction pair and a twist row on one limit surface ([`Projection::twist_coupling`]): PGS's
//! 3-D step must converge to the wrench of most dissipation on that surface — antiparallel, in
//! the ball's units `u = (f₁, f₂, τ′/r̄)`, to the slip `g = (v_p, r̄ ω)` it leaves at the point
//! `p` where the force acts — and, where the budget suffices, to sticking.

use nalgebra::{Matrix3, Vector3};
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
use tatami_lcp::{
    Block, BodyId, Jacobian, Problem, Projection, Row, RowBound, SolverBody, TwistCoupling,
};

/// The radius `r̄` (m) of the test's limit surface.
const RADIUS: f64 = 0.05;
/// Where the friction force acts, relative to the rows' point (m), off it in both axes.
const CENTRE: [f64; 2] = [0.02, -0.01];

/// The ball `|(f₁, f₂, (τ − (p × f)·n)/r̄)| ≤ limit`, a fixed budget (N·s).
struct Ball {
    limit: f64,
}

impl Ball {
    /// The wrench in the ball's units.
    fn units(impulses: &[f64]) -> Vector3<f64> {
        let [px, py] = CENTRE;
        let (f1, f2, twist) = (impulses[0], impulses[1], impulses[2]);
        Vector3::new(f1, f2, (twist - (px * f2 - py * f1)) / RADIUS)
    }
}

impl Projection for Ball {
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        let norm = Self::units(impulses).norm();
        if norm > self.limit {
            for impulse in impulses.iter_mut() {
                *impulse *= self.limit / norm;
            }
        }
    }

    fn tangent_pair(&self) -> Option<usize> {
        Some(0)
    }

    fn twist_coupling(&self, _impulses: &[f64]) -> Option<TwistCoupling> {
        Some(TwistCoupling {
            row: 2,
            radius: RADIUS,
            centre: CENTRE,
        })
    }

    fn bound(&self, _row: usize) -> Option<RowBound> {
        None
    }
}

/// A row of body A's motion against the fixed ground: linear along `linear`, angular along
/// `angular`.
fn row(linear: Vector3<f64>, angular: Vector3<f64>) -> Row {
    Row {
        jacobian: Jacobian {
            linear_a: linear,
            angular_a: angular,
            linear_b: -linear,
            angular_b: -angular,
        },
        target: 0.0,
        impulse: 0.0,
    }
}

/// A 1 kg plate sliding at 1 m/s off the axes and spinning at 20 rad/s, its rows at the point
/// 1 cm under its centre: friction along x and y there, twist about z.
fn sliding_plate(limit: f64) -> Problem<Ball> {
    let r = Vector3::new(0.0, 0.0, -0.01);
    let plate = SolverBody {
        inv_mass: 1.0,
        inv_inertia_world: Matrix3::from_diagonal(&Vector3::new(
            1.0 / 8e-4,
            1.0 / 8e-4,
            1.0 / 1.6e-3,
        )),
        linear_velocity: Vector3::new(0.6, 0.8, 0.0),
        angular_velocity: Vector3::new(0.0, 0.0, 20.0),
    };
    Problem {
        bodies: vec![SolverBody::fixed(), plate],
        rows: vec![
            row(Vector3::x(), r.cross(&Vector3::x())),
            row(Vector3::y(), r.cross(&Vector3::y())),
            row(Vector3::zeros(), Vector3::z()),
        ],
        blocks: vec![Block {
            body_a: BodyId(1),
            body_b: BodyId(0),
            rows: 0..3,
            projection: Ball { limit },
        }],
    }
}

/// Solves with 200 sweeps, far past convergence, and returns the wrench in the ball's units
/// and the slip `g` left, also in them.
fn solve(problem: &mut Problem<Ball>) -> (Vector3<f64>, Vector3<f64>) {
    let params = PgsParams {
        iterations: 200,
        ..PgsParams::default()
    };
    pgs::solve_in_place(problem, &mut PgsWorkspace::default(), &params).unwrap();
    let impulses: Vec<f64> = problem.rows.iter().map(|r| r.impulse).collect();
    let (ground, plate) = (&problem.bodies[0], &problem.bodies[1]);
    let e: Vec<f64> = problem
        .rows
        .iter()
        .map(|r| r.jacobian.velocity(plate, ground))
        .collect();
    let [px, py] = CENTRE;
    let slip = Vector3::new(e[0] - py * e[2], e[1] + px * e[2], RADIUS * e[2]);
    (Ball::units(&impulses), slip)
}

/// A budget a tenth of what stopping takes: the wrench is on the ball's rim, antiparallel to
/// the slip it leaves, to rounding (1e-12 of unit vectors after 200 sweeps).
#[test]
fn a_slipping_face_takes_the_wrench_of_most_dissipation() {
    let mut problem = sliding_plate(0.1);
    let (wrench, slip) = solve(&mut problem);
    assert!((wrench.norm() - 0.1).abs() < 1e-12, "{wrench}");
    let along = wrench.normalize() + slip.normalize();
    assert!(along.norm() < 1e-12, "wrench {wrench} against slip {slip}");
    // Both the slide and the spin are still slowed: neither part of the budget is zero.
    assert!(
        wrench.xy().norm() > 0.01 && wrench.z.abs() > 0.01,
        "{wrench}"
    );
}

/// A budget ten times what stopping takes: the plate sticks (no slip left, to 1e-12 m/s) with
/// the wrench inside the ball.
#[test]
fn a_face_with_budget_to_spare_sticks() {
    let mut problem = sliding_plate(10.0);
    let (wrench, slip) = solve(&mut problem);
    assert!(slip.norm() < 1e-12, "{slip}");
    assert!(wrench.norm() < 10.0, "{wrench}");
}
