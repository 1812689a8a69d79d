//! The patch model (Rapier ≥ 0.29, Jolt, Box3D): a normal row per support vertex, and friction
//! as two tangent rows at the friction centre `c` (the vertices' average) plus one twist row,
//! bounded by the vertices' total normal impulse: `|f_t| ≤ μ Σ λᵢ`, `|τ| ≤ μ Σ dᵢ λᵢ` with
//! `dᵢ = |vᵢ − c|`. One block of `k + 3` rows.

use nalgebra::Point2;
use tatami_geometry::PolygonKind;
use tatami_lcp::{Block, LinearSet, Projection, Row, RowBound};

use crate::jacobian::{
    Witness, angular_jacobian, block_friction_motion, point_jacobian, point_motion, twist_rate,
};
use crate::target::normal_target;
use crate::turns::{bent, friction_bend};
use crate::vertex;
use crate::{Contact, ContactProjection, ContactRows, ContactSettings, FrictionCone, Turns};

/// The projection of a patch block: rows `λ₁…λₖ` (normals), then `f1, f2, τ`.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchProjection {
    /// Distance of each vertex from the friction centre (m).
    pub distances: Vec<f64>,
    /// Force friction coefficient for this step.
    pub friction: f64,
    /// Twist friction coefficient for this step.
    pub twist_friction: f64,
    /// Box or circular friction bound.
    pub cone: FrictionCone,
}

impl Projection for PatchProjection {
    fn project(&mut self, impulses: &mut [f64], _changed: usize) {
        let k = self.distances.len();
        let (normals, friction) = impulses.split_at_mut(k);
        let mut total = 0.0;
        let mut moment = 0.0;
        for (lambda, d) in normals.iter_mut().zip(&self.distances) {
            *lambda = lambda.max(0.0);
            total += *lambda;
            moment += d * *lambda;
        }
        self.cone.clamp(&mut friction[..2], self.friction * total);
        let twist = self.twist_friction * moment;
        friction[2] = friction[2].max(-twist).min(twist);
    }

    fn tangent_pair(&self) -> Option<usize> {
        self.cone.tangent_pair(self.distances.len())
    }

    /// The vertices' normal rows; friction and twist are bounded by their sum.
    fn leading_normal_rows(&self) -> usize {
        self.distances.len()
    }

    /// The normal rows are plain bounds; the friction rows are bounded by a sum of normals, which
    /// is not a product of row bounds (see [`Projection::linear_set`]).
    fn bound(&self, row: usize) -> Option<RowBound> {
        (row < self.distances.len()).then_some(RowBound::NonNegative)
    }

    /// A generator per normal row; friction earns `μ` from each, twist `μ_t dᵢ`.
    fn linear_set(&self, rows: usize) -> Option<LinearSet> {
        let k = self.distances.len();
        let mut set = LinearSet::new(rows);
        let normals: Vec<usize> = (0..k).map(|i| set.generator(vec![(i, 1.0)])).collect();
        let earn: Vec<(usize, f64)> = normals.iter().map(|&v| (v, self.friction)).collect();
        self.cone.add_to(&mut set, k, &earn);
        let twist = normals
            .iter()
            .zip(&self.distances)
            .map(|(&v, d)| (v, self.twist_friction * d))
            .collect();
        set.symmetric(k + 2, twist);
        Some(set)
    }
}

/// Appends the patch block, then the vertex model's block for each landing point
/// ([`vertex::build_landing`]: as under the face model, a cylinder on one rim point has the
/// rim beside it held), and each row's penetration bias to `out`. The contact must be
/// validated.
pub(crate) fn build(
    contact: &Contact,
    (dt, turns): (f64, &Turns),
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) {
    let frame = &contact.frame;
    let vertices = contact.support.vertices();
    let centre = friction_centre(contact);
    let start = out.rows.len();
    for (vertex, &depth) in vertices.iter().zip(&contact.depths) {
        let witness = Witness::at(contact, &frame.to_world(vertex), depth);
        let (normal_speed, _) = point_motion(contact, out.bodies, &witness);
        let target = normal_target(
            depth,
            normal_speed,
            contact.bounce_speed,
            contact.material.restitution,
            dt,
            settings,
        );
        let bend = turns.bend_at(contact, &witness, (depth, normal_speed), settings);
        out.rows.push(Row {
            jacobian: point_jacobian(contact, &witness, &frame.normal),
            target: bent(target.velocity, &frame.normal, &bend, dt),
            impulse: 0.0,
        });
        out.biases.push(target.bias);
    }
    out.biases.extend([0.0; 3]);
    let c = Witness::at(contact, &frame.to_world(&centre), contact.depth());
    // A face on a face keeps its material points together while they stick (its weld bends
    // its friction rows: `crate::turns`); an edge may roll.
    let (normal_speed, slip, weld) =
        block_friction_motion(contact, out.bodies, &c, dt, settings.slip_threshold);
    let friction_bend = friction_bend(
        contact.support.kind() == PolygonKind::Polygon,
        turns.bend_at(contact, &c, (contact.depth(), normal_speed), settings),
    );
    let distances: Vec<f64> = vertices.iter().map(|v| (v - centre).norm()).collect();
    let mean_distance = distances.iter().sum::<f64>() / distances.len() as f64;
    let twist_rate = twist_rate(contact, out.bodies);
    let friction = [frame.tangent1, frame.tangent2].map(|direction| {
        (
            point_jacobian(contact, &c, &direction),
            bent(weld.dot(&direction), &direction, &friction_bend, dt),
        )
    });
    for (jacobian, target) in friction
        .into_iter()
        .chain([(angular_jacobian(&frame.normal), 0.0)])
    {
        out.rows.push(Row {
            jacobian,
            target,
            impulse: 0.0,
        });
    }
    let material = &contact.material;
    out.blocks.push(Block {
        body_a: contact.body_a,
        body_b: contact.body_b,
        rows: start..out.rows.len(),
        projection: ContactProjection::Patch(PatchProjection {
            friction: material.friction(slip, settings.slip_threshold),
            twist_friction: material.friction(twist_rate * mean_distance, settings.slip_threshold),
            distances,
            cone: settings.friction_cone,
        }),
    });
    let landing = contact.landing.iter().map(|l| (&l.point, &l.depth));
    vertex::build_landing(contact, landing, (dt, turns), settings, out);
}

/// The friction centre of a patch: the average of the support vertices (plane coordinates).
pub fn friction_centre(contact: &Contact) -> Point2<f64> {
    let vertices = contact.support.vertices();
    Point2::from(
        vertices
            .iter()
            .map(|v| v.coords)
            .sum::<nalgebra::Vector2<f64>>()
            / vertices.len() as f64,
    )
}
