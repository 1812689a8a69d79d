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
//! Each item is a pure function of its own data, so which thread does it changes nothing in the
//! result.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

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
