//! Round bodies roll as rigid-body mechanics says: down a ramp at the closed form's
//! acceleration, and on the flat at the speed friction leaves them once they stop slipping,
//! without losing energy while they roll. Under every contact model, the scenes turned off the
//! world's axes.

mod common;

use common::{G, rotation};
use nalgebra::{UnitQuaternion, Vector3};
use tatami_world::{BodyDesc, ContactModel, Shape, World};

/// Friction of every body (the pair's μ is their average).
const MU: f64 = 0.5;
/// Radius of the ball and the cylinder (m).
const RADIUS: f64 = 0.3;
/// Time step (s): 60 Hz, the real-time rate.
const DT: f64 = 1.0 / 60.0;

/// A ball (`I = 2/5 m r²`), a cylinder lying across the slope (`I = 1/2 m r²` about its axis)
/// and a 0.5 m cube, each 1 kg, at rest on a ramp tilted `degrees` and turned 40° about the
/// vertical, 3 m apart across it, run for `seconds`; returns per body its speed down the slope
/// and its displacement across it.
fn down_a_ramp(model: ContactModel, degrees: f64, seconds: f64) -> [(f64, f64); 3] {
    let ramp = rotation([0.0, 0.0, 1.0], 40.0) * rotation([1.0, 0.0, 0.0], degrees);
    let normal = ramp * Vector3::z();
    let down = (-Vector3::z() + normal * normal.z).normalize();
    let across = normal.cross(&down);
    // The ramp's top face passes through the origin.
    let at = |side: f64, height: f64| {
        let p = across * side + normal * height;
        [p.x, p.y, p.z]
    };
    let lying = UnitQuaternion::rotation_between(&Vector3::z(), &across).expect("not opposite");
    let centre = -normal;
    let mut world = World::builder()
        .model(model)
        .gravity([0.0, 0.0, -G])
        .body(
            BodyDesc::fixed(Shape::cuboid([60.0, 60.0, 2.0]))
                .position([centre.x, centre.y, centre.z])
                .rotation(ramp)
                .friction(MU),
        )
        .body(
            BodyDesc::dynamic(Shape::sphere(RADIUS))
                .mass(1.0)
                .friction(MU)
                .position(at(-3.0, RADIUS)),
        )
        .body(
            BodyDesc::dynamic(Shape::cylinder(RADIUS, 0.5))
                .mass(1.0)
                .friction(MU)
                .position(at(0.0, RADIUS))
                .rotation(lying),
        )
        .body(
            BodyDesc::dynamic(Shape::cuboid([0.5; 3]))
                .mass(1.0)
                .friction(MU)
                .position(at(3.0, 0.25))
                .rotation(ramp),
        )
        .build()
        .unwrap();
    let start: Vec<_> = world.bodies().iter().map(|b| b.position()).collect();
    for _ in 0..(seconds / DT).round() as usize {
        world.step(DT).unwrap();
    }
    std::array::from_fn(|k| {
        let body = &world.bodies()[k + 1];
        let moved = body.position() - start[k + 1];
        (body.linear_velocity().dot(&down), moved.dot(&across))
    })
}

/// Ramps of 15° and 30°: the ball and the cylinder roll without slipping (μ = 0.5 is more than
/// the `(2/7) tan θ` and `(1/3) tan θ` that takes, 0.33 at 30°), so their centres accelerate at
/// `(5/7) g sin θ` and `(2/3) g sin θ`; the cube holds at 15° (tan 15° < μ) and slides at 30° at
/// `g (sin θ − μ cos θ)`. Speeds after 2 s within 0.1% of the closed forms' (the steps'
/// discretisation is exact for a constant acceleration: the speeds read the closed forms' to
/// 5e-5 or better), and nothing drifts across the slope by more than 1e-4 of its way down (the
/// face model's bodies by 1e-13 m; the vertex and patch models' cylinder, its line's two
/// points solved one after the other, by up to 1.2e-5 of its way), or a micrometre held.
#[test]
fn a_ball_and_a_cylinder_roll_down_a_ramp_at_the_closed_forms_rates() {
    let seconds = 2.0;
    for model in ContactModel::ALL {
        for degrees in [15f64, 30.0] {
            let theta = degrees.to_radians();
            let rates = [
                5.0 / 7.0 * G * theta.sin(),
                2.0 / 3.0 * G * theta.sin(),
                (G * (theta.sin() - MU * theta.cos())).max(0.0),
            ];
            let moved = down_a_ramp(model, degrees, seconds);
            for ((name, rate), (speed, across)) in
                ["ball", "cylinder", "cube"].iter().zip(rates).zip(moved)
            {
                let expected = rate * seconds;
                let case = format!("{} at {degrees}°: {name}", model.name());
                println!(
                    "{case}: {speed:.5} m/s down the slope (closed form {expected:.5}), {across:.1e} m across"
                );
                assert!(
                    (speed - expected).abs() <= 1e-3 * expected.max(1.0),
                    "{case}: {speed} m/s down the slope, closed form {expected}"
                );
                let travelled = 0.5 * speed.abs() * seconds;
                assert!(
                    across.abs() <= 1e-4 * travelled + 1e-6,
                    "{case}: drifted {across} m across the slope in {travelled} m"
                );
            }
        }
    }
}

