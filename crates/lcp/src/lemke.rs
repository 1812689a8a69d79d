//! Lemke's complementary pivoting for the standard LCP `z ≥ 0, w = A z + q ≥ 0, zᵀw = 0`.
//!
//! Tableau form of `w − A z − e z₀ = q` (covering vector `e = 1`). `z₀` enters first, replacing
//! the most negative `qᵢ`; then the complement of each leaving variable enters, until `z₀` leaves
//! (a solution) or an entering column has no positive entry (a ray: no solution found). For
//! P-matrices and positive semi-definite `A` with a feasible problem, Lemke always finishes.
//!
//! The covering vector `e` may be any positive vector ([`Covering`]); each gives a path of its
//! own through the same problem. The direct solver tries the textbook `e = 1` first, then
//! a [`Covering::Staggered`] one whose entries differ: a cylinder's cap resting on a face under
//! the vertex model gives 64 normal rows with the same `qᵢ`, and on such a problem every path
//! with `e = 1` (scaled or not, regularised or not) ended on a ray while the staggered one
//! solved it in its first attempt.
//!
//! Degenerate problems (ties in the ratio test, e.g. all `qᵢ` equal) cycle under a naive rule.
//! The **lexicographic** ratio test breaks ties by the rows of `B⁻¹` (the tableau's `w` columns),
//! which keeps every tableau row lexicographically positive and so never revisits a basis.
//!
//! After [`REFACTOR_EVERY`] pivots, again after twice as many and so on, and once more before a
//! ray is declared, the tableau is rebuilt from the original data for the current basis by one
//! LU factorisation, so round-off does not build up over hundreds of pivots (the revised simplex
//! method's refactorisation).
//!
//! After the last pivot the basic values are re-solved from the original data with an LU
//! factorisation of the final basis (faer's partial-pivot LU), removing the round-off that the
//! pivots accumulated; the polished answer is kept when its residual is smaller. The LU is
//! nalgebra's below [`FAER_LU_FROM`] unknowns and faer's from there on, where each is faster
//! (figures in the crate README).

use faer::Mat;
use faer::linalg::solvers::Solve;
use nalgebra::{DMatrix, DVector};

use crate::{LcpError, dense, residual};

/// Size from which faer's partial-pivot LU replaces nalgebra's: measured 4.8× slower than
/// nalgebra at n = 6 and 2.1× at 24, but 1.7× faster at 96 and 3.7× at 384.
pub const FAER_LU_FROM: usize = 64;

/// Pivots after which the tableau is first rebuilt from the original data for its current
/// basis; it is rebuilt again after twice as many, and so on (50, 100, 200, 400, …). Each pivot
/// adds round-off to every cell; on a 2,304-unknown pile problem it had grown enough by pivot
/// 300 to send every path off a feasible basis and onto a ray. A rebuild costs about `n`
/// pivots' worth of work (1.6 s at n = 2,304); doubling the interval bounds what rebuilds add
/// to a long path (one cycling to the pivot limit) to about `n log₂(pivots / 50)` pivots'
/// worth, where rebuilding every 50 pivots made the fuzz corpus test take 1.6 times as long.
/// Contact problems rarely need 50 pivots (crate README), so most solves never rebuild.
pub const REFACTOR_EVERY: usize = 50;

/// Relative size below which a pivot-column entry is taken as zero.
const PIVOT_TOLERANCE: f64 = 1e-12;

/// The covering vector `e > 0` of the tableau `w − A z − e z₀ = q`: which path Lemke's pivots
/// take from the start (`z₀` enters at the smallest `qᵢ / eᵢ`) to the answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Covering {
    /// `e = 1`, the textbook choice.
    #[default]
    Uniform,
    /// `eᵢ = 1 + ½ frac(i φ)` (φ the golden ratio): entries spread over `[1, 1.5)`, no two
    /// equal, so rows whose data tie (coplanar contact points) are told apart from the first
    /// pivot on.
    Staggered,
}

impl Covering {
    /// Entry `i` of the covering vector.
    fn entry(self, i: usize) -> f64 {
        match self {
            Self::Uniform => 1.0,
            Self::Staggered => {
                let golden = 0.5 * (1.0 + 5f64.sqrt());
                1.0 + 0.5 * (i as f64 * golden).fract()
            }
        }
    }
}

/// One of Lemke's paths through a problem: with or without [`solve`]'s scaling, and which
/// covering vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Path {
    /// Whether the problem is first scaled to a unit diagonal (see [`solve`]).
    pub scaled: bool,
    /// The covering vector.
    pub covering: Covering,
}

