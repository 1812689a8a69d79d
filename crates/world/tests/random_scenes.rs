//! Random small scenes with random materials, models and settings: no panic, a finite state
//! after every step, and no energy gained beyond what per-point restitution can add.
//!
//! The bodies (1–6 boxes, spheres, cylinders and hulls, apart) come from
//! [`dropped_scene`]; on top of them every material and setting is drawn: friction, kinetic
//! friction, restitution, density, launch velocities, the contact model, the friction cone,
//! 1–40 sweeps, warm starting, shock propagation, the penetration push and `dt`.

use proptest::prelude::*;
use tatami_world::dropped::dropped_scene;
use tatami_world::{ContactModel, FrictionCone, PgsParams, Solver, WarmStart};

/// Steps per scene.
const STEPS: usize = 50;

/// Largest energy gain allowed, as a fraction of the initial energy (potential above the floor
/// plus kinetic): 0.1%, as for the default settings' dropped scenes. The free rotation's
/// energy error is third order in dt, and no stabilisation may add more.
const GAIN: f64 = 1e-3;

/// Largest gain allowed when a body bounces (restitution > 0) under the vertex or patch model:
/// 3%. Newton's restitution asked of several points of one contact at once is not
/// energy-consistent (a spinning box landing on four corners cannot leave each at `e` times its
/// own approach speed without gaining energy); gains up to 1.3% were seen in a few of 4,000
/// cases. The face model asks it once per face, at `G`, and keeps [`GAIN`].
const GAIN_WITH_POINT_RESTITUTION: f64 = 0.03;

#[derive(Debug, Clone)]
struct Material {
    friction: f64,
    kinetic_ratio: f64,
    restitution: f64,
    density: f64,
    velocity: [f64; 3],
    angular_velocity: [f64; 3],
}

fn material() -> impl Strategy<Value = Material> {
    let component = -5.0..5.0f64;
    (
        0.0..1.5f64,
        0.0..=1.0f64,
        0.0..=1.0f64,
        10.0..20_000.0f64,
        [component.clone(), component.clone(), component.clone()],
        [component.clone(), component.clone(), component],
    )
        .prop_map(
            |(friction, kinetic_ratio, restitution, density, velocity, angular_velocity)| {
                Material {
                    friction,
                    kinetic_ratio,
                    restitution,
                    density,
                    velocity,
                    angular_velocity,
                }
            },
        )
}

#[derive(Debug, Clone)]
struct Settings {
    model: ContactModel,
    circle: bool,
    iterations: usize,
    warm_start: bool,
    shock_propagation: bool,
    bias_rate: f64,
    max_velocity_bias: f64,
    dt: f64,
}

fn settings() -> impl Strategy<Value = Settings> {
    (
        prop::sample::select(ContactModel::ALL.to_vec()),
        any::<bool>(),
        1..=40usize,
        any::<bool>(),
        any::<bool>(),
        0.0..=1.0f64,
        0.0..=1.0f64,
        0.002..0.02f64,
    )
        .prop_map(
            |(model, circle, iterations, warm_start, shock_propagation, bias_rate, bias, dt)| {
                Settings {
                    model,
                    circle,
                    iterations,
                    warm_start,
                    shock_propagation,
                    bias_rate,
                    max_velocity_bias: bias,
                    dt,
                }
            },
        )
}

proptest! {
    // A fixed seed: the same 1,000 cases on every run and machine.
    #![proptest_config(ProptestConfig {
        cases: 1000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x7a7a_3141),
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_scenes_stay_finite_and_gain_no_energy(
        seed in any::<u64>(),
        materials in prop::collection::vec(material(), 6),
        s in settings(),
    ) {
        let mut scene = dropped_scene(seed);
        for (body, m) in scene.bodies.iter_mut().skip(1).zip(&materials) {
            *body = body
                .clone()
                .density(m.density)
                .friction_pair(m.friction, m.friction * m.kinetic_ratio)
                .restitution(m.restitution)
                .velocity(m.velocity)
                .angular_velocity(m.angular_velocity);
        }
        let settings = &mut scene.settings;
        settings.model = s.model;
        settings.contact.friction_cone = if s.circle { FrictionCone::Circle } else { FrictionCone::Box };
        settings.solver = Solver::Pgs(PgsParams {
            iterations: s.iterations,
            warm_start: if s.warm_start { WarmStart::On } else { WarmStart::Off },
            ..PgsParams::default()
        });
        settings.shock_propagation = s.shock_propagation;
        settings.contact.bias_rate = s.bias_rate;
        settings.contact.max_velocity_bias = s.max_velocity_bias;
        let bounces = materials[..scene.bodies.len() - 1].iter().any(|m| m.restitution > 0.0);
        let bound = if bounces && s.model != ContactModel::Face {
            GAIN_WITH_POINT_RESTITUTION
        } else {
            GAIN
        };
        let mut world = scene.world().unwrap();
        let start = world.total_energy();
        for step in 0..STEPS {
            world.step(s.dt).unwrap();
            for body in world.bodies() {
                let state = [
                    body.position().coords,
                    body.linear_velocity(),
                    body.angular_velocity(),
                    body.rotation().into_inner().imag(),
                ];
                prop_assert!(
                    state.iter().all(|v| v.iter().all(|x| x.is_finite()))
                        && body.rotation().into_inner().w.is_finite(),
                    "step {step}: {body:?}"
                );
            }
            let gain = (world.total_energy() - start) / start.abs();
            prop_assert!(gain <= bound, "step {step}: energy {:.4}% above its start", gain * 100.0);
        }
    }
}
