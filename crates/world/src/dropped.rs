//! Random scenes of bodies dropped on a floor: one definition for the tests, the experiments
//! and anyone checking the engine on scenes nobody chose (energy, robustness).

use nalgebra::{Point3, UnitQuaternion, Vector3};

use crate::scene::{DEFAULT_DT, Scene};
use crate::{BodyDesc, Shape, WorldSettings};

/// Steps of a dropped scene: 5 s at the default 0.01 s, long enough to drop, bounce, slide
/// and settle.
pub const DROP_STEPS: usize = 500;

/// The xorshift generator of numbers in [0, 1) behind these scenes, for others that must be
/// the same on every machine (benchmarks' scenes).
///
/// ```
/// use tatami_world::dropped::Random;
/// let mut random = Random::new(7);
/// let x = random.between(2.0, 3.0);
/// assert!((2.0..3.0).contains(&x));
/// assert_eq!(Random::new(7).between(2.0, 3.0), x, "the same seed, the same numbers");
/// ```
#[derive(Debug, Clone)]
pub struct Random(u64);

impl Random {
    /// A generator from `seed` (any value; zero is remapped, as xorshift needs a non-zero
    /// state).
    pub fn new(seed: u64) -> Self {
        Self(if seed == 0 {
            0x9e37_79b9_7f4a_7c15
        } else {
            seed
        })
    }

    /// The next number in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next number in [lo, hi).
    pub fn between(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// Shape `k` of a pile of mixed shapes, in turn a box, a sphere, a cylinder and a hull of 10
/// random points, each sized at random within a 1 m cube — the piles that the benchmarks
/// measure beside Rapier and the tests run on more than one thread.
///
/// ```
/// use tatami_world::Shape;
/// use tatami_world::dropped::{Random, mixed_shape};
/// let mut random = Random::new(1);
/// assert!(matches!(mixed_shape(&mut random, 5), Shape::Sphere { .. }));
/// ```
pub fn mixed_shape(random: &mut Random, k: usize) -> Shape {
    match k % 4 {
        0 => Shape::cuboid([
            random.between(0.4, 1.0),
            random.between(0.4, 1.0),
            random.between(0.4, 1.0),
        ]),
        1 => Shape::sphere(random.between(0.25, 0.5)),
        2 => Shape::cylinder(random.between(0.25, 0.5), random.between(0.4, 1.0)),
        _ => Shape::convex(
            (0..10)
                .map(|_| {
                    Point3::new(
                        random.between(-0.5, 0.5),
                        random.between(-0.5, 0.5),
                        random.between(-0.5, 0.5),
                    )
                })
                .collect(),
        ),
    }
}

/// The four fixed walls of a square bin about the vertical axis through the origin: inner
/// half-width `half`, `wall` thick, `height` tall from z = 0, friction 0.5. Put a floor under
/// them.
///
/// ```
/// use tatami_world::dropped::bin_walls;
/// let walls = bin_walls(0.5, 0.05, 1.0);
/// assert!(walls.iter().all(|w| w.fixed && w.position.z == 0.5));
/// ```
pub fn bin_walls(half: f64, wall: f64, height: f64) -> [BodyDesc; 4] {
    let span = 2.0 * half + 2.0 * wall;
    [
        (half + wall / 2.0, 0.0, wall, span),
        (-half - wall / 2.0, 0.0, wall, span),
        (0.0, half + wall / 2.0, 2.0 * half, wall),
        (0.0, -half - wall / 2.0, 2.0 * half, wall),
    ]
    .map(|(x, y, sx, sy)| {
        BodyDesc::fixed(Shape::cuboid([sx, sy, height]))
            .position([x, y, height / 2.0])
            .friction(0.5)
    })
}

/// `count` cubes of side `size` (500 kg/m³, friction 0.5) to pour into a bin of inner
/// half-width `half` ([`bin_walls`]): in layers of as many as fit 1.5 sides apart, the lowest
/// at `from` (m, their centres), each shifted by up to a tenth of its side and turned at
/// random (`seed`). The bin of small cubes that the world's tests and the benchmarks settle
/// in substeps.
///
/// ```
/// use tatami_world::dropped::cubes_to_pour;
/// let cubes = cubes_to_pour(0.1, 0.5, 300, 0.3, 7);
/// assert_eq!(cubes.len(), 300);
/// assert!(cubes.iter().all(|c| c.position.x.abs() < 0.5 && c.position.z >= 0.3));
/// ```
pub fn cubes_to_pour(size: f64, half: f64, count: usize, from: f64, seed: u64) -> Vec<BodyDesc> {
    let mut random = Random::new(seed);
    let row = (2.0 * half / (1.5 * size)).floor().max(1.0) as usize;
    let at = |i: usize| -half + 0.75 * size + i as f64 * 1.5 * size;
    (0..count)
        .map(|k| {
            let (layer, cell) = (k / (row * row), k % (row * row));
            let jitter = 0.1 * size * random.between(-1.0, 1.0);
            let mut component = || random.between(-1.0, 1.0);
            let turn = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                component(),
                component(),
                component(),
                component(),
            ));
            BodyDesc::dynamic(Shape::cuboid([size; 3]))
                .density(500.0)
                .friction(0.5)
                .position([
                    at(cell / row) + jitter,
                    at(cell % row) - jitter,
                    from + layer as f64 * 1.5 * size,
                ])
                .rotation(turn)
        })
        .collect()
}

