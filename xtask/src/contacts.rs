//! Contact CSV (`cargo xtask simulate --contacts FILE`): one row per contact per recorded step,
//! the force-sensor read-out of [`World::contact_wrenches`] in world units.
//!
//! Columns: `step`, `time` (s); `body_a`, `body_b` (names; A is pushed along `+n`); `model`;
//! `normal_force` (N, ≥ 0); `friction_1`, `friction_2` (N, along the contact frame's tangents);
//! `twist_torque` (N m, about `n` at the centre of pressure); `cop_x`, `cop_y`, `cop_z` (the
//! centre of pressure, world m); `normal_x`, `normal_y`, `normal_z` (unit `n`, from B into A);
//! `vertices` (the support polygon's vertex count). Forces are the last step's impulses divided
//! by its `dt`, acting on A (B feels the opposite). Step 0 has no contacts: they are found by a
//! step.

use std::io::Write;

use tatami_world::World;

use crate::trajectory::shortest;

/// The exact header of a contact file.
pub const HEADER: [&str; 16] = [
    "step",
    "time",
    "body_a",
    "body_b",
    "model",
    "normal_force",
    "friction_1",
    "friction_2",
    "twist_torque",
    "cop_x",
    "cop_y",
    "cop_z",
    "normal_x",
    "normal_y",
    "normal_z",
    "vertices",
];

/// Writes contact rows to any output.
pub struct ContactWriter<W: Write> {
    csv: csv::Writer<W>,
}

impl<W: Write> ContactWriter<W> {
    /// A writer that has already written the header.
    pub fn new(output: W) -> csv::Result<Self> {
        let mut csv = csv::Writer::from_writer(output);
        csv.write_record(HEADER)?;
        Ok(Self { csv })
    }

    /// One row per contact of `world`'s last step, as step `step`.
    pub fn record(&mut self, step: usize, world: &World) -> csv::Result<()> {
        let model = world.settings().model.name();
        let name = |id| world.body_by_id(id).map_or("?", |b| b.name());
        for wrench in world.contact_wrenches() {
            let p = wrench.centre_of_pressure;
            let n = wrench.normal;
            let mut record = vec![
                step.to_string(),
                shortest(world.time()),
                name(wrench.body_a).to_owned(),
                name(wrench.body_b).to_owned(),
                model.to_owned(),
            ];
            record.extend(
                [
                    wrench.normal_force,
                    wrench.friction_force[0],
                    wrench.friction_force[1],
                    wrench.twist_torque,
                    p.x,
                    p.y,
                    p.z,
                    n.x,
                    n.y,
                    n.z,
                ]
                .map(shortest),
            );
            record.push(wrench.support.len().to_string());
            self.csv.write_record(&record)?;
        }
        Ok(())
    }

    /// Flushes the output.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.csv.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tatami_world::{BodyDesc, Shape};

    /// A cube resting off-centre on a floor: after the header, one row naming both bodies, with
    /// the cube's weight as the normal force and the centre of pressure under its centre.
    #[test]
    fn a_resting_cube_writes_its_weight_under_its_centre() {
        let mut world = World::builder()
            .body(
                BodyDesc::fixed(Shape::cuboid([4.0, 4.0, 1.0]))
                    .name("floor")
                    .position([0.0, 0.0, -0.5]),
            )
            .body(
                BodyDesc::dynamic(Shape::cuboid([0.5; 3]))
                    .name("cube")
                    .mass(3.0)
                    .position([0.7, -0.3, 0.25]),
            )
            .build()
            .unwrap();
        for _ in 0..100 {
            world.step(0.01).unwrap();
        }
        let mut writer = ContactWriter::new(Vec::new()).unwrap();
        writer.record(100, &world).unwrap();
        let bytes = writer.csv.into_inner().unwrap();
        let mut reader = csv::Reader::from_reader(bytes.as_slice());
        assert!(reader.headers().unwrap().iter().eq(HEADER));
        let rows: Vec<_> = reader.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 1);
        let row = &rows[0];
        assert_eq!(
            (&row[0], &row[2], &row[3], &row[4]),
            ("100", "floor", "cube", "face")
        );
        let number = |k: usize| row[k].parse::<f64>().unwrap();
        // Converged at rest to far below these bounds (see the world's control tests).
        assert!((number(5) - 3.0 * 9.8).abs() < 1e-6);
        assert!((number(9) - 0.7).abs() < 1e-6 && (number(10) + 0.3).abs() < 1e-6);
        assert!(number(11).abs() < 1e-9, "on the floor's top");
        assert_eq!(&row[15], "4");
    }
}
