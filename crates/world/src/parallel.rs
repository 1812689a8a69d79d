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
//! own thread). Each item is a pure function of its own data, so which thread does it changes
//! nothing in the result.

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
    let claims: Vec<Mutex<&mut [T]>> = items.chunks_mut(ITEMS_PER_CLAIM).map(Mutex::new).collect();
    let next = AtomicUsize::new(0);
    let take_part = || {
        let mut own = scratch();
        while let Some(claim) = claims.get(next.fetch_add(1, Ordering::Relaxed)) {
            let mut piece = claim.lock().unwrap_or_else(PoisonError::into_inner);
            for item in piece.iter_mut() {
                work(&mut own, item);
            }
        }
    };
    rayon::in_place_scope(|scope| {
        for _ in 1..rayon::current_num_threads() {
            scope.spawn(|_| take_part());
        }
        take_part();
    });
}

/// Longest a [`Warm`] keeps a helper spinning if it is never dropped in time.
const LONGEST_WARM: Duration = Duration::from_millis(5);

/// Wakes the pool's helpers now and keeps them spinning until dropped, so that a [`for_each`]
/// called after some work on this thread finds them awake: a woken helper took 0.15 ms to
/// start (median; 1 ms at the 90th percentile) on the two-core virtual machine measured, and
/// a loop of a few milliseconds started without one lost that much of its second core. Drop
/// it just before the loop: the drop waits for the helpers that started spinning to stop, so
/// they are idle, and take the loop's work without being woken again.
#[must_use = "the helpers spin until this is dropped"]
pub(crate) struct Warm {
    spin: Arc<Spin>,
}

/// What the spinning helpers and their [`Warm`] share.
#[derive(Default)]
struct Spin {
    stop: AtomicBool,
    started: AtomicUsize,
    finished: AtomicUsize,
}

impl Warm {
    /// Starts spinning every helper of the pool.
    pub(crate) fn start() -> Self {
        let spin = Arc::new(Spin::default());
        for _ in 1..rayon::current_num_threads() {
            let spin = Arc::clone(&spin);
            rayon::spawn(move || {
                // Sequentially consistent with the drop's `stop` then `started`: either the
                // drop waits for this helper, or this helper sees `stop` and returns at once.
                spin.started.fetch_add(1, Ordering::SeqCst);
                let start = Instant::now();
                while !spin.stop.load(Ordering::SeqCst) && start.elapsed() < LONGEST_WARM {
                    for _ in 0..64 {
                        std::hint::spin_loop();
                    }
                }
                spin.finished.fetch_add(1, Ordering::SeqCst);
            });
        }
        Self { spin }
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
}
