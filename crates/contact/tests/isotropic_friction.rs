//! Coulomb friction is isotropic: a sliding contact's friction impulse is antiparallel to the slip
//! it leaves and worth `μ` times the normal impulse, whatever the orientation of the contact
//! frame's tangents (which are arbitrary) — for every model, with the default circular cone.

use std::f64::consts::PI;

use nalgebra::{Matrix3, Point3, Vector3};
use tatami_contact::{
    Contact, ContactFrame, ContactModel, ContactProjection, ContactSettings, FrictionCone, Material,
};
use tatami_geometry::ConvexPolygon;
use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
use tatami_lcp::{BodyId, Problem, SolverBody};

const MU: f64 = 0.5;
const DT: f64 = 0.01;
const G: f64 = 9.8;
const SPEED: f64 = 5.0;

/// The contact frame at the world origin with normal `+z` and its tangents turned by `turn`
/// about it: the same plane, other tangents.
fn frame(turn: f64) -> ContactFrame {
    ContactFrame {
        origin: Point3::origin(),
        tangent1: Vector3::new(turn.cos(), turn.sin(), 0.0),
        tangent2: Vector3::new(-turn.sin(), turn.cos(), 0.0),
        normal: Vector3::z(),
    }
}

/// A 1 kg, 2 m cube on the fixed ground moving at `velocity` after one step of gravity; the
/// contact is its 2 m bottom square in a frame turned by `turn`.
fn cube_on_ground(
    model: ContactModel,
    settings: &ContactSettings,
    velocity: Vector3<f64>,
    turn: f64,
) -> Problem<ContactProjection> {
    let frame = frame(turn);
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| frame.to_plane(&Point3::new(x, y, 0.0)));
    let contact = Contact {
        body_a: BodyId(0),
        body_b: BodyId(1),
        centre_a: Point3::new(0.0, 0.0, 1.0),
        centre_b: Point3::new(0.0, 0.0, -1.0),
        frame,
        support: ConvexPolygon::from_points(&corners).unwrap(),
        depths: vec![0.0; 4],
        material: Material::new(MU, MU, 0.0).unwrap(),
        landing: Vec::new(),
        bounce_speed: 0.0,
    };
    let mut cube = SolverBody::fixed();
    cube.inv_mass = 1.0;
    cube.inv_inertia_world = Matrix3::identity() * 1.5;
    cube.linear_velocity = velocity;
    let mut problem = Problem {
        bodies: vec![cube, SolverBody::fixed()],
        ..Default::default()
    };
    model.build(&contact, DT, settings, &mut problem).unwrap();
    problem.bodies[0].linear_velocity.z -= G * DT;
    problem
}

/// The cube sliding at [`SPEED`] along `heading` (rad) with the default settings.
fn sliding_cube(model: ContactModel, heading: f64, turn: f64) -> Problem<ContactProjection> {
    let velocity = Vector3::new(heading.cos(), heading.sin(), 0.0) * SPEED;
    cube_on_ground(model, &ContactSettings::default(), velocity, turn)
}

/// Solves with `sweeps`; returns the contact impulse on the cube (from its momentum change) and
/// the slip velocity it leaves at the contact's centre.
fn solve(mut problem: Problem<ContactProjection>, sweeps: usize) -> (Vector3<f64>, Vector3<f64>) {
    let before = problem.bodies[0].linear_velocity;
    let params = PgsParams {
        iterations: sweeps,
        ..PgsParams::default()
    };
    pgs::solve_in_place(&mut problem, &mut PgsWorkspace::default(), &params).unwrap();
    let cube = &problem.bodies[0];
    let impulse = cube.linear_velocity - before; // m = 1 kg
    let lever = Point3::origin() - Point3::new(0.0, 0.0, 1.0);
    let slip = cube.linear_velocity + cube.angular_velocity.cross(&lever);
    (impulse, Vector3::new(slip.x, slip.y, 0.0))
}

/// Angle (degrees) between the tangential impulse and the reversed slip.
fn misalignment(impulse: &Vector3<f64>, slip: &Vector3<f64>) -> f64 {
    let friction = Vector3::new(impulse.x, impulse.y, 0.0);
    friction.angle(&-slip).to_degrees()
}

#[test]
fn sliding_friction_opposes_the_slip_with_mu_times_the_normal_impulse() {
    for model in ContactModel::ALL {
        for heading_deg in [0.0, 15.0, 30.0, 45.0, 60.0, 90.0, 137.0, 250.0] {
            for turn in [0.0, 0.3, PI / 4.0, 1.9] {
                let heading = f64::to_radians(heading_deg);
                let (impulse, slip) = solve(sliding_cube(model, heading, turn), 15);
                let angle = misalignment(&impulse, &slip);
                let ratio = impulse.xy().norm() / (MU * impulse.z);
                let label = format!("{} heading {heading_deg}° tangents {turn}", model.name());
                assert!(angle < 0.5, "{label}: friction {angle:.3}° off the slip");
                // Sliding throughout: the friction must sit on the disc's rim (15 sweeps leave
                // the normal impulse within 1e-9 of m g dt; the ratio is exact on the rim).
                assert!((ratio - 1.0).abs() < 1e-6, "{label}: |f| = {ratio} μ f3");
            }
        }
    }
}

#[test]
fn the_converged_answer_does_not_depend_on_the_tangents() {
    for model in ContactModel::ALL {
        let reference = solve(sliding_cube(model, 0.6, 0.0), 2000);
        for turn in [0.3, PI / 4.0, 1.9, -2.4] {
            let (impulse, slip) = solve(sliding_cube(model, 0.6, turn), 2000);
            assert!(
                (impulse - reference.0).norm() < 1e-9 && (slip - reference.1).norm() < 1e-9,
                "{}: tangents turned by {turn} change the answer: {impulse} vs {}",
                model.name(),
                reference.0
            );
        }
    }
}

#[test]
fn the_box_pyramid_turns_a_diagonal_slide_towards_an_axis() {
    // The option the paper uses: each tangent bounded apart gives √2 μ f3 at 45° to the axes.
    let settings = ContactSettings {
        friction_cone: FrictionCone::Box,
        ..ContactSettings::default()
    };
    let velocity = Vector3::new(4.0, 3.0, 0.0);
    let mut problem = cube_on_ground(ContactModel::Face, &settings, velocity, 0.0);
    pgs::solve(&mut problem).unwrap();
    let v = problem.bodies[0].linear_velocity;
    let dv = Vector3::new(v.x - 4.0, v.y - 3.0, 0.0);
    // Both tangents saturate at μ m g dt: the impulse points at 45°, not along −(4, 3).
    assert!(
        (dv.x + MU * G * DT).abs() < 1e-9 && (dv.y + MU * G * DT).abs() < 1e-9,
        "{dv}"
    );
}
