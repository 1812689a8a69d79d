//! The direct solver: the contact problem solved exactly, as the reference for PGS.
//!
//! **Which problem.** The one PGS solves when every block's projection is a product of
//! [`RowBound`]s (what [`project_to_bounds`](crate::project_to_bounds) enforces): for each row,
//! with `w` its velocity relative to its target after the impulses,
//! - `NonNegative`: `λ ≥ 0 ⟂ w ≥ 0`;
//! - `Friction { normal, μ }`: `|λ| ≤ μ λₙ`, with `w = 0` inside and `λ = ∓μ λₙ` when `w ≷ 0`
//!   — box friction, one axis at a time (the *static* coefficient: the exact problem has no
//!   sticking/sliding switch);
//! - `Box { lo, hi }`: `λ` at `lo` with `w ≥ 0`, at `hi` with `w ≤ 0`, or between with `w = 0`.
//!
//! It is rewritten as a standard LCP and solved by [`lemke`](crate::lemke()):
//! a friction row becomes `λ = β⁺ − β⁻` with a slack `γ`: `β⁺ ⟂ w + γ ≥ 0`,
//! `β⁻ ⟂ −w + γ ≥ 0`, `γ ⟂ μ λₙ − β⁺ − β⁻ ≥ 0` (γ is the sliding speed); a finite box becomes
//! `λ = lo + u`, `u ⟂ w + y ≥ 0`, `y ⟂ (hi − lo) − u ≥ 0`; a half-infinite box a shifted sign
//! constraint and a free row `λ = u⁺ − u⁻`. Blocks whose projection is not a product of row
//! bounds (the face model's centre-of-pressure clamp) are rejected with
//! [`LcpError::Unsupported`]; their contact model states the equivalent bounds form.
//!
//! The rows' incoming impulses are ignored: the bodies' velocities are taken as those before any
//! contact impulse, and the answer's impulses, projected onto the row bounds to remove Lemke's
//! round-off, are written into the rows and applied.

use nalgebra::{DMatrix, DVector};

use crate::{LcpError, Problem, Projection, RowBound, dense, lemke, project_to_bounds};

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

/// Lemke rarely needs more than a few pivots per variable on contact problems; 50 leaves a wide
/// margin before [`LcpError::PivotLimit`].
pub const DEFAULT_PIVOTS_PER_VARIABLE: usize = 50;

/// 512 MiB: the dense matrices of about 4,600 standard-LCP variables, some 650 contact points
/// with box friction (7 variables each), or about 160 resting cubes of the vertex model.
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
/// variables allocates: `A` (rows²), the standard matrix (variables²) and Lemke's tableau
/// (variables × (2·variables + 2)), in f64. Saturates instead of overflowing.
pub fn dense_bytes(rows: usize, variables: usize) -> usize {
    let cells = rows
        .saturating_mul(rows)
        .saturating_add(variables.saturating_mul(variables))
        .saturating_add(variables.saturating_mul(variables.saturating_mul(2).saturating_add(2)));
    cells.saturating_mul(std::mem::size_of::<f64>())
}

/// What a direct solve did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DirectInfo {
    /// Variables of the standard LCP (≥ rows).
    pub variables: usize,
    /// Lemke pivots made.
    pub pivots: usize,
}

/// How one LCP variable enters the impulses: `λ[row] += sign · x`.
#[derive(Debug, Clone, Copy)]
struct Term {
    row: usize,
    sign: f64,
}

/// Solves `problem` exactly; writes impulses and velocities like the PGS solver.
pub fn solve<P: Projection>(
    problem: &mut Problem<P>,
    params: &DirectParams,
) -> Result<DirectInfo, LcpError> {
    problem.validate_bounds()?;
    let variables = StandardForm::variables(problem)?;
    let bytes = dense_bytes(problem.rows.len(), variables);
    if bytes > params.memory_budget {
        return Err(LcpError::TooLarge {
            variables,
            bytes,
            budget: params.memory_budget,
        });
    }
    let (a, b) = dense::assemble(problem);
    let lcp = StandardForm::new(problem, &a, &b)?;
    let (x, pivots) = lemke::solve(
        &lcp.matrix,
        &lcp.q,
        params.pivots_per_variable * lcp.q.len().max(1),
    )?;
    let mut impulses = lcp.impulses(&x);
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
    })
}

/// The standard LCP equivalent to the bounded rows, and the map back to impulses.
struct StandardForm {
    matrix: DMatrix<f64>,
    q: DVector<f64>,
    /// `λ = offset + Σ terms[v] · x[v]`.
    offset: DVector<f64>,
    terms: Vec<Option<Term>>,
}

/// The condition complementary to a variable: `sign · w[row] + extras ≥ 0`, or, for a slack,
/// `constant + extras ≥ 0`.
enum Condition {
    Velocity { row: usize, sign: f64 },
    Slack,
}

/// Accumulates variables, their conditions and the extra terms linking them.
#[derive(Default)]
struct Builder {
    terms: Vec<Option<Term>>,
    conditions: Vec<Condition>,
    constant: Vec<f64>,
    /// `(condition, variable, coefficient)` beyond the row-velocity part.
    extra: Vec<(usize, usize, f64)>,
}

