//! The incremental database shared by the CLI and the language server, in the shape of
//! salsa's `examples/calc`: files are inputs, everything computed from them is a
//! tracked query, so an edit to one file re-parses that file alone.
//!
//! `lang` still does no IO here: the front end sets each file's text, and answers
//! "does this auxiliary file exist?" through an [`AuxFiles`] it installs on the
//! database. Because that answer comes from outside salsa's view, the front end bumps
//! [`FileSystem::generation`] when the disk may have changed, which re-runs the checks
//! (not the parses).
//!
//! Inputs: `SourceFile { id, path, contents, warn_unused }` and the singleton
//! `FileSystem { generation }`. `contents` keeps up to date, as the text is edited, what
//! would otherwise be recomputed from the whole text: the line index, the parse as a scene
//! and the modifier scope; it changes only through `Database::set_text` and
//! `Database::edit`, which re-read only the statements an edit touches
//! (`scene::reparse`). The checks lower the memoized syntax trees with `Keep::Modifiers`,
//! as `radc check` does. Auxiliary files and `!` lines come from an `AuxFiles` trait object
//! the front end installs; since salsa cannot see the disk, the front end bumps
//! `FileSystem::generation` when files may have changed (checks re-run, parses do not).
//! Pinned by tests on `Database::parse_stats` (parses, whole parses and statements read,
//! per file).

mod cal;
mod queries;

pub use crate::scene::ParsedScene;
pub use cal::{
    CalDef, CalIndex, CalName, CalUse, ParsedCal, cal_index, cal_values, check_cal, parse_cal,
};
pub use queries::{
    check_scene, check_scene_set, format_scene, line_index, modifier_scope, parse_scene,
};

use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

use crate::scene::Expansion;
use crate::scene::reparse::Reparse;
use crate::scene::scope::ModifierScope;
use crate::schema::FileKind;
use crate::source::{FileId, LineIndex};

/// One scene file the front end has handed to the database.
#[salsa::input(debug)]
pub struct SourceFile {
    /// Stamped on every span computed from this file.
    #[returns(copy)]
    pub id: FileId,
    /// Where the file lives; auxiliary files are searched relative to its folder.
    pub path: String,
    /// Changed only through [`Database::set_text`] and [`Database::edit`], which keep
    /// the line index and the parse in step with the text.
    contents: FileContents,
    /// Whether unused modifiers are worth a warning (not in `.mat` libraries).
    #[returns(copy)]
    pub warn_unused: bool,
}

impl SourceFile {
    pub fn text(self, db: &dyn Db) -> &String {
        &self.contents(db).text
    }
}

/// A file's text and what is kept up to date with it as it is edited, instead of
/// being computed again from the whole text: its line index, and (once something
/// asked for it) its parse as a scene, of which an edit re-reads only the statements
/// it can change. Both are pure functions of the text (tested against computing them
/// afresh), so keeping them here rather than in tracked queries changes no answer.
#[derive(Debug)]
pub struct FileContents {
    text: String,
    lines: LineIndex,
    scene: OnceLock<ParsedScene>,
    /// Which modifier each name refers to, from `scene`; edited with it while an
    /// edit changes no name (then only spans move), else built again when asked.
    scope: OnceLock<ModifierScope>,
}

impl FileContents {
    fn new(text: String) -> Self {
        FileContents {
            lines: LineIndex::new(&text),
            text,
            scene: OnceLock::new(),
            scope: OnceLock::new(),
        }
    }

    /// Replaces bytes `start..old_end` with `inserted` (on character boundaries).
    fn edit(
        &mut self,
        file: FileId,
        start: usize,
        old_end: usize,
        inserted: &str,
    ) -> Option<Reparse> {
        self.text.replace_range(start..old_end, inserted);
        self.edited(file, start, old_end, start + inserted.len())
    }

