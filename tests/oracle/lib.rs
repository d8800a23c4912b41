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

/// What a skip message says a test needs when the oracle is missing: how to install it.
const NEEDS_ORACLE: &str = "needs the oracle: bash tests/oracle/install.sh";
/// The same when the shared corpus is missing: where it is expected.
const NEEDS_CORPUS: &str =
    "needs the shared corpus: Radiance's test scenes in ../shared/corpus/radiance";

/// The oracle's library for `test`, or `None` after a visible skip; panics when it is
/// missing and [`required`].
pub fn library_or_skip(test: &str) -> Option<PathBuf> {
    library().or_else(|| skip(test, NEEDS_ORACLE))
}

/// The shared corpus for `test`, or `None` after a visible skip; panics when it is missing
/// and [`required`].
pub fn shared_corpus_or_skip(test: &str) -> Option<PathBuf> {
    shared_corpus().or_else(|| skip(test, NEEDS_CORPUS))
}

/// Both the shared corpus and the oracle's library, for a test that compares corpus
/// scenes naming library files; `None` after a visible skip naming all that is missing.
pub fn shared_corpus_and_library_or_skip(test: &str) -> Option<(PathBuf, PathBuf)> {
    match (shared_corpus(), library()) {
        (Some(corpus), Some(library)) => Some((corpus, library)),
        (None, Some(_)) => skip(test, NEEDS_CORPUS),
        (Some(_), None) => skip(test, NEEDS_ORACLE),
        (None, None) => skip(test, &format!("{NEEDS_CORPUS}; {NEEDS_ORACLE}")),
    }
}

/// Reports a skip: a failure under `RADC_REQUIRE_ORACLE=1`, else one line written straight
/// to the standard error stream. `eprintln!` would not do: libtest captures it and shows it
/// only for failing tests, and a skip must be seen on a passing run.
fn skip<T>(test: &str, why: &str) -> Option<T> {
    skip_unless(required(), test, why, &mut std::io::stderr().lock())
}

/// [`skip`] with the requirement and the stream given, so that both can be tested.
fn skip_unless<T>(required: bool, test: &str, why: &str, out: &mut dyn Write) -> Option<T> {
    assert!(
        !required,
        "{test} {why}: not found here, and {REQUIRE}=1 forbids skipping it"
    );
    let _ = writeln!(out, "SKIPPED ({why}): {test}");
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_skip_says_what_is_needed_and_by_which_test() {
        let mut out = Vec::new();
        assert_eq!(
            skip_unless::<PathBuf>(false, "t", NEEDS_ORACLE, &mut out),
            None
        );
        assert_eq!(
            String::from_utf8_lossy(&out),
            "SKIPPED (needs the oracle: bash tests/oracle/install.sh): t\n"
        );
    }

    #[test]
    #[should_panic(expected = "t needs the oracle: bash tests/oracle/install.sh: not found here")]
    fn a_skip_fails_the_test_when_required() {
        let _ = skip_unless::<PathBuf>(true, "t", NEEDS_ORACLE, &mut Vec::new());
    }

    #[test]
    fn the_workspace_is_two_folders_up() {
        assert!(workspace().join("tests/oracle/install.sh").is_file());
    }
}
