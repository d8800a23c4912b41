//! The server's state: the database, the open documents, files read from disk for
//! multi-file scenes, and the settings. One mutex guards it (see `server.rs`);
//! handlers get a [`Document`] view while it is held.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use radc_lang::db::{Database, SceneSet, SourceFile};
use tower_lsp_server::ls_types::Uri;

use crate::aux_files::DiskAuxFiles;
use crate::config::Config;
use crate::document::Document;
use crate::rif;

struct Open {
    file: SourceFile,
    version: i32,
    /// The canonical file path, for `file:` documents.
    path: Option<PathBuf>,
}

pub struct Session {
    db: Database,
    open: HashMap<Uri, Open>,
    /// Scene files that are not open, read from disk (canonical path -> input).
    disk: HashMap<PathBuf, SourceFile>,
    /// Open documents that a `.rif` puts in a scene with other files.
    scenes: HashMap<Uri, SceneSet>,
    pub config: Config,
}

impl Default for Session {
    fn default() -> Self {
        let config = Config::default();
        Session {
            db: Database::new(Arc::new(DiskAuxFiles::new(&config))),
            open: HashMap::new(),
            disk: HashMap::new(),
            scenes: HashMap::new(),
            config,
        }
    }
}

impl Session {
    pub fn open(&mut self, uri: Uri, version: i32, text: String) {
        // A reopened document gets its old input back, whatever its last version was.
        if let Some(doc) = self.open.get_mut(&uri) {
            doc.version = version;
            self.db.set_text(doc.file, text);
        } else {
            let path = uri.to_file_path().map(|p| rif::canonical(&p));
            let name = path
                .as_ref()
                .map(|p| p.display().to_string())
                .unwrap_or_else(|| uri.as_str().to_string());
            let file = self.db.add_file(name, text);
            self.open.insert(
                uri,
                Open {
                    file,
                    version,
                    path,
                },
            );
        }
        self.refresh_scenes();
    }

    /// Replaces the text unless `version` is older than what we have (notifications
    /// may be handled out of order; with full-text sync the newest text wins).
    pub fn change(&mut self, uri: &Uri, version: i32, text: String) {
        if let Some(doc) = self.open.get_mut(uri)
            && version >= doc.version
        {
            doc.version = version;
            self.db.set_text(doc.file, text);
        }
    }

    pub fn close(&mut self, uri: &Uri) {
        // Salsa inputs are never deleted: keep the input for a reopen, drop its text.
        if let Some(doc) = self.open.get_mut(uri) {
            doc.version = i32::MIN;
            self.db.set_text(doc.file, String::new());
        }
        self.scenes.remove(uri);
        self.refresh_scenes();
    }

    pub fn version(&self, uri: &Uri) -> Option<i32> {
        self.open.get(uri).map(|d| d.version)
    }

    pub fn document<'a>(&'a self, uri: &'a Uri) -> Option<Document<'a>> {
        let doc = self.open.get(uri)?;
        Some(Document {
            db: &self.db,
            file: doc.file,
            uri,
            scene: self.scenes.get(uri).copied(),
        })
    }

    pub fn open_uris(&self) -> Vec<Uri> {
        self.open
            .iter()
            .filter(|(_, d)| d.version != i32::MIN)
            .map(|(u, _)| u.clone())
            .collect()
    }

    /// Applies new settings; files on disk are looked up afresh.
    pub fn configure(&mut self, settings: &serde_json::Value) {
        self.config.update(settings);
        let search = DiskAuxFiles::new(&self.config);
        self.db.set_aux_files(Arc::new(search));
    }

    /// Files may have appeared, changed or vanished (a save, a watched-file event):
    /// re-read the scene files kept from disk and the `.rif` files.
    pub fn file_system_changed(&mut self) {
        self.db.file_system_changed();
        let disk: Vec<(PathBuf, SourceFile)> =
            self.disk.iter().map(|(p, f)| (p.clone(), *f)).collect();
        for (path, file) in disk {
            let text = read_scene(&path).unwrap_or_default();
            if *file.text(&self.db) != text {
                self.db.set_text(file, text);
            }
        }
        self.refresh_scenes();
    }

    /// Recomputes which open documents belong to a `.rif` scene, and its files.
    fn refresh_scenes(&mut self) {
        let documents: Vec<(Uri, PathBuf)> = self
            .open
            .iter()
            .filter(|(_, d)| d.version != i32::MIN)
            .filter_map(|(u, d)| Some((u.clone(), d.path.clone()?)))
            .collect();
        for (uri, path) in documents {
            let Some(paths) = rif::scene_of(&path) else {
                self.scenes.remove(&uri);
                continue;
            };
            let files: Vec<SourceFile> = paths.iter().filter_map(|p| self.scene_file(p)).collect();
            match self.scenes.get(&uri) {
                Some(&set) => self.db.set_scene_files(set, files),
                None => {
                    let set = self.db.scene_set(files);
                    self.scenes.insert(uri, set);
                }
            }
        }
    }

    /// The input for one file of a scene: the open document's, else the disk's.
    fn scene_file(&mut self, path: &Path) -> Option<SourceFile> {
        let path = rif::canonical(path);
        let open = self
            .open
            .values()
            .find(|d| d.version != i32::MIN && d.path.as_ref() == Some(&path));
        if let Some(doc) = open {
            return Some(doc.file);
        }
        if let Some(&file) = self.disk.get(&path) {
            return Some(file);
        }
        let text = read_scene(&path)?;
        let file = self.db.add_file(path.display().to_string(), text);
        self.disk.insert(path, file);
        Some(file)
    }
}

/// A scene file's text as `radc check` reads it (invalid UTF-8 as `?`).
fn read_scene(path: &Path) -> Option<String> {
    let bytes = std::fs::read(path).ok()?;
    Some(radc_lang::source::decode(radc_lang::FileId(0), &bytes).0)
}
