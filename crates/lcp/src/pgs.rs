//! Projected Gauss–Seidel by sequential impulses: prepare → sweep → store.
//!
//! Prepare computes, per row, `M⁻¹Jᵀ` (how a unit impulse changes A's and B's velocities) and
//! `k = J M⁻¹ Jᵀ` (the effective mass is `1/k`); `A` is never formed. A sweep visits blocks in
//! order and, in each block, rows in order (the contact models put normal rows first, then
//! friction, then the face model's torques, as the paper's Springhead does):
//!
//! `Δλ = ω (target − J v) / k`, `λ += Δλ`, `v += M⁻¹Jᵀ Δλ`,
//!
//! then the block's projection maps the block's `λ` back onto its admissible set and whatever it
//! moved is pushed into the velocities too (see [`crate::Projection`] for why after every row).
//! A sweep is O(rows) plus the projections. A fixed number of sweeps is run (15, the paper's),
//! not a tolerance: real-time budgets are fixed.
//!
//! **Friction pairs.** The two tangent rows of an isotropic friction disc
//! ([`Projection::tangent_pair`]) are updated together. With `e = J₂ v − target` their 2-vector
//! of velocity errors and `K = J₂ M⁻¹ J₂ᵀ` their 2×2 block of `A`, the step is the exact line
//! search along `−e` (rapier's `ContactConstraintTangentPart`):
//!
//! `Δλ = −ω (eᵀe / eᵀKe) e`, then the projection scales `λ` back onto the disc.
//!
//! While sticking, the step converges to `e = 0` like any Gauss–Seidel step. While sliding, a
//! fixed point on the disc's rim needs `λ − s e ∥ λ` with `s > 0`, so `λ ∥ −e`: the friction
//! impulse is antiparallel to the slip velocity it leaves, whatever the tangents' orientation —
//! Coulomb's maximal dissipation. The Newton step `Δλ = −K⁻¹e` was rejected: its fixed point is
//! `λ ∥ −K⁻¹e`, off the slip direction wherever `K` is not isotropic (a cube's corner).
//!
//! **Friction pairs with a twist.** A contact face's friction force and its twist about the
//! point `p` where that force acts may share one limit surface ([`Projection::twist_coupling`]):
//! the ball `|u| ≤ μ f_n` in `u = (f₁, f₂, τ′/r̄)`, `τ′ = τ₃ − (p × f)·n`. Its conjugate
//! velocity is `g = (e₁ − p_y e₃, e₂ + p_x e₃, r̄ e₃)` — the slip at `p` and `r̄` times the
//! spin, since `λ·e = u·g` — and the pair and the twist row are stepped together along `−g`
//! in `u` (`Δλ = s d`, `d` that direction in the rows, `s = ω |g|² / dᵀKd` the exact line
//! search on the 3 × 3 block of `A`), then the projection scales `u` back onto the ball. As for
//! the pair, a fixed point on the rim has `u ∥ −g`: the wrench that dissipates most on the
//! limit surface. Stepping the twist row on its own instead, each step's scaling takes the
//! budget from the other rows: a puck sliding and spinning sped up.
//!
//! **Whole blocks.** A block that asks for it ([`Projection::whole_block`]: the face model's
//! faces) is first stepped whole, `Δλ = −ω K⁻¹ e` with `K` its own 6 × 6 block of `A`
//! (factored by Cholesky when first needed in a solve), and the step is kept if it lands in
//! the admissible set — the sticking face with its centre of pressure inside, by far the commonest
//! case, is then solved exactly for its neighbours' current velocities in one update. Otherwise
//! the block is updated row by row as above, and for the rest of the solve. This does not move
//! the fixed points: where the whole step is kept, the row-by-row update converges to the same
//! block solution; where a bound is active, the row-by-row update decides (the Newton step's
//! fixed point would be off Coulomb's slip direction, see above). It lowered the drift of the
//! holding scenes (leaning stack 0.38 → 0.25 mm, the 820-cube pyramid's largest displacement
//! 14.5 → 10.6 cm) and brought the 210-cube pyramid to rest within the contact set's reuse
//! tolerance (its collision time fell tenfold). Whole steps tried on faces with no load yet
//! made a cold start's sweeps slow; they are no longer tried there (see below).
//!
//! **Unloaded blocks.** A block whose projection names its normal rows
//! ([`Projection::leading_normal_rows`]: a contact cone, where friction and torques need a
//! normal force) ends its row-by-row update once those rows leave every impulse at zero — a
//! contact parting, or not loaded yet, as most of a cold-started tall tower is (its load climbs
//! about one contact per sweep): the other rows' steps would each be projected back to zero, so
//! the answer is the same to the bit (to the sign of a zero; `tests/unloaded_blocks.rs`). A
//! block that carries nothing and whose normal rows' steps would each be clamped back to zero
//! is skipped after reading those rows alone, before any whole step, and its other rows'
//! responses are computed only when it is first updated: a face then meets its first whole
//! step, and pays for factoring `K`, only once it is loaded. Before, an unloaded face's whole
//! step landed on zero, which sent it row by row for the rest of the solve, after paying for
//! the factor. On the 100-cube tower's first step (stack-timing experiment, the models' solves
//! timed interleaved) the face model's solve went from 0.50× the vertex model's to 0.34×.
//!
//! **Stopping, island by island.** With [`PgsParams::tolerance`] > 0 an island (blocks joined
//! through bodies an impulse can move; a fixed floor joins nothing) stops after its first sweep
//! in which no row's update moved that row's velocity by as much as the tolerance. Warm-started
//! from an exact carry-over, an island at rest then costs one sweep; a moving one runs every
//! sweep, and no longer keeps the resting ones sweeping with it. Islands share no velocity a
//! block writes, so sweeping them one after the other gives the bits of sweeping them together:
//! with a tolerance of 0 the answer is that of whole-problem sweeps. The measure is each row's own
//! velocity change, so it reads in m/s (rad/s for angular rows) whatever the masses, unlike
//! `max |Δλ|`.
//!
//! **Quiet blocks.** Within an island that goes on sweeping, a block is passed over while it is
//! quiet: its last update moved its rows' velocities by less than the tolerance, and the other
//! blocks' updates since have moved its two bodies by less than the tolerance in all (each
//! update's change is added to both its bodies; a body no impulse moves never counts as
//! moved). Its update would then change about as little as the island's stopping test lets
//! pass, so skipping it keeps the answer within that test's reach and costs three comparisons. A
//! pile is one island through its bodies' contacts, and at rest a few blocks that keep
//! trading a fraction of a mm/s kept every one of its thousands of blocks sweeping: on the
//! settled 1000-cube pile the velocity solve ran its 12 sweeps on most steps (12 485 rows, the
//! largest row change stuck at 5e-4 m/s by two blocks under one body), and with quiet blocks
//! passed over it does about two sweeps' work a step. While a pile lands its blocks are
//! rarely quiet (under 2% of the visits passed over, a ninth as it comes to rest). With a
//! tolerance of 0 nothing is passed over.
//!
//! Decision record: the projection sees the whole block, not one row, because the face model's
//! centre of pressure couples three rows (τ₁, τ₂, f₃) and cannot be clamped one row at a time.
//! Box2D relaxes and warm-starts; Jolt warm-starts; the paper does neither, so both are options
//! of this solver, off in [`PgsParams::default`]; `tatami-world` warm-starts by default, from
//! the impulse each face-model block applied last step (other models' rows matched by contact
//! feature).

use nalgebra::{Matrix6, Vector3, Vector6};

use crate::island::{BlockIslands, DisjointSets};
use crate::quiet::Quiet;
use crate::{Jacobian, LcpError, Problem, Projection, SolverBody, TwistCoupling};

/// PGS sweeps per step. Default [`DEFAULT_ITERATIONS`] = 15 (the paper; Springhead's numIter).
pub const DEFAULT_ITERATIONS: usize = 15;

/// Successive over-relaxation factor ω. Default [`DEFAULT_RELAXATION`] = 1.0 (plain
/// Gauss–Seidel, the paper's).
pub const DEFAULT_RELAXATION: f64 = 1.0;

/// Whether the impulses already in the rows are applied before the first sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WarmStart {
    /// Start every solve from zero impulses (the paper's setting).
    #[default]
    Off,
    /// Apply the rows' current impulses first (last step's, carried over by the caller).
    On,
}

/// Whether the solve records how much the impulses changed in each sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Record {
    /// Record nothing (no allocation).
    #[default]
    Nothing,
    /// Record `max |Δλ|` of every sweep in [`PgsInfo::impulse_change`].
    ImpulseChange,
}

