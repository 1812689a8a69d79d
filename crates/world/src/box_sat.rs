//! The separating axis of two boxes: parry's answer, to the bit, for less.
//!
//! parry's `sat_cuboid_cuboid` tries 15 axes (three face normals of each box and the nine
//! cross products of their edges) with two quaternion rotations an axis, and a resting pile
//! of 1000 cubes asks it for some 1,600 touching pairs a step. For a touching pair, every
//! axis's separation is found here first from the columns of the relative rotation (computed
//! as parry computes them) in a few multiplications: `|t·a| − Σ h₁ᵢ|aᵢ| − Σ h₂ⱼ|cⱼ·a|`. Only
//! the axes within [`CLOSE`] of the best are then evaluated with parry's own functions, and the
//! winner is picked in parry's order with parry's tie rule, so the normal and every trajectory
//! are the same as with parry alone (a test checks it bit for bit on random pairs). A pair
//! separated beyond the prediction along one face normal of a box, and along no other of it, is
//! answered `None` here, as parry would; other pairs separated along some face normal, which
//! parry may answer with a blend of normals, are left to parry unchanged.

use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::sat as parry_sat;
use parry3d_f64::shape::Cuboid;

use crate::apart::FaceGap;

/// Relative gap, as a fraction of the pair's size (`|t|₁ + |h₁|₁ + |h₂|₁`), within which two
/// axes' quick separations count as a tie to be settled by parry's exact arithmetic. Both
/// evaluations sum at most seven terms bounded by that size, so each is within about 1e-15 of
/// it: 1e-12 leaves a factor of a thousand.
const CLOSE: f64 = 1e-12;

/// The separating axis of two boxes (in box 1's frame, pointing out of box 1) that parry's SAT
/// finds: the face normals of either box and the edge–edge axes, the one of largest
/// separation, without building the manifold's contact points, which [`crate::support`]
/// replaces with the full support polygon. Beyond `prediction`, an error with the face normal
/// that separates the boxes most when one does by more than `prediction` (see [`crate::apart`]).
pub(crate) fn cuboid_normal(
    box1: &Cuboid,
    box2: &Cuboid,
    pos12: &Pose,
    prediction: f64,
) -> Result<Vector, Option<FaceGap>> {
    let faces = face_separations(box1, box2, pos12);
    quick_normal(box1, box2, pos12, prediction, &faces)
        .unwrap_or_else(|| parry_normal(box1, box2, pos12, prediction))
        .ok_or_else(|| face_gap(&faces.0, prediction))
}

/// The face normal of either box separating the pair most, if it does by more than
/// `prediction`. parry answers `None` for any such pair: its face groups report the best face's
/// separation, or one at least as large along a blend of separating faces.
fn face_gap(separations: &[f64; 6], prediction: f64) -> Option<FaceGap> {
    let (best, separation) = (0..6)
        .map(|k| (k, separations[k]))
        .reduce(|best, next| if next.1 > best.1 { next } else { best })?;
    (separation > prediction).then_some(FaceGap {
        separation,
        on_first: best < 3,
    })
}

/// The separations along box 1's face normals, then box 2's, from the columns of the relative
/// rotation; with those columns (box 2's axes in box 1's frame, as parry's edge test computes
/// them).
fn face_separations(box1: &Cuboid, box2: &Cuboid, pos12: &Pose) -> ([f64; 6], [Vector; 3]) {
    let (h1, h2, t) = (box1.half_extents, box2.half_extents, pos12.translation);
    let c = [
        pos12.rotation * Vector::X,
        pos12.rotation * Vector::Y,
        pos12.rotation * Vector::Z,
    ];
    let reach1 = |a: Vector| h1.dot(a.abs());
    let reach2 = |a: Vector| box2_reach(h2, &c, a);
    let mut separations = [0.0; 6];
    for i in 0..3 {
        let axis = Vector::from_array(std::array::from_fn(|k| f64::from(u8::from(k == i))));
        separations[i] = t.dot(axis).abs() - h1[i] - reach2(axis);
        separations[3 + i] = t.dot(c[i]).abs() - reach1(c[i]) - h2[i];
    }
    (separations, c)
}

