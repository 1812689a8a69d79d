//! Work on every core with the calling thread taking part: each thread claims small pieces in
//! turn until none are left.
//!
//! Why not a plain `par_iter`: called from outside the thread pool (a program's own thread, as a
//! world step is), rayon hands the whole loop to its workers and the caller sleeps until they are
//! done, so the loop waits first for a sleeping worker to wake, then the caller waits to be woken.
//! On a virtual machine of two cores a worker asleep for the length of a solve (10 ms) took
//! 0.2–1 ms to start, and after 50 ms 1.5–2.4 ms: a 4 ms loop handed over then took as long as
//! run on one thread. Here the caller starts at once and claims pieces while the helpers wake;
//! a helper that wakes late finds little or nothing left (the loop still ends only once every
//! helper has started, so a short loop waits for the slowest wake: callers keep those on their
//! own thread). [`for_each_beside`] goes further: the helpers start on the items while the
//! caller does other work first (collision's broad phase), so their wake-up is hidden behind
//! it; [`join_beside`] does the same for one job (the position pass beside the velocity solve).
//! Between two loops with a little work on the calling thread (the end of collision before the
//! rows), [`Warm`] keeps the helpers spinning, so the second loop finds them awake; between two
//! steps, [`keep_warm_for_next_step`] does, taking any work the pool is handed meanwhile.
//! Each item is a pure function of its own data, so which thread does it changes nothing in the
//! result.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// Most items one claim takes: small enough that the threads finish together, large enough
/// that claiming (one atomic add and one lock nobody else holds) costs nothing beside them.
const ITEMS_PER_CLAIM: usize = 8;

/// Calls `work(scratch, item)` once on every item, on the calling thread and the pool's
/// threads, each with its own `scratch` from `scratch()`.
pub(crate) fn for_each<T, S>(
    items: &mut [T],
    scratch: fn() -> S,
    work: impl Fn(&mut S, &mut T) + Sync,
) where
    T: Send,
{
    for_each_beside(
        items,
        scratch,
        |scratch, item| {
            work(scratch, item);
            false
        },
        || (),
    );
}

/// [`for_each`], with the calling thread running `beside` first while the pool's helpers start
/// on the items; it then joins them. Returns what `beside` returned and on how many items
/// `work` returned `true` (counted by each thread on its own and added once at its end: a
/// counter shared item by item would bounce its cache line between the cores).
pub(crate) fn for_each_beside<T, S, R>(
    items: &mut [T],
    scratch: fn() -> S,
    work: impl Fn(&mut S, &mut T) -> bool + Sync,
    beside: impl FnOnce() -> R,
) -> (R, usize)
where
    T: Send,
{
    stop_warm_for_next_step();
    let claims: Vec<Mutex<&mut [T]>> = items.chunks_mut(ITEMS_PER_CLAIM).map(Mutex::new).collect();
    let next = AtomicUsize::new(0);
    let counted = AtomicUsize::new(0);
    let take_part = || {
        let (mut own, mut count) = (scratch(), 0);
        while let Some(claim) = claims.get(next.fetch_add(1, Ordering::Relaxed)) {
            let mut piece = claim.lock().unwrap_or_else(PoisonError::into_inner);
            for item in piece.iter_mut() {
                count += usize::from(work(&mut own, item));
            }
        }
        counted.fetch_add(count, Ordering::Relaxed);
    };
    let result = rayon::in_place_scope(|scope| {
        for _ in 1..rayon::current_num_threads() {
            scope.spawn(|_| take_part());
        }
        let result = beside();
        take_part();
        result
    });
    (result, counted.into_inner())
}

/// Shares `items` between the calling thread, which takes them one at a time from the front
/// with `front` (so in order, and `front` may write to what only this thread holds), and the
/// pool's helpers, which take them from the back with `back`, until the two meet; returns how
/// many the front took. Only the helpers' share is then handled apart: the rows stage builds
/// the front's pairs straight into the problem and copies in the back's. With one thread, or
/// helpers slow to wake, the front takes them all.
pub(crate) fn from_both_ends<T>(
    items: &mut [T],
    mut front: impl FnMut(&mut T),
    back: impl Fn(&mut T) + Sync,
) -> usize
where
    T: Send,
{
    stop_warm_for_next_step();
    // The next item from the front, and one past the next from the back.
    let ends = Mutex::new((0, items.len()));
    let claim = |from_front: bool| {
        let mut ends = ends.lock().unwrap_or_else(PoisonError::into_inner);
        let (next, past) = &mut *ends;
        (*next < *past).then(|| {
            if from_front {
                *next += 1;
                *next - 1
            } else {
                *past -= 1;
                *past
            }
        })
    };
    let slots: Vec<Mutex<&mut T>> = items.iter_mut().map(Mutex::new).collect();
    let take = |k: usize| slots[k].lock().unwrap_or_else(PoisonError::into_inner);
    rayon::in_place_scope(|scope| {
        for _ in 1..rayon::current_num_threads() {
            scope.spawn(|_| {
                while let Some(k) = claim(false) {
                    back(&mut take(k));
                }
            });
        }
        while let Some(k) = claim(true) {
            front(&mut take(k));
        }
    });
    ends.into_inner().unwrap_or_else(PoisonError::into_inner).0
}

