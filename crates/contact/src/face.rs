//! The face model (the paper's method; Springhead's `PHContactSurface`): one 6-row constraint
//! per contact face at the support polygon's centroid `G`, rows `(f3, f1, f2, τ1, τ2, τ3)` with
//! target relative twist 0, kept physical by [`FaceProjection`]:
//!
//! 1. `f3 ≥ 0`; friction `|(f1, f2)| ≤ μ f3` (the isotropic default) or `|f1|, |f2| ≤ μ f3`
//!    (the paper's eq. 4 box);
//! 2. twist `|τ3 − (p × f)·n| ≤ μ f3 r̄`, `r̄` the mean distance of the polygon from `G`
//!    (exact): bounded about the centre of pressure `p` below, where the friction force `f`
//!    acts, not about `G` as the paper bounds it ([`TwistCentre`]; the same where `p = G`);
//!    with the circle, 1 and 2 are one ellipsoid by default, `|f|² + (τ′/r̄)² ≤ (μ f3)²` with
//!    `τ′ = τ3 − (p × f)·n`, the face's limit surface ([`FrictionLimit`]);
//! 3. tilt: the centre of pressure `p = (−τ2, τ1) / f3` (relative to `G`) must lie in the
//!    polygon; if not, it moves to the nearest point `p̂` and `τ1 = p̂_y f3`, `τ2 = −p̂_x f3`.
//!
//! A segment thus carries only tilt across its line and twist, and a point no torque at all: a
//! segment support is built as a 5-row block with the one tilt it can carry
//! ([`crate::segment`]), and a point support as the vertex model's 3-row block (normal and
//! friction at the point) — the same constraints without the rows their sets bound to zero. On
//! a pile of 1000 cubes half the contacts are points and a quarter segments.
//!
//! The polygon is the support polygon's bearing part: where the depth is within
//! [`bearing_depth`] of the deepest point ([`bearing_contact`]), so a face tilted within the
//! feature angle and standing off at one side is not held at its tilt. Each vertex standing off
//! that part gets a *landing block* after the face's: the vertex model's 3-row block, whose
//! normal row lets the vertex come down to the part's level within the step but not past it
//! (to the other body's surface, while the part itself is still apart: a speculative contact).
//! Unloaded while the face tips or rests, it catches the face as it lands, as the vertex and
//! patch models' far rows do: before, nothing held those vertices, and a 5 cm cube tipping
//! flat at 60 Hz turned past flat in one step and sank 29 mm into the floor. A contact's own
//! landing points ([`Contact::landing`]: a cylinder's rim beside the one rim point it rests on,
//! and the far end of the side line through that point) get the same blocks, so the rim's
//! lowest point can run round it as the cylinder wobbles without the rim beside it sinking in
//! (1 cm before, at 60 Hz), and a small cylinder nearly on its side rocks onto its other rim
//! without swinging it past flat.
//!
//! A support *tipping* about its centre gets landing blocks too. The block's normal row holds
//! `G`, so while its tilt is at the bound (the centre of pressure at an edge, or at a segment's
//! end) nothing holds that edge: the body turns about `G` and the edge sinks by its distance
//! from `G` times the tipping rate in a step. A 1 m cube lying on the floor and tipping at
//! 3 rad/s sank an edge 19 mm in one step at 60 Hz, a cylinder on its side 16 mm, where the
//! vertex model held them. So each vertex of the bearing part that the bodies' relative turn
//! at the step's start would sink below `G` by more than the slop within the step gets a
//! landing block, which lets it come down to the support's deepest level and no further: its
//! normal row carries the impulse that pivots the body about that edge (the cube and the
//! cylinder: within 0.2 mm of their start, as the vertex model; the turn after the impact as
//! the closed form's). A resting or sliding support's vertices move with `G` and get none; a
//! quarter of the slop instead of the whole let more of them through on a settling pile of
//! mixed shapes and left more deep contacts in it.

use nalgebra::{Point2, Vector2, Vector3};
use tatami_geometry::{ConvexPolygon, PolygonKind, Sector};
use tatami_lcp::{Block, LinearSet, Projection, Row, RowBound, SolverBody, TwistCoupling};

use crate::bearing::{bearing_depth, bearing_part};
use crate::jacobian::{
    Witness, angular_jacobian, block_friction_motion, point_jacobian, twist_rate,
};
use crate::limit_surface::{LimitSurface, is_coupled};
use crate::segment::SegmentProjection;
use crate::target::normal_target;
use crate::turns::{bent, friction_bend};
use crate::vertex;
use crate::{
    Contact, ContactError, ContactProjection, ContactRows, ContactSettings, FrictionCone,
    FrictionLimit, Turns, TwistCentre, TwistRadius,
};

/// Rows of a face constraint.
pub const ROWS: usize = 6;

/// Row indices within a face block.
const NORMAL: usize = 0;
const FRICTION_1: usize = 1;
const TILT_1: usize = 3;
const TILT_2: usize = 4;
const TWIST: usize = 5;

/// Below this normal impulse (N·s) a face carries no torque: the centre of pressure is undefined.
pub const MIN_NORMAL_IMPULSE: f64 = 1e-12;

/// A face's or a segment's twist interval `c ± μ r̄ f3` about its `midpoint` `c`
/// (`twist_per_normal` = `μ r̄`, `f3` the normal impulse).
pub(crate) fn twist_interval(midpoint: f64, twist_per_normal: f64, f3: f64) -> (f64, f64) {
    let twist = twist_per_normal * f3;
    (midpoint - twist, midpoint + twist)
}

