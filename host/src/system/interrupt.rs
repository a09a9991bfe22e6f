//! SIGINT and SIGTERM during a render: the first asks the render to stop after the pass under way,
//! save the image of the samples done so far (marked partial) and the checkpoint, and exit with
//! 128 + the signal's number; a second exits at once. Without this an interrupt lost every sample
//! since the last checkpoint.
use std::sync::atomic::{AtomicI32, Ordering};
use std::sync::OnceLock;

/// The first signal received (0: none).
static RECEIVED: AtomicI32 = AtomicI32::new(0);
/// What the first signal does, when not the default (an MPI rank's: `ranked.rs`); empty: say nothing.
static NOTE: OnceLock<String> = OnceLock::new();

/// Replaces what the first signal is said to do (call once, before rendering).
pub fn set_note(note: &str) {
    NOTE.set(note.to_string()).ok();
}

/// Catches SIGINT and SIGTERM from now on (a thread waits for them). Without it, or on platforms
/// without these signals, they end the process as by default.
#[cfg(unix)]
pub fn install() -> anyhow::Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])?;
    std::thread::Builder::new().name("signals".into()).spawn(move || {
        for signal in signals.forever() {
            if RECEIVED.compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst).is_err() {
                // The second: the user means it.
                signal_hook::low_level::exit(128 + signal);
            }
            let note =
                NOTE.get().map_or("saving the image after this pass (again to quit at once)", String::as_str);
            if !note.is_empty() {
                eprintln!("\n{}: {note}", if signal == SIGINT { "interrupted" } else { "terminated" });
            }
        }
    })?;
    Ok(())
}

#[cfg(not(unix))]
pub fn install() -> anyhow::Result<()> {
    Ok(())
}

/// The signal that asked the render to stop, if one did.
pub fn requested() -> Option<i32> {
    match RECEIVED.load(Ordering::SeqCst) {
        0 => None,
        signal => Some(signal),
    }
}

/// The exit status for a render stopped by `signal`, as shells report a process it killed.
pub fn exit_code(signal: i32) -> i32 {
    128 + signal
}