impl Builder {
    /// A variable entering `λ[row]` with `sign`, complementary to `sign · w[row]` (+ extras).
    fn impulse(&mut self, row: usize, sign: f64) -> usize {
        self.add(Some(Term { row, sign }), Condition::Velocity { row, sign })
    }

    /// A slack variable that enters no impulse.
    fn slack(&mut self, constant: f64) -> usize {
        let v = self.add(None, Condition::Slack);
        self.constant[v] = constant;
        v
    }

    fn add(&mut self, term: Option<Term>, condition: Condition) -> usize {
        self.terms.push(term);
        self.conditions.push(condition);
        self.constant.push(0.0);
        self.terms.len() - 1
    }
}

impl StandardForm {
    /// Variables of the standard form of `problem`, counted without building it.
    fn variables<P: Projection>(problem: &Problem<P>) -> Result<usize, LcpError> {
        let mut count = 0usize;
        for (index, block) in problem.blocks.iter().enumerate() {
            for k in 0..block.rows.len() {
                let bound = block
                    .projection
                    .bound(k)
                    .ok_or(LcpError::Unsupported { block: index })?;
                count += match bound {
                    RowBound::NonNegative => 1,
                    // β⁺, β⁻ and the sliding speed γ.
                    RowBound::Friction { .. } => 3,
                    RowBound::Box { lo, hi } => match (lo.is_finite(), hi.is_finite()) {
                        (true, false) | (false, true) => 1,
                        _ => 2,
                    },
                };
            }
        }
        Ok(count)
    }

    fn new<P: Projection>(
        problem: &Problem<P>,
        a: &DMatrix<f64>,
        b: &DVector<f64>,
    ) -> Result<Self, LcpError> {
        let m = problem.rows.len();
        let mut form = Builder::default();
        let mut offset = DVector::zeros(m);
        // Variable carrying each NonNegative row's impulse, for the friction bounds on it.
        let mut normal_variable = vec![usize::MAX; m];
        let mut friction_rows = Vec::new();
        for (index, block) in problem.blocks.iter().enumerate() {
            for (k, row) in block.rows.clone().enumerate() {
                let bound = block
                    .projection
                    .bound(k)
                    .ok_or(LcpError::Unsupported { block: index })?;
                match bound {
                    RowBound::NonNegative => normal_variable[row] = form.impulse(row, 1.0),
                    RowBound::Friction {
                        normal,
                        coefficient,
                    } => {
                        let is_normal = normal < block.rows.len()
                            && matches!(
                                block.projection.bound(normal),
                                Some(RowBound::NonNegative)
                            );
                        if !is_normal || coefficient.is_nan() || coefficient < 0.0 {
                            return Err(LcpError::Unsupported { block: index });
                        }
                        friction_rows.push((row, block.rows.start + normal, coefficient));
                    }
                    RowBound::Box { lo, hi } => {
                        if lo.is_nan() || hi.is_nan() || lo > hi {
                            return Err(LcpError::InvalidBounds { row, lo, hi });
                        }
                        match (lo.is_finite(), hi.is_finite()) {
                            (true, true) => {
                                offset[row] = lo;
                                let u = form.impulse(row, 1.0);
                                let y = form.slack(hi - lo);
                                form.extra.extend([(u, y, 1.0), (y, u, -1.0)]);
                            }
                            (true, false) => {
                                offset[row] = lo;
                                form.impulse(row, 1.0);
                            }
                            (false, true) => {
                                offset[row] = hi;
                                form.impulse(row, -1.0);
                            }
                            (false, false) => {
                                form.impulse(row, 1.0);
                                form.impulse(row, -1.0);
                            }
                        }
                    }
                }
            }
        }
        for (row, normal_row, coefficient) in friction_rows {
            let plus = form.impulse(row, 1.0);
            let minus = form.impulse(row, -1.0);
            let slack = form.slack(0.0);
            form.extra.extend([
                (plus, slack, 1.0),
                (minus, slack, 1.0),
                (slack, plus, -1.0),
                (slack, minus, -1.0),
                (slack, normal_variable[normal_row], coefficient),
            ]);
        }

        let n = form.terms.len();
        let velocity_at_offset = a * &offset + b;
        let mut matrix = DMatrix::zeros(n, n);
        let mut q = DVector::from_vec(form.constant);
        for (c, condition) in form.conditions.iter().enumerate() {
            if let Condition::Velocity { row, sign } = *condition {
                q[c] += sign * velocity_at_offset[row];
                for (v, term) in form.terms.iter().enumerate() {
                    if let Some(t) = term {
                        matrix[(c, v)] += sign * t.sign * a[(row, t.row)];
                    }
                }
            }
        }
        for (c, v, coefficient) in form.extra {
            matrix[(c, v)] += coefficient;
        }
        Ok(Self {
            matrix,
            q,
            offset,
            terms: form.terms,
        })
    }

    fn impulses(&self, x: &DVector<f64>) -> DVector<f64> {
        let mut lambda = self.offset.clone();
        for (v, term) in self.terms.iter().enumerate() {
            if let Some(t) = term {
                lambda[t.row] += t.sign * x[v];
            }
        }
        lambda
    }
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
