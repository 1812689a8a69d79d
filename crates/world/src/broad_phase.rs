//! Broad phase: sort and sweep over bounding boxes along the axis where the boxes spread most,
//! in strips across the axis where they spread second most.
//!
//! O(n log n + k) for n boxes and k overlapping pairs when the boxes are spread along one axis;
//! the axis choice keeps a vertical tower (all boxes at the same x and y) from degenerating to
//! O(n²). A pile spread over a floor is spread along two axes: a box's extent along the sweep
//! axis then covers a fixed share of all the boxes, and the sweep tried every one of them (a
//! sixth of the 1000-cube pile's boxes for each box). Cut into strips a couple of boxes wide
//! across it, each box meets only the boxes of its strips. The order is kept from step to step,
//! so the sort starts from an almost sorted list, and each strip's boxes are copied in that
//! order, so the sweep's inner loop reads memory in sequence.
//!
//! The sweep runs over the boxes grown by a slack ([`SLACK_SHARE`]), and its pairs are kept:
//! while every box stays inside its grown one, the pairs whose boxes overlap are among them and
//! are picked out by testing those alone, as Box2D's and Rapier's broad phases keep fat boxes.
//! A box that leaves its grown one is grown again where it is and tested against every grown
//! box; when many leave at once, everything is swept afresh. The same pairs come out either
//! way, so nothing after the broad phase can tell. The 1000-cube pile swept its 4,200 pairs in
//! 0.32–0.39 ms a step, and its collision at rest fell from 0.73–0.85 to 0.51–0.58 ms a step
//! (seconds 8–10; 5,400 grown pairs, none swept after its fourth second).

use nalgebra::Vector3;

use crate::nearly_sorted::sort_nearly_in_order_by;

/// A box as the sweep reads it: its bounds, whether its body is static, and its index.
#[derive(Debug, Clone, Copy)]
struct Swept {
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    is_static: bool,
    index: usize,
}

/// Slack a box is grown by for the sweep, as a share of its least width (all round): 5 cm for
/// a 1 m cube's box, so that a body creeping at 1 mm/s leaves it after about a minute, while a
/// pile's grown boxes overlap in few pairs more than its boxes do.
const SLACK_SHARE: f64 = 0.05;

/// Most boxes that may leave their grown ones in a pass for the pairs to be brought up to date
/// box by box. Each such box is tested against every box, a few nanoseconds a box, where a
/// sweep takes some 350 ns a box (the 1000-cube pile's, at any count of boxes): this many cost
/// a fraction of a sweep.
const MOST_REGROWN: usize = 64;

/// The broad phase's state between steps: the grown boxes and their overlapping pairs, the
/// boxes' order along the sweep axis, and scratch.
#[derive(Debug, Default, Clone)]
pub(crate) struct SweepAndPrune {
    /// Each box grown by its slack when it was last swept or left its grown box.
    grown: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Which boxes were static when the grown pairs were found.
    grown_static: Vec<bool>,
    /// Every pair, not both static, whose grown boxes overlap, in increasing order.
    grown_pairs: Vec<(usize, usize)>,
    /// Scratch: whether each box left its grown box in this pass.
    left: Vec<bool>,
    /// How many passes swept every box.
    #[cfg(test)]
    sweeps: usize,
    order: Vec<usize>,
    /// The boxes of every strip in turn, each strip in sweep order.
    swept: Vec<Swept>,
    /// Where each strip's boxes start in `swept`, and where the last ends.
    starts: Vec<usize>,
    /// Scratch: where the next box of each strip goes in `swept`.
    cursor: Vec<usize>,
    /// Scratch: the boxes' extents across the strips.
    extents: Vec<f64>,
    /// Scratch: the pairs as the strips find them, before they are put in order; and the
    /// regrown pairs once in order, swapped into the grown pairs.
    found: Vec<(usize, usize)>,
    /// Scratch: where each box's pairs as the lower index start in the ordered list.
    firsts: Vec<usize>,
}

/// Strip width as a multiple of the boxes' median extent across the strips: a box of median
/// size then lies in one strip, or two.
const STRIP_WIDTH: f64 = 2.0;

/// Fewest boxes per strip on average: fewer strips than this allows would cost more in copies
/// of boxes spanning several strips than they save.
const BOXES_PER_STRIP: usize = 16;

/// The strips across `axis`: their first lower bound, width and count.
#[derive(Debug, Clone, Copy)]
struct Strips {
    start: f64,
    width: f64,
    count: usize,
}

