//! The vertex model against closed-form rigid-body physics.

mod common;

use common::{DT, G, SIDE, cube, floor, resting_cube, rotation, run};
use tatami_lcp::pgs::{PgsParams, WarmStart};
use tatami_world::{BodyDesc, Shape, Solver, World, WorldSettings};

#[test]
fn a_resting_cube_stays_put_for_ten_seconds() {
    let mut world = resting_cube(World::builder());
    let start = world.bodies()[1].position();
    let mut deepest: f64 = 0.0;
    run(&mut world, 10.0, |w| {
        deepest = w.contacts().map(|c| c.depth()).fold(deepest, f64::max);
    });
    let cube = &world.bodies()[1];
    let drift = (cube.position() - start).norm();
    assert!(drift < 1e-4, "drift {drift} m");
    let spin = cube.angular_velocity().norm();
    assert!(spin < 1e-6, "|ω| = {spin} rad/s");
    let slop = world.settings().contact.slop;
    assert!(
        deepest <= slop,
        "penetration {deepest} m beyond the slop {slop} m"
    );
}

#[test]
fn a_dropped_cube_lands_and_rests_without_gaining_energy() {
    let mut world = World::builder()
        .body(floor())
        .body(cube("cube", [0.0, 0.0, 3.0]).rotation(rotation([1.0, 2.0, 0.0], 10.0)))
        .build()
        .unwrap();
    let e0 = world.total_energy();
    // The bias adds at most the energy of lifting the cube out of its deepest overlap beyond
    // the slop, plus the kinetic energy of that push: `m g d + m (rate d / dt)² / 2`.
    let settings = world.settings().contact;
    let mut worst_gain: f64 = 0.0;
    let mut deepest: f64 = 0.0;
    run(&mut world, 4.0, |w| {
        deepest = w.contacts().map(|c| c.depth()).fold(deepest, f64::max);
        let excess = (deepest - settings.slop).max(0.0);
        let allowance = G * excess + 0.5 * (settings.bias_rate * excess / DT).powi(2);
        worst_gain = worst_gain.max(w.total_energy() - e0 - allowance);
    });
    assert!(
        worst_gain <= 1e-9,
        "energy grew {worst_gain} J beyond the bias allowance"
    );
    let cube = &world.bodies()[1];
    assert!(
        cube.linear_velocity().norm() < 1e-3,
        "still moving: {}",
        cube.linear_velocity()
    );
    assert!(cube.angular_velocity().norm() < 1e-3, "still turning");
    // It lies flat: one face down, centre one half-side above the floor (within the slop).
    assert!(
        (cube.position().z - SIDE / 2.0).abs() < 3e-3,
        "z = {}",
        cube.position().z
    );
}

#[test]
fn a_sliding_cube_stops_after_the_closed_form_distance() {
    let (v0, mu_k) = (3.0, 0.3);
    let mut world = World::builder()
        .body(floor().friction_pair(0.5, mu_k))
        .body(
            cube("cube", [0.0, 0.0, SIDE / 2.0])
                .friction_pair(0.5, mu_k)
                .velocity([v0, 0.0, 0.0]),
        )
        .build()
        .unwrap();
    run(&mut world, 2.0, |_| {});
    let cube = &world.bodies()[1];
    assert!(cube.linear_velocity().norm() < 1e-6, "still sliding");
    let expected = v0 * v0 / (2.0 * mu_k * G);
    let travelled = cube.position().x;
    // Semi-implicit Euler stops v₀·dt/2 short (1% here); 2% is the requirement.
    let error = (travelled - expected).abs() / expected;
    assert!(
        error < 0.02,
        "travelled {travelled} m, closed form {expected} m"
    );
}

/// A cube resting on a fixed incline of `degrees`, both with friction `(μs, μk)`; returns how far
/// it moved down the slope in `seconds`.
fn slide_down_incline(degrees: f64, mu_s: f64, mu_k: f64, seconds: f64) -> f64 {
    let tilt = rotation([0.0, 1.0, 0.0], degrees);
    let up = tilt * nalgebra::Vector3::z();
    let slab = BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0]))
        .name("incline")
        .position((-up).into())
        .rotation(tilt)
        .friction_pair(mu_s, mu_k);
    let block = cube("cube", up.into())
        .rotation(tilt)
        .friction_pair(mu_s, mu_k);
    let mut world = World::builder().body(slab).body(block).build().unwrap();
    let start = world.bodies()[1].position();
    run(&mut world, seconds, |_| {});
    let downhill = tilt * nalgebra::Vector3::x();
    (world.bodies()[1].position() - start).dot(&downhill)
}

#[test]
fn a_cube_holds_on_an_incline_below_the_static_coefficient_and_slides_above() {
    let (mu_s, mu_k) = (0.6, 0.4);
    let below = (mu_s - 0.05_f64).atan().to_degrees();
    let held = slide_down_incline(below, mu_s, mu_k, 2.0);
    assert!(held.abs() < 1e-3, "tan θ = μs − 0.05 slid {held} m");
    let above = (mu_s + 0.05_f64).atan().to_degrees();
    let slid = slide_down_incline(above, mu_s, mu_k, 2.0);
    // Once sliding, kinetic friction: a = g (sin θ − μk cos θ).
    let theta = above.to_radians();
    let expected = 0.5 * G * (theta.sin() - mu_k * theta.cos()) * 4.0;
    assert!(
        slid > 0.9 * expected,
        "tan θ = μs + 0.05 slid {slid} m, expected ≈ {expected} m"
    );
}

/// The paper's solver settings (15 sweeps, relaxation 1) with warm starting: without it, 15
/// sweeps leave the four-point contacts of a 10-high stack unconverged every step, the error
/// accumulates in the stack's tilt mode, and the tower walks off within 10 s (the vertex model's
/// weakness the face model addresses).
#[test]
fn a_tower_of_ten_cubes_stands_for_ten_seconds() {
    let settings = WorldSettings {
        solver: Solver::Pgs(PgsParams {
            iterations: 15,
            warm_start: WarmStart::On,
            ..PgsParams::default()
        }),
        ..WorldSettings::default()
    };
    let mut builder = World::builder().settings(settings).body(floor());
    for k in 0..10 {
        builder = builder.body(cube(
            &format!("cube{k}"),
            [0.0, 0.0, SIDE / 2.0 + SIDE * k as f64],
        ));
    }
    let mut world = builder.build().unwrap();
    let top_start = world.bodies()[10].position();
    run(&mut world, 10.0, |_| {});
    let top = world.bodies()[10].position();
    let sway = (top.xy() - top_start.xy()).norm();
    let drop = top_start.z - top.z;
    // Standing: the top cube is within 2 cm of where it started (the stack is 20 m high; a
    // falling tower moves metres), each of the ten contacts at most a slop deep.
    assert!(sway < 0.02, "top cube moved {sway} m sideways");
    assert!(
        drop < 10.0 * world.settings().contact.slop,
        "top cube dropped {drop} m"
    );
}
