//! End-to-end tests of `radc calc`: the calcomp-semantics goldens produced by real
//! rcalc (tests/oracle/regen_cal_semantics.py), plus the command's own behaviour.

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cal-semantics")
}

fn radc_calc(args: &[&str], stdin: &str) -> Output {
    let mut cmd = common::radc(["calc"]);
    cmd.args(args)
        .current_dir(data_dir())
        .env("RAYPATH", data_dir());
    common::run(cmd, stdin.as_bytes())
}

#[test]
fn matches_rcalc_on_the_semantics_goldens() {
    let text = std::fs::read_to_string(data_dir().join("golden.json")).expect("golden.json");
    let cases: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    let cases = cases.as_array().expect("a list of cases");
    assert!(cases.len() >= 70);
    let mut failures = Vec::new();
    // Both engines: the JIT (the default) and the reference interpreter.
    for (engine, case) in [&[][..], &["--interp"][..]]
        .into_iter()
        .flat_map(|e| cases.iter().map(move |c| (e, c)))
    {
        let name = case["name"].as_str().unwrap_or("?");
        let args: Vec<&str> = engine
            .iter()
            .copied()
            .chain(
                case["args"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter_map(|v| v.as_str()),
            )
            .collect();
        let stdin = case["stdin"].as_str().unwrap_or("");
        let want_out = case["stdout"].as_str().unwrap_or("");
        let want_ok = case["status"].as_i64() == Some(0);
        let out = radc_calc(&args, stdin);
        let got_out = String::from_utf8_lossy(&out.stdout);
        if got_out != want_out || out.status.success() != want_ok {
            failures.push(format!(
                "{name} {engine:?}: rcalc {want_out:?} (ok: {want_ok}), radc {got_out:?} (status {:?})\n  stderr: {}",
                out.status.code(),
                String::from_utf8_lossy(&out.stderr).trim()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases (each run by both engines) differ from rcalc:\n{}",
        failures.len(),
        cases.len() * 2,
        failures.join("\n")
    );
}

#[test]
fn syntax_errors_are_diagnostics_with_codes() {
    let out = radc_calc(&["-e", "$1 = 1 +; $2 = sqt(2)", "-e", "x = (1"], "");
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("E0501"), "{err}");
    // Both bad statements are reported, not only the first.
    assert_eq!(err.matches("E0501").count(), 2, "{err}");
}

#[test]
fn bad_options_are_usage_errors() {
    for args in [&["-z"][..], &["-e"][..], &["-ix"][..]] {
        let out = radc_calc(args, "");
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
}

#[test]
fn warnings_go_to_stderr_unless_w() {
    let out = radc_calc(&["-e", "z=$1;$1=1/z"], "0\n");
    assert_eq!(String::from_utf8_lossy(&out.stdout), "0\n");
    assert!(String::from_utf8_lossy(&out.stderr).contains("Division by zero"));
    let out = radc_calc(&["-w", "-e", "z=$1;$1=1/z"], "0\n");
    assert!(out.stderr.is_empty());
}

#[test]
fn binary_output_writes_doubles() {
    let out = radc_calc(&["-od", "-e", "$1=$1;$3=2"], "1.5\n");
    let bytes = out.stdout;
    assert_eq!(bytes.len(), 24);
    let v: Vec<f64> = bytes
        .chunks(8)
        .map(|c| f64::from_ne_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    assert_eq!(v, [1.5, 0.0, 2.0]);
}

/// The JIT runs by default: it declines a program only with a note on stderr, and
/// `--interp` gives the same bytes.
#[test]
fn jit_is_the_default_and_agrees_with_interp() {
    let expr =
        "f(x,y) = if(x-y, sqrt(x*x+y*y)*sin(x), exp(-x*y/100)); $1 = f($1,$2); $2 = $1/($2-1)";
    let rows = "1 2\n3 1\n-4.5 1e3\n";
    let jit = radc_calc(&["-e", expr], rows);
    let interp = radc_calc(&["--interp", "-e", expr], rows);
    let jit_err = String::from_utf8_lossy(&jit.stderr);
    assert!(!jit_err.contains("using the interpreter"), "{jit_err}");
    assert!(jit_err.contains("Division by zero"), "{jit_err}");
    assert_eq!(jit.stdout, interp.stdout);
    assert_eq!(jit.stderr, interp.stderr);
    assert_eq!(String::from_utf8_lossy(&jit.stdout).lines().count(), 3);
}

/// Several threads write exactly what one writes: outputs in order, warnings and a
/// fatal error at the record where they happen, `recno` counted across chunks, and
/// `cond` filtering; over enough rows for many chunks per thread.
#[test]
fn threads_write_what_one_thread_writes() {
    // About 1.2 MB: several chunks for each of three threads.
    let rows: String = (0..200_000)
        .map(|i| format!("{} {}\n", i % 1000, (i * 7) % 13))
        .collect();
    let program = "cond = $1 - 3; $1 = recno; $2 = $1/($2-5); $3 = sqrt($1)";
    // The same, plus a record that stops the run (an undefined function is called).
    let failing = "cond = $1 - 3; $1 = recno; $2 = $1/($2-5); $3 = if(recno-50000, nosuch(1), 2)";
    for expr in [program, failing] {
        let one = radc_calc(&["--threads", "1", "-e", expr], &rows);
        let many = radc_calc(&["--threads", "3", "-e", expr], &rows);
        assert_eq!(one.status.code(), many.status.code(), "{expr}");
        assert!(one.stdout == many.stdout, "outputs differ for {expr}");
        assert_eq!(
            String::from_utf8_lossy(&one.stderr),
            String::from_utf8_lossy(&many.stderr),
            "{expr}"
        );
        assert!(one.stderr.len() > 1000, "warnings expected");
    }
    // Recursion (its depth warnings are once per run) keeps a program on one thread.
    let fact = "f(n) = if(n-.5, n*f(n-1), 1); $1 = f(150 + $1 - $1)";
    let rows = &rows[..10_000];
    let one = radc_calc(&["--threads", "1", "-e", fact], rows);
    let many = radc_calc(&["--threads", "3", "-e", fact], rows);
    assert_eq!(one.stderr, many.stderr);
    assert!(one.stdout == many.stdout);
}