/// The projection of a face block onto its admissible wrenches.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceProjection {
    /// The support polygon (contact-plane coordinates).
    pub support: ConvexPolygon,
    /// `G`, where the constraint acts.
    pub centre: Point2<f64>,
    /// Force friction coefficient for this step.
    pub friction: f64,
    /// `μ r̄`: the twist bound per unit normal impulse (m).
    pub twist_per_normal: f64,
    /// Box or circular friction bound.
    pub cone: FrictionCone,
    /// Remove the torque's part parallel to the force first (paper's eq. 12 variant).
    pub remove_parallel_torque: bool,
    /// About which point the twist is bounded.
    pub twist_centre: TwistCentre,
    /// Whether the friction force and the twist share one limit surface (with the circle
    /// cone and without the parallel-torque variant).
    pub friction_limit: FrictionLimit,
    /// Fan sector of the last centre of pressure: the next search starts there.
    pub hint: Sector,
    /// The polygon's [clearance](ConvexPolygon::clearance) about `G`: a centre of pressure
    /// nearer `G` than this is inside without a search, as it is on most updates of a resting
    /// face (0 turns the shortcut off).
    pub clearance: f64,
}

impl FaceProjection {
    /// The centre of pressure of impulses `λ`, relative to `G`; `None` when `f3` is too small.
    pub fn centre_of_pressure(impulses: &[f64]) -> Option<Point2<f64>> {
        let f3 = impulses[NORMAL];
        (f3 > MIN_NORMAL_IMPULSE)
            .then(|| Point2::new(-impulses[TILT_2] / f3, impulses[TILT_1] / f3))
    }

    /// The middle of the twist's admissible interval `τ3 ∈ c ± μ r̄ f3` for impulses `λ`:
    /// about the centre of pressure `p` ([`TwistCentre::CentreOfPressure`]), where the friction
    /// force acts, `c` is that force's moment there, `(p × f)·n = −(τ1 f1 + τ2 f2) / f3`, so
    /// the bound holds for the twist about `p`; about `G`, and under the paper's parallel-torque
    /// variant, 0.
    pub fn twist_midpoint(&self, impulses: &[f64]) -> f64 {
        let f3 = impulses[NORMAL];
        if self.twist_centre == TwistCentre::Centroid
            || self.remove_parallel_torque
            || f3 <= MIN_NORMAL_IMPULSE
        {
            return 0.0;
        }
        -(impulses[TILT_1] * impulses[FRICTION_1] + impulses[TILT_2] * impulses[FRICTION_1 + 1])
            / f3
    }

    /// The twist's admissible interval ([`twist_interval`] about [`Self::twist_midpoint`]), as
    /// the projection clamps to it and `admissible` reads it.
    fn twist_bounds(&self, impulses: &[f64]) -> (f64, f64) {
        twist_interval(
            self.twist_midpoint(impulses),
            self.twist_per_normal,
            impulses[NORMAL],
        )
    }

    /// The friction force's and the twist's one limit surface under the normal impulse `f3`,
    /// when they share one ([`FrictionLimit::Coupled`] with the circle, and not under the
    /// parallel-torque variant).
    fn limit_surface(&self, f3: f64) -> Option<LimitSurface> {
        (is_coupled(self.friction_limit, self.cone) && !self.remove_parallel_torque).then_some(
            LimitSurface {
                force: self.friction * f3,
                twist: self.twist_per_normal * f3,
                friction_row: FRICTION_1,
                twist_row: TWIST,
            },
        )
    }

    fn clamp_zmp(&mut self, impulses: &mut [f64]) {
        let f3 = impulses[NORMAL];
        let Some(p) = Self::centre_of_pressure(impulses) else {
            impulses[TILT_1] = 0.0;
            impulses[TILT_2] = 0.0;
            impulses[TWIST] = 0.0;
            return;
        };
        if p.coords.norm_squared() < self.clearance * self.clearance {
            return;
        }
        let absolute = self.centre + p.coords;
        // One search: the nearest point is the point itself when it is inside.
        let (nearest, sector) = self.support.nearest_point_from(&absolute, self.hint);
        self.hint = sector;
        if nearest == absolute {
            return;
        }
        let p_hat = nearest - self.centre;
        impulses[TILT_1] = p_hat.y * f3;
        impulses[TILT_2] = -p_hat.x * f3;
    }
}

impl Projection for FaceProjection {
    #[inline]
    fn project(&mut self, impulses: &mut [f64], changed: usize) {
        impulses[NORMAL] = impulses[NORMAL].max(0.0);
        if let Some(surface) = self.limit_surface(impulses[NORMAL]) {
            // The centre of pressure first: the ellipsoid is about it.
            if matches!(changed, NORMAL | TILT_1 | TILT_2) {
                self.clamp_zmp(impulses);
            }
            surface.clamp(impulses, |λ| self.twist_midpoint(λ));
            return;
        }
        let f3 = impulses[NORMAL];
        self.cone.clamp(&mut impulses[1..3], self.friction * f3);
        if self.remove_parallel_torque {
            let force = nalgebra::Vector3::new(impulses[1], impulses[2], f3);
            let torque = nalgebra::Vector3::new(impulses[3], impulses[4], impulses[5]);
            let f2 = force.norm_squared();
            if f2 > 0.0 {
                let perpendicular = torque - force * (torque.dot(&force) / f2);
                impulses[3..6].copy_from_slice(perpendicular.as_slice());
            }
        }
        // The centre of pressure moves only when f3 or a tilt torque changed.
        if matches!(changed, NORMAL | TILT_1 | TILT_2) || self.remove_parallel_torque {
            self.clamp_zmp(impulses);
        }
        let (low, high) = self.twist_bounds(impulses);
        impulses[TWIST] = impulses[TWIST].max(low).min(high);
    }

    #[inline]
    fn tangent_pair(&self) -> Option<usize> {
        self.cone.tangent_pair(FRICTION_1)
    }

