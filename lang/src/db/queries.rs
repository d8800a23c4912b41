//! The tracked queries. Each takes the database and an input and is re-run only when
//! something it read changed.

use std::cell::RefCell;
use std::path::PathBuf;

use super::{Db, FileSystem, SceneSet, SourceFile};
use crate::diagnostic::Diagnostic;
use crate::scene::scope::ModifierScope;
use crate::scene::syntax::SceneFile;
use crate::scene::{self, CommandExpander, Expansion, FileLookup, Keep, Lowering};
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
    db.note_parse(file);
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
    let lookup = DbLookup::new(db, files);
    // Only what a check needs is kept (`radc check` lowers the same way): surfaces are
    // checked and dropped, so an edit re-lowers without building the scene's IR.
    let mut lowering = Lowering::new(&lookup, &lookup, Keep::Modifiers);
    for (f, p) in files.iter().zip(&parsed) {
        let warn_unused = f.warn_unused(db);
        for item in &p.syntax.items {
            lowering.item(item, warn_unused);
        }
    }
    let (_scene, more) = lowering.finish();
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

/// The lowering's view of the outside world, through [`Db::aux_files`]. Files it
/// brings in (command output, function files) get ids counted down from the top of
/// the id space, so they never collide with the database's own files.
struct DbLookup<'a> {
    db: &'a dyn Db,
    files: &'a [SourceFile],
    /// Ids handed out so far, each with the path of the scene file it came from.
    extra: RefCell<Vec<(FileId, PathBuf)>>,
}

/// `FileId(u32::MAX)` is the lowering's "no file" marker; extra ids count down below it.
const FIRST_EXTRA_ID: u32 = u32::MAX - 1;

impl<'a> DbLookup<'a> {
    fn new(db: &'a dyn Db, files: &'a [SourceFile]) -> Self {
        DbLookup {
            db,
            files,
            extra: RefCell::new(Vec::new()),
        }
    }

    /// The scene file a name in `from` is searched from (for extra files: the scene
    /// file whose command or function file brought them in).
    fn path_of(&self, from: FileId) -> PathBuf {
        if let Some(f) = self.files.iter().find(|f| f.id(self.db) == from) {
            return PathBuf::from(f.path(self.db));
        }
        let extra = self.extra.borrow();
        match extra.iter().find(|(id, _)| *id == from) {
            Some((_, path)) => path.clone(),
            None => self
                .files
                .first()
                .map(|f| PathBuf::from(f.path(self.db)))
                .unwrap_or_default(),
        }
    }

    fn new_id(&self, from: FileId) -> FileId {
        let path = self.path_of(from);
        let mut extra = self.extra.borrow_mut();
        let id = FileId(FIRST_EXTRA_ID.saturating_sub(extra.len() as u32));
        extra.push((id, path));
        id
    }
}

impl FileLookup for DbLookup<'_> {
    fn exists(&self, name: &str, kind: FileKind, from: FileId) -> bool {
        self.db.aux_files().exists(name, kind, &self.path_of(from))
    }

    fn read(&self, name: &str, kind: FileKind, from: FileId) -> Option<String> {
        self.db.aux_files().read(name, kind, &self.path_of(from))
    }

    fn read_head(&self, name: &str, kind: FileKind, from: FileId, max: usize) -> Option<Vec<u8>> {
        self.db
            .aux_files()
            .read_head(name, kind, &self.path_of(from), max)
    }

    fn load(&self, name: &str, kind: FileKind, from: FileId) -> Option<(FileId, String)> {
        let text = self.read(name, kind, from)?;
        Some((self.new_id(from), text))
    }
}

impl CommandExpander for DbLookup<'_> {
    fn expand(&self, command: &str, from: FileId, _depth: u32) -> Expansion {
        match self.db.aux_files().expand(command, &self.path_of(from)) {
            Ok(text) => Expansion::Text {
                file: self.new_id(from),
                text,
            },
            Err(Expansion::Partial {
                text,
                message,
                hint,
                ..
            }) => Expansion::Partial {
                file: self.new_id(from),
                text,
                message,
                hint,
            },
            Err(why) => why,
        }
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

    /// Expands `!gen NAME` to a plastic called NAME.
    struct Generator;

    impl crate::db::AuxFiles for Generator {
        fn exists(&self, _: &str, _: FileKind, _: &std::path::Path) -> bool {
            true
        }

        fn expand(&self, command: &str, _: &std::path::Path) -> Result<String, Expansion> {
            match command.strip_prefix("gen ") {
                Some(name) => Ok(format!("void plastic {name}\n0\n0\n5 1 1 1 0 0\n")),
                None => Err(Expansion::NotExpanded {
                    reason: "no".into(),
                }),
            }
        }
    }

    #[test]
    fn commands_expand_through_the_front_end() {
        let mut db = Database::new(std::sync::Arc::new(Generator));
        let text = "!gen red\nred sphere ball\n0\n0\n4 0 0 0 1\n!other\n";
        let a = db.add_file("a.rad", text);
        let codes: Vec<_> = check_scene(&db, a).iter().map(|d| d.code.id).collect();
        assert_eq!(codes, ["W0303"]);
        // A problem inside the output points back at the command line.
        db.set_text(a, "!gen x y\n");
        let diags = check_scene(&db, a);
        assert!(!diags.is_empty());
        assert!(diags.iter().all(|d| d.span.file != a.id(&db)));
        assert!(
            diags
                .iter()
                .all(|d| d.labels.iter().any(|l| l.span.file == a.id(&db)))
        );
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
