//! Building a world step by step.

use nalgebra::Vector3;
use tatami_contact::ContactModel;

use crate::{BodyDesc, World, WorldError, WorldSettings};

/// Standard gravity used by default (m/s², along −z), as in the paper.
pub const DEFAULT_GRAVITY: f64 = 9.8;

/// Strongest gravity a world takes (m/s²), a thousand g: beyond it one step's impulses leave
/// the range the bounds on speeds and masses keep finite (gravity of 1e308 gave NaN states).
pub const GRAVITY_LIMIT: f64 = 1e4;

/// Collects gravity, settings and bodies; [`WorldBuilder::build`] validates them all.
#[derive(Debug, Clone)]
pub struct WorldBuilder {
    gravity: Vector3<f64>,
    settings: WorldSettings,
    bodies: Vec<BodyDesc>,
}

impl Default for WorldBuilder {
    fn default() -> Self {
        Self {
            gravity: Vector3::new(0.0, 0.0, -DEFAULT_GRAVITY),
            settings: WorldSettings::default(),
            bodies: Vec::new(),
        }
    }
}

impl WorldBuilder {
    /// Sets gravity (m/s²).
    pub fn gravity(mut self, gravity: [f64; 3]) -> Self {
        self.gravity = gravity.into();
        self
    }

    /// Sets all settings.
    pub fn settings(mut self, settings: WorldSettings) -> Self {
        self.settings = settings;
        self
    }

    /// Sets the contact model.
    pub fn model(mut self, model: ContactModel) -> Self {
        self.settings.model = model;
        self
    }

    /// Adds a body.
    pub fn body(mut self, desc: BodyDesc) -> Self {
        self.bodies.push(desc);
        self
    }

    /// The world, or the first invalid setting or body.
    pub fn build(self) -> Result<World, WorldError> {
        if !(self.gravity.iter().all(|g| g.is_finite()) && self.gravity.norm() <= GRAVITY_LIMIT) {
            return Err(WorldError::InvalidSettings {
                field: "gravity",
                reason: format!(
                    "must be finite and at most {GRAVITY_LIMIT:e} m/s² in size, got {:?}",
                    self.gravity.as_slice()
                ),
            });
        }
        self.settings.validate()?;
        let mut world = World::empty(self.gravity, self.settings);
        for desc in self.bodies {
            world.add_body(desc)?;
        }
        Ok(world)
    }
}
