//! Projection of a point contact's three rows: normal, then friction along `t1`, `t2`.

use tatami_lcp::{LinearSet, Projection, RowBound};

use crate::FrictionCone;

/// Keeps `(λₙ, λ₁, λ₂)` in the friction cone: `λₙ ≥ 0`, tangential impulse bounded by `μ λₙ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointFriction {
    /// Friction coefficient chosen for this step (static or kinetic).
    pub coefficient: f64,
    /// Box or circular bound.
    pub cone: FrictionCone,
}

impl Projection for PointFriction {
    #[inline]
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        impulses[0] = impulses[0].max(0.0);
        let limit = self.coefficient * impulses[0];
        self.cone.clamp(&mut impulses[1..3], limit);
    }

    #[inline]
    fn tangent_pair(&self) -> Option<usize> {
        self.cone.tangent_pair(1)
    }

    /// The normal row; without it the cone holds no friction.
    #[inline]
    fn leading_normal_rows(&self) -> usize {
        1
    }

    /// The box cone as row bounds; the circular cone is not a product of row bounds.
    fn bound(&self, row: usize) -> Option<RowBound> {
        match (row, self.cone) {
            (0, _) => Some(RowBound::NonNegative),
            (1 | 2, FrictionCone::Box) => Some(RowBound::Friction {
                normal: 0,
                coefficient: self.coefficient,
            }),
            _ => None,
        }
    }

    /// `λₙ ≥ 0` and the cone ([`FrictionCone::add_to`]).
    fn linear_set(&self, rows: usize) -> Option<LinearSet> {
        let mut set = LinearSet::new(rows);
        let normal = set.generator(vec![(0, 1.0)]);
        self.cone.add_to(&mut set, 1, &[(normal, self.coefficient)]);
        Some(set)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_scales_the_tangential_impulse_onto_the_cone() {
        let mut p = PointFriction {
            coefficient: 0.5,
            cone: FrictionCone::Circle,
        };
        let mut impulses = [2.0, 3.0, 4.0];
        p.project(&mut impulses, 1);
        assert!((impulses[1].hypot(impulses[2]) - 1.0).abs() < 1e-12);
        assert!(
            (impulses[1] / impulses[2] - 0.75).abs() < 1e-12,
            "direction kept"
        );
    }

    #[test]
    fn box_clamps_each_axis_and_a_pulling_normal_to_zero() {
        let mut p = PointFriction {
            coefficient: 0.5,
            cone: FrictionCone::Box,
        };
        let mut impulses = [2.0, 3.0, -0.4];
        p.project(&mut impulses, 1);
        assert_eq!(impulses, [2.0, 1.0, -0.4]);
        let mut pulling = [-1.0, 3.0, -0.4];
        p.project(&mut pulling, 0);
        assert_eq!(pulling, [0.0, 0.0, 0.0]);
    }
}
