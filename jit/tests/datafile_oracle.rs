//! Data-file interpolation against Radiance: replays the goldens written by
//! `tests/oracle/regen_datafile_goldens.py` (rtrace evaluating a `brightdata` pattern) and
//! requires the same single-precision value at every query point. Data files come from
//! `tests/data/datafile` (always compared) and from Radiance's test scenes in
//! `../shared/corpus` (read in place; the tests of those are skipped visibly when that
//! folder is absent, and fail under `RADC_REQUIRE_ORACLE=1`: see the `radc-oracle` crate).

use std::path::{Path, PathBuf};

use radc_jit::datafile::{DataFile, DataFileErrorKind};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("jit lives inside the workspace")
        .to_path_buf()
}

/// The goldens whose `# source:` line names a data file of `origin` (`local` or
/// `corpus`), each with the data file's name.
fn goldens(origin: &str) -> Vec<(PathBuf, String)> {
    let dir = repo_root().join("tests/data/datafile/goldens");
    let mut goldens: Vec<(PathBuf, String)> = std::fs::read_dir(&dir)
        .expect("golden directory")
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "golden"))
        .filter_map(|p| {
            let text = std::fs::read_to_string(&p).expect("read golden");
            let label = text
                .lines()
                .find_map(|l| l.strip_prefix("# source: "))
                .unwrap_or_else(|| panic!("{} names no source", p.display()))
                .to_owned();
            let (from, name) = label
                .split_once(' ')
                .unwrap_or_else(|| panic!("bad golden source {label:?}"));
            assert!(
                matches!(from, "local" | "corpus"),
                "unknown golden source {label:?}"
            );
            (from == origin).then(|| (p, name.to_owned()))
        })
        .collect();
    goldens.sort();
    assert!(
        !goldens.is_empty(),
        "no {origin} goldens in {}",
        dir.display()
    );
    goldens
}

/// Compares one golden file against the data file it was made from; returns (points
/// checked, mismatches).
fn check_golden(golden: &Path, path: &Path) -> (usize, Vec<String>) {
    let text = std::fs::read_to_string(golden).expect("read golden");
    let data = DataFile::parse(&std::fs::read_to_string(path).expect("read data file"))
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
    (checked, mismatches)
}

/// Every golden of `origin`, its data file found in `folder`; all mismatches at once.
fn assert_goldens_match(origin: &str, folder: &Path) {
    let mut total = 0;
    let mut mismatches = Vec::new();
    for (golden, name) in goldens(origin) {
        let path = folder.join(&name);
        assert!(
            path.is_file(),
            "{}: data file {} is missing",
            golden.display(),
            path.display()
        );
        let (n, bad) = check_golden(&golden, &path);
        total += n;
        mismatches.extend(bad);
    }
    assert!(total > 0, "the {origin} goldens hold no points");
    assert!(
        mismatches.is_empty(),
        "{} of {total} points differ from rtrace:\n{}",
        mismatches.len(),
        mismatches.join("\n")
    );
}

#[test]
fn interpolation_matches_rtrace() {
    assert_goldens_match("local", &repo_root().join("tests/data/datafile"));
}

/// The same for the data files of Radiance's test scenes.
#[test]
fn interpolation_matches_rtrace_on_corpus_data_files() {
    let Some(corpus) = radc_oracle::shared_corpus_or_skip(
        "datafile_oracle::interpolation_matches_rtrace_on_corpus_data_files",
    ) else {
        return;
    };
    assert_goldens_match("corpus", &corpus.join("test/renders"));
}

/// Radiance's own test data files all load, whatever their layout.
#[test]
fn corpus_data_files_parse() {
    let Some(corpus) =
        radc_oracle::shared_corpus_or_skip("datafile_oracle::corpus_data_files_parse")
    else {
        return;
    };
    let dir = corpus.join("test/renders");
    let entries = std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let mut parsed = 0;
    for path in entries.filter_map(Result::ok).map(|e| e.path()) {
        if path.extension().is_some_and(|x| x == "dat") {
            let text = std::fs::read_to_string(&path).expect("read data file");
            if let Err(e) = DataFile::parse(&text) {
                panic!("{}: {e}", path.display());
            }
            parsed += 1;
        }
    }
    assert!(parsed > 0, "no .dat files in {}", dir.display());
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
