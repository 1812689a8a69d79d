//! Substeps: a step of `dt` split into equal substeps when the world's bodies are small for it.
//!
//! What one step leaves undone grows as `g h²` against the bodies' size: the solve's residual is
//! a share of gravity's `g h` a step, and the overlap it lets in, `g h²` times that share, is
//! pushed out by a position pass that turns and shifts the bodies it pushes. Measured in one
//! step each at 60 Hz, 300 cubes poured into a walled bin settle within 6 s when they are 30 or
//! 50 cm wide (`g h² / L` = 0.009 and 0.005); at 10–20 cm (0.014–0.027) they kept churning at
//! 0.3–0.7 m/s with 1–2 cm overlaps after 10 s, under every model (Rapier 0.36 settles the
//! 10 cm bin). Twice the sweeps did not settle them; twice the rate did, by 2 s, its step
//! costing less over those seconds than the churning one. Small bodies land as large ones do
//! too: three stacked 1 cm cylinders went 6.7 mm into each other under the vertex model (0.35
//! mm in substeps), and stacked cubes of 1–4 cm rested at the slop, a tenth of their size,
//! where in substeps they rest within a hundredth.
//!
//! So a step is split into the fewest substeps `n` that bring `g (dt/n)²` within
//! [`SAG_SHARE`] of the typical body's thickness (the median of the awake dynamic bodies' least
//! widths), at most [`WorldSettings::max_substeps`](crate::WorldSettings::max_substeps). A
//! world of 1 m bodies at 60 Hz, or of 2 m bodies at 100 Hz, takes one; 10 cm bodies at 60 Hz
//! take two; 1 cm ones six. The median, not the thinnest, so that a few small bodies do not
//! multiply the cost of a pile of large ones.
//!
//! Each substep is a whole step of `dt/n`; forces set for the step act in every substep, a
//! kinematic body sent to a target goes a share of the way in each, and a grip's press gives
//! the force it gives in one step of `dt`.
//!
//! A kinematic body's change of velocity is spread over the substeps ([`StepInputs`]); given
//! all at once at the step's start, the bodies it carries had to take it within the first
//! substep with a substep's share of friction, and a tall box on an accelerating platform went
//! over at 97% of its tipping acceleration. What substeps still cost, measured against one
//! step each: four 1 g cubes under a 100–1000 kg slab dropped on them (10⁵ : 1) are knocked up
//! to 19 mm aside instead of 7 (face model) and 11 mm instead of 0.1 (vertex), the slab rocking
//! on them after it lands; a 20 cm cube held by kinematic fingers that reach 0.3 m/s within
//! one step slips 0.36 mm and turns 1 mrad (face model; 2–5 µm in one step); a small-body
//! world's step costs up to `n` times as much. Worlds of 1 m bodies at 60 Hz (the piles,
//! pyramids and towers of the benchmarks) or 2 m bodies at 100 Hz (the paper's) take one
//! substep and are stepped to the same bits as before.
//!
//! A body that turns fast while it touches something splits the step too, into substeps in
//! which it turns by at most [`MAX_SUBSTEP_TURN`]. The contact rows hold its points' velocities
//! at the step's start, as though they moved along straight lines, while the integrator turns
//! it along the free-rotation path, on which its own angular velocity turns about its angular
//! momentum; over a large turn the two part. A top of 1 kg (a cone 20 cm tall, 20 cm across)
//! spun at 200 rad/s and let go on its tip tilted 20° should nod between 20° and 25.8° and
//! precess at 2.79 rad/s over its first 2 s (a fixed-tip top, integrated apart,
//! [`crate::heavy_top`]); in one step each at 100 Hz (2 rad a step) its tip sank 0.3 mm a step
//! and it fell over within a second; at 60 Hz too. Only a body's turn that moves its shape
//! counts: none for a ball, and none about a cylinder's axis, so a rolling ball or wheel takes
//! one step.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use tatami_contact::Contact;

use crate::Body;

/// Most a step's gravity fall `g h²` may be of the typical body's thickness before the step is
/// split (see the module doc): between the 30 cm cubes' 0.009, which settle in a bin at 60 Hz,
/// and the 20 cm cubes' 0.014, which do not.
pub const SAG_SHARE: f64 = 0.01;

