//! The sparse solvers on small contact problems: PGS against the dense form and the direct
//! solver, closed-form outcomes, warm starting, and errors naming the block.

use nalgebra::{DVector, Matrix3, Vector3};
use proptest::prelude::*;
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace, Record, WarmStart};
use tatami_lcp::{
    Block, BodyId, BoundsProjection, Jacobian, LcpError, Problem, Projection, Row, RowBound,
    SolverBody, dense, direct, pgs_dense,
};

const G: f64 = 9.8;
const DT: f64 = 0.01;

fn cube(mass: f64, side: f64, velocity: Vector3<f64>) -> SolverBody {
    let inertia = mass * side * side / 6.0;
    SolverBody {
        inv_mass: 1.0 / mass,
        inv_inertia_world: Matrix3::identity() / inertia,
        linear_velocity: velocity,
        angular_velocity: Vector3::zeros(),
    }
}

/// A row of the relative velocity of A (body 1, centre at the origin) against the fixed ground at
/// the point `r` (relative to A's centre) along `direction`.
fn point_row(r: Vector3<f64>, direction: Vector3<f64>) -> Row {
    Row {
        jacobian: Jacobian {
            linear_a: direction,
            angular_a: r.cross(&direction),
            linear_b: -direction,
            angular_b: Vector3::zeros(),
        },
        target: 0.0,
        impulse: 0.0,
    }
}

/// A 2 m, 1 kg cube on the ground after gravity's step, one 3-row block (normal, t₁, t₂) per
/// bottom corner: the vertex model's problem.
fn cube_on_ground(velocity: Vector3<f64>, mu: f64) -> Problem<BoundsProjection> {
    let mut problem = Problem {
        bodies: vec![SolverBody::fixed(), cube(1.0, 2.0, velocity)],
        ..Problem::default()
    };
    for (x, y) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
        let r = Vector3::new(x, y, -1.0);
        let start = problem.rows.len();
        problem.rows.push(point_row(r, Vector3::z()));
        problem.rows.push(point_row(r, Vector3::x()));
        problem.rows.push(point_row(r, Vector3::y()));
        let friction = RowBound::Friction {
            normal: 0,
            coefficient: mu,
        };
        problem.blocks.push(Block {
            body_a: BodyId(1),
            body_b: BodyId(0),
            rows: start..start + 3,
            projection: BoundsProjection(vec![RowBound::NonNegative, friction, friction]),
        });
    }
    problem
}

/// Solves exactly, or by PGS run long enough (200 sweeps) to have converged.
fn solve_with(solver: &str, problem: &mut Problem<BoundsProjection>) {
    match solver {
        "direct" => {
            direct::solve(problem, &direct::DirectParams::default()).unwrap();
        }
        _ => {
            let params = PgsParams {
                iterations: 200,
                ..PgsParams::default()
            };
            pgs::solve_in_place(problem, &mut PgsWorkspace::default(), &params).unwrap();
        }
    }
}

fn normal_impulse_sum(problem: &Problem<BoundsProjection>) -> f64 {
    problem
        .blocks
        .iter()
        .map(|b| problem.rows[b.rows.start].impulse)
        .sum()
}

// Exact solves leave only rounding: 1e-12 of the 0.098 m/s gravity step.
const EXACT: f64 = 1e-12;

#[test]
fn resting_cube_is_stopped_by_exactly_its_weight() {
    for solver in ["direct", "pgs"] {
        let mut problem = cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5);
        solve_with(solver, &mut problem);
        let body = problem.bodies[1];
        assert!(
            body.linear_velocity.norm() < EXACT,
            "{solver}: {}",
            body.linear_velocity
        );
        assert!(
            body.angular_velocity.norm() < EXACT,
            "{solver}: {}",
            body.angular_velocity
        );
        assert!(
            (normal_impulse_sum(&problem) - G * DT).abs() < EXACT,
            "{solver}"
        );
    }
}