    /// Brings the index and the parse up to date: bytes `start..old_end` of the old
    /// text are `start..new_end` of the text now.
    fn edited(
        &mut self,
        file: FileId,
        start: usize,
        old_end: usize,
        new_end: usize,
    ) -> Option<Reparse> {
        self.lines.edit(&self.text, start, old_end, new_end);
        let Some(parsed) = self.scene.get_mut() else {
            self.scope = OnceLock::new();
            return None;
        };
        let text = &self.text;
        let scope = &mut self.scope;
        let edited = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let reparse = parsed.edit(file, text, start, old_end, new_end);
            let kept = match (scope.get_mut(), &reparse.change) {
                (Some(scope), Some(change)) => scope.edited(&parsed.syntax, change),
                _ => false,
            };
            if !kept {
                *scope = OnceLock::new();
            }
            reparse
        }));
        // A bug in the reparse must not leave a wrong tree behind: forget it, and
        // the next query parses the whole text.
        edited
            .map_err(|_| {
                self.scene = OnceLock::new();
                self.scope = OnceLock::new();
            })
            .ok()
    }
}

/// How often a file was parsed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ParseCount {
    /// Parses of the file, whole or of the statements an edit touched.
    pub parses: u64,
    /// Of those, parses of the whole file.
    pub whole: u64,
    /// Statements read, over all parses.
    pub statements: u64,
}

/// Files read in order as one scene, as `oconv` reads its arguments (materials first,
/// then the geometry that uses them).
#[salsa::input(debug)]
pub struct SceneSet {
    pub files: Vec<SourceFile>,
}

/// What the database knows of the file system: only a generation number, bumped by
/// the front end whenever files on disk may have appeared or vanished.
#[salsa::input(debug, singleton)]
pub struct FileSystem {
    #[returns(copy)]
    pub generation: u64,
}

/// The outside world as the checks see it, answered by the front end: auxiliary files
/// named by a scene, searched from the folder of the scene file at `scene_path` (then
/// wherever the front end looks), and `!` command lines. The optional methods mirror
/// [`crate::scene::FileLookup`]'s; their defaults skip the checks that need them.
pub trait AuxFiles: Send + Sync {
    fn exists(&self, name: &str, kind: FileKind, scene_path: &Path) -> bool;

    /// Where an auxiliary file is, for editors to open it.
    fn locate(
        &self,
        _name: &str,
        _kind: FileKind,
        _scene_path: &Path,
    ) -> Option<std::path::PathBuf> {
        None
    }

    /// The text of an auxiliary file, for the checks that look inside it.
    fn read(&self, _name: &str, _kind: FileKind, _scene_path: &Path) -> Option<String> {
        None
    }

    /// The first `max` bytes of an auxiliary file.
    fn read_head(
        &self,
        _name: &str,
        _kind: FileKind,
        _scene_path: &Path,
        _max: usize,
    ) -> Option<Vec<u8>> {
        None
    }

    /// The output of a `!` command line (the text after `!`), or why there is none
    /// (an [`Expansion::Partial`] holds output and a failure; the database gives its
    /// text a file id, replacing the one given). The default runs nothing.
    fn expand(&self, _command: &str, _scene_path: &Path) -> Result<String, Expansion> {
        Err(Expansion::NotExpanded {
            reason: "radc does not run commands here".into(),
        })
    }
}

/// The bytes in which two texts differ: `start..old_end` of `old` became
/// `start..new_end` of `new` (on character boundaries of both).
fn differing_bytes(old: &str, new: &str) -> (usize, usize, usize) {
    let (a, b) = (old.as_bytes(), new.as_bytes());
    let mut prefix = common_prefix(a, b);
    while !old.is_char_boundary(prefix) || !new.is_char_boundary(prefix) {
        prefix -= 1;
    }
    let most = a.len().min(b.len()) - prefix;
    let mut suffix = common_suffix(&a[a.len() - most..], &b[b.len() - most..]);
    while !old.is_char_boundary(a.len() - suffix) || !new.is_char_boundary(b.len() - suffix) {
        suffix -= 1;
    }
    (prefix, a.len() - suffix, b.len() - suffix)
}

/// Whole blocks are compared with `memcmp`, then bytes.
const BLOCK: usize = 4096;

fn common_prefix(a: &[u8], b: &[u8]) -> usize {
    let n = a.len().min(b.len());
    let mut i = 0;
    while i + BLOCK <= n && a[i..i + BLOCK] == b[i..i + BLOCK] {
        i += BLOCK;
    }
    i + a[i..n]
        .iter()
        .zip(&b[i..n])
        .take_while(|(x, y)| x == y)
        .count()
}