/// Most a dynamic body touching another may turn in a substep (rad; see the module doc): the
/// spinning top of the module doc, at 60 Hz in seven substeps, nodded within 3.4° of the
/// fixed-tip top's lowest point and precessed within 4.2% over 2 s, but sank to 44° within
/// 10 s; with the rows' bends over each substep ([`tatami_contact::turns`]) it keeps within
/// 1° and 1% over 10 s. Half a radian a step at 60 Hz is 30 rad/s: of the 1000-body piles'
/// bodies, tumbling as they land, one reached it in one step (at a quarter radian, 75 steps),
/// and the pyramids' and towers' none.
pub const MAX_SUBSTEP_TURN: f64 = 0.5;

/// Substeps of a step of `dt` for `bodies` under `gravity` touching as `contacts` pair them,
/// from 1 to `max`: for gravity's fall against the typical body's thickness, and for the
/// fastest turn of a body touching another ([`MAX_SUBSTEP_TURN`]). `scratch` is scratch.
pub(crate) fn count<'a>(
    bodies: &[Body],
    contacts: impl Iterator<Item = &'a Contact>,
    gravity: &Vector3<f64>,
    dt: f64,
    max: usize,
    scratch: &mut Scratch,
) -> usize {
    if max <= 1 {
        return 1;
    }
    let needed = for_the_fall(bodies, gravity, dt, &mut scratch.thicknesses).max(for_the_turns(
        bodies,
        contacts,
        dt,
        &mut scratch.touching,
    ));
    // Not NaN: thicknesses are positive and finite, gravity, velocities and dt are validated.
    (needed as usize).clamp(1, max)
}

/// Buffers reused by [`count`].
#[derive(Debug, Clone, Default)]
pub(crate) struct Scratch {
    /// The awake dynamic bodies' thicknesses.
    thicknesses: Vec<f64>,
    /// Per body: whether it touches another.
    touching: Vec<bool>,
}

/// Substeps (not rounded to an integer count yet, at least 1) that keep `g (dt/n)²` within
/// [`SAG_SHARE`] of the median thickness of the awake dynamic bodies.
fn for_the_fall(
    bodies: &[Body],
    gravity: &Vector3<f64>,
    dt: f64,
    thicknesses: &mut Vec<f64>,
) -> f64 {
    let fall = gravity.norm() * dt * dt;
    if fall == 0.0 {
        return 1.0;
    }
    thicknesses.clear();
    thicknesses.extend(
        bodies
            .iter()
            .filter(|body| body.is_dynamic() && !body.asleep)
            .map(|body| body.thickness),
    );
    if thicknesses.is_empty() {
        return 1.0;
    }
    let middle = thicknesses.len() / 2;
    let (_, typical, _) = thicknesses.select_nth_unstable_by(middle, f64::total_cmp);
    (fall / (SAG_SHARE * *typical)).sqrt().ceil().max(1.0)
}

/// Substeps (at least 1) in which no awake dynamic body that `contacts` pair with another turns
/// its shape by more than [`MAX_SUBSTEP_TURN`].
fn for_the_turns<'a>(
    bodies: &[Body],
    contacts: impl Iterator<Item = &'a Contact>,
    dt: f64,
    touching: &mut Vec<bool>,
) -> f64 {
    touching.clear();
    touching.resize(bodies.len(), false);
    for contact in contacts {
        touching[contact.body_a.0] = true;
        touching[contact.body_b.0] = true;
    }
    let fastest = bodies
        .iter()
        .zip(touching.iter())
        .filter(|(body, touches)| **touches && body.is_dynamic() && !body.asleep)
        .map(|(body, _)| body.shape_spin().norm())
        .fold(0.0, f64::max);
    (fastest * dt / MAX_SUBSTEP_TURN).ceil().max(1.0)
}

