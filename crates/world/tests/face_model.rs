//! The three contact models (vertex, patch, face) against closed-form rigid-body physics, and
//! every solved face wrench against the face model's constraint set.

mod common;

use common::{DT, G, SIDE, cube, floor, rotation, run};
use nalgebra::{Matrix3, Point3, Vector3};
use tatami_contact::face::FaceProjection;
use tatami_contact::{BEARING_DEPTH, BEARING_DEPTH_PER_WIDTH, ContactProjection};
use tatami_world::{
    BodyDesc, ContactModel, PgsParams, Shape, Solver, WarmStart, World, WorldSettings,
};

/// Checks every face block of the last step: `f3 ≥ 0`, friction and twist (about the centre of
/// pressure) within their bounds, the centre of pressure inside the support polygon (to 1e-9 of
/// its size).
fn assert_face_wrenches(world: &World) {
    let problem = world.problem();
    for block in &problem.blocks {
        let ContactProjection::Face(face) = &block.projection else {
            continue;
        };
        let l: Vec<f64> = problem.rows[block.rows.clone()]
            .iter()
            .map(|r| r.impulse)
            .collect();
        let f3 = l[0];
        let slack = 1e-12 * (1.0 + f3);
        assert!(f3 >= 0.0, "f3 = {f3}");
        assert!(l[1].abs() <= face.friction * f3 + slack, "friction {l:?}");
        assert!(l[2].abs() <= face.friction * f3 + slack, "friction {l:?}");
        assert!(
            (l[5] - face.twist_midpoint(&l)).abs() <= face.twist_per_normal * f3 + slack,
            "twist {l:?}"
        );
        match FaceProjection::centre_of_pressure(&l) {
            Some(p) => {
                let absolute = face.centre + p.coords;
                let nearest = face.support.nearest_point(&absolute);
                let (lo, hi) = face.support.bounding_box();
                let size = (hi - lo).norm().max(1.0);
                assert!(
                    (nearest - absolute).norm() <= 1e-9 * size,
                    "ZMP {absolute} outside the support polygon {:?}",
                    face.support.vertices()
                );
            }
            None => assert!(
                l[3] == 0.0 && l[4] == 0.0 && l[5] == 0.0,
                "torque without f3"
            ),
        }
    }
}

fn world(model: ContactModel, bodies: Vec<BodyDesc>) -> World {
    bodies
        .into_iter()
        .fold(World::builder().model(model), |b, body| b.body(body))
        .build()
        .unwrap()
}

#[test]
fn a_cube_resting_flat_does_not_rock() {
    for model in ContactModel::ALL {
        let mut w = world(model, vec![floor(), cube("cube", [0.0, 0.0, SIDE / 2.0])]);
        run(&mut w, 1.0, assert_face_wrenches);
        let spin = w.bodies()[1].angular_velocity().norm();
        println!("{}: |ω| after 1 s = {spin:e} rad/s", model.name());
        if model == ContactModel::Face {
            assert!(spin < 1e-9, "face model rocks: |ω| = {spin}");
        }
    }
}

/// A cube left on one edge, tilted by less than the feature angle, falls flat under every model
/// (it used to stay tilted for ever under the face model, whose block held the whole face's
/// turn with the far edge up to 3.3 cm off the floor). Tilted about a horizontal axis 30° off
/// the floor's axes. At rest after 3 s, it lies flat within the face model's bearing depth:
/// the face holds a tilt whose depths differ by less than [`BEARING_DEPTH`] across it, and its
/// polygon is found at the start of the last step, so twice that over the side. Before, the
/// face model left each tilt as it was.
#[test]
fn a_cube_left_tilted_on_an_edge_falls_flat() {
    let bound = (2.0 * BEARING_DEPTH / SIDE).asin();
    for model in ContactModel::ALL {
        for degrees in [0.3f64, 0.6, 0.95] {
            let tilt = degrees.to_radians();
            let axis = [30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0];
            let half = SIDE / 2.0;
            let centre = [0.0, 0.0, half * (tilt.cos() + tilt.sin())];
            let cube = cube("cube", centre).rotation(rotation(axis, degrees));
            let mut w = world(model, vec![floor(), cube]);
            run(&mut w, 3.0, assert_face_wrenches);
            let body = &w.bodies()[1];
            let up = body.rotation() * Vector3::z();
            let left = up.z.min(1.0).acos();
            assert!(
                left < bound,
                "{}: {degrees}° left {:.4}° (bound {:.4}°)",
                model.name(),
                left.to_degrees(),
                bound.to_degrees()
            );
            // At rest: turning by less than 1e-6 rad a step (the patch model's last wobble
            // takes longest to die out: 2e-6 rad/s at 3 s).
            let spin = body.angular_velocity().norm();
            assert!(
                spin < 1e-4,
                "{}: {degrees}°: |ω| = {spin} rad/s",
                model.name()
            );
        }
    }
}

