//! Errors of the contact crate.

use thiserror::Error;

/// Why a contact or its material was rejected.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ContactError {
    /// A friction coefficient was negative or not finite.
    #[error("{which} friction must be finite and ≥ 0, got {value}")]
    InvalidFriction {
        /// `"static"` or `"kinetic"`.
        which: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A restitution coefficient was outside `[0, 1]` or not finite.
    #[error("restitution must be finite and in [0, 1], got {0}")]
    InvalidRestitution(f64),
    /// A contact's bounce speed was negative or not finite.
    #[error("bounce speed must be finite and ≥ 0, got {0}")]
    InvalidBounceSpeed(f64),
    /// A contact normal was zero or not finite.
    #[error("contact normal must be finite and non-zero, got ({0}, {1}, {2})")]
    InvalidNormal(f64, f64, f64),
    /// The contact's depths do not match its support polygon's vertices.
    #[error("contact has {depths} depths for {vertices} support vertices")]
    DepthCount {
        /// Number of depths given.
        depths: usize,
        /// Number of support-polygon vertices.
        vertices: usize,
    },
    /// A contact quantity (centre, origin, depth, a body's turn) was not finite.
    #[error("contact {what} is not finite")]
    NonFinite {
        /// Which quantity.
        what: &'static str,
    },
    /// The time step was zero, negative or not finite.
    #[error("time step must be finite and > 0, got {0}")]
    InvalidTimeStep(f64),
    /// A contact names a body the problem does not have.
    #[error("contact refers to body {body}, but the problem has {bodies} bodies")]
    UnknownBody {
        /// The body index.
        body: usize,
        /// Number of bodies in the problem.
        bodies: usize,
    },
}