/// Settings of a PGS solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PgsParams {
    /// Sweeps; see [`DEFAULT_ITERATIONS`].
    pub iterations: usize,
    /// An island stops before `iterations` after a sweep in which every one of its rows' updates
    /// changed that row's own velocity by less than this (`|Δλ| · J M⁻¹ Jᵀ`: m/s, or rad/s for
    /// angular rows), and within a sweep its quiet blocks are passed over (module doc). 0, the
    /// default here and the paper's setting, runs every sweep over every block.
    pub tolerance: f64,
    /// Relaxation ω in (0, 2); see [`DEFAULT_RELAXATION`].
    pub relaxation: f64,
    /// See [`WarmStart`]; off by default, as in the paper.
    pub warm_start: WarmStart,
    /// See [`Record`].
    pub record: Record,
}

impl Default for PgsParams {
    fn default() -> Self {
        Self {
            iterations: DEFAULT_ITERATIONS,
            tolerance: 0.0,
            relaxation: DEFAULT_RELAXATION,
            warm_start: WarmStart::Off,
            record: Record::Nothing,
        }
    }
}

/// What a solve did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PgsInfo {
    /// Most sweeps an island ran: `iterations`, or fewer when every island met the `tolerance`.
    pub sweeps: usize,
    /// Row updates made (the rows of every block each sweep visited: all but the quiet ones), for
    /// throughput figures.
    pub row_updates: usize,
    /// `max |Δλ|` per sweep (over the islands that ran it) when [`Record::ImpulseChange`] was
    /// asked for, else empty.
    pub impulse_change: Vec<f64>,
}

/// How a unit impulse on a row changes A's and B's velocities: `M⁻¹Jᵀ`.
#[derive(Debug, Clone, Copy, Default)]
struct RowResponse {
    linear_a: Vector3<f64>,
    angular_a: Vector3<f64>,
    linear_b: Vector3<f64>,
    angular_b: Vector3<f64>,
    /// `k = J M⁻¹ Jᵀ`, the row's own entry of `A`.
    inverse_mass: f64,
    /// `1/k`; 0 for a row no impulse can move (both bodies fixed).
    effective_mass: f64,
    /// `J_next M⁻¹ Jᵀ`, the entry of `A` coupling the first row of a friction pair to the
    /// second; 0 for other rows.
    coupling: f64,
}

/// Most rows of a block PGS solves whole ([`Projection::whole_block`]): a contact face's six.
pub const WHOLE_BLOCK_ROWS: usize = 6;

/// Whether and how a block is stepped whole in the current solve.
#[derive(Debug, Clone, Copy)]
enum Whole {
    /// Row by row: the block does not ask for it, or its `K` is singular.
    No,
    /// Not tried yet in this solve; `K` is factored when it is.
    Untried,
    /// `K`'s Cholesky factor is in [`PgsWorkspace::factors`].
    Ready,
    /// Factored, but a whole step left its set in this solve: row by row for the rest of it
    /// (a [`resolve_in_place`] of the same problem starts it whole again).
    Left,
}

/// Buffers reused across solves so sweeps allocate nothing.
#[derive(Debug, Clone, Default)]
pub struct PgsWorkspace {
    responses: Vec<RowResponse>,
    /// Per block: how it is stepped whole in this solve.
    whole: Vec<Whole>,
    /// Per block: whether any of its impulses is nonzero (kept by the sweeps, so a skipped
    /// block's rows are not read).
    loaded: Vec<bool>,
    /// Per block: whether all its rows' responses are in `responses`. An unloaded block has
    /// only its normal rows' until it is first updated: most blocks of a cold-started tall
    /// tower never are in its solve.
    responded: Vec<bool>,
    /// Per block: `L` of `K = L Lᵀ` (`K` padded with the identity to 6 × 6), diagonal inverted
    /// ([`whole_block_factor`]), where `whole` says `Ready`. Only grown, never cleared: entries
    /// are written before they are read.
    factors: Vec<Matrix6<f64>>,
    /// The problem's blocks by island; each island stops on its own.
    islands: BlockIslands,
    block_impulse: Vec<f64>,
    /// The block's impulses as already pushed into the velocities.
    block_applied: Vec<f64>,
    /// Which blocks the sweeps pass over.
    quiet: Quiet,
}

impl PgsWorkspace {
    /// The last solve's bodies in islands: joined through each block between two bodies an
    /// impulse can move (a finite mass or inertia), the root of each island its smallest body.
    /// The solve's sweeps stop island by island on these; a caller that weighs the answer
    /// island by island (a shock pass's energy guard, say) can take them instead of joining
    /// the same blocks again. Holds no body before the first solve, and the last problem's
    /// after a solve that failed its checks.
    ///
    /// ```
    /// use nalgebra::{Matrix3, Vector3};
    /// use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
    /// use tatami_lcp::{Block, BodyId, BoundsProjection, Jacobian, Problem, Row, RowBound, SolverBody};
    ///
    /// // Bodies 0 and 1 joined by a block, 2 by one to the fixed body 3.
    /// let free = SolverBody {
    ///     inv_mass: 1.0,
    ///     inv_inertia_world: Matrix3::identity(),
    ///     linear_velocity: Vector3::zeros(),
    ///     angular_velocity: Vector3::zeros(),
    /// };
    /// let jacobian = Jacobian { linear_a: Vector3::z(), ..Jacobian::default() };
    /// let block = |a: usize, b: usize, row: usize| Block {
    ///     body_a: BodyId(a),
    ///     body_b: BodyId(b),
    ///     rows: row..row + 1,
    ///     projection: BoundsProjection(vec![RowBound::NonNegative]),
    /// };
    /// let mut problem = Problem {
    ///     bodies: vec![free, free, free, SolverBody::fixed()],
    ///     rows: vec![Row { jacobian, target: 0.0, impulse: 0.0 }; 2],
    ///     blocks: vec![block(1, 0, 0), block(2, 3, 1)],
    /// };
    /// let mut workspace = PgsWorkspace::default();
    /// pgs::solve_in_place(&mut problem, &mut workspace, &PgsParams::default())?;
    /// let islands = workspace.body_islands();
    /// assert_eq!([0, 1, 2, 3].map(|k| islands.root(k)), [0, 0, 2, 3]);
    /// # Ok::<(), tatami_lcp::LcpError>(())
    /// ```
    pub fn body_islands(&mut self) -> &mut DisjointSets {
        self.islands.body_sets()
    }
}

/// Solves `problem` with default parameters and a fresh workspace.
pub fn solve<P: Projection>(problem: &mut Problem<P>) -> Result<PgsInfo, LcpError> {
    solve_in_place(problem, &mut PgsWorkspace::default(), &PgsParams::default())
}

/// Solves `problem` in place: writes impulses into its rows and velocities into its bodies.
pub fn solve_in_place<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    params: &PgsParams,
) -> Result<PgsInfo, LcpError> {
    run(problem, workspace, params, Prepared::No)
}

/// [`solve_in_place`] for a problem last solved with `workspace` whose rows' Jacobians, blocks
/// and bodies' masses have not changed since — only targets, impulses and velocities may have
/// (a split-impulse position pass run in place on the velocity problem): the
/// rows' responses `M⁻¹Jᵀ` and the blocks' factors of the last solve are reused, which gives
/// the same answer to the bit as computing them again. A workspace that did not solve a
/// problem of this shape gets them computed.
///
/// ```
/// use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace};
/// use tatami_lcp::{BodyId, Block, BoundsProjection, Jacobian, Problem, Row, RowBound, SolverBody};
/// use nalgebra::{Matrix3, Vector3};
///
/// // A 1 kg body pressed on the ground; then the same row with another target.
/// let body = SolverBody {
///     inv_mass: 1.0,
///     inv_inertia_world: Matrix3::identity(),
///     linear_velocity: Vector3::new(0.0, 0.0, -1.0),
///     angular_velocity: Vector3::zeros(),
/// };
/// let jacobian = Jacobian {
///     linear_a: Vector3::z(),
///     angular_a: Vector3::zeros(),
///     linear_b: Vector3::zeros(),
///     angular_b: Vector3::zeros(),
/// };
/// let mut problem = Problem {
///     bodies: vec![body, SolverBody::fixed()],
///     rows: vec![Row { jacobian, target: 0.0, impulse: 0.0 }],
///     blocks: vec![Block {
///         body_a: BodyId(0),
///         body_b: BodyId(1),
///         rows: 0..1,
///         projection: BoundsProjection(vec![RowBound::NonNegative]),
///     }],
/// };
/// let mut workspace = PgsWorkspace::default();
/// pgs::solve_in_place(&mut problem, &mut workspace, &PgsParams::default())?;
/// assert!((problem.rows[0].impulse - 1.0).abs() < 1e-12);
/// problem.rows[0].target = 0.5;
/// problem.bodies[0].linear_velocity = Vector3::zeros();
/// pgs::resolve_in_place(&mut problem, &mut workspace, &PgsParams::default())?;
/// assert!((problem.rows[0].impulse - 0.5).abs() < 1e-12);
/// # Ok::<(), tatami_lcp::LcpError>(())
/// ```
pub fn resolve_in_place<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    params: &PgsParams,
) -> Result<PgsInfo, LcpError> {
    let same_shape = workspace.responses.len() >= problem.rows.len()
        && workspace.whole.len() == problem.blocks.len()
        && workspace.responded.len() == problem.blocks.len();
    let prepared = if same_shape {
        Prepared::Responses
    } else {
        Prepared::No
    };
    run(problem, workspace, params, prepared)
}

