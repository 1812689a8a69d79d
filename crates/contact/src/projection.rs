//! One projection type for the blocks of every contact model, so one problem holds them all.

use tatami_lcp::{LinearSet, Projection, RowBound, TwistCoupling};

use crate::PointFriction;
use crate::face::FaceProjection;
use crate::grip::GripProjection;
use crate::patch::PatchProjection;
use crate::segment::SegmentProjection;

/// The projection of one contact block, by model.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactProjection {
    /// A point contact of the vertex model: rows normal, t1, t2.
    Point(PointFriction),
    /// A patch-model contact: normal rows per vertex, then f1, f2, twist.
    Patch(PatchProjection),
    /// A face-model contact: rows f3, f1, f2, τ1, τ2, τ3.
    Face(FaceProjection),
    /// A face-model contact on a segment: rows f3, f1, f2, τu, τ3 ([`crate::segment`]).
    Segment(SegmentProjection),
    /// The friction of a contact pressed in by a body that cannot give way, beside the
    /// model's blocks: rows f1, f2 and maybe τ3 ([`crate::grip`]).
    Grip(GripProjection),
}

impl Projection for ContactProjection {
    #[inline]
    fn project(&mut self, impulses: &mut [f64], changed: usize) {
        match self {
            Self::Point(p) => p.project(impulses, changed),
            Self::Patch(p) => p.project(impulses, changed),
            Self::Face(p) => p.project(impulses, changed),
            Self::Segment(p) => p.project(impulses, changed),
            Self::Grip(p) => p.project(impulses, changed),
        }
    }

    #[inline]
    fn tangent_pair(&self) -> Option<usize> {
        match self {
            Self::Point(p) => p.tangent_pair(),
            Self::Patch(p) => p.tangent_pair(),
            Self::Face(p) => p.tangent_pair(),
            Self::Segment(p) => p.tangent_pair(),
            Self::Grip(p) => p.tangent_pair(),
        }
    }

    #[inline]
    fn twist_coupling(&self, impulses: &[f64]) -> Option<TwistCoupling> {
        match self {
            Self::Face(p) => p.twist_coupling(impulses),
            Self::Segment(p) => p.twist_coupling(impulses),
            Self::Grip(p) => p.twist_coupling(impulses),
            Self::Point(_) | Self::Patch(_) => None,
        }
    }

    #[inline]
    fn leading_normal_rows(&self) -> usize {
        match self {
            Self::Point(p) => p.leading_normal_rows(),
            Self::Patch(p) => p.leading_normal_rows(),
            Self::Face(p) => p.leading_normal_rows(),
            Self::Segment(p) => p.leading_normal_rows(),
            Self::Grip(p) => p.leading_normal_rows(),
        }
    }

    #[inline]
    fn whole_block(&self) -> bool {
        match self {
            Self::Face(p) => p.whole_block(),
            Self::Segment(p) => p.whole_block(),
            Self::Point(_) | Self::Patch(_) | Self::Grip(_) => false,
        }
    }

    #[inline]
    fn admissible(&mut self, impulses: &[f64]) -> bool {
        match self {
            Self::Face(p) => p.admissible(impulses),
            Self::Segment(p) => p.admissible(impulses),
            Self::Point(_) | Self::Patch(_) | Self::Grip(_) => false,
        }
    }

    fn bound(&self, row: usize) -> Option<RowBound> {
        match self {
            Self::Point(p) => p.bound(row),
            Self::Patch(p) => p.bound(row),
            Self::Face(p) => p.bound(row),
            Self::Segment(p) => p.bound(row),
            Self::Grip(p) => p.bound(row),
        }
    }

    fn linear_set(&self, rows: usize) -> Option<LinearSet> {
        match self {
            Self::Point(p) => p.linear_set(rows),
            Self::Patch(p) => p.linear_set(rows),
            Self::Face(p) => p.linear_set(rows),
            Self::Segment(p) => p.linear_set(rows),
            Self::Grip(p) => p.linear_set(rows),
        }
    }
}
