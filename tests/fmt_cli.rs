//! `radc fmt`: the command line, and the formatter's promises over every scene in the
//! test corpora: formatting is idempotent, keeps every word, and changes no
//! diagnostic (so no meaning).

use std::path::{Path, PathBuf};
use std::process::Command;

use radc_lang::db::{self, Database};
use radc_lang::scene::{self, AssumeFilesExist};
use radc_lang::{Diagnostic, FileId};

const UNTIDY: &str =
    "void plastic red 0 0 5 .5 .1 .1 .05 .1\nred polygon p 0 0 9 0 0 0 1 0 0 1 1 0\n";
const TIDY: &str = "void plastic red\n0\n0\n5 .5 .1 .1 .05 .1\nred polygon p\n0\n0\n9\n    0 0 0\n    1 0 0\n    1 1 0\n";

fn radc(args: &[&str], path: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_radc"))
        .args(args)
        .arg(path)
        .output()
        .expect("radc runs")
}

#[test]
fn prints_writes_and_checks() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("s.rad");
    std::fs::write(&path, UNTIDY).expect("write");

    let out = radc(&["fmt"], &path);
    assert!(out.status.success());
    assert_eq!(String::from_utf8_lossy(&out.stdout), TIDY);

    let out = radc(&["fmt", "--check"], &path);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        path.display().to_string()
    );

    let out = radc(&["fmt", "--write"], &path);
    assert!(out.status.success() && out.stdout.is_empty());
    assert_eq!(std::fs::read_to_string(&path).ok().as_deref(), Some(TIDY));
    assert_eq!(radc(&["fmt", "--check"], &path).status.code(), Some(0));
}

#[test]
fn refuses_broken_and_non_utf8_files() {
    let dir = tempfile::tempdir().expect("temp dir");
    let broken = dir.path().join("broken.rad");
    std::fs::write(&broken, "void plastic red 0 0 5 1 1").expect("write");
    let out = radc(&["fmt", "--write"], &broken);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("syntax errors"));
    assert_eq!(
        std::fs::read_to_string(&broken).ok().as_deref(),
        Some("void plastic red 0 0 5 1 1")
    );

    let latin1 = dir.path().join("latin1.rad");
    std::fs::write(&latin1, b"# caf\xe9\nvoid plastic red 0 0 5 1 1 1 0 0\n").expect("write");
    assert_eq!(radc(&["fmt", "--write"], &latin1).status.code(), Some(1));
    assert_eq!(radc(&["fmt", "--bogus"], &latin1).status.code(), Some(2));
}

fn scenes(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            scenes(&p, out);
        } else if p.extension().is_some_and(|x| x == "rad" || x == "mat") {
            out.push(p);
        }
    }
}

/// What a diagnostic says, without where (formatting moves words).
fn said(diags: &[Diagnostic]) -> Vec<(String, String)> {
    let mut v: Vec<_> = diags
        .iter()
        .map(|d| (d.code.id.to_string(), d.message.clone()))
        .collect();
    v.sort();
    v
}

#[test]
fn formatting_the_corpora_keeps_meaning() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    scenes(&root.join("tests/data"), &mut files);
    scenes(&root.join("examples"), &mut files);
    assert_formatting_keeps_meaning(files);
}

/// The same for Radiance's test scenes in `../shared/corpus` (skipped visibly without it).
#[test]
fn formatting_the_shared_corpus_keeps_meaning() {
    let Some(corpus) =
        radc_oracle::shared_corpus_or_skip("fmt_cli::formatting_the_shared_corpus_keeps_meaning")
    else {
        return;
    };
    let mut files = Vec::new();
    scenes(&corpus, &mut files);
    assert_formatting_keeps_meaning(files);
}

/// Formats each file twice (idempotent) and checks it again (same diagnostics).
fn assert_formatting_keeps_meaning(files: Vec<PathBuf>) {
    assert!(files.len() > 10, "scenes found: {}", files.len());
    let mut db = Database::default();
    let mut formatted_count = 0;
    for path in files {
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let file = db.add_file(path.display().to_string(), text.clone());
        let Some(once) = db::format_scene(&db, file).clone() else {
            continue;
        };
        formatted_count += 1;
        let again = db.add_file(path.display().to_string(), once.clone());
        assert_eq!(
            db::format_scene(&db, again).as_deref(),
            Some(once.as_str()),
            "{}",
            path.display()
        );
        let (_, before) = scene::check_text(FileId(0), &text, &AssumeFilesExist, true);
        let (_, after) = scene::check_text(FileId(0), &once, &AssumeFilesExist, true);
        assert_eq!(said(&before), said(&after), "{}", path.display());
    }
    assert!(formatted_count > 10, "formatted {formatted_count}");
}