/// What the workspace already holds of the problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Prepared {
    No,
    /// The responses and factors of the last solve of the same problem.
    Responses,
}

fn run<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    params: &PgsParams,
    prepared: Prepared,
) -> Result<PgsInfo, LcpError> {
    problem.validate_bounds()?;
    prepare(problem, workspace, params.warm_start, prepared);
    let mut info = PgsInfo::default();
    if params.record == Record::ImpulseChange {
        info.impulse_change.reserve_exact(params.iterations);
    }
    // Taken out for the sweeps, which borrow the rest of the workspace; put back even on error.
    let mut islands = std::mem::take(&mut workspace.islands);
    islands.group(problem);
    let solved = solve_islands(problem, workspace, &islands, params, &mut info);
    workspace.islands = islands;
    solved?;
    problem.validate_bodies()?;
    Ok(info)
}

/// Each island's sweeps, until its own first quiet sweep or `params.iterations`; `info` gets
/// the most sweeps an island ran, the row updates made, and each sweep's largest impulse change
/// over the islands that ran it.
fn solve_islands<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    islands: &BlockIslands,
    params: &PgsParams,
    info: &mut PgsInfo,
) -> Result<(), LcpError> {
    // A problem without blocks is swept as one empty island, to report its sweeps.
    let none = islands.iter().next().is_none().then_some(&[][..]);
    for blocks in islands.iter().chain(none) {
        let mut ran = params.iterations;
        for sweeps in 1..=params.iterations {
            let (change, rows) = sweep(problem, workspace, blocks, params)?;
            info.row_updates = info.row_updates.saturating_add(rows);
            if params.record == Record::ImpulseChange {
                match info.impulse_change.get_mut(sweeps - 1) {
                    Some(largest) => *largest = largest.max(change.impulse),
                    None => info.impulse_change.push(change.impulse),
                }
            }
            if change.velocity < params.tolerance {
                ran = sweeps;
                break;
            }
        }
        info.sweeps = info.sweeps.max(ran);
    }
    Ok(())
}

/// Computes `M⁻¹Jᵀ` and effective masses, and applies or clears the starting impulses.
fn prepare<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    warm_start: WarmStart,
    prepared: Prepared,
) {
    let Problem {
        bodies,
        rows,
        blocks,
    } = problem;
    // Entries are written before they are read: here, or (an unloaded block's other rows) when
    // the block is first updated.
    workspace
        .responses
        .resize(rows.len(), RowResponse::default());
    let widest = blocks.iter().map(|b| b.rows.len()).max().unwrap_or(0);
    workspace.block_impulse.resize(widest, 0.0);
    workspace.block_applied.resize(widest, 0.0);
    workspace.loaded.clear();
    workspace.quiet.reset(bodies, blocks.len());
    if prepared == Prepared::No {
        workspace.whole.clear();
        workspace.responded.clear();
    }
    if workspace.factors.len() < blocks.len() {
        workspace.factors.resize(blocks.len(), Matrix6::zeros());
    }
    for (index, block) in blocks.iter().enumerate() {
        match prepared {
            Prepared::No => {
                let asks = block.projection.whole_block() && block.rows.len() <= WHOLE_BLOCK_ROWS;
                workspace
                    .whole
                    .push(if asks { Whole::Untried } else { Whole::No });
            }
            Prepared::Responses => {
                if let Whole::Left = workspace.whole[index] {
                    workspace.whole[index] = Whole::Ready;
                }
            }
        }
        let loaded = match warm_start {
            WarmStart::On => rows[block.rows.clone()]
                .iter()
                .any(|row| row.impulse != 0.0),
            WarmStart::Off => {
                let rows = &mut rows[block.rows.clone()];
                rows.iter_mut().for_each(|row| row.impulse = 0.0);
                false
            }
        };
        workspace.loaded.push(loaded);
        let (a, b) = (bodies[block.body_a.0], bodies[block.body_b.0]);
        let responses = &mut workspace.responses[block.rows.clone()];
        let normals = block.projection.leading_normal_rows();
        if prepared == Prepared::Responses {
            // Kept, all of them or the normal rows' (the others computed when first updated).
            if loaded && !workspace.responded[index] {
                responses_of(block, rows, &a, &b, responses);
                workspace.responded[index] = true;
            }
        } else if loaded || normals == 0 {
            responses_of(block, rows, &a, &b, responses);
            workspace.responded.push(true);
        } else {
            // Unloaded: what `stays_unloaded` reads, until the block is first updated.
            let normal_rows = &rows[block.rows.clone()][..normals];
            for (row, response) in normal_rows.iter().zip(responses.iter_mut()) {
                *response = response_of(&row.jacobian, &a, &b);
            }
            workspace.responded.push(false);
        }
        if loaded {
            for (row, response) in rows[block.rows.clone()].iter().zip(responses.iter()) {
                apply(
                    bodies,
                    block.body_a.0,
                    block.body_b.0,
                    response,
                    row.impulse,
                );
            }
        }
    }
}

/// How much a sweep, or one block's update, changed the impulses.
#[derive(Debug, Clone, Copy, Default)]
struct Change {
    /// `max |Δλ|`.
    impulse: f64,
    /// `max |Δλ| · k` over the rows, `k = J M⁻¹ Jᵀ` the row's own entry of `A`: the largest
    /// change of a row's velocity by its own update.
    velocity: f64,
}

impl Change {
    fn add(&mut self, delta: f64, response: &RowResponse) {
        self.impulse = self.impulse.max(delta.abs());
        self.velocity = self.velocity.max(delta.abs() * response.inverse_mass);
    }

    fn max(self, other: Change) -> Change {
        Change {
            impulse: self.impulse.max(other.impulse),
            velocity: self.velocity.max(other.velocity),
        }
    }
}

/// One Gauss–Seidel pass over `blocks` (an island's, in order), passing over the quiet ones;
/// returns how much it changed the impulses and how many rows it visited.
fn sweep<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    blocks: &[usize],
    params: &PgsParams,
) -> Result<(Change, usize), LcpError> {
    let relaxation = params.relaxation;
    let mut largest_change = Change::default();
    let mut visited = 0;
    for &index in blocks {
        let (body_a, body_b) = (
            problem.blocks[index].body_a.0,
            problem.blocks[index].body_b.0,
        );
        if workspace
            .quiet
            .skips(index, body_a, body_b, params.tolerance)
        {
            continue;
        }
        visited += problem.blocks[index].rows.len();
        if stays_unloaded(problem, workspace, index, relaxation) {
            continue;
        }
        let rows = problem.blocks[index].rows.clone();
        if !workspace.responded[index] {
            let block = &problem.blocks[index];
            let (a, b) = (
                problem.bodies[block.body_a.0],
                problem.bodies[block.body_b.0],
            );
            let responses = &mut workspace.responses[rows.clone()];
            responses_of(block, &problem.rows, &a, &b, responses);
            workspace.responded[index] = true;
        }
        if let Whole::Untried = workspace.whole[index] {
            workspace.whole[index] = match whole_block_factor(problem, workspace, index) {
                Some(factor) => {
                    workspace.factors[index] = factor;
                    Whole::Ready
                }
                None => Whole::No,
            };
        }
        let whole = match workspace.whole[index] {
            Whole::Ready => {
                let step = update_whole_block(problem, workspace, index, relaxation)?;
                if step.is_none() {
                    // A block at a bound (sliding, tipping, parting) stays there for a while,
                    // and would pay for both updates every sweep.
                    workspace.whole[index] = Whole::Left;
                }
                step
            }
            Whole::No | Whole::Untried | Whole::Left => None,
        };
        let change = match whole {
            Some(change) => change,
            None => update_block(
                problem,
                (
                    &mut workspace.block_impulse[..],
                    &mut workspace.block_applied[..],
                ),
                index,
                &workspace.responses[rows.clone()],
                relaxation,
            )?,
        };
        workspace.loaded[index] = problem.rows[rows].iter().any(|row| row.impulse != 0.0);
        workspace
            .quiet
            .updated(index, body_a, body_b, change.velocity);
        largest_change = largest_change.max(change);
    }
    Ok((largest_change, visited))
}

