//! Bodies as the solver sees them: inverse mass properties and a velocity twist.

use nalgebra::{Matrix3, Vector3};

use crate::all_finite;

/// Index of a body in [`Problem::bodies`](crate::Problem::bodies).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct BodyId(pub usize);

/// Inverse mass, inverse world inertia and velocity of one body. A fixed body has zero inverse
/// mass and inertia, so no impulse moves it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverBody {
    /// `1/m` in 1/kg; 0 for a fixed body.
    pub inv_mass: f64,
    /// `I⁻¹` in world axes, 1/(kg m²); zero for a fixed body.
    pub inv_inertia_world: Matrix3<f64>,
    /// Linear velocity of the centre of mass, m/s, world frame.
    pub linear_velocity: Vector3<f64>,
    /// Angular velocity, rad/s, world frame.
    pub angular_velocity: Vector3<f64>,
}

impl SolverBody {
    /// A body that no impulse moves.
    pub fn fixed() -> Self {
        Self {
            inv_mass: 0.0,
            inv_inertia_world: Matrix3::zeros(),
            linear_velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
        }
    }

    /// All mass properties and velocities are finite.
    pub fn is_finite(&self) -> bool {
        self.inv_mass.is_finite()
            & all_finite(self.inv_inertia_world.as_slice())
            & all_finite(self.linear_velocity.as_slice())
            & all_finite(self.angular_velocity.as_slice())
    }
}
