//! `radc check` must read exactly what Radiance reads: a scene Radiance accepts (oconv builds
//! it and a probe rtrace renders every surface) gets no error-severity diagnostic, and a scene
//! Radiance rejects at either stage gets at least one. The verdicts live in
//! `tests/data/scenes/oracle.json`, written by `tests/oracle/regen_scene_goldens.py` from real
//! Radiance, so this test needs no Python.
//!
//! Each scene is checked from its own folder, as Radiance ran it, so relative `.cal`, `.dat`,
//! picture and octree names resolve the same way.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use serde_json::Value;

const WORKSPACE: &str = env!("CARGO_MANIFEST_DIR");
const ORACLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/scenes/oracle.json");
const SHARED_CORPUS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/corpus/radiance");
/// Keys of shared-corpus scenes in oracle.json start with this.
const SHARED_KEY: &str = "../shared/corpus/radiance/";
/// Where the corpus' own scenes live, relative to the workspace root.
const OWN_FOLDERS: [&str; 3] = [
    "tests/data/scenes/generated",
    "tests/data/scenes/valid",
    "tests/data/scenes/invalid",
];

/// One scene's entry in oracle.json.
struct Verdict {
    key: String,
    accepted: bool,
    radiance_says: String,
}

fn verdicts() -> Vec<Verdict> {
    let text = std::fs::read_to_string(ORACLE).expect("tests/data/scenes/oracle.json is readable");
    let json: Value = serde_json::from_str(&text).expect("oracle.json is JSON");
    let map = json.as_object().expect("oracle.json is an object");
    map.iter()
        .map(|(key, v)| {
            let flag = |name: &str| v.get(name).and_then(Value::as_bool).unwrap_or(false);
            Verdict {
                key: key.clone(),
                accepted: flag("oconv_ok") && flag("render_ok"),
                radiance_says: v
                    .get("radiance_says")
                    .and_then(Value::as_str)
                    .unwrap_or_default()
                    .to_owned(),
            }
        })
        .collect()
}

/// What `radc check --format json` said about one scene.
enum CheckOutcome {
    /// It ran: the error-severity diagnostics it printed (code and message).
    Diagnosed(Vec<String>),
    /// This build of radc has no `check` command yet.
    NoCheckCommand,
    /// It crashed, printed something that is not one JSON object per line, or its exit
    /// status contradicts its diagnostics.
    Broken(String),
}

fn check(scene: &Path) -> CheckOutcome {
    let (Some(dir), Some(name)) = (scene.parent(), scene.file_name()) else {
        return CheckOutcome::Broken(format!("bad scene path {}", scene.display()));
    };
    // Radiance ran with its library on RAYPATH; radc must see the same files.
    let mut command = Command::new(env!("CARGO_BIN_EXE_radc"));
    command
        .args(["check", "--format", "json"])
        .arg(name)
        .current_dir(dir);
    match oracle_lib() {
        Some(lib) => command.env("RAYPATH", format!(".:{}", lib.display())),
        None => command.env_remove("RAYPATH"),
    };
    let output = match run_with_timeout(command) {
        Ok(o) => o,
        Err(why) => return CheckOutcome::Broken(why),
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    let code = output.status.code();
    if code == Some(2) && stderr.contains("unknown command") {
        return CheckOutcome::NoCheckCommand;
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let mut errors = Vec::new();
    for line in stdout.lines().filter(|l| !l.trim().is_empty()) {
        let Ok(diagnostic) = serde_json::from_str::<Value>(line) else {
            return CheckOutcome::Broken(format!("stdout line is not JSON: {line}"));
        };
        let is_error = diagnostic.get("severity").and_then(Value::as_str) == Some("error");
        // Without the oracle's library, files Radiance found there look missing.
        let library_file = oracle_lib().is_none()
            && diagnostic.get("code").and_then(Value::as_str) == Some("E0305");
        if is_error && !library_file {
            let field = |k: &str| diagnostic.get(k).and_then(Value::as_str).unwrap_or("?");
            errors.push(format!(
                "{} {}:{}: {}",
                field("code"),
                diagnostic.get("line").unwrap_or(&Value::Null),
                diagnostic.get("column").unwrap_or(&Value::Null),
                field("message")
            ));
        }
    }
    match code {
        Some(0) if errors.is_empty() => CheckOutcome::Diagnosed(errors),
        Some(1) if !errors.is_empty() => CheckOutcome::Diagnosed(errors),
        other => CheckOutcome::Broken(format!(
            "exit status {other:?} with {} error diagnostic(s); stderr: {}",
            errors.len(),
            stderr.trim()
        )),
    }
}

/// How long one `radc check` may take: the corpus holds huge counts (`0 0 999999999`) that
/// must fail fast, not allocate or loop.
const CHECK_TIMEOUT: Duration = Duration::from_secs(30);

fn run_with_timeout(mut command: Command) -> Result<Output, String> {
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("could not run radc: {e}"))?;
    // Drain both pipes on their own threads so a chatty child cannot block on a full pipe.
    let drain = |pipe: Option<Box<dyn Read + Send>>| {
        thread::spawn(move || {
            let mut bytes = Vec::new();
            if let Some(mut pipe) = pipe {
                let _ = pipe.read_to_end(&mut bytes);
            }
            bytes
        })
    };
    let stdout = drain(
        child
            .stdout
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let stderr = drain(
        child
            .stderr
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if start.elapsed() > CHECK_TIMEOUT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!("radc check took over {CHECK_TIMEOUT:?}; killed"));
            }
            Ok(None) => thread::sleep(Duration::from_millis(5)),
            Err(e) => return Err(format!("waiting for radc: {e}")),
        }
    };
    Ok(Output {
        status,
        stdout: stdout.join().unwrap_or_default(),
        stderr: stderr.join().unwrap_or_default(),
    })
}

