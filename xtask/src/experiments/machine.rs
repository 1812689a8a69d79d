//! The machine the experiments ran on: timings mean little without it.

use std::fmt;

/// CPU model, logical cores and platform, as the report states them.
#[derive(Debug, Clone)]
pub struct Machine {
    /// CPU model name (`/proc/cpuinfo` on Linux), or "unknown CPU".
    pub cpu: String,
    /// Logical cores available to this process.
    pub cores: usize,
    /// Operating system and architecture.
    pub platform: String,
}

impl Machine {
    /// Reads the current machine's description; never fails (unknown parts say so).
    pub fn current() -> Self {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|info| {
                info.lines().find_map(|line| {
                    let (key, value) = line.split_once(':')?;
                    (key.trim() == "model name").then(|| value.trim().to_owned())
                })
            })
            .unwrap_or_else(|| "unknown CPU".to_owned());
        Self {
            cpu,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            platform: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
        }
    }
}

impl fmt::Display for Machine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}, {} logical cores, {}",
            self.cpu, self.cores, self.platform
        )
    }
}
