//! The tracked queries. Each takes the database and an input and is re-run only when
//! something it read changed.

use std::path::Path;

use super::{Db, FileSystem, SceneSet, SourceFile};
use crate::diagnostic::Diagnostic;
use crate::scene::scope::ModifierScope;
use crate::scene::syntax::SceneFile;
use crate::scene::{self, FileLookup, LowerInput};
use crate::schema::FileKind;
use crate::source::{self, FileId, LineIndex};

/// A file's syntax tree and its syntax diagnostics.
#[derive(Clone, Debug, PartialEq)]
pub struct ParsedScene {
    pub syntax: SceneFile,
    pub diagnostics: Vec<Diagnostic>,
}

/// Parses one file. Text goes through [`source::decode`] first so a NUL byte is
/// reported exactly as `radc check` reports it when reading from disk.
#[salsa::tracked(returns(ref), no_eq)]
pub fn parse_scene(db: &dyn Db, file: SourceFile) -> ParsedScene {
    let id = file.id(db);
    let text = file.text(db);
    let (syntax, mut diagnostics) = if text.contains('\0') {
        let (clean, mut diags) = source::decode(id, text.as_bytes());
        let (syntax, more) = scene::parse(id, &clean);
        diags.extend(more);
        (syntax, diags)
    } else {
        scene::parse(id, text)
    };
    diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
    ParsedScene {
        syntax,
        diagnostics,
    }
}

#[salsa::tracked(returns(ref), no_eq)]
pub fn line_index(db: &dyn Db, file: SourceFile) -> LineIndex {
    LineIndex::new(file.text(db))
}

/// Which modifier each name refers to (navigation, completion, hover).
#[salsa::tracked(returns(ref), no_eq)]
pub fn modifier_scope(db: &dyn Db, file: SourceFile) -> ModifierScope {
    ModifierScope::new(&parse_scene(db, file).syntax)
}

/// Every diagnostic for one file checked as a scene on its own, as `radc check FILE`
/// reports them (same codes, messages and order).
#[salsa::tracked(returns(ref), no_eq)]
pub fn check_scene(db: &dyn Db, file: SourceFile) -> Vec<Diagnostic> {
    check_files(db, &[file])
}

/// Every diagnostic for files read in order as one scene (`radc check a.mat b.rad`).
#[salsa::tracked(returns(ref), no_eq)]
pub fn check_scene_set(db: &dyn Db, set: SceneSet) -> Vec<Diagnostic> {
    check_files(db, set.files(db))
}

fn check_files(db: &dyn Db, files: &[SourceFile]) -> Vec<Diagnostic> {
    // The lookup below reads the disk through the front end: depend on its generation.
    if let Some(fs) = FileSystem::try_get(db) {
        fs.generation(db);
    }
    let parsed: Vec<&ParsedScene> = files.iter().map(|f| parse_scene(db, *f)).collect();
    let inputs: Vec<LowerInput<'_>> = files
        .iter()
        .zip(&parsed)
        .map(|(f, p)| LowerInput {
            file: f.id(db),
            syntax: &p.syntax,
            warn_unused: f.warn_unused(db),
        })
        .collect();
    let lookup = DbLookup { db, files };
    let (_scene, more) = scene::lower(&inputs, &lookup);
    let mut all: Vec<Diagnostic> = parsed
        .iter()
        .flat_map(|p| p.diagnostics.iter().cloned())
        .collect();
    all.extend(more);
    all.sort_by_key(|d| (d.span.file, d.span.start));
    all
}

/// The file laid out in Radiance's conventional form, or `None` when it has syntax
/// errors (formatting a misread file would move words between primitives).
#[salsa::tracked(returns(ref), no_eq)]
pub fn format_scene(db: &dyn Db, file: SourceFile) -> Option<String> {
    let parsed = parse_scene(db, file);
    scene::format::format(file.text(db), &parsed.syntax, &parsed.diagnostics)
}

struct DbLookup<'a> {
    db: &'a dyn Db,
    files: &'a [SourceFile],
}

impl FileLookup for DbLookup<'_> {
    /// Searches from the folder of the file that names `name`.
    fn exists(&self, name: &str, kind: FileKind, from: FileId) -> bool {
        let path = self
            .files
            .iter()
            .find(|f| f.id(self.db) == from)
            .map_or("", |f| f.path(self.db).as_str());
        self.db.aux_files().exists(name, kind, Path::new(path))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::db::Database;

    const MATERIAL: &str = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\n";
    const BALL: &str = "void plastic red\n0\n0\n5 .5 .1 .1 0 0\nred sphere ball\n0\n0\n4 0 0 0 1\n";

    fn parses(log: &[String]) -> usize {
        log.iter().filter(|l| l.starts_with("parse_scene")).count()
    }

    #[test]
    fn editing_one_file_reparses_only_that_file() {
        let mut db = Database::default();
        let a = db.add_file("a.rad", MATERIAL);
        let b = db.add_file("b.rad", BALL);
        db.enable_logging();
        check_scene(&db, a);
        check_scene(&db, b);
        assert_eq!(parses(&db.take_log()), 2);

        db.set_text(a, "void plastic blue\n0\n0\n5 .1 .1 .5 0 0\n");
        check_scene(&db, a);
        check_scene(&db, b);
        let log = db.take_log();
        assert_eq!(parses(&log), 1, "{log:?}");

        // Nothing changed: nothing runs.
        check_scene(&db, a);
        check_scene(&db, b);
        assert!(db.take_log().is_empty());
    }

    #[test]
    fn a_file_system_change_rechecks_without_reparsing() {
        let mut db = Database::default();
        let a = db.add_file("a.rad", BALL);
        db.enable_logging();
        check_scene(&db, a);
        db.take_log();
        db.file_system_changed();
        check_scene(&db, a);
        let log = db.take_log();
        assert_eq!(parses(&log), 0, "{log:?}");
        assert!(log.iter().any(|l| l.starts_with("check_scene")), "{log:?}");
    }

    #[test]
    fn a_scene_set_resolves_across_files_and_tracks_each() {
        let mut db = Database::default();
        let mat = db.add_file("a.mat", MATERIAL);
        let geo = db.add_file("b.rad", "red sphere ball\n0\n0\n4 0 0 0 1\n");
        let set = db.scene_set(vec![mat, geo]);
        assert!(check_scene_set(&db, set).is_empty());
        // Alone, the geometry's modifier is undefined.
        let alone: Vec<_> = check_scene(&db, geo).iter().map(|d| d.code.id).collect();
        assert_eq!(alone, ["E0301"]);
        db.enable_logging();
        db.set_text(geo, "red sphere ball\n0\n0\n4 0 0 0 2\n");
        assert!(check_scene_set(&db, set).is_empty());
        assert_eq!(parses(&db.take_log()), 1);
    }

    #[test]
    fn diagnostics_match_check_text() {
        let mut db = Database::default();
        let text = "red sphere ball\n0\n0\n4 0 0 0 1\nvoid plastc x\n0\n0\n5 1 1 1 0 0\n";
        let a = db.add_file("a.rad", text);
        let (_, mut expected) = scene::check_text(a.id(&db), text, &scene::AssumeFilesExist, true);
        expected.sort_by_key(|d| (d.span.file, d.span.start));
        assert_eq!(check_scene(&db, a), &expected);
        assert!(!expected.is_empty());
    }
}
