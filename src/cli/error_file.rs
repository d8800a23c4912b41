//! Where error and warning messages go: standard error, or the file rpict's (and
//! rtrace's) `-e errfile` names. Messages are appended, as Radiance opens the error
//! file for appending, so runs in a batch keep one log.

use std::fs::File;
use std::io::Write;
use std::path::Path;
use std::sync::{Mutex, OnceLock};

static FILE: OnceLock<Mutex<File>> = OnceLock::new();

/// Sends the rest of this run's messages to `path` (appending).
pub fn redirect(path: &Path) -> std::io::Result<()> {
    let f = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)?;
    let _ = FILE.set(Mutex::new(f));
    Ok(())
}

/// True when messages go to a file instead of standard error.
pub fn redirected() -> bool {
    FILE.get().is_some()
}

/// Runs `write` on the error file, if there is one; false when messages go to stderr.
pub fn with_file(write: impl FnOnce(&mut dyn Write)) -> bool {
    let Some(f) = FILE.get() else {
        return false;
    };
    let mut f = f.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    write(&mut *f);
    let _ = f.flush();
    true
}

/// One message line, to the error file or standard error.
pub fn line(message: &str) {
    if !with_file(|f| {
        let _ = writeln!(f, "{message}");
    }) {
        eprintln!("{message}");
    }
}

/// `eprintln!` that honours `-e`.
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::cli::error_file::line(&format!($($arg)*))
    };
}
