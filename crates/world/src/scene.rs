//! Scene files: JSON in, a validated [`World`] out (the format of DESIGN §6, extended
//! compatibly).
//!
//! Beyond DESIGN §6's fields a scene may set `steps`, `solver` (`"pgs"` or `"direct"`),
//! `tolerance` (m/s, ≥ 0: PGS stops once a sweep changes no row's velocity by this much; see
//! [`crate::PGS_TOLERANCE`], and 0 runs every sweep), `warm_start` and `shock_propagation` (both on by default), `sleeping` (off by default; see
//! [`crate::Sleeping`]), `friction_cone` (`"circle"`,
//! the isotropic default, or `"box"`, the paper's pyramid), `twist_centre`
//! (`"centre_of_pressure"`, the default, or `"centroid"`, the paper's bound; see
//! [`crate::TwistCentre`]), `friction_limit` (`"coupled"`, the default: a face's friction
//! force and twist on one ellipsoid, or `"separate"`, the paper's bounds apart; see
//! [`crate::FrictionLimit`]), `bias_rate`, `slop`,
//! `max_depenetration_speed` (m/s, > 0) and `max_velocity_bias` (m/s, ≥ 0; see
//! [`tatami_contact::ContactSettings`]), `contact_margin` (m, ≥ 0; see
//! [`WorldSettings::contact_margin`]: each pair's, and its slop, are held to its thinner
//! body's thickness below 2 cm), and `max_substeps` (1 to 1000, 8 by default: see
//! [`WorldSettings::max_substeps`]). A body may be `"kinematic": true`: it moves at its
//! `velocity` and `angular_velocity` whatever touches it (see [`BodyDesc::kinematic`]).
//!
//! Every number is checked while it is read, so an invalid scene is rejected with the field's
//! path and the line it is on — unknown fields, unknown shapes, non-finite numbers, sizes, masses
//! or `dt` that are not positive, negative friction, kinetic friction above static, `null` where
//! a value may be given, two bodies of one name, iterations outside 1 to 100 000, a struct
//! written as a positional array, malformed JSON — never a panic. A leading UTF-8 byte-order
//! mark is skipped.
//!
//! Bounds, which keep contact geometry and the solver's arithmetic within f64: lengths from
//! 0.1 mm to 100 km ([`crate::LENGTHS`]), positions within 100 km of the origin
//! ([`crate::POSITION_LIMIT`]), speeds up to 10 km/s and spins up to 10⁴ rad/s
//! ([`crate::SPEED_LIMIT`]), dynamic masses from 1 mg to 10¹² kg ([`crate::MASSES`]), gravity up
//! to 10⁴ m/s² ([`crate::GRAVITY_LIMIT`]), `dt` up to 1 s ([`crate::MAX_TIME_STEP`]), 1 to 100 000
//! iterations ([`crate::MAX_ITERATIONS`]), 1 to 10⁷ steps ([`MAX_STEPS`]), `bias_rate` in
//! [0, 1]. Convex hulls need a volume (non-coplanar points); a twist-radius grid spacing must be
//! positive. With the direct solver, a problem whose dense matrices exceed
//! [`tatami_lcp::direct::DEFAULT_MEMORY_BUDGET`] (512 MiB) is refused at the step that builds it.
//!
//! ```
//! use tatami_world::scene::Scene;
//! let scene = Scene::from_json(r#"{
//!   "dt": 0.01,
//!   "bodies": [
//!     { "name": "ground", "shape": { "box": { "size": [40, 40, 2] } }, "fixed": true,
//!       "position": [0, 0, -1] },
//!     { "name": "cube", "shape": { "box": { "size": [2, 2, 2] } }, "mass": -1.0,
//!       "position": [0, 0, 1] } ] }"#);
//! let error = scene.unwrap_err().to_string();
//! assert!(error.contains("bodies[1].mass") && error.contains("line 6"), "{error}");
//! ```

