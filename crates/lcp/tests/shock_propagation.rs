//! Shock propagation on a stack of point masses: one bottom-up pass after a short solve brings
//! every body to rest on the one below, where Gauss–Seidel alone needs many sweeps.

use nalgebra::{Matrix3, Vector3};
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace, Support};
use tatami_lcp::{
    Block, BodyId, BoundsProjection, Jacobian, LcpError, Problem, Row, RowBound, SolverBody,
};

/// A fixed floor (body 0) and `n` unit masses above it, all falling at 1 m/s; block k is the
/// normal row between body k + 1 (A, above) and body k (B, below), listed top-down.
fn falling_stack(n: usize) -> Problem<BoundsProjection> {
    let mut bodies = vec![SolverBody::fixed()];
    bodies.extend((0..n).map(|_| SolverBody {
        inv_mass: 1.0,
        inv_inertia_world: Matrix3::identity(),
        linear_velocity: Vector3::new(0.0, 0.0, -1.0),
        angular_velocity: Vector3::zeros(),
    }));
    let mut problem = Problem {
        bodies,
        rows: Vec::new(),
        blocks: Vec::new(),
    };
    for k in (0..n).rev() {
        let row = problem.rows.len();
        problem.rows.push(Row {
            jacobian: Jacobian {
                linear_a: Vector3::z(),
                angular_a: Vector3::zeros(),
                linear_b: -Vector3::z(),
                angular_b: Vector3::zeros(),
            },
            target: 0.0,
            impulse: 0.0,
        });
        problem.blocks.push(Block {
            body_a: BodyId(k + 1),
            body_b: BodyId(k),
            rows: row..row + 1,
            projection: BoundsProjection(vec![RowBound::NonNegative]),
        });
    }
    problem
}

/// Bottom-up order: the last block (floor contact) first, each carried by its body B.
fn bottom_up(n: usize) -> Vec<(usize, Support)> {
    (0..n).rev().map(|block| (block, Support::B)).collect()
}

fn fastest(problem: &Problem<BoundsProjection>) -> f64 {
    problem
        .bodies
        .iter()
        .map(|b| b.linear_velocity.norm())
        .fold(0.0, f64::max)
}

#[test]
fn one_pass_after_two_sweeps_stops_a_stack_of_fifty() {
    let n = 50;
    let params = PgsParams {
        iterations: 2,
        ..PgsParams::default()
    };
    let mut workspace = PgsWorkspace::default();
    let mut plain = falling_stack(n);
    pgs::solve_in_place(&mut plain, &mut workspace, &params).unwrap();
    // Two sweeps carry the floor's support two levels up: the top still falls.
    assert!(fastest(&plain) > 0.5, "{}", fastest(&plain));

    let mut shocked = falling_stack(n);
    pgs::solve_in_place(&mut shocked, &mut workspace, &params).unwrap();
    pgs::shock_propagation(&mut shocked, &mut workspace, &bottom_up(n)).unwrap();
    // Each body is set to the velocity of the (already resting) one below: exactly at rest.
    assert!(fastest(&shocked) < 1e-12, "{}", fastest(&shocked));
    // Every contact pushes (no pulling impulse was needed).
    assert!(shocked.rows.iter().all(|r| r.impulse >= 0.0));
}

#[test]
fn the_supporting_body_is_held_still() {
    let mut problem = falling_stack(2);
    let before = problem.bodies[1].linear_velocity;
    // Only the upper contact, carried by body 1: body 1 keeps its velocity, body 2 matches it.
    pgs::shock_propagation(
        &mut problem,
        &mut PgsWorkspace::default(),
        &[(0, Support::B)],
    )
    .unwrap();
    assert_eq!(problem.bodies[1].linear_velocity, before);
    assert!((problem.bodies[2].linear_velocity - before).norm() < 1e-12);
}

#[test]
fn an_order_past_the_last_block_is_an_error() {
    let mut problem = falling_stack(2);
    let error = pgs::shock_propagation(
        &mut problem,
        &mut PgsWorkspace::default(),
        &[(5, Support::A)],
    )
    .unwrap_err();
    assert!(
        matches!(error, LcpError::MalformedBlock { block: 5 }),
        "{error:?}"
    );
}

/// A friction bound scaled by a row outside its block indexed out of bounds in the pass; it is
/// an error naming the block, as in `solve_in_place`.
#[test]
fn a_bound_outside_its_block_is_an_error() {
    let mut problem = falling_stack(2);
    problem.blocks[0].projection = BoundsProjection(vec![RowBound::Friction {
        normal: 3,
        coefficient: 0.5,
    }]);
    let error = pgs::shock_propagation(&mut problem, &mut PgsWorkspace::default(), &bottom_up(2))
        .unwrap_err();
    assert_eq!(error, LcpError::MalformedBlock { block: 0 });
}

/// A normal row that says so ([`Projection::leading_normal_rows`]), as a contact's does.
#[derive(Debug, Clone)]
struct Normal;

