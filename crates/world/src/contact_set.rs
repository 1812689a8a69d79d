//! The persistent contact set: one entry per touching pair of bodies, owning everything about the
//! pair across steps — its contact (frame, support polygon, depths, material), a feature id per
//! support vertex (under the models that key rows by vertex), where the two bodies were when the
//! contact was computed, the blocks its rows take in this step's problem, and what it ended the
//! last solve with.
//!
//! A step uses it in stages, as Box2D v3's solver does: collision [`begin`](ContactSet::begin)s
//! a pass, [`refresh`](ContactSet::refresh)es the pairs it holds (keeping the contact of one
//! that has not moved, recomputing the others in place, on every core) while the broad phase
//! [`meet`](Meeting::meet)s each overlapping pair, [`insert`](ContactSet::insert)s new ones,
//! [`keep_apart`](ContactSet::keep_apart)s the new pairs found apart along an axis (they
//! are met, untested, while their bodies could not have closed the gap: [`crate::apart`]),
//! and [`end`](ContactSet::end)s the pass, which is where pairs no longer touching or no longer
//! met are dropped; rows are built in set order, each pair
//! recording its blocks; [`warm_start`](ContactSet::warm_start) starts every row from the last
//! solve — the face model's one block per pair from the impulse all its blocks applied to body A
//! ([`ContactImpulse`]), moved to the new block's point and read on its axes, whatever its
//! support became; the vertex and patch models' rows from the impulse of the row with the same
//! key, the feature id of the support vertex the row acts at (or the whole contact) and the
//! row's rank there, so a row is matched exactly or starts from zero, never from a neighbour's
//! impulse — and a pair with nothing stored starts its normal rows from the weight it carries
//! ([`crate::load_estimate`]); after the solve [`store`](ContactSet::store) keeps them.
//!
//! The set's order is the Gauss–Seidel order: from the highest contact to the lowest along
//! gravity, so a stack's weight reaches its base within one sweep instead of one level per sweep
//! (bottom-up lowered the first step's error of a 10-tower only from 0.094 to 0.080 m/s).

use std::ops::Range;

use nalgebra::{Matrix2, Point2, Point3, UnitQuaternion, Vector2, Vector3};
use tatami_contact::face::Bearing;
use tatami_contact::{
    Contact, ContactError, ContactImpulse, ContactModel, ContactProjection, ContactSettings,
};
use tatami_geometry::PolygonKind;
use tatami_lcp::pgs::Support;
use tatami_lcp::{Problem, Projection, SolverBody};

use crate::apart::{Apart, Placement};
use crate::broad_phase::order_by_pair;
use crate::carry::{CarryBounds, Drift, carry};
use crate::impact::Touchdown;
use crate::load_estimate::LoadEstimate;
use crate::nearly_sorted::sort_nearly_in_order_by;
use crate::parallel;
use crate::support::{FeatureId, FeatureIds, VertexIds};

/// Largest motion of either body (m; a turn counts as rad × the body's size) since a pair's
/// contact was computed for it to be kept: far below any depth that matters (the slop is 2 mm,
/// and the penetration push is 0.1 of the depth beyond it a step, so a depth 10 µm stale moves
/// the push by 1 µm; a speculative gap 10 µm stale lets the bodies close 10 µm more), and
/// above the jitter of a settled pile (half the 1000-cube pile's cubes move less than 4 µm a
/// step by its end). The motion counts from the poses the contact was computed at, so a
/// creeping body's contact is recomputed every 10 µm. Measured (`general_comparison`,
/// interleaved runs): 1 µm instead of 1 nm halved the 210-cube pyramid's collision time; 10 µm
/// instead of 1 µm took a quarter off the 1000-shape pile's (balls and cylinders rolling
/// slowly, whose contacts are the dearest to compute) and a little off the cube pile's, and
/// moved the holding and toppling scenes by micrometres (`CHANGES.md`).
pub(crate) const REUSE_TOLERANCE: f64 = 1e-5;

/// Where a body was: centre of mass and orientation.
pub(crate) type Pose = (Point3<f64>, UnitQuaternion<f64>);

/// A pair's contact as collision computes it: the contact, a feature id per support vertex, and
/// the poses of the two bodies it was computed at.
pub(crate) type Computed = (Contact, FeatureIds, [Pose; 2]);

/// What a pair's old contact leaves the one computed to replace it.
#[derive(Debug, Default)]
pub(crate) struct Recycled {
    /// Its depths buffer, for the new contact's depths.
    pub depths: Vec<f64>,
    /// Its normal, from B into A: where the search for the new one starts
    /// ([`crate::parry_bridge::contact_normal`]'s hint). `None` for a pair not held.
    pub normal: Option<Vector3<f64>>,
    /// Whether the new contact keeps that normal: the old one landed the pair, to be bounced
    /// along the normal it landed on ([`crate::impact`]).
    pub keep_normal: bool,
}

/// A pair of bodies, `(a, b)` with `a < b`.
type Pair = (usize, usize);

/// A pair kept apart: its gap, and whether the current pass met it.
type KeptApart = (Pair, Apart, bool);

/// The main thread's side of a collision pass while the held pairs are brought up to date
/// (see [`ContactSet::refresh`]): meets the pairs the broad phase finds. The broad phase finds
/// them in increasing order, and the set's lists are sorted by pair, so each is looked up by
/// walking on from where the last was found: no hashing, and memory read in sequence (with
/// hash maps, the lookups were 0.34 ms of the 1000-cube pile's step).
pub(crate) struct Meeting<'a> {
    held: &'a [(Pair, usize)],
    met: &'a mut [bool],
    apart: &'a mut [KeptApart],
    placements: &'a [Placement],
    margin: f64,
    /// Where the next lookup in `held` and in `apart` starts.
    cursors: (usize, usize),
}

impl Meeting<'_> {
    /// Meets pair `(a, b)`, found overlapping by the broad phase: `true` if the set holds it
    /// (it stays, if still touching) or holds it [apart](ContactSet::keep_apart) and its bodies
    /// cannot have closed the gap since (it stays apart, untested); `false` if it is to be
    /// computed, then [`ContactSet::insert`]ed or kept apart. Pairs met in increasing order
    /// are found in one walk through the lists; any order is correct.
    pub(crate) fn meet(&mut self, pair: Pair) -> bool {
        if let Some(k) = find(self.held, |h| h.0, &mut self.cursors.0, pair) {
            self.met[self.held[k].1] = true;
            return true;
        }
        match find(self.apart, |a| a.0, &mut self.cursors.1, pair) {
            Some(k) => {
                let (_, apart, met) = &mut self.apart[k];
                let (a, b) = (&self.placements[pair.0], &self.placements[pair.1]);
                let margin = self.margin + a.travel.closing(&b.travel);
                let still = apart.still_apart(a, b, margin);
                *met |= still;
                still
            }
            None => false,
        }
    }
}

/// The position of `pair` in `list` (sorted by `key`, without repeats), if it is there, searched
/// from `cursor` on when `pair` is not before it (the broad phase's increasing order), else
/// from the start; `cursor` is left where `pair` is or would be.
fn find<T>(list: &[T], key: impl Fn(&T) -> Pair, cursor: &mut usize, pair: Pair) -> Option<usize> {
    if *cursor > 0 && key(&list[*cursor - 1]) >= pair {
        *cursor = list.partition_point(|x| key(x) < pair);
    }
    while *cursor < list.len() && key(&list[*cursor]) < pair {
        *cursor += 1;
    }
    (*cursor < list.len() && key(&list[*cursor]) == pair).then_some(*cursor)
}

/// A row's name across steps: the feature id of the support vertex it acts at (`None` for rows
/// of the whole contact) and its rank among the contact's rows there.
type RowKey = (Option<FeatureId>, usize);

/// What the set keeps of one pair besides its contact.
#[derive(Debug, Clone)]
struct PairState {
    features: FeatureIds,
    /// The bodies' poses the contact is placed for.
    poses: [Pose; 2],
    /// How far the contact was carried since it was computed ([`carry`]).
    drift: Drift,
    /// Blocks of this step's problem.
    blocks: Range<usize>,
    /// What the last solve left, for the next warm start.
    last: Solved,
    /// Still touching as of the current collision pass (its contact kept or recomputed).
    touching: bool,
    /// Kept as it was in the current collision pass, neither body having moved by more than
    /// [`REUSE_TOLERANCE`] since its contact was found.
    still: bool,
    /// The face model's bearing part of the contact, while the contact is unchanged.
    bearing: Option<Bearing>,
    /// How the last step's contact landed the bodies on each other, for this step's bounce
    /// ([`crate::impact`]): [`ContactSet::end_step`] sets it from `landing`.
    landed: Touchdown,
    /// How this step's contact lands them, handed on when the step ends.
    landing: Touchdown,
    /// The energy (J) the landing this step's contact bounces from took, which its bounce
    /// may give back at most ([`crate::bounce_guard`]); 0 when it does not bounce.
    bounce_energy: f64,
}

