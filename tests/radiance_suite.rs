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

/// Runs `make -k TARGETS` in a copy of the suite's folder `suite` with radc's links
/// first on `PATH` and the oracle behind them; the make log, after asserting success.
fn run_suite(test: &str, suite: &str, targets: &[&str], links_needed: &[&str]) -> Option<String> {
    let (corpus, library) = radc_oracle::shared_corpus_and_library_or_skip(test)?;
    if Command::new("make").arg("--version").output().is_err() {
        eprintln!("SKIPPED (needs make): {test}");
        return None;
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
    for program in links_needed {
        assert!(links.join(program).exists(), "no link for {program}");
    }
    let work = dir.path().join(suite);
    copy_dir(&corpus.join("test").join(suite), &work);
    let oracle_bin = library.parent().expect("pyradiance").join("bin");
    let path = format!(
        "{}:{}:{}",
        links.display(),
        oracle_bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let out = Command::new("make")
        .arg("-k")
        .args(targets)
        .current_dir(&work)
        .env("PATH", &path)
        .env("RAYPATH", format!(".:{}", library.display()))
        .output()
        .expect("make runs");
    let log = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "test/{suite} failed:\n{log}");
    Some(log)
}

/// test/cal (cnt, rcalc, total, rlam, rsplit by radc; histo, tabfunc and ev by
/// Radiance), every comparison by radc's radcompare at the suite's tolerances.
#[test]
fn radiance_cal_tests_pass_with_radc_first_on_path() {
    let test = "radiance_suite::radiance_cal_tests_pass_with_radc_first_on_path";
    let needed = ["cnt", "rcalc", "total", "rlam", "rsplit", "radcompare"];
    let Some(log) = run_suite(test, "cal", &[], &needed) else {
        return;
    };
    assert_eq!(log.matches("radcompare ").count(), 9, "{log}");
}

/// test/gen for the generators radc implements (gendaymtx, replmarks and genblinds are
/// Radiance's, and the oracle's gendaymtx no longer matches the suite's reference).
#[test]
fn radiance_gen_tests_pass_with_radc_first_on_path() {
    let test = "radiance_suite::radiance_gen_tests_pass_with_radc_first_on_path";
    let targets = [
        "test-gensky",
        "test-genbox",
        "test-genrev",
        "test-genworm",
        "test-genprism",
        "test-gensurf",
    ];
    let needed = [
        "gensky",
        "genbox",
        "genrev",
        "genworm",
        "genprism",
        "gensurf",
        "radcompare",
    ];
    let Some(log) = run_suite(test, "gen", &targets, &needed) else {
        return;
    };
    assert_eq!(log.matches("radcompare ").count(), 6, "{log}");
}

/// test/util's vwrays test (vwrays and radcompare by radc).
#[test]
fn radiance_vwrays_test_passes_with_radc_first_on_path() {
    let test = "radiance_suite::radiance_vwrays_test_passes_with_radc_first_on_path";
    let Some(log) = run_suite(test, "util", &["test-vwrays"], &["vwrays", "radcompare"]) else {
        return;
    };
    assert!(
        log.contains("radcompare ref/vwrays.txt vwrays.txt"),
        "{log}"
    );
}
