//! SIGINT and SIGTERM: no partial output file, no temporary file left
//! behind, and the conventional exit status `128 + signal` (130 for SIGINT,
//! 143 for SIGTERM).
//!
//! Contract:
//! * [`install`] (called once by the binary; later calls do nothing) makes
//!   either signal end the process at once with `128 + signal` while there
//!   is nothing to clean up: no file has been registered and no
//!   [`Deferral`] started yet. Without it the signals keep their default
//!   action and [`requested`] is always `None`.
//! * The first [`register`], [`create_registered`] or [`defer`] after
//!   [`install`] starts a thread that receives the signals, and from then
//!   on it handles them: files named with [`register`] (temporary files of
//!   [`crate::output::write_atomically`], the lock of a running sweep) are
//!   deleted when a signal ends the process, then the process exits with
//!   `128 + signal`. The thread's handler is in place before the immediate
//!   exit is switched off, so no signal falls between the two. A command
//!   that never writes a file (a `run` to standard output) starts no
//!   thread.
//! * While a [`Deferral`] from [`defer`] lives (a sweep), the first signal
//!   only sets the flag read by [`requested`]: the sweep stops taking new
//!   cases, writes the ones in flight and returns; a second signal ends the
//!   process at once as above.
//!
//! The registry's lock is held while a registered file is created (see
//! [`create_registered`]) and while the signal thread deletes the files and
//! exits, so a file is either created before the clean-up (and deleted by
//! it) or never.

use std::collections::BTreeSet;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, OnceLock};

/// The first signal received, 0 for none.
static SIGNAL: AtomicI32 = AtomicI32::new(0);
/// Live [`Deferral`]s.
static DEFERRALS: AtomicUsize = AtomicUsize::new(0);
/// Files to delete when a signal ends the process.
static FILES: Mutex<BTreeSet<PathBuf>> = Mutex::new(BTreeSet::new());
/// Set once the handlers are installed.
#[cfg(feature = "cli")]
static INSTALLED: OnceLock<()> = OnceLock::new();
/// Set once the signal thread runs.
#[cfg(feature = "cli")]
static WATCHING: OnceLock<()> = OnceLock::new();
/// While true, a signal ends the process at once (nothing to clean up).
#[cfg(feature = "cli")]
static IMMEDIATE: AtomicBool = AtomicBool::new(true);

fn files() -> MutexGuard<'static, BTreeSet<PathBuf>> {
    // A panic while the set was held leaves it consistent (inserts and
    // removes are single operations), so a poisoned lock is still usable.
    FILES.lock().unwrap_or_else(|e| e.into_inner())
}

/// Starts handling SIGINT and SIGTERM (see the module docs). Idempotent.
/// The command line installs it; a library caller keeps its own handling.
#[cfg(feature = "cli")]
pub(crate) fn install() -> std::io::Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    if INSTALLED.get().is_some() {
        return Ok(());
    }
    let mut result = Ok(());
    for signal in [SIGINT, SIGTERM] {
        match signal_hook::flag::register_conditional_shutdown(signal, 128 + signal, &IMMEDIATE) {
            // One handler in place is enough for `watch` to matter: it
            // switches the immediate exit off once there is a file to
            // delete.
            Ok(_) => {
                INSTALLED.get_or_init(|| ());
            }
            Err(e) => result = Err(e),
        }
    }
    result
}

/// Hands the signals to the clean-up thread, started on the first call
/// after [`install`] (module docs). If the thread cannot be set up, the
/// immediate exit stays: an interrupted command may then leave a
/// temporary file, which is not worth refusing to run. Without the
/// command line nothing is installed and there is nothing to watch.
#[cfg(not(feature = "cli"))]
fn watch() {}

/// As above, with the handlers of the command line.
#[cfg(feature = "cli")]
fn watch() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    if INSTALLED.get().is_none() {
        return;
    }
    WATCHING.get_or_init(|| {
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
            return;
        };
        let spawned = std::thread::Builder::new().spawn(move || {
            for signal in signals.forever() {
                let first = SIGNAL
                    .compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst)
                    .is_ok();
                if first && DEFERRALS.load(Ordering::SeqCst) > 0 {
                    continue;
                }
                let registered = files();
                for path in registered.iter() {
                    let _ = std::fs::remove_file(path);
                }
                // Exits with the lock held: no registered file appears after
                // the clean-up.
                std::process::exit(128 + SIGNAL.load(Ordering::SeqCst));
            }
        });
        // The thread's handler is registered (Signals::new): from here on
        // it decides.
        if spawned.is_ok() {
            IMMEDIATE.store(false, Ordering::SeqCst);
        }
    });
}

/// The signal that asked the program to stop (`SIGINT` = 2, `SIGTERM` =
/// 15), if any.
pub(crate) fn requested() -> Option<i32> {
    match SIGNAL.load(Ordering::SeqCst) {
        0 => None,
        signal => Some(signal),
    }
}

/// The exit status after `signal`: `128 + signal`.
pub(crate) fn exit_status(signal: i32) -> u8 {
    u8::try_from(128 + signal).unwrap_or(u8::MAX)
}

/// Postpones the exit on the first signal while it lives (see the module
/// docs).
#[must_use = "the deferral ends when it is dropped"]
pub(crate) struct Deferral(());

/// Starts a [`Deferral`].
pub(crate) fn defer() -> Deferral {
    watch();
    DEFERRALS.fetch_add(1, Ordering::SeqCst);
    Deferral(())
}

impl Drop for Deferral {
    fn drop(&mut self) {
        DEFERRALS.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Marks `path` for deletion if a signal ends the process.
pub(crate) fn register(path: &Path) {
    watch();
    files().insert(path.to_owned());
}

/// Creates (truncating) `path` and marks it for deletion if a signal ends
/// the process, as one step with respect to the clean-up.
pub(crate) fn create_registered(path: &Path) -> std::io::Result<File> {
    watch();
    let mut registered = files();
    let file = File::create(path)?;
    registered.insert(path.to_owned());
    Ok(file)
}

/// Forgets `path` (it was renamed, deleted, or is complete).
pub(crate) fn unregister(path: &Path) {
    files().remove(path);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registered_files_are_listed_until_forgotten() {
        let path = std::env::temp_dir().join(format!("stickslip-interrupt-{}", std::process::id()));
        drop(create_registered(&path).unwrap());
        assert!(files().contains(&path));
        unregister(&path);
        assert!(!files().contains(&path));
        std::fs::remove_file(&path).unwrap();
        assert_eq!(exit_status(2), 130);
        assert_eq!(exit_status(15), 143);
    }
}