    /// The twist row, coupled to the friction pair by the limit surface, with `p` the centre of
    /// pressure relative to `G` (`G` itself when the twist is bounded there).
    fn twist_coupling(&self, impulses: &[f64]) -> Option<TwistCoupling> {
        let centre = match Self::centre_of_pressure(impulses) {
            Some(p) if self.twist_centre == TwistCentre::CentreOfPressure => [p.x, p.y],
            _ => [0.0, 0.0],
        };
        // Per unit normal impulse: `r̄` is the bounds' ratio whatever the load.
        self.limit_surface(1.0)?.coupling(centre)
    }

    /// `f3`; without it the face carries no friction, twist or tilt.
    #[inline]
    fn leading_normal_rows(&self) -> usize {
        NORMAL + 1
    }

    /// A face of area: its six rows are solved together while the contact sticks with its
    /// centre of pressure inside. Not a segment (built as a face block only under the
    /// parallel-torque variant), whose tilts are bounded to a line that a free step would
    /// always leave; nor under that variant at all.
    fn whole_block(&self) -> bool {
        self.support.kind() == PolygonKind::Polygon && !self.remove_parallel_torque
    }

    fn admissible(&mut self, impulses: &[f64]) -> bool {
        // Loaded (which a NaN is not), so the centre of pressure is defined; unloaded, only the
        // zero wrench is admissible. A cold-started stack's upper contacts start there (bodies
        // falling together leave them nothing to do), and a whole step that lands on zero
        // keeps the block whole for when its load arrives.
        let Some(p) = Self::centre_of_pressure(impulses) else {
            return impulses.iter().all(|&x| x == 0.0);
        };
        let f3 = impulses[NORMAL];
        let within = if let Some(surface) = self.limit_surface(f3) {
            surface.contains(impulses, self.twist_midpoint(impulses))
        } else {
            let (low, high) = self.twist_bounds(impulses);
            self.cone
                .contains(&impulses[FRICTION_1..FRICTION_1 + 2], self.friction * f3)
                && (low..=high).contains(&impulses[TWIST])
        };
        if !within {
            return false;
        }
        if p.coords.norm_squared() < self.clearance * self.clearance {
            return true;
        }
        let location = self
            .support
            .locate_from(&(self.centre + p.coords), self.hint);
        self.hint = location.sector;
        location.inside
    }

    /// Only the normal row is a plain bound: the torques' ZMP constraint is not a product of row
    /// bounds (see [`Projection::linear_set`]).
    fn bound(&self, row: usize) -> Option<RowBound> {
        (row == NORMAL).then_some(RowBound::NonNegative)
    }

    /// The face's admissible wrenches exactly: `(f3, τ1, τ2) = Σ βₖ (1, yₖ, −xₖ)` over the
    /// support polygon's vertices `(xₖ, yₖ)` relative to `G`, `βₖ ≥ 0` — the centre of pressure
    /// `(−τ2, τ1)/f3 = Σ βₖ (xₖ, yₖ)/Σ βₖ` is then any point of the polygon, and `βₖ` is the
    /// normal force at vertex `k` (its condition is that vertex's separation speed ≥ 0). Friction
    /// and twist act at `G`, bounded by `μ f3` and `μ r̄ f3` with `f3 = Σ βₖ`: the twist about
    /// `G` whatever [`TwistCentre`] says, since about the centre of pressure the bound is not
    /// linear (a product of the tilts and the friction), and apart whatever [`FrictionLimit`]
    /// says (an ellipsoid is not a polyhedron). `None` with the parallel-torque variant, which
    /// is not linear.
    fn linear_set(&self, rows: usize) -> Option<LinearSet> {
        if self.remove_parallel_torque {
            return None;
        }
        let mut set = LinearSet::new(rows);
        let vertices: Vec<usize> = self
            .support
            .vertices()
            .iter()
            .map(|v| {
                let r = v - self.centre;
                set.generator(vec![(NORMAL, 1.0), (TILT_1, r.y), (TILT_2, -r.x)])
            })
            .collect();
        let friction: Vec<(usize, f64)> = vertices.iter().map(|&v| (v, self.friction)).collect();
        self.cone.add_to(&mut set, FRICTION_1, &friction);
        let twist = vertices
            .iter()
            .map(|&v| (v, self.twist_per_normal))
            .collect();
        set.symmetric(TWIST, twist);
        Some(set)
    }
}

/// `contact` on the part of its support polygon the face model builds its block on: within
/// [`bearing_depth`] of its deepest point (the polygon cut by one line, the depths being affine
/// across it), unless every vertex is pressed in deeper than the slop, when the overlap is
/// being pushed out over all of it. `None` when that is all of it; a contact it returns is its
/// own bearing contact. Errors when the depths are not one finite value per support vertex.
///
/// ```
/// use nalgebra::{Point2, Point3, Vector3};
/// use tatami_contact::{Contact, ContactFrame, ContactSettings, Material};
/// use tatami_contact::face::bearing_contact;
/// use tatami_geometry::ConvexPolygon;
/// use tatami_lcp::BodyId;
///
/// // A 2 m square face on its edge x = −1, pressed in 1 mm there, its edge x = 1 2 cm up.
/// let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let tilted = Contact {
///     body_a: BodyId(0),
///     body_b: BodyId(1),
///     centre_a: Point3::new(0.0, 0.0, 1.0),
///     centre_b: Point3::new(0.0, 0.0, -1.0),
///     frame: ContactFrame::from_normal(Point3::origin(), Vector3::z())?,
///     support: ConvexPolygon::from_points(&square)?,
///     depths: vec![0.001, -0.02, -0.02, 0.001],
///     material: Material::new(0.5, 0.5, 0.0)?,
///     landing: Vec::new(),
///     bounce_speed: 0.0,
/// };
/// let settings = ContactSettings::default();
/// let bearing = bearing_contact(&tilted, &settings)?.expect("the far edge stands off");
/// assert!(bearing.support.area() < 0.2);
/// assert!(bearing_contact(&bearing, &settings)?.is_none());
/// // Its edge pressed in 5 mm, beyond the 2 mm slop, the far edge still up: the strip alone.
/// let landed = Contact { depths: vec![0.005, -0.02, -0.02, 0.005], ..tilted.clone() };
/// let strip = bearing_contact(&landed, &settings)?.expect("the far edge stands off");
/// assert!(strip.support.area() < 0.2);
/// // Pressed in beyond the slop all over: all of it.
/// let pressed = Contact { depths: vec![0.03, 0.005, 0.005, 0.03], ..tilted.clone() };
/// assert!(bearing_contact(&pressed, &settings)?.is_none());
/// // A depth short: an error naming the count, not a panic.
/// let short = Contact { depths: vec![0.001, -0.02], ..tilted };
/// assert!(bearing_contact(&short, &settings).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn bearing_contact(
    contact: &Contact,
    settings: &ContactSettings,
) -> Result<Option<Contact>, ContactError> {
    Bearing::of(contact, settings).map(|bearing| bearing.part.map(|part| *part))
}

