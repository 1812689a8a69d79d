//! The direct solver as a reference: it solves every contact problem a world builds — the
//! held-out scenes on which Lemke used to end on a ray, and random piles of every shape under
//! every model — each answer checked by its complementarity residual.

use tatami_lcp::LcpError;
use tatami_world::dropped::dropped_scene;
use tatami_world::{BodyDesc, ContactModel, DirectParams, Shape, Solver, World, WorldSettings};

mod common;
use common::rotation;

/// What the solver accepts (`tatami_lcp::direct::RESIDUAL_TOLERANCE`), checked here again from
/// its report.
const TOLERANCE: f64 = tatami_lcp::direct::RESIDUAL_TOLERANCE;

fn direct(model: ContactModel) -> WorldSettings {
    WorldSettings {
        model,
        solver: Solver::Direct(DirectParams::default()),
        ..WorldSettings::default()
    }
}

/// Steps `world` `steps` times; every step must succeed with an exact (or flagged regularised)
/// answer.
fn run_checked(world: &mut World, steps: usize, what: &str) {
    for step in 0..steps {
        world
            .step(0.01)
            .unwrap_or_else(|e| panic!("{what}, step {step}: {e}"));
        let info = world.direct_info().expect("the direct solver ran");
        assert!(
            info.residual <= TOLERANCE,
            "{what}, step {step}: residual {:e} ({info:?})",
            info.residual
        );
    }
}

/// The runtime scenes on which Lemke used to end on a ray: a 1 mm cube on a 100 m cube (step
/// 1), a tilted 1 mm thin plate (step 51) and a cube spinning at 10⁴ rad/s (step 71); under every
/// model, past the step that failed.
#[test]
fn the_held_out_scenes_solve() {
    for model in ContactModel::ALL {
        let mut tiny = World::builder()
            .settings(direct(model))
            .body(BodyDesc::fixed(Shape::cuboid([100.0; 3])).position([0.0, 0.0, -50.0]))
            .body(
                BodyDesc::dynamic(Shape::cuboid([1e-3; 3]))
                    .position([0.3, -0.2, 5e-4])
                    .rotation(rotation([0.0, 0.0, 1.0], 17.0)),
            )
            .build()
            .unwrap();
        run_checked(
            &mut tiny,
            20,
            &format!("{model:?} 1 mm cube on a 100 m cube"),
        );
        let mut plate = World::builder()
            .settings(direct(model))
            .body(common::floor())
            .body(
                BodyDesc::dynamic(Shape::cuboid([0.2, 0.1, 1e-3]))
                    .position([0.0, 0.0, 0.05])
                    .rotation(rotation([1.0, 1.0, 0.0], 12.0)),
            )
            .build()
            .unwrap();
        run_checked(&mut plate, 120, &format!("{model:?} tilted thin plate"));
        let mut spinning = World::builder()
            .settings(direct(model))
            .body(common::floor())
            .body(
                BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                    .position([0.0, 0.0, 0.5])
                    .angular_velocity([0.0, 0.0, 1e4]),
            )
            .build()
            .unwrap();
        run_checked(
            &mut spinning,
            100,
            &format!("{model:?} cube spinning at 1e4 rad/s"),
        );
    }
}

/// Random scenes of boxes, spheres, cylinders and hulls dropped apart on a floor
/// (`tatami_world::dropped`), run under PGS to a seeded step between 20 and 80 so that they pile
/// and touch in every way; the direct solver must solve each one's next problem under every
/// model, every answer within its residual tolerance — or say it failed.
///
/// Seed 52 under the vertex model (1,188 unknowns) had no path of Lemke's with a residual below
/// 1e-6 (the best reached 9e-5) and was refused with `LcpError::Inaccurate`; since Lemke
/// rebuilds its tableau from the data (after `REFACTOR_EVERY` pivots, then at doubling
/// intervals) it is solved, and every problem here must be.
#[test]
fn random_piles_solve_under_every_model() {
    let (mut failed, mut retried) = (Vec::new(), 0);
    for seed in 0..60 {
        for model in ContactModel::ALL {
            let mut scene = dropped_scene(seed);
            scene.settings.model = model;
            let mut world = scene.world().unwrap();
            for _ in 0..20 + seed % 61 {
                world.step(scene.dt).unwrap();
            }
            let mut problem = world.prepare_step(scene.dt).unwrap().clone();
            match tatami_lcp::direct::solve(&mut problem, &DirectParams::default()) {
                Ok(info) => {
                    retried += usize::from(info.attempts > 1);
                    assert!(
                        info.residual <= TOLERANCE,
                        "seed {seed} {model:?}: {info:?}"
                    );
                }
                Err(error) => {
                    assert!(
                        matches!(error, LcpError::Inaccurate { .. }),
                        "seed {seed} {model:?}: {error}"
                    );
                    failed.push((seed, model));
                }
            }
        }
    }
    assert!(failed.is_empty(), "failed: {failed:?}");
    // Retrying another path is the exception: 28 and 29 of the example's 600 problems (200
    // seeds) with the current build and the one before it, 4.8%, about 9 of these 180; the
    // bound is three standard deviations of that count above it.
    assert!(retried <= 17, "{retried} of 180 solves needed a retry");
}

/// A pile on which every path of Lemke's used to end on a ray after about 376 pivots: seed 108
/// of the `direct_piles` example under the vertex model (2,304 unknowns). By then the pivots'
/// round-off had moved the tableau off a feasible basis (a basic value of −7 when rebuilt from
/// the data); rebuilt after `REFACTOR_EVERY` pivots and at doubling intervals, one path
/// solves it.
#[test]
fn a_pile_whose_round_off_ended_every_path_on_a_ray_is_solved() {
    let seed = 108;
    let mut scene = dropped_scene(seed);
    scene.settings.model = ContactModel::Vertex;
    let mut world = scene.world().unwrap();
    for _ in 0..20 + seed % 131 {
        world.step(scene.dt).unwrap();
    }
    let mut problem = world.prepare_step(scene.dt).unwrap().clone();
    let info = tatami_lcp::direct::solve(&mut problem, &DirectParams::default())
        .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
    assert!(info.residual <= TOLERANCE, "seed {seed}: {info:?}");
}