/// A cube tilted within the feature angle with its low edge pressed into the floor beyond the
/// slop, as a landing leaves it, tips flat as one left on its edge does: about its edge under
/// its weight, in `√(2θ/α)` with `α = 3g / (4 × side)`, 0.1 s from 0.95° for the 2 m cube. The
/// face model keeps a support's whole polygon only while all of it is pressed in beyond the
/// slop (an overlap being pushed out over all of it); before, it kept it while the deepest
/// point was, and the position pass, which removes a tenth of the depth beyond the slop a step,
/// brings that point to the slop from above and never past it: the cube stood at its tilt, its
/// far edge up to 3.3 cm off the floor, turned flat over seconds by the pass alone (a 1 m cube
/// dropped 0.8° off flat: 0.67° after 3 s, flat after 10). Tilted about a horizontal axis 30°
/// off the floor's axes, so it stands on its lowest corner, pressed in 3 or 10 mm. Bounds: flat
/// within the bearing depth, as above, 0.5 s after the start (five times the closed form's
/// time, for the landing to settle); no corner deeper than the pressed one was (the landing
/// blocks let the far corners down to the support's deepest level and no further; 0.1 mm for
/// the sweeps' residual); at rest after 2 s.
#[test]
fn a_cube_tilted_and_pressed_in_falls_flat() {
    let bound = (2.0 * BEARING_DEPTH / SIDE).asin();
    for depth in [0.003, 0.01] {
        for degrees in [0.3f64, 0.6, 0.95] {
            let axis = [30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0];
            let turn = rotation(axis, degrees);
            // Turned off the cube's axes, it stands on its lowest corner: that one `depth` in.
            let lowest = (0..8)
                .map(|k| {
                    let corner = Vector3::from_fn(|i, _| if k >> i & 1 == 1 { 0.5 } else { -0.5 });
                    (turn * corner * SIDE).z
                })
                .fold(f64::INFINITY, f64::min);
            let cube = cube("cube", [0.0, 0.0, -lowest - depth]).rotation(turn);
            let mut w = world(ContactModel::Face, vec![floor(), cube]);
            let tilt_of = |w: &World| (w.bodies()[1].rotation() * Vector3::z()).z.min(1.0).acos();
            let case = format!("{degrees}° pressed {} mm", depth * 1e3);
            let mut deepest: f64 = 0.0;
            run(&mut w, 0.5, |w| {
                assert_face_wrenches(w);
                deepest = w.contacts().map(|c| c.depth()).fold(deepest, f64::max);
            });
            let left = tilt_of(&w);
            println!(
                "{case}: {:.4}° after 0.5 s, deepest {:.2} mm",
                left.to_degrees(),
                deepest * 1e3
            );
            assert!(
                deepest < depth + 1e-4,
                "{case}: the far edge landed {:.2} mm in",
                deepest * 1e3
            );
            assert!(
                left < bound,
                "{case}: {:.4}° after 0.5 s (bound {:.4}°)",
                left.to_degrees(),
                bound.to_degrees()
            );
            run(&mut w, 1.5, assert_face_wrenches);
            let spin = w.bodies()[1].angular_velocity().norm();
            assert!(spin < 1e-4, "{case}: |ω| = {spin} rad/s after 2 s");
            assert!(tilt_of(&w) < bound, "{case}: tipped again");
        }
    }
}

/// Cubes of 5 cm to 50 cm left on an edge, tilted by less than the feature angle, fall flat and
/// stay on the floor under the default settings, at 60 and 100 Hz. The face's bearing part is
/// within [`bearing_depth`] of its deepest point, [`BEARING_DEPTH_PER_WIDTH`] times the face's
/// diagonal on faces under 0.5 m wide, so the strip a tilted face bears on stays narrow beside
/// the face: with 0.5 mm at every size a 5 cm cube tilted by 0.9° stood so for ever, its edge
/// 0.8 mm up and its centre over the 3.2 cm strip. The landing blocks at the far corners
/// catch the face as it comes down: without them a 5 cm cube at 60 Hz turned past flat in one
/// step and sank 29 mm into the floor. Bounds: the tilt as for the 2 m cube above, twice the
/// bearing depth over the side (0.08°, where 0.5 mm would allow 0.11° to 1.1° on these sides);
/// at rest, |ω| under 1e-4 rad/s (a cube still tipping turns at rad/s); the deepest point within
/// the slop, where resting contacts stop (2 mm), and 0.1 mm for its last step's rounding.
#[test]
fn small_cubes_left_tilted_on_an_edge_fall_flat() {
    let slop = tatami_contact::ContactSettings::default().slop;
    // Twice the bearing depth over the side, the depth being that rate times the diagonal.
    let bound = (2.0 * BEARING_DEPTH_PER_WIDTH * 2f64.sqrt()).asin();
    for side in [0.05, 0.1, 0.25, 0.5] {
        let half = side / 2.0;
        for (hz, degrees) in [60.0, 100.0]
            .into_iter()
            .flat_map(|hz| [(hz, 0.3f64), (hz, 0.6), (hz, 0.95)])
        {
            let tilt = degrees.to_radians();
            let axis = [30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0];
            let cube = BodyDesc::dynamic(Shape::cuboid([side; 3]))
                .mass(0.1)
                .position([0.0, 0.0, half * (tilt.cos() + tilt.sin())])
                .rotation(rotation(axis, degrees));
            let mut w = world(ContactModel::Face, vec![floor(), cube]);
            let mut deepest: f64 = 0.0;
            for _ in 0..(3.0 * hz) as usize {
                w.step(1.0 / hz).unwrap();
                assert_face_wrenches(&w);
                deepest = w.contacts().map(|c| c.depth()).fold(deepest, f64::max);
            }
            let body = &w.bodies()[1];
            let left = (body.rotation() * Vector3::z()).z.min(1.0).acos();
            let case = format!("{side} m at {hz} Hz, {degrees}°");
            assert!(
                left < bound,
                "{case}: left {:.4}° (bound {:.4}°)",
                left.to_degrees(),
                bound.to_degrees()
            );
            let spin = body.angular_velocity().norm();
            assert!(spin < 1e-4, "{case}: |ω| = {spin} rad/s");
            assert!(deepest < slop + 1e-4, "{case}: {deepest} m into the floor");
        }
    }
}

/// Angle (rad) of the cube's rotation about y, for a cube turned about y only.
fn pitch(w: &World) -> f64 {
    let q = w.bodies()[1].rotation();
    2.0 * q.j.atan2(q.w)
}