/// The paths the direct solver tries, in order: scaled and unscaled with `e = 1`, then both
/// again with the staggered covering vector.
pub const PATHS: [Path; 4] = [
    Path {
        scaled: true,
        covering: Covering::Uniform,
    },
    Path {
        scaled: false,
        covering: Covering::Uniform,
    },
    Path {
        scaled: true,
        covering: Covering::Staggered,
    },
    Path {
        scaled: false,
        covering: Covering::Staggered,
    },
];

/// Solves `z ≥ 0, w = a z + q ≥ 0, zᵀw = 0` by Lemke's method with at most `max_pivots` pivots.
///
/// Errors: [`LcpError::RayTermination`] when no solution is found (e.g. an infeasible problem),
/// [`LcpError::PivotLimit`], [`LcpError::Overflow`], [`LcpError::NonFiniteInput`],
/// [`LcpError::DimensionMismatch`].
pub fn lemke(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    max_pivots: usize,
) -> Result<DVector<f64>, LcpError> {
    solve(a, q, max_pivots).map(|(z, _)| z)
}

/// [`lemke`](fn@lemke), also returning the number of pivots made.
///
/// The problem is first scaled to a unit diagonal, `z = D y` with `D = diag(aᵢᵢ)^(−1/2)` (1
/// where `aᵢᵢ ≤ 0`): `D a D y + D q` has the same complementarity, and its pivots compare
/// entries of one size. Contact problems mix generators whose diagonal is an inverse mass
/// (1e-3 for a 1 t body) with budget rows of unit coefficients; unscaled, the ratio test took
/// round-off for a positive entry and Lemke ended on a ray on solvable problems.
pub fn solve(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    max_pivots: usize,
) -> Result<(DVector<f64>, usize), LcpError> {
    solve_along(a, q, PATHS[0], max_pivots)
}

/// Lemke's method along `path`: [`solve`] is the first of [`PATHS`], [`solve_unscaled`] the
/// second. Returns the answer and the number of pivots made.
///
/// ```
/// use nalgebra::{DMatrix, DVector};
/// use tatami_lcp::lemke::{Covering, Path, solve_along};
/// // Two equal rows: the same answer along either covering vector.
/// let a = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
/// let q = DVector::from_vec(vec![-3.0, -3.0]);
/// for covering in [Covering::Uniform, Covering::Staggered] {
///     let (z, _) = solve_along(&a, &q, Path { scaled: true, covering }, 20)?;
///     assert!((z - DVector::from_vec(vec![1.0, 1.0])).amax() < 1e-12);
/// }
/// # Ok::<(), tatami_lcp::LcpError>(())
/// ```
pub fn solve_along(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    path: Path,
    max_pivots: usize,
) -> Result<(DVector<f64>, usize), LcpError> {
    dense::check_square_system(a, q)?;
    let n = q.len();
    if q.iter().all(|&x| x >= 0.0) {
        return Ok((DVector::zeros(n), 0));
    }
    if !path.scaled {
        return pivot_to_solution(a, q, path.covering, max_pivots);
    }
    let mut d = DVector::from_fn(n, |i, _| {
        let diagonal = a[(i, i)];
        if diagonal > 0.0 {
            1.0 / diagonal.sqrt()
        } else {
            1.0
        }
    });
    // A variable without a diagonal (a budget's multiplier) is scaled so that its largest
    // coupling to the scaled others is 1.
    for j in (0..n).filter(|&j| a[(j, j)] <= 0.0) {
        let largest = (0..n)
            .filter(|&i| a[(i, i)] > 0.0)
            .map(|i| a[(i, j)].abs().max(a[(j, i)].abs()) * d[i])
            .fold(0.0, f64::max);
        if largest > 0.0 {
            d[j] = 1.0 / largest;
        }
    }
    let scaled = DMatrix::from_fn(n, n, |i, j| d[i] * a[(i, j)] * d[j]);
    let (y, pivots) = pivot_to_solution(&scaled, &q.component_mul(&d), path.covering, max_pivots)?;
    let z = y.component_mul(&d);
    if z.iter().all(|x| x.is_finite()) {
        Ok((z, pivots))
    } else {
        Err(LcpError::Overflow { pivots })
    }
}

/// Lemke's method on the problem as given, without [`solve`]'s scaling: another path through
/// the same problem, which the direct solver tries when the scaled one fails.
pub fn solve_unscaled(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    max_pivots: usize,
) -> Result<(DVector<f64>, usize), LcpError> {
    solve_along(a, q, PATHS[1], max_pivots)
}