/// What [`ContactSet::hand_on_impacts`] hands on to a pair's contact ([`crate::impact`]).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct HandedOn {
    /// The speed its landed points bounce at in this step ([`Contact::bounce_speed`]).
    pub bounce_speed: f64,
    /// The energy (J) the landing it bounces from took; 0 when it does not bounce.
    pub bounce_energy: f64,
    /// How it lands the bodies in this step, for the next step's bounce.
    pub landing: Touchdown,
}

/// What the last solve left of a pair, for the next warm start.
#[derive(Debug, Clone, PartialEq)]
enum Solved {
    /// Not solved yet.
    Nothing,
    /// The vertex or patch model's impulses by key: where they are in
    /// [`ContactSet::impulses`] (sorted by key), and the model.
    Rows(ContactModel, Range<usize>),
    /// The face model's block, as the impulse it applied to body A.
    Face(ContactImpulse),
}

impl Solved {
    /// Whether it starts the rows of a pair under `model`.
    fn starts(&self, model: ContactModel) -> bool {
        match self {
            Self::Nothing => false,
            Self::Rows(solved_with, _) => *solved_with == model,
            Self::Face(_) => model == ContactModel::Face,
        }
    }
}

/// One touching pair.
#[derive(Debug, Clone)]
struct Entry {
    contact: Contact,
    state: PairState,
}

/// One pair of the set while its rows are built ([`ContactSet::build_in_runs`]).
pub(crate) struct PairRows<'a> {
    entry: &'a mut Entry,
}

impl PairRows<'_> {
    /// The pair's contact.
    pub(crate) fn contact(&self) -> &Contact {
        &self.entry.contact
    }

    /// How the pair landed in the last step, which its bounce in this step is from
    /// ([`crate::impact`]).
    pub(crate) fn landed(&self) -> Touchdown {
        self.entry.state.landed
    }

    /// The contact and its face-model [`Bearing`] under `settings` (an error for depths that
    /// are not one finite value per support vertex), cut only when the contact (or the slop)
    /// changed since it was last asked for: a resting pair's is cut once.
    pub(crate) fn with_bearing(
        &mut self,
        settings: &ContactSettings,
    ) -> (&Contact, Result<&Bearing, ContactError>) {
        let entry = &mut *self.entry;
        let kept = entry.state.bearing.take().filter(|b| b.is_for(settings));
        let bearing = kept.map_or_else(|| Bearing::of(&entry.contact, settings), Ok);
        let bearing = bearing.map(|bearing| &*entry.state.bearing.insert(bearing));
        (&entry.contact, bearing)
    }
}

/// Every touching pair, in Gauss–Seidel order.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactSet {
    entries: Vec<Entry>,
    /// Each entry's pair `(body A, body B)` with its position in `entries`, sorted by pair;
    /// rebuilt by [`ContactSet::end`].
    held: Vec<(Pair, usize)>,
    /// Whether the current collision pass's broad phase met each entry's pair.
    met: Vec<bool>,
    /// Pairs the broad phase meets that were last found apart along an axis, each with
    /// whether the current pass met it (see [`crate::apart`]); sorted by pair after
    /// [`ContactSet::end`].
    apart: Vec<KeptApart>,
    /// The vertex and patch models' last solve impulses by key, one run per pair (its
    /// [`Solved::Rows`]), written in set order by [`ContactSet::store`]: the warm start and the
    /// store go through memory in sequence, where a vector per pair cost a cache miss each (the
    /// two passes took 0.6 ms of the 1000-cube pile's step).
    impulses: Vec<(RowKey, f64)>,
    /// Scratch: the next store's [`ContactSet::impulses`].
    next_impulses: Vec<(RowKey, f64)>,
    /// Collision settings the contacts were computed with; others invalidate them.
    computed_with: (f64, f64, VertexIds),
    /// How far this pass carries contacts with their bodies ([`carry`]).
    carry: Option<CarryBounds>,
    /// Scratch: row keys of one contact.
    keys: Vec<RowKey>,
    /// Scratch: the entries' sort keys ([`sort_in_place`]).
    sort_keys: Vec<(i64, usize)>,
    /// Scratch: the held pairs in set order, and the counting sort's bucket starts.
    held_scratch: (Vec<(Pair, usize)>, Vec<usize>),
    /// Scratch: the shock-propagation order.
    shock_order: Vec<(usize, Support)>,
    /// Scratch: the first guess for new pairs.
    loads: LoadEstimate,
    /// Whether the guess for this step's warm start was made ahead
    /// ([`ContactSet::estimate_loads_ahead`]): `Some(true)` if it is in `loads`, `Some(false)`
    /// if no pair needed it, `None` if it is left to the warm start.
    loads_ahead: Option<bool>,
    /// Scratch: a new pair's guess shared over its support's vertices ([`shares_towards`]).
    shares: Vec<f64>,
}

impl ContactSet {
    /// Starts a collision pass with the given contact margin, feature angle and naming of
    /// support vertices: contacts computed with others are dropped (a model that keys its rows
    /// by vertex then finds every contact named), and every pair is marked unmet.
    pub(crate) fn begin(
        &mut self,
        margin: f64,
        feature_angle: f64,
        ids: VertexIds,
        carry: Option<CarryBounds>,
    ) {
        self.carry = carry;
        if self.computed_with != (margin, feature_angle, ids) {
            self.entries.clear();
            self.held.clear();
            self.apart.clear();
            self.impulses.clear();
            self.computed_with = (margin, feature_angle, ids);
        }
        self.met.clear();
        self.met.resize(self.entries.len(), false);
        self.loads_ahead = None;
    }