#[test]
fn sliding_cube_loses_mu_g_dt_of_speed() {
    // Kinetic friction saturates at every corner: Δv = −μ g Δt along the motion.
    let mu = 0.5;
    for solver in ["direct", "pgs"] {
        let mut problem = cube_on_ground(Vector3::new(1.0, 0.0, -G * DT), mu);
        solve_with(solver, &mut problem);
        let v = problem.bodies[1].linear_velocity;
        assert!((v.x - (1.0 - mu * G * DT)).abs() < 1e-9, "{solver}: {v}");
        assert!(v.y.abs() < 1e-9 && v.z.abs() < 1e-9, "{solver}: {v}");
    }
}

#[test]
fn pgs_error_against_direct_falls_with_iterations() {
    // Sliding diagonally while spinning: friction saturates at some corners, not others.
    let moving = || {
        let mut p = cube_on_ground(Vector3::new(0.3, -0.2, -G * DT), 0.8);
        p.bodies[1].angular_velocity = Vector3::new(0.1, 0.2, 0.5);
        p
    };
    let mut reference = moving();
    direct::solve(&mut reference, &direct::DirectParams::default()).unwrap();
    let reference = reference.bodies[1];
    let error = |iterations: usize| {
        let mut p = moving();
        let params = PgsParams {
            iterations,
            ..PgsParams::default()
        };
        pgs::solve_in_place(&mut p, &mut PgsWorkspace::default(), &params).unwrap();
        (p.bodies[1].linear_velocity - reference.linear_velocity).norm()
            + (p.bodies[1].angular_velocity - reference.angular_velocity).norm()
    };
    let errors: Vec<f64> = [1, 4, 15, 60, 500].iter().map(|&k| error(k)).collect();
    assert!(
        errors.windows(2).all(|w| w[1] <= w[0] + 1e-15),
        "{errors:?}"
    );
    assert!(errors[4] < 1e-9, "{errors:?}");
}

#[test]
fn recorded_impulse_change_shrinks_and_warm_start_reuses_impulses() {
    let mut problem = cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5);
    let mut workspace = PgsWorkspace::default();
    let params = PgsParams {
        iterations: 40,
        record: Record::ImpulseChange,
        ..PgsParams::default()
    };
    let info = pgs::solve_in_place(&mut problem, &mut workspace, &params).unwrap();
    assert_eq!(info.impulse_change.len(), 40);
    assert!(
        info.impulse_change[39] < 1e-3 * info.impulse_change[0],
        "{:?}",
        info.impulse_change
    );
    // Same problem again, warm-started from the converged impulses: nothing left to change.
    let impulses: Vec<f64> = problem.rows.iter().map(|r| r.impulse).collect();
    let mut again = cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5);
    for (row, impulse) in again.rows.iter_mut().zip(&impulses) {
        row.impulse = *impulse;
    }
    let warm = PgsParams {
        iterations: 1,
        warm_start: WarmStart::On,
        record: Record::ImpulseChange,
        ..params
    };
    let info = pgs::solve_in_place(&mut again, &mut workspace, &warm).unwrap();
    assert!(
        info.impulse_change[0] < 1e-6 * G * DT,
        "{:?}",
        info.impulse_change
    );
}

/// A solve with a `tolerance` stops at the first sweep that changes no row's velocity by more
/// than it, and lands where the full solve does. Off the axes: the cube slides diagonally and
/// spins, so every corner's rows are coupled.
#[test]
fn a_solve_with_a_tolerance_stops_early_near_the_converged_answer() {
    let sliding = || {
        let mut problem = cube_on_ground(Vector3::new(0.3, 0.2, -G * DT), 0.5);
        problem.bodies[1].angular_velocity = Vector3::new(0.1, -0.2, 0.4);
        problem
    };
    let mut workspace = PgsWorkspace::default();
    let mut converged = sliding();
    let full = PgsParams {
        iterations: 10_000,
        ..PgsParams::default()
    };
    let info = pgs::solve_in_place(&mut converged, &mut workspace, &full).unwrap();
    assert_eq!(info.sweeps, 10_000, "tolerance 0 runs every sweep");
    let tolerance = 1e-8;
    let mut early = sliding();
    let params = PgsParams { tolerance, ..full };
    let info = pgs::solve_in_place(&mut early, &mut workspace, &params).unwrap();
    assert!(info.sweeps < 1_000, "{} sweeps", info.sweeps);
    assert!(info.row_updates <= info.sweeps * early.rows.len());
    // PGS converges linearly, so once a sweep moves nothing by more than the tolerance the
    // remaining distance is the tolerance over (1 − rate); 100× allows a rate up to 0.99.
    let (a, b) = (&early.bodies[1], &converged.bodies[1]);
    let gap = (a.linear_velocity - b.linear_velocity)
        .norm()
        .max((a.angular_velocity - b.angular_velocity).norm());
    assert!(
        gap < 100.0 * tolerance,
        "{gap:e} m/s from the converged answer"
    );
    // Warm-started from the answer, one sweep finds nothing to do.
    let mut again = sliding();
    for (row, solved) in again.rows.iter_mut().zip(&converged.rows) {
        row.impulse = solved.impulse;
    }
    let warm = PgsParams {
        warm_start: WarmStart::On,
        ..params
    };
    let info = pgs::solve_in_place(&mut again, &mut workspace, &warm).unwrap();
    assert_eq!(info.sweeps, 1);
}