impl Strips {
    /// The strip holding coordinate `x` (the first or last beyond either end).
    fn of(&self, x: f64) -> usize {
        // A float-to-integer cast saturates: below the start is strip 0.
        (((x - self.start) / self.width) as usize).min(self.count - 1)
    }

    /// The strips a box from `lo` to `hi` across them lies in (one, should `hi` not be `lo`'s
    /// or more).
    fn spanned(&self, lo: f64, hi: f64) -> std::ops::RangeInclusive<usize> {
        let first = self.of(lo);
        first..=self.of(hi).max(first)
    }
}

/// Whether boxes `a` and `b` overlap (touching counts).
fn overlap(a: &(Vector3<f64>, Vector3<f64>), b: &(Vector3<f64>, Vector3<f64>)) -> bool {
    (0..3).all(|d| a.0[d] <= b.1[d] && b.0[d] <= a.1[d])
}

/// Whether box `inner` lies inside box `outer`.
fn inside(inner: &(Vector3<f64>, Vector3<f64>), outer: &(Vector3<f64>, Vector3<f64>)) -> bool {
    (0..3).all(|d| outer.0[d] <= inner.0[d] && inner.1[d] <= outer.1[d])
}

/// Box `(lo, hi)` grown all round by [`SLACK_SHARE`] of its least width.
fn grow((lo, hi): &(Vector3<f64>, Vector3<f64>)) -> (Vector3<f64>, Vector3<f64>) {
    let slack = Vector3::repeat(SLACK_SHARE * (hi - lo).min());
    (lo - slack, hi + slack)
}

impl SweepAndPrune {
    /// Writes to `pairs` every `(i, j)`, `i < j`, whose boxes overlap and that are not both
    /// static, in increasing order: the grown boxes' pairs that overlap, once those are up to
    /// date (module doc).
    pub(crate) fn overlapping_pairs(
        &mut self,
        boxes: &[(Vector3<f64>, Vector3<f64>)],
        is_static: &[bool],
        pairs: &mut Vec<(usize, usize)>,
    ) {
        let n = boxes.len();
        let same_boxes = self.grown.len() == n && self.grown_static == is_static;
        self.left.clear();
        if same_boxes {
            let left = boxes.iter().zip(&self.grown).map(|(b, g)| !inside(b, g));
            self.left.extend(left);
        }
        let leaving = self.left.iter().filter(|&&left| left).count();
        if !same_boxes || leaving > MOST_REGROWN {
            self.grown.clear();
            self.grown.extend(boxes.iter().map(grow));
            self.grown_static.clear();
            self.grown_static.extend_from_slice(is_static);
            let (grown, mut grown_pairs) = (
                std::mem::take(&mut self.grown),
                std::mem::take(&mut self.grown_pairs),
            );
            self.sweep(&grown, is_static, &mut grown_pairs);
            (self.grown, self.grown_pairs) = (grown, grown_pairs);
            #[cfg(test)]
            {
                self.sweeps += 1;
            }
        } else if leaving > 0 {
            self.regrow(boxes, is_static);
        }
        pairs.clear();
        pairs.extend((self.grown_pairs.iter()).filter(|&&(i, j)| overlap(&boxes[i], &boxes[j])));
    }

    /// Grows again the boxes that left their grown ones, and brings the grown pairs up to
    /// date: those of the other boxes stay as they were, and each regrown box is tested
    /// against every grown box.
    fn regrow(&mut self, boxes: &[(Vector3<f64>, Vector3<f64>)], is_static: &[bool]) {
        let left = &self.left;
        for (i, _) in left.iter().enumerate().filter(|&(_, &left)| left) {
            self.grown[i] = grow(&boxes[i]);
        }
        self.grown_pairs.retain(|&(i, j)| !left[i] && !left[j]);
        for (i, _) in left.iter().enumerate().filter(|&(_, &left)| left) {
            for (j, grown) in self.grown.iter().enumerate() {
                // A pair of two regrown boxes is found from the first of them.
                let twice = left[j] && j < i;
                if j == i || twice || (is_static[i] && is_static[j]) {
                    continue;
                }
                if overlap(&self.grown[i], grown) {
                    self.grown_pairs.push((i.min(j), i.max(j)));
                }
            }
        }
        // Put in order as the sweep's are, by the counting sort into scratch reused from pass
        // to pass (a comparison sort's merge buffer was allocated on every pass).
        order_by_pair(
            &self.grown_pairs,
            |&pair| pair,
            &mut self.firsts,
            boxes.len(),
            &mut self.found,
        );
        std::mem::swap(&mut self.grown_pairs, &mut self.found);
    }