/// Checks every scene against its verdict and panics listing all mismatches at once.
/// Returns early (passing) when radc has no `check` command yet.
fn assert_radc_agrees(scenes: &[(PathBuf, &Verdict)], corpus: &str) {
    let mut mismatches = Vec::new();
    for (path, verdict) in scenes {
        match check(path) {
            CheckOutcome::NoCheckCommand => {
                eprintln!("notice: `radc check` does not exist yet; {corpus} oracle test skipped");
                return;
            }
            CheckOutcome::Broken(why) => mismatches.push(format!("{}: {why}", verdict.key)),
            CheckOutcome::Diagnosed(errors) if verdict.accepted && !errors.is_empty() => {
                mismatches.push(format!(
                    "{}: Radiance accepts it, radc reports: {}",
                    verdict.key,
                    errors.join("; ")
                ));
            }
            CheckOutcome::Diagnosed(errors) if !verdict.accepted && errors.is_empty() => {
                mismatches.push(format!(
                    "{}: Radiance rejects it ({}), radc reports no error",
                    verdict.key, verdict.radiance_says
                ));
            }
            CheckOutcome::Diagnosed(_) => {}
        }
    }
    assert!(
        mismatches.is_empty(),
        "radc check disagrees with Radiance on {} of {} {corpus} scenes:\n{}",
        mismatches.len(),
        scenes.len(),
        mismatches.join("\n")
    );
}

#[test]
fn own_corpus_verdicts_match_radiance() {
    let verdicts = verdicts();
    let scenes: Vec<_> = verdicts
        .iter()
        .filter(|v| !v.key.starts_with(SHARED_KEY))
        .map(|v| (Path::new(WORKSPACE).join(&v.key), v))
        .collect();
    assert!(!scenes.is_empty(), "oracle.json lists no corpus scenes");
    assert_radc_agrees(&scenes, "corpus");
}

#[test]
fn shared_radiance_corpus_verdicts_match_radiance() {
    let root = Path::new(SHARED_CORPUS);
    if !root.is_dir() {
        eprintln!("notice: {SHARED_CORPUS} is absent; shared-corpus oracle test skipped");
        return;
    }
    let verdicts = verdicts();
    // Scenes with `!` lines are included: radc expands genbox, genprism and xform
    // (pipelines too) itself, and reports other commands as not expanded, which
    // agrees with Radiance's verdict on every one of them.
    let scenes: Vec<_> = verdicts
        .iter()
        .filter_map(|v| {
            v.key
                .strip_prefix(SHARED_KEY)
                .map(|rel| (root.join(rel), v))
        })
        .collect();
    assert!(
        !scenes.is_empty(),
        "oracle.json lists no shared-corpus scenes"
    );
    assert_radc_agrees(&scenes, "shared Radiance");
}

/// A scene added to a corpus folder without regenerating the goldens would go untested.
#[test]
fn every_corpus_scene_has_a_verdict() {
    let verdicts = verdicts();
    let known: std::collections::HashSet<&str> = verdicts.iter().map(|v| v.key.as_str()).collect();
    let mut missing = Vec::new();
    for folder in OWN_FOLDERS {
        let entries = std::fs::read_dir(Path::new(WORKSPACE).join(folder))
            .unwrap_or_else(|e| panic!("{folder} is readable: {e}"));
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let is_scene = name.ends_with(".rad") || name.ends_with(".mat");
            let key = format!("{folder}/{name}");
            if is_scene && !known.contains(key.as_str()) {
                missing.push(key);
            }
        }
    }
    for v in &verdicts {
        if !v.key.starts_with(SHARED_KEY) && !Path::new(WORKSPACE).join(&v.key).is_file() {
            missing.push(format!("{} (in oracle.json, not on disk)", v.key));
        }
    }
    missing.sort();
    assert!(
        missing.is_empty(),
        "run tests/oracle/regen_scene_goldens.py; out of date for:\n{}",
        missing.join("\n")
    );
}

/// The Radiance library of the installed oracle (`.oracle/lib/python3*/site-packages/
/// pyradiance/lib`), if there is one.
fn oracle_lib() -> Option<PathBuf> {
    let lib = Path::new(WORKSPACE).join(".oracle/lib");
    std::fs::read_dir(&lib)
        .ok()?
        .flatten()
        .map(|e| e.path().join("site-packages/pyradiance/lib"))
        .find(|p| p.is_dir())
}