/// What a step's caller set for the whole step, handed to each of its substeps: the applied
/// forces and torques (which a substep clears), and each kinematic body's drive. A kinematic
/// body's velocity for the step (as set, or what takes it to its target) is reached over the
/// step, not at its start: in substep `k` of `n` it moves at `v + (v − v₀)((k + ½)/n − ½)`,
/// `v₀` its last step's, which averages `v` over the step (so the step moves it `v dt`, to its
/// target exactly) and, for a steady acceleration, grows by the same amount every substep
/// across steps (a body stopped runs on and comes back within its stopping step, by at most
/// `v₀ dt / 8`); why, in the module doc. Buffers reused.
#[derive(Debug, Clone, Default)]
pub(crate) struct StepInputs {
    /// Per body with one: its force and torque.
    loads: Vec<(usize, Vector3<f64>, Vector3<f64>)>,
    /// Per kinematic body.
    drives: Vec<Drive>,
}

/// A kinematic body's motion over a step.
#[derive(Debug, Clone, Copy)]
struct Drive {
    index: usize,
    /// Where it starts.
    start: Pose,
    /// Its linear and angular velocity over the last step, and over this one.
    from: Velocities,
    to: Velocities,
    /// Its target, if one sends it.
    target: Option<Pose>,
}

/// A centre of mass and an orientation.
type Pose = (Point3<f64>, UnitQuaternion<f64>);

/// A linear and an angular velocity.
type Velocities = (Vector3<f64>, Vector3<f64>);

impl StepInputs {
    /// Reads the inputs of a step of `dt` from `bodies`.
    pub(crate) fn take(&mut self, bodies: &[Body], dt: f64) {
        self.loads.clear();
        self.drives.clear();
        for (index, body) in bodies.iter().enumerate() {
            if body.force != Vector3::zeros() || body.torque != Vector3::zeros() {
                self.loads.push((index, body.force, body.torque));
            }
            if !body.is_kinematic() {
                continue;
            }
            let to = body
                .velocity_to_target(dt)
                .unwrap_or((body.linear_velocity, body.angular_velocity));
            self.drives.push(Drive {
                index,
                start: (body.centre, body.rotation),
                from: body.drive,
                to,
                target: body.target,
            });
        }
    }

    /// Sets the inputs of substep `k` (from 0) of `count` of a step of `dt` on `bodies`: the
    /// forces again, and each kinematic body's velocity for the substep, or its target at the
    /// substep's end.
    pub(crate) fn hand_to(&self, bodies: &mut [Body], k: usize, count: usize, dt: f64) {
        for &(index, force, torque) in &self.loads {
            bodies[index].force = force;
            bodies[index].torque = torque;
        }
        let n = count as f64;
        let h = dt / n;
        for drive in &self.drives {
            let body = &mut bodies[drive.index];
            let ((v0, w0), (v, w)) = (drive.from, drive.to);
            match drive.target {
                Some(target) if k + 1 == count => body.target = Some(target),
                Some(_) => {
                    // Σ over the substeps so far of ((i + ½)/n − ½), i = 0..=k.
                    let done = (k + 1) as f64;
                    let ramp = done * done / (2.0 * n) - done / 2.0;
                    let (centre, rotation) = drive.start;
                    let moved = (v * done + (v - v0) * ramp) * h;
                    let turned = (w * done + (w - w0) * ramp) * h;
                    let mut on_the_way = UnitQuaternion::from_scaled_axis(turned) * rotation;
                    on_the_way.renormalize();
                    body.target = Some((centre + moved, on_the_way));
                }
                None => {
                    let ramp = (k as f64 + 0.5) / n - 0.5;
                    body.linear_velocity = v + (v - v0) * ramp;
                    body.angular_velocity = w + (w - w0) * ramp;
                }
            }
        }
    }

