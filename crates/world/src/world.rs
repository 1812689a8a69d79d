//! The world: bodies, settings, and the step `collision → rows → solve → integrate`.

use std::ops::Range;
use std::time::{Duration, Instant};

use nalgebra::Vector3;
use tatami_contact::{Contact, ContactModel, ContactProjection, ContactRows};
use tatami_lcp::direct::{self, DirectInfo};
use tatami_lcp::pgs::{self, HeldResponses, PgsParams, PgsWorkspace, Record, Support, WarmStart};
use tatami_lcp::{DisjointSets, LcpError, Problem, Row, SolverBody};

use crate::body::{BodyKind, Motion};
use crate::bounce_guard::BounceGuard;
use crate::collision::{self, BodyGeometry, CollisionSettings, CollisionWorkspace};
use crate::contact_set::{self, ContactSet, HandedOn, rows_of};
use crate::held_handoff::HeldHandoff;
use crate::impact::Impacts;
use crate::parallel;
use crate::parry_bridge::Collider;
use crate::press::Presses;
use crate::rewind::{RewindWorkspace, StepMotion};
use crate::rows::{self, RowInputs, RowRuns};
use crate::sleep::Islands;
use crate::substeps::{self, StepInputs};
use crate::support::Outline;
use crate::{
    Body, BodyDesc, BodyId, Solver, StepError, StepTimings, WorldBuilder, WorldError, WorldSettings,
};

/// A rigid-body world.
///
/// ```
/// use tatami_world::{BodyDesc, Shape, World};
/// let mut world = World::builder()
///     .body(BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).position([0.0, 0.0, -1.0]))
///     .body(BodyDesc::dynamic(Shape::cuboid([2.0, 2.0, 2.0])).mass(1.0).position([0.0, 0.0, 1.0]))
///     .build()?;
/// for _ in 0..100 {
///     world.step(0.01)?;
/// }
/// let cube = &world.bodies()[1];
/// assert!((cube.position().z - 1.0).abs() < 0.003, "rests on the floor");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct World {
    pub(crate) gravity: Vector3<f64>,
    pub(crate) settings: WorldSettings,
    pub(crate) bodies: Vec<Body>,
    pub(crate) geometry: Vec<BodyGeometry>,
    /// Every touching pair and its state across steps, in Gauss–Seidel order.
    pub(crate) contact_set: ContactSet,
    pub(crate) problem: Problem<ContactProjection>,
    /// The part of each row's penetration push left to the position pass (split impulses).
    biases: Vec<f64>,
    /// The contacts kinematic bodies press in beyond the slop, for their grips.
    presses: Presses,
    /// The rows stage's runs, kept between steps.
    row_runs: RowRuns,
    /// Scratch: each moving body's state after the step, checked before it is committed.
    motions: Vec<(usize, Motion)>,
    /// Scratch of the pass that puts back fast pairs driven deep into each other.
    rewind: RewindWorkspace,
    /// The position pass's answer in the last step: per body, the pseudo-velocities that move
    /// its position only. Empty on steps without biases.
    pub(crate) pseudo_velocities: Vec<SolverBody>,
    pub(crate) collision_workspace: CollisionWorkspace,
    /// The islands of touching dynamic bodies, for sleeping.
    islands: Islands,
    /// Scratch: the velocity solve's answer set aside before the shock pass, to be put back if
    /// the pass would add energy.
    set_aside: SolvedState,
    /// Holds bounces to the energy their landings took ([`crate::bounce_guard`]).
    bounce_guard: BounceGuard,
    pgs_workspace: PgsWorkspace,
    /// The position pass's problem and workspace, reused across steps.
    position_pass: PositionPass,
    /// The shock passes' held responses, computed by the position pass for both
    /// ([`HeldHandoff`]); reused across steps.
    held_responses: HeldResponses,
    timings: StepTimings,
    time: f64,
    /// Kahan compensation of `time`, so a thousand steps of 0.01 s end at exactly 10 s.
    time_compensation: f64,
    steps: usize,
    /// What the direct solver did in the last step's velocity solve.
    direct_info: Option<DirectInfo>,
    /// The last step's `dt`, which turns its impulses into forces.
    pub(crate) last_dt: f64,
    /// The handle the next added body gets.
    next_id: u64,
    /// How many substeps the step being taken is split into.
    substep_count: usize,
    /// Scratch for the substeps' count.
    substep_scratch: substeps::Scratch,
    /// Scratch: each body's turn over the step, for the contact rows.
    turns: Vec<Vector3<f64>>,
    /// The step's forces and kinematic drives, handed to its substeps.
    step_inputs: StepInputs,
}

impl World {
    /// Starts building a world: gravity `(0, 0, −9.8)`, default settings, no bodies.
    pub fn builder() -> WorldBuilder {
        WorldBuilder::default()
    }

    pub(crate) fn empty(gravity: Vector3<f64>, settings: WorldSettings) -> Self {
        Self {
            gravity,
            settings,
            bodies: Vec::new(),
            geometry: Vec::new(),
            contact_set: ContactSet::default(),
            problem: Problem::default(),
            biases: Vec::new(),
            presses: Presses::default(),
            row_runs: RowRuns::default(),
            pseudo_velocities: Vec::new(),
            motions: Vec::new(),
            rewind: RewindWorkspace::default(),
            collision_workspace: CollisionWorkspace::default(),
            islands: Islands::default(),
            set_aside: SolvedState::default(),
            bounce_guard: BounceGuard::default(),
            pgs_workspace: PgsWorkspace::default(),
            position_pass: PositionPass::default(),
            held_responses: HeldResponses::default(),
            timings: StepTimings::default(),
            time: 0.0,
            time_compensation: 0.0,
            steps: 0,
            direct_info: None,
            last_dt: 0.0,
            next_id: 0,
            substep_count: 1,
            substep_scratch: substeps::Scratch::default(),
            turns: Vec::new(),
            step_inputs: StepInputs::default(),
        }
    }

