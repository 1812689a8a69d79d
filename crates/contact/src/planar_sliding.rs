//! Coulomb friction at every point of a uniformly pressed face, summed by brute force over a
//! grid of the face: the exact friction of a flat body sliding and spinning on a plane, which
//! a face's limit surface ([`crate::FrictionLimit`]) stands in for, and the reference the
//! face model is checked against (`tatami-world`'s `tests/planar_sliding.rs`, the planar
//! sliding experiment). Every point slips one way at one speed, so a face that slides and
//! spins at once shares its friction between the two; a uniformly pressed disc stops sliding
//! and spinning at the same instant (Farkas, Bartels, Unger and Wolf, 2003).
//!
//! ```
//! use nalgebra::Vector2;
//! use tatami_contact::planar_sliding::PressedFace;
//!
//! // A 0.1 m disc on μ = 0.3 at 1 m/s, no spin: it stops at v/(μg) = 0.34 s.
//! let disc = PressedFace::disc(0.1, 24);
//! let slide = disc.slide(0.3 * 9.8, Vector2::new(1.0, 0.0), 0.0, 1e-4, 1.0);
//! assert!((slide.slide_stop.unwrap() - 1.0 / (0.3 * 9.8)).abs() < 1e-3);
//! ```

use nalgebra::{Rotation2, Vector2};

/// A flat body's face pressed uniformly on a plane, as the centres of the grid cells inside it
/// (body axes, about its centre of mass, which is over the face's centre), with the body's
/// moment of inertia about the plane's normal per unit mass.
#[derive(Debug, Clone)]
pub struct PressedFace {
    points: Vec<Vector2<f64>>,
    unit_inertia: f64,
    rim: f64,
}

/// One moment of a [`PressedFace::slide`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlideSample {
    /// Time from the start (s).
    pub time: f64,
    /// The face's velocity in the plane (m/s).
    pub velocity: Vector2<f64>,
    /// Its spin about the plane's normal (rad/s).
    pub spin: f64,
}

/// A face's slide to rest: samples, and when the slide and the spin stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct Slide {
    /// The motion at every sample time, from the start.
    pub samples: Vec<SlideSample>,
    /// When the face stopped sliding (s), if within the run.
    pub slide_stop: Option<f64>,
    /// When it stopped spinning (s), if within the run.
    pub spin_stop: Option<f64>,
}

impl PressedFace {
    /// A thin disc of `radius` (a flat cylinder's cap), on a grid of `cells` × `cells`.
    pub fn disc(radius: f64, cells: usize) -> Self {
        Self {
            points: grid(cells, radius, radius)
                .filter(|p| p.norm() <= radius)
                .collect(),
            unit_inertia: radius * radius / 2.0,
            rim: radius,
        }
    }

    /// A thin plate of half-widths `half_x` and `half_y`, on a grid of `cells` × `cells`.
    pub fn rectangle(half_x: f64, half_y: f64, cells: usize) -> Self {
        Self {
            points: grid(cells, half_x, half_y).collect(),
            unit_inertia: (half_x * half_x + half_y * half_y) / 3.0,
            rim: half_x.hypot(half_y),
        }
    }

    /// The distance of the face's farthest point from its centre (m): where a spin's speed is
    /// measured against a slide's.
    pub fn rim(&self) -> f64 {
        self.rim
    }

    /// Friction force and torque about the centre per unit `μ N` on the face turned by `angle`
    /// (rad), moving at `velocity` and spinning at `spin`: the mean of `−slip / |slip|` over its
    /// points, and of its moment. A point at rest against the plane adds nothing.
    pub fn friction(&self, angle: f64, velocity: Vector2<f64>, spin: f64) -> (Vector2<f64>, f64) {
        let turn = Rotation2::new(angle);
        let (mut force, mut torque) = (Vector2::zeros(), 0.0);
        for p in &self.points {
            let r = turn * p;
            let slip = velocity + spin * Vector2::new(-r.y, r.x);
            let norm = slip.norm();
            if norm > 0.0 {
                force -= slip / norm;
                torque -= r.perp(&slip) / norm;
            }
        }
        let n = self.points.len() as f64;
        (force / n, torque / n)
    }

