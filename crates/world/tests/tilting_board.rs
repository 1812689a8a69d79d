//! The angle of repose: a box on a board tilted slowly about a horizontal axis turned off the
//! world's axes starts to slip when the board's tilt reaches `atan μ`, under every contact
//! model, for friction coefficients from 0.3 to 0.8.

use nalgebra::{UnitQuaternion, Vector3};
use tatami_world::{BodyDesc, ContactModel, Shape, World};

const G: f64 = 9.8;
/// The board's tilt rate (rad/s): slow, so the box is nearly at rest on it when it slips.
const RATE: f64 = 0.05;
/// Time step (s).
const DT: f64 = 1.0 / 60.0;
/// The box counts as slipping once its centre moves this fast (m/s) against the board's point
/// under it.
const SLIPPING: f64 = 0.01;

/// The board's tilt (rad) when a 0.4 × 0.4 × 0.2 m, 1 kg box on it first slips, under `model`
/// with friction `mu` on both; the board is a kinematic body turning at [`RATE`] about a
/// horizontal axis 34° off the world's x axis, from level.
fn slip_angle(model: ContactModel, mu: f64) -> Option<f64> {
    let heading = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.6);
    let axis = heading * Vector3::x();
    let mut world = World::builder()
        .model(model)
        .gravity([0.0, 0.0, -G])
        .body(
            BodyDesc::kinematic(Shape::cuboid([6.0, 6.0, 0.2]))
                .name("board")
                .position([0.0, 0.0, -0.1])
                .rotation(heading)
                .angular_velocity((axis * RATE).into())
                .friction(mu),
        )
        .body(
            BodyDesc::dynamic(Shape::cuboid([0.4, 0.4, 0.2]))
                .name("box")
                .mass(1.0)
                .friction(mu)
                .position([0.0, 0.0, 0.1])
                .rotation(heading),
        )
        .build()
        .unwrap();
    for _ in 0..(1.2 / RATE / DT) as usize {
        world.step(DT).unwrap();
        let (board, body) = (world.body("board")?, world.body("box")?);
        let arm = body.position() - board.position();
        let under = board.linear_velocity() + board.angular_velocity().cross(&arm);
        if (body.linear_velocity() - under).norm() > SLIPPING {
            return Some((board.rotation() * Vector3::z()).z.acos());
        }
    }
    None
}

/// The box holds until the tilt reaches `θc = atan μ`; past it, the slip speed grows as
/// `g k RATE t² / 2` (`k = cos θc + μ sin θc`, the slope of `g (sin θ − μ cos θ)` at `θc`),
/// so it reads as slipping `RATE √(2 SLIPPING / (g k RATE))` later (0.51–0.57°). Measured
/// within 0.1° of that (two steps' tilt is 0.095°) under every model.
#[test]
fn a_box_on_a_tilting_board_slips_at_the_angle_of_repose() {
    for model in ContactModel::ALL {
        for mu in [0.3f64, 0.5, 0.8] {
            let repose = mu.atan();
            let k = repose.cos() + mu * repose.sin();
            let expected = repose + RATE * (2.0 * SLIPPING / (G * k * RATE)).sqrt();
            let slipped = slip_angle(model, mu).expect("the box slips before 1.2 rad");
            println!(
                "{model:?} μ = {mu}: slipped at {:.3}°, expected {:.3}° (repose {:.3}°)",
                slipped.to_degrees(),
                expected.to_degrees(),
                repose.to_degrees()
            );
            assert!(
                (slipped - expected).abs() < 0.1f64.to_radians(),
                "{model:?} μ = {mu}: slipped at {:.3}°, expected {:.3}°",
                slipped.to_degrees(),
                expected.to_degrees()
            );
        }
    }
}
