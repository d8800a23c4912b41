//! Differential test of `radc calc` against Radiance's rcalc.
//!
//! The cases are data: `tests/data/calc/{expressions,library}.txt` (format described at the
//! top of `expressions.txt`), with rcalc's exact stdout, stderr and exit status recorded in
//! the matching `.golden` files by `tests/oracle/regen_calc_goldens.py`. Each case is replayed
//! as `radc calc <same args>` with the same stdin and working directory, and every mismatch is
//! reported at once, by case id.
//!
//! What must match:
//! - exit status: success where rcalc succeeded, failure (any non-zero code) where it failed;
//! - for successful cases, stdout line by line and field by field (tab-separated): numbers
//!   within 1e-9 relative, everything else (`-nan`, `inf`, empty fields, line breaks)
//!   exactly. rcalc's partial output before a fatal error is not compared;
//! - warnings: radc's stderr is empty exactly when rcalc's was (the wording may differ).
//!
//! The library cases need the oracle's `.cal` library (found through RAYPATH, as rcalc
//! finds it), so they are a test of their own, skipped visibly without `.oracle/` and failed
//! under `RADC_REQUIRE_ORACLE=1` (see the `radc-oracle` crate); the expression cases need
//! nothing and always run.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

const RELATIVE_TOLERANCE: f64 = 1e-9;
const CASE_TIMEOUT: Duration = Duration::from_secs(30);

/// One case from a `.txt` case file.
struct Case {
    id: String,
    args: Vec<String>,
    stdin_rows: Vec<String>,
}

/// What rcalc did on a case.
struct Golden {
    exit: i32,
    stdout: String,
    stderr: String,
}

/// What `radc calc` did on a case.
struct Outcome {
    status: Option<ExitStatus>,
    stdout: String,
    stderr: String,
}

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/calc")
}

fn parse_cases(text: &str, file: &str) -> Vec<Case> {
    let mut cases: Vec<Case> = Vec::new();
    for (index, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        if let Some(header) = line.strip_prefix('[') {
            let id = header
                .strip_suffix(']')
                .unwrap_or_else(|| panic!("{file}:{}: malformed case header", index + 1));
            assert!(
                cases.iter().all(|c| c.id != id),
                "{file}:{}: duplicate case id {id}",
                index + 1
            );
            cases.push(Case {
                id: id.to_string(),
                args: Vec::new(),
                stdin_rows: Vec::new(),
            });
            continue;
        }
        let case = cases
            .last_mut()
            .unwrap_or_else(|| panic!("{file}:{}: content before the first case", index + 1));
        if let Some(row) = line.strip_prefix('<') {
            case.stdin_rows
                .push(row.strip_prefix(' ').unwrap_or(row).to_string());
        } else if line.starts_with('-') {
            match line.split_once(' ') {
                Some((option, value)) => {
                    case.args.push(option.to_string());
                    case.args.push(value.to_string());
                }
                None => case.args.push(line.to_string()),
            }
        } else {
            panic!("{file}:{}: unrecognised line {line:?}", index + 1);
        }
    }
    cases
}

fn unescape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('t') => out.push('\t'),
            Some('r') => out.push('\r'),
            Some(other) => out.push(other),
            None => out.push('\\'),
        }
    }
    out
}

fn parse_goldens(text: &str) -> Vec<(String, Golden)> {
    let mut goldens = Vec::new();
    let mut lines = text.split('\n').filter(|l| !l.starts_with('#'));
    while let Some(line) = lines.next() {
        let Some(id) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) else {
            continue;
        };
        let mut field = |name: &str| -> String {
            let line = lines.next().unwrap_or_default();
            let value = line
                .strip_prefix(name)
                .and_then(|l| l.strip_prefix(' '))
                .unwrap_or_else(|| panic!("golden [{id}]: expected '{name} ...', got {line:?}"));
            value.to_string()
        };
        let exit = field("exit").parse().expect("golden exit status");
        let stdout = unescape(&field("stdout"));
        let stderr = unescape(&field("stderr"));
        goldens.push((
            id.to_string(),
            Golden {
                exit,
                stdout,
                stderr,
            },
        ));
    }
    goldens
}

