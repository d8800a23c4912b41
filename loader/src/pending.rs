//! Sources found while reading a scene (command outputs, function files), numbered
//! after the files already read.

use std::cell::RefCell;
use std::path::PathBuf;

use radc_lang::FileId;

/// Files a check reads beyond the scenes named on the command line (command
/// outputs, function files), numbered after the sources already read so diagnostics
/// can point into them. Shared by the command expander and the file lookup.
pub struct PendingSources {
    first_id: u32,
    /// (display name, text, folder) in id order.
    files: RefCell<Vec<(String, String, PathBuf)>>,
}

impl PendingSources {
    pub fn new(first_id: u32) -> Self {
        PendingSources {
            first_id,
            files: RefCell::new(Vec::new()),
        }
    }

    pub fn add(&self, name: String, text: String, dir: PathBuf) -> FileId {
        let mut files = self.files.borrow_mut();
        files.push((name, text, dir));
        FileId(self.first_id + files.len() as u32 - 1)
    }

    /// The folder a pending file's relative names resolve from.
    pub fn dir_of(&self, file: FileId) -> Option<PathBuf> {
        let index = file.0.checked_sub(self.first_id)?;
        self.files.borrow().get(index as usize).map(|e| e.2.clone())
    }

    /// The files, as (display name, text), in id order.
    pub fn into_sources(self) -> Vec<(String, String)> {
        self.files
            .into_inner()
            .into_iter()
            .map(|(name, text, _)| (name, text))
            .collect()
    }
}