/// Whether block `index` carries nothing and its normal rows' steps would leave it so: each
/// would push its row below zero, where the projection clamps it back ([`Projection::
/// leading_normal_rows`]). The block's update would then change nothing, so the sweep looks at
/// its normal rows alone and moves on — a contact parting, or one not loaded yet, as are most
/// of a cold-started tall tower's contacts for most of its sweeps (the load climbs about one
/// contact per sweep). Neither is the block stepped whole: an unloaded face keeps its first
/// whole step, and the factor it needs, for when its load arrives.
fn stays_unloaded<P: Projection>(
    problem: &Problem<P>,
    workspace: &PgsWorkspace,
    index: usize,
    relaxation: f64,
) -> bool {
    let block = &problem.blocks[index];
    let normals = block.projection.leading_normal_rows();
    if normals == 0 || workspace.loaded[index] {
        return false;
    }
    let rows = &problem.rows[block.rows.clone()];
    let (a, b) = (
        &problem.bodies[block.body_a.0],
        &problem.bodies[block.body_b.0],
    );
    let responses = &workspace.responses[block.rows.clone()];
    rows.iter()
        .zip(responses)
        .take(normals)
        .all(|(row, response)| {
            // The row-by-row step from zero; a NaN is not `≤ 0` and goes on to be reported.
            -relaxation * response.effective_mass * (row.jacobian.velocity(a, b) - row.target)
                <= 0.0
        })
}

/// The Cholesky factor `L` (`K = L Lᵀ`) of block `index`, with `K = J M⁻¹ Jᵀ` its own part of
/// `A` (symmetric; padded with the identity to 6 × 6), its diagonal stored inverted (`1/Lᵢᵢ`,
/// see [`solve_factored`]); `None` if `K` is not positive definite. Factored once per solve, it
/// costs two triangular solves per update. Forming `K⁻¹` instead (one 6 × 6 product per update)
/// took 9% off a cold-started tower's 15 sweeps but made the warm-started tower's step 20%
/// slower, where a block takes one or two whole steps a solve; measured again against the
/// divisionless solves, with nalgebra's `Cholesky::inverse`, every `general_comparison` scene
/// was slower (the tower's step by 37%, the piles' velocity solve by 4–8%).
fn whole_block_factor<P: Projection>(
    problem: &Problem<P>,
    workspace: &PgsWorkspace,
    index: usize,
) -> Option<Matrix6<f64>> {
    let range = problem.blocks[index].rows.clone();
    let rows = &problem.rows[range.clone()];
    let responses = &workspace.responses[range];
    let mut k = Matrix6::identity();
    for i in 0..rows.len() {
        for j in i..rows.len() {
            k[(i, j)] = along(&rows[i].jacobian, &responses[j]);
            k[(j, i)] = k[(i, j)];
        }
    }
    factor_for_solves(k)
}

/// `L` of `k = L Lᵀ` with its diagonal inverted, for [`solve_factored`]; `None` if `k` is not
/// positive definite.
fn factor_for_solves(k: Matrix6<f64>) -> Option<Matrix6<f64>> {
    k.cholesky().map(|c| {
        let mut factor = c.unpack();
        for i in 0..WHOLE_BLOCK_ROWS {
            factor[(i, i)] = 1.0 / factor[(i, i)];
        }
        factor
    })
}

/// Solves `K x = b` in place, given `L` of `K` with its diagonal inverted
/// ([`factor_for_solves`]): `L y = b`, then `Lᵀ x = y`, multiplying by `1/Lᵢᵢ` where the
/// textbook divides by `Lᵢᵢ`. Those twelve divisions sat one after the other on the update's
/// dependency chain; without them the piles' velocity solve took 6–8% less (the
/// `general_comparison` bench, three interleaved pairs of runs, on one thread and on two).
fn solve_factored(factor: &Matrix6<f64>, b: &mut Vector6<f64>) {
    for i in 0..WHOLE_BLOCK_ROWS {
        let mut x = b[i];
        for j in 0..i {
            x -= factor[(i, j)] * b[j];
        }
        b[i] = x * factor[(i, i)];
    }
    for i in (0..WHOLE_BLOCK_ROWS).rev() {
        let mut x = b[i];
        for j in i + 1..WHOLE_BLOCK_ROWS {
            x -= factor[(j, i)] * b[j];
        }
        b[i] = x * factor[(i, i)];
    }
}

/// The whole-block step: `Δλ = −ω K⁻¹ e` for the block's velocity errors `e`, kept only if
/// `λ + Δλ` is admissible, when it is the exact solution of the block with its neighbours held
/// (one step where row-by-row updates converge over sweeps). Otherwise nothing changes and
/// `None` sends the block to the row-by-row update. Either way a fixed point is one of the
/// row-by-row update's: at a fixed point with every bound inactive `e = 0` and `Δλ = 0`.
fn update_whole_block<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &PgsWorkspace,
    index: usize,
    relaxation: f64,
) -> Result<Option<Change>, LcpError> {
    let Problem {
        bodies,
        rows,
        blocks,
    } = problem;
    let block = &mut blocks[index];
    let (ia, ib) = (block.body_a.0, block.body_b.0);
    let responses = &workspace.responses[block.rows.clone()];
    let rows = &mut rows[block.rows.clone()];
    let mut error = Vector6::zeros();
    for (e, row) in error.iter_mut().zip(rows.iter()) {
        *e = row.jacobian.velocity(&bodies[ia], &bodies[ib]) - row.target;
    }
    let factor = &workspace.factors[index];
    let mut delta = error * -relaxation;
    solve_factored(factor, &mut delta);
    let mut trial = [0.0; WHOLE_BLOCK_ROWS];
    for (k, row) in rows.iter().enumerate() {
        trial[k] = row.impulse + delta[k];
    }
    if !block.projection.admissible(&trial[..rows.len()]) {
        return Ok(None);
    }
    let mut largest_change = Change::default();
    for (k, row) in rows.iter_mut().enumerate() {
        if delta[k] != 0.0 {
            if !delta[k].is_finite() {
                return Err(LcpError::NonFinite { block: index });
            }
            apply(bodies, ia, ib, &responses[k], delta[k]);
        }
        largest_change.add(delta[k], &responses[k]);
        row.impulse = trial[k];
    }
    Ok(Some(largest_change))
}

/// Updates the rows of block `index` once each (a friction pair as one 2-D step), with its
/// rows' `responses` (its own, or the shock pass's) and `buffers` for its impulses (the
/// workspace's `block_impulse` and `block_applied`); returns how much it changed the impulses.
fn update_block<P: Projection>(
    problem: &mut Problem<P>,
    buffers: (&mut [f64], &mut [f64]),
    index: usize,
    responses: &[RowResponse],
    relaxation: f64,
) -> Result<Change, LcpError> {
    let Problem {
        bodies,
        rows,
        blocks,
    } = problem;
    let block = &mut blocks[index];
    let (ia, ib) = (block.body_a.0, block.body_b.0);
    // The two bodies' velocities are read and moved after every row: copies stay in registers
    // for the block's update instead of going through the body array each time (written back
    // below; the masses are in the responses). A block on one body keeps the copies equal, in
    // the order `apply` adds to it.
    let same = ia == ib;
    let (mut a, mut b) = (Motion::of(&bodies[ia]), Motion::of(&bodies[ib]));
    let push = |a: &mut Motion, b: &mut Motion, response: &RowResponse, delta: f64| {
        a.linear += response.linear_a * delta;
        a.angular += response.angular_a * delta;
        if same {
            *b = *a;
        }
        b.linear += response.linear_b * delta;
        b.angular += response.angular_b * delta;
        if same {
            *a = *b;
        }
    };
    let update = BlockUpdate {
        bodies: (&mut a, &mut b),
        rows: &mut rows[block.rows.clone()],
        projection: &mut block.projection,
        responses,
        buffers,
        relaxation,
    };
    // A point contact's 3 rows, a segment's 5 and a face's 6 get their own copies of the loop,
    // whose lengths the compiler then knows (the segment's copy took 6% off the instructions of
    // a 1000-cube pile's solve).
    let result = match update.rows.len() {
        3 => update_block_rows::<P, 3>(update, push),
        5 => update_block_rows::<P, 5>(update, push),
        6 => update_block_rows::<P, 6>(update, push),
        _ => update_block_rows::<P, 0>(update, push),
    };
    a.write_to(&mut bodies[ia]);
    b.write_to(&mut bodies[ib]);
    result.map_err(|()| LcpError::NonFinite { block: index })
}