#[test]
fn a_cube_tipping_over_an_edge_follows_the_closed_form() {
    let a = SIDE;
    for model in ContactModel::ALL {
        for past in [5.0_f64, 10.0, 20.0] {
            // Turned by 45° − past about y, the cube stands on its edge at x = +√2 cos(45° + …)
            // with its centre of mass `past` degrees beyond the edge, so it tips.
            let turn = 45.0 - past;
            let height = a / std::f64::consts::SQRT_2 * past.to_radians().cos();
            let tipping = cube("cube", [0.0, 0.0, height])
                .rotation(rotation([0.0, 1.0, 0.0], turn))
                .friction(1.0);
            let mut w = world(model, vec![floor().friction(1.0), tipping]);
            let phi0 = past.to_radians();
            let mut worst: f64 = 0.0;
            let mut compared = 0;
            run(&mut w, 2.0, |w| {
                assert_face_wrenches(w);
                // φ from the vertical through the edge; compare while pivoting (φ0 + 2° … 40°).
                let phi = std::f64::consts::FRAC_PI_4 - pitch(w);
                if phi > phi0 + 2f64.to_radians() && phi < 40f64.to_radians() {
                    let omega = w.bodies()[1].angular_velocity().y.abs();
                    // Energy: ½ (2/3) m a² ω² = m g (a/√2)(cos φ0 − cos φ).
                    let expected = (3.0 * G * (phi0.cos() - phi.cos())
                        / (std::f64::consts::SQRT_2 * a))
                        .sqrt();
                    worst = worst.max((omega - expected).abs() / expected);
                    compared += 1;
                }
            });
            assert!(
                compared > 5,
                "{} {past}°: only {compared} pivoting steps",
                model.name()
            );
            assert!(
                worst < 0.03,
                "{} {past}°: ω off the closed form by {:.2}%",
                model.name(),
                worst * 100.0
            );
            assert!(
                pitch(&w).abs() < 0.02,
                "{} {past}°: did not land on its face",
                model.name()
            );
        }
    }
}

/// A body lying on the floor and turning about a horizontal axis at ω₀ hits the floor with the
/// edge its turn sinks and pivots there (no bounce, friction μ = 1 enough to stick). Angular
/// momentum about that edge is kept through the impact, less what gravity's impulse `m g dt`
/// (applied before the contact in a step) takes at arm `d` from it:
/// `ω' = (I ω₀ − m g dt d) / (I + m r²)`, `I` the inertia about the parallel axis through the
/// centre of mass and `r` the centre's distance from the edge. One step at 60 Hz, for a cube on
/// a face and a cylinder on its side (a segment support), turned off the world's axes. Every
/// model pivots at the closed form's rate (to 1e-3 of it: the residual of 15 sweeps read 1e-4)
/// and keeps the edge where it was but for the step's chord, `(ω' dt)² r`. Before the face
/// model gave a tipping support's sinking vertices landing blocks it held the support at its
/// centre and turned the body about it: the 2 m cube at 1.2 rad/s left the step turning at
/// 0.71 rad/s instead of 0.24.
/// The face model cuts a resting pair's bearing part once and keeps it while the contact is
/// kept: every step, each face block's polygon and bodies are those of the bearing part cut
/// afresh from the pair's contact under the current settings — through cubes landing tilted
/// within the feature angle, one sliding, one resting tilted on a shim, the slop changed under
/// them (the tilted cube's part becomes its whole face), and a body removed (the pairs after it
/// renumbered). Each of the three ways a kept part goes stale (a contact carried, the slop, a
/// renumbering) failed it when left out.
#[test]
fn a_kept_bearing_part_is_the_one_cut_afresh() {
    let tilted = |name: &str, x: f64, degrees: f64| {
        cube(name, [x, 0.0, SIDE / 2.0 + 0.02]).rotation(rotation([0.3, 1.0, 0.0], degrees))
    };
    let bodies = vec![
        floor(),
        tilted("a", -6.0, 0.6),
        tilted("b", -2.0, 0.9),
        tilted("c", 2.0, 0.4).velocity([0.8, 0.3, 0.0]),
        tilted("d", 6.0, 0.7),
        // A 2 cm shim under cube a's far side: it rests on the floor along its near edge,
        // tilted 0.7°, its face's part along that edge bearing; a smaller slop then finds it
        // pressed in deeper than the slop, and the whole face bears.
        BodyDesc::fixed(Shape::cuboid([0.2, 3.0, 0.02])).position([-5.3, 0.0, 0.01]),
    ];
    let mut w = world(ContactModel::Face, bodies);
    let mut checked = [0, 0];
    for step in 0..120 {
        if step == 50 {
            let mut settings = *w.settings();
            settings.contact.slop = 1e-5;
            w.set_settings(settings).unwrap();
        }
        if step == 80 {
            let id = w.bodies()[2].id();
            w.remove_body(id).unwrap();
        }
        w.step(DT).unwrap();
        let settings = w.settings().contact;
        let problem = w.problem();
        for block in &problem.blocks {
            let ContactProjection::Face(face) = &block.projection else {
                continue;
            };
            let pair = (block.body_a, block.body_b);
            let contact = (w.contacts())
                .find(|c| (c.body_a, c.body_b) == pair)
                .expect("a face block's pair has a contact");
            let part = tatami_contact::face::bearing_contact(contact, &settings).unwrap();
            checked[usize::from(part.is_some())] += 1;
            let expected = part.as_ref().unwrap_or(contact);
            assert_eq!(
                face.support.vertices(),
                expected.support.vertices(),
                "step {step}, bodies {pair:?}"
            );
        }
    }
    assert!(
        checked[0] > 50 && checked[1] > 20,
        "faces whole and cut: {checked:?}"
    );
}

/// A body resting at depth 0 and set turning about `axis`, with the closed form's terms.
struct Tipping {
    name: &'static str,
    body: BodyDesc,
    axis: Vector3<f64>,
    /// Inertia about the axis through the centre of mass (per kg, the bodies are 1 kg).
    inertia: f64,
    /// Horizontal distance `d` of the centre of mass from the edge it pivots about.
    arm: f64,
    /// Squared distance `r²` of the centre of mass from that edge.
    r2: f64,
    /// Height of the body's lowest point.
    lowest: fn(&World) -> f64,
}

