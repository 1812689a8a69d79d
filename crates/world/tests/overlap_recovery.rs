//! Bodies created overlapping separate gently. By default a contact's whole push is removed by a
//! position pass of its own (split impulses, see `World::step`), which adds no velocity, and no
//! body is moved apart faster than `max_depenetration_speed` (1 m/s by default).

mod common;

use common::{rotation, six_point_hull};
use nalgebra::{UnitQuaternion, Vector3};
use tatami_world::{BodyDesc, ContactModel, Shape, World, WorldBuilder};

/// Speed of the world's fastest body (m/s).
fn fastest(world: &World) -> f64 {
    world
        .bodies()
        .iter()
        .map(|b| b.linear_velocity().norm())
        .fold(0.0, f64::max)
}

/// A fixed 60 m × 60 m floor whose top is z = 0.
fn wide_floor() -> BodyDesc {
    BodyDesc::fixed(Shape::cuboid([60.0, 60.0, 2.0]))
        .name("floor")
        .position([0.0, 0.0, -1.0])
}

/// A 1 m, 1 kg cube.
fn unit_cube(position: [f64; 3]) -> BodyDesc {
    BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
        .mass(1.0)
        .position(position)
}

/// 500 unit cubes at seeded random poses with centres in a 3 m box (z from 0.5 m to 3.5 m).
fn overlapping_cubes(builder: WorldBuilder) -> World {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut builder = builder;
    for _ in 0..500 {
        let position = [3.0 * next() - 1.5, 3.0 * next() - 1.5, 0.5 + 3.0 * next()];
        let axis = [next() - 0.5, next() - 0.5, next() - 0.5];
        builder = builder.body(unit_cube(position).rotation(rotation(axis, 360.0 * next())));
    }
    builder.build().unwrap()
}

/// Two unit cubes created at the same place on the floor separate, none faster than 5 m/s
/// (with the bias in the velocities they left at 5 m/s: 0.1 × 0.5 m / 0.01 s).
#[test]
fn two_coincident_cubes_separate_gently() {
    let mut world = World::builder()
        .body(wide_floor())
        .body(unit_cube([0.0, 0.0, 0.5]))
        .body(unit_cube([0.0, 0.0, 0.5]))
        .build()
        .unwrap();
    let mut worst: f64 = 0.0;
    for _ in 0..300 {
        world.step(0.01).unwrap();
        worst = worst.max(fastest(&world));
    }
    let [_, a, b] = world.bodies() else {
        unreachable!()
    };
    let apart = (a.centre_of_mass() - b.centre_of_mass()).norm();
    assert!(worst < 5.0, "a cube reached {worst} m/s");
    assert!(apart > 0.95, "still overlapping: centres {apart} m apart");
}

/// Without gravity, 500 overlapping cubes separate with none faster than 5 m/s (with the whole
/// push in the velocities they reached 53 m/s; by default the push moves positions only and
/// none gains any speed, while 0.2 m/s of it in the velocity solve gave 1.4 m/s). No body is
/// pushed faster than 1 m/s, so the heap's surface spreads at most that fast: from 1.5 m to the
/// ~5 m radius 500 m³ needs takes about 4 s. When the last of the 27 000 initial overlaps
/// (1.2 m) falls below 5 cm depends on the heap: between 5.3 and 6.6 s on twelve seeded heaps
/// (median 5.7 s), so the test waits 8 s.
#[test]
fn five_hundred_overlapping_cubes_separate_without_explosion() {
    let mut world = overlapping_cubes(World::builder().gravity([0.0; 3]));
    let deepest = |w: &World| w.contacts().map(|c| c.depth()).fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    world.step(0.01).unwrap();
    let start = deepest(&world);
    for _ in 0..800 {
        world.step(0.01).unwrap();
        worst = worst.max(fastest(&world));
    }
    let end = deepest(&world);
    println!("deepest overlap {start:.3} m → {end:.4} m, fastest {worst:e} m/s");
    assert!(worst < 5.0, "a cube reached {worst} m/s");
    assert!(
        start > 1.0 && end < 0.05,
        "overlap {start} m → {end} m after 8 s"
    );
}