/// A body's velocities, all a row update reads and moves of it.
#[derive(Debug, Clone, Copy)]
struct Motion {
    linear: Vector3<f64>,
    angular: Vector3<f64>,
}

impl Motion {
    fn of(body: &SolverBody) -> Self {
        Self {
            linear: body.linear_velocity,
            angular: body.angular_velocity,
        }
    }

    fn write_to(&self, body: &mut SolverBody) {
        body.linear_velocity = self.linear;
        body.angular_velocity = self.angular;
    }
}

/// What one block's row-by-row update works on: copies of its two bodies' velocities, its rows,
/// projection and responses, and the solver's buffers for its impulses.
struct BlockUpdate<'a, P> {
    bodies: (&'a mut Motion, &'a mut Motion),
    rows: &'a mut [crate::Row],
    projection: &'a mut P,
    responses: &'a [RowResponse],
    buffers: (&'a mut [f64], &'a mut [f64]),
    relaxation: f64,
}

/// [`update_block`]'s rows, on copies of the block's two bodies moved by `push`; `Err` on a
/// non-finite step. `ROWS` is the block's row count, or 0 for any.
fn update_block_rows<P: Projection, const ROWS: usize>(
    update: BlockUpdate<'_, P>,
    push: impl Fn(&mut Motion, &mut Motion, &RowResponse, f64),
) -> Result<Change, ()> {
    let BlockUpdate {
        bodies: (a, b),
        rows,
        projection,
        responses,
        buffers: (impulse, applied),
        relaxation,
    } = update;
    let n = if ROWS == 0 { rows.len() } else { ROWS };
    let rows = &mut rows[..n];
    let responses = &responses[..n];
    let impulse = &mut impulse[..n];
    let applied = &mut applied[..n];
    for (k, row) in rows.iter().enumerate() {
        impulse[k] = row.impulse;
        applied[k] = row.impulse;
    }
    let pair = projection
        .tangent_pair()
        .filter(|&first| first + 1 < rows.len());
    let normals = projection.leading_normal_rows();
    // The twist row the pair's last step also moved: not stepped again on its own.
    let mut coupled_twist = None;
    let mut k = 0;
    while k < rows.len() {
        let error = |r: usize, a: &Motion, b: &Motion| {
            rows[r]
                .jacobian
                .velocity_of([&a.linear, &a.angular], [&b.linear, &b.angular])
                - rows[r].target
        };
        if coupled_twist == Some(k) {
            k += 1;
            continue;
        }
        let width = if pair == Some(k) {
            let (e1, e2) = (error(k, a, b), error(k + 1, a, b));
            let (r1, r2) = (&responses[k], &responses[k + 1]);
            let coupling = projection
                .twist_coupling(impulse)
                .filter(|c| c.row > k + 1 && c.row < rows.len());
            coupled_twist = coupling.map(|c| c.row);
            match coupling {
                Some(c) => {
                    let e = [e1, e2, error(c.row, a, b)];
                    let twist = (&rows[c.row].jacobian, &responses[c.row]);
                    let step = twist_coupled_step(&c, e, (r1, r2), twist, relaxation);
                    for (row, delta) in [k, k + 1, c.row].into_iter().zip(step) {
                        impulse[row] += delta;
                    }
                }
                // Exact line search along −e on the quadratic ½ λᵀKλ + eᵀλ (module doc).
                None => {
                    let curvature = r1.inverse_mass * e1 * e1
                        + 2.0 * r1.coupling * e1 * e2
                        + r2.inverse_mass * e2 * e2;
                    if curvature > 0.0 {
                        let step = relaxation * (e1 * e1 + e2 * e2) / curvature;
                        impulse[k] -= step * e1;
                        impulse[k + 1] -= step * e2;
                    }
                }
            }
            2
        } else {
            impulse[k] -= relaxation * responses[k].effective_mass * error(k, a, b);
            1
        };
        projection.project(impulse, k);
        for j in 0..rows.len() {
            let delta = impulse[j] - applied[j];
            if delta != 0.0 {
                if !delta.is_finite() {
                    return Err(());
                }
                push(a, b, &responses[j], delta);
                applied[j] = impulse[j];
            }
        }
        k += width;
        // Unloaded: the rest of the block is zero and would be projected back to zero.
        if k == normals && impulse.iter().all(|&x| x == 0.0) {
            break;
        }
    }
    let mut largest_change = Change::default();
    for ((row, &new), response) in rows.iter_mut().zip(impulse.iter()).zip(responses) {
        largest_change.add(new - row.impulse, response);
        row.impulse = new;
    }
    Ok(largest_change)
}

/// The step of a friction pair and the twist row coupled to it by a limit surface (`c`): the
/// exact line search along the surface's slip direction (module doc). `e` are the three rows'
/// velocity errors, `pair` the pair's responses, `twist` the twist row's Jacobian and
/// response. Zero where no impulse moves them.
fn twist_coupled_step(
    c: &TwistCoupling,
    e: [f64; 3],
    pair: (&RowResponse, &RowResponse),
    twist: (&Jacobian, &RowResponse),
    relaxation: f64,
) -> [f64; 3] {
    let [px, py] = c.centre;
    // The slip at the centre of pressure and r̄ times the spin: the ball's conjugate velocity.
    let slip = [e[0] - py * e[2], e[1] + px * e[2], c.radius * e[2]];
    // Along −slip in the ball's units, written in the rows: τ3 = τ′ + (p × f)·n.
    let d = [
        -slip[0],
        -slip[1],
        -(c.radius * slip[2] + px * slip[1] - py * slip[0]),
    ];
    let ((r1, r2), (j3, r3)) = (pair, twist);
    let (k13, k23) = (along(j3, r1), along(j3, r2));
    let curvature = r1.inverse_mass * d[0] * d[0]
        + r2.inverse_mass * d[1] * d[1]
        + r3.inverse_mass * d[2] * d[2]
        + 2.0 * (r1.coupling * d[0] * d[1] + k13 * d[0] * d[2] + k23 * d[1] * d[2]);
    if curvature <= 0.0 {
        return [0.0; 3];
    }
    // −eᵀd = |slip|²: the quadratic's slope along d.
    let step = relaxation * (slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]) / curvature;
    d.map(|x| step * x)
}

/// Which body of a block the shock pass holds still.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Support {
    /// Body A carries body B.
    A,
    /// Body B carries body A.
    B,
}

/// A pair's sweeps in [`shock_propagation_per_pair`] stop once one changes no row's velocity by
/// more than this (m/s).
pub const SHOCK_PAIR_TOLERANCE: f64 = 1e-12;

/// Shock propagation (Guendelman, Bridson and Fedkiw, 2003): one more Gauss–Seidel pass, after
/// a solve, over the blocks in `order`, in which each block's supporting body is held still —
/// only the other body's velocity changes. Run from the ground up, it sets every body to rest
/// on the one below it exactly, so a stack's weight needs no sweeps to travel down; the price is
/// that the supporting bodies do not feel this last pass's reactions (momentum is not
/// conserved by it). A caller that runs it by default should keep its result only when it does
/// not add energy, as `tatami-world` does.
///
/// Errors as [`solve_in_place`], and [`LcpError::MalformedBlock`] for an `order` entry past the
/// last block (the problem then unchanged).
pub fn shock_propagation<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    order: &[(usize, Support)],
) -> Result<(), LcpError> {
    shock_propagation_per_pair(problem, workspace, order, 1)
}

