//! A Tatami scene file built in Rapier, for the side-by-side figures: the same bodies (boxes,
//! unrotated), masses, friction and gravity, Rapier's default integration parameters with the
//! scene's time step, sleeping off. One type per Rapier build (the crates differ only in
//! `Real`): [`RapierF64`] here, and any other build through [`rapier_scene!`](macro@crate::rapier_scene).
//! Used by the `holding_comparison` bench and the holding experiment of `cargo xtask`.

/// Defines `$name`, the scene of a Tatami [`Scene`](tatami_world::scene::Scene) in the Rapier crate `$rapier` of scalar
/// `$real`, with `new`, `step` and `positions` (the bodies' centres, in the scene's order).
#[macro_export]
macro_rules! rapier_scene {
    ($(#[$doc:meta])* $name:ident, $rapier:ident, $real:ty) => {
        $(#[$doc])*
        pub struct $name {
            bodies: $rapier::prelude::RigidBodySet,
            colliders: $rapier::prelude::ColliderSet,
            pipeline: $rapier::prelude::PhysicsPipeline,
            islands: $rapier::prelude::IslandManager,
            broad_phase: $rapier::prelude::BroadPhaseBvh,
            narrow_phase: $rapier::prelude::NarrowPhase,
            impulse_joints: $rapier::prelude::ImpulseJointSet,
            multibody_joints: $rapier::prelude::MultibodyJointSet,
            soft_bodies: $rapier::prelude::SoftBodySet,
            ccd: $rapier::prelude::CCDSolver,
            parameters: $rapier::prelude::IntegrationParameters,
            gravity: $rapier::prelude::Vector,
            handles: Vec<$rapier::prelude::RigidBodyHandle>,
        }

        impl $name {
            /// Builds `scene`; an error names what it cannot build (shapes other than boxes,
            /// rotated bodies).
            pub fn new(scene: &tatami_world::scene::Scene) -> Result<Self, String> {
                use $rapier::prelude::*;
                let mut bodies = RigidBodySet::new();
                let mut colliders = ColliderSet::new();
                let mut handles = Vec::new();
                for desc in &scene.bodies {
                    let tatami_world::Shape::Box { half_extents } = desc.shape else {
                        return Err("only boxes are built in Rapier here".to_owned());
                    };
                    if desc.rotation.angle() != 0.0 {
                        return Err("only unrotated bodies are built in Rapier here".to_owned());
                    }
                    let p = desc.position;
                    let translation = Vector::new(p.x as $real, p.y as $real, p.z as $real);
                    let body = if desc.fixed {
                        RigidBodyBuilder::fixed()
                    } else {
                        RigidBodyBuilder::dynamic().can_sleep(false)
                    };
                    let handle = bodies.insert(body.translation(translation));
                    let volume = 8.0 * half_extents.x * half_extents.y * half_extents.z;
                    let density = match desc.mass {
                        tatami_world::MassSpec::Mass(m) => m / volume,
                        tatami_world::MassSpec::Density(rho) => rho,
                    };
                    colliders.insert_with_parent(
                        ColliderBuilder::cuboid(
                            half_extents.x as $real,
                            half_extents.y as $real,
                            half_extents.z as $real,
                        )
                        .density(density as $real)
                        .friction(desc.static_friction as $real),
                        handle,
                        &mut bodies,
                    );
                    handles.push(handle);
                }
                let g = scene.gravity;
                Ok(Self {
                    bodies,
                    colliders,
                    pipeline: PhysicsPipeline::new(),
                    islands: IslandManager::new(),
                    broad_phase: BroadPhaseBvh::new(),
                    narrow_phase: NarrowPhase::new(),
                    impulse_joints: ImpulseJointSet::new(),
                    multibody_joints: MultibodyJointSet::new(),
                    soft_bodies: SoftBodySet::new(),
                    ccd: CCDSolver::new(),
                    parameters: IntegrationParameters {
                        dt: scene.dt as $real,
                        ..IntegrationParameters::default()
                    },
                    gravity: Vector::new(g.x as $real, g.y as $real, g.z as $real),
                    handles,
                })
            }

            /// One step of the scene's `dt`.
            pub fn step(&mut self) {
                self.pipeline.step(
                    self.gravity,
                    &self.parameters,
                    &mut self.islands,
                    &mut self.broad_phase,
                    &mut self.narrow_phase,
                    &mut self.bodies,
                    &mut self.colliders,
                    &mut self.impulse_joints,
                    &mut self.multibody_joints,
                    &mut self.soft_bodies,
                    &mut self.ccd,
                    &(),
                    &(),
                );
            }

            /// The bodies' centres, in the scene's order.
            pub fn positions(&self) -> Vec<[f64; 3]> {
                self.handles
                    .iter()
                    .map(|&h| {
                        let t = self.bodies[h].translation();
                        [t.x as f64, t.y as f64, t.z as f64]
                    })
                    .collect()
            }
        }
    };
}

rapier_scene!(
    /// A scene in rapier3d-f64.
    RapierF64,
    rapier3d_f64,
    f64
);