    /// Adds a body; returns its handle. It is the last of [`World::bodies`] until others are
    /// added.
    pub fn add_body(&mut self, desc: BodyDesc) -> Result<BodyId, WorldError> {
        let index = self.bodies.len();
        let id = BodyId(self.next_id);
        let mut body = Body::new(desc, id, index)?;
        let collider = Collider::new(body.shape()).ok_or_else(|| WorldError::InvalidBody {
            body: body.name().to_owned(),
            field: "shape",
            reason: "the collision library cannot build this shape".into(),
        })?;
        let outline = match (body.shape(), collider.hull_vertices()) {
            (crate::Shape::Sphere { radius }, _) => Outline::Sphere { radius: *radius },
            (
                crate::Shape::Cylinder {
                    radius,
                    half_height,
                },
                _,
            ) => Outline::Cylinder {
                radius: *radius,
                half_height: *half_height,
            },
            (crate::Shape::Box { half_extents }, Some(corners)) => {
                Outline::polyhedron(corners, Some(*half_extents))
            }
            (_, Some(vertices)) => Outline::polyhedron(vertices, None),
            (_, None) => {
                return Err(WorldError::InvalidBody {
                    body: body.name().to_owned(),
                    field: "shape",
                    reason: "the shape has no hull vertices".into(),
                });
            }
        };
        body.thickness = collider.thickness();
        self.bodies.push(body);
        self.geometry.push(BodyGeometry { collider, outline });
        self.next_id += 1;
        Ok(id)
    }

    /// The bodies, in the order they were added.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The body named `name`, if any.
    pub fn body(&self, name: &str) -> Option<&Body> {
        self.bodies.iter().find(|b| b.name() == name)
    }

    /// Gravity (m/s²).
    pub fn gravity(&self) -> Vector3<f64> {
        self.gravity
    }

    /// The settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }

    /// Replaces the settings after checking them.
    pub fn set_settings(&mut self, settings: WorldSettings) -> Result<(), WorldError> {
        settings.validate()?;
        self.settings = settings;
        Ok(())
    }

    /// Contacts found by the last step (at the start of that step's positions), one per
    /// touching pair, in the solver's Gauss–Seidel order: highest first along gravity.
    pub fn contacts(&self) -> impl ExactSizeIterator<Item = &Contact> + Clone {
        self.contact_set.contacts()
    }

    /// The last step's constraint problem, with the solved impulses in its rows (or, after
    /// [`World::prepare_step`], the unsolved problem it built). Its targets are the velocity
    /// targets: penetration is removed by a separate position pass (see [`World::step`]).
    pub fn problem(&self) -> &Problem<ContactProjection> {
        &self.problem
    }

    /// The blocks of [`World::problem`] that belong to contact `index` of [`World::contacts`]
    /// (`None` past the last contact).
    pub fn contact_blocks(&self, index: usize) -> Option<Range<usize>> {
        self.contact_set.get(index).map(|(_, blocks)| blocks)
    }

    /// What the direct solver did in the last step's velocity solve — its size, its pivots and
    /// whether it had to regularise the problem (a warning) — or `None` under PGS.
    pub fn direct_info(&self) -> Option<DirectInfo> {
        self.direct_info
    }

    /// Time spent in each stage of the last step.
    pub fn timings(&self) -> StepTimings {
        self.timings
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Kinetic plus gravitational potential energy of the dynamic bodies (J), potential zero at
    /// the origin.
    pub fn total_energy(&self) -> f64 {
        self.bodies
            .iter()
            .filter(|b| b.is_dynamic())
            .map(|b| b.kinetic_energy() - b.mass() * self.gravity.dot(&b.centre.coords))
            .sum()
    }

    /// Advances the world by `dt` seconds, in stages: collision → contact rows → velocity
    /// solve → position correction → integrate (a pair of free bodies the step drives into
    /// each other from apart put back where they met).
    ///
    /// The velocity solve is warm-started from the contact set (the face model's blocks from
    /// the impulse each applied, the other models' rows by feature id) when the solver's
    /// settings say so, as they do by default.
    ///
    /// A contact deeper than the slop is pushed out at up to `max_depenetration_speed`. Up to
    /// `max_velocity_bias` of the push (none by default) is a target of the velocity solve (a
    /// Baumgarte bias, which cold solves need to hold tall stacks); the rest goes to split
    /// impulses (Catto 2006; Bullet's `splitImpulse`): on steps that have some, a second solve
    /// of the same blocks from rest with those pushes as targets, then a ground-up pass, give
    /// pseudo-velocities that move the positions only, no body faster than
    /// `max_depenetration_speed`. Bodies created overlapping thus separate without being thrown
    /// — with the whole push in the velocities, pushes add up along chains of overlapping bodies.
    ///
    /// A step is split into equal substeps, each all of the above, when the typical body is
    /// small for it or a body touching another turns fast ([`WorldSettings::max_substeps`]; see
    /// [`SAG_SHARE`](crate::SAG_SHARE) and [`MAX_SUBSTEP_TURN`](crate::MAX_SUBSTEP_TURN)).
    /// Forces set for the step act in each, a kinematic target is reached a share at a time,
    /// and [`World::contacts`], [`World::problem`] and the contact forces are the last
    /// substep's. Should a substep fail, the world is left as that substep found it.
    ///
    /// Large scenes run on every core of rayon's pool. When the next step's collision will,
    /// the pool's helpers spin on for up to 2 ms after the step returns, or until the next
    /// step, taking any other job the pool is handed meanwhile: a step that follows at once
    /// then starts without waiting for them to wake.
    pub fn step(&mut self, dt: f64) -> Result<(), StepError> {
        check_time_step(dt)?;
        self.keep_helpers_warm();
        let count = substeps::count(
            &self.bodies,
            self.contact_set.contacts(),
            &self.gravity,
            dt,
            self.settings.max_substeps,
            &mut self.substep_scratch,
        );
        self.substep_count = count;
        self.step_inputs.take(&self.bodies, dt);
        if count == 1 {
            self.substep(dt)?;
        } else {
            let mut timings = StepTimings::default();
            for k in 0..count {
                self.step_inputs.hand_to(&mut self.bodies, k, count, dt);
                self.substep(dt / count as f64)?;
                timings += self.timings;
            }
            self.timings = timings;
        }
        self.step_inputs.finish(&mut self.bodies);
        self.keep_helpers_warm();
        let y = dt - self.time_compensation;
        let t = self.time + y;
        self.time_compensation = (t - self.time) - y;
        self.time = t;
        self.steps += 1;
        Ok(())
    }

    /// Keeps the pool's helpers spinning for the next collision pass, when it runs on every
    /// core ([`parallel::keep_warm_for_next_step`]): called as a step ends, so that the next
    /// step finds them awake, and as one starts, should they have stopped since.
    fn keep_helpers_warm(&self) {
        if self.collision_workspace.next_pass_on_every_core() {
            parallel::keep_warm_for_next_step();
        }
    }

    /// One step of `dt` through every stage, as [`World::step`] describes.
    fn substep(&mut self, dt: f64) -> Result<(), StepError> {
        let start = Instant::now();
        let warm = self.detect(dt);
        self.wake_islands();
        let collided = Instant::now();
        self.build_problem(dt, warm)?;
        let built = Instant::now();
        let (solved, warm, warm_start) = self.solve_and_correct(dt)?;
        let corrected = Instant::now();
        let kept = self.integrate(dt, warm)?;
        self.fall_asleep(dt);
        let integrated = Instant::now();
        // The contact set's warm start and its keeping of the solve's impulses are timed with
        // the rows, though they run at the solve's start and end: the stages then split the
        // step into collision, the contact set and its rows, and the solver.
        self.timings = StepTimings {
            collision: collided - start,
            setup: built - collided + warm_start + kept,
            solve: (solved - built).saturating_sub(warm_start),
            correction: corrected - solved,
            integrate: (integrated - corrected).saturating_sub(kept),
        };
        self.last_dt = dt;
        Ok(())
    }

    /// Runs the first stages of a step of `dt` (collision, contact rows) from the current state
    /// and returns the solver's input, without solving it or moving anything (one step of `dt`,
    /// whatever substeps [`World::step`] would split it into): impulses are
    /// zero, and the bodies' velocities already include gravity's impulse. Experiments and
    /// benchmarks use it to compare or time solvers alone on a world's real problem.
    ///
    /// ```
    /// use tatami_world::{BodyDesc, Shape, World};
    /// let mut world = World::builder()
    ///     .body(BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).position([0.0, 0.0, -1.0]))
    ///     .body(BodyDesc::dynamic(Shape::cuboid([2.0, 2.0, 2.0])).position([0.0, 0.0, 1.0]))
    ///     .build()?;
    /// let problem = world.prepare_step(0.01)?;
    /// assert_eq!(problem.rows.len(), 6, "face model: one 6-row constraint for the face");
    /// assert!(problem.rows.iter().all(|row| row.impulse == 0.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn prepare_step(&mut self, dt: f64) -> Result<&Problem<ContactProjection>, StepError> {
        check_time_step(dt)?;
        self.substep_count = 1;
        let warm = self.detect(dt);
        self.wake_islands();
        self.build_problem(dt, warm)?;
        Ok(&self.problem)
    }

