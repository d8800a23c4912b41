//! Data-file interpolation against Radiance: replays the goldens written by
//! `tests/oracle/regen_datafile_goldens.py` (rtrace evaluating a `brightdata` pattern) and
//! requires the same single-precision value at every query point. Data files come from
//! Radiance's test scenes in `../shared/corpus` (read in place; skipped with a notice when
//! that directory is absent) and from `tests/data/datafile`.

use std::path::{Path, PathBuf};

use radc_jit::datafile::{DataFile, DataFileErrorKind};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("jit lives inside the workspace")
        .to_path_buf()
}

/// The data file a golden's `# source:` line names, if it is present.
fn source_path(label: &str) -> Option<PathBuf> {
    let root = repo_root();
    let path = match label.split_once(' ')? {
        ("corpus", name) => root
            .join("../shared/corpus/radiance/test/renders")
            .join(name),
        ("local", name) => root.join("tests/data/datafile").join(name),
        _ => panic!("unknown golden source {label:?}"),
    };
    path.is_file().then_some(path)
}

/// Compares one golden file; returns (points checked, mismatches), or None if its data file
/// is not available here.
fn check_golden(golden: &Path) -> Option<(usize, Vec<String>)> {
    let text = std::fs::read_to_string(golden).expect("read golden");
    let label = text
        .lines()
        .find_map(|l| l.strip_prefix("# source: "))
        .expect("golden names its source");
    let Some(path) = source_path(label) else {
        eprintln!(
            "notice: {label} is not available; skipping {}",
            golden.display()
        );
        return None;
    };
    let data = DataFile::parse(&std::fs::read_to_string(&path).expect("read data file"))
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let name = golden
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut checked = 0;
    let mut mismatches = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let (coords, value) = line.split_once(" = ").expect("'coords = value' line");
        let coords: Vec<f64> = coords
            .split(' ')
            .map(|c| c.parse().expect("coordinate"))
            .collect();
        let expected: f64 = value.parse().expect("value");
        let actual = data.eval(&coords);
        // rtrace keeps colours in single precision: compare at that precision, exactly.
        let same = (actual as f32 == expected as f32) || (actual.is_nan() && expected.is_nan());
        if !same {
            mismatches.push(format!(
                "{name}: at {coords:?} rtrace gives {expected:e}, radc {actual:e}"
            ));
        }
        checked += 1;
    }
    Some((checked, mismatches))
}

#[test]
fn interpolation_matches_rtrace() {
    let dir = repo_root().join("tests/data/datafile/goldens");
    let mut goldens: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("golden directory")
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "golden"))
        .collect();
    goldens.sort();
    assert!(!goldens.is_empty(), "no goldens in {}", dir.display());
    let mut total = 0;
    let mut mismatches = Vec::new();
    for golden in &goldens {
        if let Some((n, bad)) = check_golden(golden) {
            total += n;
            mismatches.extend(bad);
        }
    }
    assert!(
        mismatches.is_empty(),
        "{} of {total} points differ from rtrace:\n{}",
        mismatches.len(),
        mismatches.join("\n")
    );
}

/// Radiance's own test data files all load, whatever their layout.
#[test]
fn corpus_data_files_parse() {
    let dir = repo_root().join("../shared/corpus/radiance/test/renders");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("notice: {} not found; skipping", dir.display());
        return;
    };
    for path in entries.filter_map(Result::ok).map(|e| e.path()) {
        if path.extension().is_some_and(|x| x == "dat") {
            let text = std::fs::read_to_string(&path).expect("read data file");
            if let Err(e) = DataFile::parse(&text) {
                panic!("{}: {e}", path.display());
            }
        }
    }
}

/// Radiance's message class for a load error. Radiance words it "unexpected EOF" whenever
/// the file is at its end when the error is noticed, even if the last word was merely bad;
/// radc names the actual problem, so that case is accepted as either.
fn radiance_classes(kind: &DataFileErrorKind, text: &str) -> Vec<&'static str> {
    let class = match kind {
        DataFileErrorKind::UnexpectedEnd { .. } => "unexpected EOF",
        DataFileErrorKind::BadDimensionCount(_) => "bad number of dimensions",
        _ => "bad format",
    };
    let at_eof = !text.ends_with(|c: char| c.is_ascii_whitespace());
    if at_eof && class == "bad format" {
        vec![class, "unexpected EOF"]
    } else {
        vec![class]
    }
}

/// Files Radiance accepts load here with the same value at (0.5, ...); files it rejects are
/// rejected here too, with an error of the same kind.
#[test]
fn malformed_files_are_judged_as_radiance_does() {
    let root = repo_root().join("tests/data/datafile");
    let golden = std::fs::read_to_string(root.join("malformed.golden")).expect("golden");
    let mut problems = Vec::new();
    let mut count = 0;
    for line in golden.lines().filter(|l| !l.starts_with('#')) {
        let (file, outcome) = line.split_once(": ").expect("'file: outcome' line");
        let bytes = std::fs::read(root.join("malformed").join(file)).expect("malformed file");
        let text = String::from_utf8_lossy(&bytes);
        let parsed = DataFile::parse(&text);
        count += 1;
        match (outcome.split_once(' '), parsed) {
            (Some(("accepted", value)), Ok(data)) => {
                let expected: f64 = value.parse().expect("value");
                let actual = data.eval(&vec![0.5; data.dimensions()]);
                if actual as f32 != expected as f32 && !(actual.is_nan() && expected.is_nan()) {
                    problems.push(format!("{file}: rtrace gives {expected}, radc {actual}"));
                }
            }
            (Some(("accepted", _)), Err(e)) => {
                problems.push(format!("{file}: Radiance accepts it, radc says {e}"));
            }
            (Some(("rejected", message)), Ok(_)) => {
                problems.push(format!(
                    "{file}: Radiance rejects it ({message}), radc accepts it"
                ));
            }
            (Some(("rejected", message)), Err(e)) => {
                if !radiance_classes(&e.kind, &text).contains(&message) {
                    problems.push(format!("{file}: Radiance says {message}, radc says {e}"));
                }
            }
            _ => panic!("malformed.golden: bad line {line:?}"),
        }
    }
    assert!(count > 0, "no malformed cases");
    assert!(
        problems.is_empty(),
        "{} of {count} malformed files judged differently:\n{}",
        problems.len(),
        problems.join("\n")
    );
}