/// [`shock_propagation`] in which each pair's blocks — the entries of `order` next to each
/// other on the same two bodies, held the same way — are swept together up to `pair_sweeps`
/// times, until a sweep changes no row's velocity by more than [`SHOCK_PAIR_TOLERANCE`].
///
/// One update of a block solved whole (the face model's) rests its body on the support
/// exactly; one pass over a face's per-vertex blocks, or over a patch's rows, does not: it
/// shares the load among the vertices otherwise than the sweeps did and leaves the body a
/// little motion, which a warm start carries into the next step. A tower of 18 levels of three
/// crossed 1.5 × 2.5 × 7.5 cm blocks at 60 Hz, at rest to 1e-15 m after 5 s, then grew that
/// motion about 5% a step until it fell at 10–15 s under the vertex and patch models; with 10
/// sweeps a pair, the pass's impulses still warm-started, it creeps by 3 nm (patch) and 0.16 µm
/// (vertex) in 60 s (`tatami-world` now warm-starts those models from the sweeps' impulses,
/// and it stands to 1e-14 m). With `pair_sweeps` = 1 this is [`shock_propagation`].
pub fn shock_propagation_per_pair<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    order: &[(usize, Support)],
    pair_sweeps: usize,
) -> Result<(), LcpError> {
    shock_pass(problem, workspace, order, pair_sweeps, None, Check::Problem)
}

/// [`shock_propagation_per_pair`] with the blocks' responses to their supported bodies
/// computed ahead ([`HeldResponses::compute`]), on another thread while the sweeps before the
/// pass run, say. The same answer to the bit, given responses computed from this problem's
/// Jacobians, blocks and bodies' masses as they are now (a copy of it with other targets,
/// impulses or velocities gives the same ones); responses computed for another `order`, or for
/// blocks of other sizes, are not used, and the pass computes its own as it goes.
///
/// ```
/// use nalgebra::{Matrix3, Vector3};
/// use tatami_lcp::pgs::{self, HeldResponses, PgsWorkspace, Support};
/// use tatami_lcp::{BodyId, Block, BoundsProjection, Jacobian, Problem, Row, RowBound, SolverBody};
///
/// // A 1 kg body falling at 1 m/s onto the ground (body 1, fixed), which holds it.
/// let body = SolverBody {
///     inv_mass: 1.0,
///     inv_inertia_world: Matrix3::identity(),
///     linear_velocity: Vector3::new(0.0, 0.0, -1.0),
///     angular_velocity: Vector3::zeros(),
/// };
/// let jacobian = Jacobian { linear_a: Vector3::z(), ..Jacobian::default() };
/// let problem = Problem {
///     bodies: vec![body, SolverBody::fixed()],
///     rows: vec![Row { jacobian, target: 0.0, impulse: 0.0 }],
///     blocks: vec![Block {
///         body_a: BodyId(0),
///         body_b: BodyId(1),
///         rows: 0..1,
///         projection: BoundsProjection(vec![RowBound::NonNegative]),
///     }],
/// };
/// let order = [(0, Support::B)];
/// let mut held = HeldResponses::default();
/// held.compute(&problem, &order)?;
/// let (mut ahead, mut as_it_goes) = (problem.clone(), problem);
/// let mut workspace = PgsWorkspace::default();
/// pgs::shock_propagation_with(&mut ahead, &mut workspace, &order, 1, &held)?;
/// pgs::shock_propagation_per_pair(&mut as_it_goes, &mut workspace, &order, 1)?;
/// assert_eq!(ahead.bodies[0].linear_velocity, Vector3::zeros());
/// assert_eq!(ahead.rows[0].impulse, as_it_goes.rows[0].impulse);
/// # Ok::<(), tatami_lcp::LcpError>(())
/// ```
pub fn shock_propagation_with<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    order: &[(usize, Support)],
    pair_sweeps: usize,
    held: &HeldResponses,
) -> Result<(), LcpError> {
    let given = held.for_order(problem, order);
    shock_pass(
        problem,
        workspace,
        order,
        pair_sweeps,
        given,
        Check::Problem,
    )
}

/// [`solve_in_place`], keeping the solved problem for a shock pass that need not check it again
/// ([`Solved`]).
///
/// ```
/// use nalgebra::{Matrix3, Vector3};
/// use tatami_lcp::pgs::{self, PgsParams, PgsWorkspace, Support};
/// use tatami_lcp::{BodyId, Block, BoundsProjection, Jacobian, Problem, Row, RowBound, SolverBody};
///
/// // A 1 kg body falling at 1 m/s onto the ground (body 1, fixed).
/// let body = SolverBody {
///     inv_mass: 1.0,
///     inv_inertia_world: Matrix3::identity(),
///     linear_velocity: Vector3::new(0.0, 0.0, -1.0),
///     angular_velocity: Vector3::zeros(),
/// };
/// let jacobian = Jacobian { linear_a: Vector3::z(), ..Jacobian::default() };
/// let mut problem = Problem {
///     bodies: vec![body, SolverBody::fixed()],
///     rows: vec![Row { jacobian, target: 0.0, impulse: 0.0 }],
///     blocks: vec![Block {
///         body_a: BodyId(0),
///         body_b: BodyId(1),
///         rows: 0..1,
///         projection: BoundsProjection(vec![RowBound::NonNegative]),
///     }],
/// };
/// let mut workspace = PgsWorkspace::default();
/// let (_, solved) = pgs::solve_for_shock(&mut problem, &mut workspace, &PgsParams::default())?;
/// let speed = solved.problem().bodies[0].linear_velocity.z;
/// solved.shock_propagation(&mut workspace, &[(0, Support::B)], 1, None)?;
/// assert!(speed.abs() < 1e-4 && problem.bodies[0].linear_velocity.z == 0.0);
/// # Ok::<(), tatami_lcp::LcpError>(())
/// ```
pub fn solve_for_shock<'a, P: Projection>(
    problem: &'a mut Problem<P>,
    workspace: &mut PgsWorkspace,
    params: &PgsParams,
) -> Result<(PgsInfo, Solved<'a, P>), LcpError> {
    let info = solve_in_place(problem, workspace, params)?;
    Ok((info, Solved { problem }))
}

/// A problem [`solve_for_shock`] has just solved, held until its shock pass. Nothing can
/// change it meanwhile, and the solve checked its rows, blocks and bounds and left its
/// impulses and velocities finite, so the pass need not check them again as
/// [`shock_propagation_per_pair`] does: about 45 instructions a row, which on a 1000-cube
/// pile's velocity solve was 3% of its instructions at rest.
#[derive(Debug)]
pub struct Solved<'a, P> {
    problem: &'a mut Problem<P>,
}

impl<P: Projection> Solved<'_, P> {
    /// The solved problem, to read (to set the solve's answer aside before the pass, say).
    pub fn problem(&self) -> &Problem<P> {
        self.problem
    }

    /// [`shock_propagation_per_pair`] on the solved problem, without checking it again, with
    /// `held` responses computed ahead as [`shock_propagation_with`] takes them: the same
    /// answer to the bit. Errors as the solve's, and [`LcpError::MalformedBlock`] for an
    /// `order` entry past the last block (the problem then unchanged).
    pub fn shock_propagation(
        self,
        workspace: &mut PgsWorkspace,
        order: &[(usize, Support)],
        pair_sweeps: usize,
        held: Option<&HeldResponses>,
    ) -> Result<(), LcpError> {
        let given = held.and_then(|held| held.for_order(self.problem, order));
        shock_pass(
            self.problem,
            workspace,
            order,
            pair_sweeps,
            given,
            Check::Solved,
        )
    }
}

/// Whether a shock pass checks its problem first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Check {
    /// Its rows, blocks and bounds ([`Problem::validate_bounds`]).
    Problem,
    /// Not again: PGS has just solved it ([`Solved`]).
    Solved,
}

/// The responses `M⁻¹Jᵀ` of the blocks of a shock pass's `order` with each block's supporting
/// body held still, in that order: what the pass computes as it goes, computed ahead for
/// [`shock_propagation_with`]. They read only the rows' Jacobians, the blocks and the bodies'
/// masses, so a split-impulse position pass, a copy of the velocity problem with other
/// targets, can compute them for both passes while the velocity sweeps run.
#[derive(Debug, Clone, Default)]
pub struct HeldResponses {
    /// The order they were computed for, each entry with its block's row count then.
    order: Vec<(usize, Support, usize)>,
    /// Each entry's rows' responses, entry after entry.
    responses: Vec<RowResponse>,
}

