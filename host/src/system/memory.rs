//! Host memory: what the machine has, and a need checked against it before anything is allocated.
//! A 32768×32768 film needs about 290 GiB here (`backend::memory`); allocating it aborted the
//! process ("memory allocation failed") instead of refusing with a message.
use anyhow::{bail, Result};

/// The memory the kernel says can be allocated without swapping (`MemAvailable` of /proc/meminfo);
/// `None` where that is not known (another OS, an old kernel).
pub fn available() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    parse_mem_available(&info)
}

/// This process's peak resident memory so far (`VmHWM` of /proc/self/status); `None` where that is
/// not known.
pub fn peak_resident() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    kib_field(&status, "VmHWM:")
}

/// `MemAvailable:  22937888 kB` → bytes.
pub fn parse_mem_available(meminfo: &str) -> Option<u64> {
    kib_field(meminfo, "MemAvailable:")
}

/// The `NAME:  1234 kB` line of a /proc file, in bytes.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find_map(|l| l.strip_prefix(name))?;
    let kib: u64 = line.trim().strip_suffix("kB")?.trim().parse().ok()?;
    kib.checked_mul(1024)
}

/// Refuses `need` bytes for `what` when more than `available` (unknown: no check).
pub fn check(need: u64, available: Option<u64>, what: &str) -> Result<()> {
    match available {
        Some(have) if need > have => bail!(
            "{what} needs about {:.1} GiB of memory and this machine has {:.1} GiB available; \
             render a smaller film (or a crop window)",
            gib(need),
            gib(have)
        ),
        _ => Ok(()),
    }
}

fn gib(bytes: u64) -> f64 {
    bytes as f64 / (1u64 << 30) as f64
}
