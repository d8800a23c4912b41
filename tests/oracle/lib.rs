//! How the workspace's tests find what lives outside the repository: the reference oracle
//! (real Radiance from PyPI's pyradiance, installed into `.oracle/` by
//! `bash tests/oracle/install.sh`) and Radiance's own test scenes in
//! `../shared/corpus/radiance/` (read in place, never copied).
//!
//! A fresh clone on a machine with nothing but Rust must pass `cargo test --workspace`, so a
//! test that needs either one asks here first: when it is there the test gets its folder;
//! when it is not, the test is skipped *visibly* (one `SKIPPED (needs ...): <test>` line on
//! the terminal, past libtest's output capture) and returns. CI installs the oracle and sets
//! `RADC_REQUIRE_ORACLE=1`: then a missing oracle or corpus fails the test by name instead,
//! so a green CI run proves that every such test ran.
//!
//! One crate (a dev-dependency of `radc`, `radc-jit` and `radc-lang`) rather than a file
//! included with `#[path]` into each test binary: the rule is written and compiled once, and
//! no test binary carries unused copies of it.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The command that installs the oracle, as the skip messages print it.
pub const INSTALL: &str = "bash tests/oracle/install.sh";

/// The variable that turns every skip into a failure (`.ci/run` sets it to `1`).
pub const REQUIRE: &str = "RADC_REQUIRE_ORACLE";

/// The workspace's root folder (this crate is `tests/oracle/`).
pub fn workspace() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.parent()
        .and_then(Path::parent)
        .unwrap_or(here)
        .to_path_buf()
}

/// Radiance's function library of the installed oracle
/// (`.oracle/lib/python3.*/site-packages/pyradiance/lib`: `rayinit.cal` and about 110 other
/// `.cal` files), where rcalc and rtrace find `-f` and scene files through RAYPATH.
pub fn library() -> Option<PathBuf> {
    std::fs::read_dir(workspace().join(".oracle/lib"))
        .ok()?
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with("python3"))
        .map(|e| e.path().join("site-packages/pyradiance/lib"))
        .find(|p| p.is_dir())
}

/// The shared corpus of Radiance's test scenes, `../shared/corpus/radiance` beside the
/// workspace, if it is there.
pub fn shared_corpus() -> Option<PathBuf> {
    let dir = workspace().join("../shared/corpus/radiance");
    dir.is_dir().then_some(dir)
}

/// Whether skipping is forbidden: `RADC_REQUIRE_ORACLE=1`.
pub fn required() -> bool {
    std::env::var_os(REQUIRE).is_some_and(|v| v == "1")
}

/// The oracle's library for `test`, or `None` after a visible skip; panics when it is
/// missing and [`required`].
pub fn library_or_skip(test: &str) -> Option<PathBuf> {
    library().or_else(|| skip(test, &format!("needs the oracle: {INSTALL}")))
}

/// The shared corpus for `test`, or `None` after a visible skip; panics when it is missing
/// and [`required`].
pub fn shared_corpus_or_skip(test: &str) -> Option<PathBuf> {
    shared_corpus().or_else(|| {
        skip(
            test,
            "needs the shared corpus: Radiance's test scenes in ../shared/corpus/radiance",
        )
    })
}

/// Both the shared corpus and the oracle's library, for a test that compares corpus
/// scenes naming library files; `None` after a visible skip naming what is missing.
pub fn shared_corpus_and_library_or_skip(test: &str) -> Option<(PathBuf, PathBuf)> {
    let corpus = shared_corpus_or_skip(test)?;
    let library = library_or_skip(test)?;
    Some((corpus, library))
}

/// Reports a skip: a failure under `RADC_REQUIRE_ORACLE=1`, else one line written straight
/// to the standard error stream. `eprintln!` would not do: libtest captures it and shows it
/// only for failing tests, and a skip must be seen on a passing run.
fn skip<T>(test: &str, why: &str) -> Option<T> {
    assert!(
        !required(),
        "{test} {why}; it is missing and {REQUIRE}=1 forbids skipping"
    );
    let line = format!("SKIPPED ({why}): {test}\n");
    let _ = std::io::stderr().lock().write_all(line.as_bytes());
    None
}