    /// Sleeping: wakes every island with a body awake or a moving kinematic body touching it;
    /// with sleeping off, wakes every body.
    fn wake_islands(&mut self) {
        if self.settings.sleeping.enabled {
            self.islands
                .wake(&mut self.bodies, self.contact_set.contacts());
        } else {
            self.bodies.iter_mut().for_each(Body::wake);
        }
    }

    /// Sleeping: puts to sleep the islands that have rested long enough.
    fn fall_asleep(&mut self, dt: f64) {
        if self.settings.sleeping.enabled {
            self.islands.fall_asleep(
                &mut self.bodies,
                self.contact_set.contacts(),
                &self.settings.sleeping,
                &self.settings.contact,
                dt,
            );
        }
    }

    /// Collision: the contact set brought to the current positions for a step of `dt`,
    /// highest contact first; with the pool's helpers kept awake for the rows when those will
    /// be built on every core (see [`collision::detect`]).
    ///
    /// A kinematic body sent to a target first gets the velocity that takes it there in the
    /// step, so its contacts are found over the step as any moving body's, speculatively: at
    /// rest until then, a bat sent 0.5 m a step (30 m/s at 60 Hz) at a 0.2 m cube was seen
    /// only once inside it, and passed through it under the vertex and patch models.
    fn detect(&mut self, dt: f64) -> Option<parallel::Warm> {
        for body in &mut self.bodies {
            if body.kind() == BodyKind::Kinematic
                && let Some(velocities) = body.velocity_to_target(dt)
            {
                (body.linear_velocity, body.angular_velocity) = velocities;
            }
        }
        let collision = CollisionSettings::of(&self.settings);
        let mut warm = collision::detect(
            &self.bodies,
            &self.geometry,
            &collision,
            &self.gravity,
            dt,
            &mut self.collision_workspace,
            &mut self.contact_set,
        );
        let impacts = Impacts {
            bodies: &self.bodies,
            gravity: &self.gravity,
            dt,
            settings: &self.settings.contact,
        };
        // Where the rows will be built on every core, so are the landings handed on: the
        // helpers kept spinning for the rows take their share, and spin on after it.
        let on_every_core = warm.take().is_some();
        self.contact_set
            .hand_on_impacts(on_every_core, |contact, met, still| {
                let bounce_speed = impacts.bounce_speed(contact, met);
                HandedOn {
                    bounce_speed,
                    bounce_energy: if bounce_speed > 0.0 {
                        impacts.landing_took(contact, met)
                    } else {
                        0.0
                    },
                    landing: impacts.landing(contact, met, bounce_speed, still),
                }
            });
        on_every_core.then(parallel::Warm::start)
    }

