//! The scene loader and the world: text straight from the fuzzer, and scenes written from fuzz
//! bytes (1–6 bodies of every shape, every model and setting, hostile numbers included) that
//! are loaded, built and stepped.

use std::fmt::Write;

use tatami_world::scene::Scene;
use tatami_world::{Solver, World};

use crate::bytes::Bytes;

/// Loads the bytes as scene text; a scene that loads is built and stepped once.
pub fn scene_loader(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(scene) = Scene::from_json(text) {
        run(&scene, 1);
    }
}

/// Writes a scene from the bytes, loads it and runs 50 steps — 5 with the direct solver, whose
/// dense solve of up to a few thousand unknowns (a cylinder's 64 cap corners in the vertex
/// model) takes up to seconds a step.
pub fn load_and_step(data: &[u8]) {
    let text = scene_text(&mut Bytes::new(data));
    if let Ok(scene) = Scene::from_json(&text) {
        let steps = match scene.settings.solver {
            Solver::Pgs(_) => 50,
            Solver::Direct(_) => 5,
        };
        run(&scene, steps);
    }
}

/// Builds the world and steps it: every `Ok` step leaves a finite state, and a failed step
/// leaves the world as it was.
fn run(scene: &Scene, steps: usize) {
    let Ok(mut world) = scene.world() else {
        return;
    };
    for _ in 0..steps {
        let before = snapshot(&world);
        match world.step(scene.dt) {
            Ok(()) => assert!(
                before.iter().all(|x| x.is_finite())
                    && snapshot(&world).iter().all(|x| x.is_finite()),
                "a step returned Ok with a non-finite state"
            ),
            Err(_) => {
                let after = snapshot(&world);
                assert!(
                    before
                        .iter()
                        .zip(&after)
                        .all(|(a, b)| a.to_bits() == b.to_bits()),
                    "a failed step changed the world"
                );
                return;
            }
        }
    }
}

/// Every body's pose and velocities, as numbers.
fn snapshot(world: &World) -> Vec<f64> {
    world
        .bodies()
        .iter()
        .flat_map(|b| {
            let q = b.rotation().into_inner();
            let mut state = b.position().coords.as_slice().to_vec();
            state.extend([q.w, q.i, q.j, q.k]);
            state.extend(b.linear_velocity().iter());
            state.extend(b.angular_velocity().iter());
            state
        })
        .collect()
}

/// A JSON number: finite values as they are, non-finite ones as a literal out of f64's range.
fn number(bytes: &mut Bytes) -> String {
    let x = bytes.number();
    if x.is_finite() {
        format!("{x:e}")
    } else {
        "1e999".into()
    }
}

fn vector(bytes: &mut Bytes, scale: f64) -> String {
    // Mostly sane (within ±scale), so that scenes get past the loader and into the step.
    let component = |b: &mut Bytes| {
        if b.below(4) == 0 {
            number(b)
        } else {
            format!("{:e}", b.within(-scale, scale))
        }
    };
    format!(
        "[{}, {}, {}]",
        component(bytes),
        component(bytes),
        component(bytes)
    )
}

/// A positive length, mostly 0.1–2 m.
fn length(bytes: &mut Bytes) -> String {
    if bytes.below(8) == 0 {
        number(bytes)
    } else {
        format!("{:e}", bytes.within(0.1, 2.0))
    }
}

/// Writes a scene: optional settings, maybe a floor, then 1–6 bodies.
fn scene_text(bytes: &mut Bytes) -> String {
    let mut text = String::from("{");
    let mut setting = |bytes: &mut Bytes, key: &str, value: &dyn Fn(&mut Bytes) -> String| {
        if bytes.below(4) == 0 {
            let v = value(bytes);
            let _ = writeln!(text, "\"{key}\": {v},");
        }
    };
    let choice = |options: &'static [&'static str]| {
        move |b: &mut Bytes| format!("\"{}\"", options[b.below(options.len())])
    };
    setting(bytes, "dt", &|b| {
        if b.flag() {
            number(b)
        } else {
            format!("{:e}", b.within(1e-3, 0.05))
        }
    });
    setting(bytes, "gravity", &|b| vector(b, 20.0));
    setting(bytes, "iterations", &|b| (b.below(40) + 1).to_string());
    setting(bytes, "model", &choice(&["vertex", "patch", "face"]));
    setting(bytes, "solver", &choice(&["pgs", "direct"]));
    setting(bytes, "warm_start", &|b| b.flag().to_string());
    setting(bytes, "shock_propagation", &|b| b.flag().to_string());
    setting(bytes, "friction_cone", &choice(&["box", "circle"]));
    setting(bytes, "bias_rate", &number);
    setting(bytes, "slop", &number);
    setting(bytes, "max_depenetration_speed", &number);
    setting(bytes, "max_velocity_bias", &number);
    text.push_str("\"bodies\": [\n");
    let mut bodies = Vec::new();
    if bytes.below(4) != 0 {
        bodies.push(
            r#"{ "name": "floor", "shape": { "box": { "size": [20, 20, 1] } }, "fixed": true, "position": [0, 0, -0.5] }"#
                .to_owned(),
        );
    }
    for i in 0..bytes.below(6) + 1 {
        bodies.push(body(bytes, i));
    }
    text.push_str(&bodies.join(",\n"));
    text.push_str("\n] }");
    text
}

/// One body: a shape, a pose, velocities and a material, each field present or not.
fn body(bytes: &mut Bytes, index: usize) -> String {
    let shape = match bytes.below(4) {
        0 => format!(
            r#"{{ "box": {{ "size": [{}, {}, {}] }} }}"#,
            length(bytes),
            length(bytes),
            length(bytes)
        ),
        1 => format!(r#"{{ "sphere": {{ "radius": {} }} }}"#, length(bytes)),
        2 => format!(
            r#"{{ "cylinder": {{ "radius": {}, "height": {} }} }}"#,
            length(bytes),
            length(bytes)
        ),
        _ => {
            let points: Vec<String> = (0..bytes.below(6) + 4)
                .map(|_| vector(bytes, 1.0))
                .collect();
            format!(r#"{{ "convex": {{ "points": [{}] }} }}"#, points.join(", "))
        }
    };
    let mut text = format!(
        "{{ \"name\": \"b{index}\", \"shape\": {shape}, \"position\": [{:e}, {:e}, {:e}]",
        bytes.within(-3.0, 3.0),
        bytes.within(-3.0, 3.0),
        bytes.within(0.5, 6.0)
    );
    let mut field = |bytes: &mut Bytes, key: &str, value: &dyn Fn(&mut Bytes) -> String| {
        if bytes.below(3) == 0 {
            let v = value(bytes);
            let _ = write!(text, ", \"{key}\": {v}");
        }
    };
    field(bytes, "fixed", &|b| (b.below(8) == 0).to_string());
    field(bytes, "mass", &|b| {
        if b.flag() {
            number(b)
        } else {
            format!("{:e}", b.within(0.1, 10.0))
        }
    });
    field(bytes, "rotation", &|b| {
        format!(
            r#"{{ "axis": {}, "angle_deg": {} }}"#,
            vector(b, 1.0),
            number(b)
        )
    });
    field(bytes, "velocity", &|b| vector(b, 5.0));
    field(bytes, "angular_velocity", &|b| vector(b, 5.0));
    field(bytes, "friction", &number);
    field(bytes, "kinetic_friction", &number);
    field(bytes, "restitution", &|b| {
        if b.flag() {
            number(b)
        } else {
            format!("{:e}", b.within(0.0, 1.0))
        }
    });
    text.push_str(" }");
    text
}
