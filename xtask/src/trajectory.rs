//! Trajectory CSV (DESIGN §6): one row per dynamic body per recorded step, world frame, every
//! number in its shortest form that reads back to the same `f64`.

use std::io::Write;

use tatami_world::World;

/// The exact header of a trajectory file.
pub const HEADER: [&str; 16] = [
    "step", "time", "body", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy",
    "wz",
];

/// Writes trajectory rows to any output.
pub struct TrajectoryWriter<W: Write> {
    csv: csv::Writer<W>,
}

impl<W: Write> TrajectoryWriter<W> {
    /// A writer that has already written the header.
    pub fn new(output: W) -> csv::Result<Self> {
        let mut csv = csv::Writer::from_writer(output);
        csv.write_record(HEADER)?;
        Ok(Self { csv })
    }

    /// One row per dynamic body of `world` at step `step`.
    pub fn record(&mut self, step: usize, world: &World) -> csv::Result<()> {
        let time = world.time();
        for body in world.bodies().iter().filter(|b| !b.is_fixed()) {
            let p = body.position();
            let q = body.rotation();
            let v = body.linear_velocity();
            let w = body.angular_velocity();
            let numbers = [
                time, p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z,
            ];
            let mut record = Vec::with_capacity(HEADER.len());
            record.push(step.to_string());
            record.push(shortest(numbers[0]));
            record.push(body.name().to_owned());
            record.extend(numbers[1..].iter().map(|&x| shortest(x)));
            self.csv.write_record(&record)?;
        }
        Ok(())
    }

    /// Flushes the output.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.csv.flush()
    }
}

/// The shortest decimal form of `x` that parses back to exactly `x` (`Debug` of `f64`).
pub(crate) fn shortest(x: f64) -> String {
    format!("{x:?}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly() {
        for x in [
            0.1,
            1.0 / 3.0,
            -2.5e-300,
            1e21,
            std::f64::consts::PI * 1e8,
            0.0,
        ] {
            assert_eq!(shortest(x).parse::<f64>().unwrap(), x);
        }
    }
}