    /// Brings the pairs the set holds up to date, and runs `broad_phase`, which meets the pairs
    /// now overlapping through its [`Meeting`]. A pair keeps its contact if neither body moved
    /// by more than [`REUSE_TOLERANCE`] since it was computed (`placements` says where each
    /// body is), so a resting stack's pairs are computed once; a pair whose bodies barely slid
    /// or turned against each other keeps it carried with them, within the bounds given to
    /// [`ContactSet::begin`] ([`carry`]); the others
    /// are recomputed in place by `compute` (from a per-thread `scratch`, and given what the old
    /// contact leaves the new one: [`Recycled`]), and a pair it returns
    /// `None` for (no longer touching) is dropped by [`ContactSet::end`], as is a pair the broad
    /// phase did not meet.
    ///
    /// With `on_every_core`, the pool's helpers recompute the pairs while this thread runs the
    /// broad phase, then this thread joins them: the broad phase's time is hidden, and the
    /// helpers wake while it runs instead of at the start of the loop. That recomputes the moved
    /// pairs the broad phase then drops too, which changes nothing but the time. Each contact is
    /// a pure function of its two bodies, so the result does not depend on the number of
    /// threads, and the old contact's memory is freed by the thread that replaces it. Returns
    /// how many contacts were recomputed.
    pub(crate) fn refresh<S>(
        &mut self,
        on_every_core: bool,
        placements: &[Placement],
        scratch: fn() -> S,
        compute: impl Fn(&mut S, (usize, usize), Recycled) -> Option<Computed> + Sync,
        broad_phase: impl FnOnce(&mut Meeting<'_>),
    ) -> usize {
        let still = |was: &Pose, now: Placement| {
            (now.pose.0 - was.0).norm() <= REUSE_TOLERANCE
                && turned_within(&now.pose.1, &was.1, now.size.max(1.0), REUSE_TOLERANCE)
        };
        // Whether the entry's contact was recomputed.
        let update = |scratch: &mut S, entry: &mut Entry| -> bool {
            let pair = (entry.contact.body_a.0, entry.contact.body_b.0);
            let [was_a, was_b] = &entry.state.poses;
            let (now_a, now_b) = (placements[pair.0], placements[pair.1]);
            entry.state.still = still(was_a, now_a) && still(was_b, now_b);
            if entry.state.still {
                entry.state.touching = true;
                return false;
            }
            let now = [now_a.pose, now_b.pose];
            // A ball's or a cylinder's contact at a point or along its side runs over its
            // surface as it rolls, staying under its centre: carried with either body, its
            // point lagged and its normal tilted with the turn, and a ball or a cylinder
            // of radius 0.2 m rolling on a floor at 5 mm/s sped up to 2.1 cm/s (a turn of 0.1° a
            // step, past which the contact is not carried), so a heap of balls never settled.
            let rolls = (now_a.round || now_b.round)
                && entry.contact.support.kind() != PolygonKind::Polygon;
            if let Some(bounds) = &self.carry
                && !rolls
                && carry(
                    &mut entry.contact,
                    &mut entry.state.drift,
                    &entry.state.poses,
                    &now,
                    bounds,
                )
            {
                entry.state.poses = now;
                entry.state.touching = true;
                entry.state.bearing = None;
                return false;
            }
            // A pair no longer touching is left without depths until `end` drops it.
            let recycled = Recycled {
                depths: std::mem::take(&mut entry.contact.depths),
                normal: Some(entry.contact.frame.normal),
                keep_normal: entry.state.landed.speed > 0.0,
            };
            entry.state.bearing = None;
            entry.state.touching = match compute(scratch, pair, recycled) {
                Some((contact, features, poses)) => {
                    entry.contact = contact;
                    entry.state.features = features;
                    entry.state.poses = poses;
                    entry.state.drift = Drift::default();
                    true
                }
                None => false,
            };
            true
        };
        let mut meeting = Meeting {
            held: &self.held,
            met: &mut self.met,
            apart: &mut self.apart,
            placements,
            margin: self.computed_with.0,
            cursors: (0, 0),
        };
        if on_every_core {
            let ((), recomputed) =
                parallel::for_each_beside(&mut self.entries, scratch, update, || {
                    broad_phase(&mut meeting)
                });
            recomputed
        } else {
            broad_phase(&mut meeting);
            let mut scratch = scratch();
            let mut recomputed = 0;
            for (entry, &met) in self.entries.iter_mut().zip(&self.met) {
                if met && update(&mut scratch, entry) {
                    recomputed += 1;
                }
            }
            recomputed
        }
    }

    /// The contact at `index`, for a test to alter.
    #[cfg(test)]
    pub(crate) fn contact_mut(&mut self, index: usize) -> &mut Contact {
        &mut self.entries[index].contact
    }

    /// Adds a pair the set did not hold, with its contact computed at `poses` and a feature id
    /// per support vertex.
    pub(crate) fn insert(&mut self, (contact, features, poses): Computed) {
        self.entries.push(Entry {
            contact,
            state: PairState {
                features,
                poses,
                drift: Drift::default(),
                blocks: 0..0,
                last: Solved::Nothing,
                touching: true,
                still: false,
                bearing: None,
                landed: Touchdown::default(),
                landing: Touchdown::default(),
                bounce_energy: 0.0,
            },
        });
        self.met.push(true);
    }

    /// Hands each pair's landing on ([`crate::impact`]): `hand_on`, given the pair's contact,
    /// how the last step's contact landed it and whether the pair was kept still in this pass,
    /// returns the contact's bounce speed and how it lands the pair, handed on to the next step by
    /// [`ContactSet::end_step`]. A kept bearing part made with another bounce speed is dropped.
    /// Another collision pass before the step ends (`World::prepare_step`, then the step)
    /// hands on the same landing again. With `on_every_core`, the pairs are shared with the
    /// pool's helpers (each pair's is a function of its own contact and state).
    pub(crate) fn hand_on_impacts(
        &mut self,
        on_every_core: bool,
        hand_on: impl Fn(&Contact, Touchdown, bool) -> HandedOn + Sync,
    ) {
        let hand = |(): &mut (), Entry { contact, state }: &mut Entry| {
            let handed = hand_on(contact, state.landed, state.still);
            if contact.bounce_speed != handed.bounce_speed {
                contact.bounce_speed = handed.bounce_speed;
                state.bearing = None;
            }
            state.bounce_energy = handed.bounce_energy;
            state.landing = handed.landing;
        };
        if on_every_core {
            parallel::for_each(&mut self.entries, || (), hand);
        } else {
            (self.entries.iter_mut()).for_each(|entry| hand(&mut (), entry));
        }
    }

    /// The pairs that bounce in this step, each with the energy (J) its landing took
    /// ([`HandedOn::bounce_energy`]).
    pub(crate) fn bounces(&self) -> impl Iterator<Item = (&Contact, f64)> {
        (self.entries.iter())
            .filter(|e| e.contact.bounce_speed > 0.0)
            .map(|e| (&e.contact, e.state.bounce_energy))
    }

    /// Ends a step: each pair's landing in it is handed on to the next
    /// ([`ContactSet::hand_on_impacts`]).
    pub(crate) fn end_step(&mut self) {
        for Entry { state, .. } in &mut self.entries {
            state.landed = state.landing;
        }
    }

    /// Keeps pair `pair`, met by the broad phase and found apart, to be skipped while it stays
    /// so (see [`Meeting::meet`]).
    pub(crate) fn keep_apart(&mut self, pair: Pair, apart: Apart) {
        self.apart.push((pair, apart, true));
    }

    /// How many pairs the set keeps apart.
    #[cfg(test)]
    pub(crate) fn kept_apart(&self) -> usize {
        self.apart.len()
    }

    /// Ends a collision pass: drops the pairs the broad phase did not meet or that no longer
    /// touch, and orders the rest from the highest contact to the lowest along `gravity`; drops
    /// the pairs kept apart that it did not meet or that were found touching. With `beside`,
    /// a helper of the pool does the pairs kept apart meanwhile (a fifth of the settling
    /// 1000-cube pile's 0.26–0.29 ms here).
    pub(crate) fn end(&mut self, gravity: &Vector3<f64>, beside: bool) {
        let Self {
            entries,
            held,
            met,
            apart,
            sort_keys,
            held_scratch,
            ..
        } = self;
        let mut order_entries = || {
            // The held list stays right while the set keeps the same pairs in the same order,
            // as a resting pile does: no pair inserted since it was built, none dropped, none
            // moved.
            let inserted = entries.len() != held.len();
            let mut met = met.iter();
            entries.retain(|e| met.next().is_some_and(|&met| met) && e.state.touching);
            let dropped = entries.len() != held.len();
            let moved = sort_in_place(entries, sort_keys, |e| {
                total_order(e.contact.frame.origin.coords.dot(gravity))
            });
            if inserted || dropped || moved {
                sort_held(entries, held_scratch, held);
            }
        };
        let mut keep_apart = || {
            // A pair found apart again after its bound ran out was not met under its old gap,
            // so no pair is kept twice.
            apart.retain_mut(|(_, _, met)| std::mem::take(met));
            // The pairs kept before and those added in this pass are two runs in pair order:
            // the stable sort finds and merges them in one pass (the unstable one sorted them
            // anew, moving records of a hundred bytes, 0.1 ms of the 1000-cube pile's step).
            apart.sort_by_key(|&(pair, _, _)| pair);
        };
        if beside {
            parallel::join_beside(order_entries, keep_apart);
        } else {
            order_entries();
            keep_apart();
        }
    }

    /// Forgets body `index` as [`World::remove_body`](crate::World::remove_body) removes it:
    /// drops its pairs and renumbers the bodies after it, in the pairs' contacts and keys.
    pub(crate) fn remove_body(&mut self, index: usize) {
        self.apart.clear();
        self.entries
            .retain(|e| e.contact.body_a.0 != index && e.contact.body_b.0 != index);
        let renumber = |body: &mut tatami_lcp::BodyId| {
            if body.0 > index {
                body.0 -= 1;
            }
        };
        for e in &mut self.entries {
            renumber(&mut e.contact.body_a);
            renumber(&mut e.contact.body_b);
            e.state.bearing = None;
        }
        sort_held(&self.entries, &mut self.held_scratch, &mut self.held);
    }

    /// The contacts, in Gauss–Seidel order.
    pub(crate) fn contacts(&self) -> impl ExactSizeIterator<Item = &Contact> + Clone {
        self.entries.iter().map(|e| &e.contact)
    }

    /// The contact at `index` of the set's order and its blocks in this step's problem.
    pub(crate) fn get(&self, index: usize) -> Option<(&Contact, Range<usize>)> {
        self.entries
            .get(index)
            .map(|e| (&e.contact, e.state.blocks.clone()))
    }

    /// Hands every pair to `front` or `back` with its index, in runs of `run` pairs, the `k`th
    /// run with `pieces[k]` (there must be a piece per run): the calling thread's `front` takes
    /// runs from the first on, in order, and, when `on_every_core`, the pool's helpers' `back`
    /// from the last ([`parallel::from_both_ends`]) until they meet. Returns how many runs the
    /// front took. A run's pairs are handed in order, whichever side takes it.
    pub(crate) fn build_in_runs<P: Send>(
        &mut self,
        pieces: &mut [P],
        run: usize,
        on_every_core: bool,
        mut front: impl FnMut(&mut P, usize, PairRows<'_>),
        back: impl Fn(&mut P, usize, PairRows<'_>) + Sync,
    ) -> usize {
        let run = run.max(1);
        assert!(
            pieces.len() >= self.entries.len().div_ceil(run),
            "a piece per run"
        );
        let mut runs: Vec<(usize, &mut [Entry], &mut P)> = (self.entries.chunks_mut(run))
            .zip(pieces)
            .enumerate()
            .map(|(k, (entries, piece))| (k * run, entries, piece))
            .collect();
        let mut front = |(first, entries, piece): &mut (usize, &mut [Entry], &mut P)| {
            for (k, entry) in entries.iter_mut().enumerate() {
                front(piece, *first + k, PairRows { entry });
            }
        };
        if on_every_core {
            let back = |(first, entries, piece): &mut (usize, &mut [Entry], &mut P)| {
                for (k, entry) in entries.iter_mut().enumerate() {
                    back(piece, *first + k, PairRows { entry });
                }
            };
            parallel::from_both_ends(&mut runs, front, back)
        } else {
            runs.iter_mut().for_each(&mut front);
            runs.len()
        }
    }

    /// Records that the contact at `index` took `blocks` of this step's problem.
    pub(crate) fn set_blocks(&mut self, index: usize, blocks: Range<usize>) {
        self.entries[index].state.blocks = blocks;
    }

    /// How many blocks the last rows stage built: the set's pairs hold their blocks in set
    /// order, so the last pair's end where they all do (until the pass after it adds pairs).
    pub(crate) fn blocks_built(&self) -> usize {
        self.entries
            .last()
            .map_or(0, |entry| entry.state.blocks.end)
    }

    /// The contact owning block `block` of this step's problem.
    pub(crate) fn contact_of_block(&self, block: usize) -> Option<&Contact> {
        self.entries
            .iter()
            .find(|e| e.state.blocks.contains(&block))
            .map(|e| &e.contact)
    }

    /// Starts every row of `problem` from the last solve under `model`: a face-model block from
    /// the impulse the pair's blocks applied to body A ([`ContactImpulse::write_face_rows`]),
    /// other rows from the impulse their key had (rows whose key is new keep zero). A pair with
    /// nothing stored under `model` (new, or last solved under another model) starts instead
    /// with the weight it carries at rest under `weight_per_mass` (gravity × dt) — see
    /// [`crate::load_estimate`]: a face-model block whose upper body rests on it alone with that
    /// weight where it acts (its tilt rows with the torque that puts the centre of pressure
    /// there), a vertex or patch model's normal rows with shares whose resultant acts there
    /// ([`shares_towards`]), any other evenly spread over its normal rows. Landing blocks start
    /// from zero ([`Entry::started_blocks`]).
    pub(crate) fn warm_start(
        &mut self,
        model: ContactModel,
        problem: &mut Problem<ContactProjection>,
        weight_per_mass: &Vector3<f64>,
    ) {
        // The estimate goes down every contact: only made when a pair needs it.
        let unstarted = |e: &Entry| !e.state.blocks.is_empty() && !e.state.last.starts(model);
        let estimate = match self.loads_ahead.take() {
            Some(true) => self.loads.last(),
            Some(false) => &[],
            None if self.entries.iter().any(unstarted) => self.loads.estimate(
                self.entries.iter().map(|e| &e.contact),
                &problem.bodies,
                weight_per_mass,
            ),
            None => &[],
        };
        for (index, entry) in self.entries.iter().enumerate() {
            if entry.state.blocks.is_empty() {
                continue;
            }
            let started = entry.started_blocks(model);
            let rows = rows_of(problem, &started);
            let stored = match (&entry.state.last, model) {
                (Solved::Face(impulse), ContactModel::Face) => {
                    impulse.write_face_rows(&mut problem.rows[rows], &entry.contact.centre_a);
                    continue;
                }
                (Solved::Rows(solved_with, stored), _) if *solved_with == model => {
                    &self.impulses[stored.clone()]
                }
                _ => {
                    let load = estimate[index];
                    match (model, load.at) {
                        // One face block: the guess with its torque about where it acts.
                        (ContactModel::Face, Some(at)) if started.len() == 1 => {
                            let linear = entry.contact.frame.normal * load.normal;
                            let centre_a = entry.contact.centre_a;
                            let impulse = ContactImpulse {
                                linear,
                                angular: (at - centre_a).cross(&linear),
                                centre_a,
                            };
                            impulse.write_face_rows(&mut problem.rows[rows], &centre_a);
                        }
                        (_, at) => {
                            let vertices = entry.contact.support.vertices();
                            let shares = &mut self.shares;
                            shares.clear();
                            shares.resize(vertices.len(), 1.0 / vertices.len() as f64);
                            if let Some(at) = at {
                                shares_towards(
                                    vertices,
                                    &entry.contact.frame.to_plane(&at),
                                    shares,
                                );
                            }
                            spread_over_normal_rows(problem, &started, load.normal, shares);
                        }
                    }
                    continue;
                }
            };
            row_keys(model, &entry.state.features, rows.len(), &mut self.keys);
            for (index, (row, key)) in problem.rows[rows].iter_mut().zip(&self.keys).enumerate() {
                // Where the rows are as they were, a row's key is at its own index: one
                // comparison instead of a search (the keys are unique).
                let found = match stored.get(index) {
                    Some((k, _)) if k == key => Some(index),
                    _ => stored.binary_search_by(|(k, _)| k.cmp(key)).ok(),
                };
                if let Some(k) = found {
                    row.impulse = stored[k].1;
                }
            }
        }
    }

    /// Makes the guess [`ContactSet::warm_start`] starts pairs with nothing stored under `model`
    /// from, for this step, if some pair has nothing: against `bodies` (their masses) and
    /// `weight_per_mass`, as the warm start would (the guess reads no velocity). The rows
    /// stage makes it on a helper while it copies the helpers' rows in; the next collision
    /// pass ([`ContactSet::begin`]) forgets it.
    pub(crate) fn estimate_loads_ahead(
        &mut self,
        model: ContactModel,
        bodies: &[SolverBody],
        weight_per_mass: &Vector3<f64>,
    ) {
        let needed = self.entries.iter().any(|e| !e.state.last.starts(model));
        if needed {
            let contacts = self.entries.iter().map(|e| &e.contact);
            self.loads.estimate(contacts, bodies, weight_per_mass);
        }
        self.loads_ahead = Some(needed);
    }

    /// Keeps what `problem`'s solve (under `model`) left of every pair for the next warm start:
    /// under the face model the impulse all the pair's blocks applied to body A (its own and
    /// its landing blocks': where a landing block pivoted a tipping body, the next step's block
    /// starts with that load at that edge, instead of rebuilding it from zero; a 1000-cube
    /// pile settled to fewer deep contacts with it), other rows' impulses by key (but for the
    /// landing blocks', which start from zero).
    pub(crate) fn store(&mut self, model: ContactModel, problem: &Problem<ContactProjection>) {
        let next = &mut self.next_impulses;
        next.clear();
        for entry in &mut self.entries {
            let started = entry.started_blocks(model);
            let state = &mut entry.state;
            let rows = rows_of(problem, &state.blocks);
            state.last = match (&state.last, model) {
                // A pair without rows this step (its bodies asleep) keeps what it had.
                (Solved::Rows(solved_with, stored), _) if rows.is_empty() => {
                    let start = next.len();
                    next.extend_from_slice(&self.impulses[stored.clone()]);
                    Solved::Rows(*solved_with, start..next.len())
                }
                (last, _) if rows.is_empty() => last.clone(),
                // The pair's own blocks: a grip's friction ([`tatami_contact::grip`]) is found
                // afresh each step with the press that bounds it, not carried into the face.
                (_, ContactModel::Face) => Solved::Face(ContactImpulse::of_rows(
                    &problem.rows[rows_of(problem, &without_grip(problem, &state.blocks))],
                    entry.contact.centre_a,
                )),
                (_, ContactModel::Vertex | ContactModel::Patch) => {
                    let rows = rows_of(problem, &started);
                    let start = next.len();
                    row_keys(model, &state.features, rows.len(), &mut self.keys);
                    next.extend(
                        self.keys
                            .iter()
                            .zip(&problem.rows[rows])
                            .map(|(key, row)| (*key, row.impulse)),
                    );
                    next[start..].sort_by_key(|(key, _)| *key);
                    Solved::Rows(model, start..next.len())
                }
            };
        }
        std::mem::swap(&mut self.impulses, &mut self.next_impulses);
    }

    /// The blocks from the lowest contact to the highest, each with its support for
    /// [`tatami_lcp::pgs::shock_propagation`] ([`shock_support`]; `bodies` give the masses).
    pub(crate) fn shock_order(
        &mut self,
        gravity: &Vector3<f64>,
        bodies: &[SolverBody],
    ) -> &[(usize, Support)] {
        self.shock_order.clear();
        for entry in self.entries.iter().rev() {
            let support = shock_support(&entry.contact, gravity, bodies);
            self.shock_order
                .extend(entry.state.blocks.clone().map(|block| (block, support)));
        }
        &self.shock_order
    }
}

/// The body the shock pass holds still at `contact`: the one lower along `gravity`
/// ([`support_of`]), but at a side contact (its normal more than 60° off `gravity`), which
/// carries no weight, the heavier when it is at least [`SIDE_CONTACT_MASS_RATIO`] times the
/// other's mass (or fixed, or kinematic). Held still there, a light body took the impulse
/// that stopped a heavy one it met side on, and the next step started from it: a 200 kg slab
/// pushed at 5 m/s into a row of 1 cm cubes threw them at 4 km/s.
fn shock_support(contact: &Contact, gravity: &Vector3<f64>, bodies: &[SolverBody]) -> Support {
    let side = contact.frame.normal.dot(gravity).abs() < SIDE_CONTACT_COS * gravity.norm();
    match heavier(contact, bodies, SIDE_CONTACT_MASS_RATIO) {
        Some(heavier) if side => heavier,
        _ => support_of(contact, gravity),
    }
}

/// The body of `contact` (masses from `bodies`) at least `ratio` (> 1) times heavier than the
/// other, a fixed or kinematic one (no inverse mass) being heavier than any free one; `None`
/// when neither is.
pub(crate) fn heavier(contact: &Contact, bodies: &[SolverBody], ratio: f64) -> Option<Support> {
    let [a, b] = [contact.body_a, contact.body_b].map(|id| bodies[id.0].inv_mass);
    if b > a && b >= ratio * a {
        Some(Support::A)
    } else if a > b && a >= ratio * b {
        Some(Support::B)
    } else {
        None
    }
}

/// A contact whose normal makes less than this cosine with gravity (more than 60° off it) is
/// a side contact for [`shock_support`].
const SIDE_CONTACT_COS: f64 = 0.5;

/// How many times heavier one body of a side contact must be to be held still by the shock
/// pass ([`shock_support`]). At every mass ratio, bodies of 3–10 mm in a bin (ratios up to
/// about 40) jostled for 10 s where they had settled by 4 s; from ten, by 6 s.
const SIDE_CONTACT_MASS_RATIO: f64 = 100.0;

/// The body of `contact` that is lower along `gravity` (by centre of mass): the one carrying the
/// other.
pub(crate) fn support_of(contact: &Contact, gravity: &Vector3<f64>) -> Support {
    let height = |c: &Point3<f64>| -c.coords.dot(gravity);
    if height(&contact.centre_a) <= height(&contact.centre_b) {
        Support::A
    } else {
        Support::B
    }
}

impl Entry {
    /// The pair's blocks under `model` that its warm start starts: the face and patch models'
    /// own block, the first (the face model's with everything the pair applied), the vertex
    /// model's block of each support vertex. The landing blocks after them start from zero:
    /// they catch a landing, a step's event.
    fn started_blocks(&self, model: ContactModel) -> Range<usize> {
        let own = match model {
            ContactModel::Face | ContactModel::Patch => 1,
            ContactModel::Vertex => self.contact.support.vertices().len(),
        };
        let blocks = &self.state.blocks;
        blocks.start..blocks.end.min(blocks.start + own)
    }
}

/// Spreads the normal impulse `load` over the normal rows of `blocks` (each block's
/// [`leading_normal_rows`](Projection::leading_normal_rows)): by `shares` when there is one
/// normal row per share, in the support's vertex order (the vertex model's blocks, the patch
/// model's rows), otherwise evenly.
fn spread_over_normal_rows(
    problem: &mut Problem<ContactProjection>,
    blocks: &Range<usize>,
    load: f64,
    shares: &[f64],
) {
    let blocks = &problem.blocks[blocks.clone()];
    let normals: usize = blocks
        .iter()
        .map(|b| b.projection.leading_normal_rows())
        .sum();
    if normals == 0 {
        return;
    }
    let by_shares = normals == shares.len();
    let rows = blocks.iter().flat_map(|b| {
        let first = b.rows.start;
        first..first + b.projection.leading_normal_rows()
    });
    for (k, row) in rows.enumerate() {
        problem.rows[row].impulse = if by_shares {
            load * shares[k]
        } else {
            load / normals as f64
        };
    }
}

/// Moves the even `shares` of a load over a support's `vertices` (plane coordinates) so that
/// their resultant acts at `at`: the least change in the least-squares sense (`δᵢ = uᵢ · λ`,
/// `uᵢ` a vertex from the vertices' mean, `(Σ uᵢ uᵢᵀ) λ = at − mean`; along its line for a
/// segment). A vertex whose share would go negative is dropped, and the rest start over
/// evenly: on a rectangle the first pass is exact up to the edges, and a point near a corner
/// ends in the triangle of the three vertices round it. A point outside ends on the nearest
/// vertices' side, the shares non-negative and summing to 1 whatever happens.
fn shares_towards(vertices: &[Point2<f64>], at: &Point2<f64>, shares: &mut [f64]) {
    // At most one pass per vertex dropped.
    for _ in 0..vertices.len() {
        let active = || {
            vertices
                .iter()
                .zip(shares.iter())
                .filter(|(_, w)| **w > 0.0)
        };
        let n = active().count() as f64;
        let mean = active().fold(Vector2::zeros(), |m, (v, _)| m + v.coords) / n;
        let spread = active().fold(Matrix2::zeros(), |s, (v, _)| {
            let u = v.coords - mean;
            s + u * u.transpose()
        });
        let offset = at.coords - mean;
        let trace = spread.trace();
        let ends = (active().next(), active().next_back());
        let lambda = match ends {
            _ if trace <= 0.0 => Vector2::zeros(), // one point: all of it there
            _ if spread.determinant() > 1e-12 * trace * trace => spread
                .try_inverse()
                .map_or(Vector2::zeros(), |inverse| inverse * offset),
            // A segment: along its line only.
            (Some((first, _)), Some((last, _))) => {
                let line = (last - first).normalize();
                line * (line.dot(&offset) / trace)
            }
            _ => Vector2::zeros(),
        };
        let mut dropped = false;
        for (share, v) in shares.iter_mut().zip(vertices) {
            if *share > 0.0 {
                *share = 1.0 / n + (v.coords - mean).dot(&lambda);
                if *share <= 0.0 {
                    *share = 0.0;
                    dropped = true;
                }
            }
        }
        if !dropped {
            return;
        }
        // Start the survivors over evenly (they keep a positive mark).
        let left = shares.iter().filter(|w| **w > 0.0).count();
        if left == 0 {
            shares.fill(1.0 / vertices.len() as f64);
            return;
        }
        for share in shares.iter_mut().filter(|w| **w > 0.0) {
            *share = 1.0 / left as f64;
        }
    }
}

/// Rebuilds `held`, the sorted list of held pairs, from `entries`, with `scratch`: the pairs in
/// set order, and the counting sort's bucket starts.
fn sort_held(
    entries: &[Entry],
    (in_set_order, firsts): &mut (Vec<(Pair, usize)>, Vec<usize>),
    held: &mut Vec<(Pair, usize)>,
) {
    in_set_order.clear();
    in_set_order.extend(
        (entries.iter().enumerate()).map(|(k, e)| ((e.contact.body_a.0, e.contact.body_b.0), k)),
    );
    let bodies = in_set_order.iter().map(|((a, b), _)| a.max(b) + 1).max();
    order_by_pair(
        in_set_order,
        |&(pair, _)| pair,
        firsts,
        bodies.unwrap_or(0),
        held,
    );
}

/// Sorts `items` by `key`, ties in their order (as a stable sort would), with `keys` as
/// scratch. The keys and positions are sorted, then each item is swapped into place once, and
/// an item already in place is not moved: an entry is about a kilobyte, sorting the entries
/// themselves moved each about log n times (1.7% of the 1000-cube pile's step in memmove alone),
/// and the standard `sort_by_cached_key`, which this follows, also swaps each item in place
/// with itself, three copies of it (0.1 ms of the pile's step, whose order changes little).
/// Returns whether any item moved.
fn sort_in_place<T>(
    items: &mut [T],
    keys: &mut Vec<(i64, usize)>,
    key: impl Fn(&T) -> i64,
) -> bool {
    keys.clear();
    keys.extend(items.iter().enumerate().map(|(i, item)| (key(item), i)));
    // Distinct keys, nearly in order from last step: a settling pile's pairs each a few
    // places off as their heights change.
    sort_nearly_in_order_by(keys, Ord::cmp);
    let mut moved = false;
    for i in 0..items.len() {
        // The item for place `i` was at `keys[i].1`, unless an earlier swap moved it on: follow
        // where each earlier place sent its item.
        let mut from = keys[i].1;
        while from < i {
            from = keys[from].1;
        }
        keys[i].1 = from;
        if from != i {
            items.swap(i, from);
            moved = true;
        }
    }
    moved
}

/// Whether turning from `was` to `now` moves a point `length` from the centre by no more than
/// `tolerance` along its arc: `now.angle_to(was) · length ≤ tolerance`, the same answer. The
/// angle `θ` lies between `2 sin(θ/2)` and `π sin(θ/2)`, where `sin(θ/2)` is the length of the
/// turn's quaternion's vector part, so the arc tangent of the angle is taken only when those
/// bounds fall on either side of the tolerance (two for each pair of a resting pile of 1000
/// bodies a step, 4% of its collision's instructions, before). A factor of `1 ± 1e-9` on each
/// bound leaves a million times their rounding.
fn turned_within(
    now: &UnitQuaternion<f64>,
    was: &UnitQuaternion<f64>,
    length: f64,
    tolerance: f64,
) -> bool {
    let turn = now.rotation_to(was);
    let half_sine = turn.imag().norm() * length;
    if 2.0 * half_sine * (1.0 - 1e-9) > tolerance {
        return false;
    }
    if std::f64::consts::PI * half_sine * (1.0 + 1e-9) < tolerance {
        return true;
    }
    turn.angle() * length <= tolerance
}

/// An integer that orders as [`f64::total_cmp`] orders `x` (the same bit trick), so floats can
/// be sort keys.
fn total_order(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ ((((bits >> 63) as u64) >> 1) as i64)
}

/// The rows of `problem` that `blocks` span.
pub(crate) fn rows_of<P>(problem: &Problem<P>, blocks: &Range<usize>) -> Range<usize> {
    if blocks.is_empty() {
        return 0..0;
    }
    let first = &problem.blocks[blocks.start];
    let last = &problem.blocks[blocks.end - 1];
    first.rows.start..last.rows.end
}

/// `blocks` less the grip that may end them ([`tatami_contact::grip::build`]).
fn without_grip(problem: &Problem<ContactProjection>, blocks: &Range<usize>) -> Range<usize> {
    let gripped = blocks
        .clone()
        .last()
        .is_some_and(|last| matches!(problem.blocks[last].projection, ContactProjection::Grip(_)));
    blocks.start..blocks.end - usize::from(gripped)
}

/// The keys of a contact's `rows` rows under `model`, for support vertices with `features`.
fn row_keys(model: ContactModel, features: &[FeatureId], rows: usize, out: &mut Vec<RowKey>) {
    out.clear();
    for row in 0..rows {
        let feature = model
            .row_vertex(features.len(), row)
            .and_then(|v| features.get(v).copied());
        let rank = out.iter().filter(|(f, _)| *f == feature).count();
        out.push((feature, rank));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pair is found, or not, as a linear search says: asked in increasing order (the
    /// broad phase's, one walk) and in a shuffled order (a search from the start when a pair
    /// comes before the cursor).
    #[test]
    fn find_looks_pairs_up_in_any_order() {
        let list: Vec<(Pair, usize)> = (0..40)
            .flat_map(|a| {
                (a + 1..40)
                    .filter(move |b| (a * 7 + b * 3) % 5 == 0)
                    .map(move |b| (a, b))
            })
            .enumerate()
            .map(|(k, pair): (usize, Pair)| (pair, k))
            .collect();
        let mut asked: Vec<Pair> = (0..40)
            .flat_map(|a| (a + 1..40).map(move |b| (a, b)))
            .collect();
        let mut random = crate::dropped::Random::new(3);
        for shuffled in [false, true] {
            if shuffled {
                for k in (1..asked.len()).rev() {
                    asked.swap(k, random.between(0.0, k as f64 + 1.0) as usize % (k + 1));
                }
            }
            let mut cursor = 0;
            for &pair in &asked {
                let expected = list.iter().position(|&(p, _)| p == pair);
                assert_eq!(
                    find(&list, |h| h.0, &mut cursor, pair),
                    expected,
                    "{pair:?}"
                );
            }
        }
    }

    /// The guess for new pairs made ahead ([`ContactSet::estimate_loads_ahead`], on a helper
    /// while the rows stage copies the helpers' rows in) starts every row as the warm start's
    /// own guess does, to the bit, under each model: a leaning stack of three cubes of 1, 3 and
    /// 0.5 kg, its pairs all new. A guess made ahead for other masses is forgotten by the
    /// next collision pass, never read by a later warm start.
    #[test]
    fn a_guess_made_ahead_starts_the_rows_as_the_warm_starts_own() {
        use crate::{BodyDesc, Shape, World, WorldSettings};
        let cube = |x: f64, z: f64, mass: f64| {
            BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                .mass(mass)
                .position([x, 0.0, z])
        };
        let dt = 1.0 / 60.0;
        for model in ContactModel::ALL {
            let mut world = World::builder()
                .settings(WorldSettings {
                    model,
                    ..WorldSettings::default()
                })
                .body(BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).position([0.0, 0.0, -1.0]))
                .body(cube(0.0, 0.5, 1.0))
                .body(cube(0.1, 1.5, 3.0))
                .body(cube(0.2, 2.5, 0.5))
                .build()
                .expect("a valid scene");
            world.prepare_step(dt).expect("collision and rows");
            let weight = world.gravity() * dt;
            let (set, problem) = (&world.contact_set, &world.problem);
            assert_eq!(set.entries.len(), 3, "{model:?}: three new pairs");
            let started = |ahead: Option<&[SolverBody]>, begin: bool| -> Vec<u64> {
                let (mut set, mut problem) = (set.clone(), problem.clone());
                if let Some(bodies) = ahead {
                    set.estimate_loads_ahead(model, bodies, &weight);
                }
                if begin {
                    let (margin, angle, ids) = set.computed_with;
                    set.begin(margin, angle, ids, set.carry);
                }
                set.warm_start(model, &mut problem, &weight);
                problem.rows.iter().map(|r| r.impulse.to_bits()).collect()
            };
            let own = started(None, false);
            assert!(
                own.iter().any(|&bits| f64::from_bits(bits) > 0.1),
                "{model:?}: the stack's weight guessed"
            );
            assert_eq!(started(Some(&problem.bodies), false), own, "{model:?}");
            // Made ahead for bodies three times as heavy, then a collision pass.
            let heavier: Vec<SolverBody> = (problem.bodies.iter())
                .map(|b| SolverBody {
                    inv_mass: b.inv_mass / 3.0,
                    ..*b
                })
                .collect();
            assert_ne!(
                started(Some(&heavier), false),
                own,
                "{model:?}: the guess is read"
            );
            assert_eq!(
                started(Some(&heavier), true),
                own,
                "{model:?}: and forgotten"
            );
        }
    }

    /// A pair asleep gets no rows, and every store keeps what it stored before it fell asleep,
    /// for the warm start of the step it wakes in; the pairs awake are stored anew.
    #[test]
    fn a_sleeping_pair_keeps_its_impulses_through_every_store() {
        use crate::{BodyDesc, Shape, Sleeping, World, WorldSettings};
        let cube = |x: f64, z: f64| {
            BodyDesc::dynamic(Shape::cuboid([1.0; 3]))
                .mass(1.0)
                .position([x, 0.0, z])
        };
        let mut world = World::builder()
            .settings(WorldSettings {
                sleeping: Sleeping::on(),
                ..WorldSettings::default()
            })
            .body(BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).position([0.0, 0.0, -1.0]))
            .body(cube(0.0, 0.5))
            .body(cube(0.0, 1.5))
            // Far off, dropped later: awake while the stack sleeps.
            .body(cube(10.0, 8.0))
            .build()
            .expect("a valid scene");
        let dt = 1.0 / 60.0;
        // Each pair with what its last solve left (the face model's impulse on A).
        let stored = |world: &World| -> Vec<(Pair, Solved)> {
            let set = &world.contact_set;
            set.entries
                .iter()
                .map(|e| {
                    (
                        (e.contact.body_a.0, e.contact.body_b.0),
                        e.state.last.clone(),
                    )
                })
                .collect()
        };
        while !world.bodies()[1].is_asleep() {
            world.step(dt).expect("a step");
            assert!(world.time() < 3.0, "the stack sleeps within 3 s");
        }
        let asleep = stored(&world);
        assert_eq!(asleep.len(), 2, "floor–bottom and bottom–top");
        assert!(asleep.iter().all(|(_, last)| match last {
            // Each carries weight (A is the lower body or the upper one).
            Solved::Face(impulse) => impulse.linear.z.abs() > 0.0,
            _ => false,
        }));
        // 1.5 s on: the far cube lands (dropped 7.5 m, 1.24 s) while the stack sleeps on.
        for _ in 0..90 {
            world.step(dt).expect("a step");
            assert!(world.bodies()[1].is_asleep(), "still asleep");
            let now = stored(&world);
            for (pair, last) in &asleep {
                let kept = now.iter().find(|(p, _)| p == pair).map(|(_, l)| l);
                assert_eq!(kept, Some(last), "pair {pair:?} at {:.2} s", world.time());
            }
        }
        // The falling cube lands meanwhile: its pair is stored while the stack's are kept.
        assert_eq!(stored(&world).len(), 3);
    }

    /// Support vertices are named only under a model that keys its rows by them: a cube
    /// resting on a box under the face model has no names; switched to the vertex model, its
    /// contact is found again with a name for each of its four corners, and the vertex model's
    /// rows then start from the impulses their last solve left; switched back, the names go.
    #[test]
    fn support_vertices_are_named_only_for_the_models_that_key_rows_by_them() {
        use crate::{BodyDesc, Shape, World, WorldSettings};
        let mut world = World::builder()
            .body(BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 1.0])).position([0.0, 0.0, -0.5]))
            .body(BodyDesc::dynamic(Shape::cuboid([1.0; 3])).position([0.3, 0.2, 0.5]))
            .build()
            .expect("a valid scene");
        let dt = 1.0 / 60.0;
        let names = |world: &World| -> Vec<FeatureIds> {
            let entries = &world.contact_set.entries;
            entries.iter().map(|e| e.state.features.clone()).collect()
        };
        let switch = |world: &mut World, model: ContactModel| {
            let settings = WorldSettings {
                model,
                ..*world.settings()
            };
            world.set_settings(settings).expect("valid settings");
        };
        for _ in 0..10 {
            world.step(dt).expect("a step");
        }
        assert_eq!(
            names(&world),
            vec![FeatureIds::new()],
            "the face model names nothing"
        );
        switch(&mut world, ContactModel::Vertex);
        world.step(dt).expect("a step");
        let named = names(&world);
        assert_eq!(named.len(), 1);
        let mut corners = named[0].to_vec();
        corners.sort();
        corners.dedup();
        assert_eq!(
            corners.len(),
            4,
            "four corners, each named once: {corners:?}"
        );
        // Body A is the floor (the lower index), B the cube.
        assert!(
            corners.iter().all(|id| matches!(id, FeatureId::B(_))),
            "the cube's corners"
        );
        // The next step's rows start from the impulses the last solve left, row by row.
        world.step(dt).expect("a step");
        let solved: Vec<f64> = world.problem().rows.iter().map(|r| r.impulse).collect();
        world.prepare_step(dt).expect("collision");
        let weight = world.gravity() * dt;
        world
            .contact_set
            .warm_start(ContactModel::Vertex, &mut world.problem, &weight);
        let started: Vec<f64> = world.problem().rows.iter().map(|r| r.impulse).collect();
        // Row by row, to the rounding the shock pass leaves on the friction rows of a cube at
        // rest (1e-14 N s against normal impulses of 40.8): a row started from zero or from an
        // estimate would be off by the order of the normal impulses.
        assert_eq!(started.len(), solved.len());
        for (start, solve) in started.iter().zip(&solved) {
            assert!(
                (start - solve).abs() <= 1e-12 * 40.0,
                "{started:?} against {solved:?}"
            );
        }
        assert!(solved.iter().step_by(3).all(|&normal| normal > 0.0));
        world.step(dt).expect("a step");
        switch(&mut world, ContactModel::Face);
        world.step(dt).expect("a step");
        assert_eq!(names(&world), vec![FeatureIds::new()]);
    }

