//! Driving a world: kinematic bodies, forces, torques, impulses, removal and the contact-wrench
//! read-out, against closed forms. Every scene is turned off the contact frame's axes.

mod common;

use common::{G, rotation};
use nalgebra::{UnitQuaternion, Vector3};
use tatami_world::{BodyDesc, BodyKind, ContactModel, Shape, World, WorldError, WorldSettings};

const DT: f64 = 0.01;

/// A 20 m fixed floor whose top is z = 0.
fn floor() -> BodyDesc {
    BodyDesc::fixed(Shape::cuboid([20.0, 20.0, 1.0]))
        .name("floor")
        .position([0.0, 0.0, -0.5])
}

/// A unit cube of 1 kg resting on the floor at `(x, y)`, turned by `yaw` degrees.
fn unit_cube(name: &str, x: f64, y: f64, yaw: f64) -> BodyDesc {
    BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
        .name(name)
        .mass(1.0)
        .position([x, y, 0.5])
        .rotation(rotation([0.0, 0.0, 1.0], yaw))
}

/// An empty world with the default settings but `model`.
fn empty_world(model: ContactModel) -> World {
    let settings = WorldSettings {
        model,
        ..WorldSettings::default()
    };
    World::builder().settings(settings).build().unwrap()
}

fn steps(world: &mut World, count: usize) {
    for _ in 0..count {
        world.step(DT).unwrap();
    }
}

/// A kinematic paddle moving at 1 m/s along a diagonal pushes a resting cube ahead of it: the
/// paddle is exactly where its velocity says (contacts do not move it), and the cube, pushed
/// from behind, keeps its face against the paddle's at the paddle's speed.
#[test]
fn a_kinematic_pusher_pushes_a_resting_cube_ahead_of_it() {
    let heading = Vector3::new(1.0, 1.0, 0.0).normalize();
    let yaw = 45.0;
    let start: Vector3<f64> = heading * -0.65;
    let mut world = World::builder().build().unwrap();
    world.add_body(floor()).unwrap();
    let cube = world.add_body(unit_cube("cube", 0.0, 0.0, yaw)).unwrap();
    let paddle = world
        .add_body(
            BodyDesc::kinematic(Shape::cuboid([0.2, 2.0, 0.9]))
                .name("paddle")
                .position([start.x, start.y, 0.5])
                .rotation(rotation([0.0, 0.0, 1.0], yaw))
                .velocity(heading.into()),
        )
        .unwrap();
    let seconds = 2.0;
    steps(&mut world, 200);
    let paddle_body = world.body_by_id(paddle).unwrap();
    assert_eq!(paddle_body.kind(), BodyKind::Kinematic);
    let travelled = paddle_body.position().coords - Vector3::new(start.x, start.y, 0.5);
    // Exact up to the sum of 200 steps' round-off.
    assert!(
        (travelled - heading * seconds).norm() < 1e-12,
        "{travelled}"
    );
    let cube_body = world.body_by_id(cube).unwrap();
    // Face to face: the paddle's half width plus the cube's, 0.6 m ahead; 1 cm for the
    // contact's slop and the speculative gap.
    let ahead = (cube_body.centre_of_mass() - paddle_body.centre_of_mass()).dot(&heading);
    assert!((ahead - 0.6).abs() < 0.01, "cube {ahead} m ahead");
    let sideways = (cube_body.centre_of_mass() - paddle_body.centre_of_mass())
        .xy()
        .perp(&heading.xy());
    assert!(sideways.abs() < 1e-3, "pushed straight, {sideways} m aside");
    let speed = cube_body.linear_velocity().dot(&heading);
    assert!((speed - 1.0).abs() < 0.02, "cube at {speed} m/s");
}

