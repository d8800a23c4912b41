//! Every `.cal` file of Radiance's library (as pyradiance ships it) must parse and
//! resolve with no errors. The files are not copied here: the test reads them from the
//! oracle installed in `.oracle/` (`bash tests/oracle/install.sh`; CI installs it and sets
//! `RADC_REQUIRE_ORACLE=1`, so there the test cannot be skipped), and is skipped visibly
//! without it (see the `radc-oracle` crate).

use radc_lang::cal::{Env, check};
use radc_lang::{Diagnostic, FileId, LineIndex};
use std::path::{Path, PathBuf};

fn cal_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "cal"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

fn show(path: &Path, text: &str, d: &Diagnostic) -> String {
    let (line, col) = LineIndex::new(text).line_col(text, d.span.start as usize);
    format!(
        "{}:{line}:{col}: {} {}",
        path.display(),
        d.code.id,
        d.message
    )
}

#[test]
fn every_library_file_parses_and_resolves() {
    let Some(dir) =
        radc_oracle::library_or_skip("cal_library::every_library_file_parses_and_resolves")
    else {
        return;
    };
    let files = cal_files(&dir);
    assert!(
        files.len() > 50,
        "only {} .cal files in {}",
        files.len(),
        dir.display()
    );
    let mut failures = Vec::new();
    for path in &files {
        let bytes = std::fs::read(path).unwrap_or_default();
        let text = String::from_utf8_lossy(&bytes);
        // A library file is used either by the renderer or by rcalc-like programs:
        // it must be clean in one of them.
        let renderer = check(FileId(0), &text, &Env::renderer());
        let rcalc = check(FileId(0), &text, &Env::rcalc());
        let best = if renderer.iter().filter(|d| d.is_error()).count()
            <= rcalc.iter().filter(|d| d.is_error()).count()
        {
            renderer
        } else {
            rcalc
        };
        failures.extend(
            best.iter()
                .filter(|d| d.is_error())
                .map(|d| show(path, &text, d)),
        );
    }
    assert!(
        failures.is_empty(),
        "{} errors:\n{}",
        failures.len(),
        failures.join("\n")
    );
    println!("{} library files checked", files.len());
}
