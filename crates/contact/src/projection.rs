//! One projection type for the blocks of every contact model, so one problem holds them all.

use tatami_lcp::{Projection, RowBound};

use crate::PointFriction;

/// The projection of one contact block, by model.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactProjection {
    /// A point contact of the vertex model: rows normal, t1, t2.
    Point(PointFriction),
}

impl Projection for ContactProjection {
    fn project(&mut self, impulses: &mut [f64], row_velocity: &[f64], changed: usize) {
        match self {
            Self::Point(p) => p.project(impulses, row_velocity, changed),
        }
    }

    fn bound(&self, row: usize) -> Option<RowBound> {
        match self {
            Self::Point(p) => p.bound(row),
        }
    }
}
