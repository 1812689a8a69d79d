//! The force-sensor read-out: what each contact transmitted over the last step, in world units.
//!
//! Whatever the model (a normal per corner, normals plus friction at the centre, or the face
//! model's single block), a contact's rows sum to one wrench on body A. Written at the
//! frame origin `O` as a force `F` and a torque `T_O`, its normal part `f = F·n` has its centre
//! of pressure where the moment of `f n` equals the in-plane part of `T_O`:
//! `p = O + n × T_O / f`. About `p` what is left of the torque is along `n` — the twist. For the
//! face model `p` is the ZMP after its projection onto the support polygon.

use nalgebra::{Point3, Vector3};
use tatami_contact::{Contact, ContactImpulse};
use tatami_lcp::Row;

use crate::BodyId;

/// One contact's wrench over the last step: the average force and torque body B exerted on
/// body A (A gets `force`, B gets `−force`), from the solved impulses divided by the step.
///
/// ```
/// use tatami_world::{BodyDesc, Shape, World};
/// let mut world = World::builder()
///     .body(BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 1.0])).position([0.0, 0.0, -0.5]))
///     .body(BodyDesc::dynamic(Shape::cuboid([1.0; 3])).mass(2.0).position([0.3, 0.2, 0.5]))
///     .build()?;
/// for _ in 0..100 {
///     world.step(0.01)?;
/// }
/// let wrench = world.contact_wrenches().next().expect("the cube rests on the slab");
/// let weight = 2.0 * 9.8;
/// assert!((wrench.normal_force - weight).abs() < 1e-6 * weight);
/// let under = wrench.centre_of_pressure - world.bodies()[1].centre_of_mass();
/// assert!(under.xy().norm() < 1e-6, "the centre of pressure is under the centre of mass");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ContactWrench {
    /// The body pushed along `+normal`.
    pub body_a: BodyId,
    /// The body pushed along `−normal`.
    pub body_b: BodyId,
    /// Unit contact normal, from B into A.
    pub normal: Vector3<f64>,
    /// The contact frame's tangents, `tangents[1] = normal × tangents[0]`.
    pub tangents: [Vector3<f64>; 2],
    /// Force on A (N).
    pub force: Vector3<f64>,
    /// Torque on A about the centre of pressure (N m); along `normal`.
    pub torque: Vector3<f64>,
    /// Where the normal force acts (world); the support polygon's origin when it is zero.
    pub centre_of_pressure: Point3<f64>,
    /// `force · normal` (N), ≥ 0; with a grip's press (the force a kinematic body's overlap
    /// presses with, [`tatami_contact::grip`]) added to the rows'.
    pub normal_force: f64,
    /// `force` along the two tangents (N).
    pub friction_force: [f64; 2],
    /// `torque · normal` (N m): torsional friction.
    pub twist_torque: f64,
    /// The support polygon's vertices (world), counter-clockwise seen from `+normal`.
    pub support: Vec<Point3<f64>>,
}

impl ContactWrench {
    /// The wrench of `contact` whose rows, solved over a step of `dt`, are `rows`, with the
    /// `press` (N s) of its grip, if it has one ([`tatami_contact::grip`]): the impulse along
    /// the normal at the support's centroid that a kinematic body's overlap presses with.
    pub(crate) fn new(
        contact: &Contact,
        (rows, press): (&[Row], f64),
        dt: f64,
        ids: [BodyId; 2],
    ) -> Self {
        let frame = &contact.frame;
        let impulse = ContactImpulse::of_rows(rows, contact.centre_a);
        let pressed = frame.normal * press;
        let centroid = frame.to_world(&contact.support.centroid());
        let force = (impulse.linear + pressed) / dt;
        // About the frame origin rather than A's centre of mass.
        let torque_origin = (impulse.angular + (centroid - contact.centre_a).cross(&pressed)) / dt
            + (contact.centre_a - frame.origin).cross(&force);
        let n = frame.normal;
        let normal_force = force.dot(&n);
        let offset = if normal_force > 0.0 {
            n.cross(&torque_origin) / normal_force
        } else {
            Vector3::zeros()
        };
        let torque = torque_origin - offset.cross(&force);
        Self {
            body_a: ids[0],
            body_b: ids[1],
            normal: n,
            tangents: [frame.tangent1, frame.tangent2],
            force,
            torque,
            centre_of_pressure: frame.origin + offset,
            normal_force,
            friction_force: [force.dot(&frame.tangent1), force.dot(&frame.tangent2)],
            twist_torque: torque.dot(&n),
            support: contact
                .support
                .vertices()
                .iter()
                .map(|v| frame.to_world(v))
                .collect(),
        }
    }
}
