//! How far a candidate solution is from solving an LCP: complementarity, feasibility, error.
//! Inputs of disagreeing sizes are a [`LcpError::DimensionMismatch`], not a panic.

use nalgebra::{DMatrix, DVector};

use crate::LcpError;

/// An error unless every length in `lengths` equals `n`.
fn sized(n: usize, lengths: &[(&str, usize)]) -> Result<(), LcpError> {
    match lengths.iter().find(|(_, len)| *len != n) {
        None => Ok(()),
        Some((what, len)) => Err(LcpError::DimensionMismatch {
            what: format!("{what} has {len} entries for {n} unknowns"),
        }),
    }
}

/// Complementarity of the standard LCP: `max |min(zᵢ, wᵢ)|`, zero exactly at a solution.
pub fn complementarity(z: &DVector<f64>, w: &DVector<f64>) -> f64 {
    z.iter()
        .zip(w.iter())
        .map(|(z, w)| z.min(*w).abs())
        .fold(0.0, f64::max)
}

/// Infeasibility of the standard LCP: the largest negative part of `z` or `w`.
pub fn infeasibility(z: &DVector<f64>, w: &DVector<f64>) -> f64 {
    z.iter()
        .chain(w.iter())
        .map(|x| (-x).max(0.0))
        .fold(0.0, f64::max)
}

/// `max(complementarity, infeasibility)` of `z` for `w = a z + q`.
pub fn lcp_error(a: &DMatrix<f64>, q: &DVector<f64>, z: &DVector<f64>) -> Result<f64, LcpError> {
    sized(
        z.len(),
        &[
            ("A's rows", a.nrows()),
            ("A's columns", a.ncols()),
            ("q", q.len()),
        ],
    )?;
    let w = a * z + q;
    Ok(complementarity(z, &w).max(infeasibility(z, &w)))
}

/// Complementarity of the boxed LCP `lo ≤ z ≤ hi`: each `zᵢ` is at `lo` with `wᵢ ≥ 0`, at `hi`
/// with `wᵢ ≤ 0`, or between with `wᵢ = 0`. Returns the largest violation, in the units of `w`
/// for interior rows and of `z` for rows outside their box.
pub fn box_complementarity(
    z: &DVector<f64>,
    w: &DVector<f64>,
    lo: &DVector<f64>,
    hi: &DVector<f64>,
) -> Result<f64, LcpError> {
    sized(
        z.len(),
        &[("w", w.len()), ("lo", lo.len()), ("hi", hi.len())],
    )?;
    Ok((0..z.len())
        .map(|i| {
            let outside = (lo[i] - z[i]).max(z[i] - hi[i]).max(0.0);
            // Natural-residual form: |z − clamp(z − w, lo, hi)|.
            let natural = (z[i] - (z[i] - w[i]).max(lo[i]).min(hi[i])).abs();
            outside.max(natural)
        })
        .fold(0.0, f64::max))
}

/// `|x − reference|∞ / max(|reference|∞, floor)`: relative error, with `floor` keeping a zero
/// reference meaningful.
pub fn relative_error(
    x: &DVector<f64>,
    reference: &DVector<f64>,
    floor: f64,
) -> Result<f64, LcpError> {
    sized(reference.len(), &[("x", x.len())])?;
    Ok((x - reference).amax() / reference.amax().max(floor))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disagreeing_sizes_are_errors_not_panics() {
        let (a, q) = (DMatrix::identity(2, 2), DVector::from_vec(vec![1.0, 2.0]));
        let z3 = DVector::zeros(3);
        assert!(matches!(
            lcp_error(&a, &q, &z3),
            Err(LcpError::DimensionMismatch { .. })
        ));
        let z2 = DVector::zeros(2);
        assert!(box_complementarity(&z2, &z2, &z2, &z3).is_err());
        assert!(relative_error(&z3, &z2, 1.0).is_err());
        assert_eq!(lcp_error(&a, &q, &z2), Ok(0.0));
    }
}