/// A contact's bearing part ([`bearing_contact`]) under one slop, kept for as long as the
/// contact does not change: a pair resting from step to step hands it to
/// [`ContactModel::build_split_bearing`](crate::ContactModel::build_split_bearing) instead of
/// having its polygon cut and its part's `r̄` integrated anew at every build (on a settled pile
/// of 1000 mixed shapes, most of the 2000 contacts are kept from one step to the next, and
/// cutting them was a quarter of building their rows).
///
/// ```
/// use nalgebra::{Point2, Point3, Vector3};
/// use tatami_contact::{Contact, ContactFrame, ContactModel, ContactSettings, Material};
/// use tatami_contact::face::Bearing;
/// use tatami_geometry::ConvexPolygon;
/// use tatami_lcp::{BodyId, Problem, SolverBody};
///
/// let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let tilted = Contact {
///     body_a: BodyId(0),
///     body_b: BodyId(1),
///     centre_a: Point3::new(0.0, 0.0, 1.0),
///     centre_b: Point3::new(0.0, 0.0, -1.0),
///     frame: ContactFrame::from_normal(Point3::origin(), Vector3::z())?,
///     support: ConvexPolygon::from_points(&square)?,
///     depths: vec![0.001, -0.02, -0.02, 0.001],
///     material: Material::new(0.5, 0.5, 0.0)?,
///     landing: Vec::new(),
///     bounce_speed: 0.0,
/// };
/// let settings = ContactSettings::default();
/// let bearing = Bearing::of(&tilted, &settings)?;
/// assert!(bearing.part().is_some_and(|part| part.support.area() < 0.2));
/// // The same rows as cutting it afresh.
/// let build = |bearing: Option<&Bearing>| -> Result<_, tatami_contact::ContactError> {
///     let mut problem = Problem { bodies: vec![SolverBody::fixed(); 2], ..Default::default() };
///     let mut biases = Vec::new();
///     ContactModel::Face.build_split_bearing(&tilted, bearing, 0.01, &settings, &mut problem, &mut biases)?;
///     Ok(problem.rows)
/// };
/// assert_eq!(build(Some(&bearing))?, build(None)?);
/// // One of a pair of other bodies is not read: cut afresh, not a panic.
/// let other = Contact { body_a: BodyId(5), body_b: BodyId(7), ..tilted.clone() };
/// assert_eq!(build(Some(&Bearing::of(&other, &settings)?))?, build(None)?);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Bearing {
    /// The part, `None` when it is the whole contact (boxed: a pair keeps its bearing, and
    /// most are whole).
    part: Option<Box<Contact>>,
    /// The contact's bearing depth.
    within: f64,
    /// The slop it was cut under.
    slop: f64,
}

impl Bearing {
    /// `contact`'s bearing part under `settings`; errors as [`bearing_contact`].
    pub fn of(contact: &Contact, settings: &ContactSettings) -> Result<Self, ContactError> {
        contact.validate_depths()?;
        let within = bearing_depth(&contact.support);
        Ok(Self {
            part: bearing_of_checked(contact, settings, within).map(Box::new),
            within,
            slop: settings.slop,
        })
    }

    /// The bearing part, `None` when it is all of the contact.
    pub fn part(&self) -> Option<&Contact> {
        self.part.as_deref()
    }

    /// Whether it was cut under `settings`' slop (bit for bit).
    pub fn is_for(&self, settings: &ContactSettings) -> bool {
        self.slop.to_bits() == settings.slop.to_bits()
    }

    /// Whether it can be `contact`'s: a part is between the same bodies.
    fn is_of(&self, contact: &Contact) -> bool {
        self.part()
            .is_none_or(|part| (part.body_a, part.body_b) == (contact.body_a, contact.body_b))
    }
}

/// [`bearing_contact`] of a contact whose depths are checked, `within` its bearing depth.
fn bearing_of_checked(
    contact: &Contact,
    settings: &ContactSettings,
    within: f64,
) -> Option<Contact> {
    if contact.depths.iter().all(|&depth| depth > settings.slop) {
        return None;
    }
    bearing_part(contact, within)
}