/// Runs `beside` on the calling thread while a helper of the pool runs `job`; a `job` no helper
/// has taken by the time `beside` ends is run on the calling thread then (one thread, or a
/// helper slow to wake). `job` runs once either way, so where it ran changes nothing in the
/// result when the two share no state, as their borrows ensure.
pub(crate) fn join_beside<A, B>(
    beside: impl FnOnce() -> A,
    job: impl FnOnce() -> B + Send,
) -> (A, B)
where
    B: Send,
{
    stop_warm_for_next_step();
    let job = Mutex::new(Some(job));
    let answer = Mutex::new(None);
    let take = || {
        let taken = job.lock().unwrap_or_else(PoisonError::into_inner).take();
        if let Some(job) = taken {
            let result = job();
            *answer.lock().unwrap_or_else(PoisonError::into_inner) = Some(result);
        }
    };
    let result = rayon::in_place_scope(|scope| {
        if rayon::current_num_threads() > 1 {
            scope.spawn(|_| take());
        }
        let result = beside();
        take();
        result
    });
    let answer = answer
        .into_inner()
        .unwrap_or_else(PoisonError::into_inner)
        .expect("the job ran: the calling thread runs it unless a helper took it, and the scope waited for the helper");
    (result, answer)
}

/// Longest a [`Warm`] keeps a helper spinning if it is not dropped in time: longer than the
/// 1000-cube pile's collision at rest (under 1 ms), which a large scene's helpers spin
/// through, and short, since worlds stepped on several threads at once share the pool, and a
/// helper spinning for one holds back the loops of the others until it stops. Measured with
/// four worlds stepped at once (`benches`' `worlds_at_once`), the spins and every other
/// parallel loop of their steps cost nothing beside the same steps with them turned off.
const LONGEST_WARM: Duration = Duration::from_millis(2);

/// Keeps the pool's helpers spinning from when it starts until it is dropped, so that a loop
/// called after some work on this thread finds them awake: a helper idle for more than some
/// tens of microseconds goes to sleep, and one woken took 0.15 ms to start (median; 1 ms at
/// the 90th percentile) on the two-core virtual machine measured, where the 1000-cube pile's
/// rows take under a millisecond on one core. Start it while the helpers are still awake from
/// a loop, and drop it just before the next: the drop waits for the helpers that started
/// spinning to stop, so they are idle and take the loop's work without being woken. Nothing
/// between may hand the pool work (its helpers are busy spinning, for up to `LONGEST_WARM`).
#[must_use = "the helpers spin until this is dropped"]
#[derive(Debug)]
pub(crate) struct Warm {
    spin: Arc<Spin>,
}

/// What the spinning helpers and their [`Warm`] (or [`keep_warm_for_next_step`]) share.
#[derive(Debug, Default)]
struct Spin {
    stop: AtomicBool,
    started: AtomicUsize,
    finished: AtomicUsize,
}

impl Spin {
    /// Spins every helper of the pool until told to stop, for at most `LONGEST_WARM`; helpers
    /// that `take_jobs` run any job the pool is handed meanwhile.
    fn start(take_jobs: bool) -> Arc<Self> {
        let spin = Arc::new(Self::default());
        for _ in 1..rayon::current_num_threads() {
            let spin = Arc::clone(&spin);
            rayon::spawn(move || {
                // Sequentially consistent with a `Warm`'s drop, `stop` then `started`: either
                // the drop waits for this helper, or this helper sees `stop` and returns at once.
                spin.started.fetch_add(1, Ordering::SeqCst);
                let start = Instant::now();
                while !spin.stop.load(Ordering::SeqCst) && start.elapsed() < LONGEST_WARM {
                    if !(take_jobs && rayon::yield_now() == Some(rayon::Yield::Executed)) {
                        for _ in 0..64 {
                            std::hint::spin_loop();
                        }
                    }
                }
                spin.finished.fetch_add(1, Ordering::SeqCst);
            });
        }
        spin
    }
}

impl Warm {
    /// Starts spinning every helper of the pool.
    pub(crate) fn start() -> Self {
        stop_warm_for_next_step();
        Self {
            spin: Spin::start(false),
        }
    }