use std::fmt;
use std::path::{Path, PathBuf};

use nalgebra::{Point3, Unit, UnitQuaternion, Vector3};
use serde::{Deserialize, Deserializer};
use tatami_contact::{ContactModel, FrictionCone, FrictionLimit, TwistCentre};
use tatami_lcp::direct::DirectParams;
use tatami_lcp::pgs::{PgsParams, WarmStart};
use thiserror::Error;

use crate::{BodyDesc, MassSpec, Shape, Solver, World, WorldError, WorldSettings};

/// Steps a scene runs when it does not say.
pub const DEFAULT_STEPS: usize = 1000;

/// Most steps a scene may ask for: 10⁷, 28 hours of simulated time at 100 Hz. A count beyond
/// it is a typo, and would keep the command line busy for years.
pub const MAX_STEPS: usize = 10_000_000;

/// Time step when a scene does not say (s).
pub const DEFAULT_DT: f64 = 0.01;

/// Why a scene was rejected.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{}: {message}", file.display())]
    Io {
        /// The scene file.
        file: PathBuf,
        /// The system's reason.
        message: String,
    },
    /// The text is not a valid scene.
    #[error("{}{field}: {message} (line {line}, column {column})", file.as_ref().map(|f| format!("{}: ", f.display())).unwrap_or_default())]
    Invalid {
        /// The scene file, when read from one.
        file: Option<PathBuf>,
        /// Path of the offending field, e.g. `bodies[1].mass` (`scene` for the whole text).
        field: String,
        /// Line of the error (1-based).
        line: usize,
        /// Column of the error (1-based).
        column: usize,
        /// What is wrong.
        message: String,
    },
}

/// A validated scene: world settings, bodies and how long to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Gravity (m/s²).
    pub gravity: Vector3<f64>,
    /// Time step (s).
    pub dt: f64,
    /// Steps to run.
    pub steps: usize,
    /// World settings (model, solver, contact tuning).
    pub settings: WorldSettings,
    /// Bodies, in order.
    pub bodies: Vec<BodyDesc>,
    /// The PGS-only settings the scene gives explicitly (`iterations`, `tolerance`,
    /// `warm_start`, `shock_propagation`), so that a run with the direct solver can say it
    /// ignores them.
    pub pgs_settings: Vec<&'static str>,
}

impl Scene {
    /// Reads and validates a scene file.
    pub fn load(file: impl AsRef<Path>) -> Result<Self, SceneError> {
        let file = file.as_ref();
        let text = std::fs::read_to_string(file).map_err(|e| SceneError::Io {
            file: file.to_owned(),
            message: e.to_string(),
        })?;
        Self::from_json(&text).map_err(|e| match e {
            SceneError::Invalid {
                field,
                line,
                column,
                message,
                ..
            } => SceneError::Invalid {
                file: Some(file.to_owned()),
                field,
                line,
                column,
                message,
            },
            io => io,
        })
    }

    /// Parses and validates a scene from JSON text.
    pub fn from_json(text: &str) -> Result<Self, SceneError> {
        // A byte-order mark some editors write is not JSON; skipping it keeps lines and columns.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut json = serde_json::Deserializer::from_str(text);
        let raw: Object<RawScene> = serde_path_to_error::deserialize(&mut json).map_err(|e| {
            let field = match e.path().to_string() {
                p if p == "." || p.is_empty() => "scene".to_owned(),
                p => p,
            };
            let inner = e.into_inner();
            let full = inner.to_string();
            let suffix = format!(" at line {} column {}", inner.line(), inner.column());
            SceneError::Invalid {
                file: None,
                field,
                line: inner.line(),
                column: inner.column(),
                message: full.strip_suffix(&suffix).unwrap_or(&full).to_owned(),
            }
        })?;
        json.end().map_err(|e| SceneError::Invalid {
            file: None,
            field: "scene".into(),
            line: e.line(),
            column: e.column(),
            message: "trailing characters after the scene".into(),
        })?;
        Ok(raw.0.into_scene())
    }