/// Appends one 6-row block at the centroid of the support polygon's bearing part
/// ([`bearing_contact`]) and each row's penetration bias to `out` —
/// for a segment the 5-row block of [`crate::segment`] (but with the parallel-torque variant,
/// which reads both tilts), for a point support the vertex model's 3-row block (see the module
/// doc); then, when that part is not all of the polygon, a landing block for each vertex off
/// it; one for each vertex of that part a tipping support sinks (module doc); and one for each
/// of the contact's landing points ([`Contact::landing`]). The contact must be validated, and
/// `cut` its [`Bearing`] if given (else it is cut here).
pub(crate) fn build(
    contact: &Contact,
    cut: Option<&Bearing>,
    (dt, turns): (f64, &Turns),
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) {
    let fresh;
    let (bearing, within) = match cut {
        Some(cut) if cut.is_for(settings) && cut.is_of(contact) => (cut.part(), cut.within),
        _ => {
            let within = bearing_depth(&contact.support);
            fresh = bearing_of_checked(contact, settings, within);
            (fresh.as_ref(), within)
        }
    };
    build_bearing(bearing.unwrap_or(contact), (dt, turns), settings, out);
    if bearing.is_some() {
        // The landing blocks (module doc): each vertex off the bearing part at its depth below
        // the part's edge, as a gap its normal row may close in this step and no more.
        let cut = contact.depth() - within;
        for (vertex, &depth) in contact.support.vertices().iter().zip(&contact.depths) {
            if depth < cut {
                let gap = depth - vertex::landing_level(cut);
                let at = (vertex, gap, contact.bounce_speed);
                vertex::build_point(contact, at, None, (dt, turns), settings, out);
            }
        }
    }
    // The vertices of the bearing part that a tipping support sinks, and the contact's landing
    // points beside its support (a rim beside its lowest point; module doc): each may come
    // down to the support's deepest level in this step and no further.
    let tipping = tipping_vertices(bearing.unwrap_or(contact), out.bodies, dt, settings);
    let landing = contact.landing.iter().map(|l| (&l.point, &l.depth));
    vertex::build_landing(contact, tipping.chain(landing), (dt, turns), settings, out);
}

/// The vertices of `contact`'s support (with their depths) that the bodies' relative turn
/// would sink below the support's centroid by more than the slop in a step of `dt`, at the
/// rates the step starts with: a support tipping about its centre (module doc). A resting
/// support's vertices move with its centre to within micrometres a step.
fn tipping_vertices<'a>(
    contact: &'a Contact,
    bodies: &[SolverBody],
    dt: f64,
    settings: &ContactSettings,
) -> impl Iterator<Item = (&'a Point2<f64>, &'a f64)> + use<'a> {
    let (a, b) = (&bodies[contact.body_a.0], &bodies[contact.body_b.0]);
    let frame = &contact.frame;
    let turn = a.angular_velocity - b.angular_velocity;
    let centre = contact.support.centroid();
    // A vertex at `r` from the centre sinks at −((ω_A − ω_B) × r) · n = −(n × (ω_A − ω_B)) · r
    // relative to it: a gradient in the plane.
    let gradient = frame.normal.cross(&turn);
    let gradient = Vector2::new(gradient.dot(&frame.tangent1), gradient.dot(&frame.tangent2));
    let limit = settings.slop;
    (contact.support.vertices().iter().zip(&contact.depths))
        .filter(move |(vertex, _)| -gradient.dot(&(*vertex - centre)) * dt > limit)
}

/// [`build`] on a contact that bears on all of its support polygon.
fn build_bearing(
    contact: &Contact,
    (dt, turns): (f64, &Turns),
    settings: &ContactSettings,
    out: &mut ContactRows<'_>,
) {
    if contact.support.kind() == PolygonKind::Point {
        return vertex::build_support(contact, (dt, turns), settings, out);
    }
    let frame = &contact.frame;
    // A segment takes its 5-row block (crate::segment): the tilt axis across it and the tilt
    // bound; not with the paper's parallel-torque variant, which reads both tilts.
    let segment = (contact.support.kind() == PolygonKind::Segment
        && !settings.remove_parallel_torque)
        .then(|| {
            let v = contact.support.vertices();
            let along = v[1] - v[0];
            let s = (frame.tangent1 * along.x + frame.tangent2 * along.y).normalize();
            (
                frame.normal.cross(&s),
                0.5 * along.norm(),
                along.normalize(),
            )
        });
    let centre = contact.support.centroid();
    let depth = contact.depth();
    let witness = Witness::at(contact, &frame.to_world(&centre), depth);
    let (normal_speed, slip, weld) =
        block_friction_motion(contact, out.bodies, &witness, dt, settings.slip_threshold);
    let bend = turns.bend_at(contact, &witness, (depth, normal_speed), settings);
    // A face on a face keeps its material points together while they stick (its weld);
    // an edge may roll.
    let friction_bend = friction_bend(contact.support.kind() == PolygonKind::Polygon, bend);
    let twist_rate = twist_rate(contact, out.bodies);
    let r_bar = match settings.twist_radius {
        TwistRadius::Exact => contact.support.centroid_mean_distance(),
        TwistRadius::Grid { spacing } => contact.support.mean_distance_grid(&centre, spacing),
    };
    let material = &contact.material;
    let twist_friction = material.friction(twist_rate * r_bar, settings.slip_threshold);
    let target = normal_target(
        depth,
        normal_speed,
        contact.bounce_speed,
        material.restitution,
        dt,
        settings,
    );
    let face_axes = [frame.tangent1, frame.tangent2, frame.normal];
    let segment_axes = segment.map(|(u, _, _)| [u, frame.normal]);
    let torque_axes: &[Vector3<f64>] = match &segment_axes {
        Some(axes) => axes,
        None => &face_axes,
    };
    let rows = 3 + torque_axes.len();
    let start = out.rows.len();
    let force_row = |direction: Vector3<f64>, target: f64, bend: &Vector3<f64>| {
        (
            point_jacobian(contact, &witness, &direction),
            bent(target, &direction, bend, dt),
        )
    };
    let forces = [
        force_row(frame.normal, target.velocity, &bend),
        force_row(frame.tangent1, weld.dot(&frame.tangent1), &friction_bend),
        force_row(frame.tangent2, weld.dot(&frame.tangent2), &friction_bend),
    ];
    let torques = torque_axes.iter().map(|axis| (angular_jacobian(axis), 0.0));
    out.rows.extend(
        forces
            .into_iter()
            .chain(torques)
            .map(|(jacobian, target)| Row {
                jacobian,
                target,
                impulse: 0.0,
            }),
    );
    out.biases.push(target.bias);
    out.biases.extend(std::iter::repeat_n(0.0, rows - 1));
    let friction = material.friction(slip, settings.slip_threshold);
    let twist_per_normal = twist_friction * r_bar;
    let projection = match segment {
        Some((_, half_length, along)) => ContactProjection::Segment(SegmentProjection {
            friction,
            twist_per_normal,
            half_length,
            along,
            twist_centre: settings.twist_centre,
            cone: settings.friction_cone,
            friction_limit: settings.friction_limit,
        }),
        None => ContactProjection::Face(FaceProjection {
            support: contact.support.clone(),
            centre,
            friction,
            twist_per_normal,
            cone: settings.friction_cone,
            remove_parallel_torque: settings.remove_parallel_torque,
            twist_centre: settings.twist_centre,
            friction_limit: settings.friction_limit,
            hint: Sector::default(),
            clearance: contact.support.centroid_clearance(),
        }),
    };
    out.blocks.push(Block {
        body_a: contact.body_a,
        body_b: contact.body_b,
        rows: start..start + rows,
        projection,
    });
}

