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
//! Off by default (`max_substeps` = 1), for what it does to bodies driven through kinematic
//! ones. A kinematic body's velocity changes at the start of a step, all at once; in one
//! step, the contacts give the bodies it carries that change within the step, as a steady
//! acceleration would, but in substeps within the first, a share of the step: friction, a
//! share of the step's too, falls short. Measured with [`MAX_SUBSTEPS`](crate::MAX_SUBSTEPS)
//! at 60 Hz: a 20 × 30 × 100 cm box on a platform whose velocity grows by `a dt` a step tilts
//! 0.46 rad at 97% of the tipping acceleration `g w / h` (face model; exactly upright in one
//! step) and a flat box on it slips 2.3 cm in 2 s at 97% of `μ g` (none in one step); a 20 cm
//! cube carried by kinematic fingers that reach 0.3 m/s within one step slips 1 mm and turns
//! 2 mrad (2–5 µm in one step). Spreading a kinematic body's change of velocity over the
//! substeps would cure it, at the price of moving it otherwise than `v dt` a step. Also
//! measured: four 1 g cubes under a 100–1000 kg slab dropped on them (10⁵ : 1) were knocked
//! up to 19 mm aside instead of 7 (face model) and 11 mm instead of 0.1 (vertex), the slab
//! rocking on them after it landed. Worlds of 1 m bodies at 60 Hz (the piles, pyramids and
//! towers of the benchmarks) or 2 m bodies at 100 Hz (the paper's) take one substep either way.

use nalgebra::{Point3, UnitQuaternion, Vector3};

use crate::Body;

/// Most a step's gravity fall `g h²` may be of the typical body's thickness before the step is
/// split (see the module doc): between the 30 cm cubes' 0.009, which settle in a bin at 60 Hz,
/// and the 20 cm cubes' 0.014, which do not.
pub const SAG_SHARE: f64 = 0.01;

/// Substeps of a step of `dt` for `bodies` under `gravity`, from 1 to `max`; `thicknesses` is
/// scratch.
pub(crate) fn count(
    bodies: &[Body],
    gravity: &Vector3<f64>,
    dt: f64,
    max: usize,
    thicknesses: &mut Vec<f64>,
) -> usize {
    let fall = gravity.norm() * dt * dt;
    if max <= 1 || fall == 0.0 {
        return 1;
    }
    thicknesses.clear();
    thicknesses.extend(
        bodies
            .iter()
            .filter(|body| body.is_dynamic() && !body.asleep)
            .map(|body| body.thickness),
    );
    if thicknesses.is_empty() {
        return 1;
    }
    let middle = thicknesses.len() / 2;
    let (_, typical, _) = thicknesses.select_nth_unstable_by(middle, f64::total_cmp);
    let needed = (fall / (SAG_SHARE * *typical)).sqrt().ceil();
    // Not NaN: the thickness is positive and finite, gravity and dt are validated.
    (needed as usize).clamp(1, max)
}

/// What a step's caller set for the whole step, handed to each of its substeps: the applied
/// forces and torques (which a substep clears), and each kinematic target, reached a share
/// at a time. Buffers reused.
#[derive(Debug, Clone, Default)]
pub(crate) struct StepInputs {
    /// Per body with one: its force and torque.
    loads: Vec<(usize, Vector3<f64>, Vector3<f64>)>,
    /// Per kinematic body sent to a target: where it starts and the target.
    targets: Vec<(usize, Pose, Pose)>,
}

/// A centre of mass and an orientation.
type Pose = (Point3<f64>, UnitQuaternion<f64>);

impl StepInputs {
    /// Reads the step's inputs from `bodies`.
    pub(crate) fn take(&mut self, bodies: &[Body]) {
        self.loads.clear();
        self.targets.clear();
        for (index, body) in bodies.iter().enumerate() {
            if body.force != Vector3::zeros() || body.torque != Vector3::zeros() {
                self.loads.push((index, body.force, body.torque));
            }
            if let Some(target) = body.target {
                self.targets
                    .push((index, (body.centre, body.rotation), target));
            }
        }
    }

    /// Sets the inputs of substep `k` (from 0) of `count` on `bodies`: the forces again, and
    /// each target `(k + 1) / count` of the way from where its body started.
    pub(crate) fn hand_to(&self, bodies: &mut [Body], k: usize, count: usize) {
        for &(index, force, torque) in &self.loads {
            bodies[index].force = force;
            bodies[index].torque = torque;
        }
        let share = (k + 1) as f64 / count as f64;
        for &(index, (centre, rotation), (to_centre, to_rotation)) in &self.targets {
            let turn = (to_rotation * rotation.inverse()).scaled_axis() * share;
            let mut on_the_way = UnitQuaternion::from_scaled_axis(turn) * rotation;
            on_the_way.renormalize();
            let last = k + 1 == count;
            bodies[index].target = Some(if last {
                (to_centre, to_rotation)
            } else {
                (centre + (to_centre - centre) * share, on_the_way)
            });
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
        count(world.bodies(), &gravity, 1.0 / 60.0, 8, &mut Vec::new())
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
        let weightless = count(world.bodies(), &Vector3::zeros(), 1.0, 8, &mut Vec::new());
        assert_eq!(weightless, 1, "no gravity, no fall");
    }
}
