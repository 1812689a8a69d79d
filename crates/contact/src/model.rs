//! Choice of contact model.

use tatami_lcp::Problem;

use crate::{
    Contact, ContactError, ContactProjection, ContactRows, ContactSettings, Turns, face, patch,
    vertex,
};

/// Which rows a contact becomes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactModel {
    /// One point constraint (3 rows) per support-polygon vertex (the paper's baseline).
    Vertex,
    /// Normal rows per vertex, friction and twist at the friction centre (Rapier, Jolt, Box3D).
    Patch,
    /// One 6-row constraint per face with torsional friction and the ZMP bound (the paper's
    /// method; the default); 5 rows on a segment, 3 on a point.
    #[default]
    Face,
}

impl ContactModel {
    /// Every model, for sweeps and comparisons.
    pub const ALL: [ContactModel; 3] = [
        ContactModel::Vertex,
        ContactModel::Patch,
        ContactModel::Face,
    ];

    /// The model's name as scenes and the command line spell it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Vertex => "vertex",
            Self::Patch => "patch",
            Self::Face => "face",
        }
    }

    /// The model named `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Appends the contact's rows and blocks to `problem`, each normal row's target including
    /// its penetration bias (Baumgarte stabilisation), so the problem is complete for one solve.
    ///
    /// The bodies' velocities in `problem` are read as those at the start of the step (before
    /// external forces): they decide static or kinetic friction and restitution.
    pub fn build(
        self,
        contact: &Contact,
        dt: f64,
        settings: &ContactSettings,
        problem: &mut Problem<ContactProjection>,
    ) -> Result<(), ContactError> {
        let first = problem.rows.len();
        let mut biases = Vec::new();
        self.build_split(contact, dt, settings, problem, &mut biases)?;
        for (row, bias) in problem.rows[first..].iter_mut().zip(biases) {
            row.target += bias;
        }
        Ok(())
    }

    /// As [`ContactModel::build`], but the penetration push beyond
    /// [`ContactSettings::max_velocity_bias`] stays out of the targets: one value per appended
    /// row is appended to `biases` (0 but on normal rows), for a solver that removes it in a
    /// position pass of its own (split impulses), so that part never becomes velocity.
    pub fn build_split(
        self,
        contact: &Contact,
        dt: f64,
        settings: &ContactSettings,
        problem: &mut Problem<ContactProjection>,
        biases: &mut Vec<f64>,
    ) -> Result<(), ContactError> {
        self.build_split_bearing(contact, None, dt, settings, problem, biases)
    }

    /// As [`ContactModel::build_split`], with the face model's bearing part of `contact` already
    /// cut ([`face::Bearing`], kept by a caller while the contact does not change): the rows
    /// are the same. `bearing` must be the contact's own; one cut under another slop, or
    /// between other bodies, is cut again, and the other models do not read it.
    pub fn build_split_bearing(
        self,
        contact: &Contact,
        bearing: Option<&face::Bearing>,
        dt: f64,
        settings: &ContactSettings,
        problem: &mut Problem<ContactProjection>,
        biases: &mut Vec<f64>,
    ) -> Result<(), ContactError> {
        self.build_rows(
            contact,
            bearing,
            dt,
            settings,
            &mut ContactRows::of(problem, biases),
        )
    }

    /// As [`ContactModel::build_split_bearing`], appending to `out`: rows, blocks and biases
    /// that may be a piece of the problem built apart from the rest (on another thread, say)
    /// against the same bodies, and joined to it afterwards ([`ContactRows::append`]).
    pub fn build_rows(
        self,
        contact: &Contact,
        bearing: Option<&face::Bearing>,
        dt: f64,
        settings: &ContactSettings,
        out: &mut ContactRows<'_>,
    ) -> Result<(), ContactError> {
        self.build_rows_turned(contact, bearing, dt, &Turns::default(), settings, out)
    }

    /// As [`ContactModel::build_rows`], for bodies that turn their shapes by `turns` over the
    /// step: each point row's target takes off how far the turns bend its points' paths off
    /// straight lines ([`crate::turns`]; a top spinning on its tip falls over without it). With
    /// no turns, the same rows.
    ///
    /// ```
    /// use nalgebra::{Matrix3, Point2, Point3, Vector3};
    /// use tatami_contact::{
    ///     Contact, ContactFrame, ContactModel, ContactRows, ContactSettings, Material, Turns,
    /// };
    /// use tatami_geometry::ConvexPolygon;
    /// use tatami_lcp::{BodyId, Problem, SolverBody};
    ///
    /// // A body resting 1 mm deep on one point 1 m below its centre, on the fixed ground.
    /// let mut body = SolverBody::fixed();
    /// body.inv_mass = 1.0;
    /// body.inv_inertia_world = Matrix3::identity();
    /// let contact = Contact {
    ///     body_a: BodyId(0),
    ///     body_b: BodyId(1),
    ///     centre_a: Point3::new(0.0, 0.0, 1.0),
    ///     centre_b: Point3::new(0.0, 0.0, -1.0),
    ///     frame: ContactFrame::from_normal(Point3::origin(), Vector3::z())?,
    ///     support: ConvexPolygon::from_points(&[Point2::origin()])?,
    ///     depths: vec![0.001],
    ///     material: Material::new(0.5, 0.5, 0.0)?,
    ///     landing: Vec::new(),
    ///     bounce_speed: 0.0,
    /// };
    /// let (dt, settings) = (0.01, ContactSettings::default());
    /// let target = |turns: &Turns| -> Result<f64, Box<dyn std::error::Error>> {
    ///     let bodies = vec![body, SolverBody::fixed()];
    ///     let mut problem = Problem { bodies, ..Default::default() };
    ///     let mut biases = Vec::new();
    ///     let mut out = ContactRows::of(&mut problem, &mut biases);
    ///     ContactModel::Face.build_rows_turned(&contact, None, dt, turns, &settings, &mut out)?;
    ///     Ok(problem.rows[0].target)
    /// };
    /// // Turned by 0.01 rad about x over the step, its point (its own, half the depth below the
    /// // plane: 1.0005 m from its centre) swings up by 1.0005 (1 − cos 0.01) = 50 µm off the
    /// // straight line: its normal row may close that much more.
    /// let turns = Turns { a: Vector3::new(0.01, 0.0, 0.0), b: Vector3::zeros() };
    /// let swing = 1.0005 * (1.0 - 0.01f64.cos());
    /// assert!((target(&turns)? - (target(&Turns::default())? - swing / dt)).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn build_rows_turned(
        self,
        contact: &Contact,
        bearing: Option<&face::Bearing>,
        dt: f64,
        turns: &Turns,
        settings: &ContactSettings,
        out: &mut ContactRows<'_>,
    ) -> Result<(), ContactError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(ContactError::InvalidTimeStep(dt));
        }
        if !(turns.a.iter().chain(turns.b.iter())).all(|x| x.is_finite()) {
            return Err(ContactError::NonFinite { what: "turn" });
        }
        contact.validate(out.bodies.len())?;
        match self {
            Self::Vertex => vertex::build(contact, (dt, turns), settings, out),
            Self::Patch => patch::build(contact, (dt, turns), settings, out),
            Self::Face => face::build(contact, bearing, (dt, turns), settings, out),
        }
        Ok(())
    }

    /// The support vertex that row `row` (counted from the contact's first row) of
    /// [`ContactModel::build`] acts at, for a contact of `vertices` support vertices; `None` for
    /// rows of the whole contact (the face model's, the patch model's friction and twist) and
    /// for a landing point's ([`Contact::landing`](crate::Contact::landing)).
    /// With the vertex's feature id this names a row across steps, for exact warm starting of
    /// the vertex and patch models; the face model's block is carried whole instead, as a
    /// [`ContactImpulse`](crate::ContactImpulse).
    pub fn row_vertex(self, vertices: usize, row: usize) -> Option<usize> {
        match self {
            Self::Vertex => Some(row / vertex::ROWS_PER_VERTEX).filter(|&v| v < vertices),
            Self::Patch => (row < vertices).then_some(row),
            Self::Face => None,
        }
    }
}