/// A random shape no wider than 1.6 m, and points of its surface (the vertices; for round
/// shapes, points of their rims) from which its extent along any direction follows.
fn shape(random: &mut Random) -> (Shape, Vec<Vector3<f64>>) {
    let rim = |radius: f64, z: f64| {
        (0..256).map(move |k| {
            let t = std::f64::consts::TAU * f64::from(k) / 256.0;
            Vector3::new(radius * t.cos(), radius * t.sin(), z)
        })
    };
    match (random.unit() * 4.0) as u32 {
        0 => {
            let size = [0.0; 3].map(|_: f64| random.between(0.2, 0.9));
            let corners = (0..8)
                .map(|k| {
                    let sign = |bit: u32| if k & (1 << bit) == 0 { -0.5 } else { 0.5 };
                    Vector3::new(sign(0) * size[0], sign(1) * size[1], sign(2) * size[2])
                })
                .collect();
            (Shape::cuboid(size), corners)
        }
        1 => {
            let radius = random.between(0.1, 0.5);
            (Shape::sphere(radius), vec![Vector3::new(0.0, 0.0, radius)])
        }
        2 => {
            let (radius, height) = (random.between(0.1, 0.5), random.between(0.2, 1.0));
            let rims = rim(radius, -height / 2.0)
                .chain(rim(radius, height / 2.0))
                .collect();
            (Shape::cylinder(radius, height), rims)
        }
        _ => {
            let points: Vec<Vector3<f64>> = (0..8)
                .map(|_| {
                    Vector3::new(
                        random.between(-0.4, 0.4),
                        random.between(-0.4, 0.4),
                        random.between(-0.4, 0.4),
                    )
                })
                .chain([
                    Vector3::new(0.3, 0.0, 0.0),
                    Vector3::new(-0.3, 0.0, 0.0),
                    Vector3::new(0.0, 0.3, 0.0),
                    Vector3::new(0.0, -0.3, 0.0),
                    Vector3::new(0.0, 0.0, 0.3),
                    Vector3::new(0.0, 0.0, -0.3),
                ])
                .collect();
            let hull = Shape::convex(points.iter().map(|p| Point3::from(*p)).collect());
            (hull, points)
        }
    }
}

/// Random scene `seed`: a floor and 1 to 6 bodies of every shape (box, sphere, cylinder, hull) at
/// random poses, densities and frictions, apart. Odd scenes drop them from up
/// to 2 m; even scenes place them at most 1 cm above the floor, where a fall's energy deficit
/// (semi-implicit Euler loses ½g²dt² per unit mass a step in free fall) cannot hide a gain.
pub fn dropped_scene(seed: u64) -> Scene {
    let mut random = Random::new(0x9e37_79b9_7f4a_7c15 ^ (seed + 1).wrapping_mul(0x2545_f491));
    let mut bodies = vec![
        BodyDesc::fixed(Shape::cuboid([40.0, 40.0, 2.0]))
            .name("floor")
            .position([0.0, 0.0, -1.0]),
    ];
    let drop = if seed.is_multiple_of(2) { 0.01 } else { 2.0 };
    let mut placed: Vec<(Point3<f64>, f64)> = Vec::new();
    let count = 1 + (random.unit() * 6.0) as usize;
    while placed.len() < count {
        let (shape, surface) = shape(&mut random);
        let axis = Vector3::new(
            random.unit() - 0.5,
            random.unit() - 0.5,
            random.unit() - 0.5,
        );
        let rotation = UnitQuaternion::from_scaled_axis(axis * 6.0);
        let lowest = match shape {
            // A ball's lowest point is one radius down whatever its turn.
            Shape::Sphere { radius } => -radius,
            _ => surface
                .iter()
                .map(|p| (rotation * p).z)
                .fold(f64::INFINITY, f64::min),
        };
        let radius = surface.iter().map(|p| p.norm()).fold(0.0, f64::max);
        let centre = Point3::new(
            random.between(-2.0, 2.0),
            random.between(-2.0, 2.0),
            -lowest + random.between(0.0, drop),
        );
        if placed
            .iter()
            .any(|(c, r)| (c - centre).norm() < r + radius + 0.01)
        {
            continue;
        }
        bodies.push(
            BodyDesc::dynamic(shape)
                .name(format!("body{}", placed.len()))
                .density(random.between(200.0, 3000.0))
                .friction(random.between(0.1, 1.0))
                .position(centre.into())
                .rotation(rotation),
        );
        placed.push((centre, radius));
    }
    Scene {
        gravity: Vector3::new(0.0, 0.0, -crate::DEFAULT_GRAVITY),
        dt: DEFAULT_DT,
        steps: DROP_STEPS,
        settings: WorldSettings::default(),
        bodies,
        pgs_settings: Vec::new(),
    }
}
