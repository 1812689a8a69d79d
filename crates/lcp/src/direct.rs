//! The direct solver: the contact problem solved exactly, as the reference for PGS.
//!
//! **Which problem.** Each block states its admissible impulses as linear constraints, a
//! [`LinearSet`] (by default from its [`RowBound`](crate::RowBound)s; the contact models give
//! theirs: the face model's centre of pressure as a cone over the support polygon's vertices,
//! the circular friction cone as an inscribed polygon). With `w` the rows' velocities relative
//! to their targets after the impulses, the answer satisfies maximal dissipation: `λ` in the
//! set, and every generator's and budget's complementarity condition of
//! [`crate::linear_set`]. For a normal row that is `λ ≥ 0 ⟂ w ≥ 0`; for box friction
//! `|λ| ≤ μ λₙ` with `w = 0` inside and `λ = ∓μ λₙ` when `w ≷ 0` (the *static* coefficient: the
//! exact problem has no sticking/sliding switch); for a box `λ` at `lo` with `w ≥ 0`, at `hi`
//! with `w ≤ 0`, or between with `w = 0`.
//!
//! **The standard LCP.** The variables are the generators' weights `x ≥ 0` and one multiplier
//! `γ ≥ 0` per budget. With `λ = offset + G x` and `w = A λ + b`, the conditions are
//! `x ⟂ Gᵀw + Sᵀγ ≥ 0` and `γ ⟂ constant + E x − S x ≥ 0`, where `S` says which generators
//! spend each budget and `E` what each earns: the matrix `[[GᵀAG, Sᵀ], [E − S, 0]]` and the
//! vector `[Gᵀ(A offset + b), constant]`. For box friction this is the familiar
//! `λ = β⁺ − β⁻`, `β± ⟂ ±w + γ ≥ 0`, `γ ⟂ μ λₙ − β⁺ − β⁻ ≥ 0`, `γ` the sliding speed. It is
//! solved by [`lemke`](crate::lemke()).
//!
//! **Assembly.** `A = J M⁻¹ Jᵀ` is assembled body by body ([`dense::assemble`]), and the
//! standard matrix block by block: `gᵀ A h` for generators of two blocks is zero unless the
//! blocks share a body that impulses move, so only such pairs are visited — three per block of a
//! tower, whatever its height. Lemke's tableau stays dense, which bounds the size: a problem
//! whose storage ([`dense_bytes`]) passes [`DirectParams::memory_budget`] is refused with
//! [`LcpError::TooLarge`], which names its unknowns, before anything is allocated.
//!
//! The rows' incoming impulses are ignored: the bodies' velocities are taken as those before any
//! contact impulse, and the answer's impulses, projected onto the row bounds to remove Lemke's
//! round-off, are written into the rows and applied.

use nalgebra::{DMatrix, DVector};

use crate::{LcpError, LinearSet, Problem, Projection, dense, lemke, project_to_bounds, residual};

/// Settings of a direct solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectParams {
    /// Lemke pivots allowed per variable of the standard LCP. Default
    /// [`DEFAULT_PIVOTS_PER_VARIABLE`].
    pub pivots_per_variable: usize,
    /// Largest dense storage (bytes) a solve may allocate; a larger problem is refused with
    /// [`LcpError::TooLarge`] before anything is allocated. Default [`DEFAULT_MEMORY_BUDGET`].
    pub memory_budget: usize,
}

/// Lemke needs one to three pivots per variable on contact problems; 10 leaves a margin before
/// [`LcpError::PivotLimit`], past which the solve is retried regularised (see
/// [`REGULARISATIONS`]) rather than cycle on.
pub const DEFAULT_PIVOTS_PER_VARIABLE: usize = 10;

/// 512 MiB: the dense matrices of about 3,600 standard-LCP variables — some 500 contact points
/// with box friction (7 variables each), 150 face contacts with the circular cone (24 each), or
/// 50 cubes resting on their four corners under the vertex model (72 each).
pub const DEFAULT_MEMORY_BUDGET: usize = 512 << 20;

impl Default for DirectParams {
    fn default() -> Self {
        Self {
            pivots_per_variable: DEFAULT_PIVOTS_PER_VARIABLE,
            memory_budget: DEFAULT_MEMORY_BUDGET,
        }
    }
}

