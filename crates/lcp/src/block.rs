//! Blocks (one contact's rows) and the projection trait the contact models implement.
//!
//! PGS updates a block's rows one at a time (a friction pair named by
//! [`Projection::tangent_pair`] as one 2-D update, or with the twist row named by
//! [`Projection::twist_coupling`] as one 3-D update); after each update it calls the block's
//! [`Projection::project`], naming the row that changed, and pushes whatever the projection moved
//! into the velocities. The block's impulses are thus admissible after every update, so the next
//! row never reacts to an impulse that is about to be clamped away (projecting only once per
//! block was tried and rejected: its fixed point is not the LCP's when a clamped row is coupled to
//! a later one). Bounds that depend on another row (friction on the normal impulse, the face
//! model's twist and centre of pressure on the normal force) live in the projection.
//!
//! The direct solver needs the admissible set as linear constraints: [`Projection::bound`] gives
//! it row by row when it is a product of [`RowBound`]s, and [`project_to_bounds`] is the PGS
//! projection of that same set, so both solvers solve one problem.

use std::ops::Range;

use crate::{BodyId, LinearSet};

/// The rows of one contact between bodies A and B, and how their impulses are projected.
#[derive(Debug, Clone, PartialEq)]
pub struct Block<P> {
    /// First body; rows' `*_a` Jacobian halves act on it.
    pub body_a: BodyId,
    /// Second body; rows' `*_b` Jacobian halves act on it.
    pub body_b: BodyId,
    /// Index range of the block's rows in [`Problem::rows`](crate::Problem::rows).
    pub rows: Range<usize>,
    /// Maps the block's impulses onto its admissible set.
    pub projection: P,
}

impl<P> Block<P> {
    /// Whether its row range and bodies lie within a problem of `rows` rows and `bodies`
    /// bodies.
    pub(crate) fn within(&self, rows: usize, bodies: usize) -> bool {
        self.rows.start <= self.rows.end
            && self.rows.end <= rows
            && self.body_a.0 < bodies
            && self.body_b.0 < bodies
    }
}

/// The admissible impulses of one row, possibly scaled by another row of the same block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RowBound {
    /// `λ ≥ 0`, complementary to `w ≥ target`: a normal row.
    NonNegative,
    /// `|λ| ≤ coefficient · λ_normal`, with `normal` the index of a [`RowBound::NonNegative`] row
    /// *within the block*: a friction or twist row (box friction, one axis at a time).
    Friction {
        /// Row index, within the block, of the normal impulse that scales the bound.
        normal: usize,
        /// Friction coefficient (times a lever arm for a twist row), ≥ 0.
        coefficient: f64,
    },
    /// `lo ≤ λ ≤ hi`, constant bounds (either may be infinite).
    Box {
        /// Lower bound.
        lo: f64,
        /// Upper bound.
        hi: f64,
    },
}

/// A friction pair and a twist row bounded by one limit surface (a contact face's, in the
/// ellipsoidal model of planar sliding): with `p` the point the friction force acts at, relative
/// to where the pair's rows measure velocity, the twist about `p` is `τ′ = τ − (p × f)·n`, and
/// the admissible `(f₁, f₂, τ′/r̄)` form a ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwistCoupling {
    /// The twist row's index within the block.
    pub row: usize,
    /// `r̄` (m): the twist bound per unit of the friction bound, so `τ′/r̄` weighs like a force.
    pub radius: f64,
    /// `p` (m), in the tangent pair's axes.
    pub centre: [f64; 2],
}

/// How a block's impulses are mapped onto its admissible set during a sweep.
pub trait Projection {
    /// Projects `impulses` (the block's rows, in order) in place after row `changed` was updated
    /// (for a [`tangent_pair`](Projection::tangent_pair), `changed` is its first row).
    fn project(&mut self, impulses: &mut [f64], changed: usize);

    /// The first of two rows (`k`, `k + 1`) that PGS updates together, as one 2-D step, before
    /// projecting: the two tangent rows of an isotropic friction disc. `None` (the default)
    /// updates every row alone, which is right for bounds that are a product of row bounds.
    ///
    /// Updating the pair row by row and then clamping the disc lets the first row take the whole
    /// friction budget: the fixed point is off the slip direction. See [`crate::pgs`] for the
    /// 2-D step and why its fixed point is Coulomb's maximal dissipation.
    fn tangent_pair(&self) -> Option<usize> {
        None
    }