/// A constant horizontal force above μmg, along a diagonal, accelerates a cube at
/// `(F − μmg)/m` along the force (the closed form of Coulomb sliding).
#[test]
fn a_force_above_mu_m_g_accelerates_a_cube_at_the_closed_form() {
    for model in ContactModel::ALL {
        let mut world = empty_world(model);
        world.add_body(floor()).unwrap();
        let mass = 2.0;
        let cube = world
            .add_body(unit_cube("cube", 0.0, 0.0, 30.0).mass(mass))
            .unwrap();
        steps(&mut world, 20);
        let direction = Vector3::new(3.0_f64.sqrt(), 1.0, 0.0) / 2.0;
        let force = 2.0 * 0.5 * mass * G;
        let v0 = world.body_by_id(cube).unwrap().linear_velocity();
        let seconds = 1.0;
        for _ in 0..100 {
            world.apply_force(cube, direction * force).unwrap();
            world.step(DT).unwrap();
        }
        let dv = world.body_by_id(cube).unwrap().linear_velocity() - v0;
        let expected = (force - 0.5 * mass * G) / mass * seconds;
        // The first step turns static friction into kinetic: a step of slack, 1%.
        let along = dv.dot(&direction);
        assert!(
            (along - expected).abs() < 0.01 * expected,
            "{model:?}: Δv {along} m/s, closed form {expected}"
        );
        let across = (dv - direction * along).norm();
        assert!(across < 1e-6 * expected, "{model:?}: bent by {across} m/s");
    }
}

/// A torque about a principal axis of a free, turned box spins it at `τ t / I` about that
/// axis (no gyroscopic term while ω stays on the axis).
#[test]
fn a_torque_spins_a_free_body_at_tau_over_i() {
    let turn = rotation([1.0, 2.0, 3.0], 40.0);
    let size = [1.0, 2.0, 3.0];
    let mass = 3.0;
    let mut world = World::builder().gravity([0.0; 3]).build().unwrap();
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(size))
                .mass(mass)
                .rotation(turn),
        )
        .unwrap();
    // The box's moment about its body y axis: m (a² + c²) / 12.
    let inertia = mass * (size[0] * size[0] + size[2] * size[2]) / 12.0;
    let axis = turn * Vector3::y();
    let torque = 0.7;
    let count = 150;
    for _ in 0..count {
        world.apply_torque(body, axis * torque).unwrap();
        world.step(DT).unwrap();
    }
    let w = world.body_by_id(body).unwrap().angular_velocity();
    let expected = torque * count as f64 * DT / inertia;
    assert!(
        (w - axis * expected).norm() < 1e-9 * expected,
        "ω {w}, closed form {expected} about {axis}"
    );
    // And a force at a point: the force's moment about the centre of mass turns the box too.
    let before = world.body_by_id(body).unwrap().angular_velocity();
    let centre = world.body_by_id(body).unwrap().centre_of_mass();
    let arm = turn * Vector3::new(0.0, 0.0, 1.0);
    let push = turn * Vector3::new(0.4, 0.0, 0.0);
    world
        .apply_force_at_point(body, push, centre + arm)
        .unwrap();
    world.step(DT).unwrap();
    let dw = world.body_by_id(body).unwrap().angular_velocity() - before;
    // r × F = z × 0.4 x = 0.4 y (body axes): about the same principal axis.
    let expected = 0.4 * DT / inertia;
    assert!((dw - axis * expected).norm() < 1e-9 * expected, "Δω {dw}");
}

/// An impulse changes a free body's velocity by `J/m` at once; at a point off the centre it
/// also turns it by `I⁻¹ (r × J)`.
#[test]
fn an_impulse_changes_the_velocity_at_once() {
    let mut world = World::builder().gravity([0.0; 3]).build().unwrap();
    let ball = world
        .add_body(BodyDesc::dynamic(Shape::sphere(0.5)).mass(2.0))
        .unwrap();
    world.apply_impulse(ball, [1.0, -2.0, 0.5]).unwrap();
    let v = world.body_by_id(ball).unwrap().linear_velocity();
    assert!((v - Vector3::new(0.5, -1.0, 0.25)).norm() < 1e-15);
    world
        .apply_impulse_at_point(ball, [0.0, 1.0, 0.0], [0.5, 0.0, 0.0])
        .unwrap();
    // I = 2/5 m r² = 0.2; r × J = (0.5, 0, 0) × (0, 1, 0) = (0, 0, 0.5).
    let w = world.body_by_id(ball).unwrap().angular_velocity();
    assert!((w - Vector3::new(0.0, 0.0, 2.5)).norm() < 1e-12, "{w}");
}