/// Bytes of dense storage a direct solve of `rows` contact rows and `variables` standard-LCP
/// variables allocates at most: `A` (rows²); the standard matrix, its regularised copy and
/// Lemke's scaled copy (3 × variables²); Lemke's tableau (variables × (2·variables + 2)); and,
/// while the tableau is rebuilt from the data for its basis, the basis and its LU factors
/// (2 × variables²) with the data's and the rebuilt tableau's columns (2 × variables ×
/// (2·variables + 2)); in f64. Saturates instead of overflowing.
pub fn dense_bytes(rows: usize, variables: usize) -> usize {
    let square = variables.saturating_mul(variables);
    let tableau = variables.saturating_mul(variables.saturating_mul(2).saturating_add(2));
    let cells = rows
        .saturating_mul(rows)
        .saturating_add(square.saturating_mul(3))
        .saturating_add(tableau)
        .saturating_add(square.saturating_mul(2))
        .saturating_add(tableau.saturating_mul(2));
    cells.saturating_mul(std::mem::size_of::<f64>())
}

/// What a direct solve did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectInfo {
    /// Variables of the standard LCP (≥ rows).
    pub variables: usize,
    /// Lemke pivots made.
    pub pivots: usize,
    /// A warning: `Some(ε)` when Lemke failed on the problem and the answer is that of the
    /// problem regularised by `ε I` (see [`REGULARISATIONS`]); its complementarity error on the
    /// true problem is of the order of `ε` times the impulses.
    pub regularisation: Option<f64>,
    /// The answer's error on the standard LCP (complementarity and feasibility) relative to the
    /// problem's scale: round-off, about 1e-15, for an exact answer.
    pub residual: f64,
    /// Lemke paths tried (1 when the first answered; see [`RESIDUAL_TOLERANCE`]).
    pub attempts: usize,
}