impl tatami_lcp::Projection for Normal {
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        impulses[0] = impulses[0].max(0.0);
    }

    fn leading_normal_rows(&self) -> usize {
        1
    }

    fn bound(&self, _row: usize) -> Option<RowBound> {
        Some(RowBound::NonNegative)
    }
}

/// Two unit masses stacked on the floor, as in [`falling_stack`] but with contact-like blocks,
/// the upper one moving at `upper` m/s along z against the lower one at rest.
fn resting_pair(upper: f64) -> Problem<Normal> {
    let stack = falling_stack(2);
    let mut problem = Problem {
        bodies: stack.bodies,
        rows: stack.rows,
        blocks: stack
            .blocks
            .into_iter()
            .map(|b| Block {
                body_a: b.body_a,
                body_b: b.body_b,
                rows: b.rows,
                projection: Normal,
            })
            .collect(),
    };
    problem.bodies[1].linear_velocity = Vector3::zeros();
    problem.bodies[2].linear_velocity = Vector3::new(0.0, 0.0, upper);
    problem
}

/// The pass skips a block that carries nothing and whose normal rows are at or past their
/// targets, before computing its responses: the answer is the one of a pass without that block,
/// to the bit. A block closing on its target is not skipped: it is loaded, and its upper body
/// brought to rest on the lower.
#[test]
fn an_unloaded_parting_block_is_passed_over_and_a_closing_one_is_not() {
    let order = bottom_up(2);
    let mut parting = resting_pair(0.5);
    pgs::shock_propagation(&mut parting, &mut PgsWorkspace::default(), &order).unwrap();
    let mut without = resting_pair(0.5);
    pgs::shock_propagation(&mut without, &mut PgsWorkspace::default(), &order[..1]).unwrap();
    assert_eq!(parting.bodies, without.bodies);
    assert_eq!(parting.rows[0].impulse, 0.0);

    let mut closing = resting_pair(-0.5);
    pgs::shock_propagation(&mut closing, &mut PgsWorkspace::default(), &order).unwrap();
    assert!(
        (closing.rows[0].impulse - 0.5).abs() < 1e-12,
        "{}",
        closing.rows[0].impulse
    );
    assert!(closing.bodies[2].linear_velocity.norm() < 1e-12);
}

/// A unit cube (1 kg, inertia 1/6 kg m²) on a fixed floor through four blocks, one normal row at
/// each corner of its base (the vertex model's), falling at 1 m/s and rolling at 0.6 rad/s.
fn cube_on_corners() -> Problem<Normal> {
    let cube = SolverBody {
        inv_mass: 1.0,
        inv_inertia_world: Matrix3::identity() * 6.0,
        linear_velocity: Vector3::new(0.0, 0.0, -1.0),
        angular_velocity: Vector3::new(0.6, 0.0, 0.0),
    };
    let mut problem = Problem {
        bodies: vec![SolverBody::fixed(), cube],
        rows: Vec::new(),
        blocks: Vec::new(),
    };
    for (x, y) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
        let arm = Vector3::new(x, y, -0.5);
        let row = problem.rows.len();
        problem.rows.push(Row {
            jacobian: Jacobian {
                linear_a: Vector3::z(),
                angular_a: arm.cross(&Vector3::z()),
                linear_b: -Vector3::z(),
                angular_b: Vector3::zeros(),
            },
            target: 0.0,
            impulse: 0.0,
        });
        problem.blocks.push(Block {
            body_a: BodyId(1),
            body_b: BodyId(0),
            rows: row..row + 1,
            projection: Normal,
        });
    }
    problem
}

/// One pass over a face's corner blocks leaves the cube moving (each corner stopped in turn, the
/// later ones undo part of the earlier); swept together until settled, the pair's blocks bring it
/// to rest on the floor, every corner pushing. With one sweep a pair the answer is
/// `shock_propagation`'s to the bit.
#[test]
fn a_pairs_blocks_swept_together_rest_a_body_on_its_corners() {
    let order: Vec<_> = (0..4).map(|block| (block, Support::B)).collect();
    let speed = |p: &Problem<Normal>| {
        let cube = &p.bodies[1];
        cube.linear_velocity.norm() + cube.angular_velocity.norm() * 0.5
    };
    let mut once = cube_on_corners();
    pgs::shock_propagation(&mut once, &mut PgsWorkspace::default(), &order).unwrap();
    let mut one_sweep = cube_on_corners();
    pgs::shock_propagation_per_pair(&mut one_sweep, &mut PgsWorkspace::default(), &order, 1)
        .unwrap();
    assert_eq!(once.bodies, one_sweep.bodies);
    assert!(speed(&once) > 1e-2, "{}", speed(&once));

    let mut swept = cube_on_corners();
    pgs::shock_propagation_per_pair(&mut swept, &mut PgsWorkspace::default(), &order, 10).unwrap();
    println!(
        "after one pass {:e} m/s, swept {:e} m/s",
        speed(&once),
        speed(&swept)
    );
    assert!(speed(&swept) < 1e-3 * speed(&once), "{}", speed(&swept));
    assert!(swept.rows.iter().all(|r| r.impulse > 0.0));
}
