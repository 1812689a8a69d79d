//! Broad phase: sort and sweep over bounding boxes along the axis where the boxes spread most.
//!
//! O(n log n + k) for n boxes and k overlapping pairs; the axis choice keeps a vertical tower
//! (all boxes at the same x and y) from degenerating to O(n²).

use nalgebra::Vector3;

/// Appends to `pairs` every `(i, j)`, `i < j`, whose boxes overlap and that are not both static.
pub(crate) fn overlapping_pairs(
    boxes: &[(Vector3<f64>, Vector3<f64>)],
    is_static: &[bool],
    order: &mut Vec<usize>,
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
    order.clear();
    order.extend(0..boxes.len());
    order.sort_by(|&i, &j| boxes[i].0[axis].total_cmp(&boxes[j].0[axis]));
    for (k, &i) in order.iter().enumerate() {
        let (lo_i, hi_i) = &boxes[i];
        for &j in &order[k + 1..] {
            let (lo_j, hi_j) = &boxes[j];
            if lo_j[axis] > hi_i[axis] {
                break;
            }
            if is_static[i] && is_static[j] {
                continue;
            }
            let overlap = (0..3).all(|d| lo_i[d] <= hi_j[d] && lo_j[d] <= hi_i[d]);
            if overlap {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    pairs.sort_unstable();
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
        let (mut order, mut pairs) = (Vec::new(), Vec::new());
        overlapping_pairs(&boxes, &is_static, &mut order, &mut pairs);
        let expected = brute_force(&boxes, &is_static);
        assert!(!expected.is_empty());
        assert_eq!(pairs, expected);
    }
}
