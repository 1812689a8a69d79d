//! Whatever the default settings do to hold contacts must not add energy: random scenes of
//! boxes, spheres, cylinders and hulls dropped on a floor, none overlapping at the start, never
//! exceed their initial energy.
//!
//! On these scenes speculative contacts land every body at depth zero, so no penetration push
//! acts at all: a stiff velocity bias (rate 1, no slop) and the old shock pass gain nothing here
//! either. The test guards the contact and integration stages; what a push does to bodies that
//! start overlapping is `overlap_recovery.rs`'s.

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
