//! The contact rows stage: every awake pair's rows (its model's blocks, the bounce of its
//! landing, the grip of a press), in the set's order.
//!
//! For a large set the pool's helpers are kept awake from collision ([`crate::parallel::Warm`]),
//! and the rows are shared: the calling thread builds runs of pairs from the first on straight
//! into the problem, the helpers runs from the last on, each into a piece of its own against the
//! same solver bodies, until the two meet ([`crate::parallel::from_both_ends`]); the helpers'
//! pieces are then appended in order. A pair's rows depend only on itself, the bodies and the
//! settings, so the problem is the one a single pass builds, to the bit, on any number of
//! threads (`tests/threads.rs`).
//!
//! The 1000-cube pile builds some 2,500 pairs' rows a step while it lands, about 0.95 ms on one
//! core. Every run built apart and all of them appended took 0.62 ms to build and 0.2 ms to
//! append (the rows stage no faster than on one thread); with the calling thread's share built
//! in place, the pile's rows stage fell from 0.83–0.85 to 0.63–0.67 ms (medians over 10 s).
//! Without the helpers kept awake, a helper woken at the rows took longer to start than a
//! pyramid's rows take.

use std::ops::Range;

use nalgebra::Vector3;
use tatami_contact::{ContactError, ContactModel, ContactProjection, ContactRows, Turns, grip};
use tatami_lcp::{Block, Row, SolverBody};

use crate::contact_set::{ContactSet, PairRows};
use crate::parallel::{self, Warm};
use crate::press::Presses;
use crate::{Body, ContactSettings, StepError, impact, tolerances};

/// Pairs a run holds: small enough that the two threads meet within a run of each other,
/// large enough that claiming a run costs nothing beside building it (about 6 µs).
const RUN: usize = 16;

/// Fewest pairs whose rows are worth building on every core, the helpers awake: below, the
/// copy of the helpers' share and the wait for the last of them cost about what they save.
const PARALLEL_ROWS: usize = 256;

/// Fewest blocks for which a collision pass on the calling thread alone wakes the pool's
/// helpers for the rows: a helper spinning through the pass cost the 210-cube pyramid (some 600
/// pairs of one block each, their rows 0.15 ms) more than it saved, in its solve's and
/// integration's time; the 820-cube one's rows (some 2,400 blocks) went from 0.64–0.77 to
/// 0.50–0.56 ms (four interleaved pairs of runs). Counted in blocks rather than pairs: the
/// resting bin of 300 small cubes holds 734 pairs, but cubes lying askew take 1,359 blocks
/// (bearing parts, landing points), and waking for them took 0.11–0.25 ms off its 2.1 ms step
/// (alternate steps of one run, seconds 5–10, three runs), where counting pairs kept its rows
/// on one thread.
const WAKE_FOR_ROWS: usize = 1024;

/// Whether the rows of a set of `pairs` pairs are worth building on every core, if the pool's
/// helpers are awake.
pub(crate) fn worth_every_core(pairs: usize) -> bool {
    pairs >= PARALLEL_ROWS
}

/// Whether the rows of `set` are worth waking the pool's helpers for: by the blocks its pairs
/// took in the last step, or by its pairs where they are more (at least a block each, once
/// their rows are built).
pub(crate) fn worth_waking(set: &ContactSet) -> bool {
    set.contacts().len().max(set.blocks_built()) >= WAKE_FOR_ROWS
}

/// What a pair's rows are built from, besides the pair.
pub(crate) struct RowInputs<'a> {
    /// The world's bodies (which are asleep, their shapes for a landing's bounce).
    pub bodies: &'a [Body],
    /// Each body's turn over the step ([`turn_of`]).
    pub turns: &'a [Vector3<f64>],
    /// Each pair's grip, if pressed.
    pub presses: &'a Presses,
    /// The contact model.
    pub model: ContactModel,
    /// The contact settings.
    pub settings: &'a ContactSettings,
    /// The step (s): a substep's, when the world's step is split.
    pub dt: f64,
    /// What a grip's press is divided by in place of `dt` (s): the world's step squared over
    /// `dt` (`dt` times the substeps squared), so that a press gives one force however the
    /// step is split ([`crate::substeps`]).
    pub grip_dt: f64,
    /// Gravity × `dt`, when the rows are to be warm-started: the guess for pairs with nothing
    /// stored is then made ahead, on a helper while the helpers' rows are copied in
    /// ([`ContactSet::estimate_loads_ahead`]).
    pub warm_start_weight: Option<Vector3<f64>>,
}