#[cfg(test)]
mod tests {
    use nalgebra::Point3;
    use tatami_lcp::{BodyId, Problem, SolverBody};

    use super::*;
    use crate::{BEARING_DEPTH, ContactFrame, ContactModel, Landing, Material};

    /// Bodies 0 and 1 touching through the polygon of `support` (plane coordinates of a frame
    /// tilted off the world's axes) at `depths`, with `landing` points.
    fn contact(support: &[Point2<f64>], depths: Vec<f64>, landing: Vec<Landing>) -> Contact {
        Contact {
            body_a: BodyId(0),
            body_b: BodyId(1),
            centre_a: Point3::new(0.1, 0.2, 1.0),
            centre_b: Point3::new(-0.3, 0.1, -1.0),
            frame: ContactFrame::from_normal(
                Point3::new(0.5, -0.2, 0.1),
                Vector3::new(0.2, -0.3, 1.0),
            )
            .unwrap(),
            support: ConvexPolygon::from_points(support).unwrap(),
            depths,
            material: Material::new(0.5, 0.5, 0.0).unwrap(),
            landing,
            bounce_speed: 0.0,
        }
    }

    /// The face model's rows of `contact` between two bodies at rest.
    fn rows_of(
        contact: &Contact,
        dt: f64,
    ) -> Result<Problem<ContactProjection>, crate::ContactError> {
        let mut problem = Problem {
            bodies: vec![SolverBody::fixed(); 2],
            ..Default::default()
        };
        ContactModel::Face.build(contact, dt, &ContactSettings::default(), &mut problem)?;
        Ok(problem)
    }

    /// A 2 m square face with `depths` at its corners (−1, −1), (1, −1), (1, 1), (−1, 1), and
    /// its rows.
    fn face_rows(depths: [f64; 4], dt: f64) -> (Contact, Problem<ContactProjection>) {
        let square =
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
        let contact = contact(&square, depths.to_vec(), Vec::new());
        let problem = rows_of(&contact, dt).unwrap();
        (contact, problem)
    }

    /// A face on its edge x = −1, the edge x = +1 2 cm up: the face's block on the strip along
    /// the touching edge, then a landing block at each far corner, whose normal row acts at the
    /// corner and lets it come down to the strip's level (0.5 mm below the deepest point) within
    /// the step and no further: target `(depth − cut) / dt`. A face lying flat within the
    /// bearing depth gets its block alone.
    #[test]
    fn a_tilted_face_gets_a_landing_block_at_each_corner_off_its_bearing_part() {
        let dt = 0.01;
        let (contact, problem) = face_rows([0.001, -0.02, -0.02, 0.001], dt);
        assert_eq!(problem.blocks.len(), 3);
        assert!(matches!(
            problem.blocks[0].projection,
            ContactProjection::Face(_)
        ));
        let cut = 0.001 - BEARING_DEPTH;
        let corners = &contact.support.vertices()[1..3];
        for (block, corner) in problem.blocks[1..].iter().zip(corners) {
            assert!(matches!(block.projection, ContactProjection::Point(_)));
            let normal = &problem.rows[block.rows.start];
            let arm = contact.frame.to_world(corner) - contact.centre_a;
            let j = &normal.jacobian;
            assert!((j.linear_a.normalize() - contact.frame.normal).norm() < 1e-12);
            assert!((j.angular_a - arm.cross(&j.linear_a)).norm() < 1e-12);
            let target = (-0.02 - cut) / dt;
            assert!((normal.target - target).abs() < 1e-12 * target.abs());
        }
        let (_, flat) = face_rows([0.001, 0.0008, 0.0007, 0.0009], dt);
        assert_eq!(flat.blocks.len(), 1, "bears on all of it");
    }