    /// A world holding the scene's bodies.
    pub fn world(&self) -> Result<World, WorldError> {
        let builder = World::builder()
            .gravity(self.gravity.into())
            .settings(self.settings);
        self.bodies
            .iter()
            .cloned()
            .fold(builder, |b, body| b.body(body))
            .build()
    }
}

/// A struct read from a JSON object only: serde also reads a struct from an array of its fields
/// in order, and a scene written that way is too easy to get silently wrong.
#[derive(Debug)]
struct Object<T>(T);

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Object<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Fields<T>(std::marker::PhantomData<T>);
        impl<'de, T: Deserialize<'de>> serde::de::Visitor<'de> for Fields<T> {
            type Value = Object<T>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a JSON object of named fields")
            }
            fn visit_map<M: serde::de::MapAccess<'de>>(
                self,
                map: M,
            ) -> Result<Self::Value, M::Error> {
                T::deserialize(serde::de::value::MapAccessDeserializer::new(map)).map(Object)
            }
        }
        d.deserialize_map(Fields(std::marker::PhantomData))
    }
}

/// A finite number.
#[derive(Debug, Clone, Copy)]
struct Finite(f64);
/// A finite number `> 0`.
#[derive(Debug, Clone, Copy)]
struct Positive(f64);
/// A finite number `≥ 0`.
#[derive(Debug, Clone, Copy)]
struct NonNegative(f64);

fn checked<'de, D: Deserializer<'de>>(
    d: D,
    ok: fn(f64) -> bool,
    wanted: &str,
) -> Result<f64, D::Error> {
    let x = f64::deserialize(d)?;
    if x.is_finite() && ok(x) {
        Ok(x)
    } else {
        Err(serde::de::Error::custom(format!(
            "must be {wanted}, got {x}"
        )))
    }
}

impl<'de> Deserialize<'de> for Finite {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        checked(d, |_| true, "finite").map(Self)
    }
}

impl<'de> Deserialize<'de> for Positive {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        checked(d, |x| x > 0.0, "finite and > 0").map(Self)
    }
}

impl<'de> Deserialize<'de> for NonNegative {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        checked(d, |x| x >= 0.0, "finite and ≥ 0").map(Self)
    }
}

fn vector(v: [Finite; 3]) -> Vector3<f64> {
    Vector3::new(v[0].0, v[1].0, v[2].0)
}

/// A contact model by name.
#[derive(Debug, Clone, Copy)]
struct ModelName(ContactModel);

impl<'de> Deserialize<'de> for ModelName {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        ContactModel::from_name(&name).map(Self).ok_or_else(|| {
            let known: Vec<_> = ContactModel::ALL.iter().map(|m| m.name()).collect();
            serde::de::Error::custom(format!(
                "unknown model `{name}`, expected one of {}",
                known.join(", ")
            ))
        })
    }
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "snake_case")]
enum SolverName {
    Pgs,
    Direct,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "snake_case")]
enum ConeName {
    Box,
    Circle,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "snake_case")]
enum TwistCentreName {
    CentreOfPressure,
    Centroid,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "snake_case")]