/// The runs of the rows stage, kept between steps so that they build without allocating.
#[derive(Debug, Clone, Default)]
pub(crate) struct RowRuns {
    runs: Vec<Run>,
    /// Each pair's blocks, in set order, as the runs are copied in.
    blocks: Vec<Range<usize>>,
}

/// A run of pairs: where each one's blocks end, and the storage of a run a helper builds.
#[derive(Debug, Clone, Default)]
struct Run {
    record: RunRecord,
    /// Rows, blocks and biases of a run a helper built, its block ranges counting from its
    /// first row; empty for a run built straight into the problem.
    rows: Vec<Row>,
    blocks: Vec<Block<ContactProjection>>,
    biases: Vec<f64>,
}

/// What building a run leaves beside its rows.
#[derive(Debug, Clone, Default)]
struct RunRecord {
    /// Per pair of the run, in order, where its blocks end in what the run was built into.
    ends: Vec<usize>,
    /// The run's first pair whose rows could not be built, and why; the run's later pairs are
    /// not built.
    failed: Option<(usize, ContactError)>,
}

impl RunRecord {
    /// Appends the rows of the pair at `index` to `out`: none for a pair with a body asleep,
    /// none after a pair of the run that failed.
    fn build(
        &mut self,
        (index, mut pair): (usize, PairRows<'_>),
        out: &mut ContactRows<'_>,
        inputs: &RowInputs<'_>,
    ) {
        let &RowInputs {
            bodies,
            turns,
            presses,
            model,
            settings,
            dt,
            grip_dt,
            ..
        } = inputs;
        let contact = pair.contact();
        let awake = !bodies[contact.body_a.0].asleep && !bodies[contact.body_b.0].asleep;
        if awake && self.failed.is_none() {
            let settings = &tolerances::pair_settings(settings, bodies, contact);
            let landed = pair.landed();
            // The face model's bearing part is kept with the pair while its contact is.
            let (contact, bearing) = match model {
                ContactModel::Face => {
                    let (contact, bearing) = pair.with_bearing(settings);
                    (contact, bearing.map(Some))
                }
                ContactModel::Vertex | ContactModel::Patch => (pair.contact(), Ok(None)),
            };
            let first_row = out.rows.len();
            let turns = Turns {
                a: turns[contact.body_a.0],
                b: turns[contact.body_b.0],
            };
            let built = bearing.and_then(|bearing| {
                model.build_rows_turned(contact, bearing, dt, &turns, settings, out)
            });
            match built {
                Err(source) => self.failed = Some((index, source)),
                Ok(()) => {
                    let rows = &mut out.rows[first_row..];
                    let at = (bodies, out.bodies);
                    impact::bounce_where_landed(contact, landed, at, rows, (settings, dt));
                    let press = presses.share(index);
                    if press > 0.0 {
                        grip::build_rows(contact, press, grip_dt, settings, out);
                    }
                    if presses.squeezed(index) {
                        out.biases[first_row..].fill(0.0);
                    }
                }
            }
        }
        self.ends.push(out.blocks.len());
    }
}

impl Run {
    fn clear(&mut self) {
        self.rows.clear();
        self.blocks.clear();
        self.biases.clear();
        self.record.ends.clear();
        self.record.failed = None;
    }

    /// The run's record, and its own rows, blocks and biases as built against `bodies`.
    fn apart<'a>(&'a mut self, bodies: &'a [SolverBody]) -> (&'a mut RunRecord, ContactRows<'a>) {
        let out = ContactRows {
            bodies,
            rows: &mut self.rows,
            blocks: &mut self.blocks,
            biases: &mut self.biases,
        };
        (&mut self.record, out)
    }
}

