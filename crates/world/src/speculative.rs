//! Speculative contacts: a pair's margin grown by how far its bodies may close in the step.
//!
//! Collision runs on the poses at the start of a step, so a contact is found only once the
//! bodies are within the margin. A cube falling at 4.4 m/s (dropped from 1 m) travels 73 mm a
//! step at 60 Hz, and with a 5 mm margin its corner met the floor only after it had sunk up to
//! that far: 50 mm in the median of eight drops (rapier3d-f64, whose contacts are speculative
//! within a fixed 2 cm, 21 mm). With each pair's margin grown by the distance its bodies'
//! points may close in the step — their centres' relative displacement `|v_A − v_B| dt` and
//! each body's turn `|ω| dt` times its reach — the contact is found a step ahead whatever the
//! speed, and its gap becomes a target the normal row may close in the step and no more (as
//! the speculative contacts of Box2D v3 and Jolt do, and Rapier's soft CCD). The pair's
//! feature angle grows by its turn in the step too, so a face that an edge's impact swings
//! down is found as a face, its far corners landing blocks that stop them at the surface; and
//! under the face model a polyhedron's vertices within the pair's closing distance of its
//! touching feature become landing points, where the turn an impact gives it within the step
//! would swing them down (a cube hitting the floor corner first at 13.8 m/s spun at 7.5 rad/s
//! and drove its next corner 93 mm into the floor in that step), as do a cylinder's rim points
//! every 45° unless it touches along its side, where it rolls (a cylinder thrown rim first at
//! a wall at 60 m/s swung its far rim 0.31 m into it without them, and went through). A pair
//! with a cylinder keeps its feature angle ([`crate::collision`] says why).
//!
//! A contact found only beyond the plain margin stands if a support point closes its gap in
//! the step and the bodies' shapes, cast along their velocities, meet within the step: the
//! contact plane of an edge a ball flies past would otherwise stop the ball (ghost
//! collisions). A dynamic body may be stopped within the step by its other contacts
//! ([`Travel::held`]), so both tests are also made with it stopped along the normal: a box
//! falling just above a box that lands closes on it at its own speed, though not at the
//! pair's. Bodies at rest keep the plain margin, so a resting pile gets no more contacts;
//! a bouncing pair is landed first and bounced on the next step ([`crate::impact`]). Drops now
//! stop within the slop (medians of 0–2 mm from 1 to 10 m, none deeper than 5 mm); the 1000-cube
//! pile's deepest overlap in flight went from 815 to 171 mm (Rapier 257 mm), its step 0–5%
//! longer.

use nalgebra::Vector3;

use crate::body::Body;

/// How far a body's points may move in the coming step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Travel {
    /// The centre of mass's displacement at its current velocity, `v dt` (m).
    pub shift: Vector3<f64>,
    /// Its turn at its current angular velocity, `ω dt` (rad, as a rotation vector).
    pub spin: Vector3<f64>,
    /// How far that turn may move a point of its shape, `|ω| dt · reach` (m).
    pub turn: f64,
    /// Whether the body may be stopped within the step by its other contacts: a dynamic body.
    pub held: bool,
}

impl Travel {
    /// `body`'s travel in a step of `dt`, its shape reaching `reach` from its centre of mass.
    pub(crate) fn of(body: &Body, reach: f64, dt: f64) -> Self {
        Self {
            held: body.is_dynamic(),
            ..Self::moving(&body.linear_velocity(), &body.angular_velocity(), reach, dt)
        }
    }

    /// The travel in a step of `dt` of a body moving at `velocity` and turning at
    /// `angular_velocity`, its shape reaching `reach` from its centre of mass.
    pub(crate) fn moving(
        velocity: &Vector3<f64>,
        angular_velocity: &Vector3<f64>,
        reach: f64,
        dt: f64,
    ) -> Self {
        let spin = angular_velocity * dt;
        Self {
            shift: velocity * dt,
            spin,
            turn: spin.norm() * reach,
            held: false,
        }
    }

    /// How far any of this body's points may move: what its bounding box grows by.
    pub(crate) fn farthest(&self) -> f64 {
        self.shift.norm() + self.turn
    }

    /// How far the points of two bodies with these travels may close on each other (m): the
    /// pair's margin grows by this. One [`held`](Self::held) may be stopped within the step,
    /// and the other then closes on it at its own shift: two boxes falling together close on
    /// each other when the lower one lands.
    pub(crate) fn closing(&self, other: &Travel) -> f64 {
        let alone = |held: bool, shift: &Vector3<f64>| if held { shift.norm() } else { 0.0 };
        let shift = (self.shift - other.shift)
            .norm()
            .max(alone(other.held, &self.shift))
            .max(alone(self.held, &other.shift));
        shift + self.turn + other.turn
    }

    /// How far two bodies with these travels may turn against each other (rad): a pair's
    /// feature angle grows by this, so a face turning onto the other body within the step is
    /// found as a face, whose corners off its bearing part get landing blocks.
    pub(crate) fn turning(&self, other: &Travel) -> f64 {
        (self.spin - other.spin).norm()
    }
}
