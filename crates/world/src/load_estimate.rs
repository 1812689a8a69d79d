//! A first guess for the normal impulses of contacts that have no stored impulses: the weight
//! each carries at rest, passed down from the top of the pile.
//!
//! Warm starting carries a pair's impulses over from the last step, but a pair that has just
//! begun to touch has none, and a cold start is slow exactly where weight must travel far:
//! Gauss–Seidel moves it about one level per sweep, so a tower of 100 cubes created at rest took
//! 255 steps of 15 sweeps before a step's impulses were its last step's (`general_comparison`
//! bench, dt 1/60) — with this guess the first step already converges in one sweep. The guess
//! is only a starting point: the sweeps correct it, and the fixed points are unchanged.
//!
//! Going down the contacts (highest first, the contact set's order), each dynamic body's
//! weight, plus what the contacts above it pass to it, is shared among the contacts it rests on
//! (those whose other body is lower along gravity) so that their normal impulses hold it up:
//! contact `c`, with `a_c = |n_c · ĝ|`, takes `N_c = W a_c / Σ a²` over the body's supports
//! (`Σ N_c a_c = W`; a side contact, `a_c = 0`, takes nothing), and passes `N_c a_c` to the body
//! under it. No contact's guess exceeds the weight `W` it holds: a lone support steep as a wall
//! (`a_c → 0`) would take `W / a_c`, a push no contact needs while friction holds the body (on a
//! slope it takes `W a_c`), and a guess far above the answer is what the sweeps undo slowest —
//! uncapped, a 1 kg cube in a heap of overlapping cubes was started at 7679 N·s (`a_c` ≈ 1e-5)
//! and left the solve at 59 m/s.
//!
//! Where the weight acts is passed down too. A body resting on one contact is held up along the
//! vertical through the centre of the weight it carries (its own and what rests on it), so that
//! contact's guess is applied where that line crosses the contact plane (the nearest point of
//! the support polygon if it crosses outside): the face model's tilt rows then start with the
//! torque that keeps the body from tipping, and the vertex and patch models' normal rows with
//! shares whose resultant acts there. A body on several contacts passes each one's share down
//! at the contact's centroid. Without the point, a stack leaning 0.1 m a level (six unit cubes,
//! `scenes/leaning_stack.json`) slid 15 mm outwards in its first 20 steps at 60 Hz under the
//! face model (12 mm and 9 mm under the vertex and patch models) while the sweeps built the
//! load's offset up from the centroids, and then held.

use nalgebra::{Point3, Vector3};
use tatami_contact::Contact;
use tatami_lcp::SolverBody;
use tatami_lcp::pgs::Support;

use crate::contact_set::support_of;

/// The guess for one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Load {
    /// Normal impulse (N·s).
    pub(crate) normal: f64,
    /// Where it acts (world), when the upper body rests on this contact alone; otherwise it is
    /// spread evenly over the contact's normal rows.
    pub(crate) at: Option<Point3<f64>>,
}

/// Reused buffers of the estimate.
#[derive(Debug, Clone, Default)]
pub(crate) struct LoadEstimate {
    /// Per body: the weight it must be held up against (N·s).
    carried: Vec<f64>,
    /// Per body: the first moment of the weight passed to it from above (N·s·m), about the
    /// world's origin.
    moment: Vec<Vector3<f64>>,
    /// Per body: `Σ a²` over the contacts it rests on.
    resting: Vec<f64>,
    /// Per body: how many contacts it rests on (`a > 0`).
    supports: Vec<u32>,
    /// Per contact: the guess.
    loads: Vec<Load>,
}

impl LoadEstimate {
    /// The last estimate's guesses, one per contact.
    pub(crate) fn last(&self) -> &[Load] {
        &self.loads
    }

