//! Whatever the default settings do to hold contacts must not add energy: random scenes of
//! boxes, spheres, cylinders and hulls dropped on a floor, none overlapping at the start, never
//! exceed their initial energy.
//!
//! On these scenes speculative contacts land every body at depth zero, so no penetration push
//! acts at all: a stiff velocity bias (rate 1, no slop) and the old shock pass gain nothing here
//! either. The test guards the contact and integration stages; what a push does to bodies that
//! start overlapping is `overlap_recovery.rs`'s.

mod common;

use common::turned;
use tatami_world::dropped::{DROP_STEPS, dropped_scene};

/// Scenes tried (the experiments run more).
const SCENES: u64 = 200;
/// Allowed gain, as a fraction of the initial energy: 0.1%. The
/// free-rotation step's energy error is third order in dt (1e-5 relative a step at most here)
/// and no stabilisation may add more.
const GAIN: f64 = 1e-3;

#[test]
fn random_dropped_scenes_never_gain_energy() {
    let mut worst = (0.0_f64, 0);
    for seed in 0..SCENES {
        let scene = dropped_scene(seed);
        let mut world = scene.world().unwrap();
        let start = world.total_energy();
        for step in 0..DROP_STEPS {
            world.step(scene.dt).unwrap();
            let gain = (world.total_energy() - start) / start.abs();
            if gain > worst.0 {
                worst = (gain, seed);
            }
            assert!(
                gain <= GAIN,
                "scene {seed}, step {step}: energy {:.4}% above its start",
                gain * 100.0
            );
        }
    }
    println!(
        "largest gain {:.2e} of the initial energy (scene {})",
        worst.0, worst.1
    );
}

/// The energy semi-implicit Euler keeps in free flight for `world`'s one dynamic body (the
/// second, after the floor) stepped by `dt` (J): the total, its kinetic part read at
/// `v + g dt / 2`, the velocity at the step's end (the body moves by `v`, which stands for the
/// step's middle).
fn kept_energy(world: &tatami_world::World, dt: f64) -> f64 {
    let body = &world.bodies()[1];
    let v = body.linear_velocity();
    let back = v + world.gravity() * (dt / 2.0);
    world.total_energy() + 0.5 * body.mass() * (back.norm_squared() - v.norm_squared())
}

/// A 0.3 m, 1 kg cube with restitution 0.9 (the floor's too) dropped from 1 m at 20 seeded
/// random turns, 3 s at 60 Hz, under every contact model, frictionless and with friction 0.5
/// and 1: each impact keeps at most 0.81 of the energy the approach brings, so the energy
/// never comes back up to where it started. The energy read is the one the integrator keeps
/// in free flight, kinetic at `v + g dt / 2`, the velocity at the step's end (semi-implicit
/// Euler moves a body by `v`, which stands for the step's middle): the plain total swings by
/// `v g dt / 2` about it (up to 4% of the drop's energy at the floor), which would hide a gain
/// or fake one.
///
/// Before the landing speed was taken at the centroid of the points that land, every landed
/// point bounced at the fastest one's speed: a face coming down tilted and turning bounced
/// whole at its fastest corner's, and the cube rose to 1.27 times its starting energy (face
/// model) and 1.13 (vertex and patch). Before the bounce was scaled by the effective masses
/// where the pair met and where it bounces, a face or edge bounced at the speed its corner
/// met at, with the corner's energy times the ratio of their effective masses: frictionless,
/// the cube rose to 1.43 (vertex, patch) and 2.61 (face) times its energy.
#[test]
fn a_bouncy_cube_tumbling_on_a_floor_never_gains_energy() {
    use tatami_world::dropped::Random;
    use tatami_world::{BodyDesc, ContactModel, Shape, World};
    const DT: f64 = 1.0 / 60.0;
    let kept = |world: &World| kept_energy(world, DT);
    for friction in [0.0, 0.5, 1.0] {
        let mut random = Random::new(17);
        for start in 0..20 {
            let turn = turned(&mut random);
            for model in [
                ContactModel::Vertex,
                ContactModel::Patch,
                ContactModel::Face,
            ] {
                let mut world = World::builder()
                    .model(model)
                    .body(
                        BodyDesc::fixed(Shape::cuboid([20.0, 20.0, 1.0]))
                            .position([0.0, 0.0, -0.5])
                            .friction(friction)
                            .restitution(0.9),
                    )
                    .body(
                        BodyDesc::dynamic(Shape::cuboid([0.3; 3]))
                            .mass(1.0)
                            .friction(friction)
                            .restitution(0.9)
                            .position([0.0, 0.0, 1.0])
                            .rotation(turn),
                    )
                    .build()
                    .expect("a valid scene");
                let dropped = kept(&world);
                for step in 0..180 {
                    world.step(DT).expect("a step");
                    let energy = kept(&world);
                    // Free flight keeps it to rounding (a few 1e-15 of it a step).
                    assert!(
                        energy <= dropped * (1.0 + 1e-12),
                        "{model:?}, friction {friction}, start {start}, step {step}: {energy} J, \
                         dropped with {dropped} J"
                    );
                }
            }
        }
    }
}