fn run_radc(args: &[String], stdin_rows: &[String], raypath: &str) -> Outcome {
    let mut child = Command::new(env!("CARGO_BIN_EXE_radc"))
        .arg("calc")
        .args(args)
        .current_dir(data_dir())
        .env("RAYPATH", raypath)
        .env("LC_ALL", "C")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn radc");
    let input: String = stdin_rows.iter().map(|r| format!("{r}\n")).collect();
    let mut stdin = child.stdin.take().expect("stdin pipe");
    let writer = std::thread::spawn(move || {
        // A program that exits without reading its input closes the pipe: not an error.
        let _ = stdin.write_all(input.as_bytes());
    });
    let stdout = drain(child.stdout.take().expect("stdout pipe"));
    let stderr = drain(child.stderr.take().expect("stderr pipe"));
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for radc") {
            break Some(status);
        }
        if started.elapsed() > CASE_TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let _ = writer.join();
    Outcome {
        status,
        stdout: stdout.join().unwrap_or_default(),
        stderr: stderr.join().unwrap_or_default(),
    }
}

fn drain(mut pipe: impl Read + Send + 'static) -> std::thread::JoinHandle<String> {
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = pipe.read_to_end(&mut bytes);
        String::from_utf8_lossy(&bytes).into_owned()
    })
}

/// A field rcalc prints with `%.9g` as a finite number; `inf`, `-nan` and empty fields are
/// compared as text.
fn as_number(field: &str) -> Option<f64> {
    let numeric = !field.is_empty()
        && field
            .bytes()
            .all(|b| b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-'))
        && field.bytes().any(|b| b.is_ascii_digit());
    numeric.then(|| field.parse().ok()).flatten()
}

fn fields_match(expected: &str, actual: &str) -> bool {
    match (as_number(expected), as_number(actual)) {
        (Some(e), Some(a)) => e == a || (e - a).abs() <= RELATIVE_TOLERANCE * e.abs().max(a.abs()),
        _ => expected == actual,
    }
}

/// The first difference between rcalc's stdout and radc's, if any.
fn stdout_difference(expected: &str, actual: &str) -> Option<String> {
    let expected_lines: Vec<&str> = expected.split('\n').collect();
    let actual_lines: Vec<&str> = actual.split('\n').collect();
    if expected_lines.len() != actual_lines.len() {
        return Some(format!(
            "{} output lines expected, {} printed",
            expected_lines.len() - 1,
            actual_lines.len() - 1
        ));
    }
    for (row, (e_line, a_line)) in expected_lines.iter().zip(&actual_lines).enumerate() {
        let e_fields: Vec<&str> = e_line.split('\t').collect();
        let a_fields: Vec<&str> = a_line.split('\t').collect();
        let same = e_fields.len() == a_fields.len()
            && e_fields
                .iter()
                .zip(&a_fields)
                .all(|(e, a)| fields_match(e, a));
        if !same {
            return Some(format!(
                "line {}: expected {e_line:?}, got {a_line:?}",
                row + 1
            ));
        }
    }
    None
}

fn compare(golden: &Golden, outcome: &Outcome) -> Option<String> {
    let Some(status) = outcome.status else {
        return Some(format!("timed out after {CASE_TIMEOUT:?}"));
    };
    let rcalc_ok = golden.exit == 0;
    if rcalc_ok != status.success() {
        return Some(format!(
            "rcalc exited {} but radc calc exited {:?}; radc stderr: {:?}; rcalc stderr: {:?}",
            golden.exit,
            status.code(),
            outcome.stderr,
            golden.stderr
        ));
    }
    if !rcalc_ok {
        return None;
    }
    if let Some(diff) = stdout_difference(&golden.stdout, &outcome.stdout) {
        return Some(diff);
    }
    match (golden.stderr.is_empty(), outcome.stderr.is_empty()) {
        (false, true) => Some(format!(
            "rcalc warned {:?} but radc calc printed nothing on stderr",
            golden.stderr
        )),
        (true, false) => Some(format!(
            "rcalc printed no warning but radc calc wrote {:?}",
            outcome.stderr
        )),
        _ => None,
    }
}

/// The two engines: the JIT (the default) and the reference interpreter.
const ENGINES: [&[&str]; 2] = [&[], &["--interp"]];

fn run_set(name: &str, engine: &[&str], raypath: &str, failures: &mut Vec<String>) -> usize {
    let dir = data_dir();
    let read = |file: &str| {
        std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("reading {file}: {e}"))
    };
    let case_file = format!("{name}.txt");
    let cases = parse_cases(&read(&case_file), &case_file);
    let goldens = parse_goldens(&read(&format!("{name}.golden")));
    assert_eq!(
        cases.iter().map(|c| c.id.as_str()).collect::<Vec<_>>(),
        goldens
            .iter()
            .map(|(id, _)| id.as_str())
            .collect::<Vec<_>>(),
        "{name}.golden is stale: run tests/oracle/regen_calc_goldens.py"
    );
    for (case, (_, golden)) in cases.iter().zip(&goldens) {
        let args: Vec<String> = engine
            .iter()
            .map(|a| a.to_string())
            .chain(case.args.iter().cloned())
            .collect();
        let outcome = run_radc(&args, &case.stdin_rows, raypath);
        if let Some(problem) = compare(golden, &outcome) {
            failures.push(format!(
                "[{name}/{}] radc calc {args:?}: {problem}",
                case.id
            ));
        }
    }
    cases.len()
}

