//! A face sliding and spinning at once on the floor (planar sliding, as a pushed part or a
//! curling stone): its friction force and twist share one budget, so it stops sliding and
//! spinning together, when per-point Coulomb friction summed over its uniformly pressed face
//! stops it. The reference is that sum by brute force, over a grid of the face, integrated in
//! small steps (the discs' closed form, Farkas et al. 2003, stops both together too).

use nalgebra::{Rotation2, UnitQuaternion, Vector2, Vector3};
use tatami_world::{BodyDesc, Shape, World};

const G: f64 = 9.8;
const MU: f64 = 0.3;
/// The world's step (s): the default users run.
const DT: f64 = 1.0 / 60.0;
/// Sliding and spinning count as stopped below this speed (m/s; the spin at the rim).
const STOPPED: f64 = 1e-3;

/// A thin plate's pressed face, as grid points about its centre (body axes), and its moment
/// of inertia about the normal per unit mass.
struct Face {
    points: Vec<Vector2<f64>>,
    unit_inertia: f64,
    /// Its largest radius: spin is measured at this rim.
    rim: f64,
}

impl Face {
    fn disc(radius: f64) -> Self {
        let n = 48;
        let points = grid(n, radius).filter(|p| p.norm() <= radius).collect();
        Self {
            points,
            unit_inertia: radius * radius / 2.0,
            rim: radius,
        }
    }

    fn square(half: f64) -> Self {
        Self {
            points: grid(48, half).collect(),
            unit_inertia: 2.0 * (2.0 * half) * (2.0 * half) / 12.0,
            rim: half,
        }
    }

    /// Friction force and torque per unit weight `μ m g` on the face turned by `angle`, moving
    /// at `v` and spinning at `omega`: the mean of `−slip/|slip|` over its points.
    fn friction(&self, angle: f64, v: Vector2<f64>, omega: f64) -> (Vector2<f64>, f64) {
        let turn = Rotation2::new(angle);
        let (mut force, mut torque) = (Vector2::zeros(), 0.0);
        for p in &self.points {
            let r = turn * p;
            let slip = v + omega * Vector2::new(-r.y, r.x);
            let norm = slip.norm();
            if norm > 0.0 {
                force -= slip / norm;
                torque -= r.perp(&slip) / norm;
            }
        }
        let n = self.points.len() as f64;
        (force / n, torque / n)
    }

    /// When (s) the brute force stops sliding and stops spinning, from `v` and `omega`, in
    /// steps of 0.2 ms (explicit Euler; a stopped motion stays stopped, the other's friction
    /// having no part along it for a face symmetric about its centre).
    fn stop_times(&self, mut v: Vector2<f64>, mut omega: f64) -> (f64, f64) {
        let h = 2e-4;
        let (mut angle, mut t) = (0.0, 0.0);
        let (mut slide_stop, mut spin_stop) = (None, None);
        while slide_stop.is_none() || spin_stop.is_none() {
            let (force, torque) = self.friction(angle, v, omega);
            if slide_stop.is_none() {
                let next = v + force * (MU * G * h);
                if next.dot(&v) <= 0.0 || next.norm() < STOPPED {
                    slide_stop = Some(t);
                    v = Vector2::zeros();
                } else {
                    v = next;
                }
            }
            if spin_stop.is_none() {
                let next = omega + torque * MU * G / self.unit_inertia * h;
                if next * omega <= 0.0 || next.abs() * self.rim < STOPPED {
                    spin_stop = Some(t);
                    omega = 0.0;
                } else {
                    omega = next;
                }
            }
            angle += omega * h;
            t += h;
        }
        (slide_stop.unwrap_or(t), spin_stop.unwrap_or(t))
    }
}

/// `n × n` cell centres over the square of half-width `half`.
fn grid(n: usize, half: f64) -> impl Iterator<Item = Vector2<f64>> {
    let at = move |i: usize| (i as f64 + 0.5) / n as f64 * 2.0 * half - half;
    (0..n).flat_map(move |i| (0..n).map(move |j| Vector2::new(at(i), at(j))))
}

