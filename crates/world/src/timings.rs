//! Wall-clock time of each stage of a step, so callers can time the solver alone.

use std::time::Duration;

/// Time spent in each stage of the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StepTimings {
    /// Broad phase, narrow phase and support polygons.
    pub collision: Duration,
    /// Contact rows and solver bodies, and the contact set's bookkeeping around the solve: its
    /// warm start of the rows from the last step's impulses and its keeping of this step's (at
    /// the solve's start and end, timed here so that collision and this stage are all the step
    /// spends outside the solver).
    pub setup: Duration,
    /// The velocity solve (with its shock pass), and the copy of the problem the position pass
    /// works on.
    pub solve: Duration,
    /// The position correction (split-impulse) pass; zero on steps where no contact is deeper
    /// than the slop. On a large problem the pass runs on a helper thread beside the velocity
    /// solve, and this is only what the step still waits for after it.
    pub correction: Duration,
    /// Velocities back to bodies, positions and orientations advanced.
    pub integrate: Duration,
}

impl std::ops::AddAssign for StepTimings {
    /// Adds `other`'s stages to these: a step's timings are its substeps' sums.
    fn add_assign(&mut self, other: Self) {
        self.collision += other.collision;
        self.setup += other.setup;
        self.solve += other.solve;
        self.correction += other.correction;
        self.integrate += other.integrate;
    }
}

impl StepTimings {
    /// Sum of the stages.
    pub fn total(&self) -> Duration {
        self.collision + self.setup + self.solve + self.correction + self.integrate
    }
}
