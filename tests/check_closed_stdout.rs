//! `radc check` piped into a reader that stops early (`radc check big.rad | head`) must
//! exit quietly, not panic on the closed pipe.

use std::io::Write;
use std::process::{Command, Stdio};

#[test]
fn a_closed_stdout_is_not_a_panic() {
    let dir = std::env::temp_dir().join(format!("radc-closed-stdout-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("many.rad");
    // Thousands of diagnostics: far more output than a pipe buffers.
    let mut text = String::new();
    for i in 0..3000 {
        text.push_str(&format!("void plastc m{i} 0 0 5 .5 .5 .5 0 0\n"));
    }
    std::fs::File::create(&scene)
        .unwrap()
        .write_all(text.as_bytes())
        .unwrap();

    let mut child = Command::new(env!("CARGO_BIN_EXE_radc"))
        .args(["check", "many.rad"])
        .current_dir(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(1), "errors in the scene: exit 1");
    std::fs::remove_dir_all(&dir).ok();
}
