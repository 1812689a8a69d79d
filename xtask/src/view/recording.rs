//! What a page shows: the bodies' shapes, and per frame every body's pose and every contact's
//! support polygon, centre of pressure and normal force — recorded from a simulation, or read
//! back from a trajectory CSV (which has no contacts).

use std::collections::HashMap;
use std::path::Path;

use nalgebra::Vector3;
use serde::Serialize;
use tatami_world::scene::Scene;
use tatami_world::{Body, Shape, World};

use crate::trajectory;

/// Everything a page draws.
#[derive(Debug, Serialize)]
pub struct Recording {
    /// The scene's file name.
    pub scene: String,
    /// Contact model name, or `trajectory` for a replay.
    pub source: String,
    /// The bodies, in the world's order.
    pub bodies: Vec<BodyView>,
    /// Step 0, every recorded step, and the last.
    pub frames: Vec<Frame>,
    /// Largest normal force of any contact in any frame (N): arrows are drawn relative to it.
    pub max_normal_force: f64,
    /// Height of the ground plane's grid: the top of the widest fixed box, or 0.
    pub ground: f64,
}

/// A body as drawn.
#[derive(Debug, Serialize)]
pub struct BodyView {
    pub name: String,
    /// `dynamic`, `fixed` or `kinematic`.
    pub kind: &'static str,
    pub shape: ShapeView,
}

/// A shape in the body frame.
#[derive(Debug, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ShapeView {
    Box {
        size: [f64; 3],
    },
    Sphere {
        radius: f64,
    },
    /// Along the body's z axis.
    Cylinder {
        radius: f64,
        height: f64,
    },
    /// The hull: vertices as x, y, z triples, triangles as index triples wound outwards.
    Convex {
        vertices: Vec<f64>,
        triangles: Vec<u32>,
    },
}

/// One instant.
#[derive(Debug, Serialize)]
pub struct Frame {
    pub step: usize,
    pub time: f64,
    /// Per body, in order: origin x, y, z and orientation qw, qx, qy, qz.
    pub poses: Vec<f64>,
    pub contacts: Vec<ContactView>,
}

/// One contact as drawn.
#[derive(Debug, Serialize)]
pub struct ContactView {
    /// Indices of the two bodies in [`Recording::bodies`].
    pub a: usize,
    pub b: usize,
    /// Normal force (N).
    pub force: f64,
    /// Centre of pressure (world).
    pub cop: [f64; 3],
    /// Unit direction of the normal force on the upper of the two bodies (against gravity; on
    /// A for a contact with a horizontal normal).
    pub up: [f64; 3],
    /// Support polygon, x, y, z per vertex.
    pub polygon: Vec<f64>,
}

/// Metres to a micrometre, unit quaternion components to 1e-8: far below what a screen shows,
/// and a page a third the size of one with every digit.
fn round(x: f64, scale: f64) -> f64 {
    (x * scale).round() / scale
}

impl Recording {
    /// The bodies of `world` and no frames yet.
    pub fn new(scene: &str, source: &str, world: &World) -> Self {
        let bodies: Vec<_> = world.bodies().iter().map(body_view).collect();
        let ground = world
            .bodies()
            .iter()
            .filter(|b| b.is_fixed() && b.rotation().angle() == 0.0)
            .filter_map(|b| match b.shape() {
                Shape::Box { half_extents: h } => Some((h.x * h.y, b.position().z + h.z)),
                _ => None,
            })
            .max_by(|x, y| x.0.total_cmp(&y.0))
            .map_or(0.0, |(_, top)| top);
        Self {
            scene: scene.to_owned(),
            source: source.to_owned(),
            bodies,
            frames: Vec::new(),
            max_normal_force: 0.0,
            ground,
        }
    }

    /// Records `world` now as step `step`, with its last step's contacts.
    pub fn record(&mut self, step: usize, world: &World) {
        let poses = world.bodies().iter().flat_map(pose).collect();
        let up = -world.gravity();
        let contacts: Vec<_> = world
            .contact_wrenches()
            .filter_map(|w| {
                let a = world.index_of(w.body_a).ok()?;
                let b = world.index_of(w.body_b).ok()?;
                let sign = if w.normal.dot(&up) >= 0.0 { 1.0 } else { -1.0 };
                let direction: Vector3<f64> = w.normal * sign;
                Some(ContactView {
                    a,
                    b,
                    force: round(w.normal_force, 1e6),
                    cop: w.centre_of_pressure.coords.map(|x| round(x, 1e6)).into(),
                    up: direction.map(|x| round(x, 1e8)).into(),
                    polygon: w
                        .support
                        .iter()
                        .flat_map(|p| p.iter().map(|x| round(*x, 1e6)).collect::<Vec<_>>())
                        .collect(),
                })
            })
            .collect();
        for contact in &contacts {
            self.max_normal_force = self.max_normal_force.max(contact.force);
        }
        self.frames.push(Frame {
            step,
            time: world.time(),
            poses,
            contacts,
        });
    }