impl HeldResponses {
    /// The responses, if they were computed for `order` on blocks of the sizes `problem`'s
    /// have.
    fn for_order<P>(
        &self,
        problem: &Problem<P>,
        order: &[(usize, Support)],
    ) -> Option<&[RowResponse]> {
        let rows = |index: usize| problem.blocks.get(index).map(|block| block.rows.len());
        let fits = self.order.len() == order.len()
            && (self.order.iter().zip(order)).all(|(&(index, support, count), &entry)| {
                (index, support) == entry && rows(index) == Some(count)
            });
        fits.then_some(&self.responses[..])
    }

    /// Computes them for `order` on `problem`, reusing this value's buffers.
    /// [`LcpError::MalformedBlock`] for an `order` entry past the last block, or a block whose
    /// rows or bodies the problem does not have (nothing is kept then).
    pub fn compute<P: Projection>(
        &mut self,
        problem: &Problem<P>,
        order: &[(usize, Support)],
    ) -> Result<(), LcpError> {
        self.order.clear();
        self.responses.clear();
        for &(index, _) in order {
            let well_formed = (problem.blocks.get(index))
                .is_some_and(|block| block.within(problem.rows.len(), problem.bodies.len()));
            if !well_formed {
                return Err(LcpError::MalformedBlock { block: index });
            }
        }
        for &(index, support) in order {
            let start = self.responses.len();
            let end = start + problem.blocks[index].rows.len();
            self.responses.resize(end, RowResponse::default());
            held_responses(problem, index, support, &mut self.responses[start..end]);
        }
        (self.order).extend(
            (order.iter())
                .map(|&(index, support)| (index, support, problem.blocks[index].rows.len())),
        );
        Ok(())
    }
}

/// The shock pass of [`shock_propagation_per_pair`], with `order`'s held responses given
/// (`held`, entry after entry) or computed as it goes, checking the problem first or not.
fn shock_pass<P: Projection>(
    problem: &mut Problem<P>,
    workspace: &mut PgsWorkspace,
    order: &[(usize, Support)],
    pair_sweeps: usize,
    held: Option<&[RowResponse]>,
    check: Check,
) -> Result<(), LcpError> {
    if check == Check::Problem {
        problem.validate_bounds()?;
    }
    let widest = problem
        .blocks
        .iter()
        .map(|b| b.rows.len())
        .max()
        .unwrap_or(0);
    for buffer in [&mut workspace.block_impulse, &mut workspace.block_applied] {
        buffer.resize(widest, 0.0);
    }
    for index in order.iter().map(|&(index, _)| index) {
        if index >= problem.blocks.len() {
            return Err(LcpError::MalformedBlock { block: index });
        }
    }
    let sweeps = pair_sweeps.max(1);
    let mut at = 0;
    // Where the next pair's given responses start in `held`.
    let mut held_at = 0;
    while at < order.len() {
        // One pair's blocks: the entries after `at` on the same two bodies, held the same way.
        let pair = |&(index, support): &(usize, Support)| {
            let block = &problem.blocks[index];
            (block.body_a, block.body_b, support)
        };
        let len = order[at..]
            .iter()
            .take_while(|entry| pair(entry) == pair(&order[at]))
            .count();
        let group = &order[at..at + len];
        at += len;
        let rows: usize = group
            .iter()
            .map(|&(index, _)| problem.blocks[index].rows.len())
            .sum();
        // The blocks' responses with the supporting body immovable: given, or written after
        // the solve's own in the group's order — all of them first when the pair is swept more
        // than once, otherwise each when its block is first updated (most blocks of a position
        // pass stay unloaded and are skipped before).
        let given = held.map(|held| &held[held_at..held_at + rows]);
        held_at += rows;
        let first = problem.rows.len();
        if given.is_none() {
            workspace
                .responses
                .resize(first + rows, RowResponse::default());
            if sweeps > 1 {
                let mut start = first;
                for &(index, support) in group {
                    let end = start + problem.blocks[index].rows.len();
                    held_responses(
                        problem,
                        index,
                        support,
                        &mut workspace.responses[start..end],
                    );
                    start = end;
                }
            }
        }
        for _ in 0..sweeps {
            let mut change = Change::default();
            let mut start = 0;
            for &(index, support) in group {
                let responses = start..start + problem.blocks[index].rows.len();
                start = responses.end;
                if stays_unloaded_held(problem, &problem.blocks[index]) {
                    continue;
                }
                let responses = match given {
                    Some(given) => &given[responses],
                    None => {
                        let responses = first + responses.start..first + responses.end;
                        let out = &mut workspace.responses[responses.clone()];
                        if sweeps == 1 {
                            held_responses(problem, index, support, out);
                        }
                        &workspace.responses[responses]
                    }
                };
                let buffers = (
                    &mut workspace.block_impulse[..],
                    &mut workspace.block_applied[..],
                );
                change = change.max(update_block(problem, buffers, index, responses, 1.0)?);
            }
            if change.velocity <= SHOCK_PAIR_TOLERANCE {
                break;
            }
        }
    }
    problem.validate_bodies()
}

/// Writes block `index`'s responses with its `support` body held still into `out` (one per
/// row).
fn held_responses<P: Projection>(
    problem: &Problem<P>,
    index: usize,
    support: Support,
    out: &mut [RowResponse],
) {
    let block = &problem.blocks[index];
    let (mut a, mut b) = (
        problem.bodies[block.body_a.0],
        problem.bodies[block.body_b.0],
    );
    let held = match support {
        Support::A => &mut a,
        Support::B => &mut b,
    };
    held.inv_mass = 0.0;
    held.inv_inertia_world = nalgebra::Matrix3::zeros();
    responses_of(block, &problem.rows, &a, &b, out);
}

/// [`stays_unloaded`] for the shock pass: whether `block` carries nothing and its normal rows
/// are each at or past their target, so that each step, whatever the responses with the held
/// body, is clamped back to zero and the update would change nothing. Most blocks of a
/// position pass, and the face model's landing blocks, are such; the pass skips them before
/// computing their responses.
fn stays_unloaded_held<P: Projection>(problem: &Problem<P>, block: &crate::Block<P>) -> bool {
    let normals = block.projection.leading_normal_rows();
    let rows = &problem.rows[block.rows.clone()];
    if normals == 0 || rows.iter().any(|row| row.impulse != 0.0) {
        return false;
    }
    let (a, b) = (
        &problem.bodies[block.body_a.0],
        &problem.bodies[block.body_b.0],
    );
    // A NaN is not `≥ 0` and goes on to be reported.
    rows[..normals]
        .iter()
        .all(|row| row.jacobian.velocity(a, b) - row.target >= 0.0)
}

/// Writes the responses of `block`'s rows between bodies `a` and `b` into `out` (one per row),
/// with the coupling of its friction pair, if any.
fn responses_of<P: Projection>(
    block: &crate::Block<P>,
    rows: &[crate::Row],
    a: &SolverBody,
    b: &SolverBody,
    out: &mut [RowResponse],
) {
    let rows = &rows[block.rows.clone()];
    for (row, response) in rows.iter().zip(out.iter_mut()) {
        *response = response_of(&row.jacobian, a, b);
    }
    if let Some(first) = block.projection.tangent_pair()
        && first + 1 < rows.len()
    {
        out[first].coupling = along(&rows[first + 1].jacobian, &out[first]);
    }
}

/// How a unit impulse on a row with Jacobian `j` changes the velocities of `a` and `b`.
#[inline]
fn response_of(j: &Jacobian, a: &SolverBody, b: &SolverBody) -> RowResponse {
    let mut response = RowResponse {
        linear_a: j.linear_a * a.inv_mass,
        angular_a: a.inv_inertia_world * j.angular_a,
        linear_b: j.linear_b * b.inv_mass,
        angular_b: b.inv_inertia_world * j.angular_b,
        ..RowResponse::default()
    };
    let k = along(j, &response);
    response.inverse_mass = k.max(0.0);
    response.effective_mass = if k > 0.0 { 1.0 / k } else { 0.0 };
    response
}

/// `J M⁻¹Jᵣᵀ`: how fast a row with Jacobian `j` moves per unit impulse of the row whose response
/// is `response`.
#[inline]
fn along(j: &Jacobian, response: &RowResponse) -> f64 {
    j.linear_a.dot(&response.linear_a)
        + j.angular_a.dot(&response.angular_a)
        + j.linear_b.dot(&response.linear_b)
        + j.angular_b.dot(&response.angular_b)
}

