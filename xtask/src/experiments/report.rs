//! `report.md`: the machine, a summary table, then one section per experiment.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;

use super::Outcome;
use super::machine::Machine;

/// Name of the report in the output folder.
pub const FILE: &str = "report.md";

/// Writes the report and returns its path.
pub fn write(
    out: &Path,
    machine: &Machine,
    quick: bool,
    outcomes: &[(Outcome, Duration)],
) -> Result<PathBuf, String> {
    let mut text = String::from("# Tatami experiments\n\n");
    let _ = writeln!(text, "Machine: {machine}. Release build, one thread.");
    if quick {
        text.push_str(
            "\n**Quick run** (`--quick`): small sizes and short runs, to check that every \
             experiment runs; the numbers are not the figures.\n",
        );
    }
    text.push_str("\n| experiment | result | run time |\n|---|---|---:|\n");
    for (outcome, took) in outcomes {
        let _ = writeln!(
            text,
            "| {} | {} | {:.1} s |",
            outcome.title,
            outcome.summary,
            took.as_secs_f64()
        );
    }
    for (i, (outcome, _)) in outcomes.iter().enumerate() {
        let _ = write!(
            text,
            "\n## {}. {}\n\n{}",
            i + 1,
            outcome.title,
            outcome.report
        );
        let _ = writeln!(text, "\nFiles: {}.", files(&outcome.files));
    }
    let path = out.join(FILE);
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

fn files(names: &[&str]) -> String {
    names
        .iter()
        .map(|name| format!("[`{name}`]({name})"))
        .collect::<Vec<_>>()
        .join(", ")
}