struct PoisonProjection;

impl Projection for PoisonProjection {
    fn project(&mut self, impulses: &mut [f64], _: usize) {
        impulses[0] = f64::NAN;
    }
    fn bound(&self, _: usize) -> Option<RowBound> {
        None
    }
}

#[test]
fn non_finite_values_stop_the_solve_naming_the_block() {
    let mut problem = cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5);
    problem.rows[7].target = f64::NAN; // block 2
    assert_eq!(
        pgs::solve(&mut problem).unwrap_err(),
        LcpError::NonFinite { block: 2 }
    );
    assert_eq!(
        direct::solve(&mut problem, &direct::DirectParams::default()).unwrap_err(),
        LcpError::NonFinite { block: 2 }
    );

    let mut problem = Problem {
        bodies: vec![
            SolverBody::fixed(),
            cube(1.0, 2.0, Vector3::new(0.0, 0.0, -1.0)),
        ],
        rows: vec![point_row(Vector3::zeros(), Vector3::z())],
        blocks: vec![Block {
            body_a: BodyId(1),
            body_b: BodyId(0),
            rows: 0..1,
            projection: PoisonProjection,
        }],
    };
    assert_eq!(
        pgs::solve(&mut problem).unwrap_err(),
        LcpError::NonFinite { block: 0 }
    );
    assert_eq!(
        direct::solve(&mut problem, &direct::DirectParams::default()).unwrap_err(),
        LcpError::Unsupported { block: 0 }
    );
    problem.bodies[1].inv_mass = f64::INFINITY;
    assert_eq!(
        pgs::solve(&mut problem).unwrap_err(),
        LcpError::NonFiniteBody { body: BodyId(1) }
    );
}

#[test]
fn malformed_blocks_are_rejected() {
    let mut problem = cube_on_ground(Vector3::zeros(), 0.5);
    problem.blocks[1].body_a = BodyId(9);
    assert_eq!(
        pgs::solve(&mut problem).unwrap_err(),
        LcpError::MalformedBlock { block: 1 }
    );
    // A reversed row range, and a friction bound scaled by a row outside its block: errors
    // naming the block, not panics (both once indexed out of bounds).
    let mut reversed = cube_on_ground(Vector3::zeros(), 0.5);
    let rows = reversed.blocks[0].rows.clone();
    reversed.blocks[0].rows = rows.end..rows.start;
    assert!(matches!(
        pgs::solve(&mut reversed).unwrap_err(),
        LcpError::MalformedBlock { block: 0 }
    ));
    let mut stray = cube_on_ground(Vector3::zeros(), 0.5);
    stray.blocks[2].projection.0[1] = RowBound::Friction {
        normal: 7,
        coefficient: 0.5,
    };
    assert_eq!(
        pgs::solve(&mut stray).unwrap_err(),
        LcpError::MalformedBlock { block: 2 }
    );
}