    /// A face tipping: A turns against B about an axis in the plane, off the frame's tangents,
    /// so the corners on one side sink faster than the centre. Each corner the turn sinks by
    /// more than the slop within the step gets a landing block at its own level (target 0 on a
    /// flat face), after the face's block; the corners rising, or sinking by less, get none.
    /// Turned about the normal (twist), slid along the plane or pushed along the normal as a
    /// whole, the face gets its block alone. Same for a segment, whose ends are its vertices.
    #[test]
    fn a_tipping_support_gets_a_landing_block_at_each_vertex_it_sinks() {
        let dt = 0.01;
        let square =
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
        let flat = contact(&square, vec![0.001; 4], Vec::new());
        let frame = flat.frame;
        let blocks_with = |contact: &Contact, linear: Vector3<f64>, angular: Vector3<f64>| {
            let mut a = SolverBody::fixed();
            a.inv_mass = 1.0;
            a.linear_velocity = linear;
            a.angular_velocity = angular;
            let mut problem = Problem {
                bodies: vec![a, SolverBody::fixed()],
                ..Default::default()
            };
            (ContactModel::Face.build(contact, dt, &ContactSettings::default(), &mut problem))
                .unwrap();
            problem
        };
        // A turn about in-plane axis (1, 2)/√5: a corner at r sinks at ω·((1, 2)/√5 × r)·n.
        let slop = ContactSettings::default().slop;
        let axis = (frame.tangent1 + frame.tangent2 * 2.0) / 5f64.sqrt();
        let sink_rate = |corner: &Point2<f64>| {
            let r = frame.tangent1 * corner.x + frame.tangent2 * corner.y;
            -axis.cross(&r).dot(&frame.normal)
        };
        for rate in [0.5, 2.0] {
            let problem = blocks_with(&flat, Vector3::zeros(), axis * rate);
            let sinking: Vec<_> = (flat.support.vertices().iter())
                .filter(|c| rate * sink_rate(c) * dt > slop)
                .collect();
            assert!(
                !sinking.is_empty() && sinking.len() < 4,
                "{rate}: {sinking:?}"
            );
            assert_eq!(problem.blocks.len(), 1 + sinking.len(), "{rate}");
            for (block, corner) in problem.blocks[1..].iter().zip(&sinking) {
                assert!(matches!(block.projection, ContactProjection::Point(_)));
                let normal = &problem.rows[block.rows.start];
                let arm = frame.to_world(corner) - flat.centre_a;
                let j = &normal.jacobian;
                assert!((j.angular_a - arm.cross(&j.linear_a)).norm() < 1e-12);
                assert_eq!(
                    normal.target, 0.0,
                    "a flat face's corner is held at its level"
                );
            }
        }
        let twist = blocks_with(&flat, Vector3::zeros(), frame.normal * 5.0);
        let slide = blocks_with(
            &flat,
            (frame.tangent1 - frame.normal) * 5.0,
            Vector3::zeros(),
        );
        assert_eq!((twist.blocks.len(), slide.blocks.len()), (1, 1));
        // A segment along the first tangent turned about the second: its ends go opposite ways.
        let ends = [Point2::new(-1.0, 0.0), Point2::new(1.0, 0.0)];
        let segment = contact(&ends, vec![0.001, 0.0005], Vec::new());
        let problem = blocks_with(&segment, Vector3::zeros(), frame.tangent2 * 2.0);
        assert_eq!(problem.blocks.len(), 2);
        assert!(matches!(
            problem.blocks[0].projection,
            ContactProjection::Segment(_)
        ));
        // The end at +t₁ sinks at −(2 t₂ × t₁) · n = 2 m/s, 2 cm in the step: its landing
        // block lets it come down the 0.5 mm to the deepest end's level within the step.
        let normal = &problem.rows[problem.blocks[1].rows.start];
        assert!((normal.target - (0.0005 - 0.001) / dt).abs() < 1e-12);
    }

    /// A point support (a cylinder's rim point, 1.5 mm in) with landing points beside it: the
    /// point's 3-row block, then one landing block per point in order, acting at the point and
    /// letting it come down to the support's depth within the step and no further: target
    /// `(depth − deepest) / dt`. A landing point deeper than the support (no gap) is held where
    /// it is: target 0. Checked under a frame off the world's axes.
    #[test]
    fn landing_points_get_a_landing_block_each_after_the_support() {
        let dt = 0.01;
        let deepest = 0.0015;
        let landing = [
            (0.1, 0.02, -0.003),
            (-0.1, 0.02, -0.001),
            (0.0, -0.03, 0.002),
        ]
        .map(|(x, y, depth)| Landing {
            point: Point2::new(x, y),
            depth,
        });
        let contact = contact(&[Point2::new(0.0, 0.0)], vec![deepest], landing.to_vec());
        let problem = rows_of(&contact, dt).unwrap();
        assert_eq!(problem.blocks.len(), 1 + landing.len());
        for block in &problem.blocks {
            assert!(matches!(block.projection, ContactProjection::Point(_)));
            assert_eq!(block.rows.len(), 3);
        }
        for (block, point) in problem.blocks[1..].iter().zip(&landing) {
            let normal = &problem.rows[block.rows.start];
            let j = &normal.jacobian;
            let arm = contact.frame.to_world(&point.point) - contact.centre_a;
            assert!((j.linear_a.normalize() - contact.frame.normal).norm() < 1e-12);
            assert!((j.angular_a - arm.cross(&j.linear_a)).norm() < 1e-12);
            let target = (point.depth - deepest).min(0.0) / dt;
            assert!((normal.target - target).abs() <= 1e-12 * target.abs());
        }
        // A non-finite landing point is refused, as a non-finite depth is.
        let mut bad = contact.clone();
        bad.landing[1].point.x = f64::NAN;
        let refused = rows_of(&bad, dt);
        assert!(matches!(
            refused,
            Err(crate::ContactError::NonFinite {
                what: "landing point"
            })
        ));
    }

