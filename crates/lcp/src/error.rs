//! Errors of the solver layer.

use thiserror::Error;

use crate::BodyId;

/// Why a solve stopped without an answer.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LcpError {
    /// Lemke's method left along an unbounded ray: it found no solution (the problem may have
    /// none, as when `A` has a non-positive row against a negative `q`).
    #[error("Lemke's method ended on a ray after {pivots} pivots: no solution found")]
    RayTermination {
        /// Pivots made before the ray was met.
        pivots: usize,
    },
    /// Every answer the direct solver found (of the problem, then of it regularised) missed
    /// complementarity by more than its tolerance.
    #[error("the direct solver's best answer has a relative residual of {residual:e}")]
    Inaccurate {
        /// The first answer's relative residual.
        residual: f64,
    },
    /// The pivot budget ran out.
    #[error("Lemke's method did not finish within {limit} pivots")]
    PivotLimit {
        /// The budget that was given.
        limit: usize,
    },
    /// The pivots overflowed f64: entries far apart in size (1e300 beside 1) made the answer
    /// infinite.
    #[error("Lemke's method overflowed after {pivots} pivots: the problem is too badly scaled")]
    Overflow {
        /// Pivots made.
        pivots: usize,
    },
    /// A matrix or vector entry was NaN or infinite.
    #[error("non-finite entry in the {what}")]
    NonFiniteInput {
        /// Which input: `"matrix"`, `"vector q"`, `"bounds"`.
        what: &'static str,
    },
    /// Sizes of the inputs do not agree.
    #[error("dimension mismatch: {what}")]
    DimensionMismatch {
        /// What disagreed, in words.
        what: String,
    },
    /// A lower bound exceeds its upper bound.
    #[error("row {row} has lower bound {lo} above upper bound {hi}")]
    InvalidBounds {
        /// The row.
        row: usize,
        /// Its lower bound.
        lo: f64,
        /// Its upper bound.
        hi: f64,
    },
    /// A body's mass properties or velocity were not finite, or its velocity overflowed in
    /// the solve.
    #[error("body {} has a non-finite mass property or velocity", body.0)]
    NonFiniteBody {
        /// The body.
        body: BodyId,
    },
    /// A block's rows or impulses became (or were given) non-finite.
    #[error("block {block} has a non-finite Jacobian, target or impulse")]
    NonFinite {
        /// Index of the block (one contact).
        block: usize,
    },
    /// A block's rows do not follow the previous block's or name an unknown body.
    #[error("block {block} does not match the rows or bodies of the problem")]
    MalformedBlock {
        /// Index of the block.
        block: usize,
    },
    /// The direct solver's dense matrices would exceed its memory budget.
    #[error(
        "the direct problem has {variables} unknowns and needs {bytes} bytes of dense storage, \
         over the budget of {budget} bytes; use the PGS solver for a problem this size"
    )]
    TooLarge {
        /// Variables of the standard LCP.
        variables: usize,
        /// Bytes the dense matrices would take.
        bytes: usize,
        /// The budget ([`DirectParams::memory_budget`](crate::direct::DirectParams)).
        budget: usize,
    },
    /// The direct solver met a block whose admissible set has no linear form
    /// ([`Projection::linear_set`](crate::Projection::linear_set) gave `None` or a malformed set).
    #[error(
        "block {block} has no linear form of its admissible set, which the direct solver needs"
    )]
    Unsupported {
        /// Index of the block.
        block: usize,
    },
}
