//! `radc check` must read exactly what Radiance reads: a scene Radiance accepts (oconv builds
//! it and a probe rtrace renders every surface) gets no error-severity diagnostic, and a scene
//! Radiance rejects at either stage gets at least one. The verdicts live in
//! `tests/data/scenes/oracle.json`, written by `tests/oracle/regen_scene_goldens.py` from real
//! Radiance, so this test needs no Python.
//!
//! Each scene is checked from its own folder, as Radiance ran it, so relative `.cal`, `.dat`,
//! picture and octree names resolve the same way. Radiance ran with its library on RAYPATH;
//! the golden lists, per scene, the library files the scene names (`library_files`). Scenes
//! that name none are checked with no RAYPATH at all, on every machine, and every error
//! counts: a missing file is a real error there. Scenes that name some are compared only
//! with the oracle's library on RAYPATH, as Radiance saw them, in tests of their own that
//! are skipped visibly without the oracle (and fail under `RADC_REQUIRE_ORACLE=1`; see the
//! `radc-oracle` crate). Scenes of `../shared/corpus` likewise need that folder.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use serde_json::Value;

const WORKSPACE: &str = env!("CARGO_MANIFEST_DIR");
const ORACLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/scenes/oracle.json");
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
    /// Files of Radiance's library the scene names: found along RAYPATH by Radiance, so
    /// radc can judge the scene as Radiance did only with the same library.
    library_files: Vec<String>,
}

impl Verdict {
    fn is_shared(&self) -> bool {
        self.key.starts_with(SHARED_KEY)
    }

    fn needs_library(&self) -> bool {
        !self.library_files.is_empty()
    }
}

fn verdicts() -> Vec<Verdict> {
    let text = std::fs::read_to_string(ORACLE).expect("tests/data/scenes/oracle.json is readable");
    let json: Value = serde_json::from_str(&text).expect("oracle.json is JSON");
    let map = json.as_object().expect("oracle.json is an object");
    map.iter()
        .map(|(key, v)| {
            let flag = |name: &str| v.get(name).and_then(Value::as_bool).unwrap_or(false);
            let library_files = v
                .get("library_files")
                .and_then(Value::as_array)
                .unwrap_or_else(|| {
                    panic!("{key}: no library_files: run tests/oracle/regen_scene_goldens.py")
                })
                .iter()
                .map(|f| {
                    f.as_str()
                        .expect("library file names are strings")
                        .to_owned()
                })
                .collect();
            Verdict {
                key: key.clone(),
                accepted: flag("oconv_ok") && flag("render_ok"),
                radiance_says: v
                    .get("radiance_says")
                    .and_then(Value::as_str)
                    .unwrap_or_default()
                    .to_owned(),
                library_files,
            }
        })
        .collect()
}

/// What `radc check --format json` said about one scene.
enum CheckOutcome {
    /// It ran: the error-severity diagnostics it printed (code and message).
    Diagnosed(Vec<String>),
    /// It crashed, printed something that is not one JSON object per line, or its exit
    /// status contradicts its diagnostics.
    Broken(String),
}

/// Runs `radc check` on `scene` from the scene's folder, with RAYPATH `.` and `library`
/// when given, else with no RAYPATH.
fn check(scene: &Path, library: Option<&Path>) -> CheckOutcome {
    let (Some(dir), Some(name)) = (scene.parent(), scene.file_name()) else {
        return CheckOutcome::Broken(format!("bad scene path {}", scene.display()));
    };
    let mut command = Command::new(env!("CARGO_BIN_EXE_radc"));
    command
        .args(["check", "--format", "json"])
        .arg(name)
        .current_dir(dir);
    match library {
        Some(lib) => command.env("RAYPATH", format!(".:{}", lib.display())),
        None => command.env_remove("RAYPATH"),
    };
    let output = match run_with_timeout(command) {
        Ok(o) => o,
        Err(why) => return CheckOutcome::Broken(why),
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    let code = output.status.code();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let mut errors = Vec::new();
    for line in stdout.lines().filter(|l| !l.trim().is_empty()) {
        let Ok(diagnostic) = serde_json::from_str::<Value>(line) else {
            return CheckOutcome::Broken(format!("stdout line is not JSON: {line}"));
        };
        if diagnostic.get("severity").and_then(Value::as_str) == Some("error") {
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

/// Checks every scene against its verdict (RAYPATH as [`check`] sets it from `library`) and
/// panics listing all mismatches at once.
fn assert_radc_agrees(scenes: &[(PathBuf, &Verdict)], corpus: &str, library: Option<&Path>) {
    assert!(!scenes.is_empty(), "oracle.json lists no {corpus} scenes");
    let mut mismatches = Vec::new();
    for (path, verdict) in scenes {
        match check(path, library) {
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

/// The own corpus' scenes (paths from the workspace) that do or do not name library files.
fn own_scenes(verdicts: &[Verdict], library: bool) -> Vec<(PathBuf, &Verdict)> {
    verdicts
        .iter()
        .filter(|v| !v.is_shared() && v.needs_library() == library)
        .map(|v| (Path::new(WORKSPACE).join(&v.key), v))
        .collect()
}

/// The shared corpus' scenes (paths from `root`) that do or do not name library files.
/// Scenes with `!` lines are included: radc expands genbox, genprism and xform (pipelines
/// too) itself, and reports other commands as not expanded, which agrees with Radiance's
/// verdict on every one of them.
fn shared_scenes<'a>(
    verdicts: &'a [Verdict],
    root: &Path,
    library: bool,
) -> Vec<(PathBuf, &'a Verdict)> {
    verdicts
        .iter()
        .filter(|v| v.needs_library() == library)
        .filter_map(|v| {
            v.key
                .strip_prefix(SHARED_KEY)
                .map(|rel| (root.join(rel), v))
        })
        .collect()
}

/// The own corpus' scenes that name no library file, on any machine.
#[test]
fn own_corpus_verdicts_match_radiance() {
    let verdicts = verdicts();
    assert_radc_agrees(&own_scenes(&verdicts, false), "corpus", None);
}

/// The own corpus' scenes that name library files (gensky's `skybright.cal`, genrev's
/// `rev.cal`, ...), with the oracle's library on RAYPATH.
#[test]
fn own_corpus_library_scenes_match_radiance() {
    let Some(lib) =
        radc_oracle::library_or_skip("scene_oracle::own_corpus_library_scenes_match_radiance")
    else {
        return;
    };
    let verdicts = verdicts();
    assert_radc_agrees(&own_scenes(&verdicts, true), "corpus library", Some(&lib));
}

/// Radiance's test scenes that name no library file.
#[test]
fn shared_radiance_corpus_verdicts_match_radiance() {
    let Some(root) = radc_oracle::shared_corpus_or_skip(
        "scene_oracle::shared_radiance_corpus_verdicts_match_radiance",
    ) else {
        return;
    };
    let verdicts = verdicts();
    assert_radc_agrees(
        &shared_scenes(&verdicts, &root, false),
        "shared Radiance",
        None,
    );
}

/// Radiance's test scenes that name library files, with the oracle's library on RAYPATH.
#[test]
fn shared_radiance_corpus_library_scenes_match_radiance() {
    let Some((root, lib)) = radc_oracle::shared_corpus_and_library_or_skip(
        "scene_oracle::shared_radiance_corpus_library_scenes_match_radiance",
    ) else {
        return;
    };
    let verdicts = verdicts();
    assert_radc_agrees(
        &shared_scenes(&verdicts, &root, true),
        "shared Radiance library",
        Some(&lib),
    );
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