    /// The twist interval by hand, the bounds apart ([`FrictionLimit::Separate`]): a 2 × 2 square about `G`, `f3 = 2` with its centre of
    /// pressure at `p = (0.5, 0)` (`τ2 = −1`) and friction `(0, 0.8)`, whose moment at `p` is
    /// `0.5 · 0.8 = 0.4`; with `μ r̄ = 0.1` the twist about `G` may be `0.4 ± 0.2`, or `±0.2`
    /// about `G` itself. The segment's likewise, its centre of pressure `x = −τu / f3 = 0.5`
    /// along `s = (0.6, 0.8)`: moment `0.5 (0.6 · 0.8 − 0.8 · 0) = 0.24`.
    #[test]
    fn the_twist_is_bounded_about_the_centre_of_pressure() {
        let square =
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
        let support = ConvexPolygon::from_points(&square).unwrap();
        let face = |twist_centre| FaceProjection {
            support: support.clone(),
            centre: Point2::origin(),
            friction: 0.5,
            twist_per_normal: 0.1,
            cone: FrictionCone::Circle,
            remove_parallel_torque: false,
            twist_centre,
            friction_limit: FrictionLimit::Separate,
            hint: Sector::default(),
            clearance: 0.0,
        };
        for (twist_centre, low, high) in [
            (TwistCentre::CentreOfPressure, 0.2, 0.6),
            (TwistCentre::Centroid, -0.2, 0.2),
        ] {
            for (twist, expected) in [
                (-0.5, low),
                (0.0, 0.0f64.max(low)),
                (0.5, 0.5f64.min(high)),
                (0.9, high),
            ] {
                let mut impulses = [2.0, 0.0, 0.8, 0.0, -1.0, twist];
                let mut projection = face(twist_centre);
                projection.project(&mut impulses, TWIST);
                assert!(
                    (impulses[TWIST] - expected).abs() < 1e-15,
                    "{twist_centre:?} {twist}: {impulses:?}"
                );
                assert!(projection.admissible(&impulses), "{twist_centre:?} {twist}");
                assert_eq!(
                    projection.admissible(&[2.0, 0.0, 0.8, 0.0, -1.0, twist]),
                    twist == expected
                );
            }
        }
        let segment = |twist_centre| SegmentProjection {
            friction: 0.5,
            twist_per_normal: 0.1,
            half_length: 1.0,
            along: Vector2::new(0.6, 0.8),
            cone: FrictionCone::Circle,
            twist_centre,
            friction_limit: FrictionLimit::Separate,
        };
        for (twist_centre, centre) in [
            (TwistCentre::CentreOfPressure, 0.24),
            (TwistCentre::Centroid, 0.0),
        ] {
            for twist in [-1.0, 1.0] {
                let mut impulses = [2.0, 0.0, 0.8, -1.0, twist];
                segment(twist_centre).project(&mut impulses, 4);
                assert!(
                    (impulses[4] - (centre + twist * 0.2)).abs() < 1e-15,
                    "{twist_centre:?}: {impulses:?}"
                );
            }
        }
    }
    /// The coupled limit surface by hand: the square above, `f3 = 2`, `μ = 0.5` (`|f| ≤ 1`),
    /// `μ r̄ = 0.1` (`r̄ = 0.2`), centre of pressure `p = (0.5, 0)` and friction `(0, 0.8)`,
    /// whose moment at `p` is 0.4: the twist about `p` may be `±0.2 √(1 − 0.8²) = ±0.12`, so
    /// `τ3 ∈ [0.28, 0.52]` stands. `τ3 = 0.9` (0.5 about `p`) is outside: `(f, τ′/r̄) = (0, 0.8,
    /// 2.5)` scales by `1/√6.89` onto the ball, force and twist together, `p` kept. Then a sweep
    /// of wrenches: each lands on or in the ball, along its own direction, and `admissible`
    /// agrees with the projection.
    #[test]
    fn the_force_and_the_twist_share_one_ellipsoid() {
        let square =
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point2::new(x, y));
        let mut face = FaceProjection {
            support: ConvexPolygon::from_points(&square).unwrap(),
            centre: Point2::origin(),
            friction: 0.5,
            twist_per_normal: 0.1,
            cone: FrictionCone::Circle,
            remove_parallel_torque: false,
            twist_centre: TwistCentre::CentreOfPressure,
            friction_limit: FrictionLimit::Coupled,
            hint: Sector::default(),
            clearance: 0.0,
        };
        for (twist, stands) in [
            (0.27, false),
            (0.28, true),
            (0.4, true),
            (0.52, true),
            (0.53, false),
        ] {
            assert_eq!(
                face.admissible(&[2.0, 0.0, 0.8, 0.0, -1.0, twist]),
                stands,
                "{twist}"
            );
        }
        let mut impulses = [2.0, 0.0, 0.8, 0.0, -1.0, 0.9];
        face.project(&mut impulses, TWIST);
        let shrink = 1.0 / 6.89f64.sqrt();
        let expected = [2.0, 0.0, 0.8 * shrink, 0.0, -1.0, 0.9 * shrink];
        for (got, want) in impulses.iter().zip(expected) {
            assert!((got - want).abs() < 1e-15, "{impulses:?}");
        }
        // The ball's units: (f1, f2, (τ3 − (p × f)·n) / r̄) with p = (0.5, 0) and r̄ = 0.2.
        let ball = |λ: &[f64; 6]| [λ[1], λ[2], (λ[5] - 0.5 * λ[2]) / 0.2];
        for i in 0..9 {
            for j in 0..9 {
                for t in 0..9 {
                    let (f1, f2, twist) = (
                        -1.2 + 0.3 * i as f64,
                        -1.2 + 0.3 * j as f64,
                        -0.6 + 0.15 * t as f64,
                    );
                    let before = [2.0, f1, f2, 0.0, -1.0, twist];
                    let mut after = before;
                    face.project(&mut after, FRICTION_1);
                    let (u, w) = (ball(&before), ball(&after));
                    let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
                    // The wrench 1 N·s from the rim is 1 N·s from it after roundings of 1e-16.
                    assert!(norm(w) <= 1.0 + 1e-12, "{before:?} → {after:?}");
                    let inside = norm(u) <= 1.0;
                    if inside {
                        assert_eq!(after, before);
                    } else {
                        assert!((norm(w) - 1.0).abs() < 1e-12, "{before:?} → {after:?}");
                        for k in 0..3 {
                            assert!((w[k] - u[k] / norm(u)).abs() < 1e-12, "{before:?}");
                        }
                    }
                    assert!(face.admissible(&after), "{before:?} → {after:?}");
                }
            }
        }
    }
}