impl RowRuns {
    /// Appends every pair's rows to `out` (whose bodies they read), in the set's order, each
    /// pair recording its blocks; the first pair in that order whose rows cannot be built is
    /// the error. The rows are built on every core when `warm` holds the pool's helpers awake
    /// since collision (it is let go as the pairs are handed out), else on this thread.
    pub(crate) fn build(
        &mut self,
        set: &mut ContactSet,
        inputs: &RowInputs<'_>,
        out: &mut ContactRows<'_>,
        warm: Option<Warm>,
    ) -> Result<(), StepError> {
        let count = set.contacts().len().div_ceil(RUN);
        if self.runs.len() < count {
            self.runs.resize_with(count, Run::default);
        }
        let runs = &mut self.runs[..count];
        runs.iter_mut().for_each(Run::clear);
        let solver_bodies = out.bodies;
        let mut start = out.blocks.len();
        let on_every_core = warm.is_some();
        drop(warm);
        let straight = set.build_in_runs(
            runs,
            RUN,
            on_every_core,
            |run, index, pair| run.record.build((index, pair), out, inputs),
            |run, index, pair| {
                let (record, mut apart) = run.apart(solver_bodies);
                record.build((index, pair), &mut apart, inputs);
            },
        );
        // The first pair in the set's order whose rows could not be built.
        if let Some((failed, source)) = runs.iter_mut().find_map(|run| run.record.failed.take()) {
            let contact = set
                .contacts()
                .nth(failed)
                .expect("a failed pair is in the set");
            return Err(StepError::Contact {
                pair: crate::world::pair_name(inputs.bodies, contact),
                source,
            });
        }
        let blocks = &mut self.blocks;
        blocks.clear();
        let mut append = || {
            for (k, run) in runs.iter_mut().enumerate() {
                let first_block = if k < straight {
                    0
                } else {
                    let first_block = out.blocks.len();
                    out.append(run.apart(solver_bodies).1);
                    first_block
                };
                for &end in &run.record.ends {
                    blocks.push(start..first_block + end);
                    start = first_block + end;
                }
            }
        };
        match inputs.warm_start_weight {
            // The helper, done with its runs, makes the warm start's guess meanwhile.
            Some(weight) if on_every_core => {
                let model = inputs.model;
                let ahead = || set.estimate_loads_ahead(model, solver_bodies, &weight);
                parallel::join_beside(append, ahead);
            }
            _ => append(),
        }
        for (index, blocks) in blocks.drain(..).enumerate() {
            set.set_blocks(index, blocks);
        }
        Ok(())
    }
}

