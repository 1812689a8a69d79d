//! The separating axis of two boxes: parry's axis, by parry's rule, for less.
//!
//! parry's `sat_cuboid_cuboid` tries 15 axes (three face normals of each box and the nine
//! cross products of their edges) with two quaternion rotations an axis, and a resting pile
//! of 1000 cubes asks it for some 1,600 touching pairs a step. For a touching pair, every
//! axis's separation is found here instead from the columns of the relative rotation (computed
//! as parry computes them) in a few multiplications: `|t·a| − Σ h₁ᵢ|aᵢ| − Σ h₂ⱼ|cⱼ·a|`, within
//! about 1e-15 of the pair's size of parry's. The winner is the first largest in parry's order,
//! turned from box 1 towards box 2 as parry turns it, so the normal is parry's up to rounding,
//! or, where two axes tie within rounding, one that separates the boxes as much by parry's own
//! measure (a test checks both on random pairs). Evaluating the winning axes again with
//! parry's functions, to match its bits, was a twentieth of the 1000-cube pile's collision. A
//! pair separated beyond the prediction along one face normal of a box, and along no other of
//! it, is answered `None` here, as parry would; other pairs separated along some face normal,
//! which parry may answer with a blend of normals, are left to parry unchanged.

use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::sat as parry_sat;
use parry3d_f64::shape::Cuboid;

use crate::apart::{AxisFrame, AxisGap};

/// Relative gap, as a fraction of the pair's size (`|t|₁ + |h₁|₁ + |h₂|₁`), within which a
/// quick separation may differ from parry's: both sum at most seven terms bounded by that size,
/// so each is within about 1e-15 of it; 1e-12 leaves a factor of a thousand.
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
) -> Result<Vector, Option<AxisGap>> {
    let faces = face_separations(box1, box2, pos12);
    match quick_normal(box1, box2, pos12, prediction, &faces) {
        Some(Some(normal)) => Ok(normal),
        Some(None) => Err(face_gap(&faces.0, prediction)),
        None => parry_normal(box1, box2, pos12, prediction)
            .map_err(|edges| face_gap(&faces.0, prediction).or(edges)),
    }
}

/// The face normal of either box separating the pair most, if it does by more than
/// `prediction`. parry answers `None` for any such pair: its face groups report the best face's
/// separation, or one at least as large along a blend of separating faces.
fn face_gap(separations: &[f64; 6], prediction: f64) -> Option<AxisGap> {
    let (best, separation) = (0..6)
        .map(|k| (k, separations[k]))
        .reduce(|best, next| if next.1 > best.1 { next } else { best })?;
    (separation > prediction).then_some(AxisGap {
        separation,
        frame: AxisFrame::of_first(best < 3),
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
/// the first: any axis separating by more than `prediction` settles the answer. Apart, the
/// edge–edge axis's gap when that axis is the one (see [`crate::apart`]).
fn parry_normal(
    box1: &Cuboid,
    box2: &Cuboid,
    pos12: &Pose,
    prediction: f64,
) -> Result<Vector, Option<AxisGap>> {
    let faces1 = parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(box1, box2, pos12);
    if faces1.0 > prediction {
        return Err(None);
    }
    let pos21 = pos12.inverse();
    let faces2 = parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(box2, box1, &pos21);
    if faces2.0 > prediction {
        return Err(None);
    }
    let edges = parry_sat::cuboid_cuboid_find_local_separating_edge_twoway(box1, box2, pos12);
    if edges.0 > prediction {
        return Err(Some(AxisGap {
            separation: edges.0,
            frame: AxisFrame::Space,
        }));
    }
    let best = [faces1, (faces2.0, pos12.rotation * -faces2.1), edges]
        .into_iter()
        .reduce(|best, axis| if axis.0 > best.0 { axis } else { best })
        .filter(|best| best.0 <= prediction)
        .ok_or(None)?;
    Ok(best.1)
}

/// [`parry_normal`]'s answer, from quick separations: for a pair overlapping along all six face
/// normals, the first axis of largest separation (see the module doc); for a pair apart along
/// one face normal of a box and no other of it, `None`. `None` (ask parry) for any other pair,
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
    // The first axis of largest separation, in parry's order, oriented from box 1 to box 2.
    let winner = (0..15).find(|&k| separations[k] == best)?;
    let axis = match winner {
        0..3 => Vector::from_array(std::array::from_fn(|k| f64::from(u8::from(k == winner)))),
        3..6 => c[winner - 3],
        _ => {
            let (l, norm) = edge_axes[winner - 6]?;
            l / norm
        }
    };
    let normal = axis * 1f64.copysign(t.dot(axis));
    Some((best <= prediction).then_some(normal))
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

    #[test]
    fn the_normal_is_parrys_to_the_bit() {
        let mut uniform = uniform_from(2024);
        let (mut quick, mut apart, mut ties, mut edge_gaps) = (0, 0, 0, 0);
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
            assert_eq!(got.is_ok(), expected.is_ok(), "case {case}");
            if let (Ok(got), Ok(expected)) = (got, expected) {
                let along = |axis: Vector| {
                    parry_sat::cuboid_cuboid_compute_separation_wrt_local_line(
                        &box1, &box2, &pos12, axis,
                    )
                };
                let (best, ours) = (along(expected), along(got));
                let size = translation.abs().element_sum() + h1.element_sum() + h2.element_sum();
                assert!(
                    ours.0 >= best.0 - CLOSE * size,
                    "case {case}: {ours:?} {best:?}"
                );
                assert!(ours.1.dot(got) > 0.0, "case {case}: turned towards box 2");
                if got.angle_between(expected) > 1e-12 {
                    ties += 1;
                }
            }
            // Apart, the gap is the widest face normal's when one separates by more than
            // `prediction`, else the edge–edge axis's, fixed in space, when it does.
            let (faces, _) = face_separations(&box1, &box2, &pos12);
            let widest = faces.into_iter().fold(f64::NEG_INFINITY, f64::max);
            let gap = got.err().flatten();
            if widest > prediction {
                assert_eq!(gap.map(|g| g.separation), Some(widest), "case {case}");
                assert_ne!(gap.map(|g| g.frame), Some(AxisFrame::Space), "case {case}");
            } else if let Some(gap) = gap {
                let edges = parry_sat::cuboid_cuboid_find_local_separating_edge_twoway(
                    &box1, &box2, &pos12,
                );
                assert_eq!((gap.separation, gap.frame), (edges.0, AxisFrame::Space));
                assert!(gap.separation > prediction, "case {case}");
                edge_gaps += 1;
            }
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
        // 60 of the 100,000 pairs when this was written.
        assert!(
            edge_gaps >= cases / 5000,
            "{edge_gaps} edge gaps of {cases}"
        );
        // A tie within rounding that the two arithmetics settle differently is rare (none of
        // these pairs, the quarter turns and the hair included, when this was written).
        assert!(
            ties < cases / 100,
            "{ties} of {cases} normals differ from parry's"
        );
    }
}
