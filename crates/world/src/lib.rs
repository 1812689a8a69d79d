//! A rigid-body world on Tatami's contact models (vertex, patch, face — the default): bodies
//! with box, sphere, cylinder and convex-hull shapes, collision with parry3d whose support
//! polygons keep every vertex of the face-face overlap, semi-implicit Euler stepping, and scene
//! files.
//!
//! A step is `collision → contact rows → velocity solve → position correction → integrate`
//! (see [`World::step`]). One persistent contact set owns every touching pair across steps —
//! its contact, what its last solve left for the warm start (the face model's block as one
//! impulse on a body; the vertex and patch models' rows by the feature id of the support vertex
//! they act at) — and its order is the solver's. The integrator turns each body by a
//! free-rotation step that conserves its angular momentum, so tumbling bodies precess and flip
//! as Euler's equations say. Each stage is timed ([`World::timings`]) so experiments can time
//! the solver call alone.
//!
//! Between steps a program drives the world through [`BodyId`] handles: poses and velocities,
//! forces, torques and impulses, kinematic bodies ([`BodyDesc::kinematic`]) and their targets,
//! removal, and each contact's wrench read back ([`World::contact_wrenches`]). Bodies at rest
//! may fall asleep in islands ([`Sleeping`], off by default) and wake on contact or any control
//! call.

mod apart;
mod body;
mod bounce_guard;
mod box_feature;
mod box_sat;
mod broad_phase;
mod builder;
mod carry;
mod collision;
mod contact_set;
mod control;
pub mod dropped;
mod error;
pub mod heavy_top;
mod held_handoff;
mod impact;
mod load_estimate;
mod nearly_sorted;
mod parallel;
mod parry_bridge;
mod press;
mod proved_normal;
mod rewind;
mod rotation;
mod rows;
mod sat;
pub mod scene;
mod settings;
mod shape;
mod sleep;
mod speculative;
mod substeps;
mod support;
mod timings;
mod tolerances;
mod world;
mod wrench;

pub use body::{
    Body, BodyDesc, BodyId, BodyKind, DEFAULT_DENSITY, DEFAULT_FRICTION, MASSES, MassSpec,
    POSITION_LIMIT, SPEED_LIMIT,
};
pub use builder::{DEFAULT_GRAVITY, GRAVITY_LIMIT, WorldBuilder};
pub use error::{StepError, WorldError};
pub use settings::{
    MAX_ITERATIONS, MAX_SUBSTEPS, PGS_ITERATIONS, PGS_TOLERANCE, SUBSTEP_LIMIT, Solver,
    WorldSettings,
};
pub use shape::{HullMesh, LENGTHS, MassProperties, Shape};
pub use sleep::{SLEEP_DEPTH_TOLERANCE, Sleeping};
pub use substeps::{MAX_SUBSTEP_TURN, SAG_SHARE};
pub use tatami_contact::{
    ContactModel, ContactProjection, ContactSettings, FrictionCone, FrictionLimit, TwistCentre,
};
pub use tatami_lcp::direct::{DirectInfo, DirectParams};
pub use tatami_lcp::pgs::{PgsParams, WarmStart};
pub use timings::StepTimings;
pub use world::{MAX_TIME_STEP, World};
pub use wrench::ContactWrench;