fn common_suffix(a: &[u8], b: &[u8]) -> usize {
    let n = a.len().min(b.len());
    let (a, b) = (&a[a.len() - n..], &b[b.len() - n..]);
    let mut k = 0;
    while k + BLOCK <= n && a[n - k - BLOCK..n - k] == b[n - k - BLOCK..n - k] {
        k += BLOCK;
    }
    k + a[..n - k]
        .iter()
        .rev()
        .zip(b[..n - k].iter().rev())
        .take_while(|(x, y)| x == y)
        .count()
}

/// For front ends without a file system, and for tests.
pub struct AssumeAuxFilesExist;

impl AuxFiles for AssumeAuxFilesExist {
    fn exists(&self, _: &str, _: FileKind, _: &Path) -> bool {
        true
    }
}

/// The queries' view of the database.
#[salsa::db]
pub trait Db: salsa::Database {
    fn aux_files(&self) -> &dyn AuxFiles;

    /// The renderer's judgement of what it would refuse (W0307), when the front end
    /// has one to give; `lang` cannot know it.
    fn render_support(&self) -> Option<&dyn crate::scene::RenderSupport> {
        None
    }

    /// Called each time a file is parsed (a query really ran, not a memo reused):
    /// how the server's statistics show that an edit re-parses only the edited file.
    fn note_parse(&self, _file: SourceFile) {}

    /// Called when a whole scene file was parsed, with its number of statements.
    fn note_statements(&self, _file: SourceFile, _statements: usize) {}
}

/// The one database implementation. Cloning it is cheap (a snapshot for readers).
#[salsa::db]
#[derive(Clone)]
pub struct Database {
    storage: salsa::Storage<Self>,
    aux_files: Arc<dyn AuxFiles>,
    next_id: Arc<Mutex<u32>>,
    /// Names of the queries salsa executed (not reused), when logging is on: how the
    /// tests see incrementality.
    log: Arc<Mutex<Option<Vec<String>>>>,
    /// How many times each file (by path) was parsed.
    parses: Arc<Mutex<HashMap<String, ParseCount>>>,
    render_support: Option<Arc<dyn crate::scene::RenderSupport>>,
}

#[salsa::db]
impl salsa::Database for Database {}

#[salsa::db]
impl Db for Database {
    fn aux_files(&self) -> &dyn AuxFiles {
        &*self.aux_files
    }

    fn render_support(&self) -> Option<&dyn crate::scene::RenderSupport> {
        self.render_support.as_deref()
    }

    fn note_parse(&self, file: SourceFile) {
        self.count(file, |c| {
            c.parses += 1;
            c.whole += 1;
        });
    }

    fn note_statements(&self, file: SourceFile, statements: usize) {
        self.count(file, |c| c.statements += statements as u64);
    }
}

impl Default for Database {
    fn default() -> Self {
        Database::new(Arc::new(AssumeAuxFilesExist))
    }
}

impl Database {
    pub fn new(aux_files: Arc<dyn AuxFiles>) -> Self {
        let log: Arc<Mutex<Option<Vec<String>>>> = Arc::default();
        let sink = log.clone();
        let storage = salsa::Storage::new(Some(Box::new(move |event: salsa::Event| {
            if let salsa::EventKind::WillExecute { database_key } = event.kind {
                let mut guard = sink.lock().unwrap_or_else(|e| e.into_inner());
                if let Some(log) = guard.as_mut() {
                    log.push(format!("{database_key:?}"));
                }
            }
        })));
        let db = Database {
            storage,
            aux_files,
            next_id: Arc::default(),
            log,
            parses: Arc::default(),
            render_support: None,
        };
        FileSystem::new(&db, 0);
        db
    }

    /// Checks report what this renderer would refuse (W0307), as `radc check` does.
    pub fn with_render_support(mut self, support: Arc<dyn crate::scene::RenderSupport>) -> Self {
        self.render_support = Some(support);
        self
    }

    /// Adds a file with a fresh [`FileId`].
    pub fn add_file(&mut self, path: impl Into<String>, text: impl Into<String>) -> SourceFile {
        let path = path.into();
        let warn_unused = !path.ends_with(".mat");
        let id = {
            let mut next = self.next_id.lock().unwrap_or_else(|e| e.into_inner());
            let id = FileId(*next);
            *next = next.saturating_add(1);
            id
        };
        SourceFile::new(self, id, path, FileContents::new(text.into()), warn_unused)
    }

