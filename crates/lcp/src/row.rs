//! One constraint row: a Jacobian between bodies A and B, a target velocity and an impulse.

use nalgebra::Vector3;

use crate::{SolverBody, all_finite};

/// The row's Jacobian: `w = linear_a·v_A + angular_a·ω_A + linear_b·v_B + angular_b·ω_B`.
///
/// For a contact the B half is usually the negation of the A half at the same point, so `w` is
/// the relative velocity of A with respect to B along the row's direction.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jacobian {
    /// Coefficient of A's linear velocity.
    pub linear_a: Vector3<f64>,
    /// Coefficient of A's angular velocity.
    pub angular_a: Vector3<f64>,
    /// Coefficient of B's linear velocity.
    pub linear_b: Vector3<f64>,
    /// Coefficient of B's angular velocity.
    pub angular_b: Vector3<f64>,
}

impl Jacobian {
    /// `w = J v` for the bodies' current velocities.
    #[inline]
    pub fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f64 {
        self.velocity_of(
            [&a.linear_velocity, &a.angular_velocity],
            [&b.linear_velocity, &b.angular_velocity],
        )
    }

    /// `J M⁻¹ Jᵀ`: how fast the row's `w` changes per unit impulse on it (the inverse of its
    /// effective mass; 0 between bodies no impulse moves).
    ///
    /// ```
    /// use nalgebra::{Matrix3, Vector3};
    /// use tatami_lcp::{Jacobian, SolverBody};
    /// let mut a = SolverBody::fixed();
    /// a.inv_mass = 0.5;
    /// a.inv_inertia_world = Matrix3::identity() * 2.0;
    /// // Along z at 1 m beside A's centre: 1/m plus (r × n)ᵀ I⁻¹ (r × n).
    /// let j = Jacobian {
    ///     linear_a: Vector3::z(),
    ///     angular_a: Vector3::x().cross(&Vector3::z()),
    ///     ..Jacobian::default()
    /// };
    /// assert_eq!(j.inverse_mass(&a, &SolverBody::fixed()), 0.5 + 2.0);
    /// ```
    pub fn inverse_mass(&self, a: &SolverBody, b: &SolverBody) -> f64 {
        a.inv_mass * self.linear_a.norm_squared()
            + self.angular_a.dot(&(a.inv_inertia_world * self.angular_a))
            + b.inv_mass * self.linear_b.norm_squared()
            + self.angular_b.dot(&(b.inv_inertia_world * self.angular_b))
    }

    /// `w = J v` for A's and B's `[linear, angular]` velocities.
    #[inline]
    pub(crate) fn velocity_of(&self, a: [&Vector3<f64>; 2], b: [&Vector3<f64>; 2]) -> f64 {
        self.linear_a.dot(a[0])
            + self.angular_a.dot(a[1])
            + self.linear_b.dot(b[0])
            + self.angular_b.dot(b[1])
    }

    /// The sum of the twelve coefficients, `±∞` or NaN if any is not finite.
    #[inline]
    fn sum(&self) -> f64 {
        let sum = (self.linear_a + self.angular_a) + (self.linear_b + self.angular_b);
        sum.x + sum.y + sum.z
    }

    fn is_finite(&self) -> bool {
        all_finite(self.linear_a.as_slice())
            & all_finite(self.angular_a.as_slice())
            & all_finite(self.linear_b.as_slice())
            & all_finite(self.angular_b.as_slice())
    }
}

/// A constraint row of a block.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Row {
    /// Jacobian between the block's bodies A and B.
    pub jacobian: Jacobian,
    /// Velocity the row drives `w` to, m/s or rad/s: 0 for a resting contact, positive on a
    /// normal row to push out penetration (the bias) or for restitution.
    pub target: f64,
    /// Accumulated impulse `λ`, N s or N m s; written by the solvers, read for warm starting.
    pub impulse: f64,
}

impl Row {
    /// Every value finite. Rows are checked before every solve: a finite sum of the values
    /// proves it at one addition each (an infinity or a NaN among them makes the sum one); only
    /// a sum that is not finite, which finite values can also reach by overflow, is looked at
    /// value by value.
    #[inline]
    pub(crate) fn is_finite(&self) -> bool {
        (self.jacobian.sum() + self.target + self.impulse).is_finite()
            || (self.jacobian.is_finite() && self.target.is_finite() && self.impulse.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row whose fourteen values are `values`, in the order Jacobian (A linear, A angular,
    /// B linear, B angular), target, impulse.
    fn row(values: [f64; 14]) -> Row {
        let v = |k: usize| Vector3::new(values[k], values[k + 1], values[k + 2]);
        Row {
            jacobian: Jacobian {
                linear_a: v(0),
                angular_a: v(3),
                linear_b: v(6),
                angular_b: v(9),
            },
            target: values[12],
            impulse: values[13],
        }
    }

    #[test]
    fn a_row_is_finite_exactly_when_every_value_is() {
        let ordinary = [
            0.5, -2.0, 3.0, 0.0, 1e-300, -7.5, 1.0, 2.0, -3.0, 4.0, 5.0, -6.0, 0.1, 9.0,
        ];
        assert!(row(ordinary).is_finite());
        // Finite values whose sum overflows, to +∞ or, by the two signs, to NaN.
        assert!(row([f64::MAX; 14]).is_finite());
        let mut both = [f64::MAX; 14];
        both[13] = -f64::MAX;
        both[0] = -f64::MAX;
        assert!(row(both).is_finite());
        for slot in 0..14 {
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                for rest in [ordinary, [f64::MAX; 14], [-f64::MAX; 14]] {
                    let mut values = rest;
                    values[slot] = bad;
                    assert!(!row(values).is_finite(), "{bad} in slot {slot}");
                }
            }
        }
        // Infinities of both signs, whose sum is NaN.
        let mut opposite = ordinary;
        opposite[2] = f64::INFINITY;
        opposite[7] = f64::NEG_INFINITY;
        assert!(!row(opposite).is_finite());
    }
}
