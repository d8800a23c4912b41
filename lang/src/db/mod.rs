//! The incremental database shared by the CLI and the language server, in the shape of
//! salsa's `examples/calc`: files are inputs, everything computed from them is a
//! tracked query, so an edit to one file re-parses that file alone.
//!
//! `lang` still does no IO here: the front end sets each file's text, and answers
//! "does this auxiliary file exist?" through an [`AuxFiles`] it installs on the
//! database. Because that answer comes from outside salsa's view, the front end bumps
//! [`FileSystem::generation`] when the disk may have changed, which re-runs the checks
//! (not the parses).

mod cal;
mod queries;

pub use cal::{
    CalDef, CalIndex, CalName, CalUse, ParsedCal, cal_index, cal_values, check_cal, parse_cal,
};
pub use queries::{
    ParsedScene, check_scene, check_scene_set, format_scene, line_index, modifier_scope,
    parse_scene,
};

use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, Mutex};

use crate::scene::Expansion;
use crate::schema::FileKind;
use crate::source::FileId;

/// One scene file the front end has handed to the database.
#[salsa::input(debug)]
pub struct SourceFile {
    /// Stamped on every span computed from this file.
    #[returns(copy)]
    pub id: FileId,
    /// Where the file lives; auxiliary files are searched relative to its folder.
    pub path: String,
    pub text: String,
    /// Whether unused modifiers are worth a warning (not in `.mat` libraries).
    #[returns(copy)]
    pub warn_unused: bool,
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

    /// Called each time a file is parsed (a query really ran, not a memo reused):
    /// how the server's statistics show that an edit re-parses only the edited file.
    fn note_parse(&self, _file: SourceFile) {}
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
    parses: Arc<Mutex<HashMap<String, u64>>>,
}

#[salsa::db]
impl salsa::Database for Database {}

#[salsa::db]
impl Db for Database {
    fn aux_files(&self) -> &dyn AuxFiles {
        &*self.aux_files
    }

    fn note_parse(&self, file: SourceFile) {
        let path = file.path(self).clone();
        let mut parses = self.parses.lock().unwrap_or_else(|e| e.into_inner());
        *parses.entry(path).or_default() += 1;
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
        };
        FileSystem::new(&db, 0);
        db
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
        SourceFile::new(self, id, path, text.into(), warn_unused)
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
    pub fn set_text(&mut self, file: SourceFile, text: impl Into<String>) {
        use salsa::Setter;
        file.set_text(self).to(text.into());
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
        let parses = self.parses.lock().unwrap_or_else(|e| e.into_inner());
        let mut counts: Vec<(String, u64)> = parses.iter().map(|(p, n)| (p.clone(), *n)).collect();
        counts.sort();
        counts
    }

    /// The queries executed since the last call.
    pub fn take_log(&self) -> Vec<String> {
        let mut log = self.log.lock().unwrap_or_else(|e| e.into_inner());
        log.as_mut().map(std::mem::take).unwrap_or_default()
    }
}
