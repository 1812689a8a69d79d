//! CSV output of the experiments: a fixed header, then one record per measurement, every number
//! in its shortest exact form.

use std::fs::File;
use std::path::Path;

use crate::trajectory::shortest;

/// A record from fields of mixed types: `record![model, n, time]`.
macro_rules! record {
    ($($field:expr),* $(,)?) => {
        [$($crate::experiments::table::Field::from($field)),*]
    };
}
pub(crate) use record;

/// A CSV file being written.
pub struct Table {
    csv: csv::Writer<File>,
    name: String,
    columns: usize,
}

/// One field of a record.
pub enum Field {
    /// A number, written exactly.
    Number(f64),
    /// A count.
    Count(usize),
    /// Text (model names, yes/no).
    Text(String),
    /// No value (e.g. a closed form past its domain).
    Empty,
}

impl From<f64> for Field {
    fn from(x: f64) -> Self {
        Field::Number(x)
    }
}

impl From<usize> for Field {
    fn from(n: usize) -> Self {
        Field::Count(n)
    }
}

impl From<&str> for Field {
    fn from(text: &str) -> Self {
        Field::Text(text.to_owned())
    }
}

impl From<bool> for Field {
    fn from(yes: bool) -> Self {
        Field::Text(if yes { "yes" } else { "no" }.to_owned())
    }
}

impl From<Option<f64>> for Field {
    fn from(x: Option<f64>) -> Self {
        x.map_or(Field::Empty, Field::Number)
    }
}

impl Table {
    /// Creates `dir/name` and writes `header`.
    pub fn create(dir: &Path, name: &str, header: &[&str]) -> Result<Self, String> {
        let path = dir.join(name);
        let file = File::create(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut csv = csv::Writer::from_writer(file);
        csv.write_record(header)
            .map_err(|e| format!("{name}: {e}"))?;
        Ok(Self {
            csv,
            name: name.to_owned(),
            columns: header.len(),
        })
    }

    /// Writes one record; it must have one field per column.
    pub fn record(&mut self, fields: impl IntoIterator<Item = Field>) -> Result<(), String> {
        let fields: Vec<String> = fields
            .into_iter()
            .map(|field| match field {
                Field::Number(x) => shortest(x),
                Field::Count(n) => n.to_string(),
                Field::Text(text) => text,
                Field::Empty => String::new(),
            })
            .collect();
        if fields.len() != self.columns {
            return Err(format!(
                "{}: a record of {} fields for {} columns",
                self.name,
                fields.len(),
                self.columns
            ));
        }
        self.csv
            .write_record(&fields)
            .map_err(|e| format!("{}: {e}", self.name))
    }

    /// Flushes the file.
    pub fn finish(mut self) -> Result<(), String> {
        self.csv.flush().map_err(|e| format!("{}: {e}", self.name))
    }
}

/// Columns of the angular-speed traces (one row per step per model).
pub const ANGULAR_SPEED_HEADER: [&str; 4] = ["step", "time", "model", "omega_rad_s"];

/// Writes `dir/name`: the angular speed of each named trace at every step of `dt`.
pub fn write_angular_speeds(
    dir: &Path,
    name: &str,
    dt: f64,
    traces: &[(&str, &[f64])],
) -> Result<(), String> {
    let mut table = Table::create(dir, name, &ANGULAR_SPEED_HEADER)?;
    for (model, omega) in traces {
        for (n, &w) in omega.iter().enumerate() {
            table.record(record![n, n as f64 * dt, *model, w])?;
        }
    }
    table.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_of_the_wrong_width_is_an_error_and_numbers_read_back() {
        let dir = std::env::temp_dir().join(format!("tatami-table-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut table = Table::create(&dir, "t.csv", &["a", "b", "c"]).unwrap();
        table.record(record!["x", 3usize, 0.1]).unwrap();
        table.record(record![Some(2.5), None::<f64>, true]).unwrap();
        let error = table.record(record!["x", 1.0]).unwrap_err();
        assert!(error.contains("2 fields for 3 columns"), "{error}");
        table.finish().unwrap();
        let text = std::fs::read_to_string(dir.join("t.csv")).unwrap();
        assert_eq!(text, "a,b,c\nx,3,0.1\n2.5,,yes\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
