//! Driving a world between steps: handles, poses and velocities set by hand, forces and
//! impulses, kinematic targets, removal, and the contacts' wrenches read back.
//!
//! Every call checks its body and its values and returns a [`WorldError`] rather than let a
//! non-finite number or a stale handle reach the solver. Forces, torques and kinematic targets
//! act over the next step only; impulses and velocities take effect at once.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use tatami_contact::grip::GripProjection;

use crate::body::BodyKind;
use crate::contact_set::rows_of;
use crate::{Body, BodyId, ContactWrench, POSITION_LIMIT, SPEED_LIMIT, World, WorldError};

impl World {
    /// The body with handle `id`, if it is still in the world.
    pub fn body_by_id(&self, id: BodyId) -> Option<&Body> {
        self.index_of(id).ok().map(|k| &self.bodies[k])
    }

    /// The position of body `id` in [`World::bodies`] (bodies keep the order they were added
    /// in, so a removal moves the later ones down by one).
    pub fn index_of(&self, id: BodyId) -> Result<usize, WorldError> {
        self.bodies
            .binary_search_by_key(&id, Body::id)
            .map_err(|_| WorldError::UnknownBody(id))
    }

    /// Moves body `id`'s origin (the shape's frame) to `position`, keeping its orientation.
    ///
    /// ```
    /// use tatami_world::{BodyDesc, Shape, World};
    /// let mut world = World::builder().build()?;
    /// let ball = world.add_body(BodyDesc::dynamic(Shape::sphere(0.5)))?;
    /// world.set_position(ball, [1.0, 2.0, 3.0])?;
    /// assert_eq!(world.body_by_id(ball).unwrap().position(), [1.0, 2.0, 3.0].into());
    /// assert!(world.set_position(ball, [f64::NAN, 0.0, 0.0]).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_position(
        &mut self,
        id: BodyId,
        position: impl Into<Point3<f64>>,
    ) -> Result<(), WorldError> {
        let position = position.into();
        let body = self.body_mut(id)?;
        check_vector(body, "position", &position.coords, POSITION_LIMIT)?;
        body.centre = position + body.rotation * body.com_offset();
        Ok(())
    }

    /// Turns body `id` to `rotation` about its origin (the shape's frame), which stays put.
    pub fn set_rotation(
        &mut self,
        id: BodyId,
        rotation: UnitQuaternion<f64>,
    ) -> Result<(), WorldError> {
        let body = self.body_mut(id)?;
        check_rotation(body, &rotation)?;
        let origin = body.position();
        body.rotation = rotation;
        body.centre = origin + rotation * body.com_offset();
        Ok(())
    }

    /// Sets the linear velocity of body `id`'s centre of mass (m/s). A kinematic body keeps it
    /// until told otherwise; a fixed body has none.
    pub fn set_velocity(
        &mut self,
        id: BodyId,
        velocity: impl Into<Vector3<f64>>,
    ) -> Result<(), WorldError> {
        let velocity = velocity.into();
        let body = self.movable(id, "have a velocity")?;
        check_vector(body, "velocity", &velocity, SPEED_LIMIT)?;
        body.linear_velocity = velocity;
        Ok(())
    }

    /// Sets body `id`'s angular velocity (rad/s, world axes).
    pub fn set_angular_velocity(
        &mut self,
        id: BodyId,
        angular_velocity: impl Into<Vector3<f64>>,
    ) -> Result<(), WorldError> {
        let angular_velocity = angular_velocity.into();
        let body = self.movable(id, "have a velocity")?;
        check_vector(body, "angular_velocity", &angular_velocity, SPEED_LIMIT)?;
        body.angular_velocity = angular_velocity;
        Ok(())
    }

    /// Sends kinematic body `id` to a pose (origin `position`, `rotation`) by the end of the
    /// next step: for that step its velocities are the ones that take it there, and dynamic
    /// bodies in its way are pushed by them. It then rests there until given another target or
    /// a velocity. Setting a target every step moves a body along a path.
    ///
    /// ```
    /// use tatami_world::{BodyDesc, Shape, World};
    /// use nalgebra::UnitQuaternion;
    /// let mut world = World::builder().build()?;
    /// let hand = world.add_body(BodyDesc::kinematic(Shape::sphere(0.1)))?;
    /// world.set_kinematic_target(hand, [0.0, 0.0, 0.02], UnitQuaternion::identity())?;
    /// world.step(0.01)?;
    /// let body = world.body_by_id(hand).unwrap();
    /// assert_eq!(body.position(), [0.0, 0.0, 0.02].into());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_kinematic_target(
        &mut self,
        id: BodyId,
        position: impl Into<Point3<f64>>,
        rotation: UnitQuaternion<f64>,
    ) -> Result<(), WorldError> {
        let position = position.into();
        let body = self.of_kind(id, BodyKind::Kinematic, "follow a target")?;
        check_vector(body, "position", &position.coords, POSITION_LIMIT)?;
        check_rotation(body, &rotation)?;
        body.target = Some((position + rotation * body.com_offset(), rotation));
        Ok(())
    }

    /// Applies `force` (N) at body `id`'s centre of mass over the next step; forces add up
    /// until the step.
    pub fn apply_force(
        &mut self,
        id: BodyId,
        force: impl Into<Vector3<f64>>,
    ) -> Result<(), WorldError> {
        let force = force.into();
        let body = self.of_kind(id, BodyKind::Dynamic, "take a force")?;
        check_vector(body, "force", &(body.force + force), f64::MAX)?;
        body.force += force;
        Ok(())
    }

    /// Applies `torque` (N m, world axes) to body `id` over the next step.
    pub fn apply_torque(
        &mut self,
        id: BodyId,
        torque: impl Into<Vector3<f64>>,
    ) -> Result<(), WorldError> {
        let torque = torque.into();
        let body = self.of_kind(id, BodyKind::Dynamic, "take a torque")?;
        check_vector(body, "torque", &(body.torque + torque), f64::MAX)?;
        body.torque += torque;
        Ok(())
    }

    /// Applies `force` (N) at the world point `point` of body `id` over the next step: the
    /// force at the centre of mass and its moment about it.
    pub fn apply_force_at_point(
        &mut self,
        id: BodyId,
        force: impl Into<Vector3<f64>>,
        point: impl Into<Point3<f64>>,
    ) -> Result<(), WorldError> {
        let (force, point) = (force.into(), point.into());
        let body = self.of_kind(id, BodyKind::Dynamic, "take a force")?;
        check_vector(body, "point", &point.coords, POSITION_LIMIT)?;
        let torque = body.torque + (point - body.centre).cross(&force);
        check_vector(body, "force", &(body.force + force), f64::MAX)?;
        check_vector(body, "torque", &torque, f64::MAX)?;
        body.force += force;
        body.torque = torque;
        Ok(())
    }

    /// Applies `impulse` (N s) at body `id`'s centre of mass now: its velocity changes by
    /// `impulse / m`.
    pub fn apply_impulse(
        &mut self,
        id: BodyId,
        impulse: impl Into<Vector3<f64>>,
    ) -> Result<(), WorldError> {
        let impulse = impulse.into();
        let body = self.of_kind(id, BodyKind::Dynamic, "take an impulse")?;
        let velocity = body.linear_velocity + impulse / body.mass();
        check_vector(body, "velocity after the impulse", &velocity, SPEED_LIMIT)?;
        body.linear_velocity = velocity;
        Ok(())
    }

    /// Applies `impulse` (N s) at the world point `point` of body `id` now: its velocity changes
    /// by `impulse / m` and its angular velocity by `I⁻¹ (r × impulse)`.
    pub fn apply_impulse_at_point(
        &mut self,
        id: BodyId,
        impulse: impl Into<Vector3<f64>>,
        point: impl Into<Point3<f64>>,
    ) -> Result<(), WorldError> {
        let (impulse, point) = (impulse.into(), point.into());
        let body = self.of_kind(id, BodyKind::Dynamic, "take an impulse")?;
        check_vector(body, "point", &point.coords, POSITION_LIMIT)?;
        let velocity = body.linear_velocity + impulse / body.mass();
        let spin = body.angular_velocity
            + body.solver_body().inv_inertia_world * (point - body.centre).cross(&impulse);
        check_vector(body, "velocity after the impulse", &velocity, SPEED_LIMIT)?;
        check_vector(
            body,
            "angular velocity after the impulse",
            &spin,
            SPEED_LIMIT,
        )?;
        body.linear_velocity = velocity;
        body.angular_velocity = spin;
        Ok(())
    }

    /// Removes body `id` and every contact it has; returns it. The bodies after it in
    /// [`World::bodies`] move down by one; handles stay valid.
    pub fn remove_body(&mut self, id: BodyId) -> Result<Body, WorldError> {
        let index = self.index_of(id)?;
        // What rested on it must fall.
        for contact in self.contact_set.contacts() {
            let (a, b) = (contact.body_a.0, contact.body_b.0);
            if a == index || b == index {
                self.bodies[a + b - index].asleep = false;
            }
        }
        self.geometry.remove(index);
        self.contact_set.remove_body(index);
        // The last problem's blocks keep naming the bodies that remain.
        let problem = &mut self.problem;
        if index < problem.bodies.len() {
            problem.bodies.remove(index);
        }
        for block in &mut problem.blocks {
            for body in [&mut block.body_a, &mut block.body_b] {
                if body.0 > index {
                    body.0 -= 1;
                }
            }
        }
        if index < self.pseudo_velocities.len() {
            self.pseudo_velocities.remove(index);
        }
        Ok(self.bodies.remove(index))
    }

    /// The force-sensor read-out: every contact's wrench over the last step (see
    /// [`ContactWrench`]), in the order of [`World::contacts`]. Empty before the first step.
    pub fn contact_wrenches(&self) -> impl Iterator<Item = ContactWrench> + '_ {
        let dt = self.last_dt;
        let count = if dt > 0.0 {
            self.contact_set.contacts().len()
        } else {
            0
        };
        (0..count).filter_map(move |k| {
            let (contact, blocks) = self.contact_set.get(k)?;
            let rows = rows_of(&self.problem, &blocks);
            let ids = [
                self.bodies.get(contact.body_a.0)?.id(),
                self.bodies.get(contact.body_b.0)?.id(),
            ];
            let press = (self.problem.blocks.get(blocks)?.iter())
                .find_map(|block| GripProjection::of(&block.projection))
                .map_or(0.0, |grip| grip.press);
            Some(ContactWrench::new(
                contact,
                (self.problem.rows.get(rows)?, press),
                dt,
                ids,
            ))
        })
    }

    /// Body `id`, woken: every call that changes a body goes through here, so a sleeping body
    /// (and its island, at the next step) wakes on any change.
    fn body_mut(&mut self, id: BodyId) -> Result<&mut Body, WorldError> {
        let index = self.index_of(id)?;
        let body = &mut self.bodies[index];
        body.wake();
        Ok(body)
    }

    /// Body `id` if it is of `kind`.
    fn of_kind(
        &mut self,
        id: BodyId,
        kind: BodyKind,
        action: &'static str,
    ) -> Result<&mut Body, WorldError> {
        let body = self.body_mut(id)?;
        if body.kind() == kind {
            Ok(body)
        } else {
            Err(wrong_kind(body, action))
        }
    }

    /// Body `id` unless it is fixed.
    fn movable(&mut self, id: BodyId, action: &'static str) -> Result<&mut Body, WorldError> {
        let body = self.body_mut(id)?;
        if body.is_fixed() {
            Err(wrong_kind(body, action))
        } else {
            Ok(body)
        }
    }
}

fn wrong_kind(body: &Body, action: &'static str) -> WorldError {
    WorldError::WrongKind {
        body: body.name().to_owned(),
        kind: body.kind().name(),
        action,
    }
}

fn invalid(body: &Body, field: &'static str, reason: String) -> WorldError {
    WorldError::InvalidBody {
        body: body.name().to_owned(),
        field,
        reason,
    }
}

/// `rotation` must be finite.
fn check_rotation(body: &Body, rotation: &UnitQuaternion<f64>) -> Result<(), WorldError> {
    if rotation.coords.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(invalid(body, "rotation", "must be finite".into()))
    }
}

/// `v` must be finite and at most `limit` in size.
fn check_vector(
    body: &Body,
    field: &'static str,
    v: &Vector3<f64>,
    limit: f64,
) -> Result<(), WorldError> {
    if !v.iter().all(|x| x.is_finite()) {
        return Err(invalid(body, field, format!("must be finite, got {v:?}")));
    }
    if v.norm() > limit {
        return Err(invalid(
            body,
            field,
            format!("must be at most {limit:e} in size"),
        ));
    }
    Ok(())
}
