//! A block's admissible impulses written as linear constraints: the form the direct solver needs.
//!
//! A block's impulses are `λ = offset + Σᵥ gᵥ xᵥ` with every `xᵥ ≥ 0` (the *generators* `gᵥ`,
//! sparse over the block's rows), under *budgets* `Σ_{v ∈ spend} xᵥ ≤ constant + Σ_{v ∈ earn}
//! cᵥ xᵥ`. Every bound Tatami's contact models use has this form:
//!
//! - a normal row `λ ≥ 0`: one generator `e_row`;
//! - box friction `|λ_t| ≤ μ λₙ`: generators `±e_t` spending a budget that earns `μ` per unit of
//!   the normal's generator;
//! - a finite box `lo ≤ λ ≤ hi`: offset `lo`, a generator `e_row`, a budget of `hi − lo`;
//! - a polygonal friction cone: generators `dⱼ` (the polygon's directions) on the tangent rows,
//!   one budget earning `μ` per unit normal (Stewart and Trinkle, 1996);
//! - the face model's centre of pressure inside the support polygon: one generator
//!   `(1, yₖ, −xₖ)` on `(f3, τ1, τ2)` per polygon vertex `(xₖ, yₖ)`, since `(f3, τ1, τ2)` is a
//!   non-negative combination of unit normal forces at the vertices exactly when `f3 ≥ 0` and
//!   the centre of pressure `(−τ2, τ1)/f3` lies in the polygon.
//!
//! The complementarity that makes a solution physical (maximal dissipation) is, with `w` the
//! block's row velocities relative to their targets and `γ_b ≥ 0` one multiplier per budget:
//! `xᵥ ⟂ gᵥᵀ w + Σ_{b: v ∈ spend_b} γ_b ≥ 0` and `γ_b ⟂ budget b's slack ≥ 0`. For friction `γ` is
//! the sliding speed; for a normal generator the condition is the contact point's separation
//! speed.

use crate::RowBound;

/// One generator: `(row within the block, coefficient)` pairs.
pub type Generator = Vec<(usize, f64)>;

/// `Σ_{v ∈ spend} xᵥ ≤ constant + Σ_{(v, c) ∈ earn} c · xᵥ`.
#[derive(Debug, Clone, PartialEq)]
pub struct Budget {
    /// Generators drawing on the budget.
    pub spend: Vec<usize>,
    /// Generators feeding it, with their rate (a friction coefficient, times a lever arm for
    /// twist).
    pub earn: Vec<(usize, f64)>,
    /// Fixed amount (a box's width); 0 for friction.
    pub constant: f64,
}

/// A block's admissible impulses as generators and budgets (module docs).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LinearSet {
    /// `λ` when every generator is zero, per row of the block.
    pub offset: Vec<f64>,
    /// The generators.
    pub generators: Vec<Generator>,
    /// The budgets.
    pub budgets: Vec<Budget>,
}

impl LinearSet {
    /// The set `{0}` of a block of `rows` rows, to add generators and budgets to.
    pub fn new(rows: usize) -> Self {
        Self {
            offset: vec![0.0; rows],
            ..Self::default()
        }
    }

    /// Adds a generator; returns its index.
    pub fn generator(&mut self, entries: Generator) -> usize {
        self.generators.push(entries);
        self.generators.len() - 1
    }

    /// Adds generators `±e_row` spending one budget that earns `earn`: `|λ_row| ≤ Σ c xᵥ`.
    pub fn symmetric(&mut self, row: usize, earn: Vec<(usize, f64)>) {
        let plus = self.generator(vec![(row, 1.0)]);
        let minus = self.generator(vec![(row, -1.0)]);
        self.budgets.push(Budget {
            spend: vec![plus, minus],
            earn,
            constant: 0.0,
        });
    }

    /// The set given by one [`RowBound`] per row; `None` if a row has none, a friction bound
    /// does not name a normal row of the block, or a bound is NaN.
    pub fn from_bounds(rows: usize, bound: impl Fn(usize) -> Option<RowBound>) -> Option<Self> {
        let mut set = Self::new(rows);
        let bounds: Vec<RowBound> = (0..rows).map(&bound).collect::<Option<_>>()?;
        // The generator carrying each normal row, for the friction budgets that earn from it.
        let mut normal = vec![None; rows];
        for (row, b) in bounds.iter().enumerate() {
            match *b {
                RowBound::NonNegative => normal[row] = Some(set.generator(vec![(row, 1.0)])),
                RowBound::Friction { .. } => {}
                RowBound::Box { lo, hi } => {
                    if lo.is_nan() || hi.is_nan() || lo > hi {
                        return None;
                    }
                    match (lo.is_finite(), hi.is_finite()) {
                        (true, true) => {
                            set.offset[row] = lo;
                            let u = set.generator(vec![(row, 1.0)]);
                            set.budgets.push(Budget {
                                spend: vec![u],
                                earn: Vec::new(),
                                constant: hi - lo,
                            });
                        }
                        (true, false) => {
                            set.offset[row] = lo;
                            set.generator(vec![(row, 1.0)]);
                        }
                        (false, true) => {
                            set.offset[row] = hi;
                            set.generator(vec![(row, -1.0)]);
                        }
                        (false, false) => {
                            set.generator(vec![(row, 1.0)]);
                            set.generator(vec![(row, -1.0)]);
                        }
                    }
                }
            }
        }
        for (row, b) in bounds.iter().enumerate() {
            if let RowBound::Friction {
                normal: n,
                coefficient,
            } = *b
            {
                let carrier = normal.get(n).copied().flatten()?;
                if coefficient.is_nan() || coefficient < 0.0 {
                    return None;
                }
                set.symmetric(row, vec![(carrier, coefficient)]);
            }
        }
        Some(set)
    }

    /// Indices in range and every number finite, rates and constants `≥ 0`: what the direct
    /// solver needs to build a solvable problem.
    pub fn is_well_formed(&self) -> bool {
        let rows = self.offset.len();
        let generators = self.generators.len();
        self.offset.iter().all(|x| x.is_finite())
            && self
                .generators
                .iter()
                .flatten()
                .all(|&(row, c)| row < rows && c.is_finite())
            && self.budgets.iter().all(|b| {
                b.constant.is_finite()
                    && b.constant >= 0.0
                    && b.spend.iter().all(|&v| v < generators)
                    && b.earn
                        .iter()
                        .all(|&(v, rate)| v < generators && rate.is_finite() && rate >= 0.0)
            })
    }

    /// Standard-LCP variables the set takes: one per generator and one per budget.
    pub fn variables(&self) -> usize {
        self.generators.len() + self.budgets.len()
    }

    /// The impulses of generator values `x` (one per generator).
    pub fn impulses(&self, x: &[f64]) -> Vec<f64> {
        let mut lambda = self.offset.clone();
        for (g, &value) in self.generators.iter().zip(x) {
            for &(row, c) in g {
                lambda[row] += c * value;
            }
        }
        lambda
    }
}