/// Replays one case set with both engines and fails listing every difference.
fn assert_set_matches(name: &str, raypath: &str) {
    let mut failures = Vec::new();
    let mut total = 0;
    for engine in ENGINES {
        total += run_set(name, engine, raypath, &mut failures);
    }
    assert!(
        failures.is_empty(),
        "{} of {total} {name} cases differ from rcalc:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn radc_calc_matches_rcalc() {
    assert_set_matches("expressions", ".");
}

/// The cases that load Radiance's library with `-f`, found along RAYPATH as rcalc found
/// them when the goldens were made.
#[test]
fn radc_calc_matches_rcalc_on_library_files() {
    let Some(lib) =
        radc_oracle::library_or_skip("calc_differential::radc_calc_matches_rcalc_on_library_files")
    else {
        return;
    };
    assert_set_matches("library", &format!(".:{}", lib.display()));
}

#[test]
fn case_files_and_goldens_agree() {
    for name in ["expressions", "library"] {
        let dir = data_dir();
        let cases = parse_cases(
            &std::fs::read_to_string(dir.join(format!("{name}.txt"))).expect("case file"),
            name,
        );
        let goldens = parse_goldens(
            &std::fs::read_to_string(dir.join(format!("{name}.golden"))).expect("golden file"),
        );
        assert_eq!(cases.len(), goldens.len(), "{name}: case and golden counts");
        for (case, (id, _)) in cases.iter().zip(&goldens) {
            assert_eq!(&case.id, id, "{name}: cases and goldens out of order");
            assert!(
                !case.args.is_empty(),
                "{name}/{}: a case needs arguments",
                case.id
            );
        }
    }
}

#[test]
fn numeric_fields_compare_with_tolerance() {
    assert!(fields_match("0.333333333", "0.333333333"));
    assert!(fields_match("1e+308", "1.0000000001e308"));
    assert!(!fields_match("1.00000001", "1.00000002"));
    assert!(!fields_match("-nan", "NaN"));
    assert!(fields_match("inf", "inf"));
    assert!(!fields_match("", "0"));
    assert_eq!(stdout_difference("1\t2\n", "1\t2\n"), None);
    assert!(stdout_difference("1\t2\n", "1\t2").is_some());
    assert!(stdout_difference("1\t\t3\n", "1\t0\t3\n").is_some());
}
