//! The solver layer: constraint rows, projected Gauss–Seidel, and a pivoting direct solver.
//!
//! It knows rows, blocks and the velocities of bodies; it knows nothing of geometry or contact
//! models. A contact model builds, for each contact, a [`Block`] of [`Row`]s between bodies A and
//! B and a [`Projection`] that maps the block's impulses onto its admissible set (normal ≥ 0,
//! friction bounded by the normal, …). Conventions (DESIGN §1): a row's velocity is `w = J v`,
//! the row wants `w⁺ = target`, and an impulse `λ` changes the velocities by `M⁻¹ Jᵀ λ`.
//!
//! - [`pgs`]: sequential impulses, the real-time solver (paper: 15 sweeps).
//! - [`direct`]: the same contact problem solved exactly by [`lemke`](fn@lemke) on an equivalent
//!   standard LCP, the reference for PGS error.
//! - [`dense`]: `A = J M⁻¹ Jᵀ`, `b` and the dense boxed PGS [`pgs_dense`].
//! - [`residual`]: complementarity, feasibility and error metrics.
//!
//! ```
//! use nalgebra::{DMatrix, DVector};
//!
//! // z ≥ 0, w = A z + q ≥ 0, zᵀw = 0 (Murty's 2×2 example): z = (4/3, 7/3), w = 0.
//! let a = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
//! let q = DVector::from_vec(vec![-5.0, -6.0]);
//! let z = tatami_lcp::lemke(&a, &q, 100)?;
//! assert!((z[0] - 4.0 / 3.0).abs() < 1e-12 && (z[1] - 7.0 / 3.0).abs() < 1e-12);
//! # Ok::<(), tatami_lcp::LcpError>(())
//! ```

mod block;
mod body;
pub mod dense;
pub mod direct;
mod error;
mod island;
pub mod lemke;
pub mod linear_set;
pub mod pgs;
mod quiet;
pub mod residual;
mod row;

pub use block::{Block, BoundsProjection, Projection, RowBound, TwistCoupling, project_to_bounds};
pub use body::{BodyId, SolverBody};
pub use dense::pgs_dense;
pub use error::LcpError;
pub use island::DisjointSets;
pub use lemke::lemke;
pub use linear_set::{Budget, LinearSet};
pub use row::{Jacobian, Row};

/// Whether every value is finite, without a branch per value (`&`, not `&&`): bodies and rows
/// are checked before every solve.
fn all_finite(values: &[f64]) -> bool {
    values.iter().fold(true, |all, x| all & x.is_finite())
}

/// Bodies, rows and blocks: one velocity-level contact problem.
///
/// Rows of block `k` are `rows[blocks[k].rows.clone()]`. The solvers write impulses into the rows
/// and the resulting velocities into the bodies.
#[derive(Debug, Clone)]
pub struct Problem<P> {
    /// Every body a row may touch; fixed bodies have zero inverse mass and inertia.
    pub bodies: Vec<SolverBody>,
    /// All rows, grouped contiguously by block.
    pub rows: Vec<Row>,
    /// One block per contact (or per contact point, for the vertex model).
    pub blocks: Vec<Block<P>>,
}

impl<P> Default for Problem<P> {
    fn default() -> Self {
        Self {
            bodies: Vec::new(),
            rows: Vec::new(),
            blocks: Vec::new(),
        }
    }
}

impl<P> Problem<P> {
    /// Checks indices and finiteness before a solve, naming the first offender.
    pub fn validate(&self) -> Result<(), LcpError> {
        self.validate_bodies()?;
        let mut next_row = 0;
        for (block, b) in self.blocks.iter().enumerate() {
            if b.rows.start != next_row || !b.within(self.rows.len(), self.bodies.len()) {
                return Err(LcpError::MalformedBlock { block });
            }
            if self.rows[b.rows.clone()].iter().any(|r| !r.is_finite()) {
                return Err(LcpError::NonFinite { block });
            }
            next_row = b.rows.end;
        }
        if next_row != self.rows.len() {
            return Err(LcpError::MalformedBlock {
                block: self.blocks.len(),
            });
        }
        Ok(())
    }
}

impl<P> Problem<P> {
    /// Every body's mass properties and velocities are finite: checked before a solve, and
    /// after it, since huge but finite rows and masses can overflow the velocities.
    pub(crate) fn validate_bodies(&self) -> Result<(), LcpError> {
        match self.bodies.iter().position(|body| !body.is_finite()) {
            Some(index) => Err(LcpError::NonFiniteBody {
                body: BodyId(index),
            }),
            None => Ok(()),
        }
    }
}

impl<P: Projection> Problem<P> {
    /// [`Problem::validate`], and every row bound is well formed: a box's `lo ≤ hi` (neither
    /// NaN), a friction coefficient `≥ 0` (not NaN) whose normal row is a
    /// [`RowBound::NonNegative`] row of its own block.
    pub fn validate_bounds(&self) -> Result<(), LcpError> {
        self.validate()?;
        for (index, block) in self.blocks.iter().enumerate() {
            let rows = block.rows.len();
            for k in 0..rows {
                match block.projection.bound(k) {
                    Some(RowBound::Box { lo, hi }) if lo.is_nan() || hi.is_nan() || lo > hi => {
                        let row = block.rows.start + k;
                        return Err(LcpError::InvalidBounds { row, lo, hi });
                    }
                    Some(RowBound::Friction {
                        normal,
                        coefficient,
                    }) if normal >= rows
                        || block.projection.bound(normal) != Some(RowBound::NonNegative)
                        || coefficient.is_nan()
                        || coefficient < 0.0 =>
                    {
                        return Err(LcpError::MalformedBlock { block: index });
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }
}
