//! The shock passes' held responses, computed once a step for both passes.
//!
//! The velocity solve and the position pass each end with a shock pass over the same blocks in
//! the same order, and each computed, block by block, the responses to the block's rows with
//! its supporting body held still ([`HeldResponses`]): on the velocity solve's thread, whose
//! length is the step's, that was 7% of its instructions on a resting 1000-cube pile. Those
//! responses read only the rows' Jacobians and the bodies' masses, which the position pass's
//! copy of the problem holds to the bit, and the position pass, shorter, runs on a helper
//! beside the velocity solve: it now computes them for both before its own sweeps, and the
//! velocity solve takes them when its sweeps end, waiting if they are still being computed.
//! When the position pass has not started by then (one thread, or a helper slow to wake), the
//! velocity solve computes its own as it goes, as before; either way the answer is the same to
//! the bit.

use std::sync::{Mutex, PoisonError};

use tatami_lcp::pgs::HeldResponses;

/// Where a step's held responses stand.
#[derive(Debug, Clone, Copy)]
enum Stage<'a> {
    /// Neither pass has come for them.
    Unclaimed,
    /// The position pass is computing them.
    Computing,
    /// Computed, for both passes.
    Ready(&'a HeldResponses),
    /// Not computed for the velocity solve: it went on without them (or they could not be).
    Passed,
}

/// One step's hand-off of the held responses from the position pass to the velocity solve.
#[derive(Debug)]
pub(crate) struct HeldHandoff<'a> {
    stage: Mutex<Stage<'a>>,
}

impl<'a> HeldHandoff<'a> {
    pub(crate) fn new() -> Self {
        Self {
            stage: Mutex::new(Stage::Unclaimed),
        }
    }

    /// The position pass's side, before its sweeps: unless the velocity solve has gone on
    /// without them, fills `held` with `compute` (`false` when it could not) and hands them
    /// over; returns them for the position pass's own shock pass when it did.
    pub(crate) fn offer(
        &self,
        held: &'a mut HeldResponses,
        compute: impl FnOnce(&mut HeldResponses) -> bool,
    ) -> Option<&'a HeldResponses> {
        {
            let mut stage = self.lock();
            if !matches!(*stage, Stage::Unclaimed) {
                return None;
            }
            *stage = Stage::Computing;
        }
        let computed = compute(held);
        let held: &'a HeldResponses = held;
        *self.lock() = if computed {
            Stage::Ready(held)
        } else {
            Stage::Passed
        };
        computed.then_some(held)
    }

    /// The velocity solve's side, when its sweeps end: the held responses if the position pass
    /// computed them, waiting while it computes them; `None` if it has not started on them, and
    /// then it will not.
    pub(crate) fn take(&self) -> Option<&'a HeldResponses> {
        loop {
            {
                let mut stage = self.lock();
                match *stage {
                    Stage::Unclaimed => {
                        *stage = Stage::Passed;
                        return None;
                    }
                    Stage::Passed => return None,
                    Stage::Ready(held) => return Some(held),
                    Stage::Computing => {}
                }
            }
            // A few hundred microseconds at most: the responses of a 1000-cube pile's blocks.
            for _ in 0..64 {
                std::hint::spin_loop();
            }
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Stage<'a>> {
        self.stage.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tatami_lcp::pgs::Support;
    use tatami_lcp::{Block, BodyId, BoundsProjection, Problem, Row, RowBound, SolverBody};

    /// A body on a fixed one through one row, and its shock order.
    fn problem() -> (Problem<BoundsProjection>, [(usize, Support); 1]) {
        let mut body = SolverBody::fixed();
        body.inv_mass = 1.0;
        let problem = Problem {
            bodies: vec![body, SolverBody::fixed()],
            rows: vec![Row::default()],
            blocks: vec![Block {
                body_a: BodyId(0),
                body_b: BodyId(1),
                rows: 0..1,
                projection: BoundsProjection(vec![RowBound::NonNegative]),
            }],
        };
        (problem, [(0, Support::B)])
    }

    #[test]
    fn the_velocity_solve_takes_what_the_position_pass_computed() {
        let (problem, order) = problem();
        let mut held = HeldResponses::default();
        let handoff = HeldHandoff::new();
        let own = handoff.offer(&mut held, |h| h.compute(&problem, &order).is_ok());
        let taken = handoff.take().expect("computed before it was asked for");
        assert!(std::ptr::eq(own.expect("computed"), taken));
    }

    #[test]
    fn a_velocity_solve_that_comes_first_goes_on_without_them() {
        let (problem, order) = problem();
        let mut held = HeldResponses::default();
        let handoff = HeldHandoff::new();
        assert!(handoff.take().is_none());
        let mut computed = false;
        let own = handoff.offer(&mut held, |h| {
            computed = true;
            h.compute(&problem, &order).is_ok()
        });
        assert!(own.is_none() && !computed, "not computed for nobody");
        assert!(handoff.take().is_none());
    }

    #[test]
    fn responses_that_could_not_be_computed_are_not_handed_over() {
        let mut held = HeldResponses::default();
        let handoff = HeldHandoff::new();
        assert!(handoff.offer(&mut held, |_| false).is_none());
        assert!(handoff.take().is_none());
    }

    /// The velocity solve asks while the position pass computes on another thread: it waits,
    /// then takes them.
    #[test]
    fn the_velocity_solve_waits_for_responses_being_computed() {
        let (problem, order) = problem();
        let mut held = HeldResponses::default();
        let handoff = HeldHandoff::new();
        let (started, release) = (
            std::sync::Barrier::new(2),
            std::sync::atomic::AtomicBool::new(false),
        );
        std::thread::scope(|scope| {
            scope.spawn(|| {
                handoff.offer(&mut held, |h| {
                    started.wait();
                    while !release.load(std::sync::atomic::Ordering::SeqCst) {
                        std::hint::spin_loop();
                    }
                    h.compute(&problem, &order).is_ok()
                })
            });
            started.wait();
            let asker = scope.spawn(|| handoff.take().is_some());
            std::thread::sleep(std::time::Duration::from_millis(20));
            assert!(
                !asker.is_finished(),
                "the asker waits while they are computed"
            );
            release.store(true, std::sync::atomic::Ordering::SeqCst);
            assert!(asker.join().expect("no panic"), "and then takes them");
        });
    }
}
