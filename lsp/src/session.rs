//! The server's state: the database, the open documents, files read from disk for
//! multi-file scenes, and the settings. One mutex guards it (see `server.rs`);
//! handlers get a [`Document`] view while it is held.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use radc_lang::LineIndex;
use radc_lang::db::{Database, ParseCount, SceneSet, SourceFile};
use tower_lsp_server::ls_types::{Position, TextDocumentContentChangeEvent, Uri};

use crate::aux_files::{DiskAuxFiles, Overlay};
use crate::config::Config;
use crate::document::{Document, Kind, OpenFile};
use crate::rif;

struct Open {
    file: SourceFile,
    version: i32,
    /// The canonical file path, for `file:` documents.
    path: Option<PathBuf>,
    kind: Kind,
}

pub struct Session {
    db: Database,
    open: HashMap<Uri, Open>,
    /// Scene files that are not open, read from disk (canonical path -> input).
    disk: HashMap<PathBuf, SourceFile>,
    /// Open documents that a `.rif` puts in a scene with other files.
    scenes: HashMap<Uri, SceneSet>,
    /// The open `.cal` documents' texts, which scene checks read instead of the disk.
    overlay: Overlay,
    pub config: Config,
}

impl Default for Session {
    fn default() -> Self {
        let config = Config::default();
        let overlay = Overlay::default();
        Session {
            db: Database::new(Arc::new(DiskAuxFiles::new(&config, overlay.clone())))
                .with_render_support(Arc::new(radc_renderer::RendererSupport)),
            open: HashMap::new(),
            disk: HashMap::new(),
            scenes: HashMap::new(),
            overlay,
            config,
        }
    }
}

impl Session {
    pub fn open(&mut self, uri: Uri, version: i32, text: String) {
        // A reopened document gets its old input back, whatever its last version was.
        let kind = Kind::of(&uri);
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
                uri.clone(),
                Open {
                    file,
                    version,
                    path,
                    kind,
                },
            );
        }
        self.cal_changed(&uri);
        self.refresh_scenes();
    }

    /// An open `.cal` document's text is what scenes naming it read: put it in the
    /// overlay and let the checks re-run (scenes are not re-parsed).
    fn cal_changed(&mut self, uri: &Uri) {
        let Some(doc) = self.open.get(uri) else {
            return;
        };
        let Some(path) = doc.path.clone().filter(|_| doc.kind == Kind::Cal) else {
            return;
        };
        let text = (doc.version != i32::MIN).then(|| doc.file.text(&self.db).clone());
        self.overlay.set(path, text);
        self.db.file_system_changed();
    }

    /// Applies one `didChange`: whole texts (a change without a range) and range edits
    /// (incremental sync), in order. A whole text older than what we have is ignored
    /// (the newest text wins); range edits apply to the text of the version before
    /// theirs, so they are applied only to an older text.
    pub fn change(
        &mut self,
        uri: &Uri,
        version: i32,
        changes: Vec<TextDocumentContentChangeEvent>,
    ) {
        let Some(doc) = self.open.get_mut(uri) else {
            return;
        };
        let ranged = changes.iter().any(|c| c.range.is_some());
        if version < doc.version || (ranged && version == doc.version) {
            return;
        }
        doc.version = version;
        let file = doc.file;
        for c in changes {
            match c.range {
                None => self.db.set_text(file, c.text),
                Some(range) => {
                    let text = file.text(&self.db);
                    let lines = radc_lang::db::line_index(&self.db, file);
                    let start = offset(text, lines, range.start);
                    let end = offset(text, lines, range.end).max(start);
                    self.db.edit(file, start..end, &c.text);
                }
            }
        }
        self.cal_changed(uri);
    }

    pub fn close(&mut self, uri: &Uri) {
        // Salsa inputs are never deleted: keep the input for a reopen, drop its text.
        if let Some(doc) = self.open.get_mut(uri) {
            doc.version = i32::MIN;
            self.db.set_text(doc.file, String::new());
        }
        self.cal_changed(uri);
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
            kind: doc.kind,
            workspace: self.workspace(),
        })
    }

    /// Every open document and every scene file read from disk, for the requests
    /// that reach across files (workspace symbols, references and rename).
    pub fn workspace(&self) -> Vec<OpenFile> {
        let open = self
            .open
            .iter()
            .filter(|(_, d)| d.version != i32::MIN)
            .map(|(u, d)| OpenFile {
                uri: u.clone(),
                file: d.file,
                kind: d.kind,
            });
        let open_paths: Vec<&PathBuf> =
            self.open.values().filter_map(|d| d.path.as_ref()).collect();
        let disk = self
            .disk
            .iter()
            .filter(|(p, _)| !open_paths.contains(p))
            .filter_map(|(p, f)| {
                Some(OpenFile {
                    uri: Uri::from_file_path(p)?,
                    file: *f,
                    kind: Kind::Scene,
                })
            });
        let mut all: Vec<OpenFile> = open.chain(disk).collect();
        all.sort_by(|a, b| a.uri.as_str().cmp(b.uri.as_str()));
        all
    }

    pub fn db(&self) -> &Database {
        &self.db
    }

    /// How each file was parsed (the `radc/stats` request).
    pub fn parse_stats(&self) -> Vec<(String, ParseCount)> {
        self.db.parse_stats()
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
        let search = DiskAuxFiles::new(&self.config, self.overlay.clone());
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
            .filter(|(_, d)| d.version != i32::MIN && d.kind == Kind::Scene)
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

/// The byte offset of an LSP position (line, UTF-16 column) in `text`, clamped to its
/// line and to the text (as the protocol asks of positions past an end).
fn offset(text: &str, lines: &LineIndex, pos: Position) -> usize {
    let line = pos.line as usize;
    if line >= lines.line_count() {
        return text.len();
    }
    let line_start = lines.line_start(line);
    let mut units = 0u32;
    for (i, c) in text[line_start..].char_indices() {
        if units >= pos.character || c == '\n' {
            return line_start + i;
        }
        units += c.len_utf16() as u32;
    }
    text.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edit(text: &str, range: (u32, u32, u32, u32), new: &str) -> String {
        let mut s = Session::default();
        let uri: Uri = "file:///x/a.rad".parse().expect("uri");
        s.open(uri.clone(), 1, text.to_string());
        let change = TextDocumentContentChangeEvent {
            range: Some(tower_lsp_server::ls_types::Range::new(
                Position::new(range.0, range.1),
                Position::new(range.2, range.3),
            )),
            range_length: None,
            text: new.to_string(),
        };
        s.change(&uri, 2, vec![change.clone()]);
        // The same version again is not applied twice.
        s.change(&uri, 2, vec![change]);
        s.document(&uri)
            .map(|d| d.text().to_string())
            .unwrap_or_default()
    }

    #[test]
    fn range_edits_count_utf16_columns() {
        assert_eq!(edit("ab\ncd\n", (1, 1, 1, 2), "X"), "ab\ncX\n");
        assert_eq!(edit("ab\ncd\n", (0, 1, 1, 1), ""), "ad\n");
        // '😀' is two UTF-16 units.
        assert_eq!(edit("😀x\n", (0, 2, 0, 3), "y"), "😀y\n");
        // Past the end: appended.
        assert_eq!(edit("ab", (5, 0, 5, 0), "!"), "ab!");
    }
}
