//! Which blocks a PGS sweep passes over as quiet ([`crate::pgs`], "Quiet blocks").
//!
//! A block is quiet while its last update changed its rows' velocities by less than the
//! tolerance and the other blocks' updates have since moved its two bodies by less than the
//! tolerance in all. Each update's change, the largest of its rows' own velocity changes, is
//! added to both its bodies: for the lighter body that is about how much it moved, for a
//! heavier one more, so a body is never taken for stiller than it is. A body no impulse
//! moves (a floor, a kinematic body) never counts as moved, or every block on the floor would
//! be woken by every other.

use crate::SolverBody;
use crate::island::movable;

/// Per-solve record of the updates' changes, by body and by block.
#[derive(Debug, Clone, Default)]
pub(crate) struct Quiet {
    /// Per body: the sum of the changes of the updates that moved it in this solve (0 for a body
    /// no impulse moves).
    moved: Vec<f64>,
    /// Per body: whether an impulse moves it.
    movable: Vec<bool>,
    /// Per block: its last update's change, and its bodies' `moved` just after it; an infinite
    /// change before its first update.
    last: Vec<(f64, [f64; 2])>,
}

impl Quiet {
    /// Before a solve of a problem of `bodies` and `blocks` blocks: nothing quiet yet.
    pub(crate) fn reset(&mut self, bodies: &[SolverBody], blocks: usize) {
        self.moved.clear();
        self.moved.resize(bodies.len(), 0.0);
        self.movable.clear();
        self.movable.extend(bodies.iter().map(movable));
        self.last.clear();
        self.last.resize(blocks, (f64::INFINITY, [0.0; 2]));
    }

    /// Whether `block`, between bodies `a` and `b`, is quiet under `tolerance` (never for a
    /// tolerance of 0).
    #[inline]
    pub(crate) fn skips(&self, block: usize, a: usize, b: usize, tolerance: f64) -> bool {
        let (change, seen) = self.last[block];
        change < tolerance
            && self.moved[a] - seen[0] < tolerance
            && self.moved[b] - seen[1] < tolerance
    }

    /// Records `block`'s update, which changed its rows' velocities by up to `change`.
    #[inline]
    pub(crate) fn updated(&mut self, block: usize, a: usize, b: usize, change: f64) {
        for body in [a, b] {
            if self.movable[body] {
                self.moved[body] += change;
            }
        }
        self.last[block] = (change, [self.moved[a], self.moved[b]]);
    }
}
