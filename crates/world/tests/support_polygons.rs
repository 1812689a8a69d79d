//! Support polygons of box–box contacts keep every vertex of the overlap, and a resting hull's
//! contact is as deep as the hull is in the floor.

mod common;

use common::{DT, SIDE, cube, floor, rotation};
use tatami_geometry::PolygonKind;
use tatami_world::World;

/// The contacts found at the start of one step of the floor and `body`.
fn contacts_with_floor(body: tatami_world::BodyDesc) -> Vec<tatami_contact::Contact> {
    let mut world = World::builder().body(floor()).body(body).build().unwrap();
    world.step(DT).unwrap();
    world.contacts().cloned().collect()
}

/// The contact between bodies 1 and 2 (two stacked cubes on the floor).
fn between_cubes(world: &World) -> &tatami_contact::Contact {
    world
        .contacts()
        .find(|c| c.body_a.0 == 1 && c.body_b.0 == 2)
        .expect("a contact between the cubes")
}

#[test]
fn a_cube_flat_on_the_floor_gives_its_square_face() {
    let contacts = contacts_with_floor(cube("cube", [0.0, 0.0, SIDE / 2.0]));
    assert_eq!(contacts.len(), 1);
    let c = &contacts[0];
    assert_eq!(c.support.vertices().len(), 4);
    assert!((c.support.area() - SIDE * SIDE).abs() < 1e-9);
    assert!((c.frame.normal.z.abs() - 1.0).abs() < 1e-12);
}

#[test]
fn a_wide_thin_floor_still_touches_with_its_top_face_only() {
    // A 1 km × 1 km × 2 m slab: its bottom corners are within 1° (seen from the far top
    // corner) of its top face, and must not join the feature.
    for width in [40.0, 400.0, 1000.0] {
        let slab = tatami_world::BodyDesc::fixed(tatami_world::Shape::cuboid([width, width, 2.0]))
            .position([0.0, 0.0, -1.0]);
        let mut world = World::builder()
            .body(slab)
            .body(cube("cube", [0.0, 0.0, SIDE / 2.0]))
            .build()
            .unwrap();
        common::run(&mut world, 1.0, |_| {});
        let c = world.contacts().next().expect("a contact");
        assert_eq!(c.support.vertices().len(), 4, "{width} m slab");
        assert!(
            (c.support.area() - SIDE * SIDE).abs() < 1e-9,
            "{width} m slab"
        );
        let z = world.bodies()[1].position().z;
        assert!(
            (z - SIDE / 2.0).abs() < 3e-3,
            "{width} m slab: the cube sank to z = {z}"
        );
    }
}

#[test]
fn a_cube_twisted_45_degrees_on_a_cube_gives_an_octagon() {
    let mut world = World::builder()
        .body(floor())
        .body(cube("base", [0.0, 0.0, 1.0]))
        .body(cube("top", [0.0, 0.0, 3.0]).rotation(rotation([0.0, 0.0, 1.0], 45.0)))
        .build()
        .unwrap();
    world.step(DT).unwrap();
    let between = between_cubes(&world);
    assert_eq!(between.support.vertices().len(), 8);
    // A regular octagon of inradius 1: area 8 tan(π/8).
    let expected = 8.0 * (std::f64::consts::PI / 8.0).tan();
    assert!((between.support.area() - expected).abs() < 1e-9);
}

#[test]
fn a_cube_on_an_edge_gives_a_segment() {
    let centre = [0.0, 0.0, SIDE / std::f64::consts::SQRT_2];
    let contacts =
        contacts_with_floor(cube("cube", centre).rotation(rotation([0.0, 1.0, 0.0], 45.0)));
    assert_eq!(contacts.len(), 1);
    let s = &contacts[0].support;
    assert_eq!(s.kind(), PolygonKind::Segment);
    assert!(((s.vertices()[0] - s.vertices()[1]).norm() - SIDE).abs() < 1e-9);
}

