//! The direct solver on random piles: `cargo run --release -p tatami-world --example
//! direct_piles -- [SEEDS]` (150 by default). Each seed's dropped scene (`tatami_world::dropped`)
//! runs under PGS to step 20 + seed mod 131, then the direct solver solves its next problem
//! under each model. Prints every failure, then per size of the standard LCP: solves, median
//! pivots and time, how many needed another Lemke path or a regularisation, and failures.

use std::time::Instant;

use tatami_lcp::Projection;
use tatami_world::dropped::dropped_scene;
use tatami_world::{ContactModel, DirectParams};

/// Upper ends of the size classes (standard-LCP unknowns).
const CLASSES: [usize; 5] = [50, 200, 500, 1000, usize::MAX];

#[derive(Default)]
struct Class {
    pivots: Vec<usize>,
    millis: Vec<f64>,
    retried: usize,
    regularised: usize,
    failed: usize,
}

fn median<T: Copy + PartialOrd>(values: &mut [T]) -> Option<T> {
    values.sort_by(|a, b| a.partial_cmp(b).expect("no NaN"));
    values.get(values.len() / 2).copied()
}

fn main() {
    let seeds: u64 = std::env::args()
        .nth(1)
        .map_or(150, |s| s.parse().expect("a number of seeds"));
    let mut classes: Vec<Class> = CLASSES.iter().map(|_| Class::default()).collect();
    for seed in 0..seeds {
        for model in ContactModel::ALL {
            let mut scene = dropped_scene(seed);
            scene.settings.model = model;
            let mut world = scene.world().expect("dropped scenes are valid");
            for _ in 0..20 + seed % 131 {
                world.step(scene.dt).expect("PGS steps");
            }
            let mut problem = world.prepare_step(scene.dt).expect("valid").clone();
            let start = Instant::now();
            let result = tatami_lcp::direct::solve(&mut problem, &DirectParams::default());
            let millis = start.elapsed().as_secs_f64() * 1e3;
            let unknowns: usize = problem
                .blocks
                .iter()
                .filter_map(|b| b.projection.linear_set(b.rows.len()))
                .map(|set| set.variables())
                .sum();
            let class = &mut classes[CLASSES.iter().position(|&c| unknowns <= c).unwrap()];
            match result {
                Ok(info) => {
                    class.pivots.push(info.pivots);
                    class.millis.push(millis);
                    class.retried += usize::from(info.attempts > 1);
                    class.regularised += usize::from(info.regularisation.is_some());
                }
                Err(error) => {
                    class.failed += 1;
                    println!("seed {seed} {model:?} ({unknowns} unknowns): {error}");
                }
            }
        }
    }
    println!(
        "| unknowns | solves | median pivots | median time | retried | regularised | failed |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut low = 0;
    for (class, &high) in classes.iter_mut().zip(&CLASSES) {
        let solves = class.pivots.len() + class.failed;
        let pivots = median(&mut class.pivots).map_or("–".into(), |p| p.to_string());
        let time = median(&mut class.millis).map_or("–".into(), |t| format!("{t:.2} ms"));
        let range = if high == usize::MAX {
            format!("> {low}")
        } else {
            format!("{}–{high}", low + 1)
        };
        println!(
            "| {range} | {solves} | {pivots} | {time} | {} | {} | {} |",
            class.retried, class.regularised, class.failed
        );
        low = high;
    }
}