/// Lemke's pivots on a checked problem with some `qᵢ < 0`.
fn pivot_to_solution(
    a: &DMatrix<f64>,
    q: &DVector<f64>,
    covering: Covering,
    max_pivots: usize,
) -> Result<(DVector<f64>, usize), LcpError> {
    let n = q.len();
    let mut tableau = Tableau::new(a, q, covering);
    let z0 = 2 * n;
    // First pivot: z₀ replaces the row of the most negative `qᵢ / eᵢ` (which leaves every
    // right-hand side ≥ 0); among ties the last row, which keeps the tableau lexicographically
    // positive.
    let first = (0..n)
        .rev()
        .min_by(|&i, &j| (q[i] / covering.entry(i)).total_cmp(&(q[j] / covering.entry(j))))
        .expect("n > 0");
    let left = tableau.pivot(first, z0);
    let mut entering = tableau.complement(left);
    let mut pivots = 1;
    loop {
        if pivots >= max_pivots {
            return Err(LcpError::PivotLimit { limit: max_pivots });
        }
        let row = match tableau.ratio_test(entering) {
            Some(row) => row,
            // A ray on a solvable problem is round-off: the pivots' accumulated error hid the
            // entering column's positive entries. Rebuild the tableau from the original data
            // for the current basis and look again, once per ray.
            None if tableau.refactor(a, q) => tableau
                .ratio_test(entering)
                .ok_or(LcpError::RayTermination { pivots })?,
            None => return Err(LcpError::RayTermination { pivots }),
        };
        let leaving = tableau.pivot(row, entering);
        pivots += 1;
        if pivots % REFACTOR_EVERY == 0 && (pivots / REFACTOR_EVERY).is_power_of_two() {
            // At 50, 100, 200, … pivots.
            tableau.refactor(a, q);
        }
        if leaving == z0 {
            break;
        }
        entering = tableau.complement(leaving);
    }
    let z = tableau.solution();
    let polished = tableau.polish(a, q).filter(|p| {
        let error = |z| residual::lcp_error(a, q, z).unwrap_or(f64::INFINITY);
        error(p) < error(&z)
    });
    let z = polished.unwrap_or(z);
    if z.iter().all(|x| x.is_finite()) {
        Ok((z, pivots))
    } else {
        Err(LcpError::Overflow { pivots })
    }
}

/// Row-major tableau `[w (n) | z (n) | z₀ | rhs]` with the basic variable of each row.
struct Tableau {
    n: usize,
    covering: Covering,
    width: usize,
    cells: Vec<f64>,
    basis: Vec<usize>,
    scale: f64,
    /// Copy of the pivot row, reused so pivots allocate nothing.
    pivot_row: Vec<f64>,
}

/// Entry `(i, v)` of the starting tableau `[I | −A | −e | q]` (`e` the covering vector):
/// column `v` is `wᵥ` for `v < n`, `z_(v−n)` up to `2n`, then `z₀`, then the right-hand side.
fn data_cell(a: &DMatrix<f64>, q: &DVector<f64>, covering: Covering, i: usize, v: usize) -> f64 {
    let n = q.len();
    match v {
        v if v < n => f64::from(u8::from(i == v)),
        v if v < 2 * n => -a[(i, v - n)],
        v if v == 2 * n => -covering.entry(i),
        _ => q[i],
    }
}

impl Tableau {
    fn new(a: &DMatrix<f64>, q: &DVector<f64>, covering: Covering) -> Self {
        let n = q.len();
        let width = 2 * n + 2;
        let cells = (0..n * width)
            .map(|k| data_cell(a, q, covering, k / width, k % width))
            .collect();
        let scale = a.amax().max(1.0);
        Self {
            n,
            covering,
            width,
            cells,
            basis: (0..n).collect(),
            scale,
            pivot_row: vec![0.0; width],
        }
    }

    fn at(&self, i: usize, j: usize) -> f64 {
        self.cells[i * self.width + j]
    }

    fn rhs(&self, i: usize) -> f64 {
        self.at(i, self.width - 1)
    }

    /// `wᵢ ↔ zᵢ`.
    fn complement(&self, variable: usize) -> usize {
        if variable < self.n {
            variable + self.n
        } else {
            variable - self.n
        }
    }

