//! World settings: contact model, solver, contact tuning, collision tolerances.

use tatami_contact::{ContactModel, ContactSettings, TwistRadius};
use tatami_lcp::direct::DirectParams;
use tatami_lcp::pgs::{PgsParams, WarmStart};

use crate::{Sleeping, WorldError};

/// Most PGS sweeps a world accepts: far beyond convergence for any contact problem (the paper
/// uses 15), and small enough that a step always ends — 2⁶⁴ − 1 sweeps would hang it.
pub const MAX_ITERATIONS: usize = 100_000;

/// Which solver a step calls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Solver {
    /// Projected Gauss–Seidel (sequential impulses), the default.
    Pgs(PgsParams),
    /// The pivoting direct solver (dense, exact; for reference and comparison), for every
    /// contact model. Its problem must be linear, so it takes the circular friction cone as its
    /// inscribed polygon of [`tatami_contact::FrictionCone::DIRECT_FACETS`] sides, and the face
    /// model's twist bound about the support's centroid
    /// ([`tatami_contact::TwistCentre::Centroid`]) and apart from the friction force
    /// ([`tatami_contact::FrictionLimit::Separate`]).
    Direct(DirectParams),
}

/// The default PGS solve stops an island early once a sweep changes every one of its rows'
/// velocities by less than this (m/s, or rad/s for angular rows; [`PgsParams::tolerance`]):
/// 0.1 mm/s, a thousandth of what gravity adds in a step at 100 Hz. Resting islands,
/// warm-started, then take one or two sweeps; moving ones take all of them.
pub const PGS_TOLERANCE: f64 = 1e-4;

/// Most sweeps of the default PGS solve: 12, where the paper runs 15
/// ([`tatami_lcp::pgs::DEFAULT_ITERATIONS`]). Warm-started, with new contacts starting from the
/// weight they carry and the shock pass after the sweeps, 12 hold every stack, pyramid and
/// tipping body the world's tests check, and the 1000-cube pile's step took 15% less
/// (`general_comparison`); at 10 or 11 a body tipping on its support no longer pivots about
/// its edge within the closed form's 0.1%.
pub const PGS_ITERATIONS: usize = 12;

impl Default for Solver {
    /// PGS with up to [`PGS_ITERATIONS`] sweeps, warm-started from the contact set's impulses
    /// of the last step (a face-model block from the impulse it applied, other rows by feature
    /// id): the solver's residual then carries over instead of sinking stacks anew every step;
    /// it stops early at [`PGS_TOLERANCE`].
    fn default() -> Self {
        Self::Pgs(PgsParams {
            warm_start: WarmStart::On,
            tolerance: PGS_TOLERANCE,
            iterations: PGS_ITERATIONS,
            ..PgsParams::default()
        })
    }
}

/// Everything a step needs besides the bodies and gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSettings {
    /// How contacts become rows.
    pub model: ContactModel,
    /// How the rows are solved.
    pub solver: Solver,
    /// Bias, slop, restitution threshold, friction switching and cone.
    pub contact: ContactSettings,
    /// Bodies closer than this (m) get a contact, so a resting gap is closed without bouncing.
    /// A pair's margin is at most a quarter, and its slop ([`ContactSettings::slop`]) a tenth,
    /// of its thinner body's thickness (its least width), so thin and small bodies get
    /// tolerances of their own scale; bodies over 2 cm thick keep the settings'.
    pub contact_margin: f64,
    /// Faces tilted by less than this (rad) from the contact plane count as flat, so a resting
    /// face keeps its full support polygon.
    pub feature_angle: f64,
    /// After each PGS solve, one more pass from the ground up in which every contact's lower
    /// body is held still ([`pgs::shock_propagation`](tatami_lcp::pgs::shock_propagation)):
    /// a stack's weight reaches the floor in one pass instead of one level per sweep. The pass
    /// is kept only if it leaves the bodies with no more kinetic energy than the sweeps did, so
    /// it can stop a stack but never launch one. On by default.
    pub shock_propagation: bool,
    /// Islands of bodies at rest fall asleep and cost nothing until woken (see [`Sleeping`]).
    /// Off by default.
    pub sleeping: Sleeping,
    /// Most substeps a step is split into when its bodies are small for it or one turns fast
    /// (1 to [`SUBSTEP_LIMIT`]; 1 never splits): a step falls into the fewest that keep
    /// gravity's fall in one, `g (dt/n)²`, within [`SAG_SHARE`](crate::SAG_SHARE) of the
    /// typical body's thickness, and the turn of each body touching another within
    /// [`MAX_SUBSTEP_TURN`](crate::MAX_SUBSTEP_TURN). Default [`MAX_SUBSTEPS`].
    pub max_substeps: usize,
}