#[test]
fn a_body_tipping_on_its_support_pivots_about_the_edge_it_sinks() {
    let dt = 1.0 / 60.0;
    let (radius, length) = (0.4, 0.9);
    let turn = nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.5);
    let on_side = turn * rotation([1.0, 0.0, 0.0], 90.0);
    let cube_inertia = SIDE * SIDE / 6.0;
    let cylinder_inertia = (3.0 * radius * radius + length * length) / 12.0;
    let cases = [
        Tipping {
            name: "cube",
            body: cube("cube", [0.3, -0.2, SIDE / 2.0]).rotation(turn),
            axis: turn * Vector3::y(),
            inertia: cube_inertia,
            arm: SIDE / 2.0,
            r2: SIDE * SIDE / 2.0,
            lowest: |w| {
                let b = &w.bodies()[1];
                (0..8)
                    .map(|i| {
                        let s = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
                        let corner = Vector3::new(s(1), s(2), s(4)) * SIDE / 2.0;
                        (b.position() + b.rotation() * corner).z
                    })
                    .fold(f64::INFINITY, f64::min)
            },
        },
        Tipping {
            name: "cylinder",
            body: BodyDesc::dynamic(Shape::cylinder(0.4, 0.9))
                .mass(1.0)
                .position([0.3, -0.2, radius])
                .rotation(on_side),
            axis: (on_side * Vector3::z()).cross(&Vector3::z()).normalize(),
            inertia: cylinder_inertia,
            arm: length / 2.0,
            r2: length * length / 4.0 + radius * radius,
            lowest: |w| {
                let b = &w.bodies()[1];
                (0..720)
                    .flat_map(|k| {
                        let t = std::f64::consts::TAU * k as f64 / 720.0;
                        [-0.45, 0.45].map(|z| {
                            let rim = Vector3::new(0.4 * t.cos(), 0.4 * t.sin(), z);
                            (b.position() + b.rotation() * rim).z
                        })
                    })
                    .fold(f64::INFINITY, f64::min)
            },
        },
    ];
    for Tipping {
        name,
        body,
        axis,
        inertia,
        arm,
        r2,
        lowest,
    } in cases
    {
        for model in ContactModel::ALL {
            for omega0 in [1.2, 3.0, 6.0] {
                let spin = axis * omega0;
                let tipping = body.clone().friction(1.0).angular_velocity(spin.into());
                let mut w = world(model, vec![floor().friction(1.0), tipping]);
                let start = lowest(&w);
                w.step(dt).unwrap();
                let omega = w.bodies()[1].angular_velocity();
                let expected = (inertia * omega0 - G * dt * arm) / (inertia + r2);
                let case = format!("{name}, {}, {omega0} rad/s", model.name());
                let about = omega.dot(&axis);
                assert!(
                    (about - expected).abs() < 1e-3 * expected,
                    "{case}: ω' = {about}, closed form {expected}"
                );
                assert!(
                    (omega - axis * about).norm() < 1e-3 * expected,
                    "{case}: {omega}"
                );
                let chord = (expected * dt).powi(2) * r2.sqrt();
                let sunk = start - lowest(&w);
                assert!(
                    sunk < chord,
                    "{case}: the edge sank {sunk} m (chord {chord})"
                );
            }
        }
    }
}

#[test]
fn a_cube_on_a_corner_falls() {
    let diagonal = Vector3::new(1.0, 1.0, 1.0).normalize();
    // The body diagonal two degrees off the vertical, in no symmetry plane of the cube (a
    // symmetric push would balance it on an edge): the centre of mass is past the corner.
    let upright = nalgebra::UnitQuaternion::rotation_between(&diagonal, &Vector3::z()).unwrap();
    let tilt = rotation([1.0, -0.4, 0.0], 2.0) * upright;
    let lowest = (0..8)
        .map(|i| {
            let s = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
            (tilt * Vector3::new(s(1), s(2), s(4))).z
        })
        .fold(f64::INFINITY, f64::min);
    for model in ContactModel::ALL {
        let on_corner = cube("cube", [0.0, 0.0, -lowest])
            .rotation(tilt)
            .friction(1.0);
        let mut w = world(model, vec![floor().friction(1.0), on_corner]);
        run(&mut w, 4.0, assert_face_wrenches);
        let z = w.bodies()[1].position().z;
        assert!(z < 1.2, "{}: the cube is still up at z = {z}", model.name());
    }
}

#[test]
fn a_cube_over_a_ledge_tips_iff_its_centre_of_mass_is_beyond_the_edge() {
    for model in ContactModel::ALL {
        for (overhang, tips) in [(0.2, true), (-0.2, false)] {
            // A 4 m fixed block with its edge at x = 2; the cube's centre at 2 + overhang.
            let ledge = BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 2.0]))
                .name("ledge")
                .position([0.0, 0.0, -1.0])
                .friction(1.0);
            let c = cube("cube", [2.0 + overhang, 0.0, SIDE / 2.0]).friction(1.0);
            let mut w = world(model, vec![ledge, c]);
            run(&mut w, 1.5, assert_face_wrenches);
            let turned = w.bodies()[1].rotation().angle();
            if tips {
                assert!(
                    turned > 0.3,
                    "{} {overhang}: turned only {turned} rad",
                    model.name()
                );
            } else {
                let moved =
                    (w.bodies()[1].position() - Point3::new(2.0 + overhang, 0.0, 1.0)).norm();
                assert!(
                    turned < 1e-3 && moved < 3e-3,
                    "{} {overhang}: turned {turned}, moved {moved}",
                    model.name()
                );
            }
        }
    }
}

