//! Substeps ([`WorldSettings::max_substeps`]): a step split when the typical body is small for
//! it, with the step's forces in every substep and a kinematic target reached a share at a time.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use tatami_world::dropped::{bin_walls, cubes_to_pour};
use tatami_world::{BodyDesc, MAX_SUBSTEPS, Shape, World, WorldSettings};

/// 300 cubes of 10 cm poured into a walled bin 1 m across under `settings`.
fn bin(settings: WorldSettings) -> World {
    let floor = BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 0.2])).position([0.0, 0.0, -0.1]);
    let bodies = std::iter::once(floor)
        .chain(bin_walls(0.5, 0.05, 2.0))
        .chain(cubes_to_pour(0.1, 0.5, 300, 0.3, 7));
    bodies
        .fold(World::builder().settings(settings), |b, body| b.body(body))
        .build()
        .unwrap()
}

/// With up to [`MAX_SUBSTEPS`] a step.
fn in_substeps() -> WorldSettings {
    WorldSettings {
        max_substeps: MAX_SUBSTEPS,
        ..WorldSettings::default()
    }
}

/// 300 cubes of 10 cm poured into a 1 m bin at 60 Hz (`g dt² / L` = 0.027), in substeps (two
/// here): they are at rest within 6 s, no two more than the slop (2 mm, 0.1 mm spared for the
/// position pass) into each other. In one step each (`max_substeps` = 1) they still churn at
/// 0.3–0.7 m/s with 1–2 cm overlaps after 10 s, under every model (Rapier 0.36 settles them).
#[test]
fn a_bin_of_small_cubes_settles_in_substeps() {
    let settings = in_substeps();
    let mut world = bin(settings);
    for _ in 0..360 {
        world.step(1.0 / 60.0).unwrap();
    }
    let fastest = world
        .bodies()
        .iter()
        .map(|b| b.linear_velocity().norm())
        .fold(0.0, f64::max);
    let deepest = world.contacts().map(|c| c.depth()).fold(0.0, f64::max);
    assert!(fastest < 1e-3, "still moving at {fastest} m/s");
    assert!(deepest < 2.1e-3, "{deepest} m deep");
}

/// A step split in substeps keeps what was set for the whole step: a body pushed sideways by a
/// constant force for a step of 1/60 s (split in eight for these 5 mm bodies) moves as the
/// force says, `F dt / m` in speed (the force acts in every substep), and a kinematic body sent
/// to a target ends the step there, having moved a share of the way in each substep (from rest,
/// faster and faster): a cube in its path, which it reaches on the way while turning, is pushed
/// on rather than passed through.
#[test]
fn forces_and_targets_last_the_whole_step() {
    let mut world = World::builder()
        .settings(in_substeps())
        .body(BodyDesc::dynamic(Shape::cuboid([0.005; 3])).mass(0.01))
        .body(BodyDesc::kinematic(Shape::cuboid([0.005; 3])).position([1.0, 0.0, 0.0]))
        .body(
            BodyDesc::dynamic(Shape::cuboid([0.005; 3]))
                .mass(0.01)
                .position([1.03, 0.0, 0.0]),
        )
        .build()
        .unwrap();
    let (free, hand) = (world.bodies()[0].id(), world.bodies()[1].id());
    world.apply_force(free, [0.06, 0.0, 0.0]).unwrap();
    let target = Point3::new(1.06, 0.0, 0.0);
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3);
    world.set_kinematic_target(hand, target, turn).unwrap();
    world.step(1.0 / 60.0).unwrap();
    let speed = world.bodies()[0].linear_velocity().x;
    assert!(
        (speed - 0.06 / 0.01 / 60.0).abs() < 1e-12,
        "free body at {speed} m/s"
    );
    let at = &world.bodies()[1];
    assert!(
        (at.position() - target).norm() < 1e-12,
        "the hand at {}",
        at.position()
    );
    assert!(at.rotation().angle_to(&turn) < 1e-12);
    let pushed = world.bodies()[2].position() - Point3::new(1.03, 0.0, 0.0);
    let deepest = world.contacts().map(|c| c.depth()).fold(0.0, f64::max);
    assert!(pushed.norm() > 0.025, "the cube moved only {pushed}");
    // The pair's slop is a tenth of 5 mm; 0.1 mm to spare.
    assert!(deepest < 6e-4, "the hand is {deepest} m into the cube");
    // From rest, the hand's speed grows over the step's eight substeps to average 3.6 m/s,
    // 5.2 m/s in the last; sent all the way within the first substep it would have gone
    // 29 m/s and thrown the cube so.
    let speed = world.bodies()[2].linear_velocity().norm();
    assert!(speed < 5.5, "the cube was thrown at {speed} m/s");
}

/// A row of 30 dominoes of 1 × 2.5 × 5 cm, 3 cm apart, the first tipped at 20 rad/s, at 60
/// Hz in substeps (six for 1 cm bodies): all fall, none more than 1
/// mm into another on the way (the pairs' slop, a tenth of the thickness), under every model,
/// and they end at rest. In one step each they went up to 6–8 mm into each other as each
/// landed on the one before it.
#[test]
fn a_row_of_dominoes_falls_without_sinking_into_each_other() {
    let (thick, wide, tall) = (0.01, 0.025, 0.05);
    for model in tatami_world::ContactModel::ALL {
        let mut builder = World::builder()
            .settings(WorldSettings {
                model,
                ..in_substeps()
            })
            .body(BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 0.2])).position([0.0, 0.0, -0.1]));
        for k in 0..30 {
            let domino = BodyDesc::dynamic(Shape::cuboid([thick, wide, tall]))
                .density(700.0)
                .friction(0.5)
                .position([0.03 * k as f64, 0.0, tall / 2.0]);
            let tipped = if k == 0 {
                domino.angular_velocity([0.0, 20.0, 0.0])
            } else {
                domino
            };
            builder = builder.body(tipped);
        }
        let mut world = builder.build().unwrap();
        let mut deepest: f64 = 0.0;
        for _ in 0..240 {
            world.step(1.0 / 60.0).unwrap();
            deepest = world.contacts().map(|c| c.depth()).fold(deepest, f64::max);
        }
        let standing = world.bodies()[1..]
            .iter()
            .filter(|b| b.position().z > 0.4 * tall)
            .count();
        let fastest = world
            .bodies()
            .iter()
            .map(|b| b.linear_velocity().norm())
            .fold(0.0, f64::max);
        assert_eq!(standing, 0, "{model:?}: {standing} still standing");
        assert!(deepest < 1e-3, "{model:?}: {deepest} m deep");
        assert!(fastest < 1e-4, "{model:?}: still moving at {fastest} m/s");
    }
}