/// A problem with a non-finite row and a malformed block is reported by whichever comes first
/// in block order, and a row no block covers is a malformed block past the last.
#[test]
fn the_first_offending_block_is_named() {
    let nan_in = |block: usize, malformed: usize| {
        let mut problem = cube_on_ground(Vector3::zeros(), 0.5);
        let row = problem.blocks[block].rows.start;
        problem.rows[row].jacobian.angular_a.y = f64::NAN;
        problem.blocks[malformed].body_b = BodyId(9);
        problem.validate().unwrap_err()
    };
    assert_eq!(nan_in(1, 3), LcpError::NonFinite { block: 1 });
    assert_eq!(nan_in(3, 1), LcpError::MalformedBlock { block: 1 });
    assert_eq!(nan_in(2, 2), LcpError::MalformedBlock { block: 2 });
    let mut uncovered = cube_on_ground(Vector3::zeros(), 0.5);
    uncovered.blocks.pop();
    assert_eq!(
        uncovered.validate().unwrap_err(),
        LcpError::MalformedBlock { block: 3 }
    );
    uncovered.rows.last_mut().unwrap().impulse = f64::INFINITY;
    assert_eq!(
        uncovered.validate().unwrap_err(),
        LcpError::MalformedBlock { block: 3 }
    );
}