/// Two 0.3 m, 1 kg cubes with restitution 0.9 and 1 thrown at each other along a diagonal
/// at 5 m/s each, no gravity, from 20 seeded random turns, under the face model: no impact
/// gives back more than the approach brought, so their kinetic energy never exceeds what they
/// were thrown with. Before the bounce handed on was read off the step's own bounce (it was
/// read off the contact, which held the last step's, or none when found afresh), a pair
/// bounced, handed its landing on again and bounced once more: they parted with up to 1.44
/// and 1.75 times their energy.
#[test]
fn bouncy_cubes_thrown_at_each_other_never_gain_energy() {
    use nalgebra::{UnitQuaternion, Vector3};
    use tatami_world::dropped::Random;
    use tatami_world::{BodyDesc, Shape, World};
    let direction = Vector3::new(1.0, 2.0, 2.0) / 3.0;
    for restitution in [0.9, 1.0] {
        let mut random = Random::new(17);
        for start in 0..20 {
            let (turn_a, turn_b) = (turned(&mut random), turned(&mut random));
            let cube = |at: f64, turn: UnitQuaternion<f64>| {
                BodyDesc::dynamic(Shape::cuboid([0.3; 3]))
                    .mass(1.0)
                    .restitution(restitution)
                    .position((direction * at).into())
                    .rotation(turn)
                    .velocity((direction * (-at.signum() * 5.0)).into())
            };
            let mut world = World::builder()
                .gravity([0.0; 3])
                .body(cube(-0.6, turn_a))
                .body(cube(0.6, turn_b))
                .build()
                .expect("a valid scene");
            let kinetic =
                |world: &World| -> f64 { world.bodies().iter().map(|b| b.kinetic_energy()).sum() };
            let thrown = kinetic(&world);
            for step in 0..60 {
                world.step(1.0 / 60.0).expect("a step");
                let energy = kinetic(&world);
                assert!(
                    energy <= thrown,
                    "e = {restitution}, start {start}, step {step}: {energy} J, thrown with {thrown} J"
                );
            }
        }
    }
}

/// Cylinders (0.15 m radius, 0.3 m long) and 10-point hulls (`mixed_shape`'s, about 1 m
/// across), 1 kg, with restitution 0.95 and 1 (the floor's too), dropped from 1 m at 20 seeded
/// random turns, 3 s at 60 Hz, under every contact model, frictionless and with friction 0.5
/// and 1: the energy the integrator keeps in free flight (as in the cube's test above) never
/// rises above the drop's. With restitution 0.95 to rounding; with 1 by at most 0.1%: bounces
/// that give back all their landings took leave no margin for the free-rotation step's own
/// energy error (third order in dt), which a hull spinning fast between bounces adds up to
/// 2.2e-4 of its energy in a few steps of flight, nor for the potential energy of a push out
/// of an overlap a landing left. Before each bounce was held to what its landing took
/// (`bounce_guard.rs`), and before the points that bounce were read as the support's alone
/// (landing points, whose rows do not bounce at the speed handed on, made the normal cap
/// count energy no row gave back), they rose to 1.061 (0.95, frictionless) and 1.37 (1)
/// times it: bounced off a rim or a corner, friction's reaction at the points that stick
/// turned spin into lift, which the cap, reading the normal alone, did not count.
#[test]
fn bouncy_cylinders_and_hulls_never_gain_energy() {
    use tatami_world::dropped::{Random, mixed_shape};
    use tatami_world::{BodyDesc, ContactModel, Shape, World};
    const DT: f64 = 1.0 / 60.0;
    let kept = |world: &World| kept_energy(world, DT);
    let mut worst = (0.0_f64, String::new());
    for (restitution, bound) in [(0.95, 1e-12), (1.0, 1e-3)] {
        for friction in [0.0, 0.5, 1.0] {
            for model in [
                ContactModel::Vertex,
                ContactModel::Patch,
                ContactModel::Face,
            ] {
                let mut random = Random::new(31);
                for start in 0..20 {
                    let shape = if start % 2 == 0 {
                        Shape::cylinder(0.15, 0.3)
                    } else {
                        mixed_shape(&mut random, 3)
                    };
                    let mut world = World::builder()
                        .model(model)
                        .body(
                            BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 1.0]))
                                .position([0.0, 0.0, -0.5])
                                .friction(friction)
                                .restitution(restitution),
                        )
                        .body(
                            BodyDesc::dynamic(shape)
                                .mass(1.0)
                                .friction(friction)
                                .restitution(restitution)
                                .position([0.0, 0.0, 1.0])
                                .rotation(turned(&mut random)),
                        )
                        .build()
                        .expect("a valid scene");
                    let dropped = kept(&world);
                    for step in 0..180 {
                        world.step(DT).expect("a step");
                        let gain = kept(&world) / dropped - 1.0;
                        let case = format!(
                            "e = {restitution}, friction {friction}, {model:?}, start {start}, \
                             step {step}"
                        );
                        if gain > worst.0 {
                            worst = (gain, case.clone());
                        }
                        assert!(gain <= bound, "{case}: {gain:.2e} above the drop's energy");
                    }
                }
            }
        }
    }
    println!("largest gain {:.2e} ({})", worst.0, worst.1);
}
