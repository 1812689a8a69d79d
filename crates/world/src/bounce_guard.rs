//! No bounce gives back more energy than its landing took.
//!
//! A bouncing pair lands in one step and bounces in the next, its support points at one speed
//! ([`crate::impact`]) capped so that they get back at most `e²` of what the landing took. That
//! cap reads the pair's coupling along the normal alone; friction is not in it. Where the
//! points that bounce stick, friction's reaction turns the body's spin into lift as well: a
//! cylinder with restitution 0.95 and friction 1, dropped 1 m turning at random, bounced off
//! its rim with 1.06 times the energy it was dropped with.
//!
//! So after the velocity solve, each island with a bounce (dynamic bodies joined by their
//! contacts, touching no kinematic body, which may do work on it) is checked: the contacts'
//! work on it in the step may not exceed the energy its bounces' landings took
//! ([`Impacts::landing_took`](crate::impact::Impacts::landing_took)). That work is the change
//! of the energy the integrator keeps in free flight, the kinetic energy at each body's
//! velocity less half a step of gravity ([`crate::impact`]'s module doc), from the solve's
//! start (gravity's impulse added) to its end. Where it passes the bound, every velocity of
//! the island is scaled by one factor below 1 to meet it. Scaled so, a contact's normal
//! velocity keeps to any target at or below zero (resting, or closing a gap), and one that
//! bounces keeps parting, slower; the impulses are not changed. A bounce the normal cap holds
//! to `e²` of its landing stays under the bound, and a step without a bounce is not read.

use nalgebra::Vector3;
use tatami_contact::{Contact, ContactProjection};
use tatami_lcp::{DisjointSets, Problem, SolverBody};

use crate::body::Body;
use crate::sleep::join_dynamic;

/// Islands with a bounce: their energies before the velocity solve, and what their bounces'
/// landings took; buffers reused.
#[derive(Debug, Clone, Default)]
pub(crate) struct BounceGuard {
    /// The dynamic bodies, joined through the problem's blocks.
    islands: DisjointSets,
    /// Per body root: its island's accounts (read at roots only).
    accounts: Vec<Account>,
    /// Half a step of gravity's change of velocity (m/s): kinetic energies are read at the
    /// velocities less it. `None` when the step has no bounce, and the guard no work.
    half_step: Option<Vector3<f64>>,
}

/// One island's energies (J).
#[derive(Debug, Clone, Copy, Default)]
struct Account {
    /// Kinetic energy before the solve.
    before: f64,
    /// What its bounces' landings took.
    landings_took: f64,
    /// Whether a kinematic body touches it.
    driven: bool,
    /// Kinetic energy after the solve if every velocity is scaled by `s`:
    /// `scaled[0] s² − scaled[1] s + scaled[2]`.
    scaled: [f64; 3],
}

impl BounceGuard {
    /// Reads the islands of `problem` (built, with gravity's impulse for a step of `dt`, not
    /// yet solved) that have one of `bounces` (each pair that bounces in this step, with what
    /// its landing took): their kinetic energy now.
    pub(crate) fn before_solve<'a>(
        &mut self,
        (problem, bodies): (&Problem<ContactProjection>, &[Body]),
        (gravity, dt): (&Vector3<f64>, f64),
        bounces: impl Iterator<Item = (&'a Contact, f64)>,
    ) {
        let mut bounces = bounces.peekable();
        if bounces.peek().is_none() {
            self.half_step = None;
            return;
        }
        let half_step = gravity * (dt / 2.0);
        self.half_step = Some(half_step);
        let pairs = problem.blocks.iter().map(|b| (b.body_a.0, b.body_b.0));
        join_dynamic(&mut self.islands, bodies, pairs);
        self.accounts.clear();
        self.accounts.resize(bodies.len(), Account::default());
        for block in &problem.blocks {
            let (a, b) = (block.body_a.0, block.body_b.0);
            for (body, other) in [(a, b), (b, a)] {
                if bodies[body].is_dynamic() && bodies[other].is_kinematic() {
                    self.accounts[self.islands.root(body)].driven = true;
                }
            }
        }
        for (contact, took) in bounces {
            let (a, b) = (contact.body_a.0, contact.body_b.0);
            let body = if bodies[a].is_dynamic() { a } else { b };
            if bodies[body].is_dynamic() {
                self.accounts[self.islands.root(body)].landings_took += took;
            }
        }
        for (k, (body, solved)) in bodies.iter().zip(&problem.bodies).enumerate() {
            if body.is_dynamic() {
                let [quadratic, linear, constant] = scaled_energy(body, solved, &half_step);
                self.accounts[self.islands.root(k)].before += quadratic - linear + constant;
            }
        }
    }