/// Angular deceleration (rad/s²) of `body` (resting flat on the floor) spun about z at `omega0`,
/// fitted by least squares over the part of the spin-down between 90% and 10% of that rate.
fn spin_down_rate(model: ContactModel, mu: f64, omega0: f64, body: BodyDesc) -> f64 {
    let spinning = body.friction(mu).angular_velocity([0.0, 0.0, omega0]);
    let mut w = world(model, vec![floor().friction(mu), spinning]);
    let mut samples = Vec::new();
    run(&mut w, 2.0, |w| {
        assert_face_wrenches(w);
        let rate = w.bodies()[1].angular_velocity().z;
        if rate < 0.9 * omega0 && rate > 0.1 * omega0 {
            samples.push((w.time(), rate));
        }
    });
    let n = samples.len() as f64;
    let (st, sw) = samples
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, r)| (a + t, b + r));
    let (mt, mw) = (st / n, sw / n);
    let (cov, var) = samples.iter().fold((0.0, 0.0), |(c, v), (t, r)| {
        (c + (t - mt) * (r - mw), v + (t - mt) * (t - mt))
    });
    -cov / var
}

#[test]
fn a_spinning_cube_stops_at_the_uniform_pressure_rate() {
    let (mu, omega0) = (0.5, 5.0);
    // Uniform pressure over the a × a face: torque μ m g r̄, r̄ = a(√2 + ln(1 + √2))/6,
    // about I_z = m a²/6.
    let r_bar = SIDE * (2f64.sqrt() + (1.0 + 2f64.sqrt()).ln()) / 6.0;
    let expected = mu * G * r_bar / (SIDE * SIDE / 6.0);
    let flat = || cube("cube", [0.0, 0.0, SIDE / 2.0]);
    let face = spin_down_rate(ContactModel::Face, mu, omega0, flat());
    assert!(
        (face - expected).abs() / expected < 0.02,
        "face: {face} rad/s², closed form {expected}"
    );
    for model in [ContactModel::Vertex, ContactModel::Patch] {
        let rate = spin_down_rate(model, mu, omega0, flat());
        println!(
            "{}: spin-down {rate:.3} rad/s² ({:.2}× the closed form)",
            model.name(),
            rate / expected
        );
    }
}

#[test]
fn the_centre_of_pressure_of_a_tetrahedron_leans_toward_the_pulled_vertex() {
    // A tetrahedron on its base triangle, gravity tilted 10° toward the base vertex at +x.
    let height = 1.5;
    let r3 = 3f64.sqrt() / 2.0;
    let points = vec![
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(-0.5, r3, 0.0),
        Point3::new(-0.5, -r3, 0.0),
        Point3::new(0.0, 0.0, height),
    ];
    let lean = 10f64.to_radians();
    let gravity = [G * lean.sin(), 0.0, -G * lean.cos()];
    let tetra = BodyDesc::dynamic(Shape::convex(points))
        .name("tetra")
        .mass(1.0)
        .friction(1.0);
    let mut w = World::builder()
        .model(ContactModel::Face)
        .gravity(gravity)
        .body(floor().friction(1.0))
        .body(tetra)
        .build()
        .unwrap();
    run(&mut w, 0.5, assert_face_wrenches);
    let contact = w.contacts().next().expect("one contact");
    assert_eq!(contact.support.vertices().len(), 3);
    let block = &w.problem().blocks[w.contact_blocks(0).expect("one contact").start];
    let impulses: Vec<f64> = w.problem().rows[block.rows.clone()]
        .iter()
        .map(|r| r.impulse)
        .collect();
    let p = FaceProjection::centre_of_pressure(&impulses).expect("loaded");
    let frame = &contact.frame;
    let zmp = frame.to_world(&(contact.support.centroid() + p.coords));
    // Static balance: the line of action of gravity through the centre of mass (h/4 above the
    // base's centroid at the origin) meets the floor h/4 · tan(lean) toward +x.
    let expected = height / 4.0 * lean.tan();
    assert!(
        (zmp.x - expected).abs() < 0.01 * expected + 1e-3,
        "ZMP at {zmp}, expected x = {expected}"
    );
    assert!(zmp.y.abs() < 1e-3, "ZMP at {zmp}");
    assert!(
        w.bodies()[1].linear_velocity().norm() < 1e-3,
        "the tetrahedron moved"
    );
}

#[test]
fn a_standing_cylinder_spins_down_at_the_disc_rate() {
    let (mu, omega0, radius, height, mass) = (0.5, 5.0, 1.0, 1.0, 1.0);
    let standing = || {
        BodyDesc::dynamic(Shape::cylinder(radius, height))
            .name("cylinder")
            .mass(mass)
            .position([0.0, 0.0, height / 2.0])
    };
    // A disc under uniform pressure: torque (2/3) μ N R about I = m R² / 2.
    let expected = (2.0 / 3.0) * mu * mass * G * radius / (0.5 * mass * radius * radius);
    let face = spin_down_rate(ContactModel::Face, mu, omega0, standing());
    assert!(
        (face - expected).abs() / expected < 0.03,
        "face: {face} rad/s², closed form {expected}"
    );
    for model in [ContactModel::Vertex, ContactModel::Patch] {
        let rate = spin_down_rate(model, mu, omega0, standing());
        println!(
            "{}: cylinder spin-down {rate:.3} rad/s² ({:.2}× the disc rate)",
            model.name(),
            rate / expected
        );
    }
}

/// A box meeting another in [`plastic_face_impact`]: centre, half-extents, mass (infinite for a
/// fixed or kinematic box), and linear and angular velocity.
type ImpactBox<'a> = (&'a Point3<f64>, &'a Vector3<f64>, f64, [Vector3<f64>; 2]);