    /// Contact rows from the velocities at the start of the step, then gravity's impulse. A
    /// contact a kinematic body presses in beyond the slop gets a grip beside the model's
    /// blocks, and one that squeezes its body no pushes for the position pass
    /// ([`crate::press`]). A bounce acts where its landing met
    /// ([`crate::impact::bounce_where_landed`]).
    ///
    /// In the contact set's order, on both cores while collision kept the pool's helpers
    /// awake for it ([`crate::rows`]: the calling thread builds from the first pair on
    /// straight into the problem, the helpers from the last on apart, and only their share is
    /// copied in). Every run built apart and then all appended cost as much in the copy as the
    /// second core saved (the 1000-cube pile's rows 0.94–0.97 ms on two threads against
    /// 0.88–0.93 ms on one): a row and its block are a few hundred bytes, and the build of a
    /// face, about 0.3 µs, does little more than write them.
    fn build_problem(&mut self, dt: f64, warm: Option<parallel::Warm>) -> Result<(), StepError> {
        let problem = &mut self.problem;
        problem.bodies.clear();
        problem
            .bodies
            .extend(self.bodies.iter().map(Body::solver_body));
        problem.rows.clear();
        problem.blocks.clear();
        self.biases.clear();
        let contact_settings = self.settings.contact;
        (self.presses).find(&self.bodies, self.contact_set.contacts(), &contact_settings);
        self.turns.clear();
        (self.turns).extend(self.bodies.iter().map(|body| rows::turn_of(body, dt)));
        let inputs = RowInputs {
            bodies: &self.bodies,
            turns: &self.turns,
            presses: &self.presses,
            model: self.settings.model,
            settings: &contact_settings,
            dt,
            grip_dt: dt * (self.substep_count * self.substep_count) as f64,
            warm_start_weight: warm_starts(&self.settings).then(|| self.gravity * dt),
        };
        let mut out = ContactRows::of(problem, &mut self.biases);
        (self.row_runs).build(&mut self.contact_set, &inputs, &mut out, warm)?;
        // Gravity's impulse and the applied forces'.
        for (solver_body, body) in problem.bodies.iter_mut().zip(&self.bodies) {
            match body.kind() {
                BodyKind::Dynamic if body.asleep => {}
                BodyKind::Dynamic => {
                    solver_body.linear_velocity += (self.gravity + body.force / body.mass()) * dt;
                    solver_body.angular_velocity +=
                        solver_body.inv_inertia_world * body.torque * dt;
                }
                // A kinematic body moves at its own velocity, its target's since collision.
                BodyKind::Kinematic | BodyKind::Fixed => {}
            }
        }
        Ok(())
    }

    /// The velocity solve, then (on steps with pushes left to it) the position pass. The pass
    /// solves its own copy of the problem ([`PositionPass`]) and shares nothing with the velocity
    /// solve, so on a large problem it runs on a helper thread meanwhile
    /// ([`parallel::join_beside`]); either way the answer is the same to the bit. Returns when
    /// the velocity solve ended and how long its warm start took, for the stage timings, and,
    /// when the helper that ran the pass is kept spinning for the bodies' motions
    /// ([`World::integrate`]), what keeps it so.
    fn solve_and_correct(
        &mut self,
        dt: f64,
    ) -> Result<(Instant, Option<parallel::Warm>, Duration), StepError> {
        self.direct_info = None;
        self.pseudo_velocities.clear();
        let correcting = self.biases.iter().any(|&bias| bias != 0.0);
        let beside = self.problem.rows.len() >= POSITION_PASS_BESIDE_ROWS;
        if correcting {
            (self.position_pass).set_up(&self.problem, &self.biases, beside);
        }
        // The helper that cloned the blocks spins until it takes the position pass below:
        // asleep by then and woken for it, it started the pass up to 2 ms late, and
        // at rest, where the pass takes about as long as the velocity solve, the step waited.
        let until_the_pass = (correcting && beside).then(parallel::Warm::start);
        let warm_start = Instant::now();
        if warm_starts(&self.settings) {
            self.contact_set.warm_start(
                self.settings.model,
                &mut self.problem,
                &(self.gravity * dt),
            );
            // A squeeze leaves its normal forces undetermined. The face model's blocks carried
            // them from step to step and they grew (a cube carried up by two fingers: 9 N on
            // each after 10 s, 30 N after 60 s, its press 5.4 N): each side's block took up
            // tilt with normal force, which pushed the body into the other side. Its grips bear
            // the squeeze, so those blocks start from zero. The vertex and patch models' stay
            // warm-started: theirs held steady (8.9 and 9.3 N), and from zero their corners
            // left the cube turning by 0.2 mrad as it was carried.
            // So do the blocks of two free bodies far apart in mass
            // ([`COLD_START_MASS_RATIO`]).
            let face = self.settings.model == ContactModel::Face;
            for index in 0..self.contact_set.contacts().len() {
                let Some((contact, blocks)) = self.contact_set.get(index) else {
                    continue;
                };
                if face && self.presses.squeezed(index)
                    || far_apart_in_mass(contact, &self.problem.bodies)
                {
                    let rows = rows_of(&self.problem, &blocks);
                    self.problem.rows[rows]
                        .iter_mut()
                        .for_each(|row| row.impulse = 0.0);
                }
            }
        }
        let warm_start = warm_start.elapsed();
        (self.bounce_guard).before_solve(
            (&self.problem, &self.bodies),
            (&self.gravity, dt),
            self.contact_set.bounces(),
        );
        let under_gravity = self.gravity != Vector3::zeros();
        let order = if self.settings.shock_propagation || (correcting && under_gravity) {
            self.contact_set
                .shock_order(&self.gravity, &self.problem.bodies)
        } else {
            &[]
        };
        drop(until_the_pass);
        let mut velocity = VelocitySolve {
            problem: &mut self.problem,
            workspace: &mut self.pgs_workspace,
            set_aside: &mut self.set_aside,
            bodies: &self.bodies,
            settings: &self.settings,
            order,
        };
        let position = &mut self.position_pass;
        let settings = &self.settings;
        // The helper that ran the pass, done before the velocity solve, spins on to take its
        // share of the bodies' motions (not the calling thread, should it run the pass after
        // the velocity solve: a helper woken then would start late).
        let caller = std::thread::current().id();
        let spin_on = || {
            (self.bodies.len() >= PARALLEL_MOTIONS && std::thread::current().id() != caller)
                .then(parallel::Warm::start)
        };
        let mut for_motions = None;
        let ((velocity_result, solved), position_result) = if !correcting {
            ((velocity.run(None), Instant::now()), Ok(()))
        } else if beside {
            // The position pass computes the shock passes' held responses for both, when the
            // velocity solve runs one.
            let handoff = HeldHandoff::new();
            let held = settings
                .shock_propagation
                .then_some((&handoff, &mut self.held_responses));
            let (velocity, (position, spinning)) = parallel::join_beside(
                || (velocity.run(Some(&handoff)), Instant::now()),
                || {
                    let result = position.solve(settings, under_gravity, order, held);
                    (result, spin_on())
                },
            );
            for_motions = spinning;
            (velocity, position)
        } else {
            let velocity_result = velocity.run(None);
            let solved = Instant::now();
            // A failed velocity solve ends the step; its pushes are not needed then.
            let position_result = match velocity_result {
                Ok(_) => position.solve(settings, under_gravity, order, None),
                Err(_) => Ok(()),
            };
            ((velocity_result, solved), position_result)
        };
        let name = |world: &Self, source: LcpError| StepError::Solver {
            pair: world.contact_of_error(&source),
            source,
        };
        self.direct_info = velocity_result.map_err(|source| name(self, source))?;
        position_result.map_err(|source| name(self, source))?;
        self.bounce_guard
            .after_solve(&mut self.problem, &self.bodies);
        if correcting {
            self.limit_pseudo_velocities();
        }
        Ok((solved, for_motions, warm_start))
    }