enum FrictionLimitName {
    Coupled,
    Separate,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    #[serde(default, deserialize_with = "gravity")]
    gravity: Option<Vector3<f64>>,
    #[serde(default, deserialize_with = "time_step")]
    dt: Option<f64>,
    #[serde(default, deserialize_with = "step_count")]
    steps: Option<usize>,
    #[serde(default, deserialize_with = "at_least_one")]
    iterations: Option<usize>,
    #[serde(default, deserialize_with = "present")]
    tolerance: Option<NonNegative>,
    #[serde(default, deserialize_with = "present")]
    model: Option<ModelName>,
    #[serde(default, deserialize_with = "present")]
    solver: Option<SolverName>,
    #[serde(default, deserialize_with = "present")]
    warm_start: Option<bool>,
    #[serde(default, deserialize_with = "present")]
    shock_propagation: Option<bool>,
    #[serde(default, deserialize_with = "present")]
    sleeping: Option<bool>,
    #[serde(default, deserialize_with = "present")]
    friction_cone: Option<ConeName>,
    #[serde(default, deserialize_with = "present")]
    twist_centre: Option<TwistCentreName>,
    #[serde(default, deserialize_with = "present")]
    friction_limit: Option<FrictionLimitName>,
    #[serde(default, deserialize_with = "fraction")]
    bias_rate: Option<f64>,
    #[serde(default, deserialize_with = "present")]
    slop: Option<NonNegative>,
    #[serde(default, deserialize_with = "present")]
    contact_margin: Option<NonNegative>,
    #[serde(default, deserialize_with = "present")]
    max_depenetration_speed: Option<Positive>,
    #[serde(default, deserialize_with = "present")]
    max_velocity_bias: Option<NonNegative>,
    #[serde(default, deserialize_with = "substep_limit")]
    max_substeps: Option<usize>,
    #[serde(deserialize_with = "named_once")]
    bodies: Vec<RawBody>,
}

/// A time step: finite, > 0 and at most [`crate::MAX_TIME_STEP`].
fn time_step<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    checked(
        d,
        |dt| dt > 0.0 && dt <= crate::MAX_TIME_STEP,
        "> 0 and at most 1 s",
    )
    .map(Some)
}

/// Gravity: finite, at most [`crate::GRAVITY_LIMIT`] in size.
fn gravity<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Vector3<f64>>, D::Error> {
    let g = vector(<[Finite; 3]>::deserialize(d)?);
    if g.norm() <= crate::GRAVITY_LIMIT {
        Ok(Some(g))
    } else {
        Err(serde::de::Error::custom(format!(
            "must be at most {:e} m/s² in size, got {:e}",
            crate::GRAVITY_LIMIT,
            g.norm()
        )))
    }
}

/// A fraction in [0, 1].
fn fraction<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    checked(d, |x| (0.0..=1.0).contains(&x), "in [0, 1]").map(Some)
}

/// A step count: 1 to [`MAX_STEPS`].
fn step_count<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
    let n = usize::deserialize(d)?;
    if (1..=MAX_STEPS).contains(&n) {
        Ok(Some(n))
    } else {
        Err(serde::de::Error::custom(format!(
            "must be 1 to {MAX_STEPS}, got {n}"
        )))
    }
}

/// An optional field that, when given, holds a value: `null` is an error, not "absent" (a
/// `"mass": null` once fell back to the default density without a word).
fn present<'de, D: Deserializer<'de>, T: Deserialize<'de>>(d: D) -> Result<Option<T>, D::Error> {
    T::deserialize(d).map(Some)
}

/// The bodies, each name used once (trajectories are keyed by name).
fn named_once<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<RawBody>, D::Error> {
    let bodies = Vec::<RawBody>::deserialize(d)?;
    for (j, body) in bodies.iter().enumerate() {
        let Some(name) = &body.0.name else { continue };
        if let Some(i) = bodies[..j]
            .iter()
            .position(|b| b.0.name.as_deref() == Some(name.as_str()))
        {
            return Err(serde::de::Error::custom(format!(
                "bodies[{i}] and bodies[{j}] are both named `{name}`; names must differ"
            )));
        }
    }
    Ok(bodies)
}

fn at_least_one<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
    one_to(usize::deserialize(d)?, crate::settings::MAX_ITERATIONS)
}

fn substep_limit<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
    one_to(usize::deserialize(d)?, crate::SUBSTEP_LIMIT)
}

/// `n` if it is from 1 to `most`, else the error naming the range.
fn one_to<E: serde::de::Error>(n: usize, most: usize) -> Result<Option<usize>, E> {
    if (1..=most).contains(&n) {
        Ok(Some(n))
    } else {
        Err(E::custom(format!("must be 1 to {most}, got {n}")))
    }
}

