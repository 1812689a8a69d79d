//! Errors of world building and stepping.

use tatami_contact::ContactError;
use tatami_lcp::LcpError;
use thiserror::Error;

/// Why a world, a body or the settings were rejected.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WorldError {
    /// A body's field is invalid.
    #[error("body `{body}`: {field}: {reason}")]
    InvalidBody {
        /// The body's name (or `#index` when unnamed).
        body: String,
        /// The offending field.
        field: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// A shape is invalid (size not positive, hull without volume…).
    #[error("{reason}")]
    InvalidShape {
        /// What is wrong with it.
        reason: String,
    },
    /// No body of the world has this handle (it was removed, or belongs to another world).
    #[error("no {0} in this world")]
    UnknownBody(crate::BodyId),
    /// The body's kind does not allow the action: only dynamic bodies take forces and impulses,
    /// and a fixed body has no velocity or target.
    #[error("body `{body}`: a {kind} body cannot {action}")]
    WrongKind {
        /// The body's name.
        body: String,
        /// `fixed`, `kinematic` or `dynamic`.
        kind: &'static str,
        /// What was asked.
        action: &'static str,
    },
    /// A world setting is invalid.
    #[error("setting {field}: {reason}")]
    InvalidSettings {
        /// The offending setting.
        field: &'static str,
        /// What is wrong with it.
        reason: String,
    },
}

/// Why a step failed. The world is left as it was before the step's integration.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum StepError {
    /// `dt` was zero, negative, not finite or longer than `MAX_TIME_STEP`.
    #[error("time step must be > 0 and at most 1 s, got {0}")]
    InvalidTimeStep(f64),
    /// A contact could not be turned into rows.
    #[error("contact {pair}: {source}")]
    Contact {
        /// The two bodies, `a–b`.
        pair: String,
        /// The contact model's error.
        source: ContactError,
    },
    /// The solver failed on a contact (non-finite value, unsupported projection, pivot limit).
    #[error("solver failed{}: {source}", pair.as_ref().map(|p| format!(" on contact {p}")).unwrap_or_default())]
    Solver {
        /// The two bodies of the contact the solver names, if it names one.
        pair: Option<String>,
        /// The solver's error.
        source: LcpError,
    },
    /// A body's state became non-finite.
    #[error("body `{body}` reached a non-finite state")]
    NonFiniteState {
        /// The body's name.
        body: String,
    },
}
