//! Auxiliary files on disk for a scene read by `radc check`, `trace`, `render` and
//! `build`: found along `Policy::SceneCurrentRaypath`, with radc's built-in library
//! texts where no file of that name is found.

use std::path::{Path, PathBuf};

use radc_lang::FileId;
use radc_lang::scene::FileLookup;
use radc_lang::schema::FileKind;
use radc_lang::search_path::{Found, Policy, SearchPath};

use crate::pending::PendingSources;

/// Auxiliary files on disk, found along the search path of `radc check` and the
/// language server (`Policy::SceneCurrentRaypath`: the folder of the scene file that
/// names it, the current folder, then each folder of RAYPATH).
pub struct SceneFiles<'a> {
    scene_dirs: Vec<(FileId, PathBuf)>,
    search: SearchPath,
    pending: &'a PendingSources,
}

impl<'a> SceneFiles<'a> {
    pub fn new(scene_dirs: Vec<(FileId, PathBuf)>, pending: &'a PendingSources) -> Self {
        let raypath = std::env::var_os("RAYPATH");
        SceneFiles {
            scene_dirs,
            search: SearchPath::new(Policy::SceneCurrentRaypath, raypath.as_deref()),
            pending,
        }
    }

    fn scene_dir(&self, from: FileId) -> Option<PathBuf> {
        self.scene_dirs
            .iter()
            .find(|(f, _)| *f == from)
            .map(|(_, d)| d.clone())
            .or_else(|| self.pending.dir_of(from))
    }

    fn find(&self, name: &str, from: FileId) -> Option<PathBuf> {
        let dir = self.scene_dir(from);
        self.search.find(name, dir.as_deref(), Path::exists)
    }

    /// radc's own text of a library function file, used only when no file of that
    /// name is on the search path.
    fn builtin(&self, name: &str, kind: FileKind, from: FileId) -> Option<&'static str> {
        let dir = self.scene_dir(from);
        match self
            .search
            .lookup(name, kind, dir.as_deref(), Path::exists)?
        {
            Found::Builtin(text) => Some(text),
            Found::File(..) => None,
        }
    }
}

/// Auxiliary files larger than this are not read for content checks (by the CLI and
/// the language server alike).
pub const MAX_AUX_FILE: u64 = 64 << 20;

impl FileLookup for SceneFiles<'_> {
    fn exists(&self, name: &str, kind: FileKind, from: FileId) -> bool {
        self.find(name, from).is_some() || self.builtin(name, kind, from).is_some()
    }

    fn read(&self, name: &str, kind: FileKind, from: FileId) -> Option<String> {
        if let Some(text) = self.builtin(name, kind, from) {
            return Some(text.to_string());
        }
        let path = self.find(name, from)?;
        if std::fs::metadata(&path).ok()?.len() > MAX_AUX_FILE {
            return None;
        }
        let bytes = std::fs::read(path).ok()?;
        Some(String::from_utf8_lossy(&bytes).into_owned())
    }

    fn load(&self, name: &str, kind: FileKind, from: FileId) -> Option<(FileId, String)> {
        if let Some(text) = self.builtin(name, kind, from) {
            let shown = format!("{name} (built into radc)");
            let id = self.pending.add(shown, text.to_string(), PathBuf::new());
            return Some((id, text.to_string()));
        }
        let text = self.read(name, kind, from)?;
        let dir = self
            .find(name, from)
            .and_then(|p| p.parent().map(Path::to_path_buf))
            .unwrap_or_default();
        Some((self.pending.add(name.to_string(), text.clone(), dir), text))
    }

    fn read_head(&self, name: &str, kind: FileKind, from: FileId, max: usize) -> Option<Vec<u8>> {
        use std::io::Read;
        if let Some(text) = self.builtin(name, kind, from) {
            return Some(text.bytes().take(max).collect());
        }
        let file = std::fs::File::open(self.find(name, from)?).ok()?;
        let mut head = Vec::with_capacity(max.min(1 << 16));
        file.take(max as u64).read_to_end(&mut head).ok()?;
        Some(head)
    }
}