    /// The position pass's answer as pseudo-velocities. Pushes add up along chains of
    /// overlapping bodies; no body is moved faster than one contact may push.
    fn limit_pseudo_velocities(&mut self) {
        self.pseudo_velocities
            .clone_from(&self.position_pass.problem.bodies);
        let limit = self.settings.contact.max_depenetration_speed;
        for (body, solid) in self.pseudo_velocities.iter_mut().zip(&self.geometry) {
            let reach = solid.outline.size();
            let speed = body
                .linear_velocity
                .norm()
                .max(body.angular_velocity.norm() * reach);
            if speed > limit {
                body.linear_velocity *= limit / speed;
                body.angular_velocity *= limit / speed;
            }
        }
    }

    /// The contact a solver error names through its block, if any.
    fn contact_of_error(&self, error: &LcpError) -> Option<String> {
        let block = match error {
            LcpError::NonFinite { block }
            | LcpError::MalformedBlock { block }
            | LcpError::Unsupported { block } => *block,
            _ => return None,
        };
        let contact = self.contact_set.contact_of_block(block)?;
        Some(pair_name(&self.bodies, contact))
    }

    /// Semi-implicit Euler: the solved velocities move the bodies; each turns by the
    /// free-rotation step that keeps its angular momentum (the gyroscopic term). Every new
    /// state is computed and checked before any is committed, and the impulses are kept for the
    /// next warm start only then, so a step that would leave a non-finite state changes neither
    /// the bodies nor the impulses and names the body.
    /// The position correction's pseudo-velocities, when the step has one, move the positions
    /// too.
    ///
    /// Each body's motion is its own, so with `warm` helpers still spinning they take a share
    /// of them. Returns how long the contact set took to keep the impulses and end the step.
    fn integrate(&mut self, dt: f64, warm: Option<parallel::Warm>) -> Result<Duration, StepError> {
        let corrections = &self.pseudo_velocities;
        let (bodies, solved) = (&self.bodies, &self.problem.bodies);
        self.motions.clear();
        self.motions.extend(
            (bodies.iter().enumerate())
                .filter(|(_, body)| !body.is_fixed() && !body.asleep)
                .map(|(index, body)| (index, body.motion_now())),
        );
        let move_one = |(index, motion): &mut (usize, Motion)| {
            *motion = bodies[*index].motion(&solved[*index], corrections.get(*index), dt);
        };
        match warm {
            Some(warm) if warm.all_spinning() => {
                drop(warm);
                parallel::for_each(&mut self.motions, || (), |(), item| move_one(item));
            }
            _ => self.motions.iter_mut().for_each(move_one),
        }
        if let Some((index, _)) = self.motions.iter().find(|(_, motion)| !motion.is_finite()) {
            return Err(StepError::NonFiniteState {
                body: self.bodies[*index].name().to_owned(),
            });
        }
        // A pair of free bodies the step drives into each other from apart is put back where
        // they met ([`crate::rewind`]).
        let step = StepMotion {
            bodies: &self.bodies,
            geometry: &self.geometry,
            placements: &self.collision_workspace.placements,
            solved: &self.problem.bodies,
            dt,
            margin: self.settings.contact_margin,
            slop: self.settings.contact.slop,
        };
        let pairs = self.collision_workspace.pairs();
        let contacts = self.contact_set.contacts();
        (self.rewind).rewind(&step, pairs, contacts, &mut self.motions);
        // Every body's new state is finite: commit them all, and the solve's impulses.
        for (index, motion) in &self.motions {
            self.bodies[*index].set_motion(motion);
        }
        for body in &mut self.bodies {
            body.force = Vector3::zeros();
            body.torque = Vector3::zeros();
            body.target = None;
        }
        let kept = Instant::now();
        if warm_starts(&self.settings) {
            let from_sweeps = warm_starts_from_the_sweeps(&self.settings)
                && self.set_aside.impulses.len() == self.problem.rows.len();
            if from_sweeps {
                self.set_aside.swap_impulses(&mut self.problem);
            }
            self.contact_set.store(self.settings.model, &self.problem);
            if from_sweeps {
                self.set_aside.swap_impulses(&mut self.problem);
            }
        }
        self.contact_set.end_step();
        Ok(kept.elapsed())
    }
}

/// The velocity solve's borrows of the world, apart from the position pass's.
struct VelocitySolve<'a> {
    problem: &'a mut Problem<ContactProjection>,
    workspace: &'a mut PgsWorkspace,
    set_aside: &'a mut SolvedState,
    bodies: &'a [Body],
    settings: &'a WorldSettings,
    /// [`ContactSet::shock_order`], when the shock pass runs.
    order: &'a [(usize, Support)],
}

impl VelocitySolve<'_> {
    /// PGS (warm-started by the caller) and, when asked, the guarded shock pass, with the held
    /// responses the position pass computed if it hands them over; or the direct solver, whose
    /// report it returns.
    ///
    /// The shock pass is kept in each island (bodies joined by contacts) only if it leaves that
    /// island's bodies with no more kinetic energy than the solve did: held still, a
    /// supporting body does not feel the pass's reactions, which can push its load up as if off
    /// a fixed floor; undone then, the pass can only take energy out (a falling stack stopped
    /// on its base). Island by island, what the pass does to one pile does not decide whether
    /// another keeps it. It runs on the problem as solved, without checking it again
    /// ([`pgs::Solved`]).
    fn run(&mut self, held: Option<&HeldHandoff<'_>>) -> Result<Option<DirectInfo>, LcpError> {
        match &self.settings.solver {
            Solver::Pgs(params) if self.settings.shock_propagation => {
                let (_, solved) = pgs::solve_for_shock(self.problem, self.workspace, params)?;
                // The solve's answer set aside, to be put back in the islands the pass gains in.
                self.set_aside.save(solved.problem());
                let sweeps = shock_sweeps_per_pair(self.settings.model);
                let held = held.and_then(HeldHandoff::take);
                solved.shock_propagation(self.workspace, self.order, sweeps, held)?;
                let islands = self.workspace.body_islands();
                (self.set_aside).restore_islands_that_gained(self.problem, self.bodies, islands);
                Ok(None)
            }
            Solver::Pgs(params) => {
                pgs::solve_in_place(self.problem, self.workspace, params)?;
                Ok(None)
            }
            Solver::Direct(params) => direct::solve(self.problem, params).map(Some),
        }
    }
}