    /// Ends the step on `bodies`: each kinematic body keeps the velocity it was set (a body a
    /// target sent rests there) and remembers its step's ([`Body::drive`]).
    pub(crate) fn finish(&self, bodies: &mut [Body]) {
        for drive in &self.drives {
            let body = &mut bodies[drive.index];
            if drive.target.is_none() {
                (body.linear_velocity, body.angular_velocity) = drive.to;
            }
            body.drive = drive.to;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDesc, Shape, World};

    /// Substeps at 60 Hz for a world of `cubes` of each size.
    fn at_60_hz(sizes: &[(f64, usize)]) -> usize {
        let mut builder = World::builder();
        for &(size, cubes) in sizes {
            for _ in 0..cubes {
                builder = builder.body(BodyDesc::dynamic(Shape::cuboid([size; 3])));
            }
        }
        let world = builder.build().unwrap();
        let gravity = Vector3::new(0.0, 0.0, -9.8);
        let scratch = &mut Scratch::default();
        count(
            world.bodies(),
            std::iter::empty(),
            &gravity,
            1.0 / 60.0,
            8,
            scratch,
        )
    }

    /// The counts the module doc gives, from `g dt² / (SAG_SHARE L)` = 0.27, 2.7 and 27 for
    /// cubes of 1 m, 10 cm and 1 cm at 60 Hz; the typical body is the median.
    #[test]
    fn small_bodies_split_the_step() {
        assert_eq!(at_60_hz(&[(1.0, 1)]), 1);
        assert_eq!(at_60_hz(&[(0.1, 1)]), 2);
        assert_eq!(at_60_hz(&[(0.01, 1)]), 6);
        assert_eq!(at_60_hz(&[(0.001, 1)]), 8, "held to the most");
        assert_eq!(at_60_hz(&[(1.0, 3), (0.01, 2)]), 1, "a few small ones");
        assert_eq!(at_60_hz(&[(1.0, 2), (0.01, 3)]), 6);
        assert_eq!(at_60_hz(&[]), 1);
        let world = World::builder()
            .body(BodyDesc::dynamic(Shape::cuboid([0.01; 3])))
            .build()
            .unwrap();
        let scratch = &mut Scratch::default();
        let weightless = count(
            world.bodies(),
            std::iter::empty(),
            &Vector3::zeros(),
            1.0,
            8,
            scratch,
        );
        assert_eq!(weightless, 1, "no gravity, no fall");
    }

    /// Substeps at 60 Hz, without gravity, for a 1 m `shape` spinning at `spin` (rad/s, world
    /// axes; its axis, if any, along x) resting on a floor, or away from it.
    fn spinning(shape: Shape, spin: [f64; 3], on_the_floor: bool) -> usize {
        let height = if on_the_floor { 0.5 } else { 5.0 };
        let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
        let mut world = World::builder()
            .gravity([0.0; 3])
            .body(BodyDesc::fixed(Shape::cuboid([10.0, 10.0, 1.0])).position([0.0, 0.0, -0.5]))
            .body(
                BodyDesc::dynamic(shape)
                    .position([0.0, 0.0, height])
                    .rotation(turn)
                    .angular_velocity(spin),
            )
            .build()
            .unwrap();
        world.prepare_step(1.0 / 60.0).unwrap();
        let contacts = world.contacts();
        let scratch = &mut Scratch::default();
        count(
            world.bodies(),
            contacts,
            &Vector3::zeros(),
            1.0 / 60.0,
            8,
            scratch,
        )
    }

    /// A body touching another is split into turns of at most `MAX_SUBSTEP_TURN` = 0.5 rad: 60
    /// rad/s at 60 Hz is 1 rad a step, so two substeps, 100 rad/s four, 1000 held to the most;
    /// alone, or turning a ball or a cylinder about its axis into itself, one.
    #[test]
    fn fast_turns_split_the_step() {
        let cube = || Shape::cuboid([1.0; 3]);
        assert_eq!(spinning(cube(), [0.0, 0.0, 29.0], true), 1);
        assert_eq!(spinning(cube(), [0.0, 0.0, 60.0], true), 2);
        assert_eq!(spinning(cube(), [0.0, 100.0, 0.0], true), 4);
        assert_eq!(
            spinning(cube(), [1000.0, 0.0, 0.0], true),
            8,
            "held to the most"
        );
        assert_eq!(
            spinning(cube(), [0.0, 100.0, 0.0], false),
            1,
            "touching nothing"
        );
        assert_eq!(spinning(Shape::sphere(0.5), [0.0, 100.0, 0.0], true), 1);
        let wheel = || Shape::cylinder(0.5, 0.3);
        assert_eq!(
            spinning(wheel(), [100.0, 0.0, 0.0], true),
            1,
            "about its axis"
        );
        assert_eq!(
            spinning(wheel(), [0.0, 100.0, 0.0], true),
            4,
            "across its axis"
        );
    }
}