/// Random bodies and one-row blocks with constant box bounds: one-row blocks make the block
/// projection a per-row clamp, which is exactly what the dense PGS does.
fn random_problem() -> impl Strategy<Value = Problem<BoundsProjection>> {
    let body = (
        0.1..10.0f64,
        0.1..10.0f64,
        prop::array::uniform3(-1.0..1.0f64),
        prop::array::uniform3(-1.0..1.0f64),
    )
        .prop_map(|(m, i, v, w)| SolverBody {
            inv_mass: 1.0 / m,
            inv_inertia_world: Matrix3::from_diagonal(&Vector3::new(1.0 / i, 2.0 / i, 0.5 / i)),
            linear_velocity: Vector3::from(v),
            angular_velocity: Vector3::from(w),
        });
    let row = (
        0usize..6,
        0usize..6,
        prop::array::uniform12(-1.0..1.0f64),
        -1.0..1.0f64,
        -2.0..0.0f64,
        0.0..2.0f64,
    );
    (
        prop::collection::vec(body, 2..6),
        prop::collection::vec(row, 1..30),
    )
        .prop_map(|(bodies, rows)| {
            let mut problem = Problem {
                bodies,
                ..Problem::default()
            };
            let n = problem.bodies.len();
            for (a, b, j, target, lo, hi) in rows {
                let (a, b) = (a % n, (a + 1 + b % (n - 1)) % n);
                let start = problem.rows.len();
                problem.rows.push(Row {
                    jacobian: Jacobian {
                        linear_a: Vector3::new(j[0], j[1], j[2]),
                        angular_a: Vector3::new(j[3], j[4], j[5]),
                        linear_b: Vector3::new(j[6], j[7], j[8]),
                        angular_b: Vector3::new(j[9], j[10], j[11]),
                    },
                    target,
                    impulse: 0.0,
                });
                problem.blocks.push(Block {
                    body_a: BodyId(a),
                    body_b: BodyId(b),
                    rows: start..start + 1,
                    projection: BoundsProjection(vec![RowBound::Box { lo, hi }]),
                });
            }
            problem
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn sparse_and_dense_pgs_give_the_same_impulses(problem in random_problem(), iterations in 1usize..40) {
        let (a, b) = dense::assemble(&problem);
        let bounds = |pick: fn(RowBound) -> f64| DVector::from_iterator(
            problem.blocks.len(),
            problem.blocks.iter().map(|blk| pick(blk.projection.0[0])),
        );
        let lo = bounds(|r| if let RowBound::Box { lo, .. } = r { lo } else { unreachable!() });
        let hi = bounds(|r| if let RowBound::Box { hi, .. } = r { hi } else { unreachable!() });
        let dense_z = pgs_dense(&a, &b, &lo, &hi, iterations);
        let mut sparse = problem.clone();
        let params = PgsParams { iterations, ..PgsParams::default() };
        pgs::solve_in_place(&mut sparse, &mut PgsWorkspace::default(), &params).unwrap();
        for (k, row) in sparse.rows.iter().enumerate() {
            // The two evaluate the same sums in different orders: rounding only.
            prop_assert!((row.impulse - dense_z[k]).abs() <= 1e-9 * (1.0 + dense_z[k].abs()),
                "row {}: sparse {} dense {}", k, row.impulse, dense_z[k]);
        }
    }

    /// A second solve of the same rows with new targets from rest (the split-impulse position
    /// pass) reusing the first solve's responses gives the bits a fresh solve gives.
    #[test]
    fn a_resolve_gives_the_bits_of_a_fresh_solve(
        problem in random_problem(),
        targets in prop::collection::vec(-1.0..1.0f64, 30),
        iterations in 1usize..20,
    ) {
        let params = PgsParams { iterations, ..PgsParams::default() };
        let mut first = problem.clone();
        let mut workspace = PgsWorkspace::default();
        pgs::solve_in_place(&mut first, &mut workspace, &params).unwrap();
        for (row, &target) in first.rows.iter_mut().zip(&targets) {
            row.target = target;
        }
        for body in &mut first.bodies {
            body.linear_velocity = Vector3::zeros();
            body.angular_velocity = Vector3::zeros();
        }
        let mut fresh = first.clone();
        pgs::resolve_in_place(&mut first, &mut workspace, &params).unwrap();
        pgs::solve_in_place(&mut fresh, &mut PgsWorkspace::default(), &params).unwrap();
        for (again, new) in first.rows.iter().zip(&fresh.rows) {
            prop_assert_eq!(again.impulse.to_bits(), new.impulse.to_bits());
        }
        for (again, new) in first.bodies.iter().zip(&fresh.bodies) {
            prop_assert_eq!(again.linear_velocity, new.linear_velocity);
            prop_assert_eq!(again.angular_velocity, new.angular_velocity);
        }
    }
}

/// The cube's 12 rows become 28 standard variables (1 + 3 + 3 per corner); a budget one byte
/// short of their dense storage refuses the solve before allocating, naming the unknowns, and the
/// exact budget solves it. The storage: `A`, three standard-size matrices, the tableau, and
/// for a rebuild of the tableau a basis with its factors and two tableau-wide blocks.
#[test]
fn a_direct_problem_over_the_memory_budget_is_refused() {
    let (square, tableau) = (28 * 28, 28 * (2 * 28 + 2));
    let bytes = 8 * (12 * 12 + 3 * square + tableau + 2 * square + 2 * tableau);
    assert_eq!(direct::dense_bytes(12, 28), bytes);
    let mut problem = cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5);
    let tight = direct::DirectParams {
        memory_budget: bytes - 1,
        ..Default::default()
    };
    assert_eq!(
        direct::solve(&mut problem, &tight).unwrap_err(),
        LcpError::TooLarge {
            variables: 28,
            bytes,
            budget: bytes - 1
        }
    );
    let exact = direct::DirectParams {
        memory_budget: bytes,
        ..Default::default()
    };
    direct::solve(&mut problem, &exact).unwrap();
    assert!(direct::dense_bytes(usize::MAX, usize::MAX) == usize::MAX);
}

/// A box bound with `lo > hi`, a negative friction coefficient or a friction row scaled by a
/// row that is not a normal (itself, here) was solved by PGS as if valid, leaving an impulse
/// outside its bounds (found by fuzzing); every solver now refuses them.
#[test]
fn malformed_row_bounds_are_refused_by_every_solver() {
    let one_row = |bound: RowBound| Problem {
        bodies: vec![
            SolverBody::fixed(),
            cube(1.0, 2.0, Vector3::new(0.0, 0.0, -1.0)),
        ],
        rows: vec![
            point_row(Vector3::zeros(), Vector3::z()),
            point_row(Vector3::zeros(), Vector3::x()),
        ],
        blocks: vec![Block {
            body_a: BodyId(1),
            body_b: BodyId(0),
            rows: 0..2,
            projection: BoundsProjection(vec![RowBound::NonNegative, bound]),
        }],
    };
    let reversed = one_row(RowBound::Box { lo: 0.02, hi: 0.0 });
    let negative = one_row(RowBound::Friction {
        normal: 0,
        coefficient: -0.5,
    });
    let circular = one_row(RowBound::Friction {
        normal: 1,
        coefficient: 0.5,
    });
    for (mut problem, expected) in [
        (circular, LcpError::MalformedBlock { block: 0 }),
        (
            reversed,
            LcpError::InvalidBounds {
                row: 1,
                lo: 0.02,
                hi: 0.0,
            },
        ),
        (negative, LcpError::MalformedBlock { block: 0 }),
    ] {
        assert_eq!(pgs::solve(&mut problem.clone()).unwrap_err(), expected);
        let mut workspace = PgsWorkspace::default();
        assert_eq!(
            pgs::shock_propagation(&mut problem.clone(), &mut workspace, &[]).unwrap_err(),
            expected
        );
        assert_eq!(
            direct::solve(&mut problem, &direct::DirectParams::default()).unwrap_err(),
            expected
        );
    }
}

/// Finite but huge numbers overflow the velocities within the solve: here a warm-start
/// impulse of 1e300 on a body of 1e-10 kg. PGS once returned `Ok` with an infinite body (found
/// by fuzzing); it now names the body.
#[test]
fn velocities_that_overflow_in_the_solve_name_the_body() {
    let mut row = point_row(Vector3::zeros(), Vector3::z());
    row.impulse = 1e300;
    let mut problem = Problem {
        bodies: vec![SolverBody::fixed(), cube(1e-10, 2.0, Vector3::zeros())],
        rows: vec![row],
        blocks: vec![Block {
            body_a: BodyId(1),
            body_b: BodyId(0),
            rows: 0..1,
            projection: BoundsProjection(vec![RowBound::NonNegative]),
        }],
    };
    let params = PgsParams {
        warm_start: WarmStart::On,
        ..PgsParams::default()
    };
    assert_eq!(
        pgs::solve_in_place(&mut problem, &mut PgsWorkspace::default(), &params).unwrap_err(),
        LcpError::NonFiniteBody { body: BodyId(1) }
    );
}

/// A six-row block that is all equalities (every impulse admissible), solved whole or not.
struct Free {
    whole: bool,
}

impl Projection for Free {
    fn project(&mut self, _: &mut [f64], _: usize) {}
    fn whole_block(&self) -> bool {
        self.whole
    }
    fn admissible(&mut self, _: &[f64]) -> bool {
        true
    }
    fn bound(&self, _: usize) -> Option<RowBound> {
        None
    }
}

/// One face-like block of six coupled rows — three point rows at a corner of a tilted 2 m cube
/// and three angular rows — holding a sliding, spinning cube still. Row-by-row, one sweep leaves
/// the rows' velocities far from zero (the rows are coupled); solved whole with its own 6 × 6
/// effective mass, one sweep leaves them zero to rounding, and both reach the same impulses
/// when swept to convergence.
#[test]
fn a_block_solved_whole_is_exact_in_one_sweep() {
    let r = Vector3::new(0.7, -0.4, -1.0);
    let mut body = cube(1.0, 2.0, Vector3::new(0.3, -0.2, -G * DT));
    body.angular_velocity = Vector3::new(0.1, 0.5, -0.3);
    let problem = |whole: bool| {
        let mut rows: Vec<Row> = [Vector3::z(), Vector3::x(), Vector3::y()]
            .into_iter()
            .map(|d| point_row(r, d))
            .collect();
        for axis in [Vector3::x(), Vector3::y(), Vector3::z()] {
            rows.push(Row {
                jacobian: Jacobian {
                    linear_a: Vector3::zeros(),
                    angular_a: axis,
                    linear_b: Vector3::zeros(),
                    angular_b: -axis,
                },
                target: 0.0,
                impulse: 0.0,
            });
        }
        Problem {
            bodies: vec![SolverBody::fixed(), body],
            rows,
            blocks: vec![Block {
                body_a: BodyId(1),
                body_b: BodyId(0),
                rows: 0..6,
                projection: Free { whole },
            }],
        }
    };
    let residual = |p: &Problem<Free>| {
        p.rows
            .iter()
            .map(|row| (row.jacobian.velocity(&p.bodies[1], &p.bodies[0]) - row.target).abs())
            .fold(0.0, f64::max)
    };
    let sweeps = |n: usize| PgsParams {
        iterations: n,
        ..PgsParams::default()
    };
    let mut workspace = PgsWorkspace::default();
    let mut whole = problem(true);
    pgs::solve_in_place(&mut whole, &mut workspace, &sweeps(1)).unwrap();
    let mut by_row = problem(false);
    pgs::solve_in_place(&mut by_row, &mut workspace, &sweeps(1)).unwrap();
    assert!(residual(&whole) < 1e-12, "whole: {}", residual(&whole));
    assert!(
        residual(&by_row) > 1e-2,
        "row by row: {}",
        residual(&by_row)
    );
    let mut converged = problem(false);
    pgs::solve_in_place(&mut converged, &mut workspace, &sweeps(2000)).unwrap();
    for (a, b) in whole.rows.iter().zip(&converged.rows) {
        assert!(
            (a.impulse - b.impulse).abs() < 1e-9,
            "{} against {}",
            a.impulse,
            b.impulse
        );
    }
}

/// Two vertex-model cubes on one fixed ground, their blocks interleaved (a block of the first,
/// one of the second, …): two islands, since the ground joins nothing.
fn side_by_side(
    first: &Problem<BoundsProjection>,
    second: &Problem<BoundsProjection>,
) -> Problem<BoundsProjection> {
    let mut problem = Problem {
        bodies: vec![SolverBody::fixed(), first.bodies[1], second.bodies[1]],
        ..Problem::default()
    };
    for (a, b) in first.blocks.iter().zip(&second.blocks) {
        for (block, body, source) in [(a, 1, first), (b, 2, second)] {
            let start = problem.rows.len();
            problem
                .rows
                .extend_from_slice(&source.rows[block.rows.clone()]);
            problem.blocks.push(Block {
                body_a: BodyId(body),
                rows: start..problem.rows.len(),
                ..block.clone()
            });
        }
    }
    problem
}

/// Islands: a cube sliding diagonally and spinning beside one at rest on the same fixed ground.
/// With a tolerance of 0 solving them together gives each cube's bits solved alone (blocks of
/// different islands share no velocity they write); with a tolerance the resting cube,
/// warm-started from its answer, stops after one sweep while the sliding one keeps sweeping, and
/// each lands on its own solve's bits.
#[test]
fn islands_are_solved_as_if_alone_and_stop_on_their_own() {
    let sliding = || {
        let mut problem = cube_on_ground(Vector3::new(0.3, 0.2, -G * DT), 0.5);
        problem.bodies[1].angular_velocity = Vector3::new(0.1, -0.2, 0.4);
        problem
    };
    let resting = || cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5);
    let mut workspace = PgsWorkspace::default();
    let every_sweep = PgsParams {
        iterations: 40,
        ..PgsParams::default()
    };
    let mut together = side_by_side(&sliding(), &resting());
    pgs::solve_in_place(&mut together, &mut workspace, &every_sweep).unwrap();
    let mut alone = [sliding(), resting()];
    for problem in &mut alone {
        pgs::solve_in_place(problem, &mut workspace, &every_sweep).unwrap();
    }
    let solved = side_by_side(&alone[0], &alone[1]);
    for (row, expected) in together.rows.iter().zip(&solved.rows) {
        assert_eq!(row.impulse.to_bits(), expected.impulse.to_bits());
    }
    assert_eq!(together.bodies, solved.bodies);

    // The resting cube warm-started from its converged answer, the sliding one from zero.
    let converged_rest = alone[1].clone();
    let warm = PgsParams {
        iterations: 200,
        tolerance: 1e-8,
        warm_start: WarmStart::On,
        ..PgsParams::default()
    };
    let mut together = side_by_side(&sliding(), &converged_rest);
    together.bodies[2] = resting().bodies[1];
    let info = pgs::solve_in_place(&mut together, &mut workspace, &warm).unwrap();
    let mut sliding_alone = sliding();
    let sliding_info = pgs::solve_in_place(&mut sliding_alone, &mut workspace, &warm).unwrap();
    let mut rest_alone = converged_rest.clone();
    rest_alone.bodies[1] = resting().bodies[1];
    let rest_info = pgs::solve_in_place(&mut rest_alone, &mut workspace, &warm).unwrap();
    assert_eq!(
        rest_info.sweeps, 1,
        "the resting cube's answer is already there"
    );
    assert!(sliding_info.sweeps > 5, "{} sweeps", sliding_info.sweeps);
    assert_eq!(info.sweeps, sliding_info.sweeps);
    assert_eq!(
        info.row_updates,
        sliding_info.row_updates + rest_info.row_updates,
        "the resting island swept once"
    );
    let expected = side_by_side(&sliding_alone, &rest_alone);
    for (row, expected) in together.rows.iter().zip(&expected.rows) {
        assert_eq!(row.impulse.to_bits(), expected.impulse.to_bits());
    }
    assert_eq!(together.bodies, expected.bodies);
}

