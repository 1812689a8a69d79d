//! Islands are solved on their own: what one island does, a far-away one does not change.

mod common;

use common::{DT, SIDE, cube, floor, rotation};
use tatami_world::{BodyDesc, World};

/// A stack of three cubes, each offset a quarter side from the one below and turned a little,
/// settling on the floor with the default settings.
fn offset_stack() -> Vec<BodyDesc> {
    (0..3)
        .map(|k| {
            let shift = 0.25 * SIDE * k as f64;
            cube(
                &format!("stack{k}"),
                [shift, 0.5 * shift, SIDE * (k as f64 + 0.5)],
            )
            .rotation(rotation([0.0, 0.0, 1.0], 7.0 * k as f64))
        })
        .collect()
}

fn world(bodies: impl IntoIterator<Item = BodyDesc>) -> World {
    bodies
        .into_iter()
        .fold(World::builder().body(floor()), |b, body| b.body(body))
        .build()
        .unwrap()
}

/// The stack's positions and orientations, to the bit.
fn stack_state(world: &World) -> Vec<[u64; 7]> {
    world
        .bodies()
        .iter()
        .filter(|body| body.name().starts_with("stack"))
        .map(|body| {
            let (p, q) = (body.position(), body.rotation());
            [p.x, p.y, p.z, q.w, q.i, q.j, q.k].map(f64::to_bits)
        })
        .collect()
}

/// With the default settings (PGS stopped at a tolerance, the shock pass and the position pass),
/// a stack settling on the floor moves to the same bits whether or not a cube slides and spins
/// across the floor 12 m away: the floor joins no island, each island's sweeps stop on their
/// own, and the slider's motion cannot keep the stack's solve running longer.
#[test]
fn a_far_away_sliding_cube_does_not_change_a_settling_stack() {
    let slider = cube("slider", [12.0, -3.0, SIDE / 2.0])
        .velocity([2.0, 1.5, 0.0])
        .angular_velocity([0.0, 0.0, 3.0]);
    let mut alone = world(offset_stack());
    let mut beside = world(offset_stack().into_iter().chain([slider]));
    let mut moved = false;
    for _ in 0..200 {
        alone.step(DT).unwrap();
        beside.step(DT).unwrap();
        assert_eq!(stack_state(&alone), stack_state(&beside));
        moved |= beside.body("slider").unwrap().linear_velocity().norm() > 0.5;
    }
    assert!(moved, "the slider slid while the stack settled");
    let top = alone.body("stack2").unwrap();
    assert!(top.position().z > 2.0 * SIDE, "the stack stands");
}
