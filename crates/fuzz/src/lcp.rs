//! The solver entry points: PGS, shock propagation and the direct solver on contact problems
//! from fuzz bytes, then Lemke, dense PGS and the residuals on dense systems of any size.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace, Support, WarmStart};
use tatami_lcp::{
    Block, BodyId, BoundsProjection, Jacobian, Problem, Projection, Row, RowBound, SolverBody,
    dense, direct, lemke, residual,
};

use crate::bytes::Bytes;

/// One contact problem through every sparse solver, then one dense system through Lemke.
pub fn lcp(data: &[u8]) {
    let mut bytes = Bytes::new(data);
    let problem = problem(&mut bytes);

    let params = PgsParams {
        iterations: bytes.below(30) + 1,
        tolerance: bytes.number(),
        relaxation: bytes.number(),
        warm_start: if bytes.flag() {
            WarmStart::On
        } else {
            WarmStart::Off
        },
        ..PgsParams::default()
    };
    let mut workspace = PgsWorkspace::default();
    let mut solved = problem.clone();
    if pgs::solve_in_place(&mut solved, &mut workspace, &params).is_ok() {
        assert_admissible(&solved, "pgs");
        let order: Vec<_> = (0..bytes.below(6))
            .map(|_| {
                let support = if bytes.flag() { Support::A } else { Support::B };
                (bytes.below(solved.blocks.len() + 1), support)
            })
            .collect();
        if pgs::shock_propagation(&mut solved, &mut workspace, &order).is_ok() {
            assert_admissible(&solved, "shock propagation");
        }
    }
    // The same blocks with the promise that lets PGS skip unloaded ones, where they keep it.
    let mut promised = Problem {
        bodies: problem.bodies.clone(),
        rows: problem.rows.clone(),
        blocks: problem
            .blocks
            .iter()
            .map(|b| Block {
                body_a: b.body_a,
                body_b: b.body_b,
                rows: b.rows.clone(),
                projection: Cone(b.projection.clone()),
            })
            .collect(),
    };
    if pgs::solve_in_place(&mut promised, &mut workspace, &params).is_ok() {
        assert_admissible(&promised, "pgs, unloaded blocks skipped");
    }
    let mut exact = problem;
    if direct::solve(&mut exact, &direct::DirectParams::default()).is_ok() {
        assert_admissible(&exact, "direct");
    }

    dense_system(&mut bytes);
}

/// Up to 4 bodies (body 0 fixed) and 4 blocks of 1–3 rows, every number drawn.
fn problem(bytes: &mut Bytes) -> Problem<BoundsProjection> {
    let mut bodies = vec![SolverBody::fixed()];
    for _ in 0..bytes.below(4) {
        let mut v = || Vector3::new(bytes.number(), bytes.number(), bytes.number());
        let (linear_velocity, angular_velocity, inertia) = (v(), v(), v());
        bodies.push(SolverBody {
            inv_mass: bytes.number(),
            inv_inertia_world: Matrix3::from_diagonal(&inertia),
            linear_velocity,
            angular_velocity,
        });
    }
    let mut problem = Problem {
        bodies,
        ..Problem::default()
    };
    for _ in 0..bytes.below(5) {
        let start = problem.rows.len();
        let size = bytes.below(3) + 1;
        let bounds = (0..size)
            .map(|_| match bytes.below(3) {
                0 => RowBound::NonNegative,
                1 => RowBound::Friction {
                    normal: bytes.below(4),
                    coefficient: bytes.number(),
                },
                _ => RowBound::Box {
                    lo: bytes.number(),
                    hi: bytes.number(),
                },
            })
            .collect();
        for _ in 0..size {
            let mut v = || Vector3::new(bytes.number(), bytes.number(), bytes.number());
            let jacobian = Jacobian {
                linear_a: v(),
                angular_a: v(),
                linear_b: v(),
                angular_b: v(),
            };
            problem.rows.push(Row {
                jacobian,
                target: bytes.number(),
                impulse: bytes.number(),
            });
        }
        let bodies = problem.bodies.len() + 1; // one past the end: a malformed block
        problem.blocks.push(Block {
            body_a: BodyId(bytes.below(bodies)),
            body_b: BodyId(bytes.below(bodies)),
            rows: start..start + size,
            projection: BoundsProjection(bounds),
        });
    }
    problem
}

