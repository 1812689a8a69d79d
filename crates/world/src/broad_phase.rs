//! Broad phase: sort and sweep over bounding boxes along the axis where the boxes spread most.
//!
//! O(n log n + k) for n boxes and k overlapping pairs; the axis choice keeps a vertical tower
//! (all boxes at the same x and y) from degenerating to O(n²). The order is kept from step to
//! step, so the sort starts from an almost sorted list, and the sweep runs over the boxes copied
//! in that order, so its inner loop reads memory in sequence.

use nalgebra::Vector3;

/// A box as the sweep reads it: its bounds, whether its body is static, and its index.
#[derive(Debug, Clone, Copy)]
struct Swept {
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    is_static: bool,
    index: usize,
}

/// The broad phase's state between steps: the boxes' order along the sweep axis, and scratch.
#[derive(Debug, Default, Clone)]
pub(crate) struct SweepAndPrune {
    order: Vec<usize>,
    swept: Vec<Swept>,
}

impl SweepAndPrune {
    /// Writes to `pairs` every `(i, j)`, `i < j`, whose boxes overlap and that are not both
    /// static, in increasing order.
    pub(crate) fn overlapping_pairs(
        &mut self,
        boxes: &[(Vector3<f64>, Vector3<f64>)],
        is_static: &[bool],
        pairs: &mut Vec<(usize, usize)>,
    ) {
        pairs.clear();
        let n = boxes.len() as f64;
        let centre = |(lo, hi): &(Vector3<f64>, Vector3<f64>)| (lo + hi) / 2.0;
        let mean = boxes.iter().map(centre).sum::<Vector3<f64>>() / n.max(1.0);
        let spread = boxes
            .iter()
            .map(|b| (centre(b) - mean).map(|x| x * x))
            .sum::<Vector3<f64>>();
        let axis = spread.imax();
        // Last step's order is a permutation of the same indices unless bodies were added or
        // removed; the pairs found do not depend on how ties are ordered.
        if self.order.len() != boxes.len() {
            self.order.clear();
            self.order.extend(0..boxes.len());
        }
        self.order
            .sort_by(|&i, &j| boxes[i].0[axis].total_cmp(&boxes[j].0[axis]));
        self.swept.clear();
        self.swept.extend(self.order.iter().map(|&index| Swept {
            lo: boxes[index].0,
            hi: boxes[index].1,
            is_static: is_static[index],
            index,
        }));
        for (k, a) in self.swept.iter().enumerate() {
            for b in &self.swept[k + 1..] {
                if b.lo[axis] > a.hi[axis] {
                    break;
                }
                if a.is_static && b.is_static {
                    continue;
                }
                let overlap = (0..3).all(|d| a.lo[d] <= b.hi[d] && b.lo[d] <= a.hi[d]);
                if overlap {
                    pairs.push((a.index.min(b.index), a.index.max(b.index)));
                }
            }
        }
        pairs.sort_unstable();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every overlapping pair, by checking all of them.
    fn brute_force(
        boxes: &[(Vector3<f64>, Vector3<f64>)],
        is_static: &[bool],
    ) -> Vec<(usize, usize)> {
        let mut pairs = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
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
}
