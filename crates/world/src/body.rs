//! Rigid bodies and their description for building a world.

use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3};
use tatami_lcp::SolverBody;

use crate::rotation::{PrincipalInertia, free_rotation};
use crate::{Shape, WorldError};

/// Density used when a dynamic body gives neither mass nor density: water, 1000 kg/m³.
pub const DEFAULT_DENSITY: f64 = 1000.0;

/// How far from the origin a body may be placed (m): the reach of [`crate::LENGTHS`], within
/// which contact geometry keeps its precision.
pub const POSITION_LIMIT: f64 = 1e5;

/// Fastest a body may be given (m/s, and rad/s for spin): far beyond anything a 0.01 s step
/// resolves (10 km/s moves a body 100 m a step), and small enough that impulses stay finite.
pub const SPEED_LIMIT: f64 = 1e4;

/// Masses a dynamic body may have (kg): with the solver's 12 to 15 sweeps a mass ratio beyond about
/// 1000 already strains it; these only keep its arithmetic finite (fixed bodies' masses are
/// nominal and not checked).
pub const MASSES: std::ops::RangeInclusive<f64> = 1e-6..=1e12;

/// Friction coefficient when a body gives none.
pub const DEFAULT_FRICTION: f64 = 0.5;

/// How a body's mass is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MassSpec {
    /// Total mass (kg).
    Mass(f64),
    /// Density (kg/m³); mass is density × volume.
    Density(f64),
}

/// Everything needed to add a body to a world (builder style).
///
/// ```
/// use tatami_world::{BodyDesc, Shape};
/// let cube = BodyDesc::dynamic(Shape::cuboid([2.0, 2.0, 2.0]))
///     .name("cube")
///     .mass(1.0)
///     .position([0.0, 0.0, 1.0])
///     .friction(0.5);
/// # let _ = cube;
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BodyDesc {
    /// Name used in errors and trajectories.
    pub name: Option<String>,
    /// Collision shape.
    pub shape: Shape,
    /// Fixed bodies never move.
    pub fixed: bool,
    /// Kinematic bodies move exactly at their velocities, whatever touches them: gravity and
    /// contacts do not act on them, and they push dynamic bodies as if their mass were infinite.
    pub kinematic: bool,
    /// Mass or density.
    pub mass: MassSpec,
    /// Principal moments (body axes) about the centre of mass; the solid shape's when `None`.
    pub inertia: Option<Vector3<f64>>,
    /// Position of the body's origin (the shape's frame).
    pub position: Point3<f64>,
    /// Orientation.
    pub rotation: UnitQuaternion<f64>,
    /// Linear velocity of the centre of mass.
    pub velocity: Vector3<f64>,
    /// Angular velocity (world axes).
    pub angular_velocity: Vector3<f64>,
    /// Static friction coefficient. A touching pair's coefficients are the means of its two
    /// bodies' (friction and restitution alike): a body of friction 0 against one of 0.6 slides
    /// on it at 0.3, and a frictionless contact needs both bodies at 0.
    pub static_friction: f64,
    /// Kinetic friction coefficient (a pair's is the mean of its bodies').
    pub kinetic_friction: f64,
    /// Restitution coefficient in `[0, 1]` (a pair's is the mean of its bodies').
    pub restitution: f64,
}

impl BodyDesc {
    /// A dynamic body of density [`DEFAULT_DENSITY`], at rest at the origin.
    pub fn dynamic(shape: Shape) -> Self {
        Self {
            name: None,
            shape,
            fixed: false,
            kinematic: false,
            mass: MassSpec::Density(DEFAULT_DENSITY),
            inertia: None,
            position: Point3::origin(),
            rotation: UnitQuaternion::identity(),
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
            static_friction: DEFAULT_FRICTION,
            kinetic_friction: DEFAULT_FRICTION,
            restitution: 0.0,
        }
    }

    /// A fixed body.
    pub fn fixed(shape: Shape) -> Self {
        Self {
            fixed: true,
            ..Self::dynamic(shape)
        }
    }