/// The bodies' velocities after a frictionless, perfectly plastic impact of box 1's `+x` face on
/// box 2's `−x` face: the faces end with no relative normal velocity and no relative tilt rate
/// (the face model's constraint), from the normal impulse `λ` and the couple `(τy, τz)` at the
/// patch centroid `c`, solved from their 3 × 3 linear system. Returns box 1's linear and angular
/// velocity and the centre of pressure's offset from `c` (y, z), or `None` if `λ ≤ 0`.
fn plastic_face_impact(
    box1: ImpactBox,
    box2: ImpactBox,
    c: &Point3<f64>,
) -> Option<([Vector3<f64>; 2], [f64; 2])> {
    let inverse_inertia = |half: &Vector3<f64>, mass: f64| {
        let (x, y, z) = (half.x * half.x, half.y * half.y, half.z * half.z);
        Matrix3::from_diagonal(&Vector3::new(y + z, x + z, x + y).map(|i| 3.0 / (mass * i)))
    };
    let (x1, h1, m1, [v1, w1]) = box1;
    let (x2, h2, m2, [v2, w2]) = box2;
    let (inv_m1, inv_i1) = (1.0 / m1, inverse_inertia(h1, m1));
    let (inv_m2, inv_i2) = if m2.is_finite() {
        (1.0 / m2, inverse_inertia(h2, m2))
    } else {
        (0.0, Matrix3::zeros())
    };
    let n = -Vector3::x();
    let (r1, r2) = (c - x1, c - x2);
    // Box 1's velocities after `λ n` at `c` and the couple `τ`, box 2's after the opposite.
    let after = |u: &Vector3<f64>| {
        let (force, couple) = (n * u[0], Vector3::new(0.0, u[1], u[2]));
        (
            v1 + force * inv_m1,
            w1 + inv_i1 * (r1.cross(&force) + couple),
            v2 - force * inv_m2,
            w2 - inv_i2 * (r2.cross(&force) + couple),
        )
    };
    let residual = |u: &Vector3<f64>| {
        let (a, b, c, d) = after(u);
        let relative = (a + b.cross(&r1)) - (c + d.cross(&r2));
        Vector3::new(relative.dot(&n), b.y - d.y, b.z - d.z)
    };
    let free = residual(&Vector3::zeros());
    let system = Matrix3::from_columns(&[0, 1, 2].map(|k| residual(&Vector3::ith(k, 1.0)) - free));
    let u = system.lu().solve(&-free)?;
    let (v, w, _, _) = after(&u);
    (u[0] > 0.0).then(|| ([v, w], [u[2] / u[0], -u[1] / u[0]]))
}

/// The scenario of Jolt's `TestEstimateCollisionResponse`
/// (`UnitTests/Physics/EstimateCollisionResponseTest.cpp`): a 0.2 × 2 × 4 m box moving at (1,
/// 1, 0) m/s and spinning at 0 or ±1 rad/s about y meets, face on, 0.1 mm in, a 0.4 × 6 × 8 m
/// box that is fixed, kinematic or dynamic at (−1, 0, 0) m/s, offset by 0, 0.5 or its whole
/// half-extent along y and z; no gravity. Frictionless and without restitution, one step of the
/// face model must give the plastic face impact ([`plastic_face_impact`]) wherever its centre
/// of pressure is inside the patch (by 5% of the patch's half-widths: on the patch's edge the
/// face tips, and the closed form no longer holds). Jolt compares with its own estimate; here
/// the reference is the rigid-body closed form. The model's answer is checked, so the solve runs
/// to convergence (200 sweeps; the default 15 stop 7.5 × 10⁻³ rad/s short in two starts, box
/// 1 spinning at −1 rad/s on the dynamic box offset by 3 m along y): 38 of the 52 starts
/// checked agree to 10⁻¹⁰, the rest to 8.1 × 10⁻⁵ (m/s, rad/s; not pinned down); the bound is
/// 2 × 10⁻⁴.
#[test]
fn a_face_impact_leaves_the_plastic_closed_forms_velocities() {
    let (h1, h2) = (Vector3::new(0.1, 1.0, 2.0), Vector3::new(0.2, 3.0, 4.0));
    let x1 = Point3::new(1.0, 2.0, 3.0);
    let density = 1000.0;
    let volume = |h: &Vector3<f64>| 8.0 * h.x * h.y * h.z;
    let (m1, m2) = (density * volume(&h1), density * volume(&h2));
    let mut checked = 0;
    for kind in ["fixed", "kinematic", "dynamic"] {
        for (y, z) in [0.0, 0.5, h2.y]
            .into_iter()
            .flat_map(|y| [0.0, 0.5, h2.z].map(|z| (y, z)))
        {
            for spin in [0.0, -1.0, 1.0] {
                let x2 = x1 + Vector3::new(h1.x + h2.x - 1e-4, y, z);
                let shape = Shape::cuboid((h2 * 2.0).into());
                let (box2, v2, mass2) = match kind {
                    "fixed" => (BodyDesc::fixed(shape), Vector3::zeros(), f64::INFINITY),
                    "kinematic" => (BodyDesc::kinematic(shape), -Vector3::x(), f64::INFINITY),
                    _ => (BodyDesc::dynamic(shape).density(density), -Vector3::x(), m2),
                };
                let (v1, w1) = (Vector3::new(1.0, 1.0, 0.0), Vector3::new(0.0, spin, 0.0));
                let converged = WorldSettings {
                    solver: Solver::Pgs(PgsParams {
                        iterations: 200,
                        warm_start: WarmStart::On,
                        ..PgsParams::default()
                    }),
                    ..WorldSettings::default()
                };
                let mut world = World::builder()
                    .settings(converged)
                    .gravity([0.0; 3])
                    .body(
                        BodyDesc::dynamic(Shape::cuboid((h1 * 2.0).into()))
                            .density(density)
                            .position(x1.into())
                            .velocity(v1.into())
                            .angular_velocity(w1.into())
                            .friction(0.0),
                    )
                    .body(box2.position(x2.into()).velocity(v2.into()).friction(0.0))
                    .build()
                    .unwrap();
                world.step(1.0 / 60.0).unwrap();
                // The patch: box 1's face within box 2's, in y and z.
                let span = |axis: usize| {
                    let low = (x1[axis] - h1[axis]).max(x2[axis] - h2[axis]);
                    let high = (x1[axis] + h1[axis]).min(x2[axis] + h2[axis]);
                    (0.5 * (low + high), 0.5 * (high - low))
                };
                let ((cy, half_y), (cz, half_z)) = (span(1), span(2));
                let c = Point3::new(x1.x + h1.x, cy, cz);
                let zero = Vector3::zeros();
                let Some(([v, w], [dy, dz])) = plastic_face_impact(
                    (&x1, &h1, m1, [v1, w1]),
                    (&x2, &h2, mass2, [v2, zero]),
                    &c,
                ) else {
                    continue;
                };
                if dy.abs() > 0.95 * half_y || dz.abs() > 0.95 * half_z {
                    continue;
                }
                checked += 1;
                let body = &world.bodies()[0];
                let case = format!("{kind} box, offset ({y}, {z}), spin {spin}");
                assert!(
                    (body.linear_velocity() - v).norm() < 2e-4,
                    "{case}: {} against {v}",
                    body.linear_velocity()
                );
                assert!(
                    (body.angular_velocity() - w).norm() < 2e-4,
                    "{case}: {} against {w}",
                    body.angular_velocity()
                );
            }
        }
    }
    // Of the 81 starts, those whose centre of pressure lies well inside the patch.
    assert!(checked >= 40, "only {checked} starts checked");
}