impl RawScene {
    fn into_scene(self) -> Scene {
        let mut settings = WorldSettings::default();
        if let Some(ModelName(model)) = self.model {
            settings.model = model;
        }
        let Solver::Pgs(default_pgs) = Solver::default() else {
            unreachable!("the default solver is PGS")
        };
        let pgs = PgsParams {
            iterations: self.iterations.unwrap_or(default_pgs.iterations),
            tolerance: self.tolerance.map_or(default_pgs.tolerance, |t| t.0),
            warm_start: match self.warm_start {
                Some(true) => WarmStart::On,
                Some(false) => WarmStart::Off,
                None => default_pgs.warm_start,
            },
            ..default_pgs
        };
        settings.solver = match self.solver {
            Some(SolverName::Direct) => Solver::Direct(DirectParams::default()),
            Some(SolverName::Pgs) | None => Solver::Pgs(pgs),
        };
        if let Some(cone) = self.friction_cone {
            settings.contact.friction_cone = match cone {
                ConeName::Box => FrictionCone::Box,
                ConeName::Circle => FrictionCone::Circle,
            };
        }
        if let Some(centre) = self.twist_centre {
            settings.contact.twist_centre = match centre {
                TwistCentreName::CentreOfPressure => TwistCentre::CentreOfPressure,
                TwistCentreName::Centroid => TwistCentre::Centroid,
            };
        }
        if let Some(limit) = self.friction_limit {
            settings.contact.friction_limit = match limit {
                FrictionLimitName::Coupled => FrictionLimit::Coupled,
                FrictionLimitName::Separate => FrictionLimit::Separate,
            };
        }
        if let Some(rate) = self.bias_rate {
            settings.contact.bias_rate = rate;
        }
        if let Some(slop) = self.slop {
            settings.contact.slop = slop.0;
        }
        if let Some(margin) = self.contact_margin {
            settings.contact_margin = margin.0;
        }
        if let Some(speed) = self.max_depenetration_speed {
            settings.contact.max_depenetration_speed = speed.0;
        }
        if let Some(speed) = self.max_velocity_bias {
            settings.contact.max_velocity_bias = speed.0;
        }
        if let Some(on) = self.shock_propagation {
            settings.shock_propagation = on;
        }
        if let Some(n) = self.max_substeps {
            settings.max_substeps = n;
        }
        if self.sleeping == Some(true) {
            settings.sleeping = crate::Sleeping::on();
        }
        let given = [
            ("iterations", self.iterations.is_some()),
            ("tolerance", self.tolerance.is_some()),
            ("warm_start", self.warm_start.is_some()),
            ("shock_propagation", self.shock_propagation.is_some()),
        ];
        Scene {
            pgs_settings: given
                .into_iter()
                .filter_map(|(name, set)| set.then_some(name))
                .collect(),
            gravity: self
                .gravity
                .unwrap_or(Vector3::new(0.0, 0.0, -crate::DEFAULT_GRAVITY)),
            dt: self.dt.unwrap_or(DEFAULT_DT),
            steps: self.steps.unwrap_or(DEFAULT_STEPS),
            settings,
            bodies: self.bodies.into_iter().map(|b| b.0).collect(),
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
enum RawShape {
    Box { size: [Positive; 3] },
    Sphere { radius: Positive },
    Cylinder { radius: Positive, height: Positive },
    Convex { points: Vec<[Finite; 3]> },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRotation {
    axis: [Finite; 3],
    angle_deg: Finite,
}

/// A body checked as a whole once its fields are read (so the error still has a line).
#[derive(Debug)]
struct RawBody(BodyDesc);

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyFields {
    #[serde(default, deserialize_with = "present")]
    name: Option<String>,
    shape: RawShape,
    #[serde(default)]
    fixed: bool,
    #[serde(default)]
    kinematic: bool,
    #[serde(default, deserialize_with = "present")]
    mass: Option<Positive>,
    #[serde(default, deserialize_with = "present")]
    density: Option<Positive>,
    #[serde(default, deserialize_with = "present")]
    inertia: Option<[Positive; 3]>,
    #[serde(default, deserialize_with = "present")]
    position: Option<[Finite; 3]>,
    #[serde(default, deserialize_with = "present")]
    rotation: Option<Object<RawRotation>>,
    #[serde(default, deserialize_with = "present")]
    velocity: Option<[Finite; 3]>,
    #[serde(default, deserialize_with = "present")]
    angular_velocity: Option<[Finite; 3]>,
    #[serde(default, deserialize_with = "present")]
    friction: Option<NonNegative>,
    #[serde(default, deserialize_with = "present")]
    static_friction: Option<NonNegative>,
    #[serde(default, deserialize_with = "present")]
    kinetic_friction: Option<NonNegative>,
    #[serde(default, deserialize_with = "present")]
    restitution: Option<NonNegative>,
}

impl<'de> Deserialize<'de> for RawBody {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let Object(fields) = Object::<BodyFields>::deserialize(d)?;
        fields
            .into_desc()
            .map(Self)
            .map_err(serde::de::Error::custom)
    }
}

/// A body-level inconsistency, reported at the end of the body's object.
struct BodyProblem(String);

impl fmt::Display for BodyProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl BodyFields {
    fn into_desc(self) -> Result<BodyDesc, BodyProblem> {
        let shape = match self.shape {
            RawShape::Box { size } => Shape::cuboid(size.map(|s| s.0)),
            RawShape::Sphere { radius } => Shape::sphere(radius.0),
            RawShape::Cylinder { radius, height } => Shape::cylinder(radius.0, height.0),
            RawShape::Convex { points } => Shape::convex(
                points
                    .into_iter()
                    .map(|p| Point3::from(vector(p)))
                    .collect(),
            ),
        };
        let mut desc = BodyDesc::dynamic(shape);
        desc.fixed = self.fixed;
        desc.kinematic = self.kinematic;
        desc.name = self.name;
        desc.mass = match (self.mass, self.density) {
            (Some(_), Some(_)) => {
                return Err(BodyProblem("give `mass` or `density`, not both".into()));
            }
            (Some(m), None) => MassSpec::Mass(m.0),
            (None, Some(rho)) => MassSpec::Density(rho.0),
            (None, None) => desc.mass,
        };
        desc.inertia = self.inertia.map(|i| Vector3::new(i[0].0, i[1].0, i[2].0));
        if let Some(p) = self.position {
            desc.position = vector(p).into();
        }
        if let Some(Object(r)) = self.rotation {
            // Scaled by its largest component first: the norm of [1e200, 1e200, 0] overflows.
            let axis = vector(r.axis);
            let axis = Unit::try_new(axis / axis.amax().max(f64::MIN_POSITIVE), 0.0)
                .ok_or_else(|| BodyProblem("rotation.axis must not be zero".into()))?;
            desc.rotation = UnitQuaternion::from_axis_angle(&axis, r.angle_deg.0.to_radians());
        }
        if let Some(v) = self.velocity {
            desc.velocity = vector(v);
        }
        if let Some(w) = self.angular_velocity {
            desc.angular_velocity = vector(w);
        }
        if let Some(mu) = self.friction {
            desc = desc.friction(mu.0);
        }
        if let Some(mu) = self.static_friction {
            desc.static_friction = mu.0;
        }
        if let Some(mu) = self.kinetic_friction {
            desc.kinetic_friction = mu.0;
        }
        if let Some(e) = self.restitution {
            desc.restitution = e.0;
        }
        desc.validate().map_err(|e| BodyProblem(e.to_string()))?;
        Ok(desc)
    }
}