    /// Writes to `pairs` every `(i, j)`, `i < j`, whose boxes overlap and that are not both
    /// static, in increasing order, by sweeping them all.
    fn sweep(
        &mut self,
        boxes: &[(Vector3<f64>, Vector3<f64>)],
        is_static: &[bool],
        pairs: &mut Vec<(usize, usize)>,
    ) {
        self.found.clear();
        let n = boxes.len() as f64;
        let centre = |(lo, hi): &(Vector3<f64>, Vector3<f64>)| (lo + hi) / 2.0;
        let mean = boxes.iter().map(centre).sum::<Vector3<f64>>() / n.max(1.0);
        let spread = boxes
            .iter()
            .map(|b| (centre(b) - mean).map(|x| x * x))
            .sum::<Vector3<f64>>();
        let axis = spread.imax();
        let across = (0..3)
            .filter(|&d| d != axis)
            .max_by(|&d, &e| spread[d].total_cmp(&spread[e]))
            .unwrap_or(0);
        // Last step's order is a permutation of the same indices unless bodies were added or
        // removed; the pairs found do not depend on how ties are ordered.
        if self.order.len() != boxes.len() {
            self.order.clear();
            self.order.extend(0..boxes.len());
        }
        sort_nearly_in_order_by(&mut self.order, |&i, &j| {
            boxes[i].0[axis].total_cmp(&boxes[j].0[axis])
        });
        let strips = self.strips(boxes, across);
        // Counting sort into the strips, in sweep order: count, then place.
        self.starts.clear();
        self.starts.resize(strips.count + 1, 0);
        for (lo, hi) in boxes {
            for strip in strips.spanned(lo[across], hi[across]) {
                self.starts[strip + 1] += 1;
            }
        }
        for strip in 0..strips.count {
            self.starts[strip + 1] += self.starts[strip];
        }
        let placeholder = Swept {
            lo: Vector3::zeros(),
            hi: Vector3::zeros(),
            is_static: false,
            index: 0,
        };
        self.swept.clear();
        self.swept.resize(self.starts[strips.count], placeholder);
        self.cursor.clone_from(&self.starts);
        for &index in &self.order {
            let (lo, hi) = boxes[index];
            for next in &mut self.cursor[strips.spanned(lo[across], hi[across])] {
                self.swept[*next] = Swept {
                    lo,
                    hi,
                    is_static: is_static[index],
                    index,
                };
                *next += 1;
            }
        }
        for (strip, bounds) in self.starts.windows(2).enumerate() {
            let swept = &self.swept[bounds[0]..bounds[1]];
            for (k, a) in swept.iter().enumerate() {
                for b in &swept[k + 1..] {
                    if b.lo[axis] > a.hi[axis] {
                        break;
                    }
                    if a.is_static && b.is_static {
                        continue;
                    }
                    // A pair sharing several strips is reported from the one where their
                    // overlap across the strips begins.
                    if overlap(&(a.lo, a.hi), &(b.lo, b.hi))
                        && strips.of(a.lo[across].max(b.lo[across])) == strip
                    {
                        self.found
                            .push((a.index.min(b.index), a.index.max(b.index)));
                    }
                }
            }
        }
        order_by_pair(
            &self.found,
            |&pair| pair,
            &mut self.firsts,
            boxes.len(),
            pairs,
        );
    }

    /// Strips across `across` [`STRIP_WIDTH`] median boxes wide, at most one per
    /// [`BOXES_PER_STRIP`] boxes, spanning the boxes' centres.
    fn strips(&mut self, boxes: &[(Vector3<f64>, Vector3<f64>)], across: usize) -> Strips {
        let one = Strips {
            start: 0.0,
            width: 1.0,
            count: 1,
        };
        if boxes.len() < 2 * BOXES_PER_STRIP {
            return one;
        }
        self.extents.clear();
        self.extents
            .extend(boxes.iter().map(|(lo, hi)| hi[across] - lo[across]));
        let middle = self.extents.len() / 2;
        let (_, median, _) = self.extents.select_nth_unstable_by(middle, f64::total_cmp);
        let width = STRIP_WIDTH * *median;
        let (start, end) = boxes
            .iter()
            .map(|(lo, hi)| (lo[across] + hi[across]) / 2.0)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(s, e), c| {
                (s.min(c), e.max(c))
            });
        let count = ((end - start) / width).ceil();
        if !(width > 0.0 && count.is_finite() && count >= 2.0) {
            return one;
        }
        Strips {
            start,
            width,
            count: (count as usize).min(boxes.len() / BOXES_PER_STRIP),
        }
    }
}

