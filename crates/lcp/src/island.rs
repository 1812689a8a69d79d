//! A problem's blocks grouped by island: blocks joined through bodies an impulse can move.
//!
//! A block changes only its two bodies' velocities, and a fixed body's not at all (its inverse
//! mass and inertia are zero), so the blocks of two islands never read what the other writes:
//! PGS may run one island's sweeps after the other's and get the same bits as sweeping the whole
//! problem. What islands change is stopping: each island stops after its own first quiet sweep
//! ([`crate::pgs::PgsParams::tolerance`]), so a pile at rest beside one still moving costs one
//! sweep, not all of them. A floor does not join what rests on it, as in Box2D, Jolt and Rapier.

use std::ops::Range;

use crate::{Problem, SolverBody};

/// Disjoint sets of `0..n` (union–find), for grouping bodies into islands; the buffer is reused
/// across [`reset`](DisjointSets::reset)s.
///
/// ```
/// use tatami_lcp::DisjointSets;
/// let mut sets = DisjointSets::default();
/// sets.reset(4);
/// sets.join(3, 1);
/// sets.join(1, 2);
/// assert_eq!(sets.root(3), 1, "the smallest index is the root");
/// assert_eq!(sets.root(2), 1);
/// assert_eq!(sets.root(0), 0);
/// ```
#[derive(Debug, Clone, Default)]
pub struct DisjointSets {
    /// `parent[i] == i` at a root.
    parent: Vec<usize>,
}

impl DisjointSets {
    /// `n` sets of one element each.
    pub fn reset(&mut self, n: usize) {
        self.parent.clear();
        self.parent.extend(0..n);
    }

    /// Joins the sets of `a` and `b`. The smaller root becomes the root, so the sets' roots do
    /// not depend on the order of the joins.
    pub fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        self.parent[ra.max(rb)] = ra.min(rb);
    }

    /// The root of `k`'s set (its smallest element), halving the path on the way.
    pub fn root(&mut self, mut k: usize) -> usize {
        while self.parent[k] != k {
            self.parent[k] = self.parent[self.parent[k]];
            k = self.parent[k];
        }
        k
    }
}

/// The blocks of a problem in island order, each island's in their problem order; buffers
/// reused across solves.
#[derive(Debug, Clone, Default)]
pub(crate) struct BlockIslands {
    /// Per body: whether an impulse can move it ([`movable`]), read twice for every block on
    /// it. Asked of the body each time (a 3 × 3 comparison), it was a third of the grouping's
    /// instructions on a resting 1000-cube pile.
    movable: Vec<bool>,
    /// The bodies, joined through the blocks between two movable ones.
    sets: DisjointSets,
    /// Per body root: its island's index, once its first block is met.
    island_of_root: Vec<usize>,
    /// Per block: its island's index.
    island_of_block: Vec<usize>,
    /// Block indices, island after island.
    blocks: Vec<usize>,
    /// Per island: its range in `blocks`.
    ranges: Vec<Range<usize>>,
}

/// Whether an impulse can move `body`: it joins the islands of the blocks on it.
pub(crate) fn movable(body: &SolverBody) -> bool {
    body.inv_mass != 0.0 || body.inv_inertia_world != nalgebra::Matrix3::zeros()
}

impl BlockIslands {
    /// Groups `problem`'s blocks. Islands come in the order of their first blocks; blocks
    /// between immovable bodies only (they change nothing) form one island of their own.
    pub(crate) fn group<P>(&mut self, problem: &Problem<P>) {
        let bodies = &problem.bodies;
        self.movable.clear();
        self.movable.extend(bodies.iter().map(movable));
        let movable = &self.movable;
        self.sets.reset(bodies.len());
        for block in &problem.blocks {
            let (a, b) = (block.body_a.0, block.body_b.0);
            if movable[a] && movable[b] {
                self.sets.join(a, b);
            }
        }
        const UNSEEN: usize = usize::MAX;
        self.island_of_root.clear();
        self.island_of_root.resize(bodies.len() + 1, UNSEEN);
        self.island_of_block.clear();
        let mut islands = 0;
        for block in &problem.blocks {
            let (a, b) = (block.body_a.0, block.body_b.0);
            // The immovable blocks' island is keyed past the last body.
            let key = if movable[a] {
                self.sets.root(a)
            } else if movable[b] {
                self.sets.root(b)
            } else {
                bodies.len()
            };
            if self.island_of_root[key] == UNSEEN {
                self.island_of_root[key] = islands;
                islands += 1;
            }
            self.island_of_block.push(self.island_of_root[key]);
        }
        // Counting sort of the blocks by island, stable.
        self.ranges.clear();
        self.ranges.resize(islands, 0..0);
        for &island in &self.island_of_block {
            self.ranges[island].end += 1;
        }
        let mut start = 0;
        for range in &mut self.ranges {
            let count = range.end;
            *range = start..start;
            start += count;
        }
        self.blocks.clear();
        self.blocks.resize(problem.blocks.len(), 0);
        for (index, &island) in self.island_of_block.iter().enumerate() {
            let range = &mut self.ranges[island];
            self.blocks[range.end] = index;
            range.end += 1;
        }
    }

    /// The islands' blocks, one slice per island.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &[usize]> {
        self.ranges.iter().map(|range| &self.blocks[range.clone()])
    }

    /// The bodies as [`BlockIslands::group`] joined them.
    pub(crate) fn body_sets(&mut self) -> &mut DisjointSets {
        &mut self.sets
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Block, BodyId, BoundsProjection};

    fn block(a: usize, b: usize) -> Block<BoundsProjection> {
        Block {
            body_a: BodyId(a),
            body_b: BodyId(b),
            rows: 0..0,
            projection: BoundsProjection(Vec::new()),
        }
    }

    fn body(inv_mass: f64) -> SolverBody {
        SolverBody {
            inv_mass,
            ..SolverBody::fixed()
        }
    }

    #[test]
    fn a_floor_does_not_join_what_rests_on_it() {
        // Body 0 is a floor; 1–2 touch, 3–4 touch, both pairs on the floor; 5 alone on it.
        let problem = Problem {
            bodies: vec![
                body(0.0),
                body(1.0),
                body(1.0),
                body(1.0),
                body(1.0),
                body(1.0),
            ],
            rows: Vec::new(),
            blocks: vec![
                block(1, 0),
                block(3, 4),
                block(0, 5),
                block(2, 1),
                block(0, 0),
                block(4, 0),
                block(2, 0),
            ],
        };
        let mut islands = BlockIslands::default();
        islands.group(&problem);
        let grouped: Vec<&[usize]> = islands.iter().collect();
        assert_eq!(grouped, vec![&[0, 3, 6][..], &[1, 5], &[2], &[4]]);
    }

    #[test]
    fn a_body_with_only_inertia_joins_islands() {
        let spinning = SolverBody {
            inv_inertia_world: nalgebra::Matrix3::identity(),
            ..SolverBody::fixed()
        };
        let problem = Problem {
            bodies: vec![body(1.0), spinning, body(1.0)],
            rows: Vec::new(),
            blocks: vec![block(0, 1), block(2, 1)],
        };
        let mut islands = BlockIslands::default();
        islands.group(&problem);
        assert_eq!(islands.iter().count(), 1);
    }
}