    /// Whether every helper of the pool is spinning now (none has stopped at `LONGEST_WARM`):
    /// a loop after the drop then finds them all awake, where one that has to wake a helper
    /// waits for it.
    pub(crate) fn all_spinning(&self) -> bool {
        let helpers = rayon::current_num_threads() - 1;
        helpers > 0
            && self.spin.started.load(Ordering::SeqCst) == helpers
            && self.spin.finished.load(Ordering::SeqCst) == 0
    }
}

impl Drop for Warm {
    fn drop(&mut self) {
        self.spin.stop.store(true, Ordering::SeqCst);
        let started = self.spin.started.load(Ordering::SeqCst);
        while self.spin.finished.load(Ordering::SeqCst) < started {
            std::hint::spin_loop();
        }
    }
}

/// The helpers [`keep_warm_for_next_step`] set spinning, and when.
static WARM_FOR_NEXT_STEP: Mutex<Option<(Arc<Spin>, Instant)>> = Mutex::new(None);

/// Keeps the pool's helpers spinning, for at most [`LONGEST_WARM`], until a loop of this
/// module starts (on any thread), so that the next step's first loop finds them awake (called
/// at a step's end, and at its start should the helpers have stopped since). Woken at the
/// loop instead, a helper started the 1000-cube pile's collision late (0.4–0.9 ms a step
/// while the pile lands, where the caller's broad phase ahead of it takes 0.5 ms), and the
/// step was 0.3–0.5 ms longer. Unlike a [`Warm`]'s, these helpers take any job the pool is
/// handed while they spin (`rayon::yield_now`), so a program's own parallel work between two
/// steps is not held back, and nothing waits for them to stop. Does nothing on a thread of the
/// pool (a world stepped as a job of the pool would keep its siblings from their jobs) or in a
/// pool of one thread.
pub(crate) fn keep_warm_for_next_step() {
    if rayon::current_num_threads() < 2 || rayon::current_thread_index().is_some() {
        return;
    }
    let mut warm = WARM_FOR_NEXT_STEP
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    // Started less than half their spin ago, they still spin well into the coming loop.
    if let Some((_, since)) = &*warm
        && since.elapsed() < LONGEST_WARM / 2
    {
        return;
    }
    if let Some((spin, _)) = warm.take() {
        spin.stop.store(true, Ordering::SeqCst);
    }
    let spin = Spin::start(true);
    *warm = Some((spin, Instant::now()));
}