/// Quiet blocks: a row of cubes on one fixed ground, each touching the next through a side
/// contact that carries nothing, so the row is one island. The first cube slides away from the
/// second, diagonally and spinning; the others rest, warm-started from their converged answers.
/// With a tolerance the resting cubes' blocks and the side contacts between them are updated in
/// the first sweep only and passed over after it, while the sliding cube's keep sweeping; and
/// the sliding cube lands on its bits solved alone: nothing else moved it, so its blocks were
/// passed over exactly when they were alone.
#[test]
fn quiet_blocks_are_passed_over_while_their_island_sweeps_on() {
    const RESTING: usize = 8;
    let sliding = || {
        let mut problem = cube_on_ground(Vector3::new(-0.3, 0.2, -G * DT), 0.5);
        problem.bodies[1].angular_velocity = Vector3::new(0.1, -0.2, 0.4);
        problem
    };
    let params = PgsParams {
        iterations: 200,
        tolerance: 1e-8,
        warm_start: WarmStart::On,
        ..PgsParams::default()
    };
    let mut workspace = PgsWorkspace::default();
    let mut rest = cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5);
    pgs::solve_in_place(&mut rest, &mut workspace, &params).unwrap();
    rest.bodies[1] = cube_on_ground(Vector3::new(0.0, 0.0, -G * DT), 0.5).bodies[1];

    // Body 1 slides; bodies 2.. rest, each 2 m along x from the one before.
    let mut row = sliding();
    for k in 0..RESTING {
        let body = row.bodies.len();
        row.bodies.push(rest.bodies[1]);
        for block in &rest.blocks {
            let start = row.rows.len();
            row.rows.extend_from_slice(&rest.rows[block.rows.clone()]);
            row.blocks.push(Block {
                body_a: BodyId(body),
                rows: start..row.rows.len(),
                ..block.clone()
            });
        }
        // The side contact between the faces that touch: B's velocity away from A along x.
        let start = row.rows.len();
        row.rows.push(Row {
            jacobian: Jacobian {
                linear_a: -Vector3::x(),
                angular_a: Vector3::zeros(),
                linear_b: Vector3::x(),
                angular_b: Vector3::zeros(),
            },
            target: 0.0,
            impulse: 0.0,
        });
        row.blocks.push(Block {
            body_a: BodyId(body - 1),
            body_b: BodyId(body),
            rows: start..start + 1,
            projection: BoundsProjection(vec![RowBound::NonNegative]),
        });
        assert_eq!(body, k + 2);
    }
    let info = pgs::solve_in_place(&mut row, &mut workspace, &params).unwrap();
    let mut alone = sliding();
    let alone_info = pgs::solve_in_place(&mut alone, &mut workspace, &params).unwrap();
    assert!(alone_info.sweeps > 5, "{} sweeps", alone_info.sweeps);
    assert_eq!(info.sweeps, alone_info.sweeps);
    let resting_rows = RESTING * rest.rows.len();
    // Every block is updated in the first sweep; after it only the sliding cube's own blocks
    // and, while that cube moves, the side contact on it.
    let once = alone_info.row_updates + resting_rows + RESTING;
    assert!(
        (once..once + info.sweeps).contains(&info.row_updates),
        "{} row updates, {once} in the first sweep and the sliding cube's",
        info.row_updates
    );
    assert_eq!(row.bodies[1], alone.bodies[1]);
    for (row, expected) in row.rows.iter().zip(&alone.rows) {
        assert_eq!(row.impulse.to_bits(), expected.impulse.to_bits());
    }
    // Their warm start is an answer met to the tolerance, and one sweep keeps them within it.
    for body in &row.bodies[2..] {
        let speed = body
            .linear_velocity
            .norm()
            .max(body.angular_velocity.norm());
        assert!(speed < params.tolerance, "{body:?}");
    }
}
