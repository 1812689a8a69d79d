//! Dense forms: `A = J M⁻¹ Jᵀ` and `b` of a [`Problem`], and a dense boxed PGS.
//!
//! `A` is assembled body by body: a body couples only the rows that touch it, so each body adds
//! `Jᵢ M⁻¹ Jⱼᵀ` for the pairs of its rows. That is O(Σ rows-per-body²) instead of the
//! O(rows² × bodies) of multiplying a dense `J` by `M⁻¹Jᵀ`, and gives the same matrix.

use nalgebra::{DMatrix, DVector, Vector3};

use crate::{LcpError, Problem};

/// One row's Jacobian half on one body: (row, linear part, angular part).
type RowHalf = (usize, Vector3<f64>, Vector3<f64>);

/// `A = J M⁻¹ Jᵀ` and `b = J v − target`, so that the rows' velocities relative to their targets
/// after impulses `λ` are `A λ + b` (paper eq. 2).
pub fn assemble<P>(problem: &Problem<P>) -> (DMatrix<f64>, DVector<f64>) {
    let m = problem.rows.len();
    let mut a = DMatrix::zeros(m, m);
    let mut b = DVector::zeros(m);
    // Per body: (row, linear Jacobian, angular Jacobian) of every row that touches it.
    let mut touching: Vec<Vec<RowHalf>> = vec![Vec::new(); problem.bodies.len()];
    for block in &problem.blocks {
        let (body_a, body_b) = (
            &problem.bodies[block.body_a.0],
            &problem.bodies[block.body_b.0],
        );
        for r in block.rows.clone() {
            let row = &problem.rows[r];
            let j = &row.jacobian;
            b[r] = j.velocity(body_a, body_b) - row.target;
            touching[block.body_a.0].push((r, j.linear_a, j.angular_a));
            touching[block.body_b.0].push((r, j.linear_b, j.angular_b));
        }
    }
    for (body, rows) in problem.bodies.iter().zip(&touching) {
        if body.inv_mass == 0.0 && body.inv_inertia_world.iter().all(|&x| x == 0.0) {
            continue;
        }
        for &(r, lin_r, ang_r) in rows {
            let (lin_response, ang_response) =
                (lin_r * body.inv_mass, body.inv_inertia_world * ang_r);
            for &(c, lin_c, ang_c) in rows {
                a[(c, r)] += lin_c.dot(&lin_response) + ang_c.dot(&ang_response);
            }
        }
    }
    (a, b)
}

/// Projected Gauss–Seidel on the dense boxed LCP: find `lo ≤ z ≤ hi` with, for `w = a z + q`,
/// `wᵢ ≥ 0` where `zᵢ = loᵢ`, `wᵢ ≤ 0` where `zᵢ = hiᵢ`, `wᵢ = 0` between. Starts from `z = 0`
/// clamped into the box and runs `iterations` sweeps in row order; rows with `aᵢᵢ ≤ 0` stay put.
///
/// For invalid input (sizes that disagree, non-finite `a` or `q`, NaN bounds or `lo > hi`) it
/// returns a vector of NaN of `q`'s length rather than panic; [`try_pgs_dense`] gives the typed
/// error instead.
pub fn pgs_dense(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    lo: &DVector<f64>,
    hi: &DVector<f64>,
    iterations: usize,
) -> DVector<f64> {
    try_pgs_dense(a, q, lo, hi, iterations)
        .unwrap_or_else(|_| DVector::from_element(q.len(), f64::NAN))
}

/// [`pgs_dense`] with its input checked.
pub fn try_pgs_dense(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    lo: &DVector<f64>,
    hi: &DVector<f64>,
    iterations: usize,
) -> Result<DVector<f64>, LcpError> {
    check_square_system(a, q)?;
    let n = q.len();
    if lo.len() != n || hi.len() != n {
        return Err(LcpError::DimensionMismatch {
            what: format!("q has {n} entries but lo {} and hi {}", lo.len(), hi.len()),
        });
    }
    for i in 0..n {
        if lo[i].is_nan() || hi[i].is_nan() || lo[i] > hi[i] {
            return Err(LcpError::InvalidBounds {
                row: i,
                lo: lo[i],
                hi: hi[i],
            });
        }
    }
    let mut z = DVector::from_fn(n, |i, _| 0.0f64.max(lo[i]).min(hi[i]));
    for _ in 0..iterations {
        for i in 0..n {
            let diagonal = a[(i, i)];
            if diagonal > 0.0 {
                let w = a.row(i).dot(&z.transpose()) + q[i];
                z[i] = (z[i] - w / diagonal).max(lo[i]).min(hi[i]);
            }
        }
    }
    Ok(z)
}

/// Checks that `a` is square, matches `q`, and both are finite.
pub(crate) fn check_square_system(a: &DMatrix<f64>, q: &DVector<f64>) -> Result<(), LcpError> {
    let n = q.len();
    if a.nrows() != n || a.ncols() != n {
        return Err(LcpError::DimensionMismatch {
            what: format!(
                "matrix is {}×{} but q has {n} entries",
                a.nrows(),
                a.ncols()
            ),
        });
    }
    if a.iter().any(|x| !x.is_finite()) {
        return Err(LcpError::NonFiniteInput { what: "matrix" });
    }
    if q.iter().any(|x| !x.is_finite()) {
        return Err(LcpError::NonFiniteInput { what: "vector q" });
    }
    Ok(())
}