    /// A kinematic body: it moves at its `velocity` and `angular_velocity` (or as
    /// [`World::set_kinematic_target`](crate::World::set_kinematic_target) says), is moved by
    /// neither gravity nor contacts, and pushes dynamic bodies as if its mass were infinite. A
    /// step moves it by `velocity · dt` (to its target) exactly; when the step is split in
    /// substeps, a change of its velocity is spread over them, so that within the step it
    /// moves as if it changed speed steadily
    /// ([`WorldSettings::max_substeps`](crate::WorldSettings::max_substeps)).
    ///
    /// ```
    /// use tatami_world::{BodyDesc, Shape};
    /// let paddle = BodyDesc::kinematic(Shape::cuboid([0.2, 2.0, 1.0])).velocity([1.0, 0.0, 0.0]);
    /// assert!(paddle.kinematic && !paddle.fixed);
    /// ```
    pub fn kinematic(shape: Shape) -> Self {
        Self {
            kinematic: true,
            ..Self::dynamic(shape)
        }
    }

    /// Sets the name.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// Sets the total mass (kg).
    pub fn mass(mut self, mass: f64) -> Self {
        self.mass = MassSpec::Mass(mass);
        self
    }

    /// Sets the density (kg/m³).
    pub fn density(mut self, density: f64) -> Self {
        self.mass = MassSpec::Density(density);
        self
    }

    /// Overrides the principal moments of inertia (body axes, about the centre of mass).
    pub fn inertia(mut self, moments: [f64; 3]) -> Self {
        self.inertia = Some(moments.into());
        self
    }

    /// Sets the position of the body's origin.
    pub fn position(mut self, position: [f64; 3]) -> Self {
        self.position = position.into();
        self
    }

    /// Sets the orientation.
    pub fn rotation(mut self, rotation: UnitQuaternion<f64>) -> Self {
        self.rotation = rotation;
        self
    }

    /// Sets the linear velocity.
    pub fn velocity(mut self, velocity: [f64; 3]) -> Self {
        self.velocity = velocity.into();
        self
    }

    /// Sets the angular velocity (world axes).
    pub fn angular_velocity(mut self, angular_velocity: [f64; 3]) -> Self {
        self.angular_velocity = angular_velocity.into();
        self
    }

    /// Sets both friction coefficients; a touching pair's are the means of its two bodies'
    /// ([`BodyDesc::static_friction`]).
    pub fn friction(mut self, mu: f64) -> Self {
        self.static_friction = mu;
        self.kinetic_friction = mu;
        self
    }

    /// Sets the static and kinetic friction coefficients apart.
    pub fn friction_pair(mut self, static_friction: f64, kinetic_friction: f64) -> Self {
        self.static_friction = static_friction;
        self.kinetic_friction = kinetic_friction;
        self
    }

    /// Checks the description as [`World::add_body`](crate::World::add_body) would.
    pub fn validate(&self) -> Result<(), WorldError> {
        Body::new(self.clone(), BodyId(0), 0).map(drop)
    }

    /// Sets the restitution coefficient.
    pub fn restitution(mut self, restitution: f64) -> Self {
        self.restitution = restitution;
        self
    }
}

/// A body's state after a step, computed before it is committed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Motion {
    pub centre: Point3<f64>,
    pub rotation: UnitQuaternion<f64>,
    pub linear_velocity: Vector3<f64>,
    pub angular_velocity: Vector3<f64>,
}

impl Motion {
    /// Every component is finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.centre
            .iter()
            .chain(self.rotation.coords.iter())
            .chain(self.linear_velocity.iter())
            .chain(self.angular_velocity.iter())
            .all(|x| x.is_finite())
    }
}