/// A cube tilted by less than the feature angle (1° by default) rests on its whole bottom face,
/// and by more on its lowest edge: the face's far edge, 3.3 cm up at 0.95°, stays in the
/// support polygon. Turned 30° about the vertical, so the tilt is off the floor's axes.
#[test]
fn a_cube_tilted_under_the_feature_angle_rests_on_its_face() {
    for (degrees, kind, vertices) in [
        (0.95f64, PolygonKind::Polygon, 4),
        (1.05, PolygonKind::Segment, 2),
    ] {
        let tilt = degrees.to_radians();
        let half = SIDE / 2.0;
        // The lowest edge on the floor.
        let centre = [0.0, 0.0, half * (tilt.cos() + tilt.sin())];
        let turn = rotation([0.0, 0.0, 1.0], 30.0) * rotation([1.0, 0.0, 0.0], degrees);
        let contacts = contacts_with_floor(cube("cube", centre).rotation(turn));
        assert_eq!(contacts.len(), 1, "{degrees}°");
        let s = &contacts[0].support;
        assert_eq!(s.kind(), kind, "{degrees}°");
        assert_eq!(s.vertices().len(), vertices, "{degrees}°");
    }
}

#[test]
fn a_cube_on_a_corner_gives_a_point() {
    // Turn the body diagonal (1, 1, 1) onto the vertical: one corner points straight down.
    let diagonal = nalgebra::Vector3::new(1.0, 1.0, 1.0).normalize();
    let tilt =
        nalgebra::UnitQuaternion::rotation_between(&diagonal, &nalgebra::Vector3::z()).unwrap();
    let centre = [0.0, 0.0, SIDE * 3f64.sqrt() / 2.0];
    let contacts = contacts_with_floor(cube("cube", centre).rotation(tilt));
    assert_eq!(contacts.len(), 1);
    assert_eq!(contacts[0].support.kind(), PolygonKind::Point);
    let corner = contacts[0]
        .frame
        .to_world(&contacts[0].support.vertices()[0]);
    assert!(corner.x.abs() < 1e-9 && corner.y.abs() < 1e-9 && corner.z.abs() < 1e-9);
}

#[test]
fn nearly_aligned_stacked_cubes_get_a_vertical_normal_and_a_shallow_depth() {
    // Two cubes on top of each other, 1 mm of overlap, the upper one turned by a hair.
    for twist in [0.0, 1e-6, 1e-3, 0.5] {
        let mut world = World::builder()
            .body(floor())
            .body(cube("base", [0.0, 0.0, 1.0]))
            .body(cube("top", [1e-4, -2e-4, 2.999]).rotation(rotation([0.3, 0.2, 1.0], twist)))
            .build()
            .unwrap();
        world.step(DT).unwrap();
        let c = between_cubes(&world);
        // The normal is one of the two faces' normals: within the top cube's tilt of vertical.
        let tilt = (world.bodies()[2].rotation() * nalgebra::Vector3::z())
            .z
            .acos();
        let off_vertical = c.frame.normal.z.abs().min(1.0).acos();
        assert!(
            off_vertical <= tilt + 1e-9,
            "twist {twist}: normal {:?}",
            c.frame.normal
        );
        let depth = c.depth();
        assert!(depth > 0.0 && depth < 0.01, "twist {twist}: depth {depth}");
        assert!(
            c.support.area() > 0.9 * SIDE * SIDE,
            "twist {twist}: area {}",
            c.support.area()
        );
    }
}

/// 48 random 10-point hulls dropped side by side onto the floor from up to 1 m, turned at
/// random, settled for 4 s at 60 Hz, then for the next second each floor contact's depth
/// against its hull's true lowest point: the same to 0.2 mm, the most a contact kept or
/// carried with its bodies may lag the poses (10 µm of motion kept, 0.1 mm of slip carried,
/// see `carry.rs`). A hull resting on two faces folded within the feature angle used to read
/// the least-squares plane between them, millimetres shallower than its fold (1.5 mm against
/// 5.7 on a pile), under the slop that would have pushed it out.
#[test]
fn resting_hulls_read_their_true_depth_in_the_floor() {
    use nalgebra::{Quaternion, UnitQuaternion};
    use tatami_world::dropped::{Random, mixed_shape};
    let mut random = Random::new(2024);
    let mut builder = World::builder().body(floor());
    for k in 0..48 {
        let (x, y) = ((k % 8) as f64 * 1.6 - 5.6, (k / 8) as f64 * 1.6 - 4.0);
        let turn = UnitQuaternion::from_quaternion(Quaternion::new(
            random.between(-1.0, 1.0),
            random.between(-1.0, 1.0),
            random.between(-1.0, 1.0),
            random.between(-1.0, 1.0),
        ));
        // The fourth shape of the cycle: a hull of 10 points in a 1 m cube.
        let hull = mixed_shape(&mut random, 3);
        builder = builder.body(
            tatami_world::BodyDesc::dynamic(hull)
                .mass(1.0)
                .position([x, y, 1.0 + random.between(0.0, 1.0)])
                .rotation(turn),
        );
    }
    let mut world = builder.build().unwrap();
    let dt = 1.0 / 60.0;
    let mut compared = 0;
    for step in 0..300 {
        world.step(dt).unwrap();
        if step < 240 {
            continue;
        }
        world.prepare_step(dt).unwrap();
        for contact in world.contacts().filter(|c| c.body_a.0 == 0) {
            let body = &world.bodies()[contact.body_b.0];
            let tatami_world::Shape::Convex { points } = body.shape() else {
                unreachable!("only hulls are dropped");
            };
            let lowest = points
                .iter()
                .map(|p| (body.position() + body.rotation() * p.coords).z)
                .fold(f64::INFINITY, f64::min);
            let error = (contact.depth() - -lowest).abs();
            assert!(
                error <= 2e-4,
                "step {step}: hull {} {} mm in the floor, its contact {} mm",
                contact.body_b.0,
                -lowest * 1e3,
                contact.depth() * 1e3
            );
            compared += 1;
        }
    }
    assert!(compared > 1000, "only {compared} floor contacts compared");
}