/// The position pass of split impulses, on its own copy of the velocity problem: the same
/// rows, blocks and masses, the bodies at rest, the pushes the velocity solve left as targets.
/// Solved from rest with the same solver (then, under gravity, a ground-up pass), it gives
/// pseudo-velocities that move positions only (see [`World::step`]). Sharing nothing with the
/// velocity solve, it can run beside it; copying costs less than the pass it lets run there.
#[derive(Debug, Clone, Default)]
struct PositionPass {
    problem: Problem<ContactProjection>,
    workspace: PgsWorkspace,
}

impl PositionPass {
    /// Copies `velocity`'s problem as built, with `biases` (one per row) as the targets; with
    /// `beside`, the blocks are cloned on a helper while this thread copies the bodies and rows:
    /// the copy stands ahead of the velocity solve, 0.16–0.17 ms of the settling 1000-cube
    /// pile's step on one thread (the blocks' clone about half of it), 0.13–0.16 ms so.
    fn set_up(&mut self, velocity: &Problem<ContactProjection>, biases: &[f64], beside: bool) {
        let Problem {
            bodies,
            rows,
            blocks,
        } = &mut self.problem;
        let mut bodies_and_rows = || {
            bodies.clear();
            bodies.extend(velocity.bodies.iter().map(|body| SolverBody {
                linear_velocity: Vector3::zeros(),
                angular_velocity: Vector3::zeros(),
                ..*body
            }));
            rows.clear();
            rows.extend(velocity.rows.iter().zip(biases).map(|(row, &bias)| Row {
                target: bias,
                impulse: 0.0,
                ..*row
            }));
        };
        let mut clone_blocks = || blocks.clone_from(&velocity.blocks);
        if beside {
            parallel::join_beside(bodies_and_rows, clone_blocks);
        } else {
            bodies_and_rows();
            clone_blocks();
        }
    }

    /// Solves the pass with `settings`' solver; `order` is [`ContactSet::shock_order`] under
    /// gravity. With `held`, it first computes the shock passes' held responses for both
    /// passes into the buffer given and hands them to the velocity solve ([`HeldHandoff`]).
    fn solve<'a>(
        &mut self,
        settings: &WorldSettings,
        under_gravity: bool,
        order: &[(usize, Support)],
        held: Option<(&HeldHandoff<'a>, &'a mut HeldResponses)>,
    ) -> Result<(), LcpError> {
        match &settings.solver {
            Solver::Pgs(params) => {
                let problem = &self.problem;
                let held = held.and_then(|(handoff, held)| {
                    handoff.offer(held, |held| held.compute(problem, order).is_ok())
                });
                let from_rest = PgsParams {
                    warm_start: WarmStart::Off,
                    record: Record::Nothing,
                    iterations: if under_gravity {
                        params.iterations.min(CORRECTION_SWEEPS_UNDER_GRAVITY)
                    } else {
                        params.iterations
                    },
                    ..*params
                };
                let (_, solved) =
                    pgs::solve_for_shock(&mut self.problem, &mut self.workspace, &from_rest)?;
                // Then, under gravity, one pass from the ground up holding each contact's lower
                // body still: pseudo-velocities carry no momentum, so nothing is lost by it, and
                // a stack whatever its height or mass ratio (1 kg under 1000 kg) is pushed apart
                // at once, where sweeps from rest carry a push up one level per sweep. Without
                // gravity there is no ground to go up from.
                if under_gravity {
                    let sweeps = shock_sweeps_per_pair(settings.model);
                    solved.shock_propagation(&mut self.workspace, order, sweeps, held)?;
                }
                Ok(())
            }
            Solver::Direct(params) => direct::solve(&mut self.problem, params).map(drop),
        }
    }
}

/// Shock-pass sweeps over each pair's blocks under `model`
/// ([`pgs::shock_propagation_per_pair`]). A face-model block is solved whole, and one update
/// rests its body on the support exactly. The vertex model's blocks of one face, and a patch's
/// rows, share the load among the vertices, and one pass over them leaves the body moving a
/// little: with the pass's impulses warm-started, a tower of crossed blocks grew that motion
/// until it fell; with the sweeps' ([`warm_starts_from_the_sweeps`]), a cube held by friction
/// on a 15° ramp crept across it at 0.5 µm/s. Ten sweeps a pair, ending early once settled,
/// rest both.
fn shock_sweeps_per_pair(model: ContactModel) -> usize {
    match model {
        ContactModel::Face => 1,
        ContactModel::Vertex | ContactModel::Patch => 10,
    }
}

/// How many times heavier than the other one of two free bodies must be for their contact to
/// start each step from zero impulses, under every model. Warm-started, a 1 g cube under a
/// 100–1000 kg slab dropped onto it took first what the last step's shock pass had applied
/// to stop the slab (tens of N s), which 12 sweeps at that ratio did not undo: within 3 s the
/// cubes were squeezed through the floor or thrown kilometres under the face model (the
/// patch model lost one by 28 mm). From zero, every such drop holds them. The 1 kg cube under
/// 1000 kg of the holding scenes stays warm-started.
const COLD_START_MASS_RATIO: f64 = 1e4;

/// Whether `contact` is between two free bodies (of `bodies`) [`COLD_START_MASS_RATIO`] or
/// more apart in mass.
fn far_apart_in_mass(contact: &Contact, bodies: &[SolverBody]) -> bool {
    let free = [contact.body_a, contact.body_b].map(|id| bodies[id.0].inv_mass > 0.0);
    free == [true, true] && contact_set::heavier(contact, bodies, COLD_START_MASS_RATIO).is_some()
}

