//! What the end-to-end tests share: running the `radc` binary on some input.

use std::io::Write;
use std::process::{Command, Output, Stdio};

/// `radc ARGS...`, ready for [`run`] (add a working directory or environment first).
pub fn radc<I, S>(args: I) -> Command
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_radc"));
    cmd.args(args);
    cmd
}

/// Runs `cmd` with `input` on its standard input and collects what it writes. The
/// input is written from another thread, so a big input never waits for output to be
/// read; a command that exits before reading it (a refused scene) is not an error.
pub fn run(mut cmd: Command, input: &[u8]) -> Output {
    let mut child = cmd
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("radc runs");
    let writer = child.stdin.take().map(|mut stdin| {
        let input = input.to_vec();
        std::thread::spawn(move || {
            let _ = stdin.write_all(&input);
        })
    });
    let output = child.wait_with_output().expect("radc finishes");
    if let Some(w) = writer {
        let _ = w.join();
    }
    output
}