/// Stops the helpers [`keep_warm_for_next_step`] set spinning, if any, without waiting: each
/// stops within a spin, or once the job it took ends.
fn stop_warm_for_next_step() {
    let warm = WARM_FOR_NEXT_STEP
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .take();
    if let Some((spin, _)) = warm {
        spin.stop.store(true, Ordering::SeqCst);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_item_is_done_once_with_a_scratch_of_its_thread() {
        for len in [0, 1, 7, 8, 9, 100, 1001] {
            let mut items: Vec<(usize, u32)> = (0..len).map(|i| (i, 0)).collect();
            for_each(&mut items, Vec::<usize>::new, |seen, (index, visits)| {
                // The scratch is the thread's own: it only grows while this thread works.
                seen.push(*index);
                assert!(seen.windows(2).all(|w| w[0] < w[1]), "claims go forward");
                *visits += 1;
            });
            assert!(
                items
                    .iter()
                    .enumerate()
                    .all(|(i, &(index, visits))| index == i && visits == 1),
                "{len} items"
            );
        }
    }

    #[test]
    fn beside_runs_on_the_calling_thread_while_every_item_is_done_once() {
        let caller = std::thread::current().id();
        for len in [0, 1, 9, 1001] {
            let mut items: Vec<(usize, u32)> = (0..len).map(|i| (i, 0)).collect();
            let (ran_on, odd) = for_each_beside(
                &mut items,
                || (),
                |(), (index, visits)| {
                    *visits += 1;
                    *index % 2 == 1
                },
                || std::thread::current().id(),
            );
            assert_eq!(ran_on, caller, "{len} items");
            assert_eq!(odd, len / 2, "items counted, {len} items");
            assert!(items.iter().all(|&(_, v)| v == 1), "{len} items");
        }
    }

    #[test]
    fn from_both_ends_the_front_takes_a_prefix_in_order_and_every_item_is_done_once() {
        let check = |case: &str| {
            let caller = std::thread::current().id();
            for len in [0, 1, 2, 9, 1001] {
                let mut items: Vec<(usize, u32, bool)> = (0..len).map(|i| (i, 0, false)).collect();
                let mut order = Vec::new();
                let taken = from_both_ends(
                    &mut items,
                    |(index, visits, by_front)| {
                        assert_eq!(std::thread::current().id(), caller, "{case}");
                        order.push(*index);
                        *visits += 1;
                        *by_front = true;
                    },
                    |(_, visits, _)| *visits += 1,
                );
                assert_eq!(order, (0..taken).collect::<Vec<_>>(), "{case}, {len} items");
                assert!(
                    items
                        .iter()
                        .all(|&(i, v, by_front)| v == 1 && by_front == (i < taken)),
                    "{case}, {len} items"
                );
            }
        };
        check("global pool");
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| check(&format!("{threads} threads")));
        }
    }

    #[test]
    fn a_loop_after_a_warm_pool_does_every_item_once_and_the_helpers_stop() {
        for _ in 0..20 {
            let warm = Warm::start();
            let spin = Arc::clone(&warm.spin);
            drop(warm);
            let mut items = vec![0u32; 100];
            for_each(&mut items, || (), |(), visits| *visits += 1);
            assert!(items.iter().all(|&v| v == 1));
            // Every helper's spin ends once it runs: at once when it starts after the drop, and
            // bounded by `LONGEST_WARM` anyway; 10 s only guards against a hang.
            let deadline = Instant::now() + Duration::from_secs(10);
            let helpers = rayon::current_num_threads() - 1;
            while spin.finished.load(Ordering::SeqCst) < helpers {
                assert!(Instant::now() < deadline, "a helper kept spinning");
                std::thread::yield_now();
            }
        }
    }

    /// Helpers kept spinning for the next step leave a job handed to the pool meanwhile free
    /// to run, are stopped by the next loop, which does every item once, and end their spins.
    #[test]
    fn helpers_kept_warm_for_the_next_step_stop_at_the_next_loop() {
        let mut seen = 0;
        for _ in 0..20 {
            keep_warm_for_next_step();
            let spin = WARM_FOR_NEXT_STEP
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .as_ref()
                .map(|(spin, _)| Arc::clone(spin));
            // A program's own job: 10 s only guards against a hang.
            let (sender, receiver) = std::sync::mpsc::channel();
            rayon::spawn(move || sender.send(()).unwrap());
            receiver
                .recv_timeout(Duration::from_secs(10))
                .expect("the job ran");
            let mut items = vec![0u32; 100];
            for_each(&mut items, || (), |(), visits| *visits += 1);
            assert!(items.iter().all(|&v| v == 1));
            // None on a pool of one thread, or should another test's loop have stopped them
            // before they were read here.
            let Some(spin) = spin else { continue };
            seen += 1;
            assert!(spin.stop.load(Ordering::SeqCst), "the loop stopped them");
            let deadline = Instant::now() + Duration::from_secs(10);
            while spin.finished.load(Ordering::SeqCst) < rayon::current_num_threads() - 1 {
                assert!(Instant::now() < deadline, "a helper kept spinning");
                std::thread::yield_now();
            }
        }
        assert!(seen > 0 || rayon::current_num_threads() == 1);
    }

    /// Helpers still spinning say so; none do once they have stopped at `LONGEST_WARM`, nor
    /// on a pool of one thread, where there are none.
    #[test]
    fn a_warm_pool_says_whether_its_helpers_still_spin() {
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        assert!(!one.install(|| Warm::start().all_spinning()));
        let two = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        two.install(|| {
            let warm = Warm::start();
            let deadline = Instant::now() + Duration::from_secs(10);
            while warm.spin.started.load(Ordering::SeqCst) == 0 {
                assert!(Instant::now() < deadline, "the helper never started");
                std::thread::yield_now();
            }
            // Spinning, unless it has already stopped (read on both sides, as it may stop
            // meanwhile); a finished helper is never counted.
            let finished = || warm.spin.finished.load(Ordering::SeqCst);
            let (before, spinning, after) = (finished(), warm.all_spinning(), finished());
            if before == after {
                assert_eq!(spinning, after == 0);
            }
            while warm.spin.finished.load(Ordering::SeqCst) == 0 {
                assert!(Instant::now() < deadline, "the helper never stopped");
                std::thread::yield_now();
            }
            assert!(!warm.all_spinning());
        });
    }

    #[test]
    fn join_beside_runs_the_job_once_and_beside_on_the_calling_thread() {
        let check = |case: &str| {
            let caller = std::thread::current().id();
            let runs = AtomicUsize::new(0);
            let (ran_on, answer) = join_beside(
                || std::thread::current().id(),
                || {
                    runs.fetch_add(1, Ordering::Relaxed);
                    (1..=100u64).sum::<u64>()
                },
            );
            assert_eq!(ran_on, caller, "{case}");
            assert_eq!(answer, 5050, "{case}");
            assert_eq!(runs.into_inner(), 1, "{case}");
        };
        // From outside any pool, as a program's own thread steps a world, and from inside one.
        check("global pool");
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| check(&format!("{threads} threads")));
        }
    }
}