    /// The face's slide from `velocity` and `spin` under friction `mu_g` (μ times gravity,
    /// m/s²), by explicit Euler steps of `step` (s), sampled every step, for at most `until`
    /// (s). A motion whose next step would reverse it stops there and stays stopped: the
    /// other's friction has no part along it on a face symmetric about its centre.
    pub fn slide(
        &self,
        mu_g: f64,
        velocity: Vector2<f64>,
        spin: f64,
        step: f64,
        until: f64,
    ) -> Slide {
        let (mut v, mut w, mut angle, mut t) = (velocity, spin, 0.0, 0.0);
        let (mut slide_stop, mut spin_stop) = (None, None);
        let mut samples = vec![SlideSample {
            time: 0.0,
            velocity: v,
            spin: w,
        }];
        while t < until && (slide_stop.is_none() || spin_stop.is_none()) {
            let (force, torque) = self.friction(angle, v, w);
            if slide_stop.is_none() {
                let next = v + force * (mu_g * step);
                if next.dot(&v) <= 0.0 {
                    slide_stop = Some(t + step);
                    v = Vector2::zeros();
                } else {
                    v = next;
                }
            }
            if spin_stop.is_none() {
                let next = w + torque * mu_g / self.unit_inertia * step;
                if next * w <= 0.0 {
                    spin_stop = Some(t + step);
                    w = 0.0;
                } else {
                    w = next;
                }
            }
            angle += w * step;
            t += step;
            samples.push(SlideSample {
                time: t,
                velocity: v,
                spin: w,
            });
        }
        Slide {
            samples,
            slide_stop,
            spin_stop,
        }
    }
}

/// `cells × cells` cell centres over the rectangle of half-widths `half_x`, `half_y`.
fn grid(cells: usize, half_x: f64, half_y: f64) -> impl Iterator<Item = Vector2<f64>> {
    let at = move |i: usize, half: f64| ((i as f64 + 0.5) / cells as f64 * 2.0 - 1.0) * half;
    (0..cells)
        .flat_map(move |i| (0..cells).map(move |j| Vector2::new(at(i, half_x), at(j, half_y))))
}

#[cfg(test)]
mod tests {
    use super::*;

    const MU_G: f64 = 0.3 * 9.8;
    const STEP: f64 = 1e-4;

    /// Pure spin against the uniform-pressure closed forms: a disc's torque is `μ N (2R/3)`, a
    /// square's `μ N r̄` with `r̄ = a (√2 + ln(1 + √2)) / 6` (`a` its side), within 0.5%: the
    /// 48 × 48 grid's cells inside the disc's rim stand in for its area to 0.2%.
    #[test]
    fn a_spinning_face_stops_as_its_mean_radius_says() {
        let disc = PressedFace::disc(0.1, 48);
        let stop = disc
            .slide(MU_G, Vector2::zeros(), 20.0, STEP, 2.0)
            .spin_stop
            .unwrap();
        let closed = 20.0 * (0.1 * 0.1 / 2.0) / (MU_G * 2.0 * 0.1 / 3.0);
        assert!(
            (stop - closed).abs() < 5e-3 * closed,
            "{stop} against {closed}"
        );
        let square = PressedFace::rectangle(0.1, 0.1, 48);
        let r_bar = 0.2 * (2f64.sqrt() + (1.0 + 2f64.sqrt()).ln()) / 6.0;
        let stop = square
            .slide(MU_G, Vector2::zeros(), 20.0, STEP, 2.0)
            .spin_stop
            .unwrap();
        let closed = 20.0 * (0.2 * 0.2 / 6.0) / (MU_G * r_bar);
        assert!(
            (stop - closed).abs() < 5e-3 * closed,
            "{stop} against {closed}"
        );
    }

    /// A disc sliding and spinning stops both at once (Farkas et al. 2003), later than either
    /// pure motion would: each slows the other's friction. To the step of 0.1 ms.
    #[test]
    fn a_disc_stops_sliding_and_spinning_together() {
        let disc = PressedFace::disc(0.1, 48);
        let slide = disc.slide(MU_G, Vector2::new(0.6, 0.8), 20.0, STEP, 2.0);
        let (slide_stop, spin_stop) = (slide.slide_stop.unwrap(), slide.spin_stop.unwrap());
        assert!(
            (slide_stop - spin_stop).abs() <= 2.0 * STEP,
            "{slide_stop} and {spin_stop}"
        );
        assert!(slide_stop > 1.0 / MU_G, "{slide_stop}");
        // Straight on, as the disc's symmetry has it.
        let heading = |s: &SlideSample| s.velocity.y.atan2(s.velocity.x);
        let moving: Vec<_> = slide
            .samples
            .iter()
            .filter(|s| s.velocity.norm() > 0.01)
            .collect();
        let worst = moving
            .iter()
            .map(|s| (heading(s) - heading(moving[0])).abs())
            .fold(0.0, f64::max);
        // The grid turning with the disc is symmetric only to its cells: 1.3 mrad at worst.
        assert!(worst < 5e-3, "{worst}");
    }
}
