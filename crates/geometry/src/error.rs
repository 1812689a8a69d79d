//! Errors of the geometry crate.

use thiserror::Error;

/// Why a polygon or a query was rejected.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeometryError {
    /// [`ConvexPolygon::from_points`](crate::ConvexPolygon::from_points) was given no points.
    #[error("a polygon needs at least one point, got none")]
    NoPoints,
    /// A coordinate was NaN or infinite.
    #[error("point {index} has a non-finite coordinate ({x}, {y})")]
    NonFinitePoint {
        /// Position of the offending point in the input slice.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// A coordinate's size exceeded [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    #[error("point {index} ({x}, {y}) is farther than {max:e} from the origin along an axis")]
    OutOfRange {
        /// Position of the offending point in the input slice.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
        /// The limit, [`MAX_COORDINATE`](crate::MAX_COORDINATE).
        max: f64,
    },
    /// A grid spacing was zero, negative or not finite.
    #[error("grid spacing must be finite and positive, got {0}")]
    InvalidSpacing(f64),
}
