//! Scene files: the examples in `scenes/` load and run; every kind of invalid scene is rejected
//! with an error naming the field and the line.

use std::path::Path;

mod common;

use common::rejection;
use tatami_world::WorldSettings;
use tatami_world::scene::{Scene, SceneError};

/// A valid scene with one dynamic cube, laid out one field per line so errors have known lines.
/// `edit` replaces one line (1-based) to make it invalid.
fn scene_with(line: usize, replacement: &str) -> String {
    let lines = [
        r#"{"#,                                                  // 1
        r#"  "gravity": [0, 0, -9.8],"#,                         // 2
        r#"  "dt": 0.01,"#,                                      // 3
        r#"  "model": "vertex","#,                               // 4
        r#"  "bodies": ["#,                                      // 5
        r#"    { "name": "ground", "fixed": true,"#,             // 6
        r#"      "shape": { "box": { "size": [40, 40, 2] } },"#, // 7
        r#"      "position": [0, 0, -1] },"#,                    // 8
        r#"    { "name": "cube","#,                              // 9
        r#"      "shape": { "box": { "size": [2, 2, 2] } },"#,   // 10
        r#"      "mass": 1.0,"#,                                 // 11
        r#"      "friction": 0.5,"#,                             // 12
        r#"      "position": [0, 0, 1] } ] }"#,                  // 13
    ];
    let mut lines: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    if line > 0 {
        lines[line - 1] = replacement.to_owned();
    }
    lines.join("\n")
}

#[test]
fn the_unedited_scene_is_valid() {
    let scene = Scene::from_json(&scene_with(0, "")).unwrap();
    assert_eq!(scene.bodies.len(), 2);
    assert!(scene.world().is_ok());
}

