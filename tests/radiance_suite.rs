//! Radiance's own test suite with radc first on `PATH`: `radc links` makes links named
//! for the programs radc stands in for, and the suite's Makefile runs them (the programs
//! radc does not implement come from the oracle behind them). Needs the shared corpus and
//! the oracle.

mod common;

use std::path::Path;
use std::process::Command;

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("folder");
    for e in std::fs::read_dir(from).expect("read").flatten() {
        let p = e.path();
        let target = to.join(e.file_name());
        if p.is_dir() {
            copy_dir(&p, &target);
        } else {
            std::fs::copy(&p, &target).expect("copy");
        }
    }
}

/// test/cal (cnt, rcalc, total, rlam, rsplit by radc; histo, tabfunc and ev by
/// Radiance), every comparison by radc's radcompare at the suite's tolerances.
#[test]
fn radiance_cal_tests_pass_with_radc_first_on_path() {
    let test = "radiance_suite::radiance_cal_tests_pass_with_radc_first_on_path";
    let Some((corpus, library)) = radc_oracle::shared_corpus_and_library_or_skip(test) else {
        return;
    };
    if Command::new("make").arg("--version").output().is_err() {
        eprintln!("SKIPPED (needs make): {test}");
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let links = dir.path().join("links");
    std::fs::create_dir(&links).expect("links");
    let out = common::run(common::radc(["links", links.to_str().expect("path")]), b"");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for program in ["cnt", "rcalc", "total", "rlam", "rsplit", "radcompare"] {
        assert!(links.join(program).exists(), "no link for {program}");
    }
    let cal = dir.path().join("cal");
    copy_dir(&corpus.join("test/cal"), &cal);
    let oracle_bin = library.parent().expect("pyradiance").join("bin");
    let path = format!(
        "{}:{}:{}",
        links.display(),
        oracle_bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let out = Command::new("make")
        .arg("-k")
        .current_dir(&cal)
        .env("PATH", &path)
        .env("RAYPATH", format!(".:{}", library.display()))
        .output()
        .expect("make runs");
    let log = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "test/cal failed:\n{log}");
    assert_eq!(log.matches("radcompare ").count(), 9, "{log}");
}
