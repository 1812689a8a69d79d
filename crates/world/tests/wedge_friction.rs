//! Friction in a V-groove: a cube lying in a 90° groove presses on both walls with normal forces
//! √2 larger than on a flat incline, so it holds up to a steeper tilt of the groove's axis and
//! slides with the closed-form acceleration above it. Off the axes: the groove is tilted about
//! one horizontal axis and turned about the vertical, so no wall and no slide direction lies
//! along a world axis, and both contacts carry load and friction at once.

use nalgebra::{UnitQuaternion, Vector3};
use tatami_world::{BodyDesc, Shape, World};

const G: f64 = 9.8;
const MU: f64 = 0.5;
const DT: f64 = 1.0 / 60.0;
const STEPS: usize = 120;

/// A 1 m, 1 kg cube in a groove whose walls are two fixed plates at ±45° about its axis, the
/// axis tilted down by `tilt` degrees and turned by `turn` degrees about the vertical. Returns
/// how far the cube moved along the axis (downhill positive) and across it after [`STEPS`]
/// steps, with the default settings.
fn slide(tilt: f64, turn: f64) -> (f64, f64) {
    let groove = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn.to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), tilt.to_radians());
    let walls = groove * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 45f64.to_radians());
    let centre = Vector3::new(0.0, 0.0, 3.0);
    // Each plate (1 m thick) touches one of the cube's two lower faces over the whole face.
    let plate = |size: [f64; 3], towards: Vector3<f64>| {
        BodyDesc::fixed(Shape::cuboid(size))
            .position((centre + walls * towards).into())
            .rotation(walls)
            .friction(MU)
    };
    let mut world = World::builder()
        .gravity([0.0, 0.0, -G])
        .body(plate([10.0, 1.0, 10.0], -Vector3::y()))
        .body(plate([10.0, 10.0, 1.0], -Vector3::z()))
        .body(
            BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                .name("cube")
                .mass(1.0)
                .friction(MU)
                .position(centre.into())
                .rotation(walls),
        )
        .build()
        .unwrap();
    for _ in 0..STEPS {
        world.step(DT).unwrap();
    }
    let moved = world.body("cube").unwrap().position().coords - centre;
    // Rotating +x down by `tilt` about +y points it downhill.
    let downhill = groove * Vector3::x();
    let along = moved.dot(&downhill);
    (along, (moved - downhill * along).norm())
}

/// Sliding needs `tan γ > μ √2` (each wall's normal force is `W cos γ / √2`, their friction
/// `2 μ W cos γ / √2`): 35.26° at μ = 0.5. At 33° the cube holds; at 37.5°, 40° and 45° it
/// slides with `a = g (sin γ − μ √2 cos γ)`, which semi-implicit Euler turns into
/// `x(n) = a dt² n (n + 1) / 2` after n steps. Tolerances: holding, 1 mm in 2 s (the contacts'
/// slop is 2 mm, and a creep would grow past it); sliding, between `x(n − 1)` and `x(n)`, each
/// widened by 0.1%: the first step starts from rest with no impulses to warm-start from and
/// its sweeps leave the cube up to a step behind (0.65 of one at every tilt here), after which
/// the face rows are exact; across the groove, 1 mm (the walls are symmetric about the slide).
#[test]
fn a_cube_in_a_v_groove_holds_below_the_wedge_angle_and_slides_above_it() {
    for turn in [0.0, 30.0] {
        let (held, across) = slide(33.0, turn);
        assert!(held.abs() < 1e-3, "turn {turn}°: crept {held} m at 33°");
        assert!(across < 1e-3, "turn {turn}°: {across} m across the groove");
        for tilt in [37.5f64, 40.0, 45.0] {
            let g = tilt.to_radians();
            let a = G * (g.sin() - MU * 2f64.sqrt() * g.cos());
            let x = |n: f64| a * DT * DT * n * (n + 1.0) / 2.0;
            let n = STEPS as f64;
            let (along, across) = slide(tilt, turn);
            assert!(
                along > x(n - 1.0) * 0.999 && along < x(n) * 1.001,
                "turn {turn}°, tilt {tilt}°: slid {along} m, closed form {} to {} m",
                x(n - 1.0),
                x(n)
            );
            assert!(
                across < 1e-3,
                "turn {turn}°, tilt {tilt}°: {across} m across"
            );
        }
    }
}