/// A rigid body in a world. Its state is its centre of mass, orientation and velocities.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    name: String,
    shape: Shape,
    id: BodyId,
    kind: BodyKind,
    mass: f64,
    inertia_local: Matrix3<f64>,
    inv_inertia_local: Matrix3<f64>,
    /// The inertia's principal frame, for the free rotation ([`free_rotation`]).
    principal: PrincipalInertia,
    /// Centre of mass in the body frame.
    com_offset: Vector3<f64>,
    pub(crate) centre: Point3<f64>,
    pub(crate) rotation: UnitQuaternion<f64>,
    pub(crate) linear_velocity: Vector3<f64>,
    pub(crate) angular_velocity: Vector3<f64>,
    pub(crate) static_friction: f64,
    pub(crate) kinetic_friction: f64,
    pub(crate) restitution: f64,
    /// Force (N) and torque about the centre of mass (N m) applied for the next step.
    pub(crate) force: Vector3<f64>,
    pub(crate) torque: Vector3<f64>,
    /// A kinematic body's pose for the end of the next step: centre of mass and orientation.
    pub(crate) target: Option<(Point3<f64>, UnitQuaternion<f64>)>,
    /// The linear and angular velocity a kinematic body moved at over its last step (from its
    /// target, or as set), which a step split in substeps turns from ([`crate::substeps`]).
    pub(crate) drive: (Vector3<f64>, Vector3<f64>),
    /// Asleep (see [`crate::Sleeping`]): not solved, not moved, until woken.
    pub(crate) asleep: bool,
    /// How long (s) the body has been slower than the sleeping thresholds.
    pub(crate) rest_time: f64,
    /// The least width across the shape (m, [`crate::parry_bridge::Collider::thickness`]),
    /// which holds its pairs' margin and slop; set when the body joins a world.
    pub(crate) thickness: f64,
}

/// How a body moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BodyKind {
    /// Moved by gravity, forces and contacts.
    Dynamic,
    /// Never moves.
    Fixed,
    /// Moves as prescribed; pushes dynamic bodies as if its mass were infinite.
    Kinematic,
}

impl BodyKind {
    /// `dynamic`, `fixed` or `kinematic`, as in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Dynamic => "dynamic",
            Self::Fixed => "fixed",
            Self::Kinematic => "kinematic",
        }
    }
}

/// A body's handle in a [`World`](crate::World), returned by
/// [`World::add_body`](crate::World::add_body): it names the same body for the world's whole
/// life, through the removal of others, and is never given to another body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct BodyId(pub(crate) u64);

impl std::fmt::Display for BodyId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "body {}", self.0)
    }
}