/// Solves `problem` exactly; writes impulses and velocities like the PGS solver.
pub fn solve<P: Projection>(
    problem: &mut Problem<P>,
    params: &DirectParams,
) -> Result<DirectInfo, LcpError> {
    problem.validate_bounds()?;
    let sets = problem
        .blocks
        .iter()
        .enumerate()
        .map(|(index, block)| {
            block
                .projection
                .linear_set(block.rows.len())
                .filter(|set| set.offset.len() == block.rows.len() && set.is_well_formed())
                .ok_or(LcpError::Unsupported { block: index })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let variables = sets.iter().map(LinearSet::variables).sum();
    let bytes = dense_bytes(problem.rows.len(), variables);
    if bytes > params.memory_budget {
        return Err(LcpError::TooLarge {
            variables,
            bytes,
            budget: params.memory_budget,
        });
    }
    let (a, b) = dense::assemble(problem);
    let lcp = StandardForm::new(problem, sets, &a, &b);
    let Standard {
        x,
        pivots,
        regularisation,
        residual,
        attempts,
    } = solve_standard(&lcp.matrix, &lcp.q, params)?;
    let mut impulses = lcp.impulses(problem, &x);
    // Lemke keeps w ≥ 0 only to round-off, so a slack's bound may be missed by a few ulps of
    // the problem's scale; projecting onto the row bounds makes every answer admissible.
    for block in &problem.blocks {
        let rows = block.rows.clone();
        project_to_bounds(
            |k| block.projection.bound(k),
            &mut impulses.as_mut_slice()[rows],
        );
    }
    apply(problem, &impulses);
    problem.validate_bodies()?;
    Ok(DirectInfo {
        variables: lcp.q.len(),
        pivots,
        regularisation,
        residual,
        attempts,
    })
}

/// The standard LCP's error at `x` — the larger of its complementarity `max |min(xᵢ, wᵢ)|` and
/// infeasibility — relative to the problem's scale `|q|∞ + |M|∞ |x|∞`.
fn relative_residual(matrix: &DMatrix<f64>, q: &DVector<f64>, x: &DVector<f64>) -> f64 {
    let w = matrix * x + q;
    let error = residual::complementarity(x, &w).max(residual::infeasibility(x, &w));
    let scale = q.amax() + matrix.amax() * x.amax();
    if scale > 0.0 { error / scale } else { error }
}

/// Regularisations tried, relative to the largest diagonal entry, when Lemke fails on the
/// problem as it is.
pub const REGULARISATIONS: [f64; 3] = [1e-12, 1e-10, 1e-8];

/// Largest relative residual (see [`DirectInfo::residual`]) of an accepted answer: far above the
/// round-off of an exact one (below 1e-9 on contact problems), far below any error that shows
/// in a trajectory.
pub const RESIDUAL_TOLERANCE: f64 = 1e-6;

/// Solves `M z + q` by Lemke's method, accepting an answer only when its residual is within
/// [`RESIDUAL_TOLERANCE`]. Lemke's pivots decide on signs of round-off-sized entries, so on a
/// degenerate contact problem one path ends on a ray, or on a basis that is not quite
/// complementary, where another finds the answer. The paths tried, in order: each of
/// [`lemke::PATHS`] (scaled and unscaled, with the covering vector `e = 1` and then with a
/// staggered one) on the problem, then on `(M + ε I)` for each ε of [`REGULARISATIONS`]
/// (times M's largest diagonal). Returns the answer,
/// its pivots, the ε used if any, the residual on the true problem and the paths tried.
fn solve_standard(
    matrix: &DMatrix<f64>,
    q: &DVector<f64>,
    params: &DirectParams,
) -> Result<Standard, LcpError> {
    let limit = params.pivots_per_variable * q.len().max(1);
    let scale = matrix.diagonal().amax();
    let mut first_error = None;
    let mut attempts = 0;
    for relative in std::iter::once(None).chain(REGULARISATIONS.map(Some)) {
        let epsilon = relative.map(|r| r * scale);
        let regularised;
        let system = match epsilon {
            None => matrix,
            Some(epsilon) => {
                regularised = matrix + DMatrix::from_diagonal_element(q.len(), q.len(), epsilon);
                &regularised
            }
        };
        for path in lemke::PATHS {
            attempts += 1;
            let error = match lemke::solve_along(system, q, path, limit) {
                Ok((x, pivots)) => {
                    let residual = relative_residual(matrix, q, &x);
                    if residual <= RESIDUAL_TOLERANCE {
                        return Ok(Standard {
                            x,
                            pivots,
                            regularisation: epsilon,
                            residual,
                            attempts,
                        });
                    }
                    LcpError::Inaccurate { residual }
                }
                Err(e @ (LcpError::RayTermination { .. } | LcpError::PivotLimit { .. })) => e,
                Err(e) => return Err(e),
            };
            first_error.get_or_insert(error);
        }
    }
    Err(first_error.expect("at least one attempt"))
}

/// An accepted answer of [`solve_standard`].
struct Standard {
    x: DVector<f64>,
    pivots: usize,
    regularisation: Option<f64>,
    residual: f64,
    attempts: usize,
}

/// The standard LCP equivalent to the blocks' linear sets, and the map back to impulses.
struct StandardForm {
    matrix: DMatrix<f64>,
    q: DVector<f64>,
    /// Each block's set and the index of its first variable: its generators, then one slack
    /// per budget.
    sets: Vec<(usize, LinearSet)>,
}

impl StandardForm {
    /// Writes the complementarity of [`crate::linear_set`] for every block: generator `v` has
    /// the condition `gᵥᵀ w + Σ γ ≥ 0` (the budgets it spends), budget `b` the condition
    /// `constant + Σ c·x_earn − Σ x_spend ≥ 0`, with `w = A λ + b` and `λ = offset + G x`.
    fn new<P>(
        problem: &Problem<P>,
        sets: Vec<LinearSet>,
        a: &DMatrix<f64>,
        b: &DVector<f64>,
    ) -> Self {
        let m = problem.rows.len();
        let mut offset = DVector::zeros(m);
        let mut placed = Vec::with_capacity(sets.len());
        let mut n = 0;
        for (block, set) in problem.blocks.iter().zip(&sets) {
            let first_row = block.rows.start;
            for (k, &value) in set.offset.iter().enumerate() {
                offset[first_row + k] = value;
            }
            placed.push(n);
            n += set.variables();
        }
        let velocity_at_offset = a * &offset + b;
        let mut matrix = DMatrix::zeros(n, n);
        let mut q = DVector::zeros(n);
        for (i, (block, set)) in problem.blocks.iter().zip(&sets).enumerate() {
            let rows = block.rows.start;
            for (v, generator) in set.generators.iter().enumerate() {
                q[placed[i] + v] = generator
                    .iter()
                    .map(|&(k, c)| c * velocity_at_offset[rows + k])
                    .sum();
            }
        }
        // gᵀ A h for generators g of block i and h of block j: zero unless the blocks share a
        // moving body, so only those pairs are visited (a tower's block meets three).
        for (i, j) in coupled_blocks(problem) {
            let (rows_i, rows_j) = (problem.blocks[i].rows.start, problem.blocks[j].rows.start);
            for (c, g) in sets[i].generators.iter().enumerate() {
                for (v, h) in sets[j].generators.iter().enumerate() {
                    matrix[(placed[i] + c, placed[j] + v)] = g
                        .iter()
                        .flat_map(|&(k, x)| {
                            h.iter()
                                .map(move |&(l, y)| x * y * a[(rows_i + k, rows_j + l)])
                        })
                        .sum();
                }
            }
        }
        for (set, &first) in sets.iter().zip(&placed) {
            for (index, budget) in set.budgets.iter().enumerate() {
                let slack = first + set.generators.len() + index;
                q[slack] = budget.constant;
                for &v in &budget.spend {
                    matrix[(first + v, slack)] += 1.0;
                    matrix[(slack, first + v)] -= 1.0;
                }
                for &(v, rate) in &budget.earn {
                    matrix[(slack, first + v)] += rate;
                }
            }
        }
        Self {
            matrix,
            q,
            sets: placed.into_iter().zip(sets).collect(),
        }
    }

    /// The impulses of the LCP's answer `x`.
    fn impulses<P>(&self, problem: &Problem<P>, x: &DVector<f64>) -> DVector<f64> {
        let mut lambda = DVector::zeros(problem.rows.len());
        for (block, (first, set)) in problem.blocks.iter().zip(&self.sets) {
            let values = &x.as_slice()[*first..*first + set.generators.len()];
            for (k, value) in set.impulses(values).into_iter().enumerate() {
                lambda[block.rows.start + k] = value;
            }
        }
        lambda
    }
}

/// Every ordered pair of blocks `(i, j)` (with `i = j`) that share a body an impulse moves.
fn coupled_blocks<P>(problem: &Problem<P>) -> Vec<(usize, usize)> {
    let mut touching: Vec<Vec<usize>> = vec![Vec::new(); problem.bodies.len()];
    for (index, block) in problem.blocks.iter().enumerate() {
        for body in [block.body_a.0, block.body_b.0] {
            let b = &problem.bodies[body];
            let moves = b.inv_mass != 0.0 || b.inv_inertia_world.iter().any(|&x| x != 0.0);
            if moves && touching[body].last() != Some(&index) {
                touching[body].push(index);
            }
        }
    }
    let mut pairs: Vec<(usize, usize)> = touching
        .iter()
        .flat_map(|blocks| {
            blocks
                .iter()
                .flat_map(|&i| blocks.iter().map(move |&j| (i, j)))
        })
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// Writes `impulses` into the rows and pushes them into the bodies' velocities.
fn apply<P>(problem: &mut Problem<P>, impulses: &DVector<f64>) {
    let Problem {
        bodies,
        rows,
        blocks,
    } = problem;
    for block in blocks.iter() {
        let (ia, ib) = (block.body_a.0, block.body_b.0);
        for r in block.rows.clone() {
            let (j, impulse) = (rows[r].jacobian, impulses[r]);
            rows[r].impulse = impulse;
            let (a, b) = (bodies[ia], bodies[ib]);
            bodies[ia].linear_velocity += j.linear_a * (a.inv_mass * impulse);
            bodies[ia].angular_velocity += a.inv_inertia_world * j.angular_a * impulse;
            bodies[ib].linear_velocity += j.linear_b * (b.inv_mass * impulse);
            bodies[ib].angular_velocity += b.inv_inertia_world * j.angular_b * impulse;
        }
    }
}
