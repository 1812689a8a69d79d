//! How far a candidate solution is from solving an LCP: complementarity, feasibility, error.

use nalgebra::{DMatrix, DVector};

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
pub fn lcp_error(a: &DMatrix<f64>, q: &DVector<f64>, z: &DVector<f64>) -> f64 {
    let w = a * z + q;
    complementarity(z, &w).max(infeasibility(z, &w))
}

/// Complementarity of the boxed LCP `lo ≤ z ≤ hi`: each `zᵢ` is at `lo` with `wᵢ ≥ 0`, at `hi`
/// with `wᵢ ≤ 0`, or between with `wᵢ = 0`. Returns the largest violation, in the units of `w`
/// for interior rows and of `z` for rows outside their box.
pub fn box_complementarity(
    z: &DVector<f64>,
    w: &DVector<f64>,
    lo: &DVector<f64>,
    hi: &DVector<f64>,
) -> f64 {
    (0..z.len())
        .map(|i| {
            let outside = (lo[i] - z[i]).max(z[i] - hi[i]).max(0.0);
            // Natural-residual form: |z − clamp(z − w, lo, hi)|.
            let natural = (z[i] - (z[i] - w[i]).max(lo[i]).min(hi[i])).abs();
            outside.max(natural)
        })
        .fold(0.0, f64::max)
}

/// `|x − reference|∞ / max(|reference|∞, floor)`: relative error, with `floor` keeping a zero
/// reference meaningful.
pub fn relative_error(x: &DVector<f64>, reference: &DVector<f64>, floor: f64) -> f64 {
    (x - reference).amax() / reference.amax().max(floor)
}