/// parry's three calls, in the order that lets most pairs whose bounding boxes overlap stop at
/// the first: any axis separating by more than `prediction` settles the answer.
fn parry_normal(box1: &Cuboid, box2: &Cuboid, pos12: &Pose, prediction: f64) -> Option<Vector> {
    let faces1 = parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(box1, box2, pos12);
    if faces1.0 > prediction {
        return None;
    }
    let pos21 = pos12.inverse();
    let faces2 = parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(box2, box1, &pos21);
    if faces2.0 > prediction {
        return None;
    }
    let edges = parry_sat::cuboid_cuboid_find_local_separating_edge_twoway(box1, box2, pos12);
    let best = [faces1, (faces2.0, pos12.rotation * -faces2.1), edges]
        .into_iter()
        .reduce(|best, axis| if axis.0 > best.0 { axis } else { best })?;
    (best.0 <= prediction).then_some(best.1)
}

/// [`parry_normal`]'s answer, from quick separations: for a pair overlapping along all six face
/// normals, with parry's arithmetic on the close axes only; for a pair apart along one face
/// normal of a box and no other of it, `None`. `None` (ask parry) for any other pair,
/// non-finite input included. `faces` is [`face_separations`]'s answer for the pair.
fn quick_normal(
    box1: &Cuboid,
    box2: &Cuboid,
    pos12: &Pose,
    prediction: f64,
    (faces, c): &([f64; 6], [Vector; 3]),
) -> Option<Option<Vector>> {
    let (h1, h2, t) = (box1.half_extents, box2.half_extents, pos12.translation);
    let reach1 = |a: Vector| h1.dot(a.abs());
    let reach2 = |a: Vector| box2_reach(h2, c, a);
    let close = CLOSE * (t.abs().element_sum() + h1.element_sum() + h2.element_sum());
    // parry's order: box 1's faces, box 2's faces, then the edge pairs.
    let mut separations = [f64::NEG_INFINITY; 15];
    separations[..6].copy_from_slice(faces);
    // Apart: parry answers `None` as soon as one box's face normals separate the pair by more
    // than `prediction` — without a blend, which it makes of two or more normals separating
    // by zero or more, so a box with one at most that might is decided here.
    let apart = |faces: &[f64]| {
        faces.iter().filter(|&&s| s >= -close).count() <= 1
            && faces.iter().any(|&s| s > prediction + close)
    };
    if apart(&separations[..3]) || apart(&separations[3..6]) {
        return Some(None);
    }
    // Overlapping along every face normal (so parry neither stops early nor blends), by more
    // than the rounding: else parry decides.
    if !separations[..6].iter().all(|&s| s < -close) {
        return None;
    }
    // Edge pairs: the separation along the unnormalised axis L, divided once by |L|. Every
    // term is a product with L's own components, so its rounding shrinks with |L| and the
    // division leaves it within `close` even for nearly parallel edges (|L| down to 1e-16); the
    // shortcut cₖ · L = ±(box 2's third axis)ᵢ would not, its error from the rotation's
    // orthonormality being divided by |L|.
    let edge_axes = edge_axes(c);
    for (k, axis) in edge_axes.iter().enumerate() {
        if let Some((l, norm)) = *axis {
            separations[6 + k] = (t.dot(l).abs() - reach1(l) - reach2(l)) / norm;
        }
    }
    let best = separations
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    if !best.is_finite() {
        return None;
    }
    let near = |k: usize| separations[k] >= best - close;
    // The close axes with parry's separations, in parry's order; a face group is evaluated
    // whole, as parry returns its best.
    let mut candidates: [Option<(f64, Vector)>; 11] = [None; 11];
    if (0..3).any(near) {
        candidates[0] =
            Some(parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(box1, box2, pos12));
    }
    if (3..6).any(near) {
        let faces2 = parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(
            box2,
            box1,
            &pos12.inverse(),
        );
        candidates[1] = Some((faces2.0, pos12.rotation * -faces2.1));
    }
    for (k, axis) in edge_axes.iter().enumerate() {
        if let Some((l, norm)) = *axis
            && near(6 + k)
        {
            candidates[2 + k] = Some(parry_sat::cuboid_cuboid_compute_separation_wrt_local_line(
                box1,
                box2,
                pos12,
                l / norm,
            ));
        }
    }
    let winner = candidates
        .into_iter()
        .flatten()
        .reduce(|best, axis| if axis.0 > best.0 { axis } else { best })?;
    Some((winner.0 <= prediction).then_some(winner.1))
}

