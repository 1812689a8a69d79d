//! Inputs shared by the Criterion benchmarks in `benches/benches/`.
//!
//! Each bench target builds its scenes from here so that every benchmark of a concept measures
//! the same input.

pub mod rapier_scene;

pub use rapier_scene::RapierF64;

use nalgebra::{DMatrix, DVector, Matrix3, Point2, Vector3};
use tatami_geometry::ConvexPolygon;
use tatami_lcp::{Block, BodyId, BoundsProjection, Jacobian, Problem, Row, RowBound, SolverBody};

/// A regular `n`-gon of circumradius `radius` centred at the origin, first vertex on `+x`.
pub fn regular_polygon(n: usize, radius: f64) -> ConvexPolygon {
    let points: Vec<_> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            Point2::new(radius * t.cos(), radius * t.sin())
        })
        .collect();
    ConvexPolygon::from_points(&points).expect("a regular polygon has finite vertices")
}

/// `count` query points on a spiral from the centre to twice `radius`: half inside a polygon of
/// that circumradius, half outside, at every angle, so no branch is favoured.
pub fn spiral_queries(count: usize, radius: f64) -> Vec<Point2<f64>> {
    (0..count)
        .map(|k| {
            let s = (k as f64 + 0.5) / count as f64;
            let t = 97.0 * std::f64::consts::TAU * s; // many turns, incommensurate with n
            Point2::new(2.0 * radius * s * t.cos(), 2.0 * radius * s * t.sin())
        })
        .collect()
}

/// A chain of `blocks` 6-row blocks (normal, two friction, twist and two bounded tilt rows, the
/// shape of a face contact) linking `blocks + 1` unit cubes, the first fixed; every body starts
/// with gravity's step of velocity so the rows have work to do.
pub fn chain_problem(blocks: usize) -> Problem<BoundsProjection> {
    let mut problem = Problem::default();
    problem.bodies.push(SolverBody::fixed());
    for _ in 0..blocks {
        problem.bodies.push(SolverBody {
            inv_mass: 1.0,
            inv_inertia_world: Matrix3::identity() * 6.0,
            linear_velocity: Vector3::new(0.0, 0.0, -0.098),
            angular_velocity: Vector3::zeros(),
        });
    }
    let axes = [Vector3::z(), Vector3::x(), Vector3::y()];
    let lever = Vector3::new(0.0, 0.0, -0.5);
    for k in 0..blocks {
        let start = problem.rows.len();
        for axis in axes {
            problem.rows.push(point_row(lever.cross(&axis), axis));
        }
        for axis in axes {
            problem.rows.push(Row {
                jacobian: Jacobian {
                    angular_a: axis,
                    angular_b: -axis,
                    ..Jacobian::default()
                },
                ..Row::default()
            });
        }
        let friction = RowBound::Friction {
            normal: 0,
            coefficient: 0.5,
        };
        problem.blocks.push(Block {
            body_a: BodyId(k + 1),
            body_b: BodyId(k),
            rows: start..start + 6,
            projection: BoundsProjection(vec![
                RowBound::NonNegative,
                friction,
                friction,
                RowBound::Friction {
                    normal: 0,
                    coefficient: 0.2,
                },
                RowBound::Box { lo: -1.0, hi: 1.0 },
                RowBound::Box { lo: -1.0, hi: 1.0 },
            ]),
        });
    }
    problem
}

fn point_row(angular: Vector3<f64>, axis: Vector3<f64>) -> Row {
    Row {
        jacobian: Jacobian {
            linear_a: axis,
            angular_a: angular,
            linear_b: -axis,
            angular_b: -angular,
        },
        ..Row::default()
    }
}

/// A deterministic random SPD LCP of size `n`: `A = BᵀB/n + 0.1 I`, `q` in [−1, 1]ⁿ.
pub fn spd_lcp(n: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>) {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407)
        | 1;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let b = DMatrix::from_fn(n, n, |_, _| next());
    let a = b.transpose() * &b / n as f64 + DMatrix::identity(n, n) * 0.1;
    let q = DVector::from_fn(n, |_, _| next());
    (a, q)
}

/// Edge of the benchmark cubes (m): the paper's 2 m boxes.
pub const CUBE_SIDE: f64 = 2.0;

/// Centres of a vertical tower of `n` cubes standing on the plane z = 0.
pub fn tower_centres(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|k| [0.0, 0.0, CUBE_SIDE * (k as f64 + 0.5)])
        .collect()
}

/// Centres of a planar pyramid (in the x–z plane) with `base` cubes in its bottom row and one
/// fewer in each row above, each row centred: `base (base + 1) / 2` cubes, as in Rapier's and
/// Box2D's pyramid benchmarks.
pub fn pyramid_centres(base: usize) -> Vec<[f64; 3]> {
    (0..base)
        .flat_map(|row| {
            let count = base - row;
            (0..count).map(move |i| {
                let x = (i as f64 - (count - 1) as f64 / 2.0) * CUBE_SIDE;
                [x, 0.0, CUBE_SIDE * (row as f64 + 0.5)]
            })
        })
        .collect()
}

/// A Tatami world of 1 kg cubes at `centres` on a fixed 400 m × 400 m floor (top face at
/// z = 0), default friction, with `settings`.
pub fn tatami_cubes(
    centres: &[[f64; 3]],
    settings: tatami_world::WorldSettings,
) -> tatami_world::World {
    use tatami_world::{BodyDesc, Shape, World};
    let floor = BodyDesc::fixed(Shape::cuboid([400.0, 400.0, 2.0]))
        .name("floor")
        .position([0.0, 0.0, -1.0]);
    centres
        .iter()
        .enumerate()
        .fold(
            World::builder().settings(settings).body(floor),
            |world, (k, &centre)| {
                world.body(
                    BodyDesc::dynamic(Shape::cuboid([CUBE_SIDE; 3]))
                        .name(format!("cube{k}"))
                        .mass(1.0)
                        .position(centre),
                )
            },
        )
        .build()
        .expect("valid cubes on a floor")
}

#[cfg(test)]
mod scene_tests {
    use super::*;

    #[test]
    fn a_pyramid_of_base_twenty_has_210_touching_cubes() {
        let centres = pyramid_centres(20);
        assert_eq!(centres.len(), 210);
        // Every cube above the bottom row rests on two cubes half a cube to either side.
        for c in centres.iter().filter(|c| c[2] > CUBE_SIDE) {
            let below = |dx: f64| {
                centres.iter().any(|b| {
                    (b[0] - (c[0] + dx)).abs() < 1e-12 && (b[2] - (c[2] - CUBE_SIDE)).abs() < 1e-12
                })
            };
            assert!(below(-CUBE_SIDE / 2.0) && below(CUBE_SIDE / 2.0), "{c:?}");
        }
        assert_eq!(tower_centres(3)[2], [0.0, 0.0, 5.0]);
    }
}