/// A cylinder lying on its side touches the floor along a segment, which the face model holds
/// with one 5-row block whose twist is bounded by `μ r̄ f3` about the centre of pressure, `r̄`
/// the segment's mean distance from it. Spun about the vertical, its line of contact takes
/// uniform pressure: torque `μ N L / 4` about `I = m (3 r² + L²) / 12`. Turned 30° about the
/// vertical, off the floor's axes. The face model's rate agrees to round-off (9.3038 rad/s²,
/// its twist bound exact for a segment); the bound is the standing disc's 3%, whose 64-gon cap
/// only approximates the disc.
#[test]
fn a_cylinder_lying_on_its_side_spins_down_at_the_line_rate() {
    let (mu, omega0, radius, length, mass) = (0.5, 5.0, 0.2, 1.5, 1.0);
    let lying = || {
        BodyDesc::dynamic(Shape::cylinder(radius, length))
            .name("cylinder")
            .mass(mass)
            .position([0.0, 0.0, radius])
            .rotation(rotation([0.0, 0.0, 1.0], 30.0) * rotation([1.0, 0.0, 0.0], 90.0))
    };
    let inertia = mass * (3.0 * radius * radius + length * length) / 12.0;
    let expected = mu * mass * G * length / 4.0 / inertia;
    let face = spin_down_rate(ContactModel::Face, mu, omega0, lying());
    assert!(
        (face - expected).abs() / expected < 0.03,
        "face: {face} rad/s², closed form {expected}"
    );
    for model in [ContactModel::Vertex, ContactModel::Patch] {
        let rate = spin_down_rate(model, mu, omega0, lying());
        println!(
            "{}: lying cylinder spin-down {rate:.3} rad/s² ({:.2}× the line rate)",
            model.name(),
            rate / expected
        );
    }
}