/// Row bounds that name their normal rows ([`Projection::leading_normal_rows`]) when they keep
/// its promise: the leading non-negative rows, when every other row is friction on one of them.
#[derive(Debug, Clone)]
struct Cone(BoundsProjection);

impl Projection for Cone {
    fn project(&mut self, impulses: &mut [f64], changed: usize) {
        self.0.project(impulses, changed);
    }

    fn bound(&self, row: usize) -> Option<RowBound> {
        self.0.bound(row)
    }

    fn leading_normal_rows(&self) -> usize {
        let bounds = &self.0.0;
        let normals = bounds
            .iter()
            .take_while(|&&b| b == RowBound::NonNegative)
            .count();
        let friction_on_them = bounds[normals..].iter().all(|b| {
            matches!(b, RowBound::Friction { normal, coefficient }
                if *normal < normals && coefficient.is_finite())
        });
        if friction_on_them { normals } else { 0 }
    }
}

/// A solve that returned `Ok` left finite impulses and velocities within every row bound.
fn assert_admissible<P: Projection + std::fmt::Debug>(problem: &Problem<P>, solver: &str) {
    for body in &problem.bodies {
        assert!(
            body.is_finite(),
            "{solver}: non-finite body after Ok: {problem:?}"
        );
    }
    for block in &problem.blocks {
        let impulses: Vec<f64> = problem.rows[block.rows.clone()]
            .iter()
            .map(|r| r.impulse)
            .collect();
        assert!(
            impulses.iter().all(|x| x.is_finite()),
            "{solver}: non-finite impulse"
        );
        for (k, &impulse) in impulses.iter().enumerate() {
            // Bounds hold to the rounding of the numbers involved: the impulses and the bounds.
            let Some(row_bound) = block.projection.bound(k) else {
                continue;
            };
            let bound = match row_bound {
                RowBound::Box { lo, hi } => [lo, hi]
                    .into_iter()
                    .filter(|x| x.is_finite())
                    .fold(0.0, |m: f64, x| m.max(x.abs())),
                _ => 0.0,
            };
            let slack = 1e-9 * impulses.iter().fold(bound.max(1.0), |m, x| m.max(x.abs()));
            let ok = match row_bound {
                RowBound::NonNegative => impulse >= -slack,
                RowBound::Friction {
                    normal,
                    coefficient,
                } => {
                    impulse.abs() <= coefficient * impulses[normal].max(0.0) * (1.0 + 1e-9) + slack
                }
                RowBound::Box { lo, hi } => impulse >= lo - slack && impulse <= hi + slack,
            };
            assert!(
                ok,
                "{solver}: impulse {impulse} outside {row_bound:?}, block {impulses:?} {:?}",
                block.projection
            );
        }
    }
}

/// A dense `n × n` system with mismatched sizes now and then, through Lemke, dense PGS and the
/// residuals.
fn dense_system(bytes: &mut Bytes) {
    let n = bytes.below(7);
    let a = DMatrix::from_fn(n, n, |_, _| bytes.number());
    let q_len = if bytes.below(8) == 0 {
        bytes.below(7)
    } else {
        n
    };
    let q = DVector::from_fn(q_len, |_, _| bytes.number());
    if let Ok(z) = lemke(&a, &q, 50 * (n + 1)) {
        assert!(
            z.iter().all(|x| x.is_finite() && *x >= 0.0),
            "lemke: {z} a {a:?} q {q:?}"
        );
        let error = residual::lcp_error(&a, &q, &z).expect("sizes agree");
        assert!(error.is_finite(), "lemke: error {error}");
    }
    let lo = DVector::from_fn(n, |_, _| bytes.number());
    let hi = DVector::from_fn(n, |_, _| bytes.number());
    if let Ok(z) = dense::try_pgs_dense(&a, &q, &lo, &hi, bytes.below(20)) {
        let w = DVector::from_fn(n, |_, _| bytes.number());
        let _ = residual::box_complementarity(&z, &w, &lo, &hi);
    }
    let _ = residual::lcp_error(&a, &q, &DVector::zeros(bytes.below(7)));
}
