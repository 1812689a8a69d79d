//! Property tests: Lemke on random SPD and P-matrix problems up to 60×60, along each of its
//! paths; PGS converging to its answer; infeasible problems ending on a ray.

use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use tatami_lcp::lemke::{PATHS, solve_along};
use tatami_lcp::{LcpError, lemke, pgs_dense, residual};

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 96,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties.txt",
        ))),
        ..ProptestConfig::default()
    }
}

/// For `n` in `sizes`: an n×n matrix of entries in [−1, 1] and a vector q in [−1, 1]ⁿ.
fn raw(
    sizes: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = (DMatrix<f64>, DVector<f64>)> {
    sizes.prop_flat_map(|n| {
        (
            prop::collection::vec(-1.0..1.0f64, n * n)
                .prop_map(move |v| DMatrix::from_vec(n, n, v)),
            prop::collection::vec(-1.0..1.0f64, n).prop_map(DVector::from_vec),
        )
    })
}

/// `BᵀB + 0.1 I`: symmetric positive definite, condition number up to ~10⁴ at n = 60.
fn spd(b: &DMatrix<f64>) -> DMatrix<f64> {
    b.transpose() * b + DMatrix::identity(b.nrows(), b.nrows()) * 0.1
}

/// A strictly row-diagonally-dominant matrix with positive diagonal: a (generally non-symmetric)
/// P-matrix, so the LCP has exactly one solution.
fn p_matrix(b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut m = b.clone();
    for i in 0..m.nrows() {
        let off: f64 = (0..m.ncols())
            .filter(|&j| j != i)
            .map(|j| m[(i, j)].abs())
            .sum();
        m[(i, i)] = off + 0.5 + m[(i, i)].abs();
    }
    m
}

/// Solutions are checked relative to the data's scale: pivots lose a few digits per
/// condition-number decade, and 1e-9 leaves room for the 1e4 of these matrices.
fn tolerance(a: &DMatrix<f64>, q: &DVector<f64>) -> f64 {
    1e-9 * a.amax().max(q.amax()).max(1.0)
}

/// Lemke finishes with a feasible, complementary answer to [`tolerance`].
fn assert_lemke_solves(a: &DMatrix<f64>, q: &DVector<f64>) -> Result<(), TestCaseError> {
    let z = lemke(a, q, 20 * q.len() + 10).map_err(|e| TestCaseError::fail(e.to_string()))?;
    assert_solution(a, q, &z)
}

/// `z` is feasible and complementary to [`tolerance`].
fn assert_solution(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    z: &DVector<f64>,
) -> Result<(), TestCaseError> {
    let w = a * z + q;
    prop_assert!(residual::infeasibility(z, &w) <= tolerance(a, q));
    prop_assert!(residual::complementarity(z, &w) <= tolerance(a, q));
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn lemke_solves_spd_problems((b, q) in raw(1..=60)) {
        let a = spd(&b);
        assert_lemke_solves(&a, &q)?;
    }

    #[test]
    fn lemke_solves_large_spd_problems_through_the_faer_polish((b, q) in raw(64..=100)) {
        // Sizes from lemke::FAER_LU_FROM = 64 on take the faer branch of the final-basis polish.
        let a = spd(&b);
        assert_lemke_solves(&a, &q)?;
    }

    #[test]
    fn lemke_solves_p_matrix_problems((b, q) in raw(1..=60)) {
        let a = p_matrix(&b);
        assert_lemke_solves(&a, &q)?;
    }

    /// Every path the direct solver takes (scaled or not, either covering vector) solves SPD
    /// and P-matrix problems, and ends an infeasible one on a ray.
    #[test]
    fn every_path_solves_what_lemke_solves((b, q) in raw(1..=40), row in 0usize..40) {
        let n = q.len();
        for path in PATHS {
            for a in [spd(&b), p_matrix(&b)] {
                let (z, _) = solve_along(&a, &q, path, 20 * n + 10)
                    .map_err(|e| TestCaseError::fail(format!("{path:?}: {e}")))?;
                assert_solution(&a, &q, &z)?;
            }
            let (mut a, mut q) = (p_matrix(&b), q.clone());
            let row = row % n;
            for j in 0..n {
                a[(row, j)] = -a[(row, j)].abs();
            }
            q[row] = -q[row].abs() - 0.1;
            let result = solve_along(&a, &q, path, 50 * n + 10);
            prop_assert!(matches!(result, Err(LcpError::RayTermination { .. })), "{path:?}: {result:?}");
        }
    }

    #[test]
    fn pgs_converges_to_lemke_on_spd_problems((b, q) in raw(1..=30)) {
        let a = spd(&b);
        let n = q.len();
        let reference = lemke(&a, &q, 20 * n + 10).unwrap();
        let lo = DVector::zeros(n);
        let hi = DVector::from_element(n, f64::INFINITY);
        let errors: Vec<f64> = [5, 50, 2000]
            .iter()
            .map(|&k| (pgs_dense(&a, &q, &lo, &hi, k) - &reference).amax())
            .collect();
        // Gauss–Seidel on an SPD LCP converges (the projected iteration is a contraction in the
        // A-norm); with conditioning up to 1e4 the error after 2000 sweeps is small, not tiny.
        prop_assert!(errors[2] <= errors[0] + 1e-12, "{:?}", errors);
        prop_assert!(errors[2] <= 1e-3 * reference.amax().max(1.0), "{:?}", errors);
    }

    #[test]
    fn infeasible_problems_end_on_a_ray((b, q) in raw(1..=40), row in 0usize..40) {
        // Row `row` of A ≤ 0 against q_row < 0: w_row < 0 for every z ≥ 0.
        let mut a = p_matrix(&b);
        let n = q.len();
        let row = row % n;
        let mut q = q;
        for j in 0..n {
            a[(row, j)] = -a[(row, j)].abs();
        }
        q[row] = -q[row].abs() - 0.1;
        let result = lemke(&a, &q, 50 * n + 10);
        prop_assert!(matches!(result, Err(LcpError::RayTermination { .. })), "{:?}", result);
    }
}