/// With gravity on a 60 m floor none leaves the floor (with the bias in the velocities 430 of
/// them did), and no body is faster than a fall from the highest point any body reached, plus
/// the 1 m/s a push may give. 500 m³ of cubes must settle into a heap 5–7 m tall (a cone at
/// μ = 0.5's 27° slope), and cubes that slide or fall off its top reach 8 m/s under gravity;
/// the 5 m/s bound holds for what the recovery itself gives (the test above).
#[test]
fn five_hundred_overlapping_cubes_stay_on_the_floor() {
    let mut world = overlapping_cubes(World::builder().body(wide_floor()));
    let (mut worst, mut peak): (f64, f64) = (0.0, 0.0);
    for _ in 0..300 {
        world.step(0.01).unwrap();
        worst = worst.max(fastest(&world));
        let top = world.bodies().iter().map(|b| b.centre_of_mass().z);
        peak = peak.max(top.fold(0.0, f64::max));
    }
    let off_floor = world
        .bodies()
        .iter()
        .filter(|b| !b.is_fixed())
        .filter(|b| {
            let c = b.centre_of_mass();
            c.x.abs() > 30.0 || c.y.abs() > 30.0 || c.z < 0.0
        })
        .count();
    println!("fastest {worst:.2} m/s, highest centre {peak:.2} m");
    assert_eq!(off_floor, 0, "{off_floor} cubes left the floor");
    // A fall from the highest centre to a resting one (0.5 m), plus the 1 m/s a push may add.
    let free_fall = (2.0 * 9.8 * (peak - 0.5)).sqrt() + 1.0;
    assert!(
        worst < free_fall,
        "{worst:.2} m/s; a fall from {peak:.2} m gives {free_fall:.2}"
    );
}

/// A 3 cm, six-point hull created 14 mm into the floor, tilted so that one vertex is deepest
/// and two more are below the floor's surface beside it, at 60 Hz under every model: pushed out
/// to the slop (2 mm, with 0.1 mm to spare for the position pass's settling) within a second,
/// and at rest. The contact's touching feature was the deepest vertex alone; the body turned
/// about it, the vertices beside it sank further, the next step's feature was the face they
/// made, and the vertex and patch models rocked the hull 14–19 mm deep for good (it came out
/// of a stack of three such hulls dropped onto each other). A pair in deeper than its margin
/// now has the vertices that stand back from its feature by less than its depth as landing
/// points.
#[test]
fn a_hull_created_deep_in_the_floor_on_a_vertex_comes_out() {
    let size = 0.03;
    let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.716, -1.338, 0.487));
    for model in ContactModel::ALL {
        let mut world = World::builder()
            .model(model)
            .body(wide_floor())
            .body(
                BodyDesc::dynamic(six_point_hull(size))
                    .density(1000.0)
                    .position([0.0, 0.0, -0.0041])
                    .rotation(tilt),
            )
            .build()
            .unwrap();
        // The contact as created, before any step moves the hull.
        world.prepare_step(1.0 / 60.0).unwrap();
        let depth = |world: &World| {
            world
                .contacts()
                .map(|c| c.depth())
                .fold(f64::NEG_INFINITY, f64::max)
        };
        assert!(
            depth(&world) > 0.013,
            "{model:?}: created {} m deep",
            depth(&world)
        );
        let mut deepest: f64 = 0.0;
        for step in 0..120 {
            world.step(1.0 / 60.0).unwrap();
            if step >= 60 {
                deepest = deepest.max(depth(&world));
            }
        }
        println!(
            "{model:?}: {:.2} mm deep over the second second",
            deepest * 1e3
        );
        assert!(deepest < 2.1e-3, "{model:?}: {deepest} m deep");
        assert!(fastest(&world) < 1e-3, "{model:?}: {} m/s", fastest(&world));
    }
}