/// A ball and a cylinder lying across `heading`, 1 kg each, on a floor turned 25° about the
/// vertical, 6 m apart, moving at `velocity` and turning at `spin`.
fn on_the_flat(
    model: ContactModel,
    heading: Vector3<f64>,
    velocity: [f64; 3],
    spin: [f64; 3],
) -> World {
    let axis = Vector3::z().cross(&heading);
    let lying = UnitQuaternion::rotation_between(&Vector3::z(), &axis).expect("not opposite");
    World::builder()
        .model(model)
        .gravity([0.0, 0.0, -G])
        .body(
            BodyDesc::fixed(Shape::cuboid([200.0, 200.0, 2.0]))
                .position([0.0, 0.0, -1.0])
                .rotation(rotation([0.0, 0.0, 1.0], 25.0))
                .friction(MU),
        )
        .body(
            BodyDesc::dynamic(Shape::sphere(RADIUS))
                .mass(1.0)
                .friction(MU)
                .position([0.0, -3.0, RADIUS])
                .velocity(velocity)
                .angular_velocity(spin),
        )
        .body(
            BodyDesc::dynamic(Shape::cylinder(RADIUS, 0.5))
                .mass(1.0)
                .friction(MU)
                .position([0.0, 3.0, RADIUS])
                .rotation(lying)
                .velocity(velocity)
                .angular_velocity(spin),
        )
        .build()
        .unwrap()
}

/// A ball and a cylinder on their side launched at 2 m/s with backspin (`ω r = v` the wrong
/// way) slide until friction has them rolling, at `v (1 − k) / (1 + k)` with `k = I / (m r²)`:
/// 3/7 of it for the ball, 1/3 for the cylinder. From then on they roll at that speed and their
/// energy stays as it is (to 1e-9 of it: nothing slips, so friction does no work). On a floor
/// turned 25° about the vertical, heading 35° off its axes.
#[test]
fn backspin_ends_in_rolling_at_the_closed_forms_speed() {
    let speed = 2.0;
    let heading = Vector3::new(35f64.to_radians().cos(), 35f64.to_radians().sin(), 0.0);
    let axis = Vector3::z().cross(&heading);
    // Rolling forward turns about `axis` at v / r; backspin turns the other way.
    let backspin = -axis * (speed / RADIUS);
    let velocity = [speed * heading.x, speed * heading.y, 0.0];
    let spin = [backspin.x, backspin.y, backspin.z];
    for model in ContactModel::ALL {
        let mut world = on_the_flat(model, heading, velocity, spin);
        // Slipping ends after (v − v') / (μ g), under 0.3 s here.
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        let rolled = world.total_energy();
        for _ in 0..180 {
            world.step(DT).unwrap();
        }
        for (k, (name, inertia)) in [("ball", 0.4), ("cylinder", 0.5)].into_iter().enumerate() {
            let body = &world.bodies()[k + 1];
            let expected = speed * (1.0 - inertia) / (1.0 + inertia);
            let v = body.linear_velocity().dot(&heading);
            let case = format!("{}: {name}", model.name());
            println!("{case}: rolls at {v:.6} m/s (closed form {expected:.6})");
            assert!(
                (v - expected).abs() < 1e-3 * expected,
                "{case}: rolls at {v} m/s, closed form {expected}"
            );
        }
        let energy = world.total_energy();
        assert!(
            (energy - rolled).abs() <= 1e-9 * rolled,
            "{}: energy {rolled} J after 1 s, {energy} J after 4 s",
            model.name()
        );
    }
}

/// A ball and a cylinder on their side rolling slowly on a floor turned 25° about the vertical,
/// heading 35° off its axes, at 0.2, 1 and 5 mm/s: rolling without slipping on the flat, each
/// keeps its speed for 10 s (within 0.1%, and its heading within 1e-3 rad), under every model.
/// Their contacts run over their surfaces as they roll. The face model carries a pair's contact
/// with its bodies while they slide and turn against each other by under 0.1 mm and 0.1°
/// (`carry.rs`); carried with the rolling body, the contact's point lagged and its normal
/// tilted with the turn, and the ball at 0.2 mm/s sped up to 3.2 cm/s, where its turn passes
/// 0.1° a step and its contact is found afresh every step: a settled heap of balls never came
/// to rest.
#[test]
fn a_slow_roll_keeps_its_speed() {
    let heading = Vector3::new(35f64.to_radians().cos(), 35f64.to_radians().sin(), 0.0);
    let axis = Vector3::z().cross(&heading);
    for model in ContactModel::ALL {
        for speed in [2e-4, 1e-3, 5e-3] {
            let velocity = [speed * heading.x, speed * heading.y, 0.0];
            let roll = axis * (speed / RADIUS);
            let spin = [roll.x, roll.y, roll.z];
            let mut world = on_the_flat(model, heading, velocity, spin);
            for _ in 0..(10.0 / DT).round() as usize {
                world.step(DT).unwrap();
            }
            for (k, name) in ["ball", "cylinder"].into_iter().enumerate() {
                let v = world.bodies()[k + 1].linear_velocity();
                let case = format!("{} {name} at {speed} m/s", model.name());
                let turned = v.angle(&heading);
                println!(
                    "{case}: {:.6e} m/s after 10 s, {turned:.1e} rad off",
                    v.norm()
                );
                assert!(
                    (v.norm() - speed).abs() <= 1e-3 * speed,
                    "{case}: {} m/s after 10 s",
                    v.norm()
                );
                assert!(turned <= 1e-3, "{case}: turned {turned} rad");
            }
        }
    }
}
