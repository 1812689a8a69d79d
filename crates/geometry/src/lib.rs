//! Two-dimensional convex support polygons for face contact.
//!
//! When two bodies touch face to face, the overlap of the touching features, drawn in the contact
//! plane, is the *support polygon* `S`. The face contact model needs four things from it, and this
//! crate provides each in its own file:
//!
//! - [`polygon`]: `S` itself — a convex hull, counter-clockwise, that keeps every corner and
//!   degrades gracefully to a segment (edge contact) or a point (corner contact);
//! - [`area`]: signed area (paper eq. 17), area, centroid, and the exact mean distance
//!   `r̄ = (1/A) ∫_S |x − c| dA` that bounds torsional friction (paper eqs. 7–9 use a grid; the
//!   grid form is kept for reproduction);
//! - [`locate`]: the paper's fan-sector binary search (§3.2.2.1) — which sector of the fan around
//!   the centroid a point lies in, and whether it is inside, in O(log n);
//! - [`nearest`]: the nearest point of `S` to a point outside it (§3.2.3), where the centre of
//!   pressure is moved when it leaves the support.
//!
//! [`brute_force`] holds the obvious O(n) versions used as references by tests and benchmarks.
//!
//! ```
//! use nalgebra::Point2;
//! use tatami_geometry::ConvexPolygon;
//!
//! let square = ConvexPolygon::from_points(&[
//!     Point2::new(-1.0, -1.0), Point2::new(1.0, -1.0),
//!     Point2::new(1.0, 1.0), Point2::new(-1.0, 1.0),
//!     Point2::new(0.0, -1.0), // on an edge: dropped
//! ])?;
//! assert_eq!(square.vertices().len(), 4);
//! assert!(square.contains(&Point2::new(0.5, 0.5)));
//! assert_eq!(square.nearest_point(&Point2::new(3.0, 0.0)), Point2::new(1.0, 0.0));
//! // r̄ of a square of side a is a(√2 + ln(1 + √2))/6 ≈ 0.3826 a.
//! assert!((square.mean_distance(&Point2::origin()) - 2.0 * 0.382_597_858).abs() < 1e-8);
//! # Ok::<(), tatami_geometry::GeometryError>(())
//! ```

pub mod area;
pub mod brute_force;
mod error;
mod kept;
pub mod locate;
pub mod nearest;
pub mod polygon;

pub use area::signed_area;
pub use error::GeometryError;
pub use locate::{Location, Sector};
pub use polygon::{ConvexPolygon, MAX_COORDINATE, PolygonKind};