/// How far `body` turns the points its contacts hold over a step of `dt` (rad; see
/// [`Turns`]): zero under a nanoradian, which bends no point of a body under a kilometre by
/// more than a femtometre, so that a body at rest costs its rows nothing for it.
pub(crate) fn turn_of(body: &Body, dt: f64) -> Vector3<f64> {
    let turn = body.material_spin() * dt;
    if turn.norm_squared() < 1e-18 {
        Vector3::zeros()
    } else {
        turn
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Point2, Point3, UnitQuaternion, Vector3};
    use tatami_contact::{Contact, ContactFrame, Material};
    use tatami_geometry::ConvexPolygon;
    use tatami_lcp::{BodyId, Problem, SolverBody};

    use super::*;
    use crate::contact_set::Pose;
    use crate::{BodyDesc, Shape, World};

    /// A floor and two cubes, "a" and "b", with their solver bodies.
    fn bodies() -> (World, Vec<SolverBody>) {
        let world = World::builder()
            .body(BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).name("floor"))
            .body(
                BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                    .name("a")
                    .position([0.0, 0.0, 1.5]),
            )
            .body(
                BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                    .name("b")
                    .position([3.0, 0.0, 1.5]),
            )
            .build()
            .expect("a valid scene");
        let solver = world.bodies().iter().map(Body::solver_body).collect();
        (world, solver)
    }

    /// `pairs` face contacts of cube "a" or "b" (in turn) on the floor, tilted a little off the
    /// world's axes, each a little deeper than the last.
    fn set_of(pairs: usize) -> ContactSet {
        let mut set = ContactSet::default();
        let square =
            [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)].map(|(x, y)| Point2::new(x, y));
        let normal = Vector3::new(0.05, -0.03, 1.0).normalize();
        for k in 0..pairs {
            let (body, x) = if k % 2 == 0 { (1, 0.0) } else { (2, 3.0) };
            let depth = 1e-4 * (k % 7) as f64;
            let contact = Contact {
                body_a: BodyId(body),
                body_b: BodyId(0),
                centre_a: Point3::new(x, 0.0, 1.5),
                centre_b: Point3::new(0.0, 0.0, 0.0),
                frame: ContactFrame::from_normal(Point3::new(x, 0.0, 1.0), normal).unwrap(),
                support: ConvexPolygon::from_points(&square).unwrap(),
                depths: vec![depth; 4],
                material: Material::new(0.5, 0.5, 0.0).unwrap(),
                landing: Vec::new(),
                bounce_speed: 0.0,
            };
            let pose: Pose = (Point3::new(x, 0.0, 1.5), UnitQuaternion::identity());
            set.insert((contact, Default::default(), [pose, pose]));
        }
        set
    }

    /// Builds `set`'s rows in a pool of `threads` threads, on every core when `parallel`.
    fn build(
        set: &mut ContactSet,
        threads: usize,
        parallel: bool,
    ) -> Result<(Problem<ContactProjection>, Vec<f64>), StepError> {
        let (world, solver) = bodies();
        let presses = Presses::default();
        let settings = ContactSettings::default();
        let turns: Vec<_> = world
            .bodies()
            .iter()
            .map(|b| turn_of(b, 1.0 / 60.0))
            .collect();
        let inputs = RowInputs {
            bodies: world.bodies(),
            turns: &turns,
            presses: &presses,
            model: ContactModel::Face,
            settings: &settings,
            dt: 1.0 / 60.0,
            grip_dt: 1.0 / 60.0,
            warm_start_weight: None,
        };
        let mut problem = Problem {
            bodies: solver,
            ..Default::default()
        };
        let mut biases = Vec::new();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let warm = parallel.then(|| {
                let warm = Warm::start();
                // Time for the helpers to wake and spin, as collision gives them: the rows
                // then start with both threads (not a condition of the answer, which is the
                // same either way, but of the test's reaching the helpers' side).
                std::thread::sleep(std::time::Duration::from_millis(3));
                warm
            });
            let mut out = ContactRows::of(&mut problem, &mut biases);
            RowRuns::default().build(set, &inputs, &mut out, warm)
        })?;
        Ok((problem, biases))
    }

    /// Built on two threads (the helpers' runs apart, then appended) the rows, blocks, biases
    /// and each pair's blocks are those built in one pass on one thread. How many runs the
    /// helper takes depends on when it gets to them (now and then none): repeated, the helper's
    /// side is all but sure to be reached (checked by breaking the join's offsets: caught).
    #[test]
    fn rows_built_on_every_core_are_those_of_one_pass() {
        let pairs = 600;
        let mut one = set_of(pairs);
        let (serial, serial_biases) = build(&mut one, 1, false).unwrap();
        assert_eq!(serial.blocks.len(), pairs, "a face block a pair");
        for index in 0..pairs {
            assert_eq!(one.get(index).unwrap().1, index..index + 1, "pair {index}");
        }
        for attempt in 0..20 {
            let mut two = set_of(pairs);
            let (shared, shared_biases) = build(&mut two, 2, true).unwrap();
            assert_eq!(shared.rows, serial.rows, "attempt {attempt}");
            assert_eq!(shared.blocks, serial.blocks, "attempt {attempt}");
            assert_eq!(shared_biases, serial_biases, "attempt {attempt}");
            for index in 0..pairs {
                let (got, want) = (two.get(index).unwrap().1, one.get(index).unwrap().1);
                assert_eq!(got, want, "attempt {attempt}, pair {index}");
            }
        }
    }

    /// The helpers are woken for the rows by the blocks the last rows stage built: 600 faces
    /// flat on the floor take a block each, short of the mark, but 600 faces on one edge, the
    /// far edge 2 cm up, take a block for the edge and a landing block at each far corner.
    #[test]
    fn the_rows_are_worth_waking_for_by_their_blocks() {
        let pairs = 600;
        let mut flat = set_of(pairs);
        let (problem, _) = build(&mut flat, 1, false).unwrap();
        assert_eq!((flat.blocks_built(), problem.blocks.len()), (pairs, pairs));
        assert!(!worth_waking(&flat));
        let mut tilted = set_of(pairs);
        assert!(!worth_waking(&tilted), "no rows built yet");
        for index in 0..pairs {
            tilted.contact_mut(index).depths = vec![0.02, 0.0, 0.0, 0.02];
        }
        let (problem, _) = build(&mut tilted, 1, false).unwrap();
        assert_eq!(tilted.blocks_built(), problem.blocks.len());
        assert_eq!(
            problem.blocks.len(),
            3 * pairs,
            "a face and two landings a pair"
        );
        assert!(worth_waking(&tilted));
    }

    /// A pair whose rows cannot be built is an error naming it; of two such, the first in the
    /// set's order, wherever the threads built them.
    #[test]
    fn the_first_pair_that_fails_in_set_order_is_the_error() {
        let pairs = 600;
        for (threads, parallel) in [(1, false), (2, true), (3, true)] {
            for (bad, named) in [
                (vec![101, 500], "b–floor"),
                (vec![500], "a–floor"),
                (vec![599], "b–floor"),
            ] {
                let mut set = set_of(pairs);
                for &index in &bad {
                    // A material built by hand past `Material::new`'s checks.
                    set.contact_mut(index).material.static_friction = f64::NAN;
                }
                match build(&mut set, threads, parallel) {
                    Err(StepError::Contact { pair, .. }) => {
                        assert_eq!(pair, named, "{threads} threads, bad {bad:?}");
                    }
                    other => panic!("{threads} threads, bad {bad:?}: {other:?}"),
                }
            }
        }
    }
}
