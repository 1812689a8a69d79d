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
//! parry's functions, to match its bits, was a twentieth of the 1000-cube pile's collision.
//!
//! Parry is asked only where it blends a box's face normals (two or more of them separating
//! the pair by zero or more), where a separation is within rounding of zero or of the
//! prediction, or where two axes tie within rounding. A pair some face normal separates beyond
//! the prediction is answered apart here with the widest face normal's gap, which is what
//! asking parry first gave: it answers every such pair apart, and its gap gave way to that
//! face's. A pair at most one of each box's normals separates, by less than the prediction
//! (bodies closing within the step, or resting just apart within the margin), takes parry's
//! axis as found here, to the bit, or, apart along an edge pair, the gap of parry's edge test
//! alone (its face tests cannot stop it first). These pairs took 3.8% of the 1000-cube pile's
//! collision instructions over its first 2.75 s (the cubes falling and landing) in parry's
//! whole test; the answers are the same bits.
//!
//! A pair apart always comes with its gap: the axis that showed it and the separation along it
//! ([`crate::apart`] keeps the pair apart by it, untested, while its bodies could not have
//! closed it). That is a face normal, parry's blend of one box's face normals (it measures the
//! true boxes along the blend, so the blend is an axis fixed in that box), or an edge–edge axis,
//! fixed in space. A pair apart with no gap was tested afresh every step: some 185 pairs of a
//! resting pile of 1000 cubes, apart along an edge–edge axis alone.

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
/// replaces with the full support polygon. Beyond `prediction`, an error with the gap that shows
/// it (the module doc; `None` only for non-finite input): the face normal that separates the
/// boxes most when one does by more than `prediction`.
pub(crate) fn cuboid_normal(
    box1: &Cuboid,
    box2: &Cuboid,
    pos12: &Pose,
    prediction: f64,
) -> Result<Vector, Option<AxisGap>> {
    let faces = face_separations(box1, box2, pos12);
    quick_normal(box1, box2, pos12, prediction, &faces).unwrap_or_else(|| {
        parry_normal(box1, box2, pos12, prediction)
            .map_err(|gap| face_gap(&faces.0, prediction).or(gap))
    })
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
/// the first: any axis separating by more than `prediction` settles the answer. Apart, the gap
/// along the axis that showed it (see [`crate::apart`]): a box's face normal or parry's blend of
/// its face normals, fixed in that box, or the edge–edge axis, fixed in space.
fn parry_normal(
    box1: &Cuboid,
    box2: &Cuboid,
    pos12: &Pose,
    prediction: f64,
) -> Result<Vector, Option<AxisGap>> {
    let faces1 = parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(box1, box2, pos12);
    // parry measures a blend of box 1's normals as it measures a normal: the true shapes'
    // support points along it, so its separation is a gap along an axis fixed in box 1.
    if faces1.0 > prediction {
        return Err(Some(AxisGap {
            separation: faces1.0,
            frame: AxisFrame::First,
        }));
    }
    let pos21 = pos12.inverse();
    let faces2 = parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(box2, box1, &pos21);
    if faces2.0 > prediction {
        return Err(Some(AxisGap {
            separation: faces2.0,
            frame: AxisFrame::Second,
        }));
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

/// [`cuboid_normal`]'s answer, from quick separations: for a pair some face normal separates by
/// more than `prediction` (beyond the rounding), the widest face normal's gap; for a pair at
/// most one of each box's face normals separates by zero or more, none by about `prediction`
/// (so parry blends none), the first axis of largest separation (see the module doc), or, when
/// that separates the pair by more than `prediction`, its gap (an edge–edge axis, fixed in
/// space). `None` (ask parry) for any other pair, non-finite input included. `faces` is
/// [`face_separations`]'s answer for the pair.
fn quick_normal(
    box1: &Cuboid,
    box2: &Cuboid,
    pos12: &Pose,
    prediction: f64,
    (faces, c): &([f64; 6], [Vector; 3]),
) -> Option<Result<Vector, Option<AxisGap>>> {
    let (h1, h2, t) = (box1.half_extents, box2.half_extents, pos12.translation);
    let reach1 = |a: Vector| h1.dot(a.abs());
    let reach2 = |a: Vector| box2_reach(h2, c, a);
    let close = CLOSE * (t.abs().element_sum() + h1.element_sum() + h2.element_sum());
    // parry's order: box 1's faces, box 2's faces, then the edge pairs.
    let mut separations = [f64::NEG_INFINITY; 15];
    separations[..6].copy_from_slice(faces);
    // Apart: parry answers `None` as soon as one box's face normals (or its blend of them,
    // which separates at least as much) separate the pair by more than `prediction`, and
    // `cuboid_normal` then gives the widest face normal's gap; beyond the rounding, that is
    // decided here.
    if faces.iter().any(|&s| s > prediction + close) {
        return Some(Err(face_gap(faces, prediction)));
    }
    // Parry blends a box's normals when two or more of them separate by zero or more: with at
    // most one of each box's past overlapping by the rounding, it takes no blend, and with none
    // about `prediction` it does not stop early either. Else parry decides.
    let overlapping = faces.iter().all(|&s| s < -close);
    let unblended = |faces: &[f64]| faces.iter().filter(|&&s| s >= -close).count() <= 1;
    let near_prediction = faces.iter().any(|&s| (s - prediction).abs() <= close);
    // A NaN separation counts in none of these tests: parry decides, as it did before.
    let finite = faces.iter().all(|s| s.is_finite());
    if !(finite && unblended(&faces[..3]) && unblended(&faces[3..])) || near_prediction {
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
    // A pair some face normal may separate gets parry's own bits: apart along an edge pair,
    // the gap parry's edge test measures (its face tests cannot stop it first); else the
    // normal found here where no other axis comes within rounding of it, and parry's choice
    // where one does. (Overlapping pairs keep the answer they have always had here, ties
    // within rounding settled by this arithmetic.)
    if !overlapping {
        if best > prediction + close {
            let edges =
                parry_sat::cuboid_cuboid_find_local_separating_edge_twoway(box1, box2, pos12);
            return Some(Err(Some(AxisGap {
                separation: edges.0,
                frame: AxisFrame::Space,
            })));
        }
        let tied = (0..15).any(|k| k != winner && separations[k] >= best - close);
        if best > prediction || tied {
            return None;
        }
    }
    if best > prediction {
        // No face normal separates by `prediction`, so the axis is an edge pair's: the
        // separation along it, as it is now, bounds the distance (see [`crate::apart`]).
        // Without it, a resting pile of 1000 cubes tested some 185 such pairs afresh every step.
        return Some(Err(Some(AxisGap {
            separation: best,
            frame: AxisFrame::Space,
        })));
    }
    Some(Ok(axis * 1f64.copysign(t.dot(axis))))
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

    /// Case `case`'s size scale (1 cm to 10 m, in turn), two boxes' half extents at that scale
    /// and a random unit axis.
    fn random_boxes(
        uniform: &mut impl FnMut() -> f64,
        case: usize,
    ) -> (f64, Vector, Vector, Vector) {
        let scale = [0.01, 0.1, 1.0, 10.0][case % 4];
        let mut half = || Vector::new(uniform(), uniform(), uniform()) * scale + scale * 0.1;
        let (h1, h2) = (half(), half());
        let axis = Vector::new(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalize();
        (scale, h1, h2, axis)
    }

    #[test]
    fn the_normal_is_parrys_to_the_bit() {
        let mut uniform = uniform_from(2024);
        let (mut quick, mut apart, mut ties, mut edge_gaps) = (0, 0, 0, 0);
        let mut blended = 0;
        let cases = 100_000;
        for case in 0..cases {
            let (scale, h1, h2, axis) = random_boxes(&mut uniform, case);
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
            // Apart, always with a gap beyond `prediction` that the boxes' distance is at least
            // (parry's distance query; within the quick test's rounding): the widest face
            // normal's when one separates by more than `prediction`, else parry's blend of one
            // box's normals, fixed in that box, or an edge–edge axis, fixed in space.
            if let Err(gap) = got {
                let gap = gap.unwrap_or_else(|| panic!("case {case}: apart without a gap"));
                let size = translation.abs().element_sum() + h1.element_sum() + h2.element_sum();
                assert!(gap.separation > prediction, "case {case}");
                let distance = parry3d_f64::query::distance(&Pose::IDENTITY, &box1, &pos12, &box2)
                    .expect("boxes")
                    .distance;
                assert!(
                    gap.separation <= distance + CLOSE * size,
                    "case {case}: gap {gap:?} past the distance {distance}"
                );
                let (faces, _) = face_separations(&box1, &box2, &pos12);
                let widest = faces.into_iter().fold(f64::NEG_INFINITY, f64::max);
                if widest > prediction {
                    assert_eq!(gap.separation, widest, "case {case}");
                    assert_ne!(gap.frame, AxisFrame::Space, "case {case}");
                } else if gap.frame == AxisFrame::Space {
                    let edges = parry_sat::cuboid_cuboid_find_local_separating_edge_twoway(
                        &box1, &box2, &pos12,
                    );
                    assert!(
                        (gap.separation - edges.0).abs() <= CLOSE * size,
                        "case {case}: {gap:?} against parry's {edges:?}"
                    );
                    edge_gaps += 1;
                } else {
                    let faces = match gap.frame {
                        AxisFrame::First => {
                            parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(
                                &box1, &box2, &pos12,
                            )
                        }
                        _ => parry_sat::cuboid_cuboid_find_local_separating_normal_oneway(
                            &box2,
                            &box1,
                            &pos12.inverse(),
                        ),
                    };
                    assert_eq!(gap.separation, faces.0, "case {case}: parry's blend");
                }
            }
            let faces = face_separations(&box1, &box2, &pos12);
            match quick_normal(&box1, &box2, &pos12, prediction, &faces) {
                Some(Ok(_)) => quick += 1,
                // An edge–edge gap: for a pair overlapping along every face normal the quick
                // test's own (within `CLOSE` of parry's, above), else parry's edge test's.
                Some(Err(Some(AxisGap {
                    frame: AxisFrame::Space,
                    ..
                }))) => apart += 1,
                Some(Err(gap)) => {
                    apart += 1;
                    // Apart along a face normal without asking parry: what asking it first
                    // gives, to the bit.
                    let asked = parry_normal(&box1, &box2, &pos12, prediction)
                        .map_err(|parrys| face_gap(&faces.0, prediction).or(parrys));
                    assert_eq!(Err(gap), asked, "case {case}");
                    let separating =
                        |normals: &[f64]| normals.iter().filter(|&&s| s >= 0.0).count() > 1;
                    if separating(&faces.0[..3]) || separating(&faces.0[3..]) {
                        blended += 1;
                    }
                }
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
        // Pairs two or more of a box's normals separate, which parry blends: apart here too
        // (7,185 of the 100,000 when this was written).
        assert!(
            blended > cases / 100,
            "{blended} pairs apart along two normals of a box of {cases}"
        );
        // 1,016 of the 100,000 pairs when this was written (60 before the quick test kept its
        // edge axes' gaps).
        assert!(edge_gaps >= cases / 500, "{edge_gaps} edge gaps of {cases}");
        // A tie within rounding that the two arithmetics settle differently is rare (none of
        // these pairs, the quarter turns and the hair included, when this was written).
        assert!(
            ties < cases / 100,
            "{ties} of {cases} normals differ from parry's"
        );
    }

    /// Boxes turned anyhow, box 2 set against a face of box 1 with a gap from an overlap of the
    /// prediction to twice the prediction (bodies closing within the step, or resting within
    /// the margin): where the quick test answers, it answers as parry does, to the bit,
    /// wherever no other axis ties the winner within rounding.
    #[test]
    fn boxes_about_to_touch_get_parrys_answer_to_the_bit() {
        let mut uniform = uniform_from(77);
        let (mut answered, mut ties) = (0, 0);
        let cases = 20_000;
        for case in 0..cases {
            let (scale, h1, h2, axis) = random_boxes(&mut uniform, case);
            let rotation = Rotation::from_axis_angle(axis, uniform() * std::f64::consts::TAU);
            let c = [
                rotation * Vector::X,
                rotation * Vector::Y,
                rotation * Vector::Z,
            ];
            let face = case % 3;
            let normal =
                Vector::from_array(std::array::from_fn(|k| f64::from(u8::from(k == face))))
                    * if case % 2 == 0 { 1.0 } else { -1.0 };
            let prediction = 0.005 * scale;
            let gap = prediction * (3.0 * uniform() - 1.0);
            // Box 2's nearest point along the face's normal that far beyond it, anywhere over it.
            let lateral = Vector::from_array(std::array::from_fn(|k| {
                if k == face {
                    0.0
                } else {
                    (2.0 * uniform() - 1.0) * h1[k]
                }
            }));
            let translation = normal * (h1[face] + box2_reach(h2, &c, normal) + gap) + lateral;
            let pos12 = Pose::from_parts(translation, rotation);
            let (box1, box2) = (Cuboid::new(h1), Cuboid::new(h2));
            let close =
                CLOSE * (translation.abs().element_sum() + h1.element_sum() + h2.element_sum());
            let faces = face_separations(&box1, &box2, &pos12);
            let Some(quick) = quick_normal(&box1, &box2, &pos12, prediction, &faces) else {
                continue;
            };
            answered += 1;
            let parrys = parry_normal(&box1, &box2, &pos12, prediction)
                .map_err(|parrys| face_gap(&faces.0, prediction).or(parrys));
            match (quick, parrys) {
                (Ok(ours), Ok(theirs)) if ours != theirs => {
                    // A tie: parry's axis separates the pair as much, within rounding.
                    let along = |axis: Vector| {
                        parry_sat::cuboid_cuboid_compute_separation_wrt_local_line(
                            &box1, &box2, &pos12, axis,
                        )
                        .0
                    };
                    assert!(
                        (along(ours) - along(theirs)).abs() <= close,
                        "case {case}: {ours:?} against parry's {theirs:?}"
                    );
                    ties += 1;
                }
                // Overlapping along every face normal: the quick test's own edge gap, within
                // rounding of parry's, as in `the_normal_is_parrys_to_the_bit`.
                (Err(Some(ours)), Err(Some(theirs))) if faces.0.iter().all(|&s| s < -close) => {
                    assert_eq!(
                        (ours.frame, theirs.frame),
                        (AxisFrame::Space, AxisFrame::Space)
                    );
                    assert!(
                        (ours.separation - theirs.separation).abs() <= close,
                        "case {case}"
                    );
                }
                (ours, theirs) => assert_eq!(ours, theirs, "case {case}"),
            }
        }
        assert!(answered > cases / 2, "answered {answered} of {cases}");
        assert!(ties < cases / 100, "{ties} ties of {cases}");
    }

    /// Two unit cubes side by side, the second moved 4 mm past the first's edge along x and
    /// along y: each face normal separates them by 4 mm, within a prediction of 5 mm, but they
    /// are 4√2 mm apart, as parry's blend of the first's two normals shows. Without its gap
    /// the pair was apart with nothing to keep it so, and was tested afresh every step.
    #[test]
    fn a_box_past_another_ones_edge_is_apart_along_parrys_blend() {
        let unit = Cuboid::new(Vector::splat(0.5));
        let gap = 0.004;
        let pos12 = Pose::from_translation(Vector::new(1.0 + gap, 1.0 + gap, 0.3));
        let prediction = 0.005;
        let (faces, _) = face_separations(&unit, &unit, &pos12);
        assert!(faces.iter().all(|&s| s <= prediction), "{faces:?}");
        let gap_found = cuboid_normal(&unit, &unit, &pos12, prediction)
            .expect_err("apart")
            .expect("with a gap");
        assert_eq!(gap_found.frame, AxisFrame::First);
        assert!(
            (gap_found.separation - gap * std::f64::consts::SQRT_2).abs() < 1e-15,
            "{gap_found:?}"
        );
    }
}