    /// Runs `scene` for its steps, recording step 0, every `every`-th step and the last.
    pub fn simulate(name: &str, scene: &Scene, every: usize) -> Result<Self, String> {
        let mut world = scene.world().map_err(|e| e.to_string())?;
        let mut recording = Self::new(name, world.settings().model.name(), &world);
        recording.record(0, &world);
        for step in 1..=scene.steps {
            world
                .step(scene.dt)
                .map_err(|e| format!("step {step}: {e}"))?;
            if step % every == 0 || step == scene.steps {
                recording.record(step, &world);
            }
        }
        Ok(recording)
    }

    /// Reads back the trajectory CSV at `path` of `scene`'s bodies: the bodies it names move,
    /// the others (fixed ones) stay where the scene puts them. Every row is checked.
    pub fn replay(name: &str, scene: &Scene, path: &Path) -> Result<Self, String> {
        let world = scene.world().map_err(|e| e.to_string())?;
        let mut recording = Self::new(name, "trajectory", &world);
        let initial: Vec<f64> = world.bodies().iter().flat_map(pose).collect();
        let index: HashMap<&str, usize> = world
            .bodies()
            .iter()
            .enumerate()
            .map(|(k, b)| (b.name(), k))
            .collect();
        let fail = |line: u64, reason: String| format!("{}:{line}: {reason}", path.display());
        let mut reader =
            csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let header = reader.headers().map_err(|e| fail(1, e.to_string()))?;
        if header.iter().ne(trajectory::HEADER) {
            return Err(fail(
                1,
                format!(
                    "not a trajectory: the header must be `{}`",
                    trajectory::HEADER.join(",")
                ),
            ));
        }
        for record in reader.records() {
            let record = record.map_err(|e| e.to_string())?;
            let line = record.position().map_or(0, |p| p.line());
            let number = |k: usize| -> Result<f64, String> {
                record[k]
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| fail(line, format!("`{}` is not a finite number", &record[k])))
            };
            let step: usize = record[0]
                .parse()
                .map_err(|_| fail(line, format!("`{}` is not a step number", &record[0])))?;
            let time = number(1)?;
            let body = *index.get(&record[2]).ok_or_else(|| {
                fail(
                    line,
                    format!("the scene has no body named `{}`", &record[2]),
                )
            })?;
            let new_frame = recording.frames.last().is_none_or(|f| f.step != step);
            if new_frame {
                if recording.frames.last().is_some_and(|f| f.step > step) {
                    return Err(fail(line, format!("step {step} comes after a later step")));
                }
                recording.frames.push(Frame {
                    step,
                    time,
                    poses: initial.clone(),
                    contacts: Vec::new(),
                });
            }
            let frame = recording.frames.last_mut().expect("pushed above");
            for (k, column) in (3..10).enumerate() {
                frame.poses[7 * body + k] = round(number(column)?, 1e8);
            }
        }
        if recording.frames.is_empty() {
            return Err(format!("{}: the trajectory has no rows", path.display()));
        }
        Ok(recording)
    }
}

fn body_view(body: &Body) -> BodyView {
    let shape = match body.shape() {
        Shape::Box { half_extents: h } => ShapeView::Box {
            size: (h * 2.0).into(),
        },
        Shape::Sphere { radius } => ShapeView::Sphere { radius: *radius },
        Shape::Cylinder {
            radius,
            half_height,
        } => ShapeView::Cylinder {
            radius: *radius,
            height: 2.0 * half_height,
        },
        convex @ Shape::Convex { .. } => {
            let hull = convex.hull_mesh().unwrap_or_default();
            ShapeView::Convex {
                vertices: hull
                    .vertices
                    .iter()
                    .flat_map(|p| p.coords.iter().copied())
                    .collect(),
                triangles: hull.triangles.into_iter().flatten().collect(),
            }
        }
    };
    BodyView {
        name: body.name().to_owned(),
        kind: body.kind().name(),
        shape,
    }
}

/// Origin and orientation, rounded.
fn pose(body: &Body) -> [f64; 7] {
    let p = body.position();
    let q = body.rotation();
    [
        round(p.x, 1e6),
        round(p.y, 1e6),
        round(p.z, 1e6),
        round(q.w, 1e8),
        round(q.i, 1e8),
        round(q.j, 1e8),
        round(q.k, 1e8),
    ]
}