    /// A segment whose ends are clipped by other edges from one step to the next (its end
    /// features renamed, as a cube lying across another's edge in a settling pile has it)
    /// starts from the impulses it ended with, its tilt too; and so, turned into a face or
    /// with its ends swapped, from the same weight and tilt. Named by its first end's feature,
    /// the segments' tilts restarted from zero about 30 times a step in the 1000-cube pile,
    /// which kept it creeping.
    #[test]
    fn a_segment_starts_from_its_last_impulses_whatever_its_ends_are_named() {
        use nalgebra::Point2;
        use tatami_contact::{ContactFrame, ContactSettings, Material};
        use tatami_geometry::ConvexPolygon;
        use tatami_lcp::{BodyId, SolverBody};
        let contact = |ends: &[(f64, f64)]| {
            let points: Vec<_> = ends.iter().map(|&(x, y)| Point2::new(x, y)).collect();
            let support = ConvexPolygon::from_points(&points).expect("a support");
            Contact {
                body_a: BodyId(0),
                body_b: BodyId(1),
                centre_a: Point3::new(0.1, 0.0, 0.5),
                centre_b: Point3::new(0.0, 0.0, -0.5),
                frame: ContactFrame::from_normal(Point3::origin(), Vector3::z()).expect("a frame"),
                depths: vec![0.0; support.vertices().len()],
                support,
                material: Material::new(0.5, 0.5, 0.0).expect("a material"),
                landing: Vec::new(),
                bounce_speed: 0.0,
            }
        };
        let rows = |set: &mut ContactSet| {
            let mut problem = Problem {
                bodies: vec![SolverBody::fixed(); 2],
                ..Problem::default()
            };
            let (contact, _) = set.get(0).expect("one pair");
            ContactModel::Face
                .build(contact, 0.01, &ContactSettings::default(), &mut problem)
                .expect("rows");
            set.set_blocks(0, 0..problem.blocks.len());
            problem
        };
        let segment = contact(&[(-0.5, 0.0), (0.5, 0.0)]);
        let pose = (Point3::origin(), UnitQuaternion::identity());
        let mut set = ContactSet::default();
        let features = [FeatureId::Crossing(4, 5), FeatureId::A(6)]
            .into_iter()
            .collect();
        set.insert((segment.clone(), features, [pose; 2]));
        let mut solved = rows(&mut set);
        // Weight, friction, tilt across the segment (the centre of pressure off its middle)
        // and twist.
        for (row, impulse) in solved.rows.iter_mut().zip([0.16, 0.01, -0.02, 0.03, 0.004]) {
            row.impulse = impulse;
        }
        set.store(ContactModel::Face, &solved);
        let impulses = |problem: &Problem<ContactProjection>| -> Vec<f64> {
            problem.rows.iter().map(|row| row.impulse).collect()
        };
        // Impulses below 0.2 carried through a few products and sums: rounding is ~1e-17, and
        // a row restarted from zero (the old naming) misses by 0.004 or more.
        let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15);
        let weight = Vector3::new(0.0, 0.0, -9.81 / 100.0);
        // The first end renamed.
        set.entries[0].state.features = [FeatureId::Crossing(6, 5), FeatureId::A(6)]
            .into_iter()
            .collect();
        let mut next = rows(&mut set);
        set.warm_start(ContactModel::Face, &mut next, &weight);
        assert!(
            close(&impulses(&next), &impulses(&solved)),
            "{:?}",
            impulses(&next)
        );
        // The ends swapped: the tilt axis turns over, and its impulse with it.
        set.entries[0].contact = contact(&[(0.5, 0.0), (-0.5, 0.0)]);
        let mut swapped = rows(&mut set);
        set.warm_start(ContactModel::Face, &mut swapped, &weight);
        let applied =
            |p: &Problem<ContactProjection>| ContactImpulse::of_rows(&p.rows, segment.centre_a);
        let same = |a: ContactImpulse, b: ContactImpulse| {
            (a.linear - b.linear).norm() < 1e-15 && (a.angular - b.angular).norm() < 1e-15
        };
        assert!(same(applied(&swapped), applied(&solved)));
        // A face now, over the segment and on one side of it: the same weight and tilt.
        set.entries[0].contact = contact(&[(-0.5, 0.0), (0.5, 0.0), (0.5, 0.3), (-0.5, 0.3)]);
        let mut face = rows(&mut set);
        set.warm_start(ContactModel::Face, &mut face, &weight);
        assert!(same(applied(&face), applied(&solved)));
    }

    /// The bounded test of a turn answers as the arc tangent does, for turns of 1e-9 to 3 rad
    /// about random axes and lengths that put the arc anywhere from a thousandth to a thousand
    /// times the tolerance, and on both sides of it within 1e-12.
    #[test]
    fn turned_within_answers_as_the_angle_does() {
        let mut random = crate::dropped::Random::new(11);
        let tolerance = REUSE_TOLERANCE;
        let (mut inside, mut outside) = (0, 0);
        for case in 0..20_000 {
            let axis = nalgebra::Unit::new_normalize(Vector3::new(
                random.between(-1.0, 1.0),
                random.between(-1.0, 1.0),
                random.between(-1.0, 1.0),
            ));
            let was = UnitQuaternion::from_euler_angles(
                random.between(-3.0, 3.0),
                random.between(-3.0, 3.0),
                random.between(-3.0, 3.0),
            );
            let angle = 10f64.powf(random.between(-9.0, 0.5));
            let now = UnitQuaternion::from_axis_angle(&axis, angle) * was;
            let exact = now.angle_to(&was);
            let length = if case % 4 == 0 {
                // At the tolerance, to rounding.
                tolerance / exact * (1.0 + random.between(-1e-12, 1e-12))
            } else {
                tolerance / exact * 10f64.powf(random.between(-3.0, 3.0))
            };
            let expected = exact * length <= tolerance;
            assert_eq!(
                turned_within(&now, &was, length, tolerance),
                expected,
                "case {case}: {angle} rad, {length} m"
            );
            if expected { inside += 1 } else { outside += 1 }
        }
        assert!(
            inside > 5000 && outside > 5000,
            "{inside} within, {outside} not"
        );
    }

    /// Against the standard stable sort, on keys with many ties and orders near sorted and
    /// far from it.
    #[test]
    fn sort_in_place_is_a_stable_sort() {
        let mut random = crate::dropped::Random::new(5);
        let mut keys = Vec::new();
        for len in [0, 1, 2, 7, 100, 1000] {
            for spread in [2.0, 50.0, 1e6] {
                let items: Vec<(i64, usize)> = (0..len)
                    .map(|i| (random.between(0.0, spread) as i64, i))
                    .collect();
                let mut expected = items.clone();
                expected.sort_by_key(|item| item.0);
                let mut sorted = items.clone();
                let moved = sort_in_place(&mut sorted, &mut keys, |item| item.0);
                assert_eq!(sorted, expected, "{len} items, keys below {spread}");
                assert_eq!(moved, sorted != items, "{len} items, keys below {spread}");
                // Sorted, nothing moves.
                assert!(!sort_in_place(&mut sorted, &mut keys, |item| item.0));
            }
        }
    }

    #[test]
    fn total_order_sorts_as_total_cmp() {
        let values = [
            f64::NEG_INFINITY,
            -1e300,
            -1.0,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            5e-324,
            1.0,
            2.5,
            1e300,
            f64::INFINITY,
            f64::NAN,
        ];
        for a in values {
            for b in values {
                assert_eq!(
                    total_order(a).cmp(&total_order(b)),
                    a.total_cmp(&b),
                    "{a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn rows_are_named_by_feature_and_rank() {
        let features = [FeatureId::A(4), FeatureId::Crossing(1, 2)];
        let mut keys = Vec::new();
        row_keys(ContactModel::Vertex, &features, 6, &mut keys);
        let vertex: Vec<RowKey> = [0, 1, 2, 0, 1, 2]
            .iter()
            .enumerate()
            .map(|(r, &rank)| (Some(features[r / 3]), rank))
            .collect();
        assert_eq!(keys, vertex);
        row_keys(ContactModel::Patch, &features, 5, &mut keys);
        assert_eq!(
            keys,
            [
                (Some(features[0]), 0),
                (Some(features[1]), 0),
                (None, 0),
                (None, 1),
                (None, 2)
            ]
        );
    }

    /// The resultant of the shares, and their sum.
    fn resultant(vertices: &[Point2<f64>], shares: &[f64]) -> (Point2<f64>, f64) {
        let at = vertices
            .iter()
            .zip(shares)
            .fold(Vector2::zeros(), |r, (v, w)| r + v.coords * *w);
        (at.into(), shares.iter().sum())
    }

    /// On a 2 × 1 rectangle the shares put the load where asked, up to and on the edges (where
    /// the far side's shares are zero); at the centre they stay even, and beyond an edge they
    /// stop at it. A segment shares along its line.
    #[test]
    fn shares_put_a_load_where_it_acts() {
        let rectangle = [[-1.0, -0.5], [1.0, -0.5], [1.0, 0.5], [-1.0, 0.5]].map(Point2::from);
        let mut shares = [0.25; 4];
        shares_towards(&rectangle, &Point2::origin(), &mut shares);
        assert_eq!(shares, [0.25; 4]);
        for at in [[0.3, 0.1], [-0.9, 0.45], [1.0, 0.0], [1.0, 0.5]].map(Point2::from) {
            let mut shares = [0.25; 4];
            shares_towards(&rectangle, &at, &mut shares);
            let (resultant, total) = resultant(&rectangle, &shares);
            assert!((resultant - at).norm() < 1e-15, "{at}: {shares:?}");
            assert!((total - 1.0).abs() < 1e-15 && shares.iter().all(|&w| w >= 0.0));
        }
        let mut shares = [0.25; 4];
        shares_towards(&rectangle, &Point2::new(1.5, 0.0), &mut shares);
        assert_eq!(shares, [0.0, 0.5, 0.5, 0.0]);
        let segment = [[0.0, 0.0], [2.0, 2.0]].map(Point2::from);
        let mut shares = [0.5; 2];
        shares_towards(&segment, &Point2::new(1.5, 1.5), &mut shares);
        assert!((shares[0] - 0.25).abs() < 1e-15 && (shares[1] - 0.75).abs() < 1e-15);
    }

    proptest::proptest! {
        /// Any convex polygon (the hull of 3 to 8 random points) and any point of it: the shares
        /// are non-negative, sum to 1 and put their resultant at the point.
        #[test]
        fn shares_are_a_distribution_with_their_resultant_where_asked(
            points in proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 3..8),
            weights in proptest::collection::vec(0.0f64..1.0, 8),
        ) {
            let points: Vec<_> = points.iter().map(|&(x, y)| Point2::new(x, y)).collect();
            let Ok(polygon) = tatami_geometry::ConvexPolygon::from_points(&points) else {
                return Ok(());
            };
            let vertices = polygon.vertices();
            proptest::prop_assume!(polygon.area() > 1e-3);
            // A point of the polygon: a convex combination of its vertices.
            let total: f64 = weights.iter().take(vertices.len()).sum::<f64>() + 1e-9;
            let at = vertices.iter().zip(&weights).fold(Vector2::zeros(), |p, (v, w)| {
                p + v.coords * (*w / total)
            });
            let at = Point2::from(at);
            let mut shares = vec![1.0 / vertices.len() as f64; vertices.len()];
            shares_towards(vertices, &at, &mut shares);
            let (resultant, sum) = resultant(vertices, &shares);
            proptest::prop_assert!((sum - 1.0).abs() < 1e-12);
            proptest::prop_assert!(shares.iter().all(|&w| w >= 0.0));
            proptest::prop_assert!((resultant - at).norm() < 1e-9, "{resultant} {at} {shares:?}");
        }
    }
}
