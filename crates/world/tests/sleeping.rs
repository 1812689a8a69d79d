//! Islands and sleeping ([`Sleeping`]): bodies at rest fall asleep in islands, wake on contact,
//! on any control call and when their support goes, and never with sleeping off (the default).

use nalgebra::{UnitQuaternion, Vector3};
use tatami_world::{BodyDesc, BodyId, Shape, Sleeping, World, WorldSettings};

const DT: f64 = 1.0 / 60.0;

fn sleepy() -> WorldSettings {
    WorldSettings {
        sleeping: Sleeping::on(),
        ..WorldSettings::default()
    }
}

fn floor() -> BodyDesc {
    BodyDesc::fixed(Shape::cuboid([100.0, 100.0, 2.0]))
        .name("floor")
        .position([0.0, 0.0, -1.0])
}

fn unit_cube(name: &str, centre: [f64; 3]) -> BodyDesc {
    BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
        .name(name)
        .mass(1.0)
        .position(centre)
}

fn steps(world: &mut World, seconds: f64) {
    for _ in 0..(seconds / DT).round() as usize {
        world.step(DT).unwrap();
    }
}

/// Two unit cubes stacked on the floor, asleep after 1 s.
fn sleeping_stack() -> World {
    let mut world = World::builder()
        .settings(sleepy())
        .body(floor())
        .body(unit_cube("bottom", [0.0, 0.0, 0.5]))
        .body(unit_cube("top", [0.0, 0.0, 1.5]))
        .build()
        .unwrap();
    steps(&mut world, 1.0);
    world
}

fn asleep(world: &World, name: &str) -> bool {
    world.body(name).unwrap().is_asleep()
}

/// Jolt's `TestPhysicsActivationDeactivation`: a unit box dropped from 5 m settles on the floor
/// and, within 5 s, sleeps at rest there, its centre within 1.1 × the slop (2 mm) of 0.5 m.
/// With the default settings it never sleeps.
#[test]
fn a_dropped_box_settles_and_sleeps() {
    let mut world = World::builder()
        .settings(sleepy())
        .body(floor())
        .body(unit_cube("box", [0.0, 0.0, 5.0]))
        .build()
        .unwrap();
    world.step(DT).unwrap();
    assert!(!asleep(&world, "box"));
    assert!(world.body("box").unwrap().linear_velocity().norm() > 0.0);
    steps(&mut world, 5.0);
    let body = world.body("box").unwrap();
    assert!(body.is_asleep());
    assert!(
        (body.position().z - 0.5).abs() < 1.1 * 0.002,
        "{}",
        body.position()
    );
    assert_eq!(body.linear_velocity(), Vector3::zeros());
    assert_eq!(body.angular_velocity(), Vector3::zeros());
    // Asleep, it does not move at all.
    let before = body.position();
    steps(&mut world, 1.0);
    assert_eq!(world.body("box").unwrap().position(), before);

    let mut awake = World::builder()
        .body(floor())
        .body(unit_cube("box", [0.0, 0.0, 5.0]))
        .build()
        .unwrap();
    for _ in 0..(6.0 / DT) as usize {
        awake.step(DT).unwrap();
        assert!(!asleep(&awake, "box"), "asleep with sleeping off");
    }
}

/// Jolt's `TestPhysicsActivateDuringStep`: ten touching unit boxes in a row, asleep without
/// gravity; the leftmost is sent right at 500 m/s (8 m a step). The whole row wakes in that
/// step and is pushed, in order: no box passes through its neighbour.
#[test]
fn a_sleeping_row_wakes_in_the_step_it_is_hit() {
    let mut builder = World::builder().gravity([0.0; 3]).settings(sleepy());
    for i in 0..10 {
        builder = builder.body(unit_cube(&format!("box {i}"), [i as f64, 0.0, 0.0]));
    }
    let mut world = builder.build().unwrap();
    steps(&mut world, 1.0);
    assert!(world.bodies().iter().all(|b| b.is_asleep()));
    let first = world.bodies()[0].id();
    world.set_velocity(first, [500.0, 0.0, 0.0]).unwrap();
    world.step(DT).unwrap();
    let x: Vec<f64> = world.bodies().iter().map(|b| b.position().x).collect();
    for (i, body) in world.bodies().iter().enumerate() {
        assert!(!body.is_asleep(), "box {i} still asleep");
        assert!(body.position().x > i as f64, "box {i} did not move right");
    }
    for pair in x.windows(2) {
        assert!(
            pair[0] < pair[1],
            "a box passed through its neighbour: {x:?}"
        );
    }
}

/// Islands do not join through the floor: of two cubes far apart, the one pushed along the
/// floor stays awake while the other sleeps.
#[test]
fn cubes_on_a_shared_floor_sleep_apart() {
    let mut world = World::builder()
        .settings(sleepy())
        .body(floor())
        .body(unit_cube("still", [0.0, 0.0, 0.5]))
        .body(unit_cube("pushed", [10.0, 10.0, 0.5]))
        .build()
        .unwrap();
    let pushed = world.body("pushed").unwrap().id();
    for _ in 0..(2.0 / DT) as usize {
        // 10 N along a diagonal, beyond μmg = 4.9 N: it keeps sliding.
        world.apply_force(pushed, [7.07, 7.07, 0.0]).unwrap();
        world.step(DT).unwrap();
    }
    assert!(asleep(&world, "still"));
    assert!(!asleep(&world, "pushed"));
}

