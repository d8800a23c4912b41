//! The server's state: the database, the open documents and the settings. One mutex
//! guards it (see `server.rs`); handlers get a [`Document`] view while it is held.

use std::collections::HashMap;
use std::sync::Arc;

use radc_lang::db::{Database, SourceFile};
use tower_lsp_server::ls_types::Uri;

use crate::config::Config;
use crate::document::Document;
use crate::search_path::SearchPath;

struct Open {
    file: SourceFile,
    version: i32,
}

pub struct Session {
    db: Database,
    open: HashMap<Uri, Open>,
    pub config: Config,
}

impl Default for Session {
    fn default() -> Self {
        let config = Config::default();
        Session {
            db: Database::new(Arc::new(SearchPath::new(config.raypath.clone()))),
            open: HashMap::new(),
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
            return;
        }
        let path = uri
            .to_file_path()
            .map(|p| p.display().to_string())
            .unwrap_or_else(|| uri.as_str().to_string());
        let file = self.db.add_file(path, text);
        self.open.insert(uri, Open { file, version });
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
        let search = SearchPath::new(self.config.raypath.clone());
        self.db.set_aux_files(Arc::new(search));
    }

    /// Files may have appeared or vanished (a save, a watched-file event).
    pub fn file_system_changed(&mut self) {
        self.db.file_system_changed();
    }
}
