//! `cargo xtask view`: one self-contained HTML page that replays a scene in 3-D — every shape as
//! it is, orbit/pan/zoom, play, pause, a time slider, playback speed — with each contact's
//! support polygon, centre of pressure and normal force drawn on request.
//!
//! The page embeds three.js (vendored in `xtask/assets/three`, see its README) and the
//! recording as JSON, so it works opened from disk, with no network and no server. Its contract
//! for automated checks: once drawn, `<body>` carries `data-ready="true"`, `data-frames` and
//! `data-bodies`, and `window.tatami` offers `seek(time)` and the counts `frames` and `bodies`
//! (and `data`, the recording). `data-step` and `data-time` follow the frame shown.

mod recording;

use std::path::{Path, PathBuf};

use recording::Recording;

use crate::simulate::{self, Overrides};

/// Options of `cargo xtask view`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The scene file (JSON).
    scene: PathBuf,
    #[command(flatten)]
    overrides: Overrides,
    /// Replay this trajectory CSV of the scene (from `cargo xtask simulate`) instead of
    /// simulating it; it has no contacts to draw.
    #[arg(long)]
    trajectory: Option<PathBuf>,
    /// Record every K-th step (step 0 and the last are always recorded); by default the
    /// fewest steps apart that keep 60 frames per simulated second.
    #[arg(long)]
    every: Option<usize>,
    /// The page to write; `target/view/<scene>.html` by default.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// three.js and its orbit controls, from the npm release (see `xtask/assets/three`).
const THREE: &str = include_str!("../../assets/three/three.module.min.js");
const ORBIT_CONTROLS: &str = include_str!("../../assets/three/OrbitControls.js");
const TEMPLATE: &str = include_str!("page.html");

/// Simulates or replays the scene and writes the page.
pub fn run(args: &Args) -> Result<(), String> {
    let scene = simulate::load(&args.scene, &args.overrides)?;
    let every = match args.every {
        Some(0) => return Err("--every must be ≥ 1".into()),
        Some(k) => k,
        None => ((1.0 / 60.0) / scene.dt).ceil().max(1.0) as usize,
    };
    let stem = args
        .scene
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let recording = match &args.trajectory {
        Some(path) => Recording::replay(&stem, &scene, path)?,
        None => Recording::simulate(&stem, &scene, every)?,
    };
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new("target/view").join(format!("{stem}.html")));
    if let Some(folder) = out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    }
    std::fs::write(&out, page(&recording)).map_err(|e| format!("{}: {e}", out.display()))?;
    eprintln!(
        "{}: {} frames of {} bodies",
        out.display(),
        recording.frames.len(),
        recording.bodies.len()
    );
    Ok(())
}

/// The page: the template with three.js, the controls and the recording put in.
fn page(recording: &Recording) -> String {
    // `<` only ever appears inside JSON strings, where `\u003c` means the same; so no name can
    // close the script element or open a comment in it.
    let data = serde_json::to_string(recording)
        .expect("a recording is plain data")
        .replace('<', "\\u003c");
    TEMPLATE
        .replace("{{title}}", &html_escape(&recording.scene))
        .replace("/*{{three}}*/", THREE)
        .replace("/*{{orbit_controls}}*/", ORBIT_CONTROLS)
        .replace("{{recording}}", &data)
}

fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use tatami_world::scene::Scene;

    /// The recording embedded in `page`, parsed back.
    fn embedded(page: &str) -> serde_json::Value {
        let open = r#"<script type="application/json" id="tatami-data">"#;
        let start = page.find(open).expect("data element") + open.len();
        let end = start + page[start..].find("</script>").expect("closed");
        serde_json::from_str(&page[start..end]).expect("valid JSON")
    }

    fn scene(name: &str) -> Scene {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../scenes")
            .join(name);
        Scene::load(&path).unwrap()
    }

    /// The vendored sources can sit in a script element whole: nothing in them closes it or
    /// opens an HTML comment, and the controls import three by the name the page replaces.
    #[test]
    fn the_vendored_sources_embed_as_they_are() {
        for source in [THREE, ORBIT_CONTROLS] {
            assert!(!source.contains("</script") && !source.contains("<!--"));
        }
        assert!(ORBIT_CONTROLS.contains("from 'three';"));
        assert!(THREE.contains("WebGLRenderer"));
    }

    /// A simulated tower's page (face model, which holds it still) holds the whole library, one frame per recorded step with a pose
    /// per body, and the contacts of every frame after the first: the weight each contact carries
    /// grows down the tower, and its centre of pressure is on the support polygon's plane.
    #[test]
    fn a_page_embeds_its_frames_bodies_and_contacts() {
        let mut scene = scene("tower_10.json");
        scene.steps = 100;
        scene.settings.model = tatami_world::ContactModel::Face;
        let recording = Recording::simulate("tower_10", &scene, 30).unwrap();
        let html = page(&recording);
        assert!(html.starts_with("<!doctype html>"));
        assert!(html.contains(THREE) && html.contains(ORBIT_CONTROLS));
        assert!(
            !html.contains("{{") && !html.contains("/*{{"),
            "every slot filled"
        );
        assert!(html.contains("<title>Tatami — tower_10</title>"));
        let data = embedded(&html);
        let bodies = data["bodies"].as_array().unwrap();
        assert_eq!(bodies.len(), 11, "the floor and ten cubes");
        assert_eq!(bodies[0]["kind"], "fixed");
        assert_eq!(bodies[1]["shape"]["box"]["size"][0], 2.0);
        let frames = data["frames"].as_array().unwrap();
        let steps: Vec<_> = frames.iter().map(|f| f["step"].as_u64().unwrap()).collect();
        assert_eq!(steps, [0, 30, 60, 90, 100]);
        for frame in frames {
            assert_eq!(frame["poses"].as_array().unwrap().len(), 7 * 11);
        }
        assert!(frames[0]["contacts"].as_array().unwrap().is_empty());
        let last = frames.last().unwrap()["contacts"].as_array().unwrap();
        assert_eq!(last.len(), 10, "one face contact per level");
        let force = |c: &serde_json::Value| c["force"].as_f64().unwrap();
        let mut forces: Vec<_> = last.iter().map(force).collect();
        forces.sort_by(f64::total_cmp);
        for (k, f) in forces.iter().enumerate() {
            // Level k from the top carries k + 1 cubes of 1 kg: within 1% after 100 steps (the
            // scene's solver is cold-started, so it settles over the first steps).
            let weight = (k + 1) as f64 * 9.8;
            assert!((f - weight).abs() < 0.01 * weight, "{f} N for {weight} N");
        }
        for contact in last {
            let cop_z = contact["cop"][2].as_f64().unwrap();
            let polygon = contact["polygon"].as_array().unwrap();
            assert_eq!(polygon.len(), 12, "four vertices, x, y, z each");
            for z in polygon.iter().skip(2).step_by(3) {
                assert!((cop_z - z.as_f64().unwrap()).abs() < 1e-5, "a level face");
            }
            assert_eq!(contact["up"][2], 1.0);
        }
        let largest = frames
            .iter()
            .flat_map(|f| f["contacts"].as_array().unwrap().iter().map(force))
            .fold(0.0, f64::max);
        assert_eq!(data["max_normal_force"].as_f64().unwrap(), largest);
    }

    /// Every shape is sent as it is — a hull as outward triangles over its vertices — and a body
    /// named to break out of the script element stays inside it.
    #[test]
    fn shapes_and_hostile_names_embed_safely() {
        let scene = Scene::from_json(
            r#"{ "bodies": [
              { "name": "</script><!--", "shape": { "convex": { "points":
                [[0,0,0],[1,0,0],[0,1,0],[0,0,1],[1,1,1],[0.2,0.2,0.2]] } } },
              { "shape": { "cylinder": { "radius": 0.5, "height": 2 } }, "position": [3, 0, 0] },
              { "shape": { "sphere": { "radius": 0.5 } }, "position": [6, 0, 0] } ] }"#,
        )
        .unwrap();
        let world = scene.world().unwrap();
        let recording = Recording::new("<hull>", "face", &world);
        let html = page(&recording);
        assert_eq!(html.matches("</script>").count(), 4, "only the page's own");
        assert!(html.contains("<title>Tatami — &lt;hull&gt;</title>"));
        let data = embedded(&html);
        assert_eq!(data["bodies"][0]["name"], "</script><!--");
        let hull = &data["bodies"][0]["shape"]["convex"];
        let vertices = hull["vertices"].as_array().unwrap().len() / 3;
        assert_eq!(vertices, 5, "the interior point is not a vertex");
        let triangles = hull["triangles"].as_array().unwrap();
        assert_eq!(triangles.len(), 3 * 6, "a triangular bipyramid has 6 faces");
        assert!(
            triangles
                .iter()
                .all(|i| (i.as_u64().unwrap() as usize) < vertices)
        );
        assert_eq!(data["bodies"][1]["shape"]["cylinder"]["height"], 2.0);
        assert_eq!(data["bodies"][2]["shape"]["sphere"]["radius"], 0.5);
    }

    /// A replayed trajectory moves the bodies it names and keeps the fixed ones where the scene
    /// has them; a trajectory naming a body the scene lacks is refused with its line.
    #[test]
    fn a_trajectory_replays_onto_its_scene() {
        let scene = scene("cube_on_floor.json");
        let folder = std::env::temp_dir().join(format!("tatami-view-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let path = folder.join("t.csv");
        let header = crate::trajectory::HEADER.join(",");
        let cube = scene.world().unwrap().bodies()[1].name().to_owned();
        std::fs::write(
            &path,
            format!(
                "{header}\n0,0.0,{cube},0,0,1,1,0,0,0,0,0,0,0,0,0\n\
                 5,0.05,{cube},0.5,0,1,1,0,0,0,0,0,0,0,0,0\n"
            ),
        )
        .unwrap();
        let recording = Recording::replay("cube", &scene, &path).unwrap();
        assert_eq!(recording.frames.len(), 2);
        assert_eq!(recording.frames[1].poses[7], 0.5, "the cube's x");
        let floor = scene.world().unwrap().bodies()[0].position();
        assert_eq!(recording.frames[1].poses[2], floor.z, "the floor stays");
        std::fs::write(
            &path,
            format!("{header}\n0,0.0,nobody,0,0,1,1,0,0,0,0,0,0,0,0,0\n"),
        )
        .unwrap();
        let error = Recording::replay("cube", &scene, &path).unwrap_err();
        assert!(error.contains(":2:") && error.contains("nobody"), "{error}");
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