    /// The normal impulse of each of `contacts` (highest first) that holds the dynamic `bodies`
    /// against `weight_per_mass` (gravity × dt) at rest, and where it acts; zeros without
    /// gravity.
    pub(crate) fn estimate<'a>(
        &mut self,
        contacts: impl Iterator<Item = &'a Contact> + Clone,
        bodies: &[SolverBody],
        weight_per_mass: &Vector3<f64>,
    ) -> &[Load] {
        self.loads.clear();
        let g = weight_per_mass.norm();
        if g == 0.0 {
            self.loads.extend(contacts.map(|_| Load {
                normal: 0.0,
                at: None,
            }));
            return &self.loads;
        }
        let down = weight_per_mass / g;
        let weight = |b: &SolverBody| {
            if b.inv_mass > 0.0 {
                g / b.inv_mass
            } else {
                0.0
            }
        };
        self.carried.clear();
        self.carried.extend(bodies.iter().map(weight));
        self.moment.clear();
        self.moment.resize(bodies.len(), Vector3::zeros());
        self.resting.clear();
        self.resting.resize(bodies.len(), 0.0);
        self.supports.clear();
        self.supports.resize(bodies.len(), 0);
        let roles = |c: &Contact| match support_of(c, &down) {
            Support::A => (c.body_b.0, c.body_a.0),
            Support::B => (c.body_a.0, c.body_b.0),
        };
        for contact in contacts.clone() {
            let (upper, _) = roles(contact);
            let a = contact.frame.normal.dot(&down);
            self.resting[upper] += a * a;
            self.supports[upper] += u32::from(a != 0.0);
        }
        for contact in contacts {
            let (upper, lower) = roles(contact);
            let a = contact.frame.normal.dot(&down).abs();
            if bodies[upper].inv_mass == 0.0 || self.resting[upper] == 0.0 {
                self.loads.push(Load {
                    normal: 0.0,
                    at: None,
                });
                continue;
            }
            let carried = self.carried[upper];
            let normal = (carried * a / self.resting[upper]).min(carried);
            let centroid = contact.frame.to_world(&contact.support.centroid());
            // The body's one support is this contact (a side contact, a = 0, holds nothing).
            let at = if self.supports[upper] == 1 && a > 0.0 {
                let own = if upper == contact.body_a.0 {
                    contact.centre_a
                } else {
                    contact.centre_b
                };
                let centre = (self.moment[upper] + own.coords * weight(&bodies[upper])) / carried;
                // Where the vertical through the centre crosses the contact plane.
                let n = &contact.frame.normal;
                let crossing = centre + down * ((centroid.coords - centre).dot(n) / down.dot(n));
                let inside = contact
                    .support
                    .nearest_point(&contact.frame.to_plane(&crossing.into()));
                Some(contact.frame.to_world(&inside)).filter(|p| p.iter().all(|x| x.is_finite()))
            } else {
                None
            };
            self.carried[lower] += normal * a;
            self.moment[lower] += at.unwrap_or(centroid).coords * (normal * a);
            self.loads.push(Load { normal, at });
        }
        &self.loads
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Point2, Point3};
    use tatami_contact::{ContactFrame, Material};

    use tatami_geometry::ConvexPolygon;
    use tatami_lcp::BodyId;

    use super::*;

    /// A contact between `a` above and `b` below, with normal `normal` (from B to A).
    fn contact(a: usize, b: usize, heights: [f64; 2], normal: Vector3<f64>) -> Contact {
        Contact {
            body_a: BodyId(a),
            body_b: BodyId(b),
            centre_a: Point3::new(0.0, 0.0, heights[0]),
            centre_b: Point3::new(0.0, 0.0, heights[1]),
            frame: ContactFrame::from_normal(Point3::origin(), normal).unwrap(),
            support: ConvexPolygon::from_points(&[Point2::origin()]).unwrap(),
            depths: vec![0.0],
            material: Material::new(0.5, 0.5, 0.0).unwrap(),
            landing: Vec::new(),
            bounce_speed: 0.0,
        }
    }

    fn normals(loads: &[Load]) -> Vec<f64> {
        loads.iter().map(|l| l.normal).collect()
    }

    fn dynamic(mass: f64) -> SolverBody {
        SolverBody {
            inv_mass: 1.0 / mass,
            ..SolverBody::fixed()
        }
    }

    /// A stack of masses 3, 2 and 1 kg (lightest on top) on a fixed floor: each contact holds
    /// the weight of everything above it — the static solution of a stack, exactly.
    #[test]
    fn a_stack_passes_its_weight_down() {
        let bodies = [
            SolverBody::fixed(),
            dynamic(3.0),
            dynamic(2.0),
            dynamic(1.0),
        ];
        let up = Vector3::z();
        let contacts = [
            contact(3, 2, [3.0, 2.0], up),
            contact(1, 2, [1.0, 2.0], -up),
            contact(1, 0, [1.0, 0.0], up),
        ];
        let weight = Vector3::new(0.0, 0.0, -0.1);
        let mut estimate = LoadEstimate::default();
        let normal = normals(estimate.estimate(contacts.iter(), &bodies, &weight));
        let expected = [0.1, 0.3, 0.6];
        for (n, e) in normal.iter().zip(expected) {
            assert!((n - e).abs() < 1e-15, "{normal:?}");
        }
    }

    /// A body resting on two supports, one flat and one tilted 60° (a = 1/2), and touching a
    /// wall (a = 0): the supports' normal impulses hold its weight along gravity
    /// (`N₁ + N₂/2 = W`), the wall takes none.
    #[test]
    fn supports_share_a_weight_by_their_slope() {
        let bodies = [SolverBody::fixed(), dynamic(2.0)];
        let tilted = Vector3::new(3f64.sqrt() / 2.0, 0.0, 0.5);
        let contacts = [
            contact(1, 0, [1.0, 0.0], Vector3::z()),
            contact(1, 0, [1.0, 0.0], tilted),
            contact(1, 0, [1.0, 0.0], Vector3::x()),
        ];
        let mut estimate = LoadEstimate::default();
        let weight = 2.0 * 9.8 * 0.01;
        let normal =
            normals(estimate.estimate(contacts.iter(), &bodies, &Vector3::new(0.0, 0.0, -0.098)));
        assert!(
            (normal[0] + 0.5 * normal[1] - weight).abs() < 1e-15,
            "{normal:?}"
        );
        assert!(
            (normal[1] - 0.5 * normal[0]).abs() < 1e-15,
            "shared as a_c: {normal:?}"
        );
        assert_eq!(normal[2], 0.0);
    }

    /// A body whose only support is nearly a wall (`a` = 1e-5): the guess is its weight, not
    /// the `W / a` (10⁵ W) that the normal alone would need, and what it passes down is that
    /// guess's part along gravity.
    #[test]
    fn a_steep_lone_support_is_guessed_at_the_weight_it_holds() {
        let bodies = [SolverBody::fixed(), dynamic(1.0), dynamic(1.0)];
        let a: f64 = 1e-5;
        let steep = Vector3::new((1.0 - a * a).sqrt(), 0.0, a);
        let contacts = [
            contact(2, 1, [2.0, 1.0], steep),
            contact(1, 0, [1.0, 0.0], Vector3::z()),
        ];
        let weight = 0.098;
        let mut estimate = LoadEstimate::default();
        let normal =
            normals(estimate.estimate(contacts.iter(), &bodies, &Vector3::new(0.0, 0.0, -weight)));
        assert!((normal[0] - weight).abs() < 1e-15, "{normal:?}");
        assert!((normal[1] - weight * (1.0 + a)).abs() < 1e-15, "{normal:?}");
    }

    /// A unit square face between `upper` (centre `centre_upper`) above and `lower`, its plane
    /// at height `height`, centred under `(x, 0)`.
    fn face(upper: usize, lower: usize, centre_upper: [f64; 3], height: f64, x: f64) -> Contact {
        let square = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
        Contact {
            body_a: BodyId(upper),
            body_b: BodyId(lower),
            centre_a: centre_upper.into(),
            centre_b: Point3::new(x, 0.0, height - 0.5),
            frame: ContactFrame::from_normal(Point3::new(x, 0.0, height), Vector3::z()).unwrap(),
            support: ConvexPolygon::from_points(&square.map(|[u, v]| Point2::new(u, v))).unwrap(),
            depths: vec![0.0; 4],
            material: Material::new(0.5, 0.5, 0.0).unwrap(),
            landing: Vec::new(),
            bounce_speed: 0.0,
        }
    }

    /// A 1 kg cube centred 0.3 m out on a 2 kg cube, on the floor: the top face's guess acts
    /// under the top cube's centre, the bottom face's under the centre of both cubes' weight
    /// (`(1 · 0.3 + 2 · 0) / 3` = 0.1 m out) — the static centres of pressure. Moved 0.5 m
    /// further out, the top cube's centre is off its support: the guess acts at the support's
    /// nearest point, and is passed down from there.
    #[test]
    fn a_lone_support_carries_its_weight_under_the_centre_of_what_it_holds() {
        let bodies = [SolverBody::fixed(), dynamic(2.0), dynamic(1.0)];
        let weight = Vector3::new(0.0, 0.0, -0.1);
        let mut estimate = LoadEstimate::default();
        for (out, top_at, bottom_at) in [(0.3, 0.3, 0.1), (0.8, 0.5, 0.5 / 3.0)] {
            let contacts = [
                face(2, 1, [out, 0.0, 1.5], 1.0, 0.0),
                face(1, 0, [0.0, 0.0, 0.5], 0.0, 0.0),
            ];
            let loads = estimate.estimate(contacts.iter(), &bodies, &weight);
            assert!((loads[0].normal - 0.1).abs() < 1e-15, "{loads:?}");
            assert!((loads[1].normal - 0.3).abs() < 1e-15, "{loads:?}");
            let top = loads[0].at.expect("one support");
            let bottom = loads[1].at.expect("one support");
            assert!(
                (top - Point3::new(top_at, 0.0, 1.0)).norm() < 1e-15,
                "{top}"
            );
            assert!(
                (bottom - Point3::new(bottom_at, 0.0, 0.0)).norm() < 1e-15,
                "{bottom}"
            );
        }
    }

    /// A body on two supports shares its weight between them, each spread over its own rows.
    #[test]
    fn a_body_on_two_supports_has_no_single_point() {
        let bodies = [SolverBody::fixed(), dynamic(1.0)];
        let contacts = [
            face(1, 0, [0.5, 0.0, 0.5], 0.0, 0.0),
            face(1, 0, [0.5, 0.0, 0.5], 0.0, 1.0),
        ];
        let mut estimate = LoadEstimate::default();
        let loads = estimate.estimate(contacts.iter(), &bodies, &Vector3::new(0.0, 0.0, -0.1));
        assert!(
            loads
                .iter()
                .all(|l| l.at.is_none() && (l.normal - 0.05).abs() < 1e-15)
        );
    }

    #[test]
    fn without_gravity_nothing_is_carried() {
        let bodies = [SolverBody::fixed(), dynamic(1.0)];
        let contacts = [contact(1, 0, [1.0, 0.0], Vector3::z())];
        let mut estimate = LoadEstimate::default();
        let normal = normals(estimate.estimate(contacts.iter(), &bodies, &Vector3::zeros()));
        assert_eq!(normal, [0.0]);
    }
}
