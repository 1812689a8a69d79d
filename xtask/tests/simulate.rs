//! `cargo xtask simulate` end to end: header, recorded steps, overrides and errors.

mod common;

use std::path::{Path, PathBuf};

use common::xtask;

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
}

#[test]
fn writes_the_trajectory_with_every_kth_step_and_the_last() {
    let path = scene("cube_on_floor.json");
    let out = xtask(&[
        "simulate",
        path.to_str().unwrap(),
        "--steps",
        "25",
        "--every",
        "10",
        "--dt",
        "0.005",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("step,time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let steps: Vec<&str> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(
        steps,
        ["0", "10", "20", "25"],
        "one dynamic body per recorded step"
    );
    // --dt overrides the scene: step 20 is at 0.1 s.
    assert!((rows[2][1].parse::<f64>().unwrap() - 0.1).abs() < 1e-12);
    assert!(rows.iter().all(|r| r.len() == 16 && r[2] == "cube"));
    let summary = String::from_utf8_lossy(&out.stderr);
    assert!(
        summary.contains("25 steps") && summary.contains("ms/step"),
        "{summary}"
    );
}

#[test]
fn bad_input_is_one_line_and_a_failure_status() {
    let missing = xtask(&["simulate", "no/such/scene.json"]);
    assert!(!missing.status.success());
    let message = String::from_utf8_lossy(&missing.stderr);
    assert_eq!(message.trim().lines().count(), 1, "{message}");
    assert!(message.starts_with("error: ") && message.contains("no/such/scene.json"));

    let path = scene("cube_on_floor.json");
    let zero_dt = xtask(&["simulate", path.to_str().unwrap(), "--dt", "0"]);
    assert!(!zero_dt.status.success());
    assert!(String::from_utf8_lossy(&zero_dt.stderr).contains("--dt"));

    let model = xtask(&["simulate", path.to_str().unwrap(), "--model", "springs"]);
    assert!(!model.status.success());
    assert!(String::from_utf8_lossy(&model.stderr).contains("unknown model `springs`"));
}

/// Every model runs under the direct solver. PGS-only settings given explicitly (by the scene or
/// the command line) are named in one line on standard error; the defaults say nothing.
#[test]
fn the_direct_solver_runs_every_model_and_names_the_pgs_settings_it_ignores() {
    let tower = scene("tower_10.json"); // sets "iterations" and "warm_start"
    let pair = scene("offset_pair.json"); // sets no solver setting
    for model in ["vertex", "patch", "face"] {
        let out = xtask(&[
            "simulate",
            pair.to_str().unwrap(),
            "--solver",
            "direct",
            "--model",
            model,
            "--steps",
            "20",
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{model}: {stderr}");
        assert!(!stderr.contains("ignores"), "{model}: {stderr}");
    }
    let out = xtask(&[
        "simulate",
        tower.to_str().unwrap(),
        "--solver",
        "direct",
        "--iterations",
        "4",
        "--steps",
        "5",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let notes: Vec<&str> = stderr.lines().filter(|l| l.contains("ignores")).collect();
    assert_eq!(notes.len(), 1, "{stderr}");
    assert!(
        notes[0].contains("`iterations`")
            && notes[0].contains("`warm_start`")
            && notes[0].contains("--iterations"),
        "{stderr}"
    );
}