/// The force sensor: a cube resting off-centre, turned, on a larger dynamic box that rests on
/// the floor. The cube's contact carries its weight through a centre of pressure under its
/// centre of mass; the box's carries both weights through a point under their common centre
/// of mass — for every model, within 1e-6 (the warm-started solver at rest converges far
/// below that).
#[test]
fn the_wrench_read_out_balances_the_weights_at_the_centres_of_mass() {
    for model in ContactModel::ALL {
        let mut world = empty_world(model);
        let floor = world.add_body(floor()).unwrap();
        let (big_mass, small_mass) = (5.0, 1.5);
        let slab = world
            .add_body(
                BodyDesc::dynamic(Shape::cuboid([3.0, 2.5, 0.5]))
                    .name("slab")
                    .mass(big_mass)
                    .position([0.3, -0.2, 0.25])
                    .rotation(rotation([0.0, 0.0, 1.0], 20.0)),
            )
            .unwrap();
        let cube = world
            .add_body(
                BodyDesc::dynamic(Shape::cuboid([0.6, 0.6, 0.6]))
                    .name("cube")
                    .mass(small_mass)
                    .position([1.0, 0.3, 0.8])
                    .rotation(rotation([0.0, 0.0, 1.0], -35.0)),
            )
            .unwrap();
        steps(&mut world, 300);
        let wrenches: Vec<_> = world.contact_wrenches().collect();
        assert_eq!(wrenches.len(), 2, "{model:?}");
        let centre = |id| world.body_by_id(id).unwrap().centre_of_mass();
        for w in &wrenches {
            let mut pair = [w.body_a, w.body_b];
            pair.sort();
            let (weight, under) = if pair == [slab, cube] {
                (small_mass * G, centre(cube).coords.xy())
            } else {
                assert_eq!(pair, [floor, slab], "{model:?}");
                let both = (centre(cube).coords * small_mass + centre(slab).coords * big_mass)
                    / (small_mass + big_mass);
                ((small_mass + big_mass) * G, both.xy())
            };
            assert!(
                (w.normal_force - weight).abs() < 1e-6 * weight,
                "{model:?}: normal force {} N, weight {weight} N",
                w.normal_force
            );
            let miss = (w.centre_of_pressure.coords.xy() - under).norm();
            assert!(miss < 1e-6, "{model:?}: centre of pressure {miss} m off");
            assert!(
                w.force.xy().norm() < 1e-6 * weight,
                "{model:?}: {}",
                w.force
            );
            assert!(w.torque.norm() < 1e-6 * weight, "{model:?}: {}", w.torque);
            assert_eq!(w.support.len(), 4, "{model:?}: a square face on a face");
            assert!(w.normal.z.abs() > 1.0 - 1e-12, "{model:?}: {}", w.normal);
        }
    }
}

/// Removing the middle cube of a stack of three mid-run: no contact names it or outlives it,
/// the handles of the others still work, and the top cube lands on the bottom one.
#[test]
fn removing_a_body_leaves_no_stale_contact() {
    let mut world = World::builder().build().unwrap();
    let floor = world.add_body(floor()).unwrap();
    let ids: Vec<_> = (0..3)
        .map(|k| {
            let desc = unit_cube(&format!("c{k}"), 0.1 * k as f64, 0.0, 10.0 * k as f64)
                .position([0.1 * k as f64, 0.0, 0.5 + k as f64]);
            world.add_body(desc).unwrap()
        })
        .collect();
    steps(&mut world, 50);
    assert_eq!(world.contacts().count(), 3);
    let removed = world.remove_body(ids[1]).unwrap();
    assert_eq!(removed.name(), "c1");
    assert_eq!(world.bodies().len(), 3);
    assert_eq!(world.index_of(ids[1]), Err(WorldError::UnknownBody(ids[1])));
    assert_eq!(world.index_of(ids[2]), Ok(2));
    let named = |world: &World| -> Vec<_> {
        world
            .contact_wrenches()
            .map(|w| (w.body_a.min(w.body_b), w.body_a.max(w.body_b)))
            .collect()
    };
    assert_eq!(
        named(&world),
        vec![(floor, ids[0])],
        "only floor–c0 is left"
    );
    assert!(world.apply_force(ids[1], [1.0, 0.0, 0.0]).is_err());
    steps(&mut world, 100);
    let mut pairs = named(&world);
    pairs.sort();
    assert_eq!(pairs, vec![(floor, ids[0]), (ids[0], ids[2])]);
    let top = world.body_by_id(ids[2]).unwrap().position();
    assert!(
        (top.z - 1.5).abs() < 0.01,
        "top cube on the bottom one: z = {}",
        top.z
    );
}