    /// The twist row that the [`tangent_pair`](Projection::tangent_pair) shares one limit
    /// surface with, for `impulses` (the block's current ones), if any: a contact face's
    /// friction force and twist bounded together, `|f|² + (τ′/r̄)² ≤ (μ f_n)²`. PGS then
    /// updates the pair and that row as one 3-D step (see [`crate::pgs`]); `None` (the default)
    /// updates the twist row alone.
    fn twist_coupling(&self, impulses: &[f64]) -> Option<TwistCoupling> {
        let _ = impulses;
        None
    }

    /// How many of the block's first rows are its normal rows, with the promise that
    /// [`project`](Projection::project) clamps each of them at zero from below and, while they
    /// are all zero, sets every other row to zero too — a contact cone, where friction and
    /// torques need a normal force. PGS then ends a block's update once its normal rows have
    /// left every impulse at zero (a contact parting, or not yet loaded): the other rows' steps
    /// would all be projected back to zero; and it skips a block that carries nothing when its
    /// normal rows' steps would all be clamped back to zero. 0 (the default) makes no such
    /// promise.
    fn leading_normal_rows(&self) -> usize {
        0
    }

    /// Whether PGS should first try the whole block at once (see [`crate::pgs`]): solve its
    /// rows together with the block's own effective mass `K⁻¹`, and keep that step when it
    /// lands in the admissible set ([`admissible`](Projection::admissible)). Blocks of at most
    /// [`crate::pgs::WHOLE_BLOCK_ROWS`] rows only. `false` by default.
    fn whole_block(&self) -> bool {
        false
    }

    /// Whether `impulses` lie in the admissible set already, so [`project`](Projection::project)
    /// would leave them as they are. Only asked of blocks that say
    /// [`whole_block`](Projection::whole_block); `false` by default.
    fn admissible(&mut self, impulses: &[f64]) -> bool {
        let _ = impulses;
        false
    }

    /// Row `row`'s bound, if the admissible set is a product of row bounds; `None` otherwise.
    fn bound(&self, row: usize) -> Option<RowBound>;

    /// The admissible set of a block of `rows` rows as linear constraints, for the direct
    /// solver; `None` if it has none (the direct solver then rejects the block). By default the
    /// set of the row bounds ([`LinearSet::from_bounds`]).
    fn linear_set(&self, rows: usize) -> Option<LinearSet> {
        LinearSet::from_bounds(rows, |k| self.bound(k))
    }
}

/// Projects `impulses` onto the bounds given by `bound_of`: normal rows first, then the rows
/// whose bounds depend on them, so friction sees the clamped normal impulse. Rows without a bound
/// are left alone. Never panics: `max`/`min` rather than `clamp`, so a NaN stays visible to the
/// solver's finiteness check.
pub fn project_to_bounds(bound_of: impl Fn(usize) -> Option<RowBound>, impulses: &mut [f64]) {
    for (k, impulse) in impulses.iter_mut().enumerate() {
        if let Some(RowBound::NonNegative) = bound_of(k) {
            *impulse = impulse.max(0.0);
        }
    }
    for k in 0..impulses.len() {
        match bound_of(k) {
            Some(RowBound::Friction {
                normal,
                coefficient,
            }) => {
                let limit = coefficient * impulses[normal].max(0.0);
                impulses[k] = impulses[k].max(-limit).min(limit);
            }
            Some(RowBound::Box { lo, hi }) => impulses[k] = impulses[k].max(lo).min(hi),
            Some(RowBound::NonNegative) | None => {}
        }
    }
}

/// A projection given by one [`RowBound`] per row.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundsProjection(pub Vec<RowBound>);

impl Projection for BoundsProjection {
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        project_to_bounds(|k| self.0.get(k).copied(), impulses);
    }

    fn bound(&self, row: usize) -> Option<RowBound> {
        self.0.get(row).copied()
    }
}