/// How far box 2 (half extents `h2`, axes `c` in box 1's frame) reaches along axis `a` from its
/// centre.
fn box2_reach(h2: Vector, c: &[Vector; 3], a: Vector) -> f64 {
    h2.x * c[0].dot(a).abs() + h2.y * c[1].dot(a).abs() + h2.z * c[2].dot(a).abs()
}

/// The nine edge–edge axes of parry's test (box 1's axes crossed with box 2's, `c`), in its
/// order, each with its length; `None` where parry skips one (parallel edges).
fn edge_axes(c: &[Vector; 3]) -> [Option<(Vector, f64)>; 9] {
    let mut axes = [None; 9];
    for (j, cj) in c.iter().enumerate() {
        let crossed = [
            Vector::new(0.0, -cj.z, cj.y),
            Vector::new(cj.z, 0.0, -cj.x),
            Vector::new(-cj.y, cj.x, 0.0),
        ];
        for (i, axis) in crossed.into_iter().enumerate() {
            let norm = axis.length();
            if norm > f64::EPSILON {
                axes[3 * j + i] = Some((axis, norm));
            }
        }
    }
    axes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parry_bridge::tests::uniform_from;
    use parry3d_f64::math::Rotation;

    fn bits(normal: Option<Vector>) -> Option<[u64; 3]> {
        normal.map(|v| v.to_array().map(f64::to_bits))
    }

    /// Random box pairs of 1 cm to 10 m, turned at random, by a few exact quarter turns, by
    /// nothing, or by a hair (1e-9 rad, where face axes tie within rounding), placed from deep
    /// overlap to just beyond the prediction: the quick test gives parry's normal to the bit,
    /// and settles most overlapping pairs, and many pairs apart, itself.
    #[test]
    fn the_normal_is_parrys_to_the_bit() {
        let mut uniform = uniform_from(2024);
        let (mut quick, mut apart) = (0, 0);
        let cases = 100_000;
        for case in 0..cases {
            let scale = [0.01, 0.1, 1.0, 10.0][case % 4];
            let mut half = || Vector::new(uniform(), uniform(), uniform()) * scale + scale * 0.1;
            let (h1, h2) = (half(), half());
            let axis = Vector::new(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalize();
            let rotation = match case % 5 {
                0 => Rotation::IDENTITY,
                1 => Rotation::from_axis_angle(Vector::Z, std::f64::consts::FRAC_PI_2),
                2 => Rotation::from_axis_angle(axis, 1e-9),
                _ => Rotation::from_axis_angle(axis, uniform() * std::f64::consts::TAU),
            };
            // From the centres' coinciding to a gap of about a tenth of the boxes' size.
            let reach = (h1 + h2).length();
            let direction =
                Vector::new(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalize();
            let translation = direction * reach * uniform() * 1.1;
            let pos12 = Pose::from_parts(translation, rotation);
            let (box1, box2) = (Cuboid::new(h1), Cuboid::new(h2));
            let prediction = 0.005 * scale;
            let expected = parry_normal(&box1, &box2, &pos12, prediction);
            let got = cuboid_normal(&box1, &box2, &pos12, prediction);
            assert_eq!(bits(got.ok()), bits(expected), "case {case}");
            // A gap is reported exactly when a face normal separates by more than `prediction`.
            let (faces, _) = face_separations(&box1, &box2, &pos12);
            let widest = faces.into_iter().fold(f64::NEG_INFINITY, f64::max);
            let gap = got.err().flatten();
            assert_eq!(
                gap.map(|g| g.separation),
                (widest > prediction).then_some(widest)
            );
            let faces = face_separations(&box1, &box2, &pos12);
            match quick_normal(&box1, &box2, &pos12, prediction, &faces) {
                Some(Some(_)) => quick += 1,
                Some(None) => apart += 1,
                None => {}
            }
        }
        assert!(
            quick > cases / 4,
            "the quick test found {quick} normals of {cases}"
        );
        assert!(
            apart > cases / 20,
            "the quick test found {apart} pairs apart of {cases}"
        );
    }
}
