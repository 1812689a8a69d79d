//! `cargo xtask …`: Tatami's task runner.
//!
//! - `cargo xtask experiments [--out DIR] [--quick]` runs the paper's experiments and Tatami's
//!   own, and writes CSV files, charts and a report.
//! - `cargo xtask simulate <scene.json> …` runs a scene and writes its trajectory CSV (and, with
//!   `--contacts`, its contact wrenches).
//! - `cargo xtask view <scene.json> …` writes a self-contained HTML page that replays the scene
//!   in 3-D with its contacts drawn.
//!
//! Errors are printed as one line on stderr with a non-zero exit status.

mod contacts;
mod experiments;
mod simulate;
mod trajectory;
mod view;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Tatami's task runner.
#[derive(Debug, Parser)]
#[command(name = "cargo xtask", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run the paper's experiments and Tatami's own; write CSV, charts and report.md.
    Experiments(experiments::Args),
    /// Run a scene file and write its trajectory as CSV.
    Simulate(simulate::Args),
    /// Write a self-contained HTML page that replays a scene (or a trajectory) in 3-D.
    View(view::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Experiments(args) => experiments::run(&args),
        Command::Simulate(args) => simulate::run(&args),
        Command::View(args) => view::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
