//! Scenes shared by the world's tests: a large fixed floor and 2 m cubes; how a scene file is
//! refused.

#![allow(dead_code)] // each test binary uses a subset

use nalgebra::{Point3, UnitQuaternion, Vector3};
use tatami_world::dropped::Random;
use tatami_world::scene::{Scene, SceneError};
use tatami_world::{BodyDesc, Shape, World, WorldBuilder};

/// Edge of the paper's cubes (m).
pub const SIDE: f64 = 2.0;
/// Gravity (m/s²).
pub const G: f64 = 9.8;
/// Time step (s).
pub const DT: f64 = 0.01;

/// A 40 m × 40 m × 2 m fixed floor whose top face is the plane z = 0.
pub fn floor() -> BodyDesc {
    BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0]))
        .name("floor")
        .position([0.0, 0.0, -1.0])
}

/// A 1 kg cube of side [`SIDE`] with its centre at `centre`.
pub fn cube(name: &str, centre: [f64; 3]) -> BodyDesc {
    BodyDesc::dynamic(Shape::cuboid([SIDE; 3]))
        .name(name)
        .mass(1.0)
        .position(centre)
}

/// Rotation by `degrees` about `axis`.
pub fn rotation(axis: [f64; 3], degrees: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(
        &nalgebra::Unit::new_normalize(Vector3::from(axis)),
        degrees.to_radians(),
    )
}

/// A rotation drawn from `random` (a normalised quaternion of uniform components), for scenes
/// turned at random.
pub fn turned(random: &mut Random) -> UnitQuaternion<f64> {
    let mut c = || random.between(-1.0, 1.0);
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(c(), c(), c(), c()))
}

/// A floor and one cube resting flat on it.
pub fn resting_cube(builder: WorldBuilder) -> World {
    builder
        .body(floor())
        .body(cube("cube", [0.0, 0.0, SIDE / 2.0]))
        .build()
        .unwrap()
}

/// Steps `world` for `seconds` at [`DT`], calling `each` after every step.
pub fn run(world: &mut World, seconds: f64, mut each: impl FnMut(&World)) {
    let steps = (seconds / DT).round() as usize;
    for _ in 0..steps {
        world.step(DT).unwrap();
        each(world);
    }
}

/// The field, line and message of the error for `text`, which must be refused.
pub fn rejection(text: &str) -> (String, usize, String) {
    match Scene::from_json(text) {
        Err(SceneError::Invalid {
            field,
            line,
            message,
            ..
        }) => (field, line, message),
        other => panic!("expected an invalid-scene error, got {other:?}"),
    }
}

/// A lopsided six-point hull about `size` across (no face parallel to another), for stacks and
/// overlaps of hulls.
pub fn six_point_hull(size: f64) -> Shape {
    let points: Vec<Point3<f64>> = [
        [1.0, 0.2, -0.4],
        [-0.8, 0.9, -0.5],
        [-0.3, -1.0, -0.45],
        [0.1, 0.0, 0.9],
        [0.7, -0.6, 0.3],
        [-0.6, 0.1, 0.5],
    ]
    .iter()
    .map(|p| Point3::from(p.map(|x| x * size / 2.0)))
    .collect();
    Shape::convex(points)
}

/// Runs `world` for `steps` steps of `dt`; returns the largest displacement of any body.
pub fn largest_move(world: &mut World, steps: usize, dt: f64) -> f64 {
    let start: Vec<Point3<f64>> = world.bodies().iter().map(|b| b.position()).collect();
    for _ in 0..steps {
        world.step(dt).unwrap();
    }
    world
        .bodies()
        .iter()
        .zip(&start)
        .map(|(b, p)| (b.position() - p).norm())
        .fold(0.0, f64::max)
}
