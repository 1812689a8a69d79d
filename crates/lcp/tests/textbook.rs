//! Lemke on LCPs with known solutions, degenerate and infeasible ones, and bad input.

use nalgebra::{DMatrix, DVector};
use tatami_lcp::{LcpError, lemke, pgs_dense, residual};

fn lcp(n: usize, a: &[f64], q: &[f64]) -> (DMatrix<f64>, DVector<f64>) {
    (DMatrix::from_row_slice(n, n, a), DVector::from_row_slice(q))
}

// Solutions below are exact rationals; Lemke's pivots and the LU polish round at 1e-15.
const EXACT: f64 = 1e-12;

#[test]
fn murty_two_by_two() {
    // Murty, "Linear Complementarity, Linear and Nonlinear Programming", example 1.1 form:
    // both rows active, z = (4/3, 7/3).
    let (a, q) = lcp(2, &[2.0, 1.0, 1.0, 2.0], &[-5.0, -6.0]);
    let z = lemke(&a, &q, 50).unwrap();
    assert!(
        (z[0] - 4.0 / 3.0).abs() < EXACT && (z[1] - 7.0 / 3.0).abs() < EXACT,
        "{z}"
    );
}

#[test]
fn one_row_inactive() {
    // z₂ = 0 with w₂ > 0: w₁ = 2 z₁ − 2 = 0 gives z₁ = 1, then w₂ = 1 + 1 = 2.
    let (a, q) = lcp(2, &[2.0, 0.0, 1.0, 1.0], &[-2.0, 1.0]);
    let z = lemke(&a, &q, 50).unwrap();
    assert!((z[0] - 1.0).abs() < EXACT && z[1].abs() < EXACT, "{z}");
}

#[test]
fn cyclic_three_by_three() {
    // Cottle–Pang–Stone's cyclic matrix (a P-matrix): unique solution z = (1/3, 1/3, 1/3).
    let (a, q) = lcp(
        3,
        &[1.0, 2.0, 0.0, 0.0, 1.0, 2.0, 2.0, 0.0, 1.0],
        &[-1.0, -1.0, -1.0],
    );
    let z = lemke(&a, &q, 50).unwrap();
    for i in 0..3 {
        assert!((z[i] - 1.0 / 3.0).abs() < EXACT, "{z}");
    }
}

#[test]
fn degenerate_equal_q_does_not_cycle() {
    // All qᵢ equal: every ratio test ties. Solution z = (1/4, 1/4, 1/4) for the
    // 2-on-the-diagonal, 1-elsewhere matrix.
    let (a, q) = lcp(
        3,
        &[2.0, 1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0, 2.0],
        &[-1.0, -1.0, -1.0],
    );
    let z = lemke(&a, &q, 30).unwrap();
    for i in 0..3 {
        assert!((z[i] - 0.25).abs() < EXACT, "{z}");
    }
    // A degenerate basis: q = 0 in one row makes a zero ratio.
    let (a, q) = lcp(
        3,
        &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0],
        &[-1.0, 0.0, -1.0],
    );
    let z = lemke(&a, &q, 30).unwrap();
    assert!(residual::lcp_error(&a, &q, &z).unwrap() < EXACT, "{z}");
}

#[test]
fn nonnegative_q_is_solved_by_zero() {
    let (a, q) = lcp(2, &[1.0, 0.0, 0.0, 1.0], &[0.0, 3.0]);
    assert_eq!(lemke(&a, &q, 1).unwrap(), DVector::zeros(2));
}

#[test]
fn infeasible_problem_ends_on_a_ray() {
    // w₁ = −z₁ − z₂ − 1 < 0 for every z ≥ 0: no solution exists.
    let (a, q) = lcp(2, &[-1.0, -1.0, 0.0, 1.0], &[-1.0, -1.0]);
    assert!(matches!(
        lemke(&a, &q, 50),
        Err(LcpError::RayTermination { .. })
    ));
}

#[test]
fn pivot_limit_is_reported() {
    let (a, q) = lcp(
        3,
        &[1.0, 2.0, 0.0, 0.0, 1.0, 2.0, 2.0, 0.0, 1.0],
        &[-1.0, -1.0, -1.0],
    );
    assert_eq!(lemke(&a, &q, 1), Err(LcpError::PivotLimit { limit: 1 }));
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let (a, q) = lcp(2, &[1.0, f64::NAN, 0.0, 1.0], &[-1.0, -1.0]);
    assert_eq!(
        lemke(&a, &q, 10),
        Err(LcpError::NonFiniteInput { what: "matrix" })
    );
    let (a, _) = lcp(2, &[1.0, 0.0, 0.0, 1.0], &[-1.0, -1.0]);
    let short = DVector::from_vec(vec![-1.0]);
    assert!(matches!(
        lemke(&a, &short, 10),
        Err(LcpError::DimensionMismatch { .. })
    ));
    let q = DVector::from_vec(vec![-1.0, f64::INFINITY]);
    assert_eq!(
        lemke(&a, &q, 10),
        Err(LcpError::NonFiniteInput { what: "vector q" })
    );
    // The dense PGS keeps its contract signature and answers NaN, loudly, instead of panicking.
    let lo = DVector::from_vec(vec![1.0, 0.0]);
    let hi = DVector::from_vec(vec![0.0, 1.0]);
    assert!(
        pgs_dense(&a, &DVector::from_vec(vec![-1.0, -1.0]), &lo, &hi, 5)
            .iter()
            .all(|x| x.is_nan())
    );
    assert!(tatami_lcp::dense::try_pgs_dense(&a, &short, &lo, &hi, 5).is_err());
}

#[test]
fn pgs_dense_solves_a_boxed_problem() {
    // Without the box, w = 0 gives z = (1, 1). The box caps z₂ at 0.5 (with w₂ = 2·0.5 + z₁ − 3
    // < 0, as an upper bound requires); then w₁ = 2z₁ + 0.5 − 3 = 0 gives z₁ = 1.25.
    let (a, q) = lcp(2, &[2.0, 1.0, 1.0, 2.0], &[-3.0, -3.0]);
    let lo = DVector::from_vec(vec![0.0, 0.0]);
    let hi = DVector::from_vec(vec![10.0, 0.5]);
    let z = pgs_dense(&a, &q, &lo, &hi, 200);
    assert!(
        (z[0] - 1.25).abs() < 1e-12 && (z[1] - 0.5).abs() < 1e-12,
        "{z}"
    );
    let w = &a * &z + &q;
    assert!(residual::box_complementarity(&z, &w, &lo, &hi).unwrap() < 1e-12);
}

/// A column-major `a` with entries from 1e-4 down to 8e-12 against `q` of −9e298: the answer
/// passes f64's 1.8e308. Lemke once returned ∞ as an answer (found by fuzzing) and now reports
/// the overflow.
#[test]
fn an_answer_beyond_f64_is_an_overflow_error() {
    let a = DMatrix::from_column_slice(
        2,
        2,
        &[
            7.843137254901962e-12,
            0.00015259021896696422,
            0.0,
            8.987563897154192e-11,
        ],
    );
    let q = DVector::from_element(2, -9.019607843137254e298);
    assert!(matches!(lemke(&a, &q, 50), Err(LcpError::Overflow { .. })));
}