    /// Groups files to be checked together, in order.
    pub fn scene_set(&mut self, files: Vec<SourceFile>) -> SceneSet {
        SceneSet::new(self, files)
    }

    /// Changes which files a scene set holds (only if they differ: no needless revision).
    pub fn set_scene_files(&mut self, set: SceneSet, files: Vec<SourceFile>) {
        use salsa::Setter;
        if *set.files(self) != files {
            set.set_files(self).to(files);
        }
    }

    /// Replaces a file's text (a new revision: dependent queries re-run on demand).
    /// Only the part that differs from the old text is parsed again.
    pub fn set_text(&mut self, file: SourceFile, text: impl Into<String>) {
        let text = text.into();
        let mut contents = self.take_contents(file);
        let (start, old_end, new_end) = differing_bytes(&contents.text, &text);
        contents.text = text;
        let reparse = contents.edited(file.id(self), start, old_end, new_end);
        self.put_contents(file, contents, reparse);
    }

    /// Replaces bytes `range` of a file's text with `inserted` (an editor's range
    /// edit), re-parsing only the statements it can change. A range past the end or
    /// inside a character is widened to the characters it touches.
    pub fn edit(&mut self, file: SourceFile, range: Range<usize>, inserted: &str) {
        let mut contents = self.take_contents(file);
        let text = &contents.text;
        let mut start = range.start.min(text.len());
        while !text.is_char_boundary(start) {
            start -= 1;
        }
        let mut end = range.end.clamp(start, text.len());
        while !text.is_char_boundary(end) {
            end += 1;
        }
        let reparse = contents.edit(file.id(self), start, end, inserted);
        self.put_contents(file, contents, reparse);
    }

    fn take_contents(&mut self, file: SourceFile) -> FileContents {
        use salsa::Setter;
        file.set_contents(self).to(FileContents::new(String::new()))
    }

    fn put_contents(&mut self, file: SourceFile, contents: FileContents, reparse: Option<Reparse>) {
        use salsa::Setter;
        file.set_contents(self).to(contents);
        if let Some(r) = reparse {
            self.count(file, |c| {
                c.parses += 1;
                c.whole += u64::from(r.whole);
                c.statements += r.statements as u64;
            });
        }
    }

    fn count(&self, file: SourceFile, f: impl FnOnce(&mut ParseCount)) {
        let path = file.path(self).clone();
        let mut parses = self.parses.lock().unwrap_or_else(|e| e.into_inner());
        f(parses.entry(path).or_default());
    }

    /// Says that files on disk may have changed: checks re-run, parses do not.
    pub fn file_system_changed(&mut self) {
        use salsa::Setter;
        let Some(fs) = FileSystem::try_get(self) else {
            FileSystem::new(self, 0);
            return;
        };
        let next = fs.generation(self).wrapping_add(1);
        fs.set_generation(self).to(next);
    }

    pub fn set_aux_files(&mut self, aux_files: Arc<dyn AuxFiles>) {
        self.aux_files = aux_files;
        self.file_system_changed();
    }

    /// Starts recording which queries execute.
    pub fn enable_logging(&self) {
        let mut log = self.log.lock().unwrap_or_else(|e| e.into_inner());
        log.get_or_insert_with(Vec::new);
    }

    /// How many times each file was parsed so far, by path, sorted by path.
    pub fn parse_counts(&self) -> Vec<(String, u64)> {
        self.parse_stats()
            .into_iter()
            .map(|(p, c)| (p, c.parses))
            .collect()
    }

    /// How each file was parsed so far (whole, by statements), by path, sorted by path.
    pub fn parse_stats(&self) -> Vec<(String, ParseCount)> {
        let parses = self.parses.lock().unwrap_or_else(|e| e.into_inner());
        let mut counts: Vec<(String, ParseCount)> =
            parses.iter().map(|(p, n)| (p.clone(), *n)).collect();
        counts.sort_by(|a, b| a.0.cmp(&b.0));
        counts
    }

    /// The queries executed since the last call.
    pub fn take_log(&self) -> Vec<String> {
        let mut log = self.log.lock().unwrap_or_else(|e| e.into_inner());
        log.as_mut().map(std::mem::take).unwrap_or_default()
    }
}