/// When (s) the engine's plate stops sliding and stops spinning, and whether its kinetic energy
/// ever grew from one step to the next: a 1 kg plate of `shape`, 2 cm thick, turned by 0.4 rad
/// about the vertical, on a fixed floor, launched at `v` (m/s) and `omega` (rad/s).
fn engine_stop_times(shape: Shape, v: Vector2<f64>, omega: f64) -> (f64, f64, bool) {
    let mut world = World::builder()
        .gravity([0.0, 0.0, -G])
        .body(
            BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 1.0]))
                .position([0.0, 0.0, -0.5])
                .friction(MU),
        )
        .body(
            BodyDesc::dynamic(shape)
                .mass(1.0)
                .friction(MU)
                .position([0.0, 0.0, 0.01])
                .rotation(UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.4))
                .velocity([v.x, v.y, 0.0])
                .angular_velocity([0.0, 0.0, omega]),
        )
        .build()
        .unwrap();
    let (mut slide_stop, mut spin_stop) = (None, None);
    let mut energy = world.bodies()[1].kinetic_energy();
    let mut gained = false;
    let mut t = 0.0;
    while (slide_stop.is_none() || spin_stop.is_none()) && t < 3.0 {
        world.step(DT).unwrap();
        t += DT;
        let plate = &world.bodies()[1];
        let now = plate.kinetic_energy();
        // Roundings of a 1 J energy: 1e-12 J.
        gained |= now > energy + 1e-12;
        energy = now;
        if slide_stop.is_none() && plate.linear_velocity().xy().norm() < STOPPED {
            slide_stop = Some(t);
        }
        if spin_stop.is_none() && plate.angular_velocity().z.abs() * 0.1 < STOPPED {
            spin_stop = Some(t);
        }
    }
    (slide_stop.unwrap_or(t), spin_stop.unwrap_or(t), gained)
}

/// A disc of 0.1 m and a 0.2 m square plate, sliding off the world's axes at 1 m/s while
/// spinning at 0.5 to 2 times that at their rim, either way, under the default settings:
/// they stop sliding and spinning within one step of each other, within 10% of per-point
/// Coulomb friction's stop — the ellipsoidal limit surface is 5–7% quicker than the exact one
/// for these faces (measured: disc 0.613 against 0.647 s at twice the speed at the rim),
/// one step of 1/60 s is 3–5% of these stops — and their energy never grows. Bounded apart,
/// the force and the twist stopped the disc sliding at 0.34 s and spinning at 0.51 s.
#[test]
fn a_sliding_spinning_face_stops_both_together_as_per_point_coulomb_does() {
    let heading = Vector2::new((2.2f64).cos(), (2.2f64).sin());
    for (name, shape, face) in [
        ("disc", Shape::cylinder(0.1, 0.02), Face::disc(0.1)),
        ("square", Shape::cuboid([0.2, 0.2, 0.02]), Face::square(0.1)),
    ] {
        for rim_speed in [0.5, 2.0, -2.0] {
            let (v, omega) = (heading, rim_speed / 0.1);
            let (slide, spin, gained) = engine_stop_times(shape.clone(), v, omega);
            let (exact_slide, exact_spin) = face.stop_times(v, omega);
            let case = format!(
                "{name} at {rim_speed} m/s on the rim: slide {slide:.3} s and spin {spin:.3} s \
                 against {exact_slide:.3} and {exact_spin:.3} s"
            );
            assert!((exact_slide - exact_spin).abs() < 0.005, "{case}");
            assert!((slide - spin).abs() <= DT + 1e-9, "{case}");
            assert!((slide - exact_slide).abs() < 0.1 * exact_slide, "{case}");
            assert!(!gained, "{case}: its energy grew");
        }
    }
}