/// Rows from which the position pass runs on a helper thread beside the velocity solve. A
/// helper asleep takes 0.2–1 ms to start on a virtual machine of two cores (see
/// [`parallel`]); below this a problem's velocity solve may end first, and the step would
/// wait for the helper.
const POSITION_PASS_BESIDE_ROWS: usize = 1024;

/// Fewest bodies whose motions the helper that ran the position pass beside the velocity
/// solve stays to share ([`World::integrate`]): a body's motion (its free rotation) takes about
/// 0.2 µs, so a few hundred are worth a loop on two cores.
const PARALLEL_MOTIONS: usize = 256;

/// A solve's answer — velocities and impulses — kept to be put back, island by island, where
/// the shock pass added energy; buffers reused.
#[derive(Debug, Clone, Default)]
struct SolvedState {
    bodies: Vec<SolverBody>,
    impulses: Vec<f64>,
    /// Per island root: the kinetic energy set aside and the one in the problem now.
    energies: Vec<(f64, f64)>,
}

impl SolvedState {
    fn save(&mut self, problem: &Problem<ContactProjection>) {
        self.bodies.clone_from(&problem.bodies);
        self.impulses.clear();
        self.impulses.extend(problem.rows.iter().map(|r| r.impulse));
    }

    /// Swaps the impulses set aside with `problem`'s.
    fn swap_impulses(&mut self, problem: &mut Problem<ContactProjection>) {
        for (row, impulse) in problem.rows.iter_mut().zip(&mut self.impulses) {
            std::mem::swap(&mut row.impulse, impulse);
        }
    }

    /// Puts back the velocities and impulses set aside in every island whose dynamic bodies
    /// have more kinetic energy in `problem` than they had then (`bodies` gives their masses).
    /// `islands` are the velocity solve's ([`PgsWorkspace::body_islands`]): its blocks join
    /// the bodies an impulse can move, which are the dynamic ones (a dynamic body's mass is
    /// finite), so they are the dynamic bodies' islands through the blocks, found once. Joined
    /// here again, and the blocks passed over where no island gained, the guard took 0.09 ms
    /// more of the settling cube pile's step, on the critical path (alternate steps of three
    /// runs, seconds 5–8; the same bits).
    fn restore_islands_that_gained(
        &mut self,
        problem: &mut Problem<ContactProjection>,
        bodies: &[Body],
        islands: &mut DisjointSets,
    ) {
        let dynamic = |k: usize| bodies[k].is_dynamic();
        // Each body's world inertia computed once for both energies.
        self.energies.clear();
        self.energies.resize(bodies.len(), (0.0, 0.0));
        let velocities = self.bodies.iter().zip(&problem.bodies);
        for (k, (body, (was, now))) in bodies.iter().zip(velocities).enumerate() {
            if !body.is_dynamic() {
                continue;
            }
            let inertia = body.inertia_world();
            let energy = &mut self.energies[islands.root(k)];
            energy.0 +=
                body.kinetic_energy_at(&inertia, &was.linear_velocity, &was.angular_velocity);
            energy.1 +=
                body.kinetic_energy_at(&inertia, &now.linear_velocity, &now.angular_velocity);
        }
        // Where no island gained, nothing is put back: the blocks need no pass.
        if !self.energies.iter().any(|(before, after)| after > before) {
            return;
        }
        let mut gained = |k: usize| {
            let (before, after) = self.energies[islands.root(k)];
            after > before
        };
        for (k, body) in problem.bodies.iter_mut().enumerate() {
            if dynamic(k) && gained(k) {
                *body = self.bodies[k];
            }
        }
        for block in &problem.blocks {
            let (a, b) = (block.body_a.0, block.body_b.0);
            let body = if dynamic(a) { a } else { b };
            if dynamic(body) && gained(body) {
                let rows = &mut problem.rows[block.rows.clone()];
                for (row, &impulse) in rows.iter_mut().zip(&self.impulses[block.rows.clone()]) {
                    row.impulse = impulse;
                }
            }
        }
    }
}

/// Whether the step's rows start from the contact set's impulses: PGS with its warm start on.
fn warm_starts(settings: &WorldSettings) -> bool {
    matches!(&settings.solver, Solver::Pgs(params) if params.warm_start == WarmStart::On)
}

/// Whether the next step's warm start takes the velocity sweeps' impulses, set aside before the
/// shock pass, rather than those the pass left (which move the bodies and are read out as the
/// contacts' forces either way): under the vertex and patch models.
///
/// A face-model block is solved whole, and the pass's update of it is the block's answer with
/// its support held. A face's per-vertex blocks, or a patch's normal rows, share its load
/// among the vertices, and the pass shares it otherwise than the sweeps do even when it sweeps
/// each pair until settled ([`shock_sweeps_per_pair`]). Carried into the next step, that share
/// left the bodies a motion which the sweeps, warm-started and stopping at their tolerance, did
/// not remove, and it grew step after step: of 100 random stable stacks of 2 to 6 boxes (5 cm
/// to 1 m, 200 to 3000 kg/m³, turned at random, 60 Hz), the worst fell 1.5 m (vertex) and 2.0
/// m (patch) in 10 s, a wide heavy box on a narrow light one. From the sweeps' impulses every
/// one stands to 1e-12 m. Under the face model the pass's impulses are kept: every stack above
/// holds either way, and the face model's runs stay as they were.
fn warm_starts_from_the_sweeps(settings: &WorldSettings) -> bool {
    settings.shock_propagation && settings.model != ContactModel::Face
}

/// Most sweeps of the position pass under gravity, before its ground-up pass. That pass carries
/// a push through a stack or pile at once, so sweeps from rest add little there: on the 820-cube
/// pyramid and the 1000-cube pile (`general_comparison` bench) 4 sweeps instead of 15 hold as
/// well (the same largest displacement, no deeper penetration) and cut the step by 28%; the
/// holding scenes' figures are unchanged to the printed digits. Without gravity there is no
/// ground to go up from and the pass keeps the velocity solve's sweeps: 4 left 500 cubes
/// created overlapping 0.68 m deep after 6 s, against under 5 cm with 15.
const CORRECTION_SWEEPS_UNDER_GRAVITY: usize = 4;

/// Longest time step a world takes (s): contacts are velocity-level and speculative over one
/// step, which means nothing over hours (a step of 1e10 s was accepted).
pub const MAX_TIME_STEP: f64 = 1.0;