/// Two stacked cubes asleep; a ball dropped on the top one wakes both (their island) in the
/// step it lands, and the ball's blow moves them.
#[test]
fn a_landing_body_wakes_the_island_it_hits() {
    let mut world = sleeping_stack();
    assert!(asleep(&world, "bottom") && asleep(&world, "top"));
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.2))
                .name("ball")
                .mass(5.0)
                .position([0.3, 0.2, 2.5]),
        )
        .unwrap();
    let rest = world.body("bottom").unwrap().position();
    let mut woke = false;
    for _ in 0..(1.0 / DT) as usize {
        world.step(DT).unwrap();
        let touching = world.contacts().any(|c| {
            let ids = [c.body_a.0, c.body_b.0].map(|k| world.bodies()[k].id());
            ids.contains(&ball)
        });
        if touching {
            woke = !asleep(&world, "bottom") && !asleep(&world, "top");
            break;
        }
        assert!(asleep(&world, "bottom"), "woke before the ball landed");
    }
    assert!(woke, "the island slept through the landing");
    steps(&mut world, 0.1);
    assert_ne!(world.body("bottom").unwrap().position(), rest);
}

/// Removing the bottom of a sleeping stack wakes the cube on it, which falls to the floor.
#[test]
fn removing_the_support_wakes_what_rests_on_it() {
    let mut world = sleeping_stack();
    assert!(asleep(&world, "top"));
    let bottom = world.body("bottom").unwrap().id();
    world.remove_body(bottom).unwrap();
    assert!(!asleep(&world, "top"));
    steps(&mut world, 1.0);
    let z = world.body("top").unwrap().position().z;
    assert!((z - 0.5).abs() < 0.01, "top cube at {z} m");
}

/// A cube on a kinematic platform creeping at 1 cm/s (below the 5 cm/s threshold) is carried,
/// never left asleep while the platform slides away under it.
#[test]
fn a_moving_platform_keeps_its_rider_awake() {
    let mut world = World::builder()
        .settings(sleepy())
        .body(
            BodyDesc::kinematic(Shape::cuboid([4.0, 4.0, 0.2]))
                .name("platform")
                .position([0.0, 0.0, 0.1])
                .velocity([0.007, 0.007, 0.0]),
        )
        .body(unit_cube("rider", [0.0, 0.0, 0.7]))
        .build()
        .unwrap();
    steps(&mut world, 3.0);
    assert!(!asleep(&world, "rider"));
    let (rider, platform) = (
        world.body("rider").unwrap(),
        world.body("platform").unwrap(),
    );
    let carried = rider.position().xy() - platform.position().xy();
    assert!(carried.norm() < 1e-3, "left behind by {carried}");
}

/// Every control call on a sleeping body wakes it; an impulse then moves it.
#[test]
fn a_control_call_wakes_a_sleeping_body() {
    let mut world = World::builder()
        .settings(sleepy())
        .body(floor())
        .body(unit_cube("cube", [0.0, 0.0, 0.5]))
        .build()
        .unwrap();
    let cube: BodyId = world.body("cube").unwrap().id();
    type Call = fn(&mut World, BodyId) -> Result<(), tatami_world::WorldError>;
    let calls: [(&str, Call); 5] = [
        ("apply_impulse", |w, id| {
            w.apply_impulse(id, [0.0, 0.0, 0.0])
        }),
        ("apply_force", |w, id| w.apply_force(id, [0.0, 0.0, 0.0])),
        ("set_velocity", |w, id| w.set_velocity(id, [0.0, 0.0, 0.0])),
        ("set_position", |w, id| {
            let p = w.body_by_id(id).unwrap().position();
            w.set_position(id, p)
        }),
        ("set_rotation", |w, id| {
            w.set_rotation(id, UnitQuaternion::identity())
        }),
    ];
    for (name, call) in calls {
        steps(&mut world, 1.0);
        assert!(asleep(&world, "cube"), "not asleep before {name}");
        call(&mut world, cube).unwrap();
        assert!(!asleep(&world, "cube"), "{name} did not wake it");
    }
    steps(&mut world, 1.0);
    world.apply_impulse(cube, [1.0, 1.0, 0.0]).unwrap();
    world.step(DT).unwrap();
    assert!(world.body("cube").unwrap().linear_velocity().norm() > 0.5);
}

/// A body does not fall asleep pressed into another beyond the slop: asleep, the position pass
/// would never push it out. A cube created 20 mm into the floor is at rest from the start while
/// the pass pushes it out a tenth of the excess a step: it slept after the 0.5 s of rest, still
/// 2.76 mm deep, for good. It must not sleep until within 0.5 mm of the slop (2 mm), and then
/// does.
#[test]
fn a_body_pressed_in_beyond_the_slop_sleeps_only_once_pushed_out() {
    let mut world = World::builder()
        .settings(sleepy())
        .body(floor())
        .body(unit_cube("cube", [0.0, 0.0, 0.48]))
        .build()
        .unwrap();
    let depth = |world: &World| world.contacts().map(|c| c.depth()).fold(0.0, f64::max);
    let mut slept_at = None;
    for step in 0..300 {
        world.step(DT).unwrap();
        if asleep(&world, "cube") && slept_at.is_none() {
            slept_at = Some((step, depth(&world)));
        }
    }
    let (step, deepest) = slept_at.expect("the cube sleeps within 5 s");
    assert!(
        deepest <= 0.0025,
        "fell asleep {deepest} m deep at step {step}"
    );
    assert!(asleep(&world, "cube"));
    assert!(depth(&world) <= 0.0025, "{} m deep asleep", depth(&world));
}
