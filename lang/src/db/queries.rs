//! The tracked queries. Each takes the database and an input and is re-run only when
//! something it read changed.

use std::cell::RefCell;
use std::path::PathBuf;

use super::{Db, FileSystem, SceneSet, SourceFile};
use crate::diagnostic::Diagnostic;
use crate::scene::scope::ModifierScope;
use crate::scene::{self, CommandExpander, Expansion, FileLookup, Keep, Lowering, ParsedScene};
use crate::schema::FileKind;
use crate::source::{FileId, LineIndex};

/// A file's syntax tree and its syntax diagnostics, parsed the first time it is
/// asked for and from then on kept up to date by the database's edits (which re-read
/// only the statements an edit touches). Queries that call it depend on the file's
/// contents, so they re-run after each edit.
pub fn parse_scene(db: &dyn Db, file: SourceFile) -> &ParsedScene {
    file.contents(db).scene.get_or_init(|| {
        let parsed = ParsedScene::new(file.id(db), file.text(db));
        db.note_parse(file);
        db.note_statements(file, parsed.syntax.items.len());
        parsed
    })
}

/// The file's line index, kept up to date by the database's edits.
pub fn line_index(db: &dyn Db, file: SourceFile) -> &LineIndex {
    &file.contents(db).lines
}

/// Which modifier each name refers to (navigation, completion, hover): built from
/// the parse the first time it is asked for, then kept up to date by the database's
/// edits while they change no name.
pub fn modifier_scope(db: &dyn Db, file: SourceFile) -> &ModifierScope {
    let contents = file.contents(db);
    contents
        .scope
        .get_or_init(|| ModifierScope::new(&parse_scene(db, file).syntax))
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
    let (scene, more) = lowering.finish();
    let mut all: Vec<Diagnostic> = parsed
        .iter()
        .flat_map(|p| p.diagnostics.iter().cloned())
        .collect();
    all.extend(more);
    if let Some(support) = db.render_support() {
        let refusals = scene::support::refusal_diagnostics(&scene, &all, support);
        all.extend(refusals);
    }
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

    /// Parses of every file so far.
    fn parses(db: &Database) -> u64 {
        db.parse_counts().iter().map(|(_, n)| n).sum()
    }

    #[test]
    fn editing_one_file_reparses_only_that_file() {
        let mut db = Database::default();
        let a = db.add_file("a.rad", MATERIAL);
        let b = db.add_file("b.rad", BALL);
        db.enable_logging();
        check_scene(&db, a);
        check_scene(&db, b);
        assert_eq!(parses(&db), 2);
        db.take_log();

        db.set_text(a, "void plastic blue\n0\n0\n5 .1 .1 .5 0 0\n");
        check_scene(&db, a);
        check_scene(&db, b);
        assert_eq!(
            db.parse_counts(),
            [("a.rad".into(), 2), ("b.rad".into(), 1)]
        );
        // The edit changed one statement of one file: only it was read again.
        let stats = db.parse_stats();
        assert_eq!((stats[0].1.whole, stats[0].1.statements), (1, 2));
        let log = db.take_log();
        assert_eq!(
            log.iter().filter(|l| l.starts_with("check_scene")).count(),
            1,
            "{log:?}"
        );

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
        assert_eq!(parses(&db), 1, "{log:?}");
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
        let before = parses(&db);
        db.set_text(geo, "red sphere ball\n0\n0\n4 0 0 0 2\n");
        assert!(check_scene_set(&db, set).is_empty());
        assert_eq!(parses(&db), before + 1);
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

/// Random edits applied one after another to a file of the database give exactly
/// what reading the new text afresh gives: the same syntax tree and syntax
/// diagnostics, the same line index and the same check.
#[cfg(test)]
mod edit_tests {
    use super::*;
    use crate::db::{AuxFiles, Database};
    use std::sync::Arc;

    /// Expands `!gen NAME` to a plastic called NAME (and `!gen` alone to a broken one).
    struct Generator;

    impl AuxFiles for Generator {
        fn exists(&self, _: &str, _: FileKind, _: &std::path::Path) -> bool {
            true
        }

        fn expand(&self, command: &str, _: &std::path::Path) -> Result<String, Expansion> {
            match command.strip_prefix("gen") {
                Some(name) if !name.trim().is_empty() => {
                    Ok(format!("void plastic {}\n0\n0\n5 1 1 1 0 0\n", name.trim()))
                }
                Some(_) => Ok("void plastic\n0\n0\n".into()),
                None => Err(Expansion::NotExpanded {
                    reason: "no".into(),
                }),
            }
        }
    }

    const START: &str = "# a room, é and 😀 in comments\n\
        void plastic red\n0\n0\n5 .5 .1 .1 0 0\n\
        red sphere ball\n0\n0\n4 0 0 0 1\n\
        !gen blue\n\
        blue polygon floor\n0\n0\n12\n 0 0 0\n 1 0 0\n 1 1 0\n 0 1 0\n\
        red alias rouge red\r\n\
        rouge ring 'a b'\r\n0\r\n0\r\n8 0 0 0 0 0 1 0 1\r\n\
        !gen green \\\n  more\n\
        void plastc bad 0 0 5 1 1 1 0 0\n\
        red cone c\n0\n0\n8 0 0 0 0 0 1 1 0.5\n\
        void plastic \"na me\"\n0\n0\n5 1 1 1 0 0\n";

    const PIECES: &[&str] = &[
        "1",
        "5",
        ".",
        "x",
        " ",
        "\n",
        "\r\n",
        "\r",
        "#",
        "# note\n",
        "!",
        "!gen q\n",
        "!ls\n",
        "\"",
        "'",
        "é",
        "😀",
        "\\",
        "\\\n",
        "0",
        "-",
        "e",
        "alias",
        "sphere",
        "plastic ",
        "void plastic m\n0\n0\n5 1 1 1 0 0\n",
        "red sphere s 0 0 4 1 2 3 1\n",
        "\t",
        "\0",
    ];

    /// A small deterministic generator (xorshift), so a failure is reproducible.
    struct Rng(u64);

    impl Rng {
        fn below(&mut self, n: usize) -> usize {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 % n.max(1) as u64) as usize
        }
    }

    /// A piece to insert; a NUL (which makes every later parse a whole one, until it
    /// is deleted) is kept rare.
    fn piece(rng: &mut Rng) -> &'static str {
        match PIECES[rng.below(PIECES.len())] {
            "\0" if rng.below(4) != 0 => "x",
            p => p,
        }
    }

    fn floor_boundary(text: &str, mut i: usize) -> usize {
        while !text.is_char_boundary(i) {
            i -= 1;
        }
        i
    }

    /// Picks an edit: a range of the text and what replaces it.
    fn random_edit(rng: &mut Rng, text: &str) -> (std::ops::Range<usize>, String) {
        let at = floor_boundary(text, rng.below(text.len() + 1));
        let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[at..].find('\n').map_or(text.len(), |i| at + i + 1);
        match rng.below(10) {
            // Delete a few characters.
            0 | 1 => {
                let end = floor_boundary(text, (at + 1 + rng.below(4)).min(text.len()));
                (at..end.max(at), String::new())
            }
            // Delete the line, or the lines up to some later point.
            2 => (line_start..line_end, String::new()),
            3 => {
                let end = floor_boundary(text, (line_end + rng.below(60)).min(text.len()));
                (line_start..end.max(line_start), String::new())
            }
            // Insert at the end of the file.
            4 => (
                text.len()..text.len(),
                PIECES[rng.below(PIECES.len())].into(),
            ),
            // Insert a piece, or replace a character with one.
            5..=7 => (at..at, piece(rng).into()),
            _ => {
                let end = text[at..].chars().next().map_or(at, |c| at + c.len_utf8());
                (at..end, piece(rng).into())
            }
        }
    }

    fn fresh_check(text: &str) -> Vec<Diagnostic> {
        let mut db = Database::new(Arc::new(Generator));
        let file = db.add_file("/x/a.rad", text);
        check_scene(&db, file).clone()
    }

    #[test]
    fn random_edits_match_reading_the_text_afresh() {
        let (mut whole, mut parses) = (0, 0);
        for seed in 1..=30u64 {
            let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ seed.wrapping_mul(0x2545_f491));
            let mut db = Database::new(Arc::new(Generator));
            let file = db.add_file("/x/a.rad", START);
            let mut text = START.to_string();
            parse_scene(&db, file);
            for step in 0..250 {
                let (range, inserted) = random_edit(&mut rng, &text);
                text.replace_range(range.clone(), &inserted);
                if step % 7 == 3 {
                    // A whole new text, as a client without range edits sends it.
                    db.set_text(file, text.clone());
                } else {
                    db.edit(file, range.clone(), &inserted);
                }
                assert_eq!(file.text(&db), &text);
                let fresh = ParsedScene::new(file.id(&db), &text);
                let context =
                    format!("seed {seed} step {step}: {range:?} -> {inserted:?} in {text:?}");
                assert_eq!(parse_scene(&db, file), &fresh, "{context}");
                assert_eq!(line_index(&db, file), &LineIndex::new(&text), "{context}");
                assert_eq!(
                    modifier_scope(&db, file),
                    &ModifierScope::new(&fresh.syntax),
                    "{context}"
                );
                if step % 5 == 0 {
                    assert_eq!(check_scene(&db, file), &fresh_check(&text), "{context}");
                }
            }
            let stats = db.parse_stats()[0].1;
            whole += stats.whole;
            parses += stats.parses;
        }
        // Most edits re-read a few statements, not the whole file (a NUL byte, while
        // it lasts, makes every parse a whole one).
        assert!(whole < parses / 4, "{whole} whole parses of {parses}");
    }

    /// The edits the random ones may miss, each checked against reading afresh.
    #[test]
    fn named_edge_cases_match_reading_afresh() {
        type Edit = fn(&str) -> (std::ops::Range<usize>, &'static str);
        let cases: &[(&str, Edit)] = &[
            // Two statements merged: the newline between the sphere and the command.
            ("merge", |t| {
                let at = t.find("0 1\n!gen blue").expect("merge") + 3;
                (at..at + 1, " ")
            }),
            // One statement split in two by a new header inside its arguments.
            ("split", |t| {
                let at = t.find(" 1 0 0\n 1 1 0").expect("split");
                (
                    at..at,
                    "\nvoid plastic cut\n0\n0\n5 1 1 1 0 0\nblue polygon f2 0 0 6",
                )
            }),
            // Inside a multi-line statement: one real of the polygon dropped.
            ("multi-line", |t| {
                let at = t.find(" 1 1 0\n").expect("real");
                (at..at + 2, "")
            }),
            // The command line edited: its expansion changes (and breaks).
            ("command", |t| {
                let at = t.find("!gen blue").expect("command") + 4;
                (at..at + 5, "")
            }),
            // A continued command line loses its backslash.
            ("continuation", |t| {
                let at = t.find("green \\").expect("continuation") + 6;
                (at..at + 1, "")
            }),
            // A comment marker and a quote typed at the start of lines.
            ("comment", |t| {
                let at = t.find("red sphere ball").expect("sphere");
                (at..at, "#")
            }),
            ("quote", |t| {
                let at = t.find("red cone").expect("cone");
                (at..at, "\"")
            }),
            // CRLF lines: the carriage return deleted, then a CRLF line added.
            ("crlf", |t| {
                let at = t.find("red\r\n").expect("crlf") + 3;
                (at..at + 1, "")
            }),
            ("crlf line", |t| {
                let at = t.find("rouge ring").expect("ring");
                (at..at, "void plastic crlf\r\n0\r\n0\r\n5 1 1 1 0 0\r\n")
            }),
            // Multibyte characters: in a comment, and as a name.
            ("utf-8", |t| {
                let at = t.find("é").expect("é");
                (at..at + "é".len(), "ü😀")
            }),
            ("utf-8 name", |t| {
                let at = t.find("sphere ball").expect("ball") + 7;
                (at..at + 4, "bälle")
            }),
            // At the end of the file: a digit appended to the last word, then a
            // half-written primitive.
            ("end", |t| (t.len() - 1..t.len(), "5")),
            ("end primitive", |t| {
                (t.len()..t.len(), "\nred sphere late\n0\n0\n4 1")
            }),
        ];
        for (name, edit) in cases {
            let mut db = Database::new(Arc::new(Generator));
            let file = db.add_file("/x/a.rad", START);
            check_scene(&db, file);
            modifier_scope(&db, file);
            let mut text = START.to_string();
            let (range, new) = edit(&text);
            assert!(text.is_char_boundary(range.start) && text.is_char_boundary(range.end));
            db.edit(file, range.clone(), new);
            text.replace_range(range, new);
            let fresh = ParsedScene::new(file.id(&db), &text);
            assert_eq!(parse_scene(&db, file), &fresh, "{name}: {text:?}");
            assert_eq!(line_index(&db, file), &LineIndex::new(&text), "{name}");
            assert_eq!(
                modifier_scope(&db, file),
                &ModifierScope::new(&fresh.syntax)
            );
            assert_eq!(check_scene(&db, file), &fresh_check(&text), "{name}");
            // And back: the original text, parsed and checked as at first.
            db.set_text(file, START);
            assert_eq!(
                parse_scene(&db, file),
                &ParsedScene::new(file.id(&db), START)
            );
            assert_eq!(check_scene(&db, file), &fresh_check(START), "{name} undone");
            let stats = db.parse_stats()[0].1;
            assert_eq!(stats.whole, 1, "{name}: {stats:?}");
        }
    }

    /// An edit that keeps every name, in order, but moves a reference into the
    /// statement before it: the reference now comes before the definition it bound
    /// to, so the scope is built again rather than edited.
    #[test]
    fn a_reference_moved_between_statements_rebinds() {
        let old = "void plastic m1\n0\n0\n5 1 1 1 0 0\n\
                   m1 mixfunc a 4 void void f . 0 0\n\
                   a mixfunc b 4 void void f . 0 0\n";
        let new = "void plastic m1\n0\n0\n5 1 1 1 0 0\n\
                   m1 mixfunc a 4 a void f . 0 0\n\
                   void mixfunc b 4 void void f . 0 0\n";
        let mut db = Database::default();
        let file = db.add_file("a.rad", old);
        let before = modifier_scope(&db, file).clone();
        assert!(
            before
                .references
                .iter()
                .any(|r| r.name == "a" && r.target.is_some())
        );
        db.set_text(file, new);
        let fresh = ModifierScope::new(&ParsedScene::new(file.id(&db), new).syntax);
        assert_eq!(modifier_scope(&db, file), &fresh);
        assert!(
            fresh
                .references
                .iter()
                .any(|r| r.name == "a" && r.target.is_none())
        );
    }

    /// A scene of many statements: an edit inside one re-reads that one alone, and
    /// the tree is still the whole file's.
    #[test]
    fn an_edit_reads_only_the_statements_it_touches() {
        let mut text = String::from("void plastic m\n0\n0\n5 .5 .5 .5 0 0\n");
        for i in 0..2000 {
            text.push_str(&format!("m sphere s{i}\n0\n0\n4 {i} 0 0 1.5\n"));
        }
        let mut db = Database::default();
        let file = db.add_file("a.rad", text.clone());
        assert!(check_scene(&db, file).is_empty());
        let radius = text.find("4 1000 0 0 1.5").expect("sphere 1000") + 13;
        let stats = |db: &Database| db.parse_stats()[0].1;
        // One digit, then one inserted (the spans after it move), then a new statement.
        for (range, new) in [
            (radius..radius + 1, "7"),
            (radius..radius, "2"),
            (0..0, "# x\n"),
        ] {
            let before = stats(&db);
            db.edit(file, range.clone(), new);
            text.replace_range(range, new);
            let after = stats(&db);
            assert_eq!(
                (after.parses, after.whole),
                (before.parses + 1, before.whole)
            );
            assert!(after.statements - before.statements <= 2, "{after:?}");
            assert_eq!(
                parse_scene(&db, file),
                &ParsedScene::new(file.id(&db), &text)
            );
        }
        // A statement deleted: the reading realigns at the next one.
        let sphere = text.find("m sphere s1500\n").expect("sphere 1500");
        let gone = sphere..sphere + "m sphere s1500\n0\n0\n4 1500 0 0 1.5\n".len();
        let before = stats(&db);
        db.edit(file, gone.clone(), "");
        text.replace_range(gone, "");
        assert!(stats(&db).statements - before.statements <= 2);
        assert_eq!(
            parse_scene(&db, file),
            &ParsedScene::new(file.id(&db), &text)
        );
        // A count changed: the primitive takes a real too few, and the rest of the
        // file is read by the recovering parser, as a full parse reads it.
        let count = text.find("4 1600 0 0").expect("sphere 1600");
        db.edit(file, count..count + 1, "3");
        text.replace_range(count..count + 1, "3");
        assert_eq!(
            parse_scene(&db, file),
            &ParsedScene::new(file.id(&db), &text)
        );
        assert_eq!(check_scene(&db, file), &fresh_check_default(&text));
        // Put back: the recovering parser's statements are replaced by clean ones.
        db.edit(file, count..count + 1, "4");
        text.replace_range(count..count + 1, "4");
        assert_eq!(
            parse_scene(&db, file),
            &ParsedScene::new(file.id(&db), &text)
        );
        assert!(check_scene(&db, file).is_empty());
    }

    fn fresh_check_default(text: &str) -> Vec<Diagnostic> {
        let mut db = Database::default();
        let file = db.add_file("a.rad", text);
        check_scene(&db, file).clone()
    }
}