/// A hull whose bottom is a square with a shallow point under its middle (the point 6 mm below
/// the corners, 0.7 m out: faces 0.49° off flat, within the 1° feature angle, so the bottom is
/// one feature) set on a ramp tilted 10° and turned 40°, under every model: its point stays
/// within the 2 mm slop of the ramp's surface (plus 0.1 mm of the push's lag) for 3 s, and the
/// contact reads the point's depth to 0.2 mm (as the hulls of the test above). The outline of
/// the feature is the square; reading only its corners' own depths, the contact missed the
/// point, which sank its whole 6 mm into the ramp while the contact read 0.
#[test]
fn a_hull_with_a_shallow_point_under_its_face_rests_on_the_point() {
    use nalgebra::{Point3, Vector3};
    use tatami_world::{BodyDesc, ContactModel, Shape};
    let point_depth = 0.006;
    let mut points = vec![Point3::new(0.0, 0.0, -point_depth)];
    for (x, y) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
        points.extend([Point3::new(x, y, 0.0), Point3::new(x, y, 0.6)]);
    }
    let ramp = rotation([0.0, 0.0, 1.0], 40.0) * rotation([1.0, 0.0, 0.0], 10.0);
    let normal = ramp * Vector3::z();
    let slop = tatami_world::WorldSettings::default().contact.slop;
    for model in [
        ContactModel::Face,
        ContactModel::Patch,
        ContactModel::Vertex,
    ] {
        let start = normal * (point_depth + 0.001);
        let mut world = World::builder()
            .model(model)
            .body(
                BodyDesc::fixed(Shape::cuboid([10.0, 10.0, 1.0]))
                    .position((-normal * 0.5).into())
                    .rotation(ramp)
                    .friction(0.8),
            )
            .body(
                BodyDesc::dynamic(Shape::convex(points.clone()))
                    .mass(1.0)
                    .position(start.into())
                    .rotation(ramp * rotation([0.0, 0.0, 1.0], 25.0))
                    .friction(0.8),
            )
            .build()
            .unwrap();
        let dt = 1.0 / 60.0;
        let (mut deepest, mut worst_reading) = (0.0_f64, 0.0_f64);
        for _ in 0..180 {
            world.step(dt).unwrap();
            let body = &world.bodies()[1];
            let depth = points
                .iter()
                .map(|p| {
                    -(body.position() + body.rotation() * p.coords)
                        .coords
                        .dot(&normal)
                })
                .fold(f64::NEG_INFINITY, f64::max);
            deepest = deepest.max(depth);
            world.prepare_step(dt).unwrap();
            for contact in world.contacts() {
                worst_reading = worst_reading.max((contact.depth() - depth).abs());
            }
        }
        println!("{model:?}: deepest {deepest:e} m, contact off by up to {worst_reading:e} m");
        assert!(
            deepest <= slop + 1e-4,
            "{model:?}: {deepest} m into the ramp"
        );
        assert!(
            worst_reading <= 2e-4,
            "{model:?}: read {worst_reading} m off"
        );
    }
}
