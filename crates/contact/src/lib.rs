//! Contact models: from one contact (two bodies, a frame, the support polygon, depths and a
//! material) to constraint rows and the block projections that keep their impulses physical.
//!
//! Every model sees the same [`Contact`]; they differ in the rows they emit:
//! - [`ContactModel::Vertex`] — one point constraint per support-polygon vertex: a normal row
//!   `λₙ ≥ 0` and two friction rows bounded by `μ λₙ` (box or circular cone). 3 rows per vertex.
//! - [`ContactModel::Patch`] — a normal row per vertex; friction and twist rows at the friction
//!   centre bounded by the total normal impulse. `k + 3` rows.
//! - [`ContactModel::Face`] — the paper's method: one 6-row constraint at the support polygon's
//!   centroid; twist bounded by torsional friction, tilt by keeping the centre of pressure (ZMP)
//!   in the polygon — the part of it that bears ([`face::bearing_contact`]) when a face tilted
//!   within the feature angle stands off at one side. 6 rows per face, whatever its vertex
//!   count; a segment's block has 5 (the tilt across it: [`segment`]) and a point's 3 (no
//!   torque). Points standing off the support within the margin, where it would land as it
//!   turns (a tilted face's far corners, a cylinder's rim beside the one point it rests on, a
//!   fast polyhedron's vertices within its step's closing distance, [`Contact::landing`]), and
//!   the vertices a support tipping about its centre would sink,
//!   get a point's 3 rows each, which let them close their gap within the step and no more.
//!
//! Beside any model's blocks, a [`grip`] bears the friction of a contact that a body which
//! cannot give way (a kinematic body) presses in beyond the slop: the world adds one where a
//! gripper's fingers squeeze a body, which split impulses would otherwise leave without a
//! normal force to grip with.
//!
//! Friction rows target no slip; where a face rests on a face and the two bodies turn together
//! (a box on a turntable), they target the relative velocity that keeps the faces' material
//! points together over the step, which semi-implicit Euler's straight-line moves of the
//! bodies' centres would otherwise part (see `jacobian::weld_velocity`).
//!
//! A point row holds each body's own point: where the bodies overlap, each one's surface, half
//! the depth either side of the contact plane. Given the bodies' turns over the step
//! ([`ContactModel::build_rows_turned`]), a point row also takes off how far those turns swing
//! its points off straight lines ([`turns`]): a top spun on its tip stays up.
//!
//! Rows are written into a [`tatami_lcp::Problem`] whose blocks carry a [`ContactProjection`],
//! so one problem holds contacts of any model and any solver of the LCP crate can solve it.
//! [`ContactModel::build_rows`] writes them instead into a [`ContactRows`]: rows, blocks and
//! biases of the caller's own beside the bodies they read, so that several threads can each
//! build contacts apart and the pieces be joined in order ([`ContactRows::append`]) into the
//! problem a single pass builds.
//!
//! ```
//! use nalgebra::{Point2, Point3, Vector3};
//! use tatami_contact::{Contact, ContactFrame, ContactModel, ContactSettings, Material};
//! use tatami_geometry::ConvexPolygon;
//! use tatami_lcp::{BodyId, Problem, SolverBody, pgs};
//!
//! // A 1 kg body resting on the fixed ground through a 2 m square, after gravity's push.
//! let mut cube = SolverBody::fixed();
//! cube.inv_mass = 1.0;
//! cube.inv_inertia_world = nalgebra::Matrix3::identity() * 1.5;
//! let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
//! let contact = Contact {
//!     body_a: BodyId(0),
//!     body_b: BodyId(1),
//!     centre_a: Point3::new(0.0, 0.0, 1.0),
//!     centre_b: Point3::new(0.0, 0.0, -1.0),
//!     frame: ContactFrame::from_normal(Point3::origin(), Vector3::z())?,
//!     support: ConvexPolygon::from_points(&square)?,
//!     depths: vec![0.0; 4],
//!     material: Material::new(0.5, 0.5, 0.0)?,
//!     landing: Vec::new(),
//!     bounce_speed: 0.0,
//! };
//! let mut problem = Problem { bodies: vec![cube, SolverBody::fixed()], ..Default::default() };
//! ContactModel::Vertex.build(&contact, 0.01, &ContactSettings::default(), &mut problem)?;
//! assert_eq!(problem.rows.len(), 12);
//!
//! problem.bodies[0].linear_velocity.z = -0.098; // one step of gravity
//! pgs::solve(&mut problem)?;
//! // 15 Gauss–Seidel sweeps over four coupled points leave a small residual.
//! let vz = problem.bodies[0].linear_velocity.z;
//! assert!(vz.abs() < 1e-3 * 0.098, "vz = {vz}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod bearing;
mod contact;
mod error;
pub mod face;
mod frame;
pub mod grip;
mod impulse;
mod jacobian;
mod limit_surface;
mod material;
mod model;
pub mod patch;
pub mod planar_sliding;
mod point_friction;
mod projection;
mod rows;
pub mod segment;
mod settings;
mod target;
pub mod turns;
pub mod vertex;

pub use bearing::{BEARING_DEPTH, BEARING_DEPTH_PER_WIDTH, bearing_depth};
pub use contact::{Contact, Landing};
pub use error::ContactError;
pub use frame::ContactFrame;
pub use impulse::ContactImpulse;
pub use material::Material;
pub use model::ContactModel;
pub use point_friction::PointFriction;
pub use projection::ContactProjection;
pub use rows::ContactRows;
pub use settings::{
    ContactSettings, DEFAULT_BIAS_RATE, DEFAULT_MAX_DEPENETRATION_SPEED, DEFAULT_MAX_VELOCITY_BIAS,
    DEFAULT_SLOP, FrictionCone, FrictionLimit, TwistCentre, TwistRadius,
};
pub use turns::{RESTING_SPEED, Turns};