/// Default [`WorldSettings::max_substeps`]: 8, which brings 5 mm bodies at 60 Hz within
/// [`SAG_SHARE`](crate::SAG_SHARE). Worlds of bodies over 27 cm at 60 Hz, or over 10 cm at
/// 100 Hz, take one step as before.
pub const MAX_SUBSTEPS: usize = 8;

/// Largest [`WorldSettings::max_substeps`] a world takes.
pub const SUBSTEP_LIMIT: usize = 1000;

impl Default for WorldSettings {
    fn default() -> Self {
        Self {
            model: ContactModel::default(),
            solver: Solver::default(),
            contact: ContactSettings::default(),
            contact_margin: 0.005,
            feature_angle: 1f64.to_radians(),
            shock_propagation: true,
            sleeping: Sleeping::default(),
            max_substeps: MAX_SUBSTEPS,
        }
    }
}

impl WorldSettings {
    /// Checks every number is finite and in range.
    pub fn validate(&self) -> Result<(), WorldError> {
        let check = |field: &'static str, value: f64, ok: bool, range: &str| {
            if value.is_finite() && ok {
                Ok(())
            } else {
                Err(WorldError::InvalidSettings {
                    field,
                    reason: format!("must be {range}, got {value}"),
                })
            }
        };
        let c = &self.contact;
        check(
            "bias_rate",
            c.bias_rate,
            (0.0..=1.0).contains(&c.bias_rate),
            "in [0, 1]",
        )?;
        check("slop", c.slop, c.slop >= 0.0, "≥ 0")?;
        check(
            "max_depenetration_speed",
            c.max_depenetration_speed,
            c.max_depenetration_speed > 0.0,
            "> 0",
        )?;
        check(
            "max_velocity_bias",
            c.max_velocity_bias,
            c.max_velocity_bias >= 0.0,
            "≥ 0",
        )?;
        check(
            "restitution_threshold",
            c.restitution_threshold,
            c.restitution_threshold >= 0.0,
            "≥ 0",
        )?;
        check(
            "slip_threshold",
            c.slip_threshold,
            c.slip_threshold >= 0.0,
            "≥ 0",
        )?;
        check(
            "contact_margin",
            self.contact_margin,
            self.contact_margin >= 0.0,
            "≥ 0",
        )?;
        let angle = self.feature_angle;
        check(
            "feature_angle",
            angle,
            angle > 0.0 && angle < std::f64::consts::FRAC_PI_4,
            "in (0, π/4) rad",
        )?;
        let sleeping = &self.sleeping;
        check(
            "sleeping.linear_speed",
            sleeping.linear_speed,
            sleeping.linear_speed >= 0.0,
            "≥ 0",
        )?;
        check(
            "sleeping.angular_speed",
            sleeping.angular_speed,
            sleeping.angular_speed >= 0.0,
            "≥ 0",
        )?;
        check("sleeping.time", sleeping.time, sleeping.time >= 0.0, "≥ 0")?;
        if let TwistRadius::Grid { spacing } = c.twist_radius {
            check("twist_radius.spacing", spacing, spacing > 0.0, "> 0 m")?;
        }
        if !(1..=SUBSTEP_LIMIT).contains(&self.max_substeps) {
            return Err(WorldError::InvalidSettings {
                field: "max_substeps",
                reason: format!("must be 1 to {SUBSTEP_LIMIT}, got {}", self.max_substeps),
            });
        }
        if let Solver::Pgs(p) = &self.solver {
            if !(1..=MAX_ITERATIONS).contains(&p.iterations) {
                return Err(WorldError::InvalidSettings {
                    field: "iterations",
                    reason: format!("must be 1 to {MAX_ITERATIONS}, got {}", p.iterations),
                });
            }
            check(
                "relaxation",
                p.relaxation,
                p.relaxation > 0.0 && p.relaxation < 2.0,
                "in (0, 2)",
            )?;
            check("tolerance", p.tolerance, p.tolerance >= 0.0, "≥ 0")?;
        }
        Ok(())
    }
}