/// A kinematic target moves a body exactly there over one step, pushing what is in the way;
/// afterwards the body rests.
#[test]
fn a_kinematic_target_is_reached_in_one_step() {
    let mut world = World::builder().build().unwrap();
    world.add_body(floor()).unwrap();
    let hand = world
        .add_body(BodyDesc::kinematic(Shape::cuboid([0.4, 0.4, 0.4])).position([0.0, 0.0, 2.0]))
        .unwrap();
    let turn = rotation([0.0, 0.0, 1.0], 5.0);
    for k in 1..=20 {
        let target = [0.01 * k as f64, 0.0, 2.0];
        let heading = turn.powf(k as f64);
        world.set_kinematic_target(hand, target, heading).unwrap();
        world.step(DT).unwrap();
        let body = world.body_by_id(hand).unwrap();
        assert!((body.position() - nalgebra::Point3::from(target)).norm() < 1e-12);
        assert!(body.rotation().angle_to(&heading) < 1e-12);
    }
    world.step(DT).unwrap();
    let body = world.body_by_id(hand).unwrap();
    assert_eq!(
        body.linear_velocity(),
        Vector3::zeros(),
        "at rest after its target"
    );
    assert!((body.position().x - 0.2).abs() < 1e-12);
}

/// A moving kinematic platform carries a box resting on it: static friction moves the box with
/// it, without slipping.
#[test]
fn a_moving_platform_carries_a_box() {
    let velocity = Vector3::new(0.4, -0.3, 0.0);
    let mut world = World::builder().build().unwrap();
    let platform = world
        .add_body(
            BodyDesc::kinematic(Shape::cuboid([3.0, 3.0, 0.2]))
                .name("platform")
                .velocity(velocity.into()),
        )
        .unwrap();
    let cube = world
        .add_body(
            unit_cube("cube", 0.2, 0.1, 25.0)
                .position([0.2, 0.1, 0.6])
                .velocity(velocity.into()),
        )
        .unwrap();
    let offset = |world: &World| {
        world.body_by_id(cube).unwrap().position() - world.body_by_id(platform).unwrap().position()
    };
    steps(&mut world, 100);
    let start = offset(&world);
    steps(&mut world, 200);
    let slip = (offset(&world) - start).norm();
    assert!(slip < 1e-3, "the box slipped {slip} m on the platform");
    let v = world.body_by_id(cube).unwrap().linear_velocity();
    assert!((v - velocity).norm() < 1e-3, "box at {v}");
}

/// Every control call checks its body and its values: no NaN, no stale handle, no force on a
/// body that cannot take one, reaches a step.
#[test]
fn control_calls_reject_bad_input() {
    let mut world = World::builder().build().unwrap();
    let floor = world.add_body(floor()).unwrap();
    let paddle = world
        .add_body(BodyDesc::kinematic(Shape::sphere(0.1)).position([0.0, 0.0, 3.0]))
        .unwrap();
    let ball = world
        .add_body(BodyDesc::dynamic(Shape::sphere(0.2)).position([0.0, 0.0, 1.0]))
        .unwrap();
    let kind = |e: WorldError| matches!(e, WorldError::WrongKind { .. });
    let value = |e: WorldError| matches!(e, WorldError::InvalidBody { .. });
    assert!(kind(world.apply_force(floor, [1.0, 0.0, 0.0]).unwrap_err()));
    assert!(kind(
        world.apply_impulse(paddle, [1.0, 0.0, 0.0]).unwrap_err()
    ));
    assert!(kind(
        world.set_velocity(floor, [1.0, 0.0, 0.0]).unwrap_err()
    ));
    assert!(kind(
        world
            .set_kinematic_target(ball, [0.0; 3], UnitQuaternion::identity())
            .unwrap_err()
    ));
    assert!(value(
        world.apply_force(ball, [f64::NAN, 0.0, 0.0]).unwrap_err()
    ));
    assert!(value(
        world
            .apply_torque(ball, [f64::INFINITY, 0.0, 0.0])
            .unwrap_err()
    ));
    assert!(value(
        world.set_velocity(paddle, [1e9, 0.0, 0.0]).unwrap_err()
    ));
    assert!(value(
        world.set_position(ball, [1e9, 0.0, 0.0]).unwrap_err()
    ));
    assert!(value(
        world.apply_impulse(ball, [1e12, 0.0, 0.0]).unwrap_err()
    ));
    world.remove_body(ball).unwrap();
    assert_eq!(
        world.set_velocity(ball, [0.0; 3]),
        Err(WorldError::UnknownBody(ball))
    );
    assert!(world.remove_body(ball).is_err());
    // Nothing rejected reached the state.
    world.step(DT).unwrap();
    assert!(
        world
            .bodies()
            .iter()
            .all(|b| b.linear_velocity().iter().all(|x| x.is_finite()))
    );
}