/// `v += M⁻¹Jᵀ λ` for both bodies of a row.
#[inline]
fn apply(bodies: &mut [SolverBody], a: usize, b: usize, response: &RowResponse, impulse: f64) {
    bodies[a].linear_velocity += response.linear_a * impulse;
    bodies[a].angular_velocity += response.angular_a * impulse;
    bodies[b].linear_velocity += response.linear_b * impulse;
    bodies[b].angular_velocity += response.angular_b * impulse;
}

#[cfg(test)]
mod tests {
    use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
    use proptest::prelude::*;

    use super::*;
    use crate::{Block, BodyId, BoundsProjection, Jacobian, Row, RowBound};

    proptest! {
        /// The solve with the inverted diagonal against nalgebra's Cholesky solve, on symmetric
        /// positive definite `K = M Mᵀ + I/10` with `M`'s entries within ±1 (eigenvalues from
        /// 0.1 to 36.1, a condition number below 400), whole and as a 3-row block padded with
        /// the identity. Both are backward stable, so they differ by about the condition number
        /// times the rounding, below 1e-13 of the answer's largest entry: 1e-12 leaves room.
        #[test]
        fn solves_as_the_textbook_cholesky_does(
            m in proptest::collection::vec(-1.0..1.0f64, 36),
            b in proptest::collection::vec(-10.0..10.0f64, 6),
            padded in any::<bool>(),
        ) {
            let m = Matrix6::from_column_slice(&m);
            let mut k = m * m.transpose() + Matrix6::identity() * 0.1;
            if padded {
                k.fixed_view_mut::<3, 6>(3, 0).fill(0.0);
                k.fixed_view_mut::<6, 3>(0, 3).fill(0.0);
                k.fixed_view_mut::<3, 3>(3, 3).fill_with_identity();
            }
            let b = Vector6::from_column_slice(&b);
            let expected = k.cholesky().expect("positive definite").solve(&b);
            let mut x = b;
            solve_factored(&factor_for_solves(k).expect("positive definite"), &mut x);
            let scale = expected.amax().max(1.0);
            prop_assert!((x - expected).amax() <= 1e-12 * scale, "{x} against {expected}");
        }
    }

    /// A matrix that is not positive definite has no factor, as before.
    #[test]
    fn an_indefinite_block_has_no_factor() {
        let mut k = Matrix6::identity();
        k[(2, 2)] = -1.0;
        assert!(factor_for_solves(k).is_none());
    }

    /// Two boxes stacked off centre on a fixed floor, falling: each contact a normal row and a
    /// friction pair under `μ = 0.5`, at a corner (`rows` 3), or the normal row alone (`rows`
    /// 1), turned so that every response has all its terms.
    fn stack(rows: usize) -> Problem<BoundsProjection> {
        let body = |z: f64| SolverBody {
            inv_mass: 1.0,
            inv_inertia_world: Matrix3::new(2.0, 0.3, 0.0, 0.3, 3.0, 0.1, 0.0, 0.1, 2.5),
            linear_velocity: Vector3::new(0.1, 0.0, -z),
            angular_velocity: Vector3::new(0.0, 0.2, 0.0),
        };
        let row = |direction: Vector3<f64>, at: Vector3<f64>, on_b: bool| Row {
            jacobian: Jacobian {
                linear_a: direction,
                angular_a: at.cross(&direction),
                linear_b: if on_b { -direction } else { Vector3::zeros() },
                angular_b: if on_b {
                    -(at + Vector3::z()).cross(&direction)
                } else {
                    Vector3::zeros()
                },
            },
            target: 0.0,
            impulse: 0.0,
        };
        let at = Vector3::new(0.4, -0.3, -0.5);
        let rows_of = |on_b: bool| {
            [Vector3::z(), Vector3::x(), Vector3::y()]
                .into_iter()
                .take(rows)
                .map(|d| row(d, at, on_b))
                .collect::<Vec<_>>()
        };
        let (lower, upper) = (rows_of(false), rows_of(true));
        let bounds = (0..rows)
            .map(|k| match k {
                0 => RowBound::NonNegative,
                _ => RowBound::Friction {
                    normal: 0,
                    coefficient: 0.5,
                },
            })
            .collect::<Vec<_>>();
        let block = |a: usize, b: usize, first: usize| Block {
            body_a: BodyId(a),
            body_b: BodyId(b),
            rows: first..first + rows,
            projection: BoundsProjection(bounds.clone()),
        };
        Problem {
            bodies: vec![SolverBody::fixed(), body(1.0), body(2.0)],
            rows: lower.into_iter().chain(upper).collect(),
            blocks: vec![block(1, 0, 0), block(2, 1, rows)],
        }
    }

    /// Every impulse and velocity as bits.
    fn bits(problem: &Problem<BoundsProjection>) -> Vec<u64> {
        let impulses = problem.rows.iter().map(|row| row.impulse);
        let velocities = (problem.bodies.iter()).flat_map(|body| {
            body.linear_velocity
                .iter()
                .chain(&body.angular_velocity)
                .copied()
        });
        impulses.chain(velocities).map(f64::to_bits).collect()
    }

    /// Held responses computed ahead give the pass computed as it goes to the bit, once and
    /// swept ten times a pair; computed for another order, or for blocks of another size (the
    /// same count of rows in all), they are not used, and the pass is still the same.
    #[test]
    fn held_responses_computed_ahead_give_the_same_bits() {
        let order = [(0, Support::B), (1, Support::B)];
        for sweeps in [1, 10] {
            let as_it_goes = |mut problem: Problem<BoundsProjection>| {
                shock_propagation_per_pair(
                    &mut problem,
                    &mut PgsWorkspace::default(),
                    &order,
                    sweeps,
                )
                .unwrap();
                bits(&problem)
            };
            let ahead = |mut problem: Problem<BoundsProjection>, held: &HeldResponses| {
                shock_propagation_with(
                    &mut problem,
                    &mut PgsWorkspace::default(),
                    &order,
                    sweeps,
                    held,
                )
                .unwrap();
                bits(&problem)
            };
            let mut held = HeldResponses::default();
            held.compute(&stack(3), &order).unwrap();
            assert_eq!(
                ahead(stack(3), &held),
                as_it_goes(stack(3)),
                "{sweeps} sweeps"
            );
            held.compute(&stack(3), &order[1..]).unwrap();
            assert_eq!(
                ahead(stack(3), &held),
                as_it_goes(stack(3)),
                "another order"
            );
            // The same six rows in all, split 2 + 4 instead of 3 + 3.
            let mut resized = stack(3);
            resized.blocks[0].rows = 0..2;
            resized.blocks[0].projection.0.truncate(2);
            resized.blocks[1].rows = 2..6;
            resized.blocks[1]
                .projection
                .0
                .insert(1, RowBound::NonNegative);
            held.compute(&resized, &order).unwrap();
            assert_eq!(ahead(stack(3), &held), as_it_goes(stack(3)), "other sizes");
        }
        // And the pass does something here: the falling boxes are stopped.
        let mut problem = stack(1);
        shock_propagation(
            &mut problem,
            &mut PgsWorkspace::default(),
            &[(0, Support::B)],
        )
        .unwrap();
        assert!(problem.rows[0].impulse > 0.0);
    }

    /// The shock pass on a problem just solved, unchecked, against the same solve and pass
    /// checked: the same bits, with and without held responses; an `order` entry past the last
    /// block is still an error, which leaves the problem as solved.
    #[test]
    fn a_solved_problem_takes_the_same_shock_pass_unchecked() {
        let order = [(0, Support::B), (1, Support::B)];
        let params = PgsParams::default();
        let mut checked = stack(3);
        let mut workspace = PgsWorkspace::default();
        solve_in_place(&mut checked, &mut workspace, &params).unwrap();
        shock_propagation_per_pair(&mut checked, &mut workspace, &order, 1).unwrap();
        let mut held = HeldResponses::default();
        held.compute(&stack(3), &order).unwrap();
        for held in [None, Some(&held)] {
            let mut problem = stack(3);
            let (_, solved) = solve_for_shock(&mut problem, &mut workspace, &params).unwrap();
            solved
                .shock_propagation(&mut workspace, &order, 1, held)
                .unwrap();
            assert_eq!(bits(&problem), bits(&checked), "held: {}", held.is_some());
        }
        let mut problem = stack(3);
        let (_, solved) = solve_for_shock(&mut problem, &mut workspace, &params).unwrap();
        let as_solved = bits(solved.problem());
        assert_eq!(
            solved.shock_propagation(&mut workspace, &[(2, Support::B)], 1, None),
            Err(LcpError::MalformedBlock { block: 2 })
        );
        assert_eq!(bits(&problem), as_solved);
    }
}