    /// The leaving row for `column`: minimum ratio `rhsᵢ / tᵢ` over `tᵢ > 0`, ties broken by
    /// `z₀` leaving if it can, then lexicographically by the rows of `B⁻¹ / tᵢ`.
    fn ratio_test(&self, column: usize) -> Option<usize> {
        let tolerance = PIVOT_TOLERANCE * self.scale;
        let candidates: Vec<usize> = (0..self.n)
            .filter(|&i| self.at(i, column) > tolerance)
            .collect();
        let ratio = |i: usize| self.rhs(i) / self.at(i, column);
        let best = candidates
            .iter()
            .map(|&i| ratio(i))
            .fold(f64::INFINITY, f64::min);
        if !best.is_finite() {
            return None;
        }
        let tie = 1e-12 * (1.0 + best.abs());
        let tied: Vec<usize> = candidates
            .into_iter()
            .filter(|&i| ratio(i) - best <= tie)
            .collect();
        if let Some(&i) = tied.iter().find(|&&i| self.basis[i] == 2 * self.n) {
            return Some(i);
        }
        tied.into_iter().min_by(|&i, &k| {
            (0..self.n)
                .map(|j| {
                    (
                        self.at(i, j) / self.at(i, column),
                        self.at(k, j) / self.at(k, column),
                    )
                })
                .map(|(x, y)| x.total_cmp(&y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    }

    /// Pivots `column` into the basis at `row`; returns the variable that left.
    fn pivot(&mut self, row: usize, column: usize) -> usize {
        let w = self.width;
        let p = self.at(row, column);
        for x in &mut self.cells[row * w..(row + 1) * w] {
            *x /= p;
        }
        self.pivot_row
            .copy_from_slice(&self.cells[row * w..(row + 1) * w]);
        for i in (0..self.n).filter(|&i| i != row) {
            let factor = self.at(i, column);
            if factor != 0.0 {
                for (x, y) in self.cells[i * w..(i + 1) * w]
                    .iter_mut()
                    .zip(&self.pivot_row)
                {
                    *x -= factor * y;
                }
            }
        }
        std::mem::replace(&mut self.basis[row], column)
    }

    /// Recomputes every cell from the original data for the current basis, `B⁻¹ [I | −A | −e |
    /// q]` with `B` the basic columns of `[I | −A | −e]`, by one LU factorisation: the pivots'
    /// accumulated round-off is gone. `false` if `B` is singular to working precision.
    fn refactor(&mut self, a: &DMatrix<f64>, q: &DVector<f64>) -> bool {
        let n = self.n;
        let column = |i: usize, v: usize| data_cell(a, q, self.covering, i, v);
        let basis = Mat::<f64>::from_fn(n, n, |i, k| column(i, self.basis[k]));
        let data = Mat::<f64>::from_fn(n, self.width, column);
        let cells = basis.partial_piv_lu().solve(&data);
        let finite = (0..n).all(|i| (0..self.width).all(|v| cells[(i, v)].is_finite()));
        if finite {
            for i in 0..n {
                for v in 0..self.width {
                    self.cells[i * self.width + v] = cells[(i, v)];
                }
            }
        }
        finite
    }

    fn solution(&self) -> DVector<f64> {
        let mut z = DVector::zeros(self.n);
        for (i, &v) in self.basis.iter().enumerate() {
            if (self.n..2 * self.n).contains(&v) {
                z[v - self.n] = self.rhs(i).max(0.0);
            }
        }
        z
    }

    /// Re-solves the final basis `B x = q` (columns of `[I | −A]`) with an LU factorisation.
    fn polish(&self, a: &DMatrix<f64>, q: &DVector<f64>) -> Option<DVector<f64>> {
        let n = self.n;
        let basis = DMatrix::from_fn(n, n, |i, k| {
            data_cell(a, q, self.covering, i, self.basis[k])
        });
        let x = lu_solve(basis, q)?;
        let mut z = DVector::zeros(n);
        for (k, &v) in self.basis.iter().enumerate() {
            if !x[k].is_finite() {
                return None;
            }
            if v >= n {
                z[v - n] = x[k].max(0.0);
            }
        }
        Some(z)
    }
}

/// `m x = rhs` by partial-pivot LU: nalgebra's below [`FAER_LU_FROM`], faer's from there on.
fn lu_solve(m: DMatrix<f64>, rhs: &DVector<f64>) -> Option<DVector<f64>> {
    let n = rhs.len();
    if n < FAER_LU_FROM {
        return m.lu().solve(rhs);
    }
    let m = Mat::<f64>::from_fn(n, n, |i, j| m[(i, j)]);
    let rhs = Mat::<f64>::from_fn(n, 1, |i, _| rhs[i]);
    let x = m.partial_piv_lu().solve(&rhs);
    Some(DVector::from_fn(n, |i, _| x[(i, 0)]))
}