fn example(name: &str) -> tatami_world::scene::Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    tatami_world::scene::Scene::load(&path).unwrap()
}

/// `scenes/paddle_sweep.json`: the turning kinematic paddle ends exactly where its velocities
/// take it, and has swept every box of the row ahead of its face.
#[test]
fn the_paddle_scene_sweeps_every_box_ahead() {
    let scene = example("paddle_sweep.json");
    let mut world = scene.world().unwrap();
    for _ in 0..scene.steps {
        world.step(scene.dt).unwrap();
    }
    let paddle = world.body("paddle").unwrap();
    let seconds = scene.steps as f64 * scene.dt;
    let start = nalgebra::Point3::new(-2.0, 0.0, 0.55);
    assert!((paddle.position() - (start + Vector3::x() * 1.2 * seconds)).norm() < 1e-9);
    let face = paddle.rotation() * Vector3::x();
    for k in 1..=5 {
        let cube = world.body(&format!("box {k}")).unwrap();
        let ahead = (cube.centre_of_mass() - paddle.centre_of_mass()).dot(&face);
        assert!(
            ahead > 0.15 + 0.3 - 0.01,
            "box {k} is {ahead} m ahead of the paddle"
        );
    }
}

/// `scenes/moving_platform.json`: the box dropped on the moving platform rides it — at the end
/// it is on top of it, moving with it.
#[test]
fn the_platform_scene_carries_the_box() {
    let scene = example("moving_platform.json");
    let mut world = scene.world().unwrap();
    for _ in 0..scene.steps {
        world.step(scene.dt).unwrap();
    }
    let platform = world.body("platform").unwrap();
    let cube = world.body("box").unwrap();
    let offset = cube.position() - platform.position();
    assert!((offset.z - 0.5).abs() < 0.01, "on top: {offset}");
    assert!(
        offset.xy().abs().max() < 1.5,
        "within the platform: {offset}"
    );
    let v = cube.linear_velocity() - platform.linear_velocity();
    assert!(v.norm() < 1e-3, "moving with it: {v}");
}

