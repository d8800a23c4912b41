//! The picture commands (`radc getinfo pvalue pflip protate ra_ppm ra_rgbe ra_xyze`): thin shells over
//! `radc_picture` with the options, outputs and exit codes of Radiance's programs
//! (1 for every error, usage errors included, as those programs exit). Messages name
//! the file and, for damaged pictures, the byte offset.

pub mod getinfo;
pub mod pfilt;
pub mod pflip;
pub mod protate;
pub mod pvalue;
pub mod ra_ppm;
pub mod ra_rgbe;
pub mod ra_xyze;

use std::io::{Read, Write};

pub use radc_picture::tools::{format_line, words_line};
use std::os::fd::AsFd;
use std::process::ExitCode;

/// Radiance's picture programs exit 1 on any error.
pub const FAILURE: u8 = 1;

/// An error message (`radc <command>: ...`) and exit status 1.
pub fn fail(command: &str, message: impl std::fmt::Display) -> ExitCode {
    eprintln!("radc {command}: {message}");
    ExitCode::from(FAILURE)
}

/// The whole of a file, or of standard input for `None`.
pub fn read_input(path: Option<&str>) -> Result<Vec<u8>, String> {
    match path {
        Some(p) => std::fs::read(p).map_err(|e| format!("cannot open {p}: {e}")),
        None => {
            let mut data = Vec::new();
            std::io::stdin()
                .lock()
                .read_to_end(&mut data)
                .map_err(|e| format!("cannot read standard input: {e}"))?;
            Ok(data)
        }
    }
}

/// Where standard output stands in its file: `fputformat` pads binary formats so the
/// data after the header is aligned, measured with `ftell(stdout)`, which fails (no
/// padding) on a pipe or terminal.
pub fn stdout_position() -> Option<u64> {
    use std::io::Seek;
    let fd = std::io::stdout().as_fd().try_clone_to_owned().ok()?;
    let mut f = std::fs::File::from(fd);
    f.stream_position().ok()
}

/// Writes `bytes` to standard output, reporting a failed write as the command's error.
pub fn write_stdout(command: &str, bytes: &[u8]) -> Result<(), ExitCode> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)
        .and_then(|_| out.flush())
        .map_err(|e| fail(command, format!("write error: {e}")))
}

/// Writes the finished output to `path`, or to standard output. Called only once the
/// whole output is made, so a failure leaves no partial file behind.
pub fn write_output(command: &str, path: Option<&str>, bytes: &[u8]) -> ExitCode {
    match path {
        Some(p) => match std::fs::write(p, bytes) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(command, format!("cannot write {p}: {e}")),
        },
        None => match write_stdout(command, bytes) {
            Ok(()) => ExitCode::SUCCESS,
            Err(code) => code,
        },
    }
}
