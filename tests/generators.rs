//! Differential tests: `radc genbox|genprism|genrev|gensky|gensurf|genworm|xform`
//! against what Radiance's programs printed for the same arguments (goldens from
//! tests/oracle/regen_generator_goldens.py): the exit status, standard output (for a
//! failure, what was written before it), and standard error, where radc may add its
//! own detail on indented `error[...]` and `hint:` lines after Radiance's.
//!
//! Each case must match its golden text exactly; when it does not, the comparison is
//! repeated primitive by primitive with numbers within 1e-6 relative, so the failure
//! says whether the difference is formatting or geometry, and where.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/generators")
}

struct Case {
    id: String,
    program: String,
    args: Vec<String>,
    stdin: Option<String>,
    status: i64,
    stderr: String,
}

fn cases() -> Vec<Case> {
    let text = std::fs::read_to_string(data_dir().join("cases.json")).expect("cases.json");
    let json: serde_json::Value = serde_json::from_str(&text).expect("cases.json is JSON");
    let list = json.as_array().expect("a list of cases");
    list.iter()
        .map(|c| Case {
            id: c["id"].as_str().expect("id").to_string(),
            program: c["program"].as_str().expect("program").to_string(),
            args: c["args"]
                .as_array()
                .expect("args")
                .iter()
                .map(|a| a.as_str().expect("arg").to_string())
                .collect(),
            stdin: c["stdin"].as_str().map(str::to_string),
            status: c["status"].as_i64().expect("status"),
            stderr: c["stderr"].as_str().expect("stderr").to_string(),
        })
        .collect()
}

fn run_radc(case: &Case) -> (i32, String, String) {
    let inputs = data_dir().join("inputs");
    let stdin = match &case.stdin {
        Some(name) => Stdio::from(std::fs::File::open(inputs.join(name)).expect("stdin file")),
        None => Stdio::null(),
    };
    let out = Command::new(env!("CARGO_BIN_EXE_radc"))
        .arg(&case.program)
        .args(&case.args)
        .current_dir(&inputs)
        .env_remove("RAYPATH")
        .stdin(stdin)
        .output()
        .expect("radc runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// radc's standard error without its own additions (indented `error[...]` and
/// `hint:` lines).
fn radiance_lines(stderr: &str) -> String {
    stderr
        .lines()
        .filter(|l| !l.starts_with("  error[") && !l.starts_with("  hint: "))
        .map(|l| format!("{l}\n"))
        .collect()
}

/// Splits scene text into primitives (blocks starting after a blank line) of words.
fn primitives(text: &str) -> Vec<Vec<&str>> {
    text.split("\n\n")
        .map(|block| block.split_whitespace().collect::<Vec<_>>())
        .filter(|words| !words.is_empty())
        .collect()
}

fn numbers_close(a: &str, b: &str) -> bool {
    match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(x), Ok(y)) => x == y || (x - y).abs() <= 1e-6 * x.abs().max(y.abs()).max(1e-6),
        _ => false,
    }
}

/// The first difference beyond tolerance, if any.
fn tolerant_difference(want: &str, got: &str) -> Option<String> {
    let (w, g) = (primitives(want), primitives(got));
    if w.len() != g.len() {
        return Some(format!(
            "{} primitives expected, {} produced",
            w.len(),
            g.len()
        ));
    }
    for (i, (pw, pg)) in w.iter().zip(&g).enumerate() {
        let same = pw.len() == pg.len()
            && pw
                .iter()
                .zip(pg)
                .all(|(a, b)| a == b || numbers_close(a, b));
        if !same {
            return Some(format!(
                "primitive {i} differs:\n  want {}\n  got  {}",
                pw.join(" "),
                pg.join(" ")
            ));
        }
    }
    None
}

#[test]
fn generators_match_radiance() {
    let cases = cases();
    assert!(cases.len() >= 40, "only {} cases", cases.len());
    let mut failures = Vec::new();
    for case in &cases {
        let (status, got, stderr) = run_radc(case);
        let label = format!("radc {} {}", case.program, case.args.join(" "));
        if i64::from(status) != case.status {
            failures.push(format!(
                "{label}: exit status {status}, Radiance's {}; stderr: {}",
                case.status,
                stderr.trim()
            ));
            continue;
        }
        if radiance_lines(&stderr) != case.stderr {
            failures.push(format!(
                "{label}: stderr differs:\n  want {:?}\n  got  {:?}",
                case.stderr, stderr
            ));
        }
        let golden = data_dir().join(format!("{}.out", case.id));
        let want = std::fs::read_to_string(&golden).expect("golden output");
        if want == got {
            continue;
        }
        match tolerant_difference(&want, &got) {
            Some(diff) => failures.push(format!("{label}: {diff}")),
            None => failures.push(format!(
                "{label}: numbers agree within 1e-6 but text differs"
            )),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases differ:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

#[test]
fn tolerance_accepts_rounding_only() {
    let a = "\nm sphere s\n0\n0\n4 1 2 3 0.5\n";
    assert_eq!(
        tolerant_difference(a, "\nm sphere s\n0\n0\n4 1.0000000001 2 3 0.5\n"),
        None
    );
    assert!(tolerant_difference(a, "\nm sphere s\n0\n0\n4 1.1 2 3 0.5\n").is_some());
    assert!(tolerant_difference(a, "\nm bubble s\n0\n0\n4 1 2 3 0.5\n").is_some());
}
