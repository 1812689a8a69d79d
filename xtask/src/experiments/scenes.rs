//! The experiments' scenes, compiled in from `scenes/`: the figures are made from the very files
//! a user runs with `cargo xtask simulate`.

use tatami_world::scene::Scene;
use tatami_world::{ContactModel, PgsParams, Solver, World, WorldSettings};

/// A scene file of `scenes/`, by name and contents.
pub struct SceneFile {
    /// File name in `scenes/`.
    pub name: &'static str,
    text: &'static str,
}

macro_rules! scene_file {
    ($name:literal) => {
        SceneFile {
            name: $name,
            text: include_str!(concat!("../../../scenes/", $name)),
        }
    };
}

/// 100 cubes of 2 m on the floor, the paper's settings (stack timing, PGS error).
pub const TOWER: SceneFile = scene_file!("tower_100.json");
/// A cube released on one edge, 5° past balance (edge toppling).
pub const EDGE: SceneFile = scene_file!("cube_on_edge.json");
/// A cube released on one corner, tilted 2° off balance (point toppling).
pub const CORNER: SceneFile = scene_file!("cube_on_corner.json");
/// A cube on a 4 m ledge, 0.2 m over its edge (ledge sweep).
pub const LEDGE: SceneFile = scene_file!("ledge.json");
/// A cube spinning flat at 5 rad/s (spin-down).
pub const CUBE_SPIN: SceneFile = scene_file!("cube_spin.json");
/// A standing cylinder spinning at 5 rad/s (spin-down).
pub const CYLINDER_SPIN: SceneFile = scene_file!("cylinder_spin.json");
/// A 0.1 m disc sliding at 1 m/s and spinning at 2 m/s at its rim (planar sliding).
pub const SLIDING_SPIN: SceneFile = scene_file!("sliding_spin.json");
/// A cube sliding at 5 m/s, 30° off the x axis (friction isotropy).
pub const DIAGONAL_SLIDE: SceneFile = scene_file!("diagonal_slide.json");
/// A 1×2×3 m box tumbling at ω = (1, 2, 3) rad/s in zero gravity (free rotation).
pub const TUMBLING_BOX: SceneFile = scene_file!("tumbling_box.json");
/// A 0.2×1×2 m plate spun about its intermediate axis, 1% off (free rotation).
pub const INTERMEDIATE_AXIS: SceneFile = scene_file!("intermediate_axis.json");
/// A cone spun on its tip (the spinning-top experiment).
pub const SPINNING_TOP: SceneFile = scene_file!("spinning_top.json");
/// Two unit cubes, the upper 0.2 m off centre (holding).
pub const OFFSET_PAIR: SceneFile = scene_file!("offset_pair.json");
/// Six unit cubes leaning 0.1 m per level (holding).
pub const LEANING_STACK: SceneFile = scene_file!("leaning_stack.json");
/// A 1 kg cube under a 1000 kg one (holding).
pub const HEAVY_ON_LIGHT: SceneFile = scene_file!("heavy_on_light.json");
/// A pyramid of 55 unit cubes, 1 mm gaps (holding).
pub const PYRAMID_55: SceneFile = scene_file!("pyramid_55.json");
/// 100 cubes of 2 m stepped at 60 Hz (holding).
pub const TOWER_100_60HZ: SceneFile = scene_file!("tower_100_60hz.json");

impl SceneFile {
    /// The parsed scene.
    pub fn load(&self) -> Result<Scene, String> {
        Scene::from_json(self.text).map_err(|e| format!("scenes/{}: {e}", self.name))
    }
}

/// The world of `scene` under `model` with the paper's solver: 15 PGS sweeps from zero impulses
/// and [`springhead_penetration`].
pub fn paper_world(scene: &Scene, model: ContactModel) -> Result<World, String> {
    let mut scene = scene.clone();
    scene.settings.model = model;
    scene.settings.solver = Solver::Pgs(PgsParams::default());
    scene.settings = springhead_penetration(scene.settings);
    scene.world().map_err(|e| e.to_string())
}

/// `settings` with the whole penetration push in the velocity solve at Springhead's rate (a
/// Baumgarte bias, as Springhead and the paper do) instead of Tatami's default, which moves
/// positions only. Without warm starting, the bias is what holds tall stacks against the
/// solver's residual: with the paper's 15 sweeps the face model's tower stands to 50 cubes with
/// it and to 10 without.
pub fn springhead_penetration(mut settings: WorldSettings) -> WorldSettings {
    settings.contact.bias_rate = SPRINGHEAD_BIAS_RATE;
    settings.contact.max_velocity_bias = settings.contact.max_depenetration_speed;
    settings
}

/// Springhead's penetration bias: a tenth of the depth beyond the slop per step.
pub const SPRINGHEAD_BIAS_RATE: f64 = 0.1;

/// Steps `world` by `dt`, naming the step in the error.
pub fn step(world: &mut World, dt: f64) -> Result<(), String> {
    world
        .step(dt)
        .map_err(|e| format!("step {}: {e}", world.steps() + 1))
}

/// Runs `scene` for its steps under `model` with the paper's solver, calling `each` after every
/// step with the step number (from 1).
pub fn run_paper(
    scene: &Scene,
    model: ContactModel,
    mut each: impl FnMut(usize, &World),
) -> Result<World, String> {
    let mut world = paper_world(scene, model)?;
    for n in 1..=scene.steps {
        step(&mut world, scene.dt).map_err(|e| format!("{} model: {e}", model.name()))?;
        each(n, &world);
    }
    Ok(world)
}

/// The kinetic friction coefficient between two bodies of a scene: the mean of theirs, as the
/// engine pairs them (`tatami-world`'s `collision::combine`).
pub fn kinetic_friction(a: &tatami_world::BodyDesc, b: &tatami_world::BodyDesc) -> f64 {
    0.5 * (a.kinetic_friction + b.kinetic_friction)
}

/// The edge length of a cubic box shape, if `shape` is one.
pub fn cube_side(shape: &tatami_world::Shape) -> Option<f64> {
    match shape {
        tatami_world::Shape::Box { half_extents }
            if half_extents
                .iter()
                .all(|&h| (h - half_extents.x).abs() < 1e-12) =>
        {
            Some(2.0 * half_extents.x)
        }
        _ => None,
    }
}