/// A time step must be finite, positive and at most [`MAX_TIME_STEP`].
fn check_time_step(dt: f64) -> Result<(), StepError> {
    if dt.is_finite() && dt > 0.0 && dt <= MAX_TIME_STEP {
        Ok(())
    } else {
        Err(StepError::InvalidTimeStep(dt))
    }
}

/// `a–b` from the contact's body names.
pub(crate) fn pair_name(bodies: &[Body], contact: &Contact) -> String {
    format!(
        "{}–{}",
        bodies[contact.body_a.0].name(),
        bodies[contact.body_b.0].name()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDesc, Shape, sleep};

    /// A step that would leave a non-finite state used to return Ok, the NaN surfacing a step
    /// later under another body's name. Validated input no longer gets there (sizes, speeds,
    /// masses and `dt` are bounded at load), so the state is forced here: a cube at the edge of
    /// f64 moving on. The step fails naming the cube and leaves bodies, time and count as they
    /// were.
    #[test]
    fn a_step_that_would_leave_a_non_finite_state_changes_nothing() {
        let mut world = World::builder()
            .gravity([0.0; 3])
            .body(BodyDesc::dynamic(Shape::cuboid([1.0; 3])).name("cube"))
            .build()
            .unwrap();
        world.step(0.01).unwrap();
        world.bodies[0].centre.x = 1.5e308;
        world.bodies[0].linear_velocity.x = 1e4;
        let before = world.bodies.clone();
        let (time, steps) = (world.time(), world.steps());
        world.bodies[0].linear_velocity.x = 1e308;
        let moving = world.bodies.clone();
        let error = world.step(1.0).unwrap_err();
        assert_eq!(
            error,
            StepError::NonFiniteState {
                body: "cube".into()
            }
        );
        assert_eq!(world.bodies, moving);
        assert_ne!(world.bodies, before);
        assert_eq!((world.time(), world.steps()), (time, steps));
    }

    /// A 1 m cube centred at `(x, 0, z)`.
    fn cube(x: f64, z: f64) -> BodyDesc {
        BodyDesc::dynamic(Shape::cuboid([1.0; 3])).position([x, 0.0, z])
    }

    /// The shock pass's energy guard undoes the pass island by island: the island it sped up
    /// gets its velocities and impulses back — its contacts with the floor included — and the
    /// island it slowed keeps the pass's, as do the floor and everything else.
    #[test]
    fn the_energy_guard_restores_only_the_islands_that_gained() {
        let mut world = World::builder()
            .body(BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).position([0.0, 0.0, -1.0]))
            .body(cube(-5.0, 0.5))
            .body(cube(-5.0, 1.5))
            .body(cube(5.0, 0.5))
            .body(cube(5.0, 1.5))
            .build()
            .unwrap();
        let mut problem = world.prepare_step(0.01).unwrap().clone();
        assert!(problem.blocks.len() >= 4, "two stacks of two on the floor");
        for (k, row) in problem.rows.iter_mut().enumerate() {
            row.impulse = k as f64;
        }
        let mut set_aside = SolvedState::default();
        set_aside.save(&problem);
        // What a pass might do: the left stack (bodies 1, 2) sped up, the right one (3, 4)
        // slowed, every impulse changed.
        for (k, factor) in [(1, 2.0), (2, 1.5), (3, 0.5), (4, 0.9)] {
            problem.bodies[k].linear_velocity *= factor;
            problem.bodies[k].angular_velocity = Vector3::new(0.0, 0.0, 0.1 * factor);
        }
        for row in &mut problem.rows {
            row.impulse += 0.5;
        }
        let passed = problem.clone();
        let mut islands = solved_islands(&problem);
        set_aside.restore_islands_that_gained(&mut problem, &world.bodies, &mut islands);
        for k in 0..problem.bodies.len() {
            let expected = if k == 1 || k == 2 {
                &set_aside.bodies[k]
            } else {
                &passed.bodies[k]
            };
            assert_eq!(&problem.bodies[k], expected, "body {k}");
        }
        let mut restored = 0;
        for block in &problem.blocks {
            let left = [block.body_a.0, block.body_b.0]
                .iter()
                .any(|&b| b == 1 || b == 2);
            for r in block.rows.clone() {
                let expected = if left {
                    set_aside.impulses[r]
                } else {
                    passed.rows[r].impulse
                };
                assert_eq!(problem.rows[r].impulse, expected, "row {r}");
                restored += usize::from(left);
            }
        }
        assert!(restored > 0 && restored < problem.rows.len());
    }

    /// The islands a PGS solve of `problem` leaves in its workspace.
    fn solved_islands(problem: &Problem<ContactProjection>) -> DisjointSets {
        let mut workspace = PgsWorkspace::default();
        pgs::solve_in_place(&mut problem.clone(), &mut workspace, &PgsParams::default())
            .expect("a solvable problem");
        std::mem::take(workspace.body_islands())
    }

    /// The energy guard weighs the velocity solve's islands as the dynamic bodies' islands
    /// through the blocks: neither the fixed floor nor a kinematic board joins the bodies on
    /// it (a board that moves, too), a stack is one island. Checked against the dynamic
    /// bodies joined afresh.
    #[test]
    fn the_solves_islands_are_the_dynamic_bodies_islands() {
        let mut world = World::builder()
            .body(BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0])).position([0.0, 0.0, -1.0]))
            .body(
                BodyDesc::kinematic(Shape::cuboid([10.0, 4.0, 0.5]))
                    .position([0.0, 0.0, 0.25])
                    .velocity([0.1, 0.0, 0.0]),
            )
            .body(cube(-3.0, 1.0))
            .body(cube(3.0, 1.0))
            .body(cube(10.0, 0.5))
            .body(cube(10.0, 1.5))
            .build()
            .unwrap();
        let problem = world.prepare_step(1.0 / 60.0).unwrap().clone();
        let mut solved = solved_islands(&problem);
        let mut joined = DisjointSets::default();
        let pairs = problem.blocks.iter().map(|b| (b.body_a.0, b.body_b.0));
        sleep::join_dynamic(&mut joined, &world.bodies, pairs);
        let roots = |sets: &mut DisjointSets| (0..6).map(|k| sets.root(k)).collect::<Vec<_>>();
        assert_eq!(roots(&mut solved), [0, 1, 2, 3, 4, 4]);
        assert_eq!(roots(&mut solved), roots(&mut joined));
    }
}