/// Writes `found` (items each naming a pair `(i, j)`, `i < n`, by `pair`; no two alike) to
/// `ordered` in increasing order: a counting sort by `i`, then each `i`'s few items in order.
/// The strips find a pile's pairs (over 10,000 while it lands) in sweep order, which a
/// comparison sort took 1% of the pile's step to put in order; the contact set's held pairs
/// come in the order of their contacts' heights.
pub(crate) fn order_by_pair<T: Copy + Ord + Default>(
    found: &[T],
    pair: impl Fn(&T) -> (usize, usize),
    firsts: &mut Vec<usize>,
    n: usize,
    ordered: &mut Vec<T>,
) {
    firsts.clear();
    firsts.resize(n + 1, 0);
    for item in found {
        firsts[pair(item).0 + 1] += 1;
    }
    for i in 0..n {
        firsts[i + 1] += firsts[i];
    }
    ordered.clear();
    ordered.resize(found.len(), T::default());
    for item in found {
        let next = &mut firsts[pair(item).0];
        ordered[*next] = *item;
        *next += 1;
    }
    // Each `firsts[i]` now holds where `i`'s items end, which is where `i + 1`'s start.
    let mut start = 0;
    for &end in &firsts[..n] {
        ordered[start..end].sort_unstable();
        start = end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Every overlapping pair, by checking all of them.
    fn brute_force(
        boxes: &[(Vector3<f64>, Vector3<f64>)],
        is_static: &[bool],
    ) -> Vec<(usize, usize)> {
        let mut pairs = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                // Written out, not the module's `overlap`: the reference stands on its own.
                let (a, b) = (&boxes[i], &boxes[j]);
                let overlap = (0..3).all(|d| a.0[d] <= b.1[d] && b.0[d] <= a.1[d]);
                if overlap && !(is_static[i] && is_static[j]) {
                    pairs.push((i, j));
                }
            }
        }
        pairs
    }

    #[test]
    fn sweep_finds_the_same_pairs_as_checking_all() {
        // A deterministic scatter of boxes of mixed sizes, some static.
        let mut state = 12345_u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut boxes = Vec::new();
        let mut is_static = Vec::new();
        for _ in 0..200 {
            let c = Vector3::new(next() * 10.0, next() * 10.0, next() * 30.0);
            let h = Vector3::new(next(), next(), next()) + Vector3::repeat(0.1);
            boxes.push((c - h, c + h));
            is_static.push(next() < 0.2);
        }
        let (mut broad_phase, mut pairs) = (SweepAndPrune::default(), Vec::new());
        broad_phase.overlapping_pairs(&boxes, &is_static, &mut pairs);
        let expected = brute_force(&boxes, &is_static);
        assert!(!expected.is_empty());
        assert_eq!(pairs, expected);
        // Again after the boxes moved, starting from the order the first sweep left.
        for (lo, hi) in &mut boxes {
            let shift = Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 4.0;
            *lo += shift;
            *hi += shift;
        }
        broad_phase.overlapping_pairs(&boxes, &is_static, &mut pairs);
        assert_eq!(pairs, brute_force(&boxes, &is_static));
    }

    /// A pile as strips see it: boxes of mixed sizes (some many strips wide) spread over a floor
    /// that spans every strip, and a tower standing on it, in a turned frame so the axes are
    /// not the world's; the pairs are the brute force's, and the pile is cut into strips.
    #[test]
    fn strips_find_the_same_pairs_as_checking_all() {
        proptest!(ProptestConfig::with_cases(64), |(
            spots in prop::collection::vec(
                ((-8.0..8.0f64, -8.0..8.0f64, 0.0..4.0f64), 0.2..1.5f64, prop::bool::weighted(0.1)),
                40..160,
            ),
            tower in 0usize..20,
            turn in 0.0..std::f64::consts::TAU,
        )| {
            let (c, s) = (turn.cos(), turn.sin());
            let turned = |x: f64, y: f64, z: f64| Vector3::new(c * x - s * y, s * x + c * y, z);
            let mut boxes = vec![(turned(-20.0, -20.0, -1.0), turned(20.0, 20.0, 0.0))];
            boxes[0] = (boxes[0].0.inf(&boxes[0].1), boxes[0].0.sup(&boxes[0].1));
            let mut is_static = vec![true];
            for ((x, y, z), size, wide) in spots {
                let half = if wide { Vector3::new(4.0 * size, size, size) } else { Vector3::repeat(size) };
                let centre = turned(x, y, z);
                boxes.push((centre - half, centre + half));
                is_static.push(false);
            }
            for level in 0..tower {
                let centre = Vector3::new(0.0, 0.0, 0.5 + level as f64);
                boxes.push((centre - Vector3::repeat(0.51), centre + Vector3::repeat(0.51)));
                is_static.push(false);
            }
            let mut broad_phase = SweepAndPrune::default();
            let strips = broad_phase.strips(&boxes, 1);
            prop_assert!(strips.count >= 2, "{strips:?}");
            let mut pairs = Vec::new();
            broad_phase.overlapping_pairs(&boxes, &is_static, &mut pairs);
            prop_assert_eq!(pairs, brute_force(&boxes, &is_static));
        });
    }

    /// Passes over boxes that move as a pile's bodies do, from step to step: all of them
    /// creeping within their slack, a few leaving it, many at once, a body turning static, a
    /// body added. Every pass finds the brute force's pairs, whether it sweeps, regrows the
    /// boxes that left or keeps the grown pairs as they were.
    #[test]
    fn grown_boxes_find_the_same_pairs_as_checking_all() {
        proptest!(ProptestConfig::with_cases(48), |(
            spots in prop::collection::vec(
                ((-6.0..6.0f64, -6.0..6.0f64, 0.0..3.0f64), 0.2..1.0f64),
                64..128,
            ),
            moves in prop::collection::vec((0usize..6, any::<u64>()), 12),
        )| {
            let mut boxes = vec![(Vector3::new(-20.0, -20.0, -1.0), Vector3::new(20.0, 20.0, 0.0))];
            let mut is_static = vec![true];
            for ((x, y, z), size) in spots {
                let centre = Vector3::new(x, y, z);
                boxes.push((centre - Vector3::repeat(size), centre + Vector3::repeat(size)));
                is_static.push(false);
            }
            let mut broad_phase = SweepAndPrune::default();
            let mut pairs = Vec::new();
            broad_phase.overlapping_pairs(&boxes, &is_static, &mut pairs);
            prop_assert_eq!(&pairs, &brute_force(&boxes, &is_static));
            let mut swept = broad_phase.sweeps;
            for (kind, seed) in moves {
                let mut random = crate::dropped::Random::new(seed);
                let n = boxes.len();
                let was_static = is_static.clone();
                let mut shift = |k: usize, by: f64| {
                    let d = Vector3::new(
                        random.between(-by, by),
                        random.between(-by, by),
                        random.between(-by, by),
                    );
                    boxes[k].0 += d;
                    boxes[k].1 += d;
                };
                match kind {
                    // Every body creeps, well within its slack (10 mm on the smallest boxes).
                    0 | 1 => (1..n).for_each(|k| shift(k, 1e-3)),
                    // Two bodies leave their slack for the same place.
                    2 => {
                        let k = 1 + seed as usize % (n - 2);
                        shift(k, 2.0);
                        boxes[n - 1] = boxes[k];
                    }
                    // Most bodies move far.
                    3 => (1..n).for_each(|k| shift(k, 1.5)),
                    // A body stops being free (a kinematic or fixed one, to the broad phase).
                    4 => is_static[1 + seed as usize % (n - 1)] = true,
                    // A body is added.
                    _ => {
                        boxes.push((Vector3::new(0.0, 0.0, 0.5), Vector3::new(1.0, 1.0, 1.5)));
                        is_static.push(false);
                    }
                }
                broad_phase.overlapping_pairs(&boxes, &is_static, &mut pairs);
                prop_assert_eq!(&pairs, &brute_force(&boxes, &is_static), "after move {}", kind);
                let sweeps = broad_phase.sweeps - swept;
                swept = broad_phase.sweeps;
                // Many boxes leaving may be swept or regrown, as many as they are; a body
                // already static made static again changes nothing.
                let changed = boxes.len() != n || is_static != was_static;
                if kind != 3 {
                    prop_assert_eq!(sweeps, usize::from(changed), "move {}", kind);
                }
            }
        });
    }
}