/// How far below the floor's top (z = 0) the lowest of `samples` points evenly round the rim
/// of `body`'s cap at height `cap` (body frame) of a cylinder of `radius` lies (m; negative
/// above it).
fn rim_depth(body: &tatami_world::Body, radius: f64, cap: f64, samples: u32) -> f64 {
    (0..samples)
        .map(|k| {
            let t = std::f64::consts::TAU * f64::from(k) / f64::from(samples);
            let rim = Vector3::new(radius * t.cos(), radius * t.sin(), cap);
            -(body.position() + body.rotation() * rim).z
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

/// A cylinder (r 0.4 m, 0.89 m tall, as in the mixed pile) set down on its cap's rim, tilted
/// past the feature angle about an axis off the floor's, and set wobbling about a horizontal
/// axis across the tilt: the lowest point of its rim runs round the rim by up to tens of
/// degrees a step at 60 Hz. It rests on that one point, and the rim beside it must not pass
/// the floor: it lands on the cap's vertices within the margin ([`tatami_contact::Contact::
/// landing`]). Held at the one point, the rim beside it went 10–18 mm into the floor while
/// the cylinder wobbled for a second or more. Bounds: the rim's true circle (sampled every
/// half degree) no deeper than the slop, where resting contacts stop, and 0.1 mm for the
/// circle below its inscribed 64-gon and the last step's rounding; then, within 3 s, lying
/// on its cap within twice the bearing depth across it (0.06°) and at rest.
#[test]
fn a_cylinder_wobbling_on_its_rim_stays_out_of_the_floor() {
    let slop = tatami_contact::ContactSettings::default().slop;
    let (radius, height) = (0.4, 0.89);
    let flat_bound = (2.0 * BEARING_DEPTH_PER_WIDTH).asin();
    let tilt_axis = [1.0, 2.0, 0.0];
    let across = Vector3::new(-2.0, 1.0, 0.0).normalize();
    for (degrees, spin) in [
        (1.4f64, 1.0),
        (1.4, 2.0),
        (1.4, 4.0),
        (3.0, 2.0),
        (3.0, 4.0),
    ] {
        let tilt = degrees.to_radians();
        let cylinder = BodyDesc::dynamic(Shape::cylinder(radius, height))
            .mass(1.0)
            .friction(0.5)
            .position([0.3, -0.2, 0.5 * height * tilt.cos() + radius * tilt.sin()])
            .rotation(rotation(tilt_axis, degrees))
            .angular_velocity((across * spin).into());
        let mut w = world(ContactModel::Face, vec![floor().friction(0.5), cylinder]);
        let mut deepest: f64 = 0.0;
        for _ in 0..180 {
            w.step(1.0 / 60.0).unwrap();
            let rim = rim_depth(&w.bodies()[1], radius, -0.5 * height, 720);
            deepest = deepest.max(rim);
        }
        let case = format!("{degrees}° at {spin} rad/s");
        assert!(deepest < slop + 1e-4, "{case}: {deepest} m into the floor");
        let body = &w.bodies()[1];
        let left = (body.rotation() * Vector3::z()).z.min(1.0).acos();
        assert!(
            left < flat_bound,
            "{case}: left at {:.3}°",
            left.to_degrees()
        );
        let still = body.angular_velocity().norm();
        assert!(still < 1e-4, "{case}: |ω| = {still} rad/s");
    }
}

/// Small cylinders (1 and 2 cm across and tall, 1000 kg/m³) let go 3 mm above the floor nearly
/// on their side, tilted 60–88° about an axis off the floor's so that one point of a cap's rim
/// is lowest, at 60 Hz under every model: each comes to lie on its side, its centre one radius
/// up. Such a cylinder rocks from one rim to the other faster the smaller it is: held at the
/// rim point, and landing on that rim's points beside it, the far end of its side line swung
/// past flat each step, became the lowest point, and the cylinder sank through the floor
/// rocking at ±14 rad/s (a 1 cm one to 11.6 mm below the floor's top from every tilt here,
/// a 2 cm one at 75° to 16 mm below). The far end now lands like the rim's points
/// ([`tatami_contact::Contact::landing`]). Bounds: both rims' true circles (sampled every
/// degree) never deeper than the slop plus 0.1 mm over the 3 s (the circles below their
/// inscribed 64-gons and the steps' rounding); at the end lying within 1° of flat, its centre
/// within the slop below one radius, and at rest (1 mm/s).
#[test]
fn a_small_cylinder_let_go_nearly_on_its_side_lies_on_the_floor() {
    let slop = tatami_contact::ContactSettings::default().slop;
    for model in ContactModel::ALL {
        for size in [0.01, 0.02] {
            let (radius, half) = (size / 2.0, size / 2.0);
            for degrees in [60.0f64, 75.0, 80.0, 85.0, 88.0] {
                let tilt = degrees.to_radians();
                let lowest = half * tilt.cos() + radius * tilt.sin();
                let cylinder = BodyDesc::dynamic(Shape::cylinder(radius, size))
                    .density(1000.0)
                    .friction(0.5)
                    .position([0.3, -0.2, lowest + 0.003])
                    .rotation(rotation([1.0, 2.0, 0.0], degrees));
                let mut w = world(model, vec![floor().friction(0.5), cylinder]);
                let mut deepest: f64 = 0.0;
                for _ in 0..180 {
                    w.step(1.0 / 60.0).unwrap();
                    for cap in [-half, half] {
                        deepest = deepest.max(rim_depth(&w.bodies()[1], radius, cap, 360));
                    }
                }
                let body = &w.bodies()[1];
                let case = format!("{}, {size} m at {degrees}°", model.name());
                let off_flat = (body.rotation() * Vector3::z()).z.abs().asin().to_degrees();
                let (height, speed) = (body.position().z, body.linear_velocity().norm());
                println!(
                    "{case}: deepest {:.3} mm, {off_flat:.3}° off flat, centre {:.3} mm, {speed:.1e} m/s",
                    deepest * 1e3,
                    height * 1e3
                );
                assert!(deepest < slop + 1e-4, "{case}: {deepest} m into the floor");
                assert!(off_flat < 1.0, "{case}: {off_flat}° off lying flat");
                assert!(
                    height > radius - slop - 1e-4 && height < radius + 1e-4,
                    "{case}: centre {height} m up"
                );
                assert!(speed < 1e-3, "{case}: {speed} m/s");
            }
        }
    }
}

/// A plank (2 × 1 × 1 m) on a 25° ramp, sticking (tan 25° = 0.47 < μ = 0.5), over the ramp's
/// corner: it bears on a 1.05 × 0.5 m part of its face, its centre of mass 5 cm inside that
/// part's far end, 0.47 m from its centroid `G` across the slope. Held by friction at its
/// centre of pressure, it stays; friction applied at `G` would need a twist of 0.47 × 0.47 f3
/// about `G`, beyond the uniform-pressure bound μ r̄ f3 (0.15 f3), and it would spin off. The
/// whole scene is turned 30° about the vertical, off the axes. Held, it may settle into the
/// 2 mm slop (the models move it by micrometres), hence 2 mm and 2 mrad; spun off, it went
/// 5.8 m and 2.4 rad in the 3 s.
#[test]
fn a_plank_sticking_on_a_ramp_over_its_corner_stays() {
    let slope = rotation([0.0, 0.0, 1.0], 30.0) * rotation([1.0, 0.0, 0.0], 25.0);
    let place = |local: [f64; 3]| slope * Vector3::from(local);
    for model in ContactModel::ALL {
        // The ramp's top face is z = 0 in its frame, for x < 1 and y < 0.
        let ramp = BodyDesc::fixed(Shape::cuboid([4.0, 3.0, 0.5]))
            .name("ramp")
            .position(place([-1.0, -1.5, -0.25]).into())
            .rotation(slope)
            .friction(0.5);
        let start = place([0.95, 0.0, 0.5]);
        let plank = BodyDesc::dynamic(Shape::cuboid([2.0, 1.0, 1.0]))
            .name("plank")
            .mass(1.0)
            .position(start.into())
            .rotation(slope)
            .friction(0.5);
        let mut w = world(model, vec![ramp, plank]);
        run(&mut w, 3.0, |_| {});
        let body = &w.bodies()[1];
        let moved = (body.position().coords - start).norm();
        let turned = body.rotation().angle_to(&slope);
        assert!(
            moved < 2e-3 && turned < 2e-3,
            "{}: moved {moved} m, turned {turned} rad",
            model.name()
        );
    }
}