    /// Scales the velocities of each island read by [`BounceGuard::before_solve`] whose
    /// energy the solve raised by more than its bounces' landings took, down to that.
    pub(crate) fn after_solve(
        &mut self,
        problem: &mut Problem<ContactProjection>,
        bodies: &[Body],
    ) {
        let Some(half_step) = self.half_step else {
            return;
        };
        for (k, (body, solved)) in bodies.iter().zip(&problem.bodies).enumerate() {
            if body.is_dynamic() {
                let terms = scaled_energy(body, solved, &half_step);
                let account = &mut self.accounts[self.islands.root(k)];
                for (sum, term) in account.scaled.iter_mut().zip(terms) {
                    *sum += term;
                }
            }
        }
        for (k, (body, solved)) in bodies.iter().zip(&mut problem.bodies).enumerate() {
            let account = self.accounts[self.islands.root(k)];
            if body.is_dynamic() && account.landings_took > 0.0 && !account.driven {
                let scale = account.scale_to(account.before + account.landings_took);
                solved.linear_velocity *= scale;
                solved.angular_velocity *= scale;
            }
        }
    }
}

impl Account {
    /// The largest factor, at most 1, that brings the island's energy after the solve to no
    /// more than `allowed`; where no factor does, the one that leaves it least. 1 (the solve's
    /// velocities kept) where the energies are not finite: the step's check of the bodies'
    /// state reports those.
    fn scale_to(&self, allowed: f64) -> f64 {
        let [a, b, c] = self.scaled;
        if !(a > 0.0 && a - b + c > allowed) {
            return 1.0;
        }
        // a s² − b s + c = allowed, its larger root: the energy grows with s beyond b / 2a.
        let least = b / (2.0 * a);
        let discriminant = b * b - 4.0 * a * (c - allowed);
        let scale = if discriminant > 0.0 {
            (b + discriminant.sqrt()) / (2.0 * a)
        } else {
            least
        };
        if scale.is_finite() {
            scale.clamp(0.0, 1.0)
        } else {
            1.0
        }
    }
}

/// `body`'s kinetic energy with `solved`'s velocities scaled by `s`, read at the linear velocity
/// less `half_step`, as `[q, l, c]` for `q s² − l s + c` (J).
fn scaled_energy(body: &Body, solved: &SolverBody, half_step: &Vector3<f64>) -> [f64; 3] {
    let v = &solved.linear_velocity;
    let moving = body.kinetic_energy_at(&body.inertia_world(), v, &solved.angular_velocity);
    [
        moving,
        body.mass() * v.dot(half_step),
        0.5 * body.mass() * half_step.norm_squared(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn account(scaled: [f64; 3]) -> Account {
        Account {
            scaled,
            ..Account::default()
        }
    }

    /// The energy `q s² − l s + c` at `scale`.
    fn energy([q, l, c]: [f64; 3], scale: f64) -> f64 {
        q * scale * scale - l * scale + c
    }

    #[test]
    fn an_island_within_its_allowance_keeps_its_velocities() {
        let terms = [10.0, 1.0, 0.1];
        assert_eq!(account(terms).scale_to(energy(terms, 1.0)), 1.0);
        assert_eq!(account(terms).scale_to(20.0), 1.0);
        // At rest: nothing to scale.
        assert_eq!(account([0.0, 0.0, 0.1]).scale_to(0.0), 1.0);
    }

    /// Over its allowance, the island is scaled to meet it exactly (to rounding), by the
    /// root nearer 1 of the quadratic: for `[10, 1, 0.1]` (9.1 J at full speed) and 5 J
    /// allowed, `10 s² − s + 0.1 = 5`, `s = (1 + √197) / 20`.
    #[test]
    fn an_island_over_its_allowance_is_scaled_to_meet_it() {
        let terms = [10.0, 1.0, 0.1];
        let scale = account(terms).scale_to(5.0);
        assert!((scale - (1.0 + 197f64.sqrt()) / 20.0).abs() < 1e-15);
        assert!((energy(terms, scale) - 5.0).abs() < 1e-12);
    }

    /// An allowance below the least energy any factor gives (`c − l² / 4q`, the gravity half
    /// step's share) is met as nearly as it can be, at the minimising factor `l / 2q`.
    #[test]
    fn an_allowance_out_of_reach_takes_the_least_energy() {
        let terms = [10.0, 1.0, 0.1];
        assert_eq!(account(terms).scale_to(0.0), 0.05);
    }

    #[test]
    fn energies_that_are_not_finite_leave_the_velocities_alone() {
        for terms in [
            [f64::NAN, 1.0, 0.1],
            [f64::INFINITY, 1.0, 0.1],
            [10.0, f64::INFINITY, 0.1],
        ] {
            assert_eq!(account(terms).scale_to(5.0), 1.0, "{terms:?}");
        }
        assert_eq!(account([10.0, 1.0, 0.1]).scale_to(f64::NAN), 1.0);
    }
}