impl Body {
    /// Validates `desc` and builds the body with handle `id`; `index` names unnamed bodies.
    pub(crate) fn new(desc: BodyDesc, id: BodyId, index: usize) -> Result<Self, WorldError> {
        let name = desc.name.clone().unwrap_or_else(|| format!("#{index}"));
        let fail = |field: &'static str, reason: String| WorldError::InvalidBody {
            body: name.clone(),
            field,
            reason,
        };
        let props = desc
            .shape
            .mass_properties()
            .map_err(|e| fail("shape", e.to_string()))?;
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        for (field, values) in [
            ("position", desc.position.coords.as_slice()),
            ("velocity", desc.velocity.as_slice()),
            ("angular_velocity", desc.angular_velocity.as_slice()),
            ("rotation", desc.rotation.coords.as_slice()),
        ] {
            if !finite(values) {
                return Err(fail(field, format!("must be finite, got {values:?}")));
            }
        }
        if desc.position.coords.norm() > POSITION_LIMIT {
            return Err(fail(
                "position",
                format!("must be within {POSITION_LIMIT:e} m of the origin"),
            ));
        }
        for (field, v) in [
            ("velocity", desc.velocity),
            ("angular_velocity", desc.angular_velocity),
        ] {
            if v.norm() > SPEED_LIMIT {
                return Err(fail(
                    field,
                    format!("must be at most {SPEED_LIMIT:e} in size"),
                ));
            }
        }
        for (field, mu) in [
            ("static_friction", desc.static_friction),
            ("kinetic_friction", desc.kinetic_friction),
        ] {
            if !(mu.is_finite() && mu >= 0.0) {
                return Err(fail(field, format!("must be finite and ≥ 0, got {mu}")));
            }
        }
        if desc.kinetic_friction > desc.static_friction {
            return Err(fail(
                "kinetic_friction",
                format!(
                    "must not exceed static_friction ({}), got {}",
                    desc.static_friction, desc.kinetic_friction
                ),
            ));
        }
        if desc.fixed && desc.kinematic {
            return Err(fail(
                "kinematic",
                "a body is fixed or kinematic, not both".into(),
            ));
        }
        let e = desc.restitution;
        if !(e.is_finite() && (0.0..=1.0).contains(&e)) {
            return Err(fail("restitution", format!("must be in [0, 1], got {e}")));
        }
        let (field, value, mass) = match desc.mass {
            MassSpec::Mass(m) => ("mass", m, m),
            MassSpec::Density(rho) => ("density", rho, rho * props.volume),
        };
        if !(value.is_finite() && value > 0.0) {
            return Err(fail(field, format!("must be finite and > 0, got {value}")));
        }
        if !desc.fixed && !desc.kinematic && !MASSES.contains(&mass) {
            return Err(fail(
                field,
                format!(
                    "gives a mass of {mass:e} kg; a dynamic body's must be from {:e} to {:e} kg",
                    MASSES.start(),
                    MASSES.end()
                ),
            ));
        }
        let inertia_local = match desc.inertia {
            None => props.unit_inertia * mass,
            Some(moments) => {
                if !moments.iter().all(|i| i.is_finite() && *i > 0.0) {
                    return Err(fail(
                        "inertia",
                        format!("moments must be finite and > 0, got {moments:?}"),
                    ));
                }
                Matrix3::from_diagonal(&moments)
            }
        };
        let inv_inertia_local = inertia_local
            .try_inverse()
            .ok_or_else(|| fail("inertia", "the inertia tensor is singular".into()))?;
        let com_offset = props.centre_of_mass.coords;
        let (linear_velocity, angular_velocity) = if desc.fixed {
            (Vector3::zeros(), Vector3::zeros())
        } else {
            (desc.velocity, desc.angular_velocity)
        };
        let kind = match (desc.fixed, desc.kinematic) {
            (true, _) => BodyKind::Fixed,
            (false, true) => BodyKind::Kinematic,
            (false, false) => BodyKind::Dynamic,
        };
        Ok(Self {
            name,
            shape: desc.shape,
            id,
            kind,
            mass,
            inertia_local,
            inv_inertia_local,
            principal: PrincipalInertia::of(&inertia_local),
            com_offset,
            centre: desc.position + desc.rotation * com_offset,
            rotation: desc.rotation,
            linear_velocity,
            angular_velocity,
            static_friction: desc.static_friction,
            kinetic_friction: desc.kinetic_friction,
            restitution: desc.restitution,
            force: Vector3::zeros(),
            torque: Vector3::zeros(),
            target: None,
            drive: (Vector3::zeros(), Vector3::zeros()),
            asleep: false,
            rest_time: 0.0,
            thickness: f64::INFINITY,
        })
    }

    /// The body's handle in its world.
    pub fn id(&self) -> BodyId {
        self.id
    }

    /// How the body moves.
    pub fn kind(&self) -> BodyKind {
        self.kind
    }

    /// Whether gravity, forces and contacts move the body.
    pub fn is_dynamic(&self) -> bool {
        self.kind == BodyKind::Dynamic
    }

    /// Whether the body moves as prescribed.
    pub fn is_kinematic(&self) -> bool {
        self.kind == BodyKind::Kinematic
    }

    /// Name (from the description, or `#index`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Collision shape.
    pub fn shape(&self) -> &Shape {
        &self.shape
    }

    /// Whether the body is asleep: at rest, skipped by the step until something wakes it (only
    /// with [`Sleeping`](crate::Sleeping) on).
    pub fn is_asleep(&self) -> bool {
        self.asleep
    }

    pub(crate) fn wake(&mut self) {
        self.asleep = false;
        self.rest_time = 0.0;
    }

    pub(crate) fn sleep(&mut self) {
        self.asleep = true;
        self.linear_velocity = Vector3::zeros();
        self.angular_velocity = Vector3::zeros();
    }

    /// A kinematic body that will move this step (a target or a velocity).
    pub(crate) fn moves(&self) -> bool {
        self.target.is_some()
            || self.linear_velocity != Vector3::zeros()
            || self.angular_velocity != Vector3::zeros()
    }

    /// Whether the body is fixed.
    pub fn is_fixed(&self) -> bool {
        self.kind == BodyKind::Fixed
    }

    /// Mass (kg); a fixed or kinematic body reports its nominal mass, which contacts ignore.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Position of the body's origin (the shape's frame).
    pub fn position(&self) -> Point3<f64> {
        self.centre - self.rotation * self.com_offset
    }

    /// Centre of mass in the body frame.
    pub(crate) fn com_offset(&self) -> Vector3<f64> {
        self.com_offset
    }

    /// Centre of mass (world).
    pub fn centre_of_mass(&self) -> Point3<f64> {
        self.centre
    }

    /// Orientation.
    pub fn rotation(&self) -> UnitQuaternion<f64> {
        self.rotation
    }

    /// Linear velocity of the centre of mass.
    pub fn linear_velocity(&self) -> Vector3<f64> {
        self.linear_velocity
    }

    /// Angular velocity (world axes).
    pub fn angular_velocity(&self) -> Vector3<f64> {
        self.angular_velocity
    }

    /// The angular velocity that swings the points a contact holds on the body (rad/s, world
    /// axes), for the rows' bends ([`tatami_contact::Turns`]): a box's or a hull's, whose
    /// contacts sit on its vertices, edges and faces; none of a ball's or a cylinder's, whose
    /// contact on its curved side or rim runs over the surface as it rolls or wobbles, so
    /// that the point touching is not the material point that swings (bent by its turn, a
    /// cylinder wobbling on its rim sank 3 mm into the floor).
    pub(crate) fn material_spin(&self) -> Vector3<f64> {
        match self.shape() {
            Shape::Box { .. } | Shape::Convex { .. } => self.angular_velocity,
            Shape::Sphere { .. } | Shape::Cylinder { .. } => Vector3::zeros(),
        }
    }

    /// The part of the angular velocity that turns the body's shape (rad/s, world axes): all
    /// of it but a ball's, which turns into itself, and a cylinder's about its own axis. A
    /// rolling ball's or wheel's contact stays under its centre while its material points
    /// swing round, so the substeps ([`crate::substeps`]) do not count that turn.
    pub(crate) fn shape_spin(&self) -> Vector3<f64> {
        let spin = self.angular_velocity;
        match self.shape() {
            Shape::Sphere { .. } => Vector3::zeros(),
            Shape::Cylinder { .. } => {
                let axis = self.rotation * Vector3::z();
                spin - axis * spin.dot(&axis)
            }
            Shape::Box { .. } | Shape::Convex { .. } => spin,
        }
    }

    /// Velocity of the body's point at `p` (world).
    pub(crate) fn velocity_at(&self, p: &Point3<f64>) -> Vector3<f64> {
        self.linear_velocity + self.angular_velocity.cross(&(p - self.centre))
    }

    /// The moment `r × n` about the centre of mass of a unit impulse along the unit `normal`
    /// at `p` (world). A ball's impulses along a normal of its surface act on the line through
    /// its centre, wherever the point stands along the contact: a ball's arm is taken from its
    /// centre.
    pub(crate) fn normal_moment(&self, p: &Point3<f64>, normal: &Vector3<f64>) -> Vector3<f64> {
        let arm = match self.shape {
            Shape::Sphere { .. } => self.position() - self.centre,
            _ => p - self.centre,
        };
        arm.cross(normal)
    }

    /// The body-frame inertia tensor, its inverse and its principal frame.
    fn inertia(&self) -> (&Matrix3<f64>, &Matrix3<f64>, &PrincipalInertia) {
        (
            &self.inertia_local,
            &self.inv_inertia_local,
            &self.principal,
        )
    }

    /// Inertia tensor about the centre of mass, world axes.
    pub fn inertia_world(&self) -> Matrix3<f64> {
        let r = self.rotation.to_rotation_matrix();
        r.matrix() * self.inertia_local * r.matrix().transpose()
    }

    /// Kinetic energy, translational plus rotational (J).
    pub fn kinetic_energy(&self) -> f64 {
        self.kinetic_energy_at(
            &self.inertia_world(),
            &self.linear_velocity,
            &self.angular_velocity,
        )
    }

    /// The kinetic energy the body would have at these velocities, in its current pose, whose
    /// world inertia is `inertia_world` (J).
    pub(crate) fn kinetic_energy_at(
        &self,
        inertia_world: &Matrix3<f64>,
        linear: &Vector3<f64>,
        angular: &Vector3<f64>,
    ) -> f64 {
        0.5 * self.mass * linear.norm_squared() + 0.5 * angular.dot(&(inertia_world * angular))
    }

    /// Where the body goes over `dt` with the solved velocities: the centre of mass along the
    /// linear velocity, the orientation and angular velocity by the free-rotation step (see
    /// [`crate::rotation`]), which keeps the angular momentum. A position `correction`'s
    /// pseudo-velocities move the centre and turn the body on top, leaving its velocities alone.
    /// A kinematic body ignores both: it moves to its target, or at its own velocities.
    pub(crate) fn motion(
        &self,
        solved: &SolverBody,
        correction: Option<&SolverBody>,
        dt: f64,
    ) -> Motion {
        if self.kind == BodyKind::Kinematic {
            // Exactly where a target sent it, then at rest until told otherwise.
            if let Some((centre, rotation)) = self.target {
                return Motion {
                    centre,
                    rotation,
                    linear_velocity: Vector3::zeros(),
                    angular_velocity: Vector3::zeros(),
                };
            }
            // Otherwise as prescribed: a constant twist over the step.
            let centre = self.centre + self.linear_velocity * dt;
            let mut rotation =
                UnitQuaternion::from_scaled_axis(self.angular_velocity * dt) * self.rotation;
            rotation.renormalize();
            return Motion {
                centre,
                rotation,
                linear_velocity: self.linear_velocity,
                angular_velocity: self.angular_velocity,
            };
        }
        let mut centre = self.centre + solved.linear_velocity * dt;
        let (mut rotation, angular_velocity) =
            free_rotation(&self.rotation, &solved.angular_velocity, self.inertia(), dt);
        if let Some(pseudo) = correction {
            centre += pseudo.linear_velocity * dt;
            rotation = UnitQuaternion::from_scaled_axis(pseudo.angular_velocity * dt) * rotation;
            rotation.renormalize();
        }
        Motion {
            centre,
            rotation,
            linear_velocity: solved.linear_velocity,
            angular_velocity,
        }
    }

    /// Its state now, as a [`Motion`].
    pub(crate) fn motion_now(&self) -> Motion {
        Motion {
            centre: self.centre,
            rotation: self.rotation,
            linear_velocity: self.linear_velocity,
            angular_velocity: self.angular_velocity,
        }
    }

    /// Takes the state `motion`.
    pub(crate) fn set_motion(&mut self, motion: &Motion) {
        self.centre = motion.centre;
        self.rotation = motion.rotation;
        self.linear_velocity = motion.linear_velocity;
        self.angular_velocity = motion.angular_velocity;
    }

    /// The linear and angular velocity that take a kinematic body from its pose to its
    /// target in `dt`, if it has one.
    pub(crate) fn velocity_to_target(&self, dt: f64) -> Option<(Vector3<f64>, Vector3<f64>)> {
        self.target.map(|(centre, rotation)| {
            (
                (centre - self.centre) / dt,
                (rotation * self.rotation.inverse()).scaled_axis() / dt,
            )
        })
    }

    /// The body as the solver sees it (fixed and kinematic bodies have zero inverse mass and
    /// inertia; a kinematic body keeps its velocity).
    pub(crate) fn solver_body(&self) -> SolverBody {
        match self.kind {
            BodyKind::Fixed => return SolverBody::fixed(),
            BodyKind::Kinematic => {
                return SolverBody {
                    linear_velocity: self.linear_velocity,
                    angular_velocity: self.angular_velocity,
                    ..SolverBody::fixed()
                };
            }
            BodyKind::Dynamic => {}
        }
        let r = self.rotation.to_rotation_matrix();
        SolverBody {
            inv_mass: 1.0 / self.mass,
            inv_inertia_world: r.matrix() * self.inv_inertia_local * r.matrix().transpose(),
            linear_velocity: self.linear_velocity,
            angular_velocity: self.angular_velocity,
        }
    }
}
