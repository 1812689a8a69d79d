//! Hostile input found by fuzzing scenes and misusing the API: each case once panicked, hung
//! or gave a silent NaN, and now runs correctly or is refused naming the field and the line.

mod common;

use common::rejection;
use tatami_world::scene::{Scene, SceneError};

/// A floor and one 2 m cube, with `cube` spliced into the cube's object and `top` into the
/// scene's.
fn scene(top: &str, cube: &str) -> String {
    format!(
        r#"{{ {top} "bodies": [
  {{ "name": "ground", "shape": {{ "box": {{ "size": [40, 40, 2] }} }}, "fixed": true,
    "position": [0, 0, -1], "friction": 1e308 }},
  {{ "name": "cube", "shape": {{ "box": {{ "size": [2, 2, 2] }} }}, "mass": 1.0,
    "position": [0, 0, 1], {cube} "velocity": [1, 0, 0] }} ] }}"#
    )
}

/// Friction 1e308 on both bodies: their average overflowed to ∞, and ∞ · 0 on a separating
/// contact was a NaN bound that made `f64::clamp` panic. Now the average is 1e308 and the cube,
/// gripped, stops at once.
#[test]
fn huge_friction_averages_without_overflow() {
    let scene = Scene::from_json(&scene("", r#""friction": 1e308,"#)).unwrap();
    let mut world = scene.world().unwrap();
    for _ in 0..50 {
        world.step(scene.dt).unwrap();
    }
    let cube = world.body("cube").unwrap();
    assert!(cube.linear_velocity().iter().all(|v| v.is_finite()));
    assert!(
        cube.linear_velocity().norm() < 1e-6,
        "{}",
        cube.linear_velocity()
    );
}

/// A rotation axis of [1e200, 1e200, 0]: its norm overflowed and the quaternion was not unit,
/// so the cube was thrown at 205 m/s. Now it is a 90° turn about (1, 1, 0)/√2.
#[test]
fn a_huge_rotation_axis_is_normalised() {
    let rotation = r#""rotation": { "axis": [1e200, 1e200, 0], "angle_deg": 90 },"#;
    let scene = Scene::from_json(&scene("", rotation)).unwrap();
    let q = scene.bodies[1].rotation;
    assert!((q.into_inner().norm() - 1.0).abs() < 1e-15);
    let axis = q.axis().unwrap();
    assert!((axis.x - 0.5f64.sqrt()).abs() < 1e-15 && (axis.y - 0.5f64.sqrt()).abs() < 1e-15);
    assert!((q.angle() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
}

/// `"iterations": 18446744073709551615` hung a release build (and overflowed a debug one).
#[test]
fn absurd_iteration_counts_are_refused_with_field_and_line() {
    let text = scene("\"iterations\": 18446744073709551615,\n", "");
    match Scene::from_json(&text) {
        Err(SceneError::Invalid {
            field,
            line,
            message,
            ..
        }) => {
            assert_eq!((field.as_str(), line), ("iterations", 1));
            assert!(message.contains("must be 1 to 100000"), "{message}");
        }
        other => panic!("accepted: {other:?}"),
    }
}

/// `"mass": null` silently fell back to the default density; `null` is now refused wherever a
/// value may be given.
#[test]
fn null_is_not_absent() {
    let (field, line, message) =
        rejection(&scene("", r#""mass": null,"#).replace(r#""mass": 1.0,"#, ""));
    assert_eq!((field.as_str(), line), ("bodies[1].mass", 5), "{message}");
    assert!(message.contains("null"), "{message}");
    let (field, _, _) = rejection(&scene("\"dt\": null,", ""));
    assert_eq!(field, "dt");
}

/// Two bodies of one name made the trajectory CSV ambiguous.
#[test]
fn body_names_must_differ() {
    let text = scene("", "").replace(r#""name": "cube""#, r#""name": "ground""#);
    let (field, _, message) = rejection(&text);
    assert_eq!(field, "bodies");
    assert!(
        message.contains("bodies[0] and bodies[1] are both named `ground`"),
        "{message}"
    );
}

/// Kinetic friction above static was accepted.
#[test]
fn kinetic_friction_may_not_exceed_static() {
    let text = scene("", r#""static_friction": 0.3, "kinetic_friction": 0.6,"#);
    let (field, line, message) = rejection(&text);
    assert_eq!((field.as_str(), line), ("bodies[1]", 5), "{message}");
    assert!(
        message.contains("kinetic_friction: must not exceed static_friction (0.3)"),
        "{message}"
    );
}

/// A UTF-8 byte-order mark (some editors write one) got "expected value"; it is skipped, and
/// lines are still counted from the first line.
#[test]
fn a_byte_order_mark_is_skipped() {
    let text = format!("\u{feff}{}", scene("", ""));
    assert!(Scene::from_json(&text).is_ok());
    let bad = format!(
        "\u{feff}{}",
        scene("", r#""mass": -1,"#).replace(r#""mass": 1.0,"#, "")
    );
    assert_eq!(rejection(&bad).1, 5);
}

/// A scene, a body or a rotation written as a positional array of its fields was accepted.
#[test]
fn structs_are_objects_not_positional_arrays() {
    let (field, line, message) = rejection("[[0, 0, -9.8], 0.01]");
    assert_eq!((field.as_str(), line), ("scene", 1));
    assert!(
        message.contains("a JSON object of named fields"),
        "{message}"
    );
    let rotation = r#""rotation": [[0, 0, 1], 30],"#;
    let (field, line, _) = rejection(&scene("", rotation));
    assert_eq!((field.as_str(), line), ("bodies[1].rotation", 5));
}

/// Sizes, masses, densities, speeds and time steps beyond what the contact geometry and the
/// solver's arithmetic hold failed only at step 1 without field or line (mass 1e300, density
/// 1e308, size 1e300), were called a singular inertia (1e-300), or were accepted (dt 1e10).
#[test]
fn out_of_range_quantities_are_refused_at_load() {
    for (cube, said) in [
        (
            r#""shape": { "box": { "size": [1e300, 2, 2] } },"#,
            "box size must be from",
        ),
        (
            r#""shape": { "box": { "size": [1e-300, 2, 2] } },"#,
            "box size must be from",
        ),
        (
            r#""shape": { "sphere": { "radius": 1e-300 } },"#,
            "sphere radius must be from",
        ),
        (r#""density": 1e308,"#, "density: gives a mass of"),
        (
            r#""angular_velocity": [1e308, 0, 0],"#,
            "angular_velocity: must be at most",
        ),
    ] {
        let text = scene("", cube).replace(r#""mass": 1.0,"#, "").replace(
            r#""shape": { "box": { "size": [2, 2, 2] } }, "#,
            if cube.contains("shape") {
                ""
            } else {
                r#""shape": { "box": { "size": [2, 2, 2] } }, "#
            },
        );
        let (field, line, message) = rejection(&text);
        assert_eq!(
            (field.as_str(), line),
            ("bodies[1]", 5),
            "{cube}: {message}"
        );
        assert!(message.contains(said), "{cube}: {message}");
    }
    for (top, field, said) in [
        ("\"gravity\": [0, 0, -1e308],", "gravity", "at most"),
        ("\"steps\": 18446744073709551615,", "steps", "must be 1 to"),
        ("\"bias_rate\": 2,", "bias_rate", "in [0, 1]"),
    ] {
        let (got, line, message) = rejection(&scene(top, ""));
        assert_eq!((got.as_str(), line), (field, 1), "{message}");
        assert!(message.contains(said), "{top}: {message}");
    }
    let (field, line, message) = rejection(&scene("\"dt\": 1e10,", ""));
    assert_eq!((field.as_str(), line), ("dt", 1), "{message}");
    let mut world = Scene::from_json(&scene("", "")).unwrap().world().unwrap();
    assert!(world.step(1e10).is_err());
}

/// At the edge of the bounds the contact geometry still holds: a cube and a standing cylinder
/// on a 100 km ground (the largest length allowed), placed 45 km from the origin, rest without
/// sinking or gaining energy (on a 3e7 m ground a cylinder gained 10⁴–10⁷× its energy, and a
/// cube fell through a 1e10 m one).
#[test]
fn bodies_rest_on_the_largest_ground_allowed() {
    let text = r#"{ "bodies": [
  { "name": "ground", "shape": { "box": { "size": [100000, 100000, 2] } }, "fixed": true,
    "position": [0, 0, -1] },
  { "name": "cube", "shape": { "box": { "size": [1, 1, 1] } }, "mass": 1.0,
    "position": [45000, 0, 0.5] },
  { "name": "cylinder", "shape": { "cylinder": { "radius": 0.5, "height": 1 } }, "mass": 1.0,
    "position": [-30000, 35000, 0.5] } ] }"#;
    let scene = Scene::from_json(text).unwrap();
    let mut world = scene.world().unwrap();
    let start = world.total_energy();
    for _ in 0..300 {
        world.step(scene.dt).unwrap();
        assert!(
            world.total_energy() <= start + 1e-6 * start.abs(),
            "energy grew"
        );
    }
    for name in ["cube", "cylinder"] {
        let body = world.body(name).unwrap();
        // Resting within the 2 mm slop of where it was placed, not moving.
        assert!(
            (body.position().z - 0.5).abs() < 2e-3,
            "{name} at {}",
            body.position()
        );
        assert!(body.linear_velocity().norm() < 1e-3, "{name} moves");
    }
}

/// `--solver direct` on 500 overlapping bodies once allocated a 66 GB matrix and aborted. Now a
/// direct problem whose dense storage exceeds the 512 MiB budget is refused by the step, naming
/// its unknowns: here 200 cubes on the floor, 4 corners each, whose circular friction cone is
/// the inscribed 16-gon (18 unknowns a corner: the normal, 16 directions, the sliding speed).
#[test]
fn a_direct_problem_beyond_the_memory_budget_is_an_error() {
    let cubes: Vec<String> = (0..200)
        .map(|i| {
            format!(
                r#"{{ "name": "c{i}", "shape": {{ "box": {{ "size": [1, 1, 1] }} }},
                  "position": [{}, {}, 0.499] }}"#,
                (i % 20) as f64 * 1.5,
                (i / 20) as f64 * 1.5
            )
        })
        .collect();
    let text = format!(
        r#"{{ "solver": "direct", "model": "vertex", "bodies": [
  {{ "name": "ground", "shape": {{ "box": {{ "size": [100, 100, 2] }} }}, "fixed": true,
    "position": [0, 0, -1] }}, {} ] }}"#,
        cubes.join(",\n")
    );
    let scene = Scene::from_json(&text).unwrap();
    let mut world = scene.world().unwrap();
    let error = world.step(scene.dt).unwrap_err().to_string();
    assert!(
        error.contains("14400 unknowns") && error.contains("budget"),
        "{error}"
    );
}

/// A PGS tolerance that is negative, NaN or infinite is refused naming the field; 0 (run every
/// sweep) and the default are accepted.
#[test]
fn a_pgs_tolerance_out_of_range_is_refused() {
    use tatami_lcp::pgs::PgsParams;
    use tatami_world::{Solver, WorldError, WorldSettings};
    let with = |tolerance: f64| WorldSettings {
        solver: Solver::Pgs(PgsParams {
            tolerance,
            ..PgsParams::default()
        }),
        ..WorldSettings::default()
    };
    for bad in [-1e-6, f64::NAN, f64::INFINITY] {
        match with(bad).validate() {
            Err(WorldError::InvalidSettings { field, .. }) => assert_eq!(field, "tolerance"),
            other => panic!("tolerance {bad}: {other:?}"),
        }
    }
    assert!(with(0.0).validate().is_ok());
    assert!(WorldSettings::default().validate().is_ok());
}