/// A body is fixed or kinematic, not both; `kinematic` is read from scenes.
#[test]
fn a_scene_body_is_fixed_or_kinematic_not_both() {
    let body = |extra: &str| {
        format!(r#"{{ "bodies": [ {{ "shape": {{ "sphere": {{ "radius": 1 }} }}{extra} }} ] }}"#)
    };
    let scene = tatami_world::scene::Scene::from_json(&body(r#", "kinematic": true"#)).unwrap();
    assert!(scene.world().unwrap().bodies()[0].is_kinematic());
    let error =
        tatami_world::scene::Scene::from_json(&body(r#", "kinematic": true, "fixed": true"#))
            .unwrap_err()
            .to_string();
    assert!(error.contains("not both"), "{error}");
}

/// A box 0.4 m wide, 0.3 m deep and 1 m tall, of 10 kg, on a floor with friction 1, pushed
/// along its width at the middle of its top edge (the force turned with the box each step):
/// it stays put while `F h < m g w / 2` and tips over on its edge past it, the centre of
/// pressure reaching the edge exactly there. At 1% under and over the threshold under every
/// model, the box turned 0.6 rad about the vertical and off the origin: 1% under, it turns by
/// under 1 mrad (measured 0 under the face model, 0.1 mrad under the patch model's); 1% over,
/// it falls on its side within 3 s. Friction (up to `μ m g`, five times the push) keeps it from
/// sliding.
#[test]
fn a_box_pushed_at_its_top_tips_over_past_the_closed_form_push() {
    let (wide, deep, tall, mass) = (0.4, 0.3, 1.0, 10.0);
    let threshold = mass * G * (wide / 2.0) / tall;
    let turn = rotation([0.0, 0.0, 1.0], 0.6f64.to_degrees());
    for model in ContactModel::ALL {
        for share in [0.99, 1.01] {
            let mut world = World::builder()
                .model(model)
                .gravity([0.0, 0.0, -G])
                .body(floor().friction(1.0))
                .body(
                    BodyDesc::dynamic(Shape::cuboid([wide, deep, tall]))
                        .mass(mass)
                        .friction(1.0)
                        .position([0.3, -0.2, tall / 2.0])
                        .rotation(turn),
                )
                .build()
                .unwrap();
            let id = world.bodies()[1].id();
            let mut tilt: f64 = 0.0;
            for _ in 0..300 {
                let body = world.body_by_id(id).unwrap();
                let top = body.position() + body.rotation() * Vector3::new(0.0, 0.0, tall / 2.0);
                let push = body.rotation() * Vector3::new(share * threshold, 0.0, 0.0);
                world.apply_force_at_point(id, push, top).unwrap();
                world.step(DT).unwrap();
                let up = world.body_by_id(id).unwrap().rotation() * Vector3::z();
                tilt = tilt.max(up.z.clamp(-1.0, 1.0).acos());
            }
            let case = format!("{model:?}, {share} of the threshold");
            if share < 1.0 {
                assert!(tilt < 1e-3, "{case}: tilted {tilt} rad");
            } else {
                assert!(tilt > 1.5, "{case}: tilted only {tilt} rad");
            }
        }
    }
}

/// A 2 kg block on a 5 kg one, pulled at the lower one's centre across a frictionless floor
/// for 1 s, with friction `μ` = 0.4 between the blocks: up to `F = μ g (m₁ + m₂)` they keep
/// together at `F / (m₁ + m₂)` (2% under it: the upper slips by micrometres, measured 0.4–12
/// µm); past it the upper slides at `μ g` and the lower runs ahead at `(F − μ m₁ g) / m₂`, the
/// speeds and the slip (`(a₂ − μ g) t² / 2`, as the integrator steps it) within 1% (5% over
/// it; measured within 0.01%). Every model, turned about the vertical.
#[test]
fn a_block_on_a_pulled_block_keeps_up_until_friction_gives() {
    let (upper, lower, mu) = (2.0, 5.0, 0.4);
    let limit = mu * G * (upper + lower);
    let turn = rotation([0.0, 0.0, 1.0], 40.0);
    for model in ContactModel::ALL {
        for share in [0.98, 1.05] {
            // Frictions average: the floor and the lower block have none, the upper twice μ.
            let mut world = World::builder()
                .model(model)
                .gravity([0.0, 0.0, -G])
                .body(floor().friction(0.0))
                .body(
                    BodyDesc::dynamic(Shape::cuboid([1.0, 0.6, 0.2]))
                        .mass(lower)
                        .friction(0.0)
                        .position([0.0, 0.0, 0.1])
                        .rotation(turn),
                )
                .body(
                    BodyDesc::dynamic(Shape::cuboid([0.3; 3]))
                        .mass(upper)
                        .friction(2.0 * mu)
                        .position([0.0, 0.0, 0.35])
                        .rotation(turn),
                )
                .build()
                .unwrap();
            let (pulled, carried) = (world.bodies()[1].id(), world.bodies()[2].id());
            let force = share * limit;
            let steps = (1.0 / DT).round() as usize;
            for _ in 0..steps {
                world
                    .apply_force(pulled, turn * Vector3::new(force, 0.0, 0.0))
                    .unwrap();
                world.step(DT).unwrap();
            }
            let t = steps as f64 * DT;
            let lower_body = world.body_by_id(pulled).unwrap();
            let upper_body = world.body_by_id(carried).unwrap();
            let slip = (upper_body.position() - lower_body.position()).xy().norm();
            let (v_lower, v_upper) = (
                lower_body.linear_velocity().norm(),
                upper_body.linear_velocity().norm(),
            );
            let case = format!("{model:?}, {share} of the limit");
            if share < 1.0 {
                let together = force / (upper + lower) * t;
                assert!(slip < 1e-4, "{case}: slipped {slip} m");
                assert!(
                    (v_lower / together - 1.0).abs() < 1e-3,
                    "{case}: {v_lower} m/s"
                );
                assert!(
                    (v_upper / together - 1.0).abs() < 1e-3,
                    "{case}: {v_upper} m/s"
                );
            } else {
                let a_lower = (force - mu * upper * G) / lower;
                // Semi-implicit Euler from rest: n steps move `a dt² n (n + 1) / 2`.
                let n = steps as f64;
                let expected_slip = (a_lower - mu * G) * DT * DT * n * (n + 1.0) / 2.0;
                assert!(
                    (v_lower / (a_lower * t) - 1.0).abs() < 0.01,
                    "{case}: {v_lower}"
                );
                assert!(
                    (v_upper / (mu * G * t) - 1.0).abs() < 0.01,
                    "{case}: {v_upper}"
                );
                assert!(
                    (slip / expected_slip - 1.0).abs() < 0.01,
                    "{case}: slipped {slip}"
                );
            }
        }
    }
}

/// Boxes on a kinematic platform whose velocity grows by `a dt` each step (friction 1 for the
/// tall box, 0.3 for the flat one; platform and box turned 29° about the vertical), at 60 Hz
/// with the defaults (two substeps for these boxes): a 20 × 30 × 100 cm box stays upright (to
/// 2 mrad; measured 0.8) at 97% of the tipping acceleration `g w / h` and tips at 103%; a 60 ×
/// 50 × 20 cm box keeps with the platform (to 1 mm; measured 0.8, from the first step, where
/// the platform starts from rest) at 97% of `μ g` and slides at 103%, under every model. The
/// platform's change of speed is spread over each step's substeps (`substeps::StepInputs`):
/// given all at the step's start, the boxes took it within the first substep, the tall one
/// went over at 97% and the flat one slipped from 60%.
#[test]
fn boxes_on_an_accelerating_platform_tip_or_slide_at_the_closed_forms() {
    let turn = rotation([0.0, 0.0, 1.0], 29.0);
    let dt = 1.0 / 60.0;
    for model in ContactModel::ALL {
        for (tall, size, mu) in [(true, [0.2, 0.3, 1.0], 1.0), (false, [0.6, 0.5, 0.2], 0.3)] {
            let threshold = if tall { G * size[0] / size[2] } else { mu * G };
            for share in [0.97, 1.03] {
                let mut world = World::builder()
                    .model(model)
                    .gravity([0.0, 0.0, -G])
                    .body(
                        BodyDesc::kinematic(Shape::cuboid([20.0, 20.0, 0.2]))
                            .position([0.0, 0.0, -0.1])
                            .rotation(turn)
                            .friction(mu),
                    )
                    .body(
                        BodyDesc::dynamic(Shape::cuboid(size))
                            .mass(3.0)
                            .friction(mu)
                            .position([0.0, 0.0, size[2] / 2.0])
                            .rotation(turn),
                    )
                    .build()
                    .unwrap();
                let (platform, body) = (world.bodies()[0].id(), world.bodies()[1].id());
                let mut tilt: f64 = 0.0;
                for k in 1..=120 {
                    let speed = share * threshold * k as f64 * dt;
                    world
                        .set_velocity(platform, turn * Vector3::new(speed, 0.0, 0.0))
                        .unwrap();
                    world.step(dt).unwrap();
                    let up = world.body_by_id(body).unwrap().rotation() * Vector3::z();
                    tilt = tilt.max(up.z.clamp(-1.0, 1.0).acos());
                }
                let on = world.body_by_id(body).unwrap().position();
                let under = world.body_by_id(platform).unwrap().position();
                let slip = (on - under).xy().norm();
                let case = format!(
                    "{model:?}, {} box, {share} of it",
                    if tall { "tall" } else { "flat" }
                );
                match (tall, share < 1.0) {
                    (true, true) => assert!(tilt < 2e-3, "{case}: tilted {tilt} rad"),
                    (true, false) => assert!(tilt > 1.5, "{case}: tilted only {tilt} rad"),
                    (false, true) => assert!(slip < 1e-3, "{case}: slipped {slip} m"),
                    (false, false) => assert!(slip > 0.05, "{case}: slipped only {slip} m"),
                }
            }
        }
    }
}
