//! Running the xtask binary from the integration tests.

/// Runs the xtask binary with `args` and returns what it printed and its status.
pub fn xtask(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .output()
        .expect("the xtask binary runs")
}