#[test]
fn each_invalid_field_is_named_with_its_line() {
    // (line edited, new text, field, message, line reported)
    let cases: &[(usize, &str, &str, &str, usize)] = &[
        (11, r#"      "mass": 0,"#, "bodies[1].mass", "> 0", 11),
        (11, r#"      "mass": -2.5,"#, "bodies[1].mass", "> 0", 11),
        (
            10,
            r#"      "shape": { "box": { "size": [2, 0, 2] } },"#,
            "bodies[1].shape.box.size[1]",
            "> 0",
            10,
        ),
        (
            10,
            r#"      "shape": { "sphere": { "radius": -1 } },"#,
            "bodies[1].shape.sphere.radius",
            "> 0",
            10,
        ),
        (
            12,
            r#"      "friction": -0.1,"#,
            "bodies[1].friction",
            "≥ 0",
            12,
        ),
        (3, r#"  "dt": 0,"#, "dt", "> 0", 3),
        (4, r#"  "tolerance": -1e-4,"#, "tolerance", "≥ 0", 4),
        (3, r#"  "dt": -0.01,"#, "dt", "> 0", 3),
        (3, r#"  "dt": 1e400,"#, "dt", "number out of range", 3),
        (
            2,
            r#"  "gravity": [0, 0, -1e999],"#,
            "gravity[2]",
            "number out of range",
            2,
        ),
        (
            12,
            r#"      "friction": 0.5, "colour": "red","#,
            "bodies[1]",
            "unknown field `colour`",
            12,
        ),
        (
            3,
            r#"  "dt": 0.01, "substeps": 4,"#,
            "substeps",
            "unknown field `substeps`",
            3,
        ),
        (
            10,
            r#"      "shape": { "cone": { "radius": 1 } },"#,
            "bodies[1].shape",
            "unknown variant `cone`",
            10,
        ),
        (
            10,
            r#"      "shape": { "box": { "size": [2, 2, 2], "round": 1 } },"#,
            "bodies[1].shape.box",
            "unknown field `round`",
            10,
        ),
        (
            4,
            r#"  "model": "springs","#,
            "model",
            "unknown model `springs`",
            4,
        ),
        (
            11,
            r#"      "mass": 1.0, "density": 5,"#,
            "bodies[1]",
            "not both",
            13,
        ),
        (
            12,
            r#"      "friction": 0.5 "#,
            "bodies[1]",
            "expected `,` or `}`",
            13,
        ),
        (3, r#"  "dt": NaN,"#, "dt", "expected value", 3),
    ];
    for &(line, replacement, field, message, reported) in cases {
        let (got_field, got_line, got_message) = rejection(&scene_with(line, replacement));
        assert!(
            got_field.starts_with(field) || field.starts_with(&got_field),
            "{replacement}: field {got_field}, expected {field}"
        );
        // A body-level problem is reported where the body's object ends, a missing comma at the
        // next token: both on line 13.
        assert_eq!(
            got_line, reported,
            "{replacement} (line {line}): {got_message}"
        );
        assert!(
            got_message.contains(message),
            "{replacement}: message {got_message:?}"
        );
    }
}

#[test]
fn a_flat_convex_hull_is_rejected_with_the_body_line() {
    let flat = r#"      "shape": { "convex": { "points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]] } },"#;
    let (field, line, message) = rejection(&scene_with(10, flat));
    assert_eq!(field, "bodies[1]");
    assert_eq!(line, 13);
    assert!(message.contains("no volume"), "{message}");
}

#[test]
fn malformed_json_and_missing_files_are_errors() {
    let (field, line, _) = rejection("{\n  \"dt\": 0.01,\n  \"bodies\": [\n");
    assert_eq!((field.as_str(), line), ("bodies", 4));
    let missing = Scene::load("no/such/scene.json").unwrap_err();
    assert!(matches!(missing, SceneError::Io { .. }));
    assert!(missing.to_string().contains("no/such/scene.json"));
}

#[test]
fn solver_options_are_read() {
    let text = scene_with(
        4,
        r#"  "model": "face", "warm_start": true, "shock_propagation": true, "sleeping": true,"#,
    );
    let scene = Scene::from_json(&text).unwrap();
    assert!(scene.settings.shock_propagation);
    assert!(scene.settings.sleeping.enabled);
    assert_eq!(scene.settings.model, tatami_world::ContactModel::Face);
    let plain = Scene::from_json(&scene_with(0, "")).unwrap();
    assert!(plain.settings.shock_propagation, "on unless switched off");
    assert!(!plain.settings.sleeping.enabled, "off unless asked for");
    let without = Scene::from_json(&scene_with(4, r#"  "shock_propagation": false,"#)).unwrap();
    assert!(!without.settings.shock_propagation);
    let tolerance = |scene: &Scene| match scene.settings.solver {
        tatami_world::Solver::Pgs(p) => p.tolerance,
        tatami_world::Solver::Direct(_) => panic!("a PGS scene"),
    };
    assert_eq!(tolerance(&plain), tatami_world::PGS_TOLERANCE);
    let every_sweep = Scene::from_json(&scene_with(4, r#"  "tolerance": 0,"#)).unwrap();
    assert_eq!(tolerance(&every_sweep), 0.0);
    assert_eq!(every_sweep.pgs_settings, ["tolerance"]);
}

#[test]
fn contact_options_are_read_and_checked() {
    let text = scene_with(
        4,
        r#"  "friction_cone": "box", "max_depenetration_speed": 2.5, "max_velocity_bias": 0, "twist_centre": "centroid", "friction_limit": "separate", "slop": 0.0001, "contact_margin": 0.001, "max_substeps": 8,"#,
    );
    let settings = Scene::from_json(&text).unwrap().settings;
    assert_eq!(settings.contact_margin, 0.001);
    assert_eq!(settings.max_substeps, 8);
    assert_eq!(settings.contact.slop, 0.0001);
    let contact = settings.contact;
    assert_eq!(contact.friction_cone, tatami_world::FrictionCone::Box);
    assert_eq!(contact.twist_centre, tatami_world::TwistCentre::Centroid);
    assert_eq!(
        contact.friction_limit,
        tatami_world::FrictionLimit::Separate
    );
    assert_eq!(contact.max_depenetration_speed, 2.5);
    assert_eq!(contact.max_velocity_bias, 0.0);
    let plain_settings = Scene::from_json(&scene_with(0, "")).unwrap().settings;
    assert_eq!(
        plain_settings.max_substeps,
        tatami_world::MAX_SUBSTEPS,
        "substeps unless asked for"
    );
    assert_eq!(
        plain_settings.contact_margin,
        WorldSettings::default().contact_margin
    );
    let plain = plain_settings.contact;
    assert_eq!(
        plain.friction_cone,
        tatami_world::FrictionCone::Circle,
        "isotropic unless asked for"
    );
    assert_eq!(
        plain.twist_centre,
        tatami_world::TwistCentre::CentreOfPressure,
        "twist about the centre of pressure unless asked for"
    );
    assert_eq!(
        plain.friction_limit,
        tatami_world::FrictionLimit::Coupled,
        "force and twist on one limit surface unless asked for"
    );
    for (option, message) in [
        (r#"  "max_depenetration_speed": 0,"#, "> 0"),
        (r#"  "max_velocity_bias": -1,"#, "≥ 0"),
        (r#"  "contact_margin": -0.001,"#, "≥ 0"),
        (r#"  "max_substeps": 0,"#, "1 to 1000"),
        (r#"  "max_substeps": 1001,"#, "1 to 1000"),
        (r#"  "twist_centre": "origin","#, "unknown variant"),
        (r#"  "friction_limit": "box","#, "unknown variant"),
    ] {
        let (field, line, got) = rejection(&scene_with(4, option));
        let name = option.trim().split('"').nth(1).unwrap();
        assert_eq!((field.as_str(), line), (name, 4), "{option}");
        assert!(got.contains(message), "{option}: {got}");
    }
}

#[test]
fn every_example_scene_loads_and_runs() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(&folder).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut world = scene.world().unwrap();
        for _ in 0..10 {
            world.step(scene.dt).unwrap();
        }
        count += 1;
    }
    assert!(count >= 4, "found {count} scenes in {}", folder.display());
}

/// Every example scene turned whole — bodies, velocities and gravity — runs the same course:
/// nothing in the step may favour the world's axes (the floor's normal along z, gravity along
/// −z). Turned so that y is up, as many tools have it, and by 37° about an arbitrary axis, each
/// run's positions, turned back, stay within 1 mm of the scene's own at every step: rounding
/// in the turned frame, grown through the contacts' events, was measured at 0.05 mm at most
/// (the pyramid of 55). Left out, as chaotic: the paddle sweep, the grasp and the ledge, where
/// a body tumbles off an edge and the same rounding grows to centimetres.
#[test]
fn every_example_scene_turned_whole_runs_the_same_course() {
    use nalgebra::{Unit, UnitQuaternion, Vector3};
    let turns = [
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), -std::f64::consts::FRAC_PI_2),
        UnitQuaternion::from_axis_angle(
            &Unit::new_normalize(Vector3::new(1.0, 2.0, 3.0)),
            37f64.to_radians(),
        ),
    ];
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(&folder).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.extension().and_then(|e| e.to_str()) != Some("json")
            || ["paddle_sweep", "grasp", "ledge"].contains(&name.as_str())
        {
            continue;
        }
        let scene = Scene::load(&path).unwrap();
        let mut own = scene.world().unwrap();
        let mut worlds: Vec<_> = turns
            .iter()
            .map(|turn| {
                let mut turned = scene.clone();
                turned.gravity = turn * turned.gravity;
                for body in &mut turned.bodies {
                    body.position = turn * body.position;
                    body.rotation = turn * body.rotation;
                    body.velocity = turn * body.velocity;
                    body.angular_velocity = turn * body.angular_velocity;
                }
                turned.world().unwrap()
            })
            .collect();
        let mut apart: f64 = 0.0;
        for _ in 0..scene.steps {
            own.step(scene.dt).unwrap();
            for (world, turn) in worlds.iter_mut().zip(&turns) {
                world.step(scene.dt).unwrap();
                for (a, b) in own.bodies().iter().zip(world.bodies()) {
                    apart = apart.max((a.position() - turn.inverse() * b.position()).norm());
                }
            }
        }
        assert!(apart < 1e-3, "{name}: the turned runs part by {apart} m");
        count += 1;
    }
    assert!(count >= 10, "found {count} scenes in {}", folder.display());
}
