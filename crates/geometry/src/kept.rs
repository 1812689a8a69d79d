//! A value of a polygon computed when first asked and kept with it.
//!
//! A contact's polygon is cloned into its constraint every step and read from several threads,
//! so the kept value sits in an atomic: a clone copies it with one load. `OnceLock`, used
//! before, clones through its `set` (a `Once` call), which was 6% of a resting 820-cube
//! pyramid's row-building instructions.

use std::sync::atomic::{AtomicU64, Ordering};

/// The bits that mean "not computed yet": a NaN that arithmetic does not produce (x86's default
/// NaN is `0xfff8…`), and one that would only be kept if computed from an input holding it,
/// which costs a recomputation each time and nothing else.
const UNSET: u64 = u64::MAX;

/// An `f64` computed when first asked for and kept; clones keep it too.
#[derive(Debug)]
pub(crate) struct Kept(AtomicU64);

impl Kept {
    /// Not computed yet.
    pub(crate) fn new() -> Self {
        Self(AtomicU64::new(UNSET))
    }

    /// The kept value, or `compute()` kept. Two threads asking at once may both compute it:
    /// a pure function of the polygon, it is the same value to the bit.
    pub(crate) fn get_or(&self, compute: impl FnOnce() -> f64) -> f64 {
        let bits = self.0.load(Ordering::Relaxed);
        if bits != UNSET {
            return f64::from_bits(bits);
        }
        let value = compute();
        self.0.store(value.to_bits(), Ordering::Relaxed);
        value
    }
}

impl Clone for Kept {
    fn clone(&self) -> Self {
        Self(AtomicU64::new(self.0.load(Ordering::Relaxed)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_is_computed_once_and_cloned_with_it() {
        let calls = std::cell::Cell::new(0);
        let ask = |kept: &Kept| {
            kept.get_or(|| {
                calls.set(calls.get() + 1);
                -0.25
            })
        };
        let kept = Kept::new();
        assert_eq!(ask(&kept), -0.25);
        assert_eq!(ask(&kept), -0.25);
        let clone = kept.clone();
        assert_eq!(ask(&clone).to_bits(), (-0.25f64).to_bits());
        assert_eq!(calls.get(), 1, "computed once, clone included");
        // Cloned before it was computed, a copy computes its own.
        let fresh = Kept::new().clone();
        assert_eq!(ask(&fresh), -0.25);
        assert_eq!(calls.get(), 2);
    }
}
