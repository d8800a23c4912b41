//! The texts a run has read (scene files, command outputs, function files), by
//! `FileId`, so diagnostics can be shown against them.

use radc_lang::{FileId, LineIndex};

/// A file as the report sees it: a display name and its (decoded) text.
pub struct SourceText {
    pub name: String,
    pub text: String,
    /// Built on first use: most files of a run have nothing to report.
    lines: std::sync::OnceLock<LineIndex>,
}

impl SourceText {
    pub fn lines(&self) -> &LineIndex {
        self.lines.get_or_init(|| LineIndex::new(&self.text))
    }
}

/// All files a run has read, indexed by `FileId`.
#[derive(Default)]
pub struct Sources {
    files: Vec<SourceText>,
}

impl Sources {
    /// The id the next added file will get.
    pub fn next_id(&self) -> FileId {
        FileId(self.files.len() as u32)
    }

    pub fn add(&mut self, name: String, text: String) -> FileId {
        self.files.push(SourceText {
            name,
            text,
            lines: std::sync::OnceLock::new(),
        });
        FileId(self.files.len() as u32 - 1)
    }

    pub fn get(&self, id: FileId) -> Option<&SourceText> {
        self.files.get(id.0 as usize)
    }

    pub fn len(&self) -> usize {
        self.files.len()
    }

    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// The files in id order.
    pub fn iter(&self) -> impl Iterator<Item = &SourceText> {
        self.files.iter()
    }
}
