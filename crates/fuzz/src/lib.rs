//! Fuzz harnesses for Tatami's public entry points.
//!
//! Each harness takes arbitrary bytes, drives one entry point with them, and panics only when
//! the engine breaks a promise: a panic inside the engine, a hang, or an `Ok` answer that is not
//! finite or not admissible. Refusals with a typed error are the expected answer to bad input.
//!
//! The harnesses are shared by the `cargo fuzz` targets in `fuzz/` (nightly, libFuzzer) and by
//! this crate's `corpus` test, which replays the committed corpus on stable.

pub mod bytes;
mod geometry;
mod lcp;
mod scene;

pub use geometry::geometry;
pub use lcp::lcp;
pub use scene::{load_and_step, scene_loader};

/// A harness: runs one input, panicking only on a broken promise.
pub type Harness = fn(&[u8]);

/// The harnesses by the name of their fuzz target and corpus folder.
pub const TARGETS: [(&str, Harness); 4] = [
    ("scene_loader", scene_loader),
    ("load_and_step", load_and_step),
    ("geometry", geometry),
    ("lcp", lcp),
];
